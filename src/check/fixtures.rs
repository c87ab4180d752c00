//! The benchmark and profiling set-up (a grid of rings and the moves that jitter them),
//! and test images shared by the test suites.

use super::Rng;
use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{Aabb, Point};

/// `rings` circles of 100 vertices (radius 25, edges ≈ 1.6 px, bound 2.5 px) on a square
/// grid of pitch 60 px: the benchmark and profiling set-up.
pub fn ring_grid(rings: usize, kind: BroadPhaseKind) -> ContourSet {
    let side = (rings as f64).sqrt().ceil() as usize;
    let pitch = 60.0;
    let extent = side as f64 * pitch;
    let mut set = ContourSet::with_broad_phase(
        Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(extent, extent),
        },
        2.5,
        kind,
    );
    for i in 0..rings {
        let c = Point::new(
            (i % side) as f64 * pitch + 30.0,
            (i / side) as f64 * pitch + 30.0,
        );
        let pts: Vec<Point> = (0..100)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 100.0;
                Point::new(c.x + 25.0 * a.cos(), c.y + 25.0 * a.sin())
            })
            .collect();
        set.add_ring(&pts).expect("grid rings are disjoint");
    }
    set
}

/// The benchmark's moves on a [`ring_grid`]: each vertex in turn steps out by a seeded
/// jitter of up to 0.2 px, then back home on the next move, like an evolving contour;
/// the set stays as built. The same seed on two sets built alike gives the same moves.
pub struct JitterMoves {
    verts: Vec<u32>,
    home: Vec<Point>,
    jitter: Vec<Point>,
    k: usize,
    out: bool,
}

/// Distinct jitters (a power of two: the index wraps by a mask).
const JITTERS: usize = 4096;

impl JitterMoves {
    pub fn new(set: &ContourSet, seed: u64) -> Self {
        let mut rng = Rng(seed);
        let verts: Vec<u32> = set.vertices().collect();
        let home = verts.iter().map(|&v| set.position(v)).collect();
        let jitter = (0..JITTERS)
            .map(|_| Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)))
            .collect();
        JitterMoves {
            verts,
            home,
            jitter,
            k: 0,
            out: true,
        }
    }

    /// The next move: which vertex, and where to.
    #[inline]
    pub fn next_move(&mut self) -> (u32, Point) {
        let k = self.k;
        let to = if self.out {
            self.home[k] + self.jitter[k & (JITTERS - 1)]
        } else {
            self.home[k]
        };
        // The next vertex by a compare, not a division: a 64-bit division alone costs
        // tens of cycles, a good part of what the benchmarks measure.
        if !self.out {
            self.k = if k + 1 == self.verts.len() { 0 } else { k + 1 };
        }
        self.out = !self.out;
        (self.verts[k], to)
    }
}

/// A bright ring (grey 200 between radii `inner` and `outer`) on dark background (grey
/// 30), centred in a `side` × `side` image: a wrap over it must open the ring's hole.
pub fn ring_image(side: u32, inner: f64, outer: f64) -> image::GrayImage {
    let c = side as f64 / 2.0;
    image::GrayImage::from_fn(side, side, |x, y| {
        let d = (x as f64 + 0.5 - c).hypot(y as f64 + 0.5 - c);
        image::Luma([if (inner..outer).contains(&d) { 200 } else { 30 }])
    })
}
