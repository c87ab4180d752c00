//! Hole nucleation: the adaptive engine opens a hole where its region covers clear
//! background.
//!
//! Seed 003's contours change topology only where fronts meet, so a contour cannot open
//! a hole in the middle of its region by itself: a wrap shrinking over a ring-shaped
//! object stops on its outside and never finds the hole, and a wrap over touching
//! phase-contrast cells would have to push a finger down each narrow channel between
//! them against the contour's own smoothing. A level set (Chan–Vese) opens such holes
//! wherever the region term says background; this is the explicit counterpart. When a
//! pyramid level is done (and once more when the finest level has settled: the
//! evolver's schedule), the region is filled on that level's pixel grid; pixels well
//! inside it (their eight neighbours inside too) whose region score is at most
//! −[`NUCLEATE_SCORE`] form connected pieces, and each piece of at least
//! [`NUCLEATE_PIXELS`] pixels gets a small hole ring at its most background-like pixel.
//! The hole is an ordinary ring: the region force grows it over the background piece,
//! and where it reaches the outside it opens through the topology core (a split, or a
//! lost hole), exactly as any other contact.
//!
//! Choices: a quarter of the contrast past the level (score −0.5) and four pixels keep
//! pixel noise from opening holes (the local level keeps at least four noise deviations
//! from the background, [`crate::image::local::FLOOR_SIGMAS`], so −0.5 is at least two
//! deviations, over four pixels at once); only the
//! adaptive engine nucleates (a new hole is a change of topology).

use crate::contours::{ContourId, ContourSet};
use crate::geometry::{fill_even_odd, Point};
use crate::image::field::neighbours8;
use crate::image::LevelView;
use crate::topology::TopologyEvent;

/// Region score a pixel must reach (or go below, towards background) to open a hole.
pub const NUCLEATE_SCORE: f64 = 0.5;

/// Smallest connected piece of background, in pixels of the level, that opens a hole.
pub const NUCLEATE_PIXELS: usize = 4;

/// Opens a hole ring at each piece of clear background inside the region of `set`, on
/// the pyramid level `view` shows (`scale` full-resolution pixels per level pixel). Returns the
/// events (one [`TopologyEvent::HoleMade`] per hole).
pub fn nucleate(set: &mut ContourSet, view: &LevelView, scale: f64) -> Vec<TopologyEvent> {
    let image = view.image();
    let (w, h) = (image.width, image.height);
    let ids: Vec<ContourId> = set.contour_ids().collect();
    let rings: Vec<Vec<Point>> = ids
        .iter()
        .map(|&id| {
            set.ring_points(id)
                .into_iter()
                .map(|p| p * (1.0 / scale))
                .collect()
        })
        .collect();
    let score = |i: usize| view.pixel_score(i);
    // Inside, and clearly background (scored only inside; listed, as they are few).
    let mut inside = Bits::new(w * h);
    let mut listed = Vec::new();
    fill_even_odd(&rings, w, h, |i| {
        inside.set(i, true);
        if score(i) <= -NUCLEATE_SCORE {
            listed.push(i);
        }
    });
    // Well inside: the eight neighbours too.
    let deep = |i: usize| {
        let (x, y) = (i % w, i / w);
        x > 0
            && y > 0
            && x + 1 < w
            && y + 1 < h
            && (y - 1..=y + 1).all(|yy| (x - 1..=x + 1).all(|xx| inside.get(yy * w + xx)))
    };
    listed.retain(|&i| deep(i));
    // The inside mask becomes the candidates' (one image-sized mask, not two).
    let mut candidate = inside;
    candidate.clear();
    for &i in &listed {
        candidate.set(i, true);
    }
    let mut centres = Vec::new();
    let mut stack = Vec::new();
    for &start in &listed {
        if !candidate.get(start) {
            continue;
        }
        // One 8-connected piece, cleared as it is visited.
        candidate.set(start, false);
        stack.push(start);
        let (mut count, mut best, mut best_score) = (0usize, start, f64::INFINITY);
        while let Some(i) = stack.pop() {
            count += 1;
            let s = score(i);
            if s < best_score {
                (best, best_score) = (i, s);
            }
            for j in neighbours8(i, w, h) {
                if candidate.get(j) {
                    candidate.set(j, false);
                    stack.push(j);
                }
            }
        }
        if count < NUCLEATE_PIXELS {
            continue;
        }
        centres.push(Point::new((best % w) as f64 + 0.5, (best / w) as f64 + 0.5));
    }
    // Which ring each hole opens in, for all at once: asking the set for every ring's
    // parent per hole cost O(rings²) a hole, minutes on a wrap over thousands of specks.
    // A new hole is a speck in its own piece of background, inside no other new hole, so
    // the enclosures found before any opens hold for all.
    let areas: Vec<f64> = ids.iter().map(|&id| set.signed_area(id).abs()).collect();
    let enclosing = innermost_rings(&rings, &areas, &centres, h);
    centres
        .into_iter()
        .zip(enclosing)
        .filter_map(|(c, k)| open_hole(set, c * scale, 0.4 * scale, ids[k?]))
        .collect()
}

