//! Tracking cells through a movie: each frame is one evolution that starts from the
//! contours of the frame before, and a cell's division is the exact split event of the
//! topology core (seed 003, §2.4: pseudo-local topology tracking, which names both pieces
//! of a ring that pinched in two), found at the frame and place it happens with no
//! threshold — not a heuristic over contours that another tool drew.
//!
//! Frame by frame:
//! - frame 0 starts from the user's shapes (clicks, strokes, a wrap) and, without any,
//!   from automatic seeds; frame t + 1 starts from frame t's contours, each shrunk a
//!   little ([`carry::shrunk`]) so a cell that moved is still under its contour, and
//!   evolves on frame t + 1 through the whole pyramid (coarse to fine, seed 004 §2.2:
//!   the coarse levels carry a contour over a large move before the fine ones settle it);
//! - the engine is [`crate::evolution::Mode::Track`]: moves go through the core under
//!   [`crate::topology::TopologyPolicy::TRACKING`], so touching cells never merge, no
//!   hole opens, and a cell that pinches splits;
//! - identity is the contour carried across frames; a contour that vanished (or was
//!   dropped as clutter) ends its track; the pieces of a split are its two children,
//!   whose parent is the track that split (a piece under [`MIN_DAUGHTER_SHARE`] of the
//!   largest is a shred, not a daughter, and is dropped);
//! - cells entering or appearing where no contour is are picked up by the frame's
//!   automatic seeds that lie wholly outside every tracked cell of the frame before.
//!
//! Memory holds the frame being tracked and the contours of the one before.

pub mod carry;
pub mod lineage;
mod resume;

pub use lineage::{Division, Lineage, Track};

use crate::evolution::{find_seeds, EvolveError, Evolver, Field, Mode, Params, Shape};
use crate::geometry::Point;
use crate::topology::TopologyEvent;
use carry::{label_raster, ring_origins, shrunk, uncovered};

/// Smallest area of a split's smaller piece, as a share of the larger, for the split to
/// be a division (daughters of a division are of one size; a shred torn off by noise
/// is not).
pub const MIN_DAUGHTER_SHARE: f64 = 0.2;

/// How tracking runs.
#[derive(Clone, Debug, PartialEq)]
pub struct TrackSettings {
    /// The evolution's parameters (the mode is set to [`Mode::Track`]).
    pub params: Params,
    /// How far (pixels) a contour moves in before the next frame starts from it.
    pub shrink: f64,
    /// Place automatic seeds on frame 0 (besides any shapes given).
    pub auto_seeds: bool,
    /// Pick up new cells with automatic seeds on every later frame.
    pub new_cells: bool,
    /// Pyramid levels a frame after the first evolves through (frame 0 uses the full
    /// pyramid of its parameters): 1 is the full resolution only, each more level
    /// carries a contour over a move twice as large.
    pub levels: usize,
}

impl TrackSettings {
    /// The defaults around `params`.
    pub fn new(params: Params) -> Self {
        TrackSettings {
            params: Params {
                mode: Mode::Track,
                ..params
            },
            shrink: 2.0,
            auto_seeds: true,
            new_cells: true,
            levels: 2,
        }
    }
}

/// One tracked cell in one frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TrackedObject {
    /// Its track.
    pub track: u32,
    /// Its outline (region on the left).
    pub ring: Vec<Point>,
    /// Area, square pixels.
    pub area: f64,
    /// Centroid.
    pub centroid: Point,
}

/// What tracking found in one frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TrackedFrame {
    /// The frame (0-based).
    pub frame: usize,
    /// The cells, by track label.
    pub objects: Vec<TrackedObject>,
    /// Divisions whose children start in this frame.
    pub divisions: Vec<Division>,
    /// Frames the evolution ran.
    pub evolution_frames: usize,
}

/// Tracks a movie frame by frame ([`Tracker::step`]).
#[derive(Clone, Debug)]
pub struct Tracker {
    settings: TrackSettings,
    init: Vec<Shape>,
    lineage: Lineage,
    /// The cells of the last frame: track and outline.
    live: Vec<(u32, Vec<Point>)>,
    /// Their label raster.
    labels: Vec<u32>,
    frame: usize,
}

impl Tracker {
    /// A tracker starting frame 0 from `init` (and automatic seeds, if the settings say so).
    pub fn new(settings: TrackSettings, init: Vec<Shape>) -> Self {
        Tracker {
            settings,
            init,
            lineage: Lineage::default(),
            live: Vec::new(),
            labels: Vec::new(),
            frame: 0,
        }
    }

    /// The tracks so far.
    pub fn lineage(&self) -> &Lineage {
        &self.lineage
    }

    /// The label raster of the last frame tracked (track labels, 0 outside).
    pub fn labels(&self) -> &[u32] {
        &self.labels
    }

