//! A run on screen: the evolver, the frames recorded for display, checkpoints to
//! continue or edit from any recorded frame, and the user's edits of the run.
//!
//! The run owns every edit the user made (hand drags, brush strokes, deletions, force
//! changes), each at its frame. The evolver has made a prefix of them; when an edit at an
//! earlier frame drops the frames after it, the later edits stay and are made again when
//! the run reaches their frame, so scrubbing back and editing never silently loses one.

use crate::evolution::{Edit, Evolver};
use crate::geometry::Point;
use crate::topology::{MotionRegion, TopologyEvent};
use std::sync::atomic::{AtomicU64, Ordering};

/// One ring as recorded for display.
#[derive(Clone, Debug)]
pub struct RingView {
    /// The ring's contour id.
    pub id: u32,
    /// The ring bounds a hole.
    pub hole: bool,
    /// Its vertices in order.
    pub points: Vec<Point>,
}

/// A recorded frame: enough to draw it and to plot its statistics.
#[derive(Clone, Debug)]
pub struct FrameRecord {
    /// The frame's index (0: the initialisation).
    pub index: usize,
    /// Unique to this recording: a frame recorded again (after an edit) gets a new one,
    /// so caches of what is drawn from it know it changed.
    pub stamp: u64,
    /// The rings.
    pub rings: Vec<RingView>,
    /// Every topology event of the frame, as the evolver logged it (holes opened
    /// between pyramid levels and hand edits included).
    pub events: Vec<TopologyEvent>,
    /// The motion regions (p, o, n, q) that caused them.
    pub motions: Vec<MotionRegion>,
    /// Area of the region, square pixels.
    pub area: f64,
    /// Contours.
    pub contours: usize,
    /// Vertices.
    pub vertices: usize,
    /// Sum of |region score|: falls as contours settle.
    pub energy: f64,
    /// The run converged with this frame.
    pub converged: bool,
}

/// The next [`FrameRecord::stamp`].
fn next_stamp() -> u64 {
    static STAMPS: AtomicU64 = AtomicU64::new(1);
    STAMPS.fetch_add(1, Ordering::Relaxed)
}

impl FrameRecord {
    fn of(
        ev: &Evolver,
        index: usize,
        events: Vec<TopologyEvent>,
        motions: Vec<MotionRegion>,
    ) -> Self {
        let set = ev.contours();
        let rings = set
            .contour_ids()
            .map(|id| RingView {
                id: id.0,
                hole: set.is_hole(id),
                points: set.ring_points(id),
            })
            .collect();
        FrameRecord {
            index,
            stamp: next_stamp(),
            rings,
            events,
            motions,
            area: set.region_area(),
            contours: set.contour_count(),
            vertices: set.vertex_count(),
            energy: 0.0,
            converged: false,
        }
    }
}

/// An evolution in progress with its recorded history.
#[derive(Clone)]
pub struct Run {
    /// The evolver, at the last recorded frame.
    pub evolver: Evolver,
    /// Frame 0 is the initialisation.
    pub history: Vec<FrameRecord>,
    /// Evolver states every few frames (and at every edit), to continue from any frame.
    checkpoints: Vec<(usize, Evolver)>,
    /// Every edit the user made, in order; the evolver has made the first
    /// `evolver.edits().len()`, the rest wait for their frame.
    edits: Vec<Edit>,
}

const CHECKPOINT_EVERY: usize = 10;

impl Run {
    pub(super) fn new(evolver: Evolver) -> Self {
        let first = FrameRecord::of(&evolver, 0, Vec::new(), Vec::new());
        Run {
            checkpoints: vec![(0, evolver.clone())],
            edits: evolver.edits().to_vec(),
            evolver,
            history: vec![first],
        }
    }

    /// The frame the evolver is at (the last one recorded).
    pub fn head(&self) -> usize {
        self.evolver.frames()
    }

    /// The last recorded frame.
    pub fn last(&self) -> usize {
        self.history.len() - 1
    }

    /// Every edit of the run, made or waiting for its frame.
    pub fn edits(&self) -> &[Edit] {
        &self.edits
    }

    /// Every topology event of the recorded frames, with its frame, in order.
    pub fn events(&self) -> impl Iterator<Item = (usize, &TopologyEvent)> {
        self.history
            .iter()
            .flat_map(|r| r.events.iter().map(move |e| (r.index, e)))
    }

