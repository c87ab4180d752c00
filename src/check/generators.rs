//! Random ring sets and random moves, degenerate ones included on purpose.

use super::Rng;
use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{Aabb, Point};

/// A star-shaped ring around `c` with radii in [r0, r1], `k` vertices, positive area
/// (outer) or reversed (hole).
pub fn star_ring(rng: &mut Rng, c: Point, r0: f64, r1: f64, k: usize, hole: bool) -> Vec<Point> {
    let mut pts: Vec<Point> = (0..k)
        .map(|i| {
            let a = std::f64::consts::TAU * (i as f64 + rng.range(-0.3, 0.3)) / k as f64;
            let r = rng.range(r0, r1);
            Point::new(c.x + r * a.cos(), c.y + r * a.sin())
        })
        .collect();
    if hole {
        pts.reverse();
    }
    pts
}

/// How moves are drawn.
#[derive(Clone, Copy, Debug)]
pub struct MoveMix {
    /// Snap every target to the integer lattice (makes exact degeneracies frequent).
    pub lattice: bool,
    /// The broad phase of the set under test.
    pub broad: BroadPhaseKind,
    /// Clamp every target to the domain, as the evolver does at the image border: many
    /// vertices and edges then lie on the walls, collinear with each other.
    pub wall: bool,
}

/// Draws a target for vertex `v`: small, medium, toward another vertex (topology events),
/// or deliberately degenerate (onto a vertex, an edge, a neighbour's line).
pub fn draw_target(set: &ContourSet, v: u32, rng: &mut Rng, mix: MoveMix) -> Point {
    let o = set.position(v);
    let other = loop {
        let w = rng.below(set.vertex_capacity()) as u32;
        if set.is_alive(w) {
            break w;
        }
    };
    let kind = rng.below(100);
    let mut q = match kind {
        0..=39 => o + Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
        40..=59 => o + Point::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0)),
        60..=79 => set.position(other) + Point::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)),
        80..=84 => set.position(other),
        85..=89 => set.position(other).lerp(set.position(set.next(other)), 0.5),
        90..=94 => {
            let (p, pp) = (
                set.position(set.prev(v)),
                set.position(set.prev(set.prev(v))),
            );
            p + (p - pp) * rng.range(0.2, 1.5)
        }
        _ => o.lerp(set.position(set.next(v)), rng.range(-0.5, 1.5)),
    };
    if mix.lattice {
        q = Point::new(q.x.round(), q.y.round());
    }
    if mix.wall {
        return set.domain().clamp(q);
    }
    set.domain().expand(10.0).clamp(q)
}

/// Builds a set of `k` star-shaped outer rings on a 3×3 layout, some with a hole.
pub fn random_rings(rng: &mut Rng, k: usize, max_edge: f64) -> ContourSet {
    random_rings_in(rng, k, max_edge, BroadPhaseKind::Bins)
}

/// [`random_rings`] with the broad phase of `kind`.
pub fn random_rings_in(rng: &mut Rng, k: usize, max_edge: f64, kind: BroadPhaseKind) -> ContourSet {
    let domain = Aabb {
        min: Point::new(0.0, 0.0),
        max: Point::new(100.0, 100.0),
    };
    let mut set = ContourSet::with_broad_phase(domain, max_edge, kind);
    let mut slots: Vec<usize> = (0..9).collect();
    for _ in 0..k.min(9) {
        let s = slots.swap_remove(rng.below(slots.len()));
        let c = Point::new(17.0 + 33.0 * (s % 3) as f64, 17.0 + 33.0 * (s / 3) as f64);
        add_star(&mut set, rng, c);
    }
    set
}

/// Adds a star-shaped ring (with a hole half the time) centred at `c` if it fits: it must
/// neither cross nor enclose nor sit inside what is there (add_ring only refuses
/// crossings; a star around small leftover rings would nest outer in outer).
pub fn add_star(set: &mut ContourSet, rng: &mut Rng, c: Point) -> bool {
    let max_edge = set.max_edge();
    let r1 = rng.range(7.0, 13.0);
    let k = ((std::f64::consts::TAU * r1 * 1.35 / max_edge).ceil() as usize).max(5) + rng.below(6);
    let outer = star_ring(rng, c, r1 * 0.6, r1, k, false);
    let fits = |set: &mut ContourSet, id| {
        let ok = set.sanity_check().is_ok();
        if !ok {
            set.remove_ring(id);
        }
        ok
    };
    match set.add_ring(&outer) {
        Ok(id) if fits(set, id) => {}
        _ => return false,
    }
    if rng.below(2) == 0 {
        let hr = r1 * 0.45;
        let kh =
            ((std::f64::consts::TAU * hr * 1.35 / max_edge).ceil() as usize).max(3) + rng.below(3);
        let hole = star_ring(rng, c, hr * 0.6, hr, kh, true);
        if let Ok(id) = set.add_ring(&hole) {
            fits(set, id);
        }
    }
    true
}
