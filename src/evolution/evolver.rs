//! `Evolver`: contours moving under image forces one frame at a time (seed 003 §3 with
//! seed 004's multiscale schedule, remeshing and convergence test).
//!
//! A frame moves every vertex once, each move through [`ContourSet::move_vertex`], so
//! every topology change is exact and reported. Evolution runs coarse to fine over the
//! pyramid: on level l the grid spacing is U = 2^l pixels, edges are kept within
//! [U, 2√2·U] (seed 004), a step is at most 0.75·U, and the level ends when the share of
//! active vertices stays below 3% (seed 004's convergence test) with the area steady for
//! three frames — or, when noise keeps vertices chattering while the area stays put, after
//! 40 frames (on a coarse level the finer one will settle them).
//!
//! The image rectangle is a wall: every target a vertex is sent to is first clamped to
//! [0, W] × [0, H], then moved with `move_vertex` as any other target, so the motion
//! region stays exact and the topology core needs no special case. A vertex pushed
//! against the wall slides along it; an object cut by the border ends with its contour
//! running along the border. Initial shapes are clipped to the rectangle the same way.
//! Only a run that reached a level-0 equilibrium is `converged`: one that stopped at
//! `max_frames` or at the frame cap with areas still drifting is only finished.
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

use super::field::{Field, Pyramid};
use super::forces::{normal_speed, ForceWeights, IntensityModel, Polarity};
use super::implicit::Implicit;
use super::init::Shape;
use super::local::{self, Modality};
use super::remesh::remesh;
use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{Aabb, Point};
use crate::topology::{MoveError, TopologyEvent};

/// Frames one pyramid level may take before the next finer level takes over.
const LEVEL_FRAMES_CAP: usize = 600;
/// Smallest share of the step a vertex whose force keeps turning round still takes.
const MIN_GAIN: f32 = 0.125;
/// Frames after which a level whose area is steady ends even if vertices still chatter.
const STALL_FRAMES: usize = 40;

/// How topology may change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Mode {
    /// Contours split, merge, make and lose holes (seed 003).
    Adaptive,
    /// Topology stays as initialised: moves that would cross are shortened to keep a gap
    /// and nearby parts repel (seed 004).
    Preserve,
    /// Topology stays as initialised, implicitly: fast marching on a cut-edge grid
    /// (seed 000; see [`super::implicit`]).
    Implicit,
}

impl Mode {
    /// The name used on the command line and in exports.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Adaptive => "adaptive",
            Mode::Preserve => "preserve",
            Mode::Implicit => "implicit",
        }
    }
}

/// Edge bound of the contour set mirroring the implicit engine (marching-squares edges are
/// at most √2 pixels).
const IMPLICIT_MAX_EDGE: f64 = 2.0;

/// Vertices on each side that follow a hand-dragged vertex (with weights falling to 0).
const HAND_FOLLOW: usize = 3;

/// Gap kept between contours in `Mode::Preserve`, in grid spacings of the level.
const PRESERVE_GAP: f64 = 0.3;

/// Parameters of an evolution. `Params::default()` is the one set that serves every
/// public case.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Params {
    pub polarity: Polarity,
    #[serde(default = "default_mode")]
    pub mode: Mode,
    pub weights: ForceWeights,
    /// Largest step per frame, as a fraction of the level's grid spacing.
    pub step: f64,
    /// Frames allowed in all.
    pub max_frames: usize,
    /// Outer regions and holes smaller than this many square pixels are dropped at the end.
    pub min_area: f64,
    /// Share of active vertices below which a level counts as converged.
    pub converged_share: f64,
    /// Coarsest pyramid level's short side, pixels.
    pub coarsest_side: usize,
    /// Broad phase of the crossing search (same results, different speed and memory).
    #[serde(default)]
    pub broad_phase: BroadPhaseKind,
    /// The kind of image (phase contrast clips the halo; see [`super::local`]).
    #[serde(default)]
    pub modality: Modality,
    /// Compare with a local decision level (see [`super::local`]) instead of the global one.
    #[serde(default = "default_local")]
    pub local: bool,
    /// Radius of the local statistics in pixels; `None`: from the seeds or the image.
    #[serde(default)]
    pub local_radius: Option<f64>,
}

fn default_local() -> bool {
    true
}

fn default_mode() -> Mode {
    Mode::Adaptive
}

