//! A run on screen: the evolver, the frames recorded for display, and checkpoints to
//! continue or edit from any recorded frame.

use crate::evolution::Evolver;
use crate::geometry::Point;
use crate::topology::{MotionRegion, TopologyEvent};

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
    /// The rings.
    pub rings: Vec<RingView>,
    /// The frame's topology events.
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

impl FrameRecord {
    fn of(
        ev: &Evolver,
        index: usize,
        events: Vec<TopologyEvent>,
        motions: Vec<MotionRegion>,
        energy: f64,
        converged: bool,
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
            rings,
            events,
            motions,
            area: set.region_area(),
            contours: set.contour_count(),
            vertices: set.vertex_count(),
            energy,
            converged,
        }
    }
}

/// An evolution in progress with its recorded history.
#[derive(Clone)]
pub struct Run {
    /// The evolver, at the run's head frame.
    pub evolver: Evolver,
    /// Frame 0 is the initialisation.
    pub history: Vec<FrameRecord>,
    /// Evolver states every few frames, to continue from any recorded frame.
    checkpoints: Vec<(usize, Evolver)>,
}

const CHECKPOINT_EVERY: usize = 10;

impl Run {
    pub(super) fn new(evolver: Evolver) -> Self {
        let first = FrameRecord::of(&evolver, 0, Vec::new(), Vec::new(), 0.0, false);
        Run {
            checkpoints: vec![(0, evolver.clone())],
            evolver,
            history: vec![first],
        }
    }

    /// The frame the evolver is at.
    pub fn head(&self) -> usize {
        self.evolver.frames()
    }

    pub(super) fn step(&mut self) -> &FrameRecord {
        let f = self.evolver.step();
        let rec = FrameRecord::of(
            &self.evolver,
            f.index,
            f.events,
            f.motions,
            f.energy,
            f.converged,
        );
        self.history.truncate(f.index);
        self.history.push(rec);
        if f.index.is_multiple_of(CHECKPOINT_EVERY) {
            self.checkpoints.retain(|(i, _)| *i < f.index);
            self.checkpoints.push((f.index, self.evolver.clone()));
        }
        self.history.last().expect("just pushed")
    }

    /// Puts the evolver back at recorded frame `n`, so stepping continues from there.
    pub(super) fn rewind(&mut self, n: usize) {
        if n == self.head() {
            return;
        }
        let (at, ev) = self
            .checkpoints
            .iter()
            .rev()
            .find(|(i, _)| *i <= n)
            .cloned()
            .expect("frame 0 is a checkpoint");
        self.evolver = ev;
        let mut i = at;
        while i < n {
            self.evolver.step();
            i += 1;
        }
        self.history.truncate(n + 1);
        self.checkpoints.retain(|(i, _)| *i <= n);
    }

    /// Applies `change` to the evolver at recorded frame `at` (a hand edit): later frames
    /// are dropped, frame `at` is recorded again with `events` and becomes a checkpoint,
    /// so stepping and rewinding continue from the edited contours.
    pub(super) fn edit_at(
        &mut self,
        at: usize,
        change: impl FnOnce(&mut Evolver) -> Vec<TopologyEvent>,
    ) -> Vec<TopologyEvent> {
        self.rewind(at);
        let events = change(&mut self.evolver);
        let (energy, converged) = (self.history[at].energy, self.history[at].converged);
        self.history[at] = FrameRecord::of(
            &self.evolver,
            at,
            events.clone(),
            Vec::new(),
            energy,
            converged,
        );
        self.checkpoints.retain(|(i, _)| *i < at);
        self.checkpoints.push((at, self.evolver.clone()));
        events
    }
}
