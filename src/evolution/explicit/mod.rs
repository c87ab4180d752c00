//! The explicit engine: polygon vertices moved one at a time through the topology core
//! (seed 003 §3), on the pyramid level the schedule gives, with remeshing after each frame
//! (edges within [U, 2√2·U] for grid spacing U = 2^level, seed 004 §2.3).
//!
//! Generic over [`Motion`]: [`Adaptive`] and [`Preserve`] share everything but how a
//! vertex moves, the extra push and the remesh gap.
//!
//! The image rectangle is a wall: every target is first clamped to [0, W] × [0, H], then
//! moved with `move_vertex` as any other target, so the motion region stays exact and the
//! topology core needs no special case. A vertex pushed against the wall slides along it.
//!
//! Choices: vertices that stayed still for a while are only revisited every eighth frame
//! unless a neighbour moves (the image does not change, so a still vertex among still
//! neighbours feels the same forces), so a long growth along a spiral costs what its tip
//! costs; a vertex whose image force turned round since its last move takes half the step
//! it took (down to an eighth; the step grows back while the force keeps its sign), so it
//! settles on an edge instead of jumping across it frame after frame (phase-contrast
//! halos made whole levels chatter until the stall rule ended them); a refused
//! (degenerate) move is retried once at half length, then the vertex waits for the next
//! frame.

mod hand;
mod motion;
pub mod nucleate;

pub use motion::{Adaptive, Motion, Preserve, Track, PRESERVE_GAP};

use super::engine::{Engine, Frame};
use super::forces::{normal_speed, ForceWeights};
use super::remesh::remesh;
use crate::contours::ContourSet;
use crate::geometry::{Aabb, Point};
use crate::image::field::Pyramid;
use crate::image::ImageModel;
use crate::topology::{MotionRegion, TopologyEvent};
use std::sync::Arc;

/// Smallest share of the step a vertex whose force keeps turning round still takes.
const MIN_GAIN: f32 = 0.125;

/// The explicit engine's state.
#[derive(Clone)]
pub struct Explicit<M: Motion> {
    set: ContourSet,
    /// What the forces read of the image.
    image: Arc<ImageModel>,
    weights: ForceWeights,
    /// Largest step per frame, as a fraction of the level's grid spacing.
    step: f64,
    /// The image rectangle: the wall no vertex crosses.
    bounds: Aabb,
    /// Per vertex id: frames since it last moved noticeably (saturating).
    still: Vec<u8>,
    /// Per vertex: the sign of the image force last time, and the share of the step it
    /// takes now (halved each time the force turns round).
    last_sign: Vec<i8>,
    gain: Vec<f32>,
    motion: std::marker::PhantomData<M>,
}

/// Grid spacing of pyramid level `level`, and the edge bounds there.
fn spacing(level: usize) -> (f64, f64, f64) {
    let scale = Pyramid::scale(level);
    (scale, scale, 2.0 * std::f64::consts::SQRT_2 * scale)
}

impl<M: Motion> Explicit<M> {
    /// What the forces read of the image (to be swapped, not shared, by the evolver).
    pub(crate) fn image_mut(&mut self) -> &mut Arc<ImageModel> {
        &mut self.image
    }

    /// An engine moving the rings of `set` under the forces of `image`.
    pub fn new(set: ContourSet, image: Arc<ImageModel>, weights: ForceWeights, step: f64) -> Self {
        let bounds = set.domain();
        Explicit {
            set,
            image,
            weights,
            step,
            bounds,
            still: Vec::new(),
            last_sign: Vec::new(),
            gain: Vec::new(),
            motion: std::marker::PhantomData,
        }
    }

    /// Moves `v` once under the image forces; returns (distance moved, |region score|).
    #[inline]
    fn move_one(
        &mut self,
        v: u32,
        level: usize,
        near: &mut Vec<u32>,
        events: &mut Vec<TopologyEvent>,
        motions: &mut Vec<MotionRegion>,
    ) -> (f64, f64) {
        let scale = Pyramid::scale(level);
        let max_step = self.step * scale;
        let w = self.weights;
        let (p, n) = (self.set.prev(v), self.set.next(v));
        let (pp, x, pn) = (
            self.set.position(p),
            self.set.position(v),
            self.set.position(n),
        );
        let normal = outward_normal(pp, x, pn);
        let probe = self.image.level(level).probe(x * (1.0 / scale), normal);
        let f = normal_speed(&probe, &w);
        // Stretching pulls to the neighbours' midpoint; bending smooths that pull.
        let lap = (pp + pn) * 0.5 - x;
        let lap_p = (self.set.position(self.set.prev(p)) + x) * 0.5 - pp;
        let lap_n = (x + self.set.position(self.set.next(n))) * 0.5 - pn;
        let bend = lap - (lap_p + lap_n) * 0.5;
        let sign = if f.speed > 0.0 { 1 } else { -1 };
        let vi = v as usize;
        self.gain[vi] = if sign == -self.last_sign[vi] {
            (self.gain[vi] * 0.5).max(MIN_GAIN)
        } else {
            (self.gain[vi] * 1.5).min(1.0)
        };
        self.last_sign[vi] = sign;
        let push = f.speed * max_step * self.gain[vi] as f64;
        let mut d = normal * push + lap * w.stretch + bend * w.bend;
        if let Some(extra) = M::push(&self.set, v, scale, near) {
            d = d + extra * max_step;
        }
        let len = d.norm();
        if len > max_step {
            d = d * (max_step / len);
        }
        let before = events.len();
        let to = self.bounds.clamp(x + d);
        let moved = M::advance(&mut self.set, v, to, scale, events);
        if events.len() > before {
            motions.push(MotionRegion::new(pp, x, pn, Some(to)));
        }
        (moved, f.region.abs())
    }
}

