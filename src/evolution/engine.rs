//! The engines behind an [`super::Evolver`]: one trait, three implementations.
//!
//! - [`super::explicit::Explicit`] moves polygon vertices through the topology core
//!   (seed 003), generic over what differs between the adaptive engine and the
//!   topology-preserving one (how a vertex moves, the extra push, the remesh gap; seed 004);
//! - [`super::implicit::ImplicitEngine`] marches fronts on a pixel grid and keeps
//!   topology with simple points and cut edges (seed 000).
//!
//! The evolver owns the schedule (pyramid levels, convergence) and the event log; an
//! engine only does frames. [`Engines`] dispatches by enum, as the broad phase does, so an
//! evolver stays `Clone` (the app's checkpoints) and calls are static.

use super::explicit::{Adaptive, Explicit, Preserve, Track};
use super::forces::ForceWeights;
use super::implicit::ImplicitEngine;
use crate::contours::ContourSet;
use crate::geometry::Point;
use crate::topology::{MotionRegion, TopologyEvent};

/// What one frame did.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// Frames done after this one (the implicit engine may count several per call).
    pub index: usize,
    /// Pyramid level the frame ran on (0: full resolution).
    pub level: usize,
    /// Topology events of the frame's moves, in order.
    pub events: Vec<TopologyEvent>,
    /// Area of the region after the frame, square pixels.
    pub area: f64,
    /// Vertices after the frame.
    pub vertices: usize,
    /// Contours (outer rings and holes) after the frame.
    pub contours: usize,
    /// Mean |displacement| in pixels.
    pub mean_speed: f64,
    /// Sum of |region score| over vertices: an energy-like measure that falls as contours
    /// settle on edges.
    pub energy: f64,
    /// Share of vertices that moved noticeably.
    pub active_share: f64,
    /// The run reached its equilibrium with this frame.
    pub converged: bool,
    /// The motion regions of the moves that caused this frame's events.
    pub motions: Vec<MotionRegion>,
}

/// An engine: advances contours one frame at a time.
pub trait Engine {
    /// One frame on pyramid level `level`; `index` is the number of frames done before.
    /// The returned frame's `level` and `converged` are the schedule's to fill.
    fn step(&mut self, index: usize, level: usize) -> Frame;
    /// Runs to the end in one call if the engine needs no frame-by-frame schedule (the
    /// implicit engine marches to its end and extracts contours once); `None` otherwise.
    fn finish(&mut self, index: usize, frames_left: usize) -> Option<Frame>;
    /// Moves to the finer pyramid level `level` (refining the rings); returns the events.
    fn refine(&mut self, level: usize) -> Vec<TopologyEvent>;
    /// The contours now.
    fn contours(&self) -> &ContourSet;
    /// The contours, for hand edits and the final clutter filter.
    fn contours_mut(&mut self) -> &mut ContourSet;
    /// `Some(done)` for an engine that knows when it is done; `None`: the schedule judges.
    fn settled(&self) -> Option<bool>;
    /// Places where the engine held fronts apart that the adaptive engine would have
    /// joined (0 for the adaptive engine).
    fn held_contacts(&self, level: usize) -> usize;
    /// New force weights and step for the frames to come (the implicit engine's speeds
    /// come from the intensity model alone: nothing changes there).
    fn set_forces(&mut self, weights: ForceWeights, step: f64);
    /// Opens holes where the region covers clear background on pyramid level `level`
    /// (only the adaptive engine; see [`super::explicit::nucleate`]); returns the events.
    fn nucleate(&mut self, level: usize) -> Vec<TopologyEvent>;
    /// A hand drag of vertex `v` towards `to` on pyramid level `level` (see
    /// [`super::Evolver::hand_drag`]): the events, and the vertex that leads at the end.
    /// An engine whose contours are extracted from a grid (the implicit one) makes no
    /// move: no event, no lead.
    fn hand_drag(&mut self, v: u32, to: Point, level: usize) -> (Vec<TopologyEvent>, Option<u32>);
    /// A brush stroke of `radius` from `from` to `to` on pyramid level `level` (see
    /// [`super::Evolver::brush`]); returns the events (none in the implicit engine).
    fn brush(&mut self, from: Point, to: Point, radius: f64, level: usize) -> Vec<TopologyEvent>;
}

/// The three engines, dispatched by enum.
#[derive(Clone)]
pub enum Engines {
    /// Topology adapts (seed 003).
    Adaptive(Explicit<Adaptive>),
    /// Topology kept explicitly with a gap (seed 004).
    Preserve(Explicit<Preserve>),
    /// One object per seed that may divide (seed 003 under the tracking policy).
    Track(Explicit<Track>),
    /// Topology kept implicitly (seed 000).
    Implicit(Box<ImplicitEngine>),
}

macro_rules! each {
    ($self:expr, $e:ident => $body:expr) => {
        match $self {
            Engines::Adaptive($e) => $body,
            Engines::Preserve($e) => $body,
            Engines::Track($e) => $body,
            Engines::Implicit($e) => $body,
        }
    };
}

impl Engines {
    /// The explicit engines' share of the image model (the implicit engine keeps its
    /// own grid and none).
    pub(crate) fn image_mut(&mut self) -> Option<&mut std::sync::Arc<crate::image::ImageModel>> {
        match self {
            Engines::Adaptive(e) => Some(e.image_mut()),
            Engines::Preserve(e) => Some(e.image_mut()),
            Engines::Track(e) => Some(e.image_mut()),
            Engines::Implicit(_) => None,
        }
    }
}

impl Engine for Engines {
    fn step(&mut self, index: usize, level: usize) -> Frame {
        each!(self, e => e.step(index, level))
    }
    fn finish(&mut self, index: usize, frames_left: usize) -> Option<Frame> {
        each!(self, e => e.finish(index, frames_left))
    }
    fn refine(&mut self, level: usize) -> Vec<TopologyEvent> {
        each!(self, e => e.refine(level))
    }
    fn contours(&self) -> &ContourSet {
        each!(self, e => e.contours())
    }
    fn contours_mut(&mut self) -> &mut ContourSet {
        each!(self, e => e.contours_mut())
    }
    fn settled(&self) -> Option<bool> {
        each!(self, e => e.settled())
    }
    fn held_contacts(&self, level: usize) -> usize {
        each!(self, e => e.held_contacts(level))
    }
    fn set_forces(&mut self, weights: ForceWeights, step: f64) {
        each!(self, e => e.set_forces(weights, step))
    }
    fn nucleate(&mut self, level: usize) -> Vec<TopologyEvent> {
        each!(self, e => e.nucleate(level))
    }
    fn hand_drag(&mut self, v: u32, to: Point, level: usize) -> (Vec<TopologyEvent>, Option<u32>) {
        each!(self, e => e.hand_drag(v, to, level))
    }
    fn brush(&mut self, from: Point, to: Point, radius: f64, level: usize) -> Vec<TopologyEvent> {
        each!(self, e => e.brush(from, to, radius, level))
    }
}
