//! `Evolver`: contours moving under image forces one frame at a time (seed 003 §3 with
//! seed 004's multiscale schedule, remeshing and convergence test).
//!
//! The evolver is thin: it prepares the image once ([`ImageModel::prepare`]: modality,
//! pyramid, intensity model, local decision levels), builds the initial rings, and then owns
//! an engine ([`super::engine`]), the schedule over pyramid levels
//! ([`super::schedule`]) and the log of topology events. Every move of the explicit
//! engines goes through [`ContourSet::move_vertex`], so every topology change is exact
//! and reported.
//!
//! The image rectangle is a wall: initial shapes are clipped to it and every target a
//! vertex is sent to is clamped to it (see [`super::explicit`]). Only a run that reached
//! a level-0 equilibrium is `converged`: one that stopped at `max_frames` or at the frame
//! cap with areas still drifting is only finished.

use super::edit::{Edit, FrameEvent};
use super::engine::{Engine, Engines, Frame};
use super::explicit::Explicit;
use super::forces::ForceWeights;
use super::implicit::{Implicit, ImplicitEngine};
use super::initial::initial_set;
use super::params::{
    check_memory, check_params, check_params_for, check_shapes, EvolveError, Mode, Params,
};
use super::schedule::Schedule;
use crate::contours::{ContourId, ContourSet};
use crate::geometry::{Aabb, Point};
use crate::image::field::{Field, Pyramid};
use crate::image::{ImageModel, IntensityModel, Stored};
use crate::shape::Shape;
use crate::topology::TopologyEvent;
use std::sync::Arc;

/// How many times the finest level may settle, open holes and run again. Holes already
/// open after every coarser level; the one round at full resolution catches background
/// too thin for the coarse grids (the channels between touching cells) at the price of
/// one more settling; a second round found nothing more (`docs/decisions.md`).
const REOPEN_ROUNDS: usize = 1;

/// Frames the edge stage of a taught run takes ([`Evolver::edges_when_finished`]): the
/// band it reads is at most [`crate::image::edges::BAND`] pixels each side of the
/// outlines, crossed in a few frames at the default step; waiting for the vertices
/// that chatter on noisy intensities to calm took 70 frames on the public colony for
/// the same scores (docs/decisions.md, 2026-12-05). The run is converged after it if it
/// was before it.
pub const EDGE_FRAMES: usize = 10;

/// Runs the evolution.
#[derive(Clone)]
pub struct Evolver {
    engine: Engines,
    schedule: Schedule,
    params: Params,
    /// What the engines read of the image.
    image: Arc<ImageModel>,
    frame: usize,
    events: Vec<FrameEvent>,
    /// The user's interventions so far, in order.
    edits: Vec<Edit>,
    /// The parameters the run started with (force changes update `params`).
    start_params: Params,
    /// Times the finest level settled and holes opened after it.
    reopened: usize,
    /// Free the coarse levels on reaching level 0 ([`Evolver::free_coarse_levels`]).
    free_coarse: bool,
    /// A taught run's P(boundary), to cut its regions at the septa it shows when the run
    /// finishes ([`Evolver::cut_when_finished`]); taken when the cut is made.
    septa: Option<Arc<Field>>,
    /// A taught run's image and its objects' polarity, to settle the objects' edges on
    /// it once the run has finished on the probabilities
    /// ([`Evolver::edges_when_finished`]); taken when that stage starts.
    edges: Option<(Arc<Field>, crate::image::Polarity)>,
    /// The frame by which the edge stage ends ([`EDGE_FRAMES`] after it starts), and
    /// whether the run had converged before it.
    edges_until: Option<(usize, bool)>,
}

impl Evolver {
    /// Prepares the image and the initial rings for `params.mode`'s engine.
    pub fn new(image: &Field, init: &[Shape], params: Params) -> Result<Self, EvolveError> {
        Self::check(image, init, &params)?;
        let model = Arc::new(ImageModel::prepare(image, &params.model_params(), init));
        Self::with_image(model, init, params)
    }

    /// [`Evolver::new`] on an image it may keep compactly for the outputs
    /// ([`ImageModel::prepare_keeping`]).
    pub fn keeping(
        image: Field,
        init: &[Shape],
        params: Params,
    ) -> Result<(Self, Stored), EvolveError> {
        Self::check(&image, init, &params)?;
        let (model, kept) = ImageModel::prepare_keeping(image, &params.model_params(), init);
        Ok((Self::with_image(Arc::new(model), init, params)?, kept))
    }

