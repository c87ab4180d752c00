//! Maxima that persist: the 0-dimensional persistence of the maxima of a height field
//! (pixels added in decreasing height, a union-find joining them; when two components
//! meet, the lower peak ends there).

use super::field::neighbours8;

/// Pixels (indices) of the maxima of `height` over its positive pixels whose persistence
/// is at least `min_persistence`, 8-connected; each component's highest maximum always.
pub fn persistent_maxima(height: &[f32], w: usize, h: usize, min_persistence: f32) -> Vec<usize> {
    const NONE: u32 = u32::MAX;
    let mut order: Vec<u32> = (0..height.len() as u32)
        .filter(|&i| height[i as usize] > 0.0)
        .collect();
    order.sort_unstable_by(|&a, &b| {
        height[b as usize]
            .total_cmp(&height[a as usize])
            .then(a.cmp(&b))
    });
    let mut parent = vec![NONE; height.len()];
    let mut peak = vec![NONE; height.len()];
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    }
    let mut seeds = Vec::new();
    for &p in &order {
        parent[p as usize] = p;
        peak[p as usize] = p;
        for q in neighbours8(p as usize, w, h) {
            let q = q as u32;
            if parent[q as usize] == NONE {
                continue;
            }
            let (mut a, mut b) = (find(&mut parent, p), find(&mut parent, q));
            if a == b {
                continue;
            }
            let (ha, hb) = (
                height[peak[a as usize] as usize],
                height[peak[b as usize] as usize],
            );
            if ha < hb {
                std::mem::swap(&mut a, &mut b);
            }
            // b's maximum ends here, at the level of the pixel that joins them.
            let pb = peak[b as usize];
            if height[pb as usize] - height[p as usize] >= min_persistence {
                seeds.push(pb as usize);
            }
            parent[b as usize] = a;
        }
    }
    for &p in &order {
        if find(&mut parent, p) == p {
            seeds.push(peak[p as usize] as usize);
        }
    }
    seeds.sort_unstable();
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_peaks_persist_and_a_bump_does_not() {
        // Heights along a line: peaks 5 and 4 joined at 2 (persistence 2), then a bump of
        // 0.5 on the slope.
        let hgt = [1.0, 3.0, 5.0, 3.0, 2.0, 3.0, 4.0, 3.0, 2.5, 3.0, 1.0];
        let s = persistent_maxima(&hgt, hgt.len(), 1, 1.0);
        assert_eq!(s, vec![2, 6]);
    }
}
