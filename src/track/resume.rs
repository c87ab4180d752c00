//! Tracking on from a frame already tracked: the app's hand corrections of frame t
//! (a wrong split undone, a merge forced) make a new frame t, and the frames after it
//! are tracked again from its contours, as [`Tracker::step`] would have from its own.
//!
//! A tracker carries more than the last frame's contours: when it looks for new cells
//! next, the size each young rod was born at, the necks it measured, the divisions whose
//! daughters were born apart ([`Memory`]). Resumed without them, the frames after a
//! correction were tracked differently far from it (new cells looked for at once, a
//! neighbour's division lost), so the app keeps each frame's memory and a resumed tracker
//! takes it back, less what a correction makes unsure ([`Memory::corrected`]): the
//! corrected frame stays as the user left it.
//!
//! A cell the user deleted stays deleted: its outline is remembered as unwanted, and in
//! the frames after it is carried and evolved as the cells are, then taken out of the
//! frame: no new cell is taken where it lies (a speck deleted at one frame was found
//! again as a new cell at the next look). So it follows the cell it was as that cell
//! moves and divides (a place that only followed the stage's drift let a nucleus deleted
//! at frame 10 come back when it divided at frame 36, beside where it was deleted).
//!
//! The cells keep their numbers: a track begun after the correction is numbered as the
//! run it replaces numbered the same cell ([`Numbers`]), and a track that run did not
//! have takes a number after all of its. Numbered on from the corrected frame, a deleted
//! cell's daughters or a cut's new cell shifted the number of every later cell, so cell
//! 40 of the movie the user had looked at was cell 38 after a correction far from it.

use super::neck::Neck;
use super::{Division, Lineage, Size, TrackSettings, TrackedFrame, TrackedObject, Tracker};
use crate::geometry::{fill_even_odd, winding_number, Point};
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// A corrected frame's cell is the one the tracker knew under its track when its area is
/// within this share of it and its centroid within this many pixels.
pub const SAME_CELL: f64 = 0.01;

/// A cell of the frame before a correction is deleted when its track is gone and the
/// corrected cells cover less than this share of its pixels (a merge or a redrawn
/// outline covers most of it).
pub const DELETED_COVER: f64 = 0.5;

/// What a tracker remembers of the frames before its next one, beyond their contours
/// and tracks ([`Tracker::memory`]). The default is what a new tracker knows: nothing,
/// so it looks for new cells at once.
#[derive(Clone, Debug)]
pub struct Memory {
    next_seeding: usize,
    residual: usize,
    look_residual: bool,
    apart: Vec<Division>,
    necks: HashMap<u32, (Neck, Option<f64>)>,
    born: HashMap<u32, Size>,
    joined: HashSet<u32>,
    unwanted: Vec<Vec<Point>>,
}

impl Default for Memory {
    fn default() -> Self {
        Memory {
            next_seeding: 0,
            residual: 0,
            look_residual: true,
            apart: Vec::new(),
            necks: HashMap::new(),
            born: HashMap::new(),
            joined: HashSet::new(),
            unwanted: Vec::new(),
        }
    }
}

impl Memory {
    /// This memory for frame `old` as corrected into `new`: the frame the user corrected
    /// is never revised, so no neck or sisters born apart are kept (a later frame would
    /// date a division into it, or take one back there); a birth size only for a cell
    /// the correction left as it was: its track the same and its area and centroid
    /// within [`SAME_CELL`] (a run
    /// opened for correction puts points on the outline's edges, which moves neither).
    /// The outlines of the cells the correction deleted ([`DELETED_COVER`]) join the
    /// places no new cell is taken (the frames are `width`×`height`). A cell the
    /// correction joined others into (their tracks gone, their pixels covered by it: a
    /// neighbour that took them in, or the mother of sisters made one again) holds
    /// together as one cell until it has grown by [`super::MIN_GROWTH`], as a cell just
    /// born does: a join made by hand came apart again at the next frame, as a new
    /// division.
    pub fn corrected(
        &self,
        old: &TrackedFrame,
        new: &TrackedFrame,
        width: usize,
        height: usize,
    ) -> Memory {
        let cell = |f: &TrackedFrame, k: u32| {
            f.objects
                .iter()
                .find(|o| o.track == k)
                .map(|o| (o.area, o.centroid))
        };
        let kept = |k: u32| match (cell(old, k), cell(new, k)) {
            (Some((a, c)), Some((b, d))) => {
                (a - b).abs() <= SAME_CELL * a && c.dist(d) <= SAME_CELL
            }
            _ => false,
        };
        let covered = new.label_raster(width, height);
        let mut unwanted = self.unwanted.clone();
        let mut joined = self.joined.clone();
        let mut born: HashMap<u32, Size> = (self.born.iter())
            .filter(|(k, _)| kept(**k))
            .map(|(k, v)| (*k, *v))
            .collect();
        for o in &old.objects {
            if new.objects.iter().any(|n| n.track == o.track) {
                continue;
            }
            // The corrected cells over the gone cell's pixels, by track.
            let mut under: HashMap<u32, usize> = HashMap::new();
            let mut all = 0usize;
            fill_even_odd(std::slice::from_ref(&o.ring), width, height, |i| {
                all += 1;
                if covered[i] != 0 {
                    *under.entry(covered[i]).or_default() += 1;
                }
            });
            let on: usize = under.values().sum();
            if all == 0 {
                continue;
            }
            if (on as f64) < DELETED_COVER * all as f64 {
                unwanted.push(o.ring.clone());
                continue;
            }
            // Joined into the cell over most of it: one that was there (a neighbour
            // took it in) or the mother of its division (sisters made one again); not a
            // cell the correction began (a cut's daughters, a cell drawn anew).
            let Some((&k, _)) = under
                .iter()
                .max_by_key(|(k, n)| (**n, std::cmp::Reverse(**k)))
            else {
                continue;
            };
            let was_there = old.objects.iter().any(|c| c.track == k);
            let its_mother =
                (old.divisions.iter()).any(|d| d.parent == k && d.children.contains(&o.track));
            if let Some(cell) = new
                .objects
                .iter()
                .find(|n| n.track == k)
                .filter(|_| was_there || its_mother)
            {
                joined.insert(k);
                born.insert(k, Size::of([cell]));
            }
        }
        // Built field by field: cloning the whole memory would copy the necks' lobes only
        // to drop them.
        Memory {
            next_seeding: self.next_seeding,
            residual: self.residual,
            look_residual: self.look_residual,
            apart: Vec::new(),
            necks: HashMap::new(),
            born,
            joined,
            unwanted,
        }
    }

