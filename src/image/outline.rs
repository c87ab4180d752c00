//! The outline of a seed's basin as a simple ring: the basin less its pixels that touch
//! another basin, without corner-only pixels, followed crack by crack and simplified
//! (Douglas–Peucker).

use crate::geometry::Point;
use rustc_hash::FxHashSet;

/// The outline (pixel corners, region on one side) of the 4-connected part of basin `l`
/// that holds pixel `at`, after removing its pixels that touch another basin, so
/// neighbouring outlines keep a gap. `None` if fewer than 9 pixels remain.
pub fn basin_outline(labels: &[u32], l: u32, at: usize, w: usize, h: usize) -> Option<Vec<Point>> {
    let get = |x: isize, y: isize| -> u32 {
        if x < 0 || y < 0 || x >= w as isize || y >= h as isize {
            0
        } else {
            labels[y as usize * w + x as usize]
        }
    };
    let keep = |x: isize, y: isize| {
        get(x, y) == l
            && [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ]
            .iter()
            .all(|&(dx, dy)| matches!(get(x + dx, y + dy), 0) || get(x + dx, y + dy) == l)
    };
    // The 4-connected part holding the peak, and its top-left pixel.
    let (ax, ay) = ((at % w) as isize, (at / w) as isize);
    if !keep(ax, ay) {
        return None;
    }
    let inside = without_corner_pixels(part_of((ax, ay), &keep), (ax, ay));
    if inside.len() < 9 {
        return None;
    }
    crack_ring(&inside)
}

/// Pixels as (x, y).
type Pixels = FxHashSet<(isize, isize)>;

/// The 4-connected part of the pixels `kept` holding pixel `at`.
fn part_of(at: (isize, isize), kept: &dyn Fn(isize, isize) -> bool) -> Pixels {
    let mut inside = Pixels::default();
    let mut stack = vec![at];
    inside.insert(at);
    while let Some((x, y)) = stack.pop() {
        for (nx, ny) in [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)] {
            if !inside.contains(&(nx, ny)) && kept(nx, ny) {
                inside.insert((nx, ny));
                stack.push((nx, ny));
            }
        }
    }
    inside
}

/// Two pixels meeting only at a corner would make the outline pass that corner twice
/// (a ring touching itself, which the contour set refuses): drops one of each such pair
/// until none is left, then keeps the part holding `at`.
fn without_corner_pixels(mut inside: Pixels, at: (isize, isize)) -> Pixels {
    loop {
        let pinched: Vec<(isize, isize)> = inside
            .iter()
            .copied()
            .filter(|&(x, y)| {
                [(1, 1), (1, -1)].iter().any(|&(dx, dy)| {
                    inside.contains(&(x + dx, y + dy))
                        && !inside.contains(&(x + dx, y))
                        && !inside.contains(&(x, y + dy))
                })
            })
            .filter(|&p| p != at)
            .collect();
        if pinched.is_empty() {
            return inside;
        }
        let kept: Pixels = inside
            .iter()
            .copied()
            .filter(|p| !pinched.contains(p))
            .collect();
        inside = part_of(at, &|x, y| kept.contains(&(x, y)));
    }
}

