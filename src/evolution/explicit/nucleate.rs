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

use crate::contours::ContourSet;
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
    let rings: Vec<Vec<Point>> = set
        .contour_ids()
        .map(|id| {
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
    let mut events = Vec::new();
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
        let centre = Point::new((best % w) as f64 + 0.5, (best / w) as f64 + 0.5) * scale;
        if let Some(event) = open_hole(set, centre, 0.4 * scale) {
            events.push(event);
        }
    }
    events
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

/// A square hole ring of half-diagonal `r` around `centre` (clockwise: a hole), unless
/// it would touch a ring; the event names the ring that encloses it.
fn open_hole(set: &mut ContourSet, centre: Point, r: f64) -> Option<TopologyEvent> {
    let ring = [
        centre + Point::new(0.0, r),
        centre + Point::new(r, 0.0),
        centre + Point::new(0.0, -r),
        centre + Point::new(-r, 0.0),
    ];
    let hole = set.add_ring(&ring).ok()?;
    let enclosing = set
        .parents()
        .into_iter()
        .find_map(|(id, parent)| (id == hole).then_some(parent))
        .flatten();
    match enclosing {
        Some(from) => Some(TopologyEvent::HoleMade { from, hole }),
        None => {
            // Outside every region after all: no hole there.
            set.remove_ring(hole);
            None
        }
    }
}