    /// Where the user deleted cells: no new cell is taken there.
    pub fn unwanted(&self) -> &[Vec<Point>] {
        &self.unwanted
    }

    /// What a new tracker knows, and where the user deleted cells (`unwanted`): the
    /// memory of a tracking reopened from its session, which keeps no more.
    pub fn with_unwanted(unwanted: Vec<Vec<Point>>) -> Memory {
        Memory {
            unwanted,
            ..Memory::default()
        }
    }
}

/// The frames a correction replaced, and their tracks: a track begun in the frames
/// tracked again keeps the number of the track the replaced run began there of the same
/// parent, on the same cell (each cell's centroid inside the other's outline).
#[derive(Clone, Debug)]
pub(super) struct Numbers {
    frames: HashMap<usize, Arc<TrackedFrame>>,
    lineage: Lineage,
    /// Numbers given again already: each once.
    given: HashSet<u32>,
}

impl Numbers {
    /// The replaced run's number for `cell`, beginning a track at frame `t` of `parent`
    /// (0: none); its frames before `t` are no longer needed.
    pub(super) fn number(&mut self, t: usize, parent: u32, cell: &TrackedObject) -> Option<u32> {
        self.frames.retain(|&k, _| k >= t);
        let inside = |p: Point, ring: &[Point]| winding_number(ring, p) != 0;
        let label = (self.frames.get(&t)?.objects.iter())
            .filter(|o| !self.given.contains(&o.track))
            .filter(|o| {
                // A division dated a frame earlier began its tracks there.
                self.lineage
                    .get(o.track)
                    .is_some_and(|tr| tr.parent == parent && (tr.first == t || tr.first + 1 == t))
            })
            .filter(|o| inside(o.centroid, &cell.ring) && inside(cell.centroid, &o.ring))
            .min_by(|a, b| {
                let d = |o: &TrackedObject| o.centroid.dist(cell.centroid);
                d(a).total_cmp(&d(b))
            })?
            .track;
        self.given.insert(label);
        Some(label)
    }
}

impl Tracker {
    /// This tracker, resumed after a correction, numbering the tracks it begins as the
    /// run it replaces did: that run's `frames` after the corrected one and its
    /// `lineage`. A track that run did not have is numbered after all of its.
    pub fn keeping_numbers(
        mut self,
        frames: impl IntoIterator<Item = Arc<TrackedFrame>>,
        lineage: &Lineage,
    ) -> Self {
        self.lineage.reserve(lineage.last_label());
        let from = self.frame;
        self.numbers = Some(Numbers {
            frames: (frames.into_iter())
                .filter(|f| f.frame >= from)
                .map(|f| (f.frame, f))
                .collect(),
            lineage: lineage.clone(),
            given: HashSet::new(),
        });
        self
    }

    /// What this tracker remembers beyond the last frame's contours and the tracks: with
    /// them, [`Tracker::resume`] gives a tracker that goes on as this one would.
    pub fn memory(&self) -> Memory {
        Memory {
            next_seeding: self.next_seeding,
            residual: self.residual,
            look_residual: self.look_residual,
            apart: self.apart.clone(),
            necks: self.necks.clone(),
            born: self.born.clone(),
            joined: self.joined.clone(),
            unwanted: self.unwanted.clone(),
        }
    }

    /// A tracker whose next frame is `last.frame + 1`, started from `last`'s cells, with
    /// the tracks so far `lineage`, on `width`×`height` frames, and what the tracker that
    /// tracked `last` remembered (`memory`; without it, new cells are looked for at once
    /// and nothing is known of the cells' births and necks, as [`Memory::default`]).
    pub fn resume(
        settings: TrackSettings,
        lineage: Lineage,
        last: &TrackedFrame,
        width: usize,
        height: usize,
        memory: Option<Memory>,
    ) -> Self {
        let mut t = Tracker::new(settings, Vec::new());
        t.lineage = lineage;
        t.live = last
            .objects
            .iter()
            .map(|o| (o.track, o.ring.clone()))
            .collect();
        t.labels = last.label_raster(width, height);
        t.frame = last.frame + 1;
        let m = memory.unwrap_or_default();
        t.next_seeding = m.next_seeding;
        t.residual = m.residual;
        t.look_residual = m.look_residual;
        t.apart = m.apart;
        t.necks = m.necks;
        t.born = m.born;
        t.joined = m.joined;
        t.unwanted = m.unwanted;
        t
    }
}