    /// Tracks the next frame.
    pub fn step(&mut self, image: &Field) -> Result<TrackedFrame, EvolveError> {
        let t = self.frame;
        let (w, h) = (image.width, image.height);
        if self.labels.len() != w * h {
            self.labels = vec![0; w * h];
        }
        let mut shapes: Vec<Shape> = Vec::new();
        let mut owners: Vec<Option<u32>> = Vec::new();
        for (track, ring) in &self.live {
            shapes.push(shrunk(ring, self.settings.shrink));
            owners.push(Some(*track));
        }
        if t == 0 {
            for s in std::mem::take(&mut self.init) {
                shapes.push(s);
                owners.push(None);
            }
        }
        let seeding = if t == 0 {
            self.settings.auto_seeds || shapes.is_empty()
        } else {
            self.settings.new_cells
        };
        if seeding {
            let p = &self.settings.params;
            let mut seeds: Vec<Shape> = find_seeds(image, p.polarity, p.modality)
                .into_iter()
                .filter(|s| t == 0 || uncovered(s, &self.labels, w, h))
                .collect();
            // New tracks are numbered left to right.
            seeds.sort_by(|a, b| {
                let (a, b) = (a.center(), b.center());
                (a.x, a.y)
                    .partial_cmp(&(b.x, b.y))
                    .unwrap_or(std::cmp::Ordering::Equal)
            });
            owners.extend(seeds.iter().map(|_| None));
            shapes.extend(seeds);
        }
        let (pieces, evolution_frames) = self.evolve(image, &shapes)?;
        let mut frame = TrackedFrame {
            frame: t,
            objects: Vec::new(),
            divisions: Vec::new(),
            evolution_frames,
        };
        for (owner, group) in owners.iter().zip(pieces) {
            self.settle(*owner, group, &mut frame);
        }
        frame.objects.sort_by_key(|o| o.track);
        self.live = frame
            .objects
            .iter()
            .map(|o| (o.track, o.ring.clone()))
            .collect();
        let rings: Vec<(u32, &[Point])> = frame
            .objects
            .iter()
            .map(|o| (o.track, o.ring.as_slice()))
            .collect();
        self.labels = label_raster(&rings, w, h);
        self.frame += 1;
        Ok(frame)
    }

    /// Evolves from `shapes`; returns, per shape, the pieces it ended as (largest first)
    /// and the frames the evolution ran.
    fn evolve(
        &self,
        image: &Field,
        shapes: &[Shape],
    ) -> Result<(Vec<Vec<TrackedObject>>, usize), EvolveError> {
        let mut pieces: Vec<Vec<TrackedObject>> = vec![Vec::new(); shapes.len()];
        if shapes.is_empty() {
            return Ok((pieces, 0));
        }
        let mut params = self.settings.params.clone();
        if self.frame > 0 {
            let side = image.width.min(image.height);
            params.coarsest_side = (side >> self.settings.levels.max(1).saturating_sub(1)).max(1);
        }
        let mut ev = match Evolver::new(image, shapes, params) {
            Ok(ev) => ev,
            Err(EvolveError::EmptyInit) => return Ok((pieces, 0)),
            Err(e) => return Err(e),
        };
        let mut origin: std::collections::HashMap<u32, usize> =
            ring_origins(ev.contours(), shapes).into_iter().collect();
        ev.run();
        ev.filter_clutter();
        for e in ev.events() {
            if let TopologyEvent::Split { from, new } = e.event {
                if let Some(&i) = origin.get(&from.0) {
                    origin.insert(new.0, i);
                }
            }
        }
        let set = ev.contours();
        for r in crate::evolution::regions(set) {
            if let Some(&i) = origin.get(&r.id.0) {
                pieces[i].push(TrackedObject {
                    track: 0,
                    ring: set.ring_points(r.id),
                    area: r.area,
                    centroid: r.centroid,
                });
            }
        }
        for g in &mut pieces {
            g.sort_by(|a, b| b.area.total_cmp(&a.area));
            if let Some(big) = g.first().map(|o| o.area) {
                g.retain(|o| o.area >= MIN_DAUGHTER_SHARE * big);
            }
        }
        Ok((pieces, ev.frames()))
    }

    /// Gives the pieces of one shape their tracks: the same track for one piece of a
    /// tracked cell, two children for two or more (the two largest; any further piece
    /// starts a track of its own), new tracks for the pieces of a new seed.
    fn settle(&mut self, owner: Option<u32>, group: Vec<TrackedObject>, frame: &mut TrackedFrame) {
        let t = frame.frame;
        let mut labels: Vec<u32> = Vec::with_capacity(group.len());
        match (owner, group.len()) {
            (_, 0) => {}
            (Some(track), 1) => {
                self.lineage.extend(track, t);
                labels.push(track);
            }
            (Some(parent), _) => {
                let children = [self.lineage.start(t, parent), self.lineage.start(t, parent)];
                frame.divisions.push(Division {
                    frame: t,
                    parent,
                    children,
                });
                labels.extend(children);
                while labels.len() < group.len() {
                    labels.push(self.lineage.start(t, 0));
                }
            }
            (None, n) => labels.extend((0..n).map(|_| self.lineage.start(t, 0))),
        }
        for (mut o, label) in group.into_iter().zip(labels) {
            o.track = label;
            frame.objects.push(o);
        }
    }
}
