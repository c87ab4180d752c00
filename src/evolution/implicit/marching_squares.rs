//! Contours from the pixel labels (seed 000 §4.5): marching squares per label, saddles
//! split (labels are 4-connected), crossings placed by [`Implicit::crossing`], segments
//! chained into rings with the region on the left.

use super::{Implicit, NONE};
use crate::geometry::{orient, Point};
use std::collections::{HashMap, HashSet};

impl Implicit {
    /// The contours: for each label, its boundary rings (region on the left: outer rings
    /// counter-clockwise in the algebraic sense, holes the other way).
    pub fn rings(&self) -> Vec<Vec<Point>> {
        let mut segments = Segments::default();
        for cy in -1..self.h as isize {
            for cx in -1..self.w as isize {
                self.cell(cx, cy, &mut segments);
            }
        }
        segments.chain()
    }

    /// The owner of pixel (x, y); `NONE` outside the image.
    fn owner_at(&self, x: isize, y: isize) -> u32 {
        let (w, h) = (self.w as isize, self.h as isize);
        if x < 0 || y < 0 || x >= w || y >= h {
            NONE
        } else {
            self.owner[(y * w + x) as usize]
        }
    }

    /// The segments of the cell with corners (cx, cy) … (cx + 1, cy + 1), one pass per
    /// label present at its corners.
    fn cell(&self, cx: isize, cy: isize, seg: &mut Segments) {
        // Cell corners: c0 (cx, cy), c1 (cx+1, cy), c2 (cx+1, cy+1), c3 (cx, cy+1).
        let c = [(cx, cy), (cx + 1, cy), (cx + 1, cy + 1), (cx, cy + 1)];
        let o = c.map(|(x, y)| self.owner_at(x, y));
        if o[0] == o[1] && o[1] == o[2] && o[2] == o[3] {
            return;
        }
        for k in 0..4 {
            let l = o[k];
            if l == NONE || o[..k].contains(&l) {
                continue;
            }
            let m = o.map(|x| x == l);
            // Crossed sides: side j joins corners j and j + 1.
            let mut pairs = [(0usize, 0usize); 2];
            let np = if m[0] && m[2] && !m[1] && !m[3] {
                pairs = [(3, 0), (1, 2)]; // saddle: cut off corner 0, then corner 2
                2
            } else if m[1] && m[3] && !m[0] && !m[2] {
                pairs = [(0, 1), (2, 3)];
                2
            } else {
                // Exactly two sides are crossed: the first and the last.
                let crossed = |j: usize| m[j] != m[(j + 1) % 4];
                let first = (0..4).find(|&j| crossed(j)).expect("two crossed sides");
                let last = (0..4).rfind(|&j| crossed(j)).expect("two crossed sides");
                pairs[0] = (first, last);
                1
            };
            for &(s0, s1) in &pairs[..np] {
                let (e0, p0) = self.crossing_point(&mut seg.point, l, c[s0], c[(s0 + 1) % 4]);
                let (e1, p1) = self.crossing_point(&mut seg.point, l, c[s1], c[(s1 + 1) % 4]);
                // A member corner the segment bounds (for a saddle, the one it cuts off;
                // otherwise all members lie on one side).
                let member = (0..4)
                    .find(|&j| {
                        m[j] && (j == s0 || j == (s0 + 1) % 4) && (j == s1 || j == (s1 + 1) % 4)
                    })
                    .or_else(|| (0..4).find(|&j| m[j]))
                    .expect("a label corner");
                let mc = centre(c[member].0, c[member].1);
                if orient(p0, p1, mc) > 0.0 {
                    seg.next.insert((l, e0), e1);
                } else {
                    seg.next.insert((l, e1), e0);
                }
            }
        }
    }

