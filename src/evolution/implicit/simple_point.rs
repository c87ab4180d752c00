//! Simple pixels (seed 000 §4.1): in 2D, with labels 4-connected and their complements
//! 8-connected, a pixel can change owner without changing topology iff its Yokoi
//! 4-connectivity number is 1.

use super::Implicit;

impl Implicit {
    /// Yokoi 4-connectivity number of pixel `i` with respect to label `l` (pixel `i`
    /// itself not counted): 1 iff adding or removing `i` keeps the label's topology.
    pub(super) fn connectivity(&self, i: usize, l: u32) -> u32 {
        let (x, y) = ((i % self.w) as isize, (i / self.w) as isize);
        // E, NE, N, NW, W, SW, S, SE (y grows downwards; the cyclic order is what counts).
        const D: [(isize, isize); 8] = [
            (1, 0),
            (1, -1),
            (0, -1),
            (-1, -1),
            (-1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ];
        let mut b = [0u32; 8];
        for (k, (dx, dy)) in D.iter().enumerate() {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && (nx as usize) < self.w && (ny as usize) < self.h {
                b[k] = (self.owner[ny as usize * self.w + nx as usize] == l) as u32;
            }
        }
        [0, 2, 4, 6]
            .iter()
            .map(|&k| b[k] - b[k] * b[(k + 1) % 8] * b[(k + 2) % 8])
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::engine;

    #[test]
    pub(super) fn connectivity_number_decides_simple_pixels() {
        // Centre pixel (2, 2) of a 5×5 grid; label 0 around it as given.
        let c = 2 * 5 + 2;
        // One neighbour: simple (growth).
        assert_eq!(engine(5, 5, &[(3, 2)]).connectivity(c, 0), 1);
        // Opposite neighbours: joining them would close a loop.
        assert_eq!(engine(5, 5, &[(3, 2), (1, 2)]).connectivity(c, 0), 2);
        // An L-shaped corner (E, NE, N): simple.
        assert_eq!(
            engine(5, 5, &[(3, 2), (3, 1), (2, 1)]).connectivity(c, 0),
            1
        );
        // Surrounded: filling a one-pixel hole is not simple.
        let all: Vec<_> = (1..4)
            .flat_map(|y| (1..4).map(move |x| (x, y)))
            .filter(|&p| p != (2, 2))
            .collect();
        assert_eq!(engine(5, 5, &all).connectivity(c, 0), 0);
        // Only diagonals: 4-connectivity does not see them, nothing to join.
        assert_eq!(engine(5, 5, &[(3, 3), (1, 1)]).connectivity(c, 0), 0);
    }
}
