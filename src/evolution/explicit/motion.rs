//! What differs between the adaptive engine and the topology-preserving one: how a vertex
//! moves, the extra push, the gap remeshing keeps.
//!
//! - [`Adaptive`] (seed 003): a move goes through [`ContourSet::move_vertex`], which
//!   splices and deletes rings where the motion region says so; a refused (degenerate)
//!   move is retried once at half length.
//! - [`Preserve`] (seed 004 §2.4): a move is shortened until its edges keep a gap of
//!   [`PRESERVE_GAP`] grid spacings to every other edge
//!   ([`ContourSet::move_vertex_preserving`]), parts closer than 1.5 spacings push each
//!   other apart (the non-self-intersection force), and remeshing removes a vertex only
//!   where the chord keeps the gap.

use crate::contours::ContourSet;
use crate::geometry::{Aabb, Point};
use crate::topology::{MoveError, TopologyEvent, TopologyPolicy};

/// Gap kept between contours in the preserving engine, in grid spacings of the level.
pub const PRESERVE_GAP: f64 = 0.3;

/// How the explicit engine moves vertices (static dispatch: no cost per move).
pub trait Motion: Clone + Default + Send + Sync + 'static {
    /// Whether contours may change topology (and so open holes in clear background).
    const ADAPTS: bool;
    /// The gap contours keep at grid spacing `scale` (`None`: contours may meet).
    fn gap(scale: f64) -> Option<f64>;
    /// Extra displacement of `v` in units of the step, if the engine pushes.
    fn push(set: &ContourSet, v: u32, scale: f64, near: &mut Vec<u32>) -> Option<Point>;
    /// Moves `v` towards `to` within a frame; returns the distance moved.
    fn advance(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        scale: f64,
        events: &mut Vec<TopologyEvent>,
    ) -> f64;
    /// One attempt of a hand-edit step (the caller retries a degenerate one shorter).
    fn attempt(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        scale: f64,
    ) -> Result<Vec<TopologyEvent>, MoveError>;
    /// Places where fronts are held apart (0 if they may meet).
    fn held(set: &ContourSet, scale: f64) -> usize;
}

/// Topology adapts: contours split, merge, make and lose holes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Adaptive;

/// Topology stays as initialised, with a gap between fronts that meet.
#[derive(Clone, Copy, Debug, Default)]
pub struct Preserve;

/// One object per seed that may divide: no merge, no new hole, splits carried out.
#[derive(Clone, Copy, Debug, Default)]
pub struct Track;

impl Motion for Adaptive {
    const ADAPTS: bool = true;
    #[inline]
    fn gap(_: f64) -> Option<f64> {
        None
    }
    #[inline]
    fn push(_: &ContourSet, _: u32, _: f64, _: &mut Vec<u32>) -> Option<Point> {
        None
    }
    fn advance(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        _: f64,
        events: &mut Vec<TopologyEvent>,
    ) -> f64 {
        shortened(set, v, to, &[1.0, 0.5], events, |s, v, q| {
            s.move_vertex(v, q)
        })
    }
    fn attempt(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        _: f64,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        set.move_vertex(v, to)
    }
    fn held(_: &ContourSet, _: f64) -> usize {
        0
    }
}

impl Motion for Preserve {
    const ADAPTS: bool = false;
    #[inline]
    fn gap(scale: f64) -> Option<f64> {
        Some(PRESERVE_GAP * scale)
    }
    fn push(set: &ContourSet, v: u32, scale: f64, near: &mut Vec<u32>) -> Option<Point> {
        Some(repulsion(set, v, 1.5 * scale, near, false))
    }
    fn advance(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        scale: f64,
        _: &mut Vec<TopologyEvent>,
    ) -> f64 {
        set.move_vertex_preserving(v, to, PRESERVE_GAP * scale)
            .unwrap_or(0.0)
    }
    fn attempt(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        scale: f64,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        set.move_vertex_preserving(v, to, PRESERVE_GAP * scale)
            .map(|_| Vec::new())
    }
    /// Vertices that ended within two gaps of another part of the boundary (not their own
    /// neighbours).
    fn held(set: &ContourSet, scale: f64) -> usize {
        held_near(set, scale, false)
    }
}

impl Motion for Track {
    const ADAPTS: bool = false;
    #[inline]
    fn gap(scale: f64) -> Option<f64> {
        Some(PRESERVE_GAP * scale)
    }
    fn push(set: &ContourSet, v: u32, scale: f64, near: &mut Vec<u32>) -> Option<Point> {
        Some(repulsion(set, v, 1.5 * scale, near, true))
    }
    fn advance(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        _: f64,
        events: &mut Vec<TopologyEvent>,
    ) -> f64 {
        shortened(set, v, to, &[1.0, 0.5, 0.25], events, |s, v, q| {
            s.move_vertex_under(v, q, TopologyPolicy::TRACKING)
        })
    }
    fn attempt(
        set: &mut ContourSet,
        v: u32,
        to: Point,
        _: f64,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        set.move_vertex_under(v, to, TopologyPolicy::TRACKING)
    }
    /// Vertices that ended within two gaps of another object.
    fn held(set: &ContourSet, scale: f64) -> usize {
        held_near(set, scale, true)
    }
}

/// Moves `v` towards `to` by the first share of the step in `shares` that `mv` accepts
/// (a degenerate or held move is retried shorter); returns the distance moved.
fn shortened(
    set: &mut ContourSet,
    v: u32,
    to: Point,
    shares: &[f64],
    events: &mut Vec<TopologyEvent>,
    mv: impl Fn(&mut ContourSet, u32, Point) -> Result<Vec<TopologyEvent>, MoveError>,
) -> f64 {
    let from = set.position(v);
    for &f in shares {
        let q = from.lerp(to, f);
        match mv(set, v, q) {
            Ok(ev) => {
                events.extend(ev);
                return from.dist(q);
            }
            Err(MoveError::Degenerate(_) | MoveError::Held(_)) => continue,
            Err(_) => return 0.0,
        }
    }
    0.0
}

/// Vertices within two gaps of another part of the boundary (with `others_only`, of
/// another object).
fn held_near(set: &ContourSet, scale: f64, others_only: bool) -> usize {
    let r = 2.0 * PRESERVE_GAP * scale;
    let mut near = Vec::new();
    set.vertices()
        .filter(|&v| repulsion(set, v, r, &mut near, others_only) != Point::default())
        .count()
}

/// Push away from vertices of other parts within `r` (not the ring's own neighbours
/// within four steps; with `others_only`, not its own ring at all): seed 004's
/// non-self-intersection force, in units of the step.
fn repulsion(set: &ContourSet, v: u32, r: f64, near: &mut Vec<u32>, others_only: bool) -> Point {
    let x = set.position(v);
    let ring = set.contour_of(v);
    let mut own = [v; 9];
    let (mut a, mut b) = (v, v);
    for i in 0..4 {
        a = set.prev(a);
        b = set.next(b);
        own[2 * i + 1] = a;
        own[2 * i + 2] = b;
    }
    set.vertices_near(&Aabb { min: x, max: x }.expand(r), near);
    let mut push = Point::default();
    for &w in near.iter() {
        if own.contains(&w) || (others_only && set.contour_of(w) == ring) {
            continue;
        }
        let d = x - set.position(w);
        let len = d.norm();
        if len > 0.0 && len < r {
            push = push + d * ((r - len) / (r * len));
        }
    }
    let l = push.norm();
    if l > 1.0 {
        push * (1.0 / l)
    } else {
        push
    }
}