/// The outline of the 4-connected pixels `inside` by crack following, simplified; `None`
/// if the walk does not close or leaves fewer than four corners.
fn crack_ring(inside: &Pixels) -> Option<Vec<Point>> {
    let &(sx, sy) = inside.iter().min_by_key(|&&(x, y)| (y, x))?;
    let is_in = |x: isize, y: isize| inside.contains(&(x, y));
    // Crack following with the region on the right: at corner (vx, vy) heading d, the
    // pixels ahead on the left and right decide: right one out → turn right, left one
    // in → turn left, else straight. Directions E, S, W, N (y down), clockwise.
    const D: [(isize, isize); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
    let ahead = |vx: isize, vy: isize, d: usize| match d {
        0 => ((vx, vy - 1), (vx, vy)),
        1 => ((vx, vy), (vx - 1, vy)),
        2 => ((vx - 1, vy), (vx - 1, vy - 1)),
        _ => ((vx - 1, vy - 1), (vx, vy - 1)),
    };
    // The top-left corner of the top-left pixel is a corner where the walk turns from
    // north to east: it starts and ends there.
    let (mut vx, mut vy, mut d) = (sx, sy, 0usize);
    let mut ring = vec![Point::new(sx as f64, sy as f64)];
    for _ in 0..8 * inside.len() + 8 {
        let ((lx, ly), (rx, ry)) = ahead(vx, vy, d);
        let nd = if !is_in(rx, ry) {
            (d + 1) % 4
        } else if is_in(lx, ly) {
            (d + 3) % 4
        } else {
            d
        };
        if nd != d {
            if (vx, vy) == (sx, sy) && nd == 0 {
                // Simplifying a narrow part can make it cross itself: keep the staircase.
                let simple = simplify(&ring, 0.75);
                let ring = if is_simple(&simple) { simple } else { ring };
                return (ring.len() >= 4).then_some(ring);
            }
            ring.push(Point::new(vx as f64, vy as f64));
            d = nd;
            continue;
        }
        vx += D[d].0;
        vy += D[d].1;
    }
    None
}

/// Whether the closed ring's edges meet only where neighbours share a corner.
fn is_simple(ring: &[Point]) -> bool {
    use crate::geometry::{segment_intersection, SegmentIntersection};
    let n = ring.len();
    let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
    (0..n).all(|i| {
        (i + 1..n).all(|j| {
            let ((a0, a1), (b0, b1)) = (edge(i), edge(j));
            match segment_intersection(a0, a1, b0, b1) {
                SegmentIntersection::None => true,
                SegmentIntersection::Overlap => false,
                _ => j == i + 1 || (i == 0 && j == n - 1),
            }
        })
    })
}

/// Douglas–Peucker on a closed ring: corners within `tol` of the chord between kept
/// ones are dropped (a staircase outline becomes its diagonals).
fn simplify(ring: &[Point], tol: f64) -> Vec<Point> {
    let n = ring.len();
    if n < 5 {
        return ring.to_vec();
    }
    // Split at the corner farthest from the first, then simplify both chains.
    let far = (1..n)
        .max_by(|&a, &b| ring[0].dist(ring[a]).total_cmp(&ring[0].dist(ring[b])))
        .unwrap_or(n / 2);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (ring[a], ring[b % n]);
        let worst = (a + 1..b)
            .map(|i| (i, crate::geometry::point_segment_distance(ring[i], p, q)))
            .max_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((i, d)) = worst {
            if d > tol {
                keep[i] = true;
                stack.extend([(a, i), (i, b)]);
            }
        }
    }
    ring.iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(&p, _)| p)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_basin_pinched_at_a_corner_still_outlines_a_simple_ring() {
        // Two blocks meeting only at a corner and joined round the side: the raw outline
        // passes the shared corner twice.
        let rows = [
            "............",
            ".####.......",
            ".####.......",
            ".####.......",
            ".####.......",
            ".##..####...",
            ".##..####...",
            ".##..####...",
            ".########...",
            ".########...",
            "............",
        ];
        let (w, h) = (rows[0].len(), rows.len());
        let labels: Vec<u32> = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| u32::from(b == b'#')))
            .collect();
        let ring = basin_outline(&labels, 1, 2 * w + 2, w, h).expect("a ring");
        assert!(is_simple(&ring));
        let area = crate::geometry::signed_area(&ring).abs();
        assert!((30.0..=50.0).contains(&area), "{area}");
    }

    #[test]
    fn rings_that_touch_or_cross_themselves_are_not_simple() {
        let p = |x, y| Point::new(x, y);
        assert!(is_simple(&[
            p(0.0, 0.0),
            p(2.0, 0.0),
            p(2.0, 2.0),
            p(0.0, 2.0)
        ]));
        let bowtie = [p(0.0, 0.0), p(2.0, 2.0), p(2.0, 0.0), p(0.0, 2.0)];
        assert!(!is_simple(&bowtie));
        // Two squares sharing the corner (1, 1), walked as one ring.
        let pinched = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(2.0, 1.0),
            p(2.0, 2.0),
            p(1.0, 2.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
        ];
        assert!(!is_simple(&pinched));
    }
}