    /// What both constructors refuse before preparing anything.
    fn check(image: &Field, init: &[Shape], params: &Params) -> Result<(), EvolveError> {
        check_params(params)?;
        if init.is_empty() {
            return Err(EvolveError::EmptyInit);
        }
        check_shapes(init, image.width, image.height)?;
        check_params_for(params, image.width, image.height)?;
        check_memory(image.width, image.height)
    }

    /// The run over an image already prepared as `params` say (see
    /// [`Params::model_params`]), from the shapes `init`.
    fn with_image(
        image: Arc<ImageModel>,
        init: &[Shape],
        params: Params,
    ) -> Result<Self, EvolveError> {
        let (width, height) = image.size();
        let domain = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(width as f64, height as f64),
        };
        let coarsest = image.coarsest();
        let set = initial_set(init, domain, Pyramid::scale(coarsest), &params)?;
        let (w, step) = (params.weights, params.step);
        let (engine, level) = match params.mode {
            Mode::Adaptive => (
                Engines::Adaptive(Explicit::new(set, image.clone(), w, step)),
                coarsest,
            ),
            Mode::Preserve => (
                Engines::Preserve(Explicit::new(set, image.clone(), w, step)),
                coarsest,
            ),
            Mode::Track => (
                Engines::Track(Explicit::new(set, image.clone(), w, step)),
                coarsest,
            ),
            Mode::Implicit => {
                let engine = ImplicitEngine::new(&image, init, domain, params.broad_phase);
                (Engines::Implicit(Box::new(engine)), 0)
            }
        };
        if engine.contours().contour_count() == 0 {
            return Err(EvolveError::EmptyInit);
        }
        let start_params = params.clone();
        Ok(Evolver {
            engine,
            schedule: Schedule::new(level),
            params,
            image,
            frame: 0,
            events: Vec::new(),
            edits: Vec::new(),
            start_params,
            reopened: 0,
            free_coarse: false,
            septa: None,
            edges: None,
            edges_until: None,
        })
    }

    /// In the topology-keeping modes, how many places held fronts apart where the adaptive
    /// engine would have changed topology: implicit — cut grid edges plus rejected
    /// pixels; preserve — vertices that ended within two gaps of another part of the
    /// boundary (not their own neighbours). 0 in adaptive mode.
    pub fn held_contacts(&self) -> usize {
        self.engine.held_contacts(self.schedule.level)
    }

    /// The contours now.
    pub fn contours(&self) -> &ContourSet {
        self.engine.contours()
    }
    /// The fast marching state, in `Mode::Implicit`.
    pub fn implicit(&self) -> Option<&Implicit> {
        match &self.engine {
            Engines::Implicit(e) => Some(e.state()),
            _ => None,
        }
    }
    /// The two-class intensity model learnt from the image and the initialisation.
    pub fn model(&self) -> IntensityModel {
        self.image.global()
    }
    /// What the engines read of the image (shared: cloning a run does not copy it).
    pub fn image(&self) -> &Arc<ImageModel> {
        &self.image
    }
    /// Frames done.
    pub fn frames(&self) -> usize {
        self.frame
    }
    /// The pyramid level frames run on now (0: full resolution).
    pub fn level(&self) -> usize {
        self.schedule.level
    }
    /// The run reached an equilibrium on the finest level (areas steady).
    pub fn is_converged(&self) -> bool {
        self.schedule.converged
    }
    /// Nothing more will happen: converged, stopped at the frame cap of the finest level,
    /// or out of frames. A finished run need not be converged.
    pub fn is_finished(&self) -> bool {
        self.schedule.converged || self.schedule.stopped || self.frame >= self.params.max_frames
    }
    /// The parameters of the run now.
    pub fn params(&self) -> &Params {
        &self.params
    }
    /// The parameters the run started with, before any [`Edit::Forces`].
    pub fn start_params(&self) -> &Params {
        &self.start_params
    }
    /// Every topology event so far, with its frame.
    pub fn events(&self) -> &[FrameEvent] {
        &self.events
    }
    /// The image's width and height in pixels.
    pub fn size(&self) -> (usize, usize) {
        self.image.size()
    }

    /// Asks the run to free the coarse pyramid and decision levels once it is on full
    /// resolution, which it never leaves (holes then open on level 0 too): a quarter of
    /// the model's memory, 66 MB for a 4096² image (docs/decisions.md, 2026-12-02). For a
    /// run driven to its end ([`crate::job::Job`]); the app keeps them, since an edit in
    /// an earlier frame replays from a coarse level. Results are the same either way.
    pub fn free_coarse_levels(&mut self) {
        self.free_coarse = true;
    }

    /// [`Evolver::free_coarse_levels`] now: false on a coarse level, or when someone else
    /// holds the model too (then nothing is freed).
    fn drop_coarse_levels(&mut self) -> bool {
        if self.schedule.level != 0 || self.image.levels() == 1 {
            return false;
        }
        // The engine's reference is swapped for a stand-in while the model is changed,
        // so the evolver's is the only one.
        let stand_in = Arc::new(ImageModel::empty());
        let theirs = self
            .engine
            .image_mut()
            .map(|slot| std::mem::replace(slot, stand_in));
        drop(theirs);
        let done = match Arc::get_mut(&mut self.image) {
            Some(model) => {
                model.drop_coarse();
                true
            }
            None => false,
        };
        if let Some(slot) = self.engine.image_mut() {
            *slot = self.image.clone();
        }
        done
    }

    /// Advances one frame: every vertex moves once, then the rings are remeshed (in
    /// `Mode::Implicit`: the fronts march one time unit).
    pub fn step(&mut self) -> Frame {
        if self.free_coarse && self.schedule.level == 0 {
            // A run that starts on level 0 (the implicit engine, or a one-level image).
            self.free_coarse = false;
            self.drop_coarse_levels();
        }
        let frame = self.engine.step(self.frame, self.schedule.level);
        self.after(frame)
    }

    /// The schedule judges a frame; the events go to the log.
    fn after(&mut self, mut frame: Frame) -> Frame {
        self.frame = frame.index;
        if let Some(done) = self.engine.settled() {
            self.schedule.converged = done;
        } else {
            let set = self.engine.contours();
            let judged = self
                .schedule
                .judge(set, frame.active_share, self.params.converged_share);
            if let Some(level) = judged {
                // Holes open on the level just finished (a quarter of the pixels of the
                // next), then the rings are refined for the finer one.
                self.open_holes(level + 1);
                if level == 0 && self.free_coarse {
                    // Before the finer rings and their bins are made: the peak.
                    self.free_coarse = false;
                    self.drop_coarse_levels();
                }
                let events = self.engine.refine(level);
                self.log_events(&events);
            } else if self.schedule.converged && self.reopened < REOPEN_ROUNDS && self.open_holes(0)
            {
                // The holes grow on: the finest level runs again.
                self.reopened += 1;
                self.schedule.resume();
            }
        }
        self.log_events(&frame.events);
        if let Some((until, converged)) = self.edges_until {
            if self.frame >= until && !self.is_finished() {
                self.schedule.end(converged);
            }
        }
        if self.is_finished() {
            self.edges_until = None;
            if let Some(line) = self.septa.take() {
                self.cut_at_necks(&line);
            }
            if let Some((image, polarity)) = self.edges.take() {
                self.settle_edges(&image, polarity);
            }
        }
        frame.level = self.schedule.level;
        frame.converged = self.schedule.converged;
        frame
    }

    /// Opens holes in clear background inside the region (adaptive engine, when the
    /// parameters allow it); logs them and says whether any opened.
    fn open_holes(&mut self, level: usize) -> bool {
        if !self.params.open_holes {
            return false;
        }
        let events = self.engine.nucleate(level);
        self.log_events(&events);
        !events.is_empty()
    }

    /// Runs until converged or out of frames.
    pub fn run(&mut self) {
        if self.schedule.converged {
            return;
        }
        let left = self.params.max_frames.saturating_sub(self.frame);
        if let Some(frame) = self.engine.finish(self.frame, left) {
            self.after(frame);
            return;
        }
        while !self.is_finished() {
            self.step();
        }
    }

    /// A hand edit: moves vertex `v` towards `to` (clamped to the image) through the
    /// topology core, a tongue of its contour following, so every step is an ordinary
    /// motion region: dragging one contour onto another merges them, pinching one splits
    /// it, closing a gap makes a hole — exactly, and the events are logged at the current
    /// frame. A converged run stays converged: the user's edit is final unless they play
    /// on. In the topology-keeping modes the contour stops short of the others instead.
    /// Returns the events. Not in `Mode::Implicit`, whose contours are extracted from a
    /// grid (returns no event). The vertex may be gone afterwards (a merge, or the remesh
    /// joined it to a neighbour): [`Evolver::vertex_near`] finds the one that took its
    /// place, for a drag to continue.
    pub fn hand_move(&mut self, v: u32, to: Point) -> Vec<TopologyEvent> {
        self.hand_drag(v, to).0
    }

    /// [`Evolver::hand_move`] for a drag: also returns the vertex that leads at the end
    /// (`None` after a merge or split: the drag has done its work).
    pub fn hand_drag(&mut self, v: u32, to: Point) -> (Vec<TopologyEvent>, Option<u32>) {
        self.edits.push(Edit::Drag {
            frame: self.frame,
            vertex: v,
            to,
        });
        let (events, lead) = self.engine.hand_drag(v, to, self.schedule.level);
        self.log_events(&events);
        (events, lead)
    }

    /// A brush stroke of `radius` from `from` to `to`: contour vertices inside the moving
    /// disc are pushed out to its rim through the topology core (see
    /// [`Engine::brush`]); the events are logged at the current frame.
    /// Not in `Mode::Implicit` (no event).
    pub fn brush(&mut self, from: Point, to: Point, radius: f64) -> Vec<TopologyEvent> {
        if check_brush(radius, from, to, self.diagonal()).is_err() {
            return Vec::new();
        }
        self.edits.push(Edit::Brush {
            frame: self.frame,
            from,
            to,
            radius,
        });
        let events = self.engine.brush(from, to, radius, self.schedule.level);
        self.log_events(&events);
        events
    }

    /// The vertex nearest to `at` within `tol` pixels, if any.
    pub fn vertex_near(&self, at: Point, tol: f64) -> Option<u32> {
        self.contours().nearest_vertex(at, tol)
    }

    /// Deletes contour `id` (an outer ring with its holes, or one hole): a hand edit.
    pub fn delete_contour(&mut self, id: ContourId) {
        self.edits.push(Edit::Delete {
            frame: self.frame,
            contour: id.0,
        });
        self.engine.contours_mut().remove_region(id);
    }

    /// New force weights and step from the current frame on: the run continues from its
    /// contours as they are (a settled run moves again under the new forces).
    pub fn set_forces(&mut self, weights: ForceWeights, step: f64) -> Result<(), EvolveError> {
        let params = Params {
            weights,
            step,
            ..self.params.clone()
        };
        check_params(&params)?;
        self.params = params;
        self.engine.set_forces(weights, step);
        self.schedule.resume();
        // New forces may leave new background inside: holes may open again.
        self.reopened = 0;
        self.edits.push(Edit::Forces {
            frame: self.frame,
            weights,
            step,
        });
        Ok(())
    }

    /// The user's interventions so far ([`Edit`]), in order.
    pub fn edits(&self) -> &[Edit] {
        &self.edits
    }

    /// Makes `edit` again (a session's replay): the caller has stepped to its frame. An
    /// edit no user could have made (a brush wider than the image's diagonal, a point
    /// that is not finite) is refused.
    pub fn redo_edit(&mut self, edit: &Edit) -> Result<(), EvolveError> {
        match *edit {
            Edit::Forces { weights, step, .. } => self.set_forces(weights, step)?,
            Edit::Drag { vertex, to, .. } => {
                if !to.is_finite() {
                    return Err(EvolveError::BadShape(format!(
                        "a drag to {to:?} is not a finite point"
                    )));
                }
                self.hand_drag(vertex, to);
            }
            Edit::Brush {
                from, to, radius, ..
            } => {
                check_brush(radius, from, to, self.diagonal())?;
                self.brush(from, to, radius);
            }
            Edit::Delete { contour, .. } => self.delete_contour(ContourId(contour)),
        }
        Ok(())
    }

    /// The image's diagonal, pixels: the largest length any edit needs.
    fn diagonal(&self) -> f64 {
        let (w, h) = self.size();
        (w as f64).hypot(h as f64)
    }

    fn log_events(&mut self, events: &[TopologyEvent]) {
        let frame = self.frame;
        self.events
            .extend(events.iter().map(|&event| FrameEvent { frame, event }));
    }

    /// Drops outer regions (with their holes) and holes smaller than `min_area`: the
    /// clutter filter of seed 003 §4. Returns how many objects went.
    pub fn filter_clutter(&mut self) -> usize {
        crate::contours::measure::drop_small(self.engine.contours_mut(), self.params.min_area)
    }

    /// Cuts the regions at the septa `line` shows
    /// ([`crate::track::neck::cut_set_at_necks`]) once, in the frame the run finishes:
    /// inside the run, so the app playing a job and the CLI running it to its end cut at
    /// the same point, before any edit made after the end.
    pub fn cut_when_finished(&mut self, line: Arc<Field>) {
        self.septa = Some(line);
    }

    /// Once the run has finished (and made its cuts), the objects' edges are settled on
    /// `image` ([`crate::image::edges`]): the run goes on, on the finest level, over the
    /// field it read with each object's outline band read from `image` (objects of
    /// `polarity`). In the frame the run finishes, as the cut: the app and the CLI settle
    /// alike. Not in the implicit engine, nor in a run with no frames left.
    pub fn edges_when_finished(&mut self, image: Arc<Field>, polarity: crate::image::Polarity) {
        self.edges = Some((image, polarity));
    }

    /// [`Evolver::edges_when_finished`]'s stage: the field swapped, the schedule resumed.
    /// Returns how many objects' edges the image set.
    fn settle_edges(&mut self, image: &Field, polarity: crate::image::Polarity) -> usize {
        if self.implicit().is_some() || self.frame >= self.params.max_frames {
            return 0;
        }
        let global = self.image.global();
        let (field, settled) = crate::image::edges::edge_field(
            self.image.fine(),
            image,
            self.engine.contours(),
            polarity,
            global.object,
            global.background,
        );
        if settled == 0 {
            return 0;
        }
        self.image = Arc::new(self.image.over(&field));
        if let Some(slot) = self.engine.image_mut() {
            *slot = self.image.clone();
        }
        self.edges_until = Some((self.frame + EDGE_FRAMES, self.schedule.converged));
        self.schedule.resume();
        settled
    }

    /// Cuts each outer region with no hole where `line` (a taught run's P(boundary))
    /// shows a septum across it ([`crate::track::neck::cut_set_at_necks`]); an implicit
    /// run is left as it is (its contours are its level set's). Returns the cuts made.
    /// Only in the frame the run finishes ([`Evolver::cut_when_finished`]).
    fn cut_at_necks(&mut self, line: &Field) -> usize {
        if self.implicit().is_some() {
            return 0;
        }
        crate::track::neck::cut_set_at_necks(self.engine.contours_mut(), line)
    }

    /// The contours with regions and holes smaller than `min_area` dropped, the run
    /// untouched (the app exports a frame and plays on).
    pub fn filtered_contours(&self, min_area: f64) -> ContourSet {
        let mut set = self.contours().clone();
        crate::contours::measure::drop_small(&mut set, min_area);
        set
    }
}