/// For each of `points` (at pixel centres of a level `h` rows high), the index of the
/// smallest of `rings` (by `areas`) that contains it: a ray along its row to the right
/// crosses that ring's edges an odd number of times (edges counted half-open in y, so a
/// vertex on the row counts once). Only the rows with points are looked at.
fn innermost_rings(
    rings: &[Vec<Point>],
    areas: &[f64],
    points: &[Point],
    h: usize,
) -> Vec<Option<usize>> {
    let row = |p: &Point| (p.y.floor().max(0.0) as usize).min(h.saturating_sub(1));
    let mut wanted = vec![false; h];
    for p in points {
        wanted[row(p)] = true;
    }
    // The crossings of each wanted row's centre line: (ring, x).
    let mut crossings: Vec<Vec<(usize, f64)>> = vec![Vec::new(); h];
    for (k, ring) in rings.iter().enumerate() {
        for (i, &a) in ring.iter().enumerate() {
            let b = ring[(i + 1) % ring.len()];
            let (lo, hi) = (a.y.min(b.y), a.y.max(b.y));
            let first = (lo - 0.5).ceil().max(0.0) as usize;
            for y in first..h {
                let yc = y as f64 + 0.5;
                if yc >= hi {
                    break;
                }
                if yc >= lo && wanted[y] {
                    let x = a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y);
                    crossings[y].push((k, x));
                }
            }
        }
    }
    points
        .iter()
        .map(|p| {
            let mut odd: Vec<usize> = Vec::new();
            for &(k, x) in &crossings[row(p)] {
                if x > p.x {
                    match odd.iter().position(|&o| o == k) {
                        Some(i) => {
                            odd.swap_remove(i);
                        }
                        None => odd.push(k),
                    }
                }
            }
            odd.into_iter()
                .min_by(|&a, &b| areas[a].total_cmp(&areas[b]))
        })
        .collect()
}

/// One bit per pixel: the masks here are image-sized and live at the run's peak (a
/// `Vec<bool>` is eight times the memory).
struct Bits(Vec<u64>);

impl Bits {
    fn new(n: usize) -> Self {
        Bits(vec![0; n.div_ceil(64)])
    }
    #[inline]
    fn get(&self, i: usize) -> bool {
        self.0[i / 64] >> (i % 64) & 1 == 1
    }
    #[inline]
    fn set(&mut self, i: usize, on: bool) {
        let bit = 1u64 << (i % 64);
        if on {
            self.0[i / 64] |= bit;
        } else {
            self.0[i / 64] &= !bit;
        }
    }
    fn clear(&mut self) {
        self.0.fill(0);
    }
}

/// A square hole ring of half-diagonal `r` around `centre` (clockwise: a hole) inside
/// ring `from`, unless it would touch a ring.
fn open_hole(
    set: &mut ContourSet,
    centre: Point,
    r: f64,
    from: ContourId,
) -> Option<TopologyEvent> {
    let ring = [
        centre + Point::new(0.0, r),
        centre + Point::new(r, 0.0),
        centre + Point::new(0.0, -r),
        centre + Point::new(-r, 0.0),
    ];
    let hole = set.add_ring(&ring).ok()?;
    Some(TopologyEvent::HoleMade { from, hole })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::signed_area;

    fn square(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
        vec![
            Point::new(x0, y0),
            Point::new(x1, y0),
            Point::new(x1, y1),
            Point::new(x0, y1),
        ]
    }

    /// An island in a hole of a region, and a region beside: each point finds the
    /// smallest ring around it, vertices on its row counted once.
    #[test]
    fn innermost_rings_find_the_smallest_ring_around_each_point() {
        let rings = vec![
            square(1.0, 1.0, 30.0, 30.0),
            square(5.0, 5.0, 25.0, 25.0),
            square(10.0, 10.0, 20.0, 20.0),
            square(40.0, 2.5, 50.0, 12.5),
        ];
        let areas: Vec<f64> = rings.iter().map(|r| signed_area(r).abs()).collect();
        let at = |x: f64, y: f64| Point::new(x + 0.5, y + 0.5);
        let points = [
            at(2.0, 15.0),
            at(7.0, 15.0),
            at(15.0, 15.0),
            at(45.0, 2.0),
            at(45.0, 12.0),
            at(35.0, 15.0),
        ];
        assert_eq!(
            innermost_rings(&rings, &areas, &points, 40),
            [Some(0), Some(1), Some(2), Some(3), None, None]
        );
    }
}