    /// Records one more frame (the evolver steps, then makes the edits due at the new
    /// frame).
    pub(super) fn step(&mut self) -> &FrameRecord {
        let before = self.evolver.events().len();
        let f = self.evolver.step();
        redo_due(&mut self.evolver, &self.edits);
        let events = self.evolver.events()[before..]
            .iter()
            .map(|e| e.event)
            .collect();
        let mut rec = FrameRecord::of(&self.evolver, f.index, events, f.motions);
        (rec.energy, rec.converged) = (f.energy, f.converged);
        self.history.truncate(f.index);
        self.history.push(rec);
        if f.index.is_multiple_of(CHECKPOINT_EVERY) {
            self.checkpoints.retain(|(i, _)| *i < f.index);
            self.checkpoints.push((f.index, self.evolver.clone()));
        }
        self.history.last().expect("just pushed")
    }

    /// The evolver as it was at recorded frame `n` (a copy; the run is untouched).
    pub fn evolver_at(&self, n: usize) -> Evolver {
        let n = n.min(self.last());
        if n == self.head() {
            return self.evolver.clone();
        }
        let (_, ev) = self.checkpoint_before(n);
        let mut ev = ev.clone();
        advance_to(&mut ev, n, &self.edits);
        ev
    }

    fn checkpoint_before(&self, n: usize) -> &(usize, Evolver) {
        self.checkpoints
            .iter()
            .rev()
            .find(|(i, _)| *i <= n)
            .expect("frame 0 is a checkpoint")
    }

    /// Puts the evolver back at recorded frame `n` and drops the frames after it, so
    /// stepping continues from there (edits made later wait for their frame).
    fn rewind(&mut self, n: usize) {
        if n == self.head() {
            return;
        }
        self.evolver = self.evolver_at(n);
        self.history.truncate(n + 1);
        self.checkpoints.retain(|(i, _)| *i <= n);
    }

    /// Applies `change` to the evolver at recorded frame `at` (a hand edit or a change of
    /// forces): later frames are dropped, frame `at` is recorded again with the edit's
    /// events added and becomes a checkpoint. Edits made at later frames stay and are made
    /// again when the run gets there. Returns the edit's events.
    pub(super) fn edit_at(
        &mut self,
        at: usize,
        change: impl FnOnce(&mut Evolver),
    ) -> Vec<TopologyEvent> {
        self.rewind(at);
        let (made, before) = (self.evolver.edits().len(), self.evolver.events().len());
        change(&mut self.evolver);
        let new = self.evolver.edits()[made..].to_vec();
        self.edits.splice(made..made, new);
        let events: Vec<TopologyEvent> = self.evolver.events()[before..]
            .iter()
            .map(|e| e.event)
            .collect();
        let old = &self.history[at];
        let mut rec = FrameRecord::of(&self.evolver, at, old.events.clone(), old.motions.clone());
        rec.events.extend(events.iter().copied());
        (rec.energy, rec.converged) = (old.energy, old.converged);
        self.history[at] = rec;
        self.checkpoints.retain(|(i, _)| *i < at);
        self.checkpoints.push((at, self.evolver.clone()));
        events
    }

    /// How many edits wait for a frame the run has not reached again.
    pub fn waiting_edits(&self) -> usize {
        self.edits.len() - self.evolver.edits().len()
    }
}

/// A session's job steps the run, so every frame it makes is recorded.
impl crate::job::Steps for Run {
    fn frames(&self) -> usize {
        self.head()
    }
    fn is_finished(&self) -> bool {
        self.evolver.is_finished()
    }
    fn step(&mut self) {
        Run::step(self);
    }
    fn run(&mut self) {
        while !self.evolver.is_finished() {
            Run::step(self);
        }
    }
    fn edit(&mut self, edit: &Edit) -> Result<(), crate::evolution::EvolveError> {
        let mut result = Ok(());
        self.edit_at(self.head(), |ev| result = ev.redo_edit(edit));
        result
    }
}

/// Steps `ev` to frame `n`, making the edits of `edits` due on the way.
fn advance_to(ev: &mut Evolver, n: usize, edits: &[Edit]) {
    while ev.frames() < n {
        ev.step();
        redo_due(ev, edits);
    }
}

/// Makes the edits of `edits` that `ev` has not made and that are due at its frame. The
/// evolver's own edits are a prefix of `edits`.
fn redo_due(ev: &mut Evolver, edits: &[Edit]) {
    while let Some(edit) = edits.get(ev.edits().len()) {
        if edit.frame() > ev.frames() {
            break;
        }
        // An edit that was valid when made stays valid: a force change checks only the
        // weights, the others tolerate contours that have gone.
        if ev.redo_edit(edit).is_err() {
            break;
        }
    }
}