impl Default for Params {
    fn default() -> Self {
        Params {
            polarity: Polarity::Dark,
            mode: Mode::Adaptive,
            weights: ForceWeights::default(),
            step: 0.75,
            max_frames: 3000,
            min_area: 20.0,
            converged_share: 0.03,
            coarsest_side: 64,
            broad_phase: BroadPhaseKind::Bins,
            modality: Modality::Generic,
            local: true,
            local_radius: None,
        }
    }
}

/// Why an evolution could not start.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum EvolveError {
    #[error("the initialisation is empty: give at least one seed, rectangle or polygon")]
    EmptyInit,
    #[error("a shape of the initialisation is not usable: {0}")]
    BadShape(String),
    #[error("parameter {name} must be {what}, got {value}")]
    BadParameter {
        name: &'static str,
        what: &'static str,
        value: f64,
    },
}

/// A topology event with the frame it happened in.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FrameEvent {
    pub frame: usize,
    #[serde(flatten)]
    pub event: TopologyEvent,
}

/// What one frame did.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    pub index: usize,
    pub level: usize,
    pub events: Vec<TopologyEvent>,
    pub area: f64,
    pub vertices: usize,
    pub contours: usize,
    /// Mean |displacement| in pixels.
    pub mean_speed: f64,
    /// Sum of |region score| over vertices: an energy-like measure that falls as contours
    /// settle on edges.
    pub energy: f64,
    pub active_share: f64,
    pub converged: bool,
    /// The motion regions (p, o, n, q) of the moves that caused this frame's events.
    pub motions: Vec<[Point; 4]>,
}

/// Runs the evolution.
#[derive(Clone)]
pub struct Evolver {
    set: ContourSet,
    pyramid: std::sync::Arc<Pyramid>,
    /// Per pyramid level, the local decision level of the region term (empty: global).
    decision: std::sync::Arc<Vec<local::Decision>>,
    params: Params,
    model: IntensityModel,
    level: usize,
    frame: usize,
    calm: usize,
    level_frames: usize,
    /// Per-contour areas (sorted by id) after each of the last frames of this level.
    areas: Vec<Vec<(u32, f64)>>,
    converged: bool,
    /// Stopped without converging: the finest level hit its frame cap.
    stopped: bool,
    /// The image rectangle: the wall no vertex crosses.
    bounds: Aabb,
    /// Per vertex id: frames since it last moved noticeably (saturating).
    still: Vec<u8>,
    /// Per vertex: the sign of the image force last time, and the share of the step it
    /// takes now (halved each time the force turns round, so a vertex settles on an edge
    /// instead of jumping across it).
    last_sign: Vec<i8>,
    gain: Vec<f32>,
    events: Vec<FrameEvent>,
    width: usize,
    height: usize,
    /// The cut-edge fast marching state in `Mode::Implicit` (the set mirrors its contours).
    implicit: Option<Box<Implicit>>,
}