    /// The crossing of label `l`'s contour with the grid edge between pixels (x0, y0) and
    /// (x1, y1), one of which belongs to `l`: its id and point (computed once per label).
    fn crossing_point(
        &self,
        point: &mut HashMap<(u32, u64), Point>,
        l: u32,
        (x0, y0): (isize, isize),
        (x1, y1): (isize, isize),
    ) -> (u64, Point) {
        let (w, h) = (self.w as isize, self.h as isize);
        let (ex, ey, dir) = if y0 == y1 {
            (x0.min(x1), y0, 0)
        } else {
            (x0, y0.min(y1), 1)
        };
        let id = edge_id(w, ex, ey, dir);
        let p = *point.entry((l, id)).or_insert_with(|| {
            let (ax, ay, bx, by) = if self.owner_at(x0, y0) == l {
                (x0, y0, x1, y1)
            } else {
                (x1, y1, x0, y0)
            };
            let inside = |x: isize, y: isize| x >= 0 && y >= 0 && x < w && y < h;
            let a = (ay * w + ax) as usize;
            let b = inside(bx, by).then(|| (by * w + bx) as usize);
            let dir = if ay == by { bx - ax } else { (by - ay) * w };
            let s = if inside(ax, ay) {
                self.crossing(a, b, dir)
            } else {
                0.5
            };
            centre(ax, ay).lerp(centre(bx, by), s)
        });
        (id, p)
    }
}

/// The centre of pixel (x, y).
fn centre(x: isize, y: isize) -> Point {
    Point::new(x as f64 + 0.5, y as f64 + 0.5)
}

/// A crossing is named by its grid edge: (x, y, 0) to (x + 1, y), (x, y, 1) to (x, y + 1),
/// over pixels padded by one all round (image width `w`).
fn edge_id(w: isize, x: isize, y: isize, dir: u64) -> u64 {
    let pw = (w + 2) as u64;
    (((y + 1) as u64 * pw + (x + 1) as u64) << 1) | dir
}

/// Directed segments between crossings, per label, and the crossings' points.
#[derive(Default)]
struct Segments {
    next: HashMap<(u32, u64), u64>,
    point: HashMap<(u32, u64), Point>,
}

impl Segments {
    /// Chains the segments into rings.
    fn chain(self) -> Vec<Vec<Point>> {
        let mut rings = Vec::new();
        let mut keys: Vec<(u32, u64)> = self.next.keys().copied().collect();
        keys.sort_unstable();
        let mut used: HashSet<(u32, u64)> = HashSet::new();
        for start in keys {
            if used.contains(&start) {
                continue;
            }
            let (l, mut e) = start;
            let mut ring = Vec::new();
            loop {
                used.insert((l, e));
                ring.push(self.point[&(l, e)]);
                match self.next.get(&(l, e)) {
                    Some(&n) => e = n,
                    None => {
                        debug_assert!(false, "marching squares left a crossing open");
                        break;
                    }
                }
                if e == start.1 {
                    break;
                }
            }
            if ring.len() >= 3 {
                rings.push(ring);
            }
        }
        rings
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::engine;
    use crate::geometry::{winding_number, Point};

    #[test]
    pub(super) fn rings_bound_exactly_the_owned_pixels() {
        // A plus, a diagonal pair (two 4-components of one label would not arise, but
        // the extraction must still separate them) and a pixel on the border.
        let e = engine(
            7,
            6,
            &[
                (2, 1),
                (1, 2),
                (2, 2),
                (3, 2),
                (2, 3),
                (5, 4),
                (6, 5),
                (0, 0),
            ],
        );
        let rings = e.rings();
        assert_eq!(rings.len(), 4);
        for y in 0..6 {
            for x in 0..7 {
                let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let w: i32 = rings.iter().map(|r| winding_number(r, p)).sum();
                assert_eq!(w != 0, e.owned(x, y), "pixel {x},{y}");
            }
        }
        for r in &rings {
            assert!(
                crate::geometry::signed_area(r) > 0.0,
                "outer rings run counter-clockwise"
            );
        }
    }
}