/// A brush of radius in (0, the image's diagonal] between finite points.
fn check_brush(radius: f64, from: Point, to: Point, diagonal: f64) -> Result<(), EvolveError> {
    if !(radius > 0.0 && radius <= diagonal) {
        return Err(EvolveError::BadParameter {
            name: "brush radius",
            what: "in (0, the image's diagonal]",
            value: radius,
        });
    }
    if !(from.is_finite() && to.is_finite()) {
        return Err(EvolveError::BadShape(format!(
            "a brush stroke from {from:?} to {to:?} has a point that is not finite"
        )));
    }
    Ok(())
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

        // The same run kept compactly, its decision levels made when first read and its
        // coarse levels freed at level 0, ends with the very same contours.
        let (mut lean, _) = Evolver::keeping(img, &wrap, Params::default()).unwrap();
        let levels = lean.image().levels();
        assert!(levels > 1);
        lean.free_coarse_levels();
        lean.run();
        assert_eq!(lean.image().levels(), 1, "the coarse levels were freed");
        assert_eq!(lean.frames(), ev.frames());
        let points = |e: &Evolver| -> Vec<(u64, u64)> {
            let set = e.contours();
            set.vertices()
                .map(|v| (set.position(v).x.to_bits(), set.position(v).y.to_bits()))
                .collect()
        };
        assert_eq!(points(&lean), points(&ev));
    }
}