impl Evolver {
    pub fn new(image: &Field, init: &[Shape], params: Params) -> Result<Self, EvolveError> {
        check_params(&params)?;
        if init.is_empty() {
            return Err(EvolveError::EmptyInit);
        }
        check_shapes(init, image.width, image.height)?;
        // Phase contrast: the halo reads as background, clipped to the level of the band a
        // wrap shows.
        let band = (params.modality == Modality::PhaseContrast)
            .then(|| hints(image, init).1)
            .flatten();
        let image = local::for_modality(image, params.polarity, params.modality, band);
        let pyramid = std::sync::Arc::new(Pyramid::new(&image, params.coarsest_side, 4));
        let level = pyramid.levels.len() - 1;
        let fine = &pyramid.levels[0].image;
        let (object_hint, background_hint) = hints(fine, init);
        let model = IntensityModel::learn(fine, params.polarity, object_hint, background_hint);
        let decision = if params.local {
            let radius = params
                .local_radius
                .unwrap_or_else(|| local::object_scale(fine, &model));
            let floor = local::floor(fine, &model, params.modality);
            pyramid
                .levels
                .iter()
                .enumerate()
                .map(|(l, lv)| {
                    let r = (radius / Pyramid::scale(l)).round().max(1.0) as usize;
                    local::decision_field(&lv.image, r, &model, floor)
                })
                .collect()
        } else {
            Vec::new()
        };
        let spacing = Pyramid::scale(level);
        let domain = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(image.width as f64, image.height as f64),
        };
        let mut set = ContourSet::with_broad_phase(
            domain,
            spacing * 2.0 * std::f64::consts::SQRT_2,
            params.broad_phase,
        );
        for shape in init {
            // Overlapping shapes: a smaller copy still seeds the region; growth joins them.
            for f in [1.0, 0.5, 0.25] {
                let ring = shape.scaled(f).ring_within(spacing * 1.5, &domain);
                if ring.len() >= 3 && set.add_ring(&ring).is_ok() {
                    break;
                }
            }
        }
        // The initial region is the union of the shapes: a ring inside another shape's
        // ring (a seed inside the wrap rectangle) bounds nothing new, and an outer ring
        // nested in an outer ring would break the orientation invariant.
        let nested: Vec<_> = set
            .parents()
            .into_iter()
            .filter(|(_, parent)| parent.is_some())
            .map(|(id, _)| id)
            .collect();
        for id in nested {
            set.remove_ring(id);
        }
        if set.contour_count() == 0 {
            return Err(EvolveError::EmptyInit);
        }
        let implicit =
            (params.mode == Mode::Implicit).then(|| Box::new(Implicit::new(fine, model, init)));
        let mut ev = Evolver {
            set,
            pyramid,
            decision: std::sync::Arc::new(decision),
            params,
            model,
            level,
            frame: 0,
            calm: 0,
            level_frames: 0,
            areas: Vec::new(),
            converged: false,
            stopped: false,
            bounds: domain,
            still: Vec::new(),
            last_sign: Vec::new(),
            gain: Vec::new(),
            events: Vec::new(),
            width: image.width,
            height: image.height,
            implicit,
        };
        if ev.implicit.is_some() {
            ev.level = 0;
            ev.mirror_implicit();
            if ev.set.contour_count() == 0 {
                return Err(EvolveError::EmptyInit);
            }
        }
        Ok(ev)
    }

    /// In the topology-keeping modes, how many places held fronts apart where the adaptive
    /// engine would have changed topology: implicit — cut grid edges plus rejected
    /// pixels; preserve — vertices that ended within two gaps of another part of the
    /// boundary (not their own neighbours). 0 in adaptive mode.
    pub fn held_contacts(&self) -> usize {
        match self.params.mode {
            Mode::Adaptive => 0,
            Mode::Implicit => self.implicit.as_ref().map_or(0, |i| i.cuts + i.rejected),
            Mode::Preserve => {
                let r = 2.0 * PRESERVE_GAP * Pyramid::scale(self.level);
                let mut near = Vec::new();
                self.set
                    .vertices()
                    .filter(|&v| repulsion(&self.set, v, r, &mut near) != Point::default())
                    .count()
            }
        }
    }

    /// Rebuilds the contour set from the implicit engine's contours.
    fn mirror_implicit(&mut self) {
        let Some(imp) = &self.implicit else { return };
        let mut set = ContourSet::with_broad_phase(
            self.set.domain(),
            IMPLICIT_MAX_EDGE,
            self.params.broad_phase,
        );
        for ring in imp.rings() {
            // Rings from marching squares are disjoint by construction; a refusal here
            // would be a bug, never silently different output in release.
            let added = set.add_ring(&ring);
            debug_assert!(added.is_ok(), "implicit ring refused: {added:?}");
        }
        self.set = set;
    }

    /// One frame of the implicit engine: the fronts advance by one time unit.
    fn step_implicit(&mut self, until: f64) -> Frame {
        debug_assert!(until.is_finite());
        let imp = self.implicit.as_mut().expect("implicit mode");
        let before = imp.conquered;
        imp.advance(until);
        let moved = imp.conquered - before;
        self.converged = imp.is_done();
        // A frame is one time unit: after a long advance, count the units it took.
        self.frame = (self.frame + 1).max(imp.time().ceil() as usize);
        self.mirror_implicit();
        let vertices = self.set.vertex_count();
        Frame {
            index: self.frame,
            level: 0,
            events: Vec::new(),
            area: self.set.region_area(),
            vertices,
            contours: self.set.contour_count(),
            mean_speed: moved as f64 / vertices.max(1) as f64,
            energy: 0.0,
            active_share: moved as f64 / vertices.max(1) as f64,
            converged: self.converged,
            motions: Vec::new(),
        }
    }

    pub fn contours(&self) -> &ContourSet {
        &self.set
    }
    /// The fast marching state, in `Mode::Implicit`.
    pub fn implicit(&self) -> Option<&Implicit> {
        self.implicit.as_deref()
    }
    pub fn model(&self) -> IntensityModel {
        self.model
    }
    pub fn frames(&self) -> usize {
        self.frame
    }
    pub fn level(&self) -> usize {
        self.level
    }
    /// The run reached an equilibrium on the finest level (areas steady).
    pub fn is_converged(&self) -> bool {
        self.converged
    }
    /// Nothing more will happen: converged, stopped at the frame cap of the finest level,
    /// or out of frames. A finished run need not be converged.
    pub fn is_finished(&self) -> bool {
        self.converged || self.stopped || self.frame >= self.params.max_frames
    }
    pub fn params(&self) -> &Params {
        &self.params
    }
    pub fn events(&self) -> &[FrameEvent] {
        &self.events
    }
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Advances one frame: every vertex moves once, then the rings are remeshed (in
    /// `Mode::Implicit`: the fronts march one time unit).
    pub fn step(&mut self) -> Frame {
        if let Some(imp) = &self.implicit {
            let until = imp.time() + 1.0;
            return self.step_implicit(until);
        }
        let scale = Pyramid::scale(self.level);
        let field = &self.pyramid.levels[self.level];
        let decision = self.decision.get(self.level);
        let max_step = self.params.step * scale;
        let w = self.params.weights;
        let mut events = Vec::new();
        let mut motions = Vec::new();
        let (mut moved_sum, mut energy, mut active, mut visited) = (0.0, 0.0, 0usize, 0usize);
        let mut order = Vec::with_capacity(self.set.vertex_count());
        self.set.vertices_in_ring_order(&mut order);
        if self.still.len() < self.set.vertex_capacity() {
            self.still.resize(self.set.vertex_capacity(), 0);
            self.last_sign.resize(self.set.vertex_capacity(), 0);
            self.gain.resize(self.set.vertex_capacity(), 1.0);
        }
        let revisit_all = self.frame % 8 == 0;
        let preserve = self.params.mode == Mode::Preserve;
        let gap = PRESERVE_GAP * scale;
        let mut near = Vec::new();
        for v in order {
            if !self.set.is_alive(v) {
                continue;
            }
            let (p, n) = (self.set.prev(v), self.set.next(v));
            let quiet = |u: u32| self.still.get(u as usize).is_some_and(|&s| s >= 3);
            if !revisit_all && quiet(v) && quiet(p) && quiet(n) {
                continue;
            }
            visited += 1;
            let (pp, x, pn) = (
                self.set.position(p),
                self.set.position(v),
                self.set.position(n),
            );
            let normal = outward_normal(pp, x, pn);
            let f = normal_speed(field, decision, &self.model, &w, x * (1.0 / scale), normal);
            energy += f.region.abs();
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
            if preserve {
                d = d + repulsion(&self.set, v, 1.5 * scale, &mut near) * max_step;
            }
            let len = d.norm();
            if len > max_step {
                d = d * (max_step / len);
            }
            let before = events.len();
            let to = self.bounds.clamp(x + d);
            let moved = if preserve {
                self.set.move_vertex_preserving(v, to, gap).unwrap_or(0.0)
            } else {
                try_move(&mut self.set, v, to, &mut events)
            };
            if events.len() > before {
                motions.push([pp, x, pn, to]);
            }
            if moved > 0.05 * scale {
                active += 1;
                self.still[v as usize] = 0;
            } else if let Some(s) = self.still.get_mut(v as usize) {
                *s = s.saturating_add(1);
            }
            moved_sum += moved;
        }
        let (d_min, d_max) = (scale, 2.0 * std::f64::consts::SQRT_2 * scale);
        remesh(
            &mut self.set,
            d_min,
            d_max,
            preserve.then_some(gap),
            &mut events,
        );

        self.frame += 1;
        self.level_frames += 1;
        let vertices = self.set.vertex_count().max(1);
        let share = active as f64 / vertices as f64;
        // Steady: no contour's area drifted over the last ten frames (a tip still growing
        // along a thin structure is few vertices but steady area growth). Judged per
        // contour, not in total: on a large image with many settled cells, one region
        // still shrinking is a tiny share of the total area, yet it is not done. Drift is
        // a net change beyond the tolerance that is also most of the path the area took:
        // contours chattering in noise go up and down and count as steady.
        let mut now: Vec<(u32, f64)> = self
            .set
            .contour_ids()
            .map(|id| (id.0, self.set.signed_area(id)))
            .collect();
        now.sort_unstable_by_key(|&(id, _)| id);
        // Eleven frames are all the test below reads.
        if self.areas.len() == 11 {
            self.areas.remove(0);
        }
        self.areas.push(now);
        let steady = |tol: f64| {
            let n = self.areas.len();
            if n <= 10 {
                return false;
            }
            let at = |k: usize, id: u32| {
                let f = &self.areas[k];
                f.binary_search_by_key(&id, |&(i, _)| i)
                    .ok()
                    .map(|j| f[j].1)
            };
            self.areas[n - 1].iter().all(|&(id, a)| {
                let Some(then) = at(n - 11, id) else {
                    return false; // too young to judge
                };
                let net = (a - then).abs();
                if net <= tol * a.abs() + scale * scale {
                    return true;
                }
                let mut path = 0.0;
                let mut prev = then;
                for k in n - 10..n {
                    let Some(x) = at(k, id) else { return false };
                    path += (x - prev).abs();
                    prev = x;
                }
                net < 0.5 * path
            })
        };
        let quiet = share < self.params.converged_share && steady(0.002);
        self.calm = if quiet { self.calm + 1 } else { 0 };
        // Contours chattering in noise without going anywhere: refine, or stop.
        let stalled =
            self.level_frames >= STALL_FRAMES && steady(if self.level > 0 { 0.01 } else { 0.003 });
        let capped = self.level_frames >= LEVEL_FRAMES_CAP;
        if self.calm >= 3 || stalled || capped || self.set.vertex_count() == 0 {
            if self.set.vertex_count() == 0 || (self.level == 0 && !capped) {
                self.converged = true;
            } else if self.level == 0 {
                // The cap ends the run; it converged only if the areas stopped drifting.
                self.converged = steady(0.003);
                self.stopped = !self.converged;
            } else {
                self.set_level(self.level - 1);
            }
        }
        self.log_events(&events);
        Frame {
            index: self.frame,
            level: self.level,
            events,
            area: self.set.region_area(),
            vertices: self.set.vertex_count(),
            contours: self.set.contour_count(),
            mean_speed: moved_sum / visited.max(1) as f64,
            energy,
            active_share: share,
            converged: self.converged,
            motions,
        }
    }

    /// Runs until converged or out of frames.
    pub fn run(&mut self) {
        if self.implicit.is_some() {
            // No intermediate contours are needed: march to the end, extract once.
            if !self.converged {
                let left = self.params.max_frames.saturating_sub(self.frame);
                let now = self.implicit.as_ref().map_or(0.0, |i| i.time());
                self.step_implicit(now + left as f64);
            }
            return;
        }
        while !self.is_finished() {
            self.step();
        }
    }

    fn set_level(&mut self, level: usize) {
        self.level = level;
        self.calm = 0;
        self.level_frames = 0;
        self.areas.clear();
        let scale = Pyramid::scale(level);
        let d_max = 2.0 * std::f64::consts::SQRT_2 * scale;
        self.still.iter_mut().for_each(|s| *s = 0);
        self.last_sign.iter_mut().for_each(|s| *s = 0);
        self.gain.iter_mut().for_each(|g| *g = 1.0);
        // Global refinement on a level change (seed 004), then the tighter edge bound: set
        // before the split, the bound would keep the coarse edges' length as its reach
        // (and the broad phase its coarse cells) for the whole level.
        let mut events = Vec::new();
        let gap = (self.params.mode == Mode::Preserve).then_some(PRESERVE_GAP * scale);
        remesh(&mut self.set, scale, d_max, gap, &mut events);
        self.set.set_max_edge(d_max);
        self.log_events(&events);
    }

    /// A hand edit: moves vertex `v` towards `to` (clamped to the image) through the
    /// topology core, in steps of a quarter of the edge bound with the moving vertex's
    /// edges split ahead of it and its three neighbours on each side following with
    /// weights ¾, ½, ¼ (a tongue, not a spike), so every step is an ordinary motion
    /// region (a degenerate one is retried at half and a quarter length): dragging one
    /// contour onto another merges them, pinching one splits it, closing a gap makes a
    /// hole — exactly, and the events are logged at the current frame. A converged run
    /// stays converged: the user's edit is final unless they play on. In the
    /// topology-keeping modes the contour stops short of the others instead. Returns
    /// the events. Not in `Mode::Implicit`, whose contours are extracted from a grid
    /// (returns no event). The vertex may be gone afterwards (a merge, or the remesh
    /// joined it to a neighbour): [`Evolver::vertex_near`] finds the one that took its
    /// place, for a drag to continue.
    pub fn hand_move(&mut self, v: u32, to: Point) -> Vec<TopologyEvent> {
        self.hand_drag(v, to).0
    }

    /// [`Evolver::hand_move`] for a drag: also returns the vertex that leads at the end.
    /// When the lead vanishes without a topology event (the edge splits and neighbours
    /// crowd it; a remesh joins it to one), the vertex of its contour nearest to where it
    /// was takes over; after a merge or split the drag has done its work (`None`).
    pub fn hand_drag(&mut self, v: u32, to: Point) -> (Vec<TopologyEvent>, Option<u32>) {
        let mut events = Vec::new();
        if self.params.mode == Mode::Implicit || !self.set.is_alive(v) {
            return (events, None);
        }
        let mut v = v;
        let to = self.bounds.clamp(to);
        let scale = Pyramid::scale(self.level);
        let bound = self.set.max_edge();
        let step = 0.25 * bound;
        let from = self.set.position(v);
        let n = (from.dist(to) / step).ceil().max(1.0) as usize;
        let gap = PRESERVE_GAP * scale;
        for k in 1..=n {
            if !self.set.is_alive(v) {
                break;
            }
            let (contour, was) = (self.set.contour_of(v), self.set.position(v));
            let before = events.len();
            // Split the moving vertex's edges that this step could stretch past the bound.
            for a in [self.set.prev(v), v] {
                let b = self.set.next(a);
                if self.set.position(a).dist(self.set.position(b)) > bound - step {
                    let _ = self.set.insert_vertex(a, 0.5);
                }
            }
            let target = from.lerp(to, k as f64 / n as f64);
            let d = target - self.set.position(v);
            // The vertex leads; its neighbours follow with falling weights, so the drag
            // pulls a tongue, not a one-vertex spike whose two edges are nearly parallel
            // (such a spike meets other contours only in degenerate crossings).
            let (mut p, mut q) = (v, v);
            let mut chain = vec![(v, 1.0)];
            for i in 1..=HAND_FOLLOW {
                p = self.set.prev(p);
                q = self.set.next(q);
                if p == q || p == v {
                    break;
                }
                let w = 1.0 - i as f64 / (HAND_FOLLOW + 1) as f64;
                chain.extend([(p, w), (q, w)]);
            }
            let mut lead_moved = true;
            for (u, w) in chain {
                if !self.set.is_alive(u) {
                    continue;
                }
                let at = self.set.position(u);
                let mut done = false;
                for f in [1.0, 0.5, 0.25] {
                    let goal = self.bounds.clamp(at + d * (w * f));
                    let moved = if self.params.mode == Mode::Preserve {
                        self.set
                            .move_vertex_preserving(u, goal, gap)
                            .map(|_| Vec::new())
                    } else {
                        self.set.move_vertex(u, goal)
                    };
                    match moved {
                        Ok(ev) => {
                            events.extend(ev);
                            done = true;
                            break;
                        }
                        Err(MoveError::Degenerate(_)) => continue,
                        Err(_) => break,
                    }
                }
                if u == v {
                    lead_moved = done;
                }
            }
            if !lead_moved {
                break;
            }
            if !self.set.is_alive(v) && events.len() == before {
                let Some(u) = self.successor(was, contour) else {
                    break;
                };
                v = u;
            }
        }
        let gap = (self.params.mode == Mode::Preserve).then_some(gap);
        let at = self
            .set
            .is_alive(v)
            .then(|| (self.set.position(v), self.set.contour_of(v)));
        let before = events.len();
        remesh(
            &mut self.set,
            scale,
            2.0 * std::f64::consts::SQRT_2 * scale,
            gap,
            &mut events,
        );
        self.log_events(&events);
        let lead = match at {
            Some(_) if self.set.is_alive(v) => Some(v),
            Some((p, c)) if events.len() == before => self.successor(p, c),
            _ => None,
        };
        (events, lead)
    }

    /// The vertex of `contour` nearest to where a dragged vertex was, within two edge
    /// bounds: it leads the drag on when the dragged one was joined to a neighbour.
    fn successor(&self, was: Point, contour: crate::contours::ContourId) -> Option<u32> {
        self.vertex_near(was, 2.0 * self.set.max_edge())
            .filter(|&u| self.set.contour_of(u) == contour)
    }

    /// The vertex nearest to `at` within `tol` pixels, if any.
    pub fn vertex_near(&self, at: Point, tol: f64) -> Option<u32> {
        let mut near = Vec::new();
        self.set
            .vertices_near(&Aabb { min: at, max: at }.expand(tol), &mut near);
        near.into_iter()
            .map(|v| (v, self.set.position(v).dist(at)))
            .filter(|&(_, d)| d <= tol)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(v, _)| v)
    }

    /// Deletes contour `id` (an outer ring with its holes, or one hole): a hand edit.
    pub fn delete_contour(&mut self, id: crate::contours::ContourId) {
        let holes: Vec<_> = self
            .set
            .parents()
            .into_iter()
            .filter(|&(_, p)| p == Some(id))
            .map(|(h, _)| h)
            .collect();
        for h in holes {
            self.set.remove_ring(h);
        }
        self.set.remove_ring(id);
    }

    fn log_events(&mut self, events: &[TopologyEvent]) {
        for &e in events {
            self.events.push(FrameEvent {
                frame: self.frame,
                event: e,
            });
        }
    }

    /// Drops outer regions (with their holes) and holes smaller than `min_area`: the
    /// clutter filter of seed 003 §4.
    pub fn filter_clutter(&mut self) {
        crate::evolution::measure::drop_small(&mut self.set, self.params.min_area);
    }
}