impl<M: Motion> Engine for Explicit<M> {
    /// Every vertex moves once (still ones among still neighbours only every eighth
    /// frame), then the rings are remeshed.
    fn step(&mut self, index: usize, level: usize) -> Frame {
        let (scale, d_min, d_max) = spacing(level);
        let mut events = Vec::new();
        let mut motions = Vec::new();
        let (mut moved_sum, mut energy, mut active, mut visited) = (0.0, 0.0, 0usize, 0usize);
        let mut order = Vec::with_capacity(self.set.vertex_count());
        self.set.vertices_in_ring_order(&mut order);
        let capacity = self.set.vertex_capacity();
        if self.still.len() < capacity {
            self.still.resize(capacity, 0);
            self.last_sign.resize(capacity, 0);
            self.gain.resize(capacity, 1.0);
        }
        let revisit_all = index.is_multiple_of(8);
        let mut near = Vec::new();
        for v in order {
            if !self.set.is_alive(v) {
                continue;
            }
            let (p, n) = (self.set.prev(v), self.set.next(v));
            let resting = |u: u32| self.still.get(u as usize).is_some_and(|&s| s >= 3);
            if !revisit_all && resting(v) && resting(p) && resting(n) {
                continue;
            }
            visited += 1;
            let (moved, region) = self.move_one(v, level, &mut near, &mut events, &mut motions);
            energy += region;
            if moved > 0.05 * scale {
                active += 1;
                self.still[v as usize] = 0;
            } else if let Some(s) = self.still.get_mut(v as usize) {
                *s = s.saturating_add(1);
            }
            moved_sum += moved;
        }
        remesh(&mut self.set, d_min, d_max, M::gap(scale), &mut events);
        let vertices = self.set.vertex_count().max(1);
        Frame {
            index: index + 1,
            level,
            events,
            area: self.set.region_area(),
            vertices: self.set.vertex_count(),
            contours: self.set.contour_count(),
            mean_speed: moved_sum / visited.max(1) as f64,
            energy,
            active_share: active as f64 / vertices as f64,
            converged: false,
            motions,
        }
    }

    fn finish(&mut self, _: usize, _: usize) -> Option<Frame> {
        None
    }

    /// Global refinement on a level change (seed 004), then the tighter edge bound: set
    /// before the split, the bound would keep the coarse edges' length as its reach (and
    /// the broad phase its coarse cells) for the whole level.
    fn refine(&mut self, level: usize) -> Vec<TopologyEvent> {
        let (scale, d_min, d_max) = spacing(level);
        self.still.iter_mut().for_each(|s| *s = 0);
        self.last_sign.iter_mut().for_each(|s| *s = 0);
        self.gain.iter_mut().for_each(|g| *g = 1.0);
        let mut events = Vec::new();
        remesh(&mut self.set, d_min, d_max, M::gap(scale), &mut events);
        self.set.set_max_edge(d_max);
        events
    }

    fn contours(&self) -> &ContourSet {
        &self.set
    }
    fn contours_mut(&mut self) -> &mut ContourSet {
        &mut self.set
    }
    fn settled(&self) -> Option<bool> {
        None
    }
    fn held_contacts(&self, level: usize) -> usize {
        M::held(&self.set, Pyramid::scale(level))
    }
    fn nucleate(&mut self, level: usize) -> Vec<TopologyEvent> {
        if !M::ADAPTS {
            return Vec::new();
        }
        let events = nucleate::nucleate(
            &mut self.set,
            &self.image.level(level),
            Pyramid::scale(level),
        );
        if !events.is_empty() {
            // New rings may reuse slots of vertices that were resting.
            self.still.iter_mut().for_each(|s| *s = 0);
        }
        events
    }
    fn set_forces(&mut self, weights: ForceWeights, step: f64) {
        self.weights = weights;
        self.step = step;
    }
    fn hand_drag(&mut self, v: u32, to: Point, level: usize) -> (Vec<TopologyEvent>, Option<u32>) {
        self.drag(v, to, level)
    }
    fn brush(&mut self, from: Point, to: Point, radius: f64, level: usize) -> Vec<TopologyEvent> {
        self.brush_stroke(from, to, radius, level)
    }
}

/// Outward unit normal at x between neighbours p and n (region on the left).
#[inline]
pub fn outward_normal(p: Point, x: Point, n: Point) -> Point {
    let right = |a: Point, b: Point| {
        let t = b - a;
        let l = t.norm();
        if l > 0.0 {
            Point::new(t.y / l, -t.x / l)
        } else {
            Point::default()
        }
    };
    let s = right(p, x) + right(x, n);
    let l = s.norm();
    if l > 0.0 {
        s * (1.0 / l)
    } else {
        Point::default()
    }
}