/// Push away from vertices of other parts within `r` (not the ring's own neighbours
/// within four steps): seed 004's non-self-intersection force, in units of the step.
fn repulsion(set: &ContourSet, v: u32, r: f64, near: &mut Vec<u32>) -> Point {
    let x = set.position(v);
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
        if own.contains(&w) {
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

/// Moves `v` towards `to`; a refused move is retried at half length. Returns the
/// distance moved.
fn try_move(set: &mut ContourSet, v: u32, to: Point, events: &mut Vec<TopologyEvent>) -> f64 {
    let from = set.position(v);
    for f in [1.0, 0.5] {
        let q = from.lerp(to, f);
        match set.move_vertex(v, q) {
            Ok(ev) => {
                events.extend(ev);
                return from.dist(q);
            }
            Err(MoveError::Degenerate(_)) => continue,
            Err(_) => return 0.0,
        }
    }
    0.0
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

fn check_params(p: &Params) -> Result<(), EvolveError> {
    let w = &p.weights;
    for (name, value) in [
        ("region", w.region),
        ("balloon", w.balloon),
        ("edge", w.edge),
        ("stretch", w.stretch),
        ("bend", w.bend),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(EvolveError::BadParameter {
                name,
                what: "a finite number ≥ 0",
                value,
            });
        }
    }
    if !(p.step.is_finite() && p.step > 0.0 && p.step <= 2.0) {
        return Err(EvolveError::BadParameter {
            name: "step",
            what: "in (0, 2]",
            value: p.step,
        });
    }
    if !(p.min_area.is_finite() && p.min_area >= 0.0) {
        return Err(EvolveError::BadParameter {
            name: "min_area",
            what: "a finite number ≥ 0",
            value: p.min_area,
        });
    }
    Ok(())
}

/// Shapes with finite coordinates and disks no larger than the image's diagonal (a ring
/// has a vertex every pixel or so: a huge radius would be a huge ring, clipped after).
fn check_shapes(init: &[Shape], width: usize, height: usize) -> Result<(), EvolveError> {
    let diagonal = (width as f64).hypot(height as f64);
    for s in init {
        let finite = match s {
            Shape::Disk { center, radius } => {
                if !(*radius > 0.0 && *radius <= diagonal) {
                    return Err(EvolveError::BadShape(format!(
                        "disk radius {radius} is not in (0, {diagonal:.0}], the image's diagonal"
                    )));
                }
                center.x.is_finite() && center.y.is_finite()
            }
            Shape::Rect { min, max } => [min.x, min.y, max.x, max.y].iter().all(|v| v.is_finite()),
            Shape::Polygon(pts) => pts.iter().all(|p| p.x.is_finite() && p.y.is_finite()),
        };
        if !finite {
            return Err(EvolveError::BadShape(format!(
                "{s:?} has a coordinate that is not finite"
            )));
        }
    }
    Ok(())
}

/// Medians of the image under the seeds (object) and along the inside of rectangles
/// (background, for a wrap).
fn hints(field: &Field, init: &[Shape]) -> (Option<f64>, Option<f64>) {
    let mut obj = Vec::new();
    let mut bg = Vec::new();
    for s in init {
        match s {
            Shape::Disk { center, radius } => {
                // Pixel centres in the disk, the loops clipped to the image: the cost is
                // the disk's part in the image, whatever the radius.
                let r = radius.max(1.0);
                let span = |c: f64, n: usize| {
                    let lo = (c - r - 0.5).ceil().clamp(0.0, n as f64) as usize;
                    let hi = (c + r - 0.5).floor().clamp(-1.0, n as f64 - 1.0);
                    lo..(hi + 1.0) as usize
                };
                for y in span(center.y, field.height) {
                    let dy = y as f64 + 0.5 - center.y;
                    for x in span(center.x, field.width) {
                        let dx = x as f64 + 0.5 - center.x;
                        if dx * dx + dy * dy <= r * r {
                            obj.push(field.at(x, y) as f64);
                        }
                    }
                }
            }
            Shape::Rect { min, max } => {
                // Pixels whose centre lies within `band` of a side: whole rows near the
                // top and bottom, the ends of the rows between.
                let band = 4.0;
                let near_x = |x: usize| {
                    let fx = x as f64 + 0.5;
                    fx - min.x < band || max.x - fx < band
                };
                let (x0, x1) = (
                    min.x.max(0.0) as usize,
                    max.x.min(field.width as f64) as usize,
                );
                for y in (min.y.max(0.0) as usize)..(max.y.min(field.height as f64) as usize) {
                    let fy = y as f64 + 0.5;
                    let whole = fy - min.y < band || max.y - fy < band;
                    let mut left = x0;
                    while left < x1 && (whole || near_x(left)) {
                        left += 1;
                    }
                    let mut right = x1;
                    while right > left && near_x(right - 1) {
                        right -= 1;
                    }
                    for x in (x0..left).chain(right..x1) {
                        bg.push(field.at(x, y) as f64);
                    }
                }
            }
            Shape::Polygon(_) => {}
        }
    }
    (median(&mut obj), median(&mut bg))
}

fn median(v: &mut [f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    let m = v.len() / 2;
    v.select_nth_unstable_by(m, |a, b| a.total_cmp(b));
    Some(v[m])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_inside_other_shapes_join_their_region() {
        let img = Field::new(64, 64, vec![0.5; 64 * 64]);
        let init = [
            Shape::Rect {
                min: Point::new(4.0, 4.0),
                max: Point::new(60.0, 60.0),
            },
            Shape::Disk {
                center: Point::new(30.0, 30.0),
                radius: 5.0,
            },
        ];
        let ev = Evolver::new(&img, &init, Params::default()).unwrap();
        assert_eq!(ev.contours().contour_count(), 1);
        ev.contours().sanity_check().unwrap();
        assert!(Evolver::new(&img, &[], Params::default()).is_err());
    }

    /// A wrap over a grid of cells ends with every cell its own contour. (At 4096² with
    /// 400 cells, judging steadiness on the total area stopped with four cells still in
    /// one region: `cargo bench --bench scale -- wrap` counts the contours.)
    #[test]
    fn a_wrap_over_many_cells_finds_every_cell() {
        let (n, pitch, r) = (8usize, 60.0, 20.0);
        let side = n * pitch as usize;
        let data: Vec<f32> = (0..side * side)
            .map(|i| {
                let (x, y) = ((i % side) as f64 + 0.5, (i / side) as f64 + 0.5);
                let (cx, cy) = (x % pitch - pitch / 2.0, y % pitch - pitch / 2.0);
                let noise = ((i * 2_654_435_761) % 97) as f32 / 97.0 - 0.5;
                (if cx * cx + cy * cy < r * r { 0.3 } else { 0.7 }) + 0.1 * noise
            })
            .collect();
        let img = Field::new(side, side, data);
        let wrap = [Shape::Rect {
            min: Point::new(4.0, 4.0),
            max: Point::new(side as f64 - 4.0, side as f64 - 4.0),
        }];
        let mut ev = Evolver::new(&img, &wrap, Params::default()).unwrap();
        ev.run();
        assert!(ev.is_converged());
        assert_eq!(ev.contours().contour_count(), n * n);
    }
}
