//! Hand corrections of a tracked movie frame (issue 26): with the Edit or Brush tool on
//! a tracked frame, the run on screen holds that frame's contours (full resolution, the
//! adaptive engine, so a merge can be forced and a split made); when a gesture ends the
//! contours become the frame again and the frames after it are tracked again from them,
//! on the background thread, as tracking would have gone on from its own contours.
//!
//! Identity across the correction: each corrected cell is the track of the frame's cell
//! it covers most. A cell that covers a daughter of a division at this frame continues
//! the mother (the wrong split undone); one cell per track continues it; two or more
//! cells of one track are a division there (the two largest its daughters); a cell over
//! no tracked cell starts a track. Tracks that no corrected cell continues end the frame
//! before (a merge forced: the larger overlap keeps its track). A cell that begins a
//! track keeps the number of the track it covers most when that one began at this frame
//! of the same parent: the daughters and new cells a correction left alone keep their
//! numbers (numbered again by size and place, two daughters of like size swapped).
//!
//! Nothing the user did is lost without asking: tracking the frames after frame t again
//! replaces any correction on them, so that is asked first ([`super::Question`]); each
//! correction is one undo step with the tracking it replaced.

use super::{Command, Question, Run, Tool, TopoApp};
use crate::evolution::{regions, Evolver, Mode, Shape};
use crate::geometry::Point;
use crate::track::{
    carry::label_raster, Division, Lineage, Memory, TrackedFrame, TrackedObject, Tracker,
};
use std::collections::HashMap;
use std::sync::Arc;

impl TopoApp {
    /// With the Edit or Brush tool on a tracked frame and no run on screen: a run holding
    /// the frame's contours, to correct them. Whether a correction run is on screen.
    pub(super) fn begin_correction(&mut self) -> bool {
        let Some(m) = &self.doc.movie else {
            return false;
        };
        if self.doc.run.is_some() {
            return m.correcting.is_some();
        }
        if !matches!(self.view.prefs.tool, Tool::Edit | Tool::Brush) {
            return false;
        }
        // While the slider follows the frames being tracked, they are not for editing.
        if self.jobs.track.is_some() && self.view.follow_tracking {
            return false;
        }
        let (Some(f), Some(image)) = (m.tracked_frame(), self.doc.image.clone()) else {
            return false;
        };
        let t = f.frame;
        let shapes: Vec<Shape> = f
            .objects
            .iter()
            .map(|o| Shape::Polygon(o.ring.clone()))
            .collect();
        if shapes.is_empty() {
            return false;
        }
        let base = m
            .tracking
            .as_ref()
            .and_then(|tr| tr.settings.as_ref())
            .map_or_else(|| self.doc.params().clone(), |s| s.params.clone());
        // Adaptive, so a merge can be forced; one level at full resolution, so the
        // rings are the tracked ones and not a coarse grid's.
        let params = crate::evolution::Params {
            mode: Mode::Adaptive,
            coarsest_side: image.width.min(image.height).clamp(8, 1 << 16),
            ..base
        };
        match Evolver::new(&image, &shapes, params) {
            Ok(ev) => {
                self.doc.run = Some(Run::new(ev));
                self.doc.shown = 0;
                if let Some(m) = self.doc.movie.as_mut() {
                    m.correcting = Some((t, 0));
                }
                true
            }
            Err(e) => {
                self.status.error = Some(e.into());
                false
            }
        }
    }

    /// The track each cell of the correction on screen keeps, and the cell's centroid, by
    /// contour id, as the canvas and the object table show them; None when no correction
    /// is on screen.
    pub fn correction_cells(&self) -> Option<HashMap<u32, (u32, Point)>> {
        correction_tracks(&self.doc, self.doc.shown_record()?)
    }

    /// Whether a correction on screen is not in the tracking yet.
    pub(super) fn correction_waiting(&self) -> bool {
        let (Some(m), Some(run)) = (&self.doc.movie, &self.doc.run) else {
            return false;
        };
        m.correcting
            .is_some_and(|(_, made)| run.edits().len() > made)
    }

    /// Called every frame: once the gesture has ended (no button held) the correction
    /// goes into the tracking; with no edit, a correction run of another tool is dropped.
    pub(super) fn poll_correction(&mut self, button_down: bool) {
        let Some((t, _)) = self.doc.movie.as_ref().and_then(|m| m.correcting) else {
            return;
        };
        if button_down || self.view.question.is_some() {
            return;
        }
        if self.correction_waiting() {
            self.commit_correction(t, false);
        } else if !matches!(self.view.prefs.tool, Tool::Edit | Tool::Brush) {
            self.reset_run();
            if let Some(m) = self.doc.movie.as_mut() {
                m.correcting = None;
            }
        }
    }

    /// Puts the correction of frame `t` into the tracking and tracks the frames after it
    /// again; asks first (unless `confirmed`) when later frames hold corrections.
    pub(super) fn commit_correction(&mut self, t: usize, confirmed: bool) {
        self.view.question = None;
        if !self.correction_waiting() {
            return;
        }
        let Some(m) = self.doc.movie.as_ref() else {
            return;
        };
        let Some(tr) = m.tracking.as_ref() else {
            return;
        };
        let later: Vec<usize> = tr.corrected.range(t + 1..).copied().collect();
        if !later.is_empty() && !confirmed {
            self.view.question = Some(Question::Retrack { frame: t, later });
            return;
        }
        let (Some(run), Some(old)) = (self.doc.run.as_ref(), tr.frames.get(t).cloned()) else {
            return;
        };
        let (w, h) = m.movie.size();
        let ev = run.evolver_at(self.doc.shown);
        let set = ev.filtered_contours(ev.params().min_area);
        let cells: Vec<TrackedObject> = regions(&set)
            .into_iter()
            .map(|r| TrackedObject {
                track: 0,
                ring: set.ring_points(r.id),
                area: r.area,
                centroid: r.centroid,
            })
            .collect();
        let (frame, lineage) = corrected(&old, &tr.lineage, cells, w, h);
        let summary = describe(&old, &frame);
        let edits = run.edits().len();
        let len = m.movie.len();
        let settings = tr.settings.clone();
        self.stop_tracking();
        let frame = Arc::new(frame);
        let m = self.doc.movie.as_mut().expect("checked");
        m.correcting = Some((t, edits));
        let tr = m.tracking.as_mut().expect("checked");
        tr.id = super::movie::next_tracking_id();
        // The frames tracked again number their cells as these did, and as the run an
        // earlier correction replaced did beyond where its tracking again has reached.
        let mut frames = tr.frames.split_off(t + 1);
        let mut lineage_then = tr.lineage.clone();
        if let Some(r) = tr.replaced.as_ref().filter(|_| !tr.complete) {
            let reached = frames.last().map_or(t, |f| f.frame);
            frames.extend(r.frames.iter().filter(|f| f.frame > reached).cloned());
            // Tracks of either run: the earlier run's where this one has none.
            for track in r.lineage.tracks() {
                lineage_then.insert(*track);
            }
        }
        let replaced = Arc::new(super::movie::Replaced {
            frames,
            lineage: lineage_then,
        });
        tr.replaced = Some(replaced.clone());
        tr.frames.truncate(t);
        tr.frames.push(frame.clone());
        // What the tracker knew after frame t (nothing, for a tracking reopened from its
        // session), less what the correction makes unsure, and where cells were deleted.
        let memory = (tr
            .memory
            .get(&t)
            .map_or_else(Memory::default, |m| Memory::clone(m)))
        .corrected(&old, &frame, w, h);
        tr.memory.retain(|&k, _| k < t);
        tr.memory.insert(t, Arc::new(memory.clone()));
        tr.lineage = lineage.clone();
        tr.stopped = None;
        tr.corrected.retain(|&f| f < t);
        tr.corrected.insert(t);
        tr.complete = t + 1 == len;
        tr.running = !tr.complete;
        let id = tr.id;
        match settings.filter(|_| t + 1 < len) {
            Some(s) => {
                let tracker =
                    replaced.numbering(Tracker::resume(s, lineage, &frame, w, h, Some(memory)));
                self.spawn_tracking(tracker, t + 1, id);
                self.status.notify(format!(
                    "frame {t} corrected ({summary}): frames {}–{} are tracked again from it",
                    t + 1,
                    len - 1
                ));
            }
            None => self
                .status
                .notify(format!("frame {t} corrected ({summary})")),
        }
    }

    /// After Undo or Redo: a job writing into a result no longer on screen stops, and a
    /// result brought back that was being tracked is tracked on.
    pub(super) fn after_undo_tracking(&mut self) {
        let (id, running) = self
            .doc
            .movie
            .as_ref()
            .and_then(|m| m.tracking.as_ref())
            .map_or((None, false), |t| (Some(t.id), t.running && !t.complete));
        if self
            .jobs
            .track
            .as_ref()
            .is_some_and(|j| Some(j.tracking) != id)
        {
            self.stop_tracking();
        }
        if running && self.jobs.track.is_none() {
            self.apply_now(Command::ContinueTrack);
        }
    }
}

/// Per contour id of a correction on screen: the track its cell would keep, and the
/// cell's centroid.
pub type CellTracks = HashMap<u32, (u32, Point)>;

/// [`correction_tracks`] of the recording on screen, measured once per recording and
/// tracking (the table and the canvas draw every frame).
#[derive(Default)]
pub struct CorrectionTracks(Option<((u64, u64), Arc<CellTracks>)>);

impl CorrectionTracks {
    /// The tracks of the correction on screen, if one is.
    pub fn get(&mut self, doc: &super::Document) -> Option<Arc<CellTracks>> {
        let rec = doc.shown_record()?;
        let tracking = doc.movie.as_ref()?.tracking.as_ref()?.id;
        let key = (rec.stamp, tracking);
        if self.0.as_ref().is_none_or(|(k, _)| *k != key) {
            self.0 = Some((key, Arc::new(correction_tracks(doc, rec)?)));
        }
        self.0.as_ref().map(|(_, t)| t.clone())
    }
}

/// The tracks the cells of a correction on screen would keep were it put in now: by
/// contour id of the frame record `rec` (holes under their cell's), for the cells the
/// correction keeps (rings of at least the run's smallest area), as [`corrected`] gives
/// them. So the correction view shows each cell in its track's colour and number, as
/// the tracked frame did, and a cut or a join shows the tracks it makes. None when no
/// correction is on screen.
pub(super) fn correction_tracks(
    doc: &super::Document,
    rec: &super::FrameRecord,
) -> Option<CellTracks> {
    let m = doc.movie.as_ref()?;
    let (t, _) = m.correcting?;
    let tr = m.tracking.as_ref()?;
    let old = tr.frames.get(t)?;
    let min_area = doc.run.as_ref()?.evolver.params().min_area;
    let (w, h) = m.movie.size();
    let rings: Vec<(u32, bool, &[Point])> = (rec.rings.iter())
        .map(|r| (r.id, r.hole, r.points.as_slice()))
        .collect();
    let outer = |id: u32| rec.rings.iter().find(|r| r.id == id && !r.hole);
    let kept: Vec<(Vec<u32>, TrackedObject)> = crate::contours::measure::regions_of_rings(&rings)
        .into_iter()
        .filter_map(|r| {
            let ring = &outer(r.id.0)?.points;
            (crate::geometry::signed_area(ring).abs() >= min_area).then(|| {
                let cell = TrackedObject {
                    track: 0,
                    ring: ring.clone(),
                    area: r.area,
                    centroid: r.centroid,
                };
                let ids = std::iter::once(r.id).chain(r.holes).map(|c| c.0);
                (ids.collect(), cell)
            })
        })
        .collect();
    let cells = kept.iter().map(|(_, c)| c.clone()).collect();
    let (frame, _) = corrected(old, &tr.lineage, cells, w, h);
    let mut tracks = CellTracks::new();
    for (ids, c) in &kept {
        if let Some(o) = frame.objects.iter().find(|o| o.ring == c.ring) {
            tracks.extend(ids.iter().map(|&id| (id, (o.track, c.centroid))));
        }
    }
    Some(tracks)
}

/// What a correction changed, in words.
fn describe(old: &TrackedFrame, new: &TrackedFrame) -> String {
    let tracks = |f: &TrackedFrame| f.objects.iter().map(|o| o.track).collect::<Vec<_>>();
    let (a, b) = (tracks(old), tracks(new));
    let ended: Vec<String> = a
        .iter()
        .filter(|t| !b.contains(t))
        .map(u32::to_string)
        .collect();
    let started: Vec<String> = b
        .iter()
        .filter(|t| !a.contains(t))
        .map(u32::to_string)
        .collect();
    let mut parts = vec![format!("{} cells", b.len())];
    if !ended.is_empty() {
        parts.push(format!("no longer here: {}", ended.join(", ")));
    }
    if !started.is_empty() {
        parts.push(format!("new: {}", started.join(", ")));
    }
    parts.join("; ")
}

/// The tracked frame `old` corrected to the cells `cells` (track labels not yet given),
/// and the lineage with it: the tracks before `old.frame` as they were, those of the
/// frame given by the rules of the module's docs, none after.
pub fn corrected(
    old: &TrackedFrame,
    lineage: &Lineage,
    mut cells: Vec<TrackedObject>,
    width: usize,
    height: usize,
) -> (TrackedFrame, Lineage) {
    let t = old.frame;
    // The tracks that began before t, as they were up to t − 1.
    let mut new = lineage.before(t);
    // Cells from left to right: new tracks are numbered so, as tracking numbers them.
    cells.sort_by(|a, b| {
        (a.centroid.x, a.centroid.y)
            .partial_cmp(&(b.centroid.x, b.centroid.y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let now: Vec<(u32, &[Point])> = cells
        .iter()
        .enumerate()
        .map(|(k, c)| (k as u32 + 1, c.ring.as_slice()))
        .collect();
    let (was, now) = (
        old.label_raster(width, height),
        label_raster(&now, width, height),
    );
    let mut overlap: HashMap<(u32, u32), usize> = HashMap::new();
    for (&n, &o) in now.iter().zip(&was) {
        if n != 0 && o != 0 {
            *overlap.entry((n, o)).or_default() += 1;
        }
    }
    // The tracked cell each cell covers most.
    let covers = |k: usize| -> Option<u32> {
        overlap
            .iter()
            .filter(|((n, _), _)| *n == k as u32 + 1)
            .max_by_key(|((_, o), c)| (**c, std::cmp::Reverse(*o)))
            .map(|((_, o), _)| *o)
    };
    // The track each cell continues: the one it covers most, a daughter born at t
    // standing for its mother.
    let base = |k: usize| -> Option<u32> {
        let owner = covers(k)?;
        let tr = lineage.get(owner)?;
        if tr.first < t {
            Some(owner)
        } else {
            (tr.parent != 0).then_some(tr.parent)
        }
    };
    let mut groups: Vec<(Option<u32>, Vec<usize>)> = Vec::new();
    for k in 0..cells.len() {
        let b = base(k);
        match groups.iter_mut().find(|(g, _)| b.is_some() && *g == b) {
            Some((_, members)) => members.push(k),
            None => groups.push((b, vec![k])),
        }
    }
    let mut frame = TrackedFrame {
        frame: t,
        objects: Vec::new(),
        divisions: Vec::new(),
        undone: Vec::new(),
        earlier: Vec::new(),
        evolution_frames: old.evolution_frames,
    };
    // Each cell's parent when it begins a track here (0: a new cell), or the track it
    // continues.
    let mut begins: Vec<Option<u32>> = vec![None; cells.len()];
    let mut label_of = vec![0u32; cells.len()];
    let mut divided: Vec<(u32, [usize; 2])> = Vec::new();
    for (b, mut members) in groups {
        match (b, members.len()) {
            (Some(p), 1) => {
                new.extend(p, t);
                label_of[members[0]] = p;
            }
            (Some(p), _) => {
                members.sort_by(|&a, &b| cells[b].area.total_cmp(&cells[a].area));
                divided.push((p, [members[0], members[1]]));
                begins[members[0]] = Some(p);
                begins[members[1]] = Some(p);
                for &k in &members[2..] {
                    begins[k] = Some(0);
                }
            }
            (None, _) => {
                for &k in &members {
                    begins[k] = Some(0);
                }
            }
        }
    }
    // A cell that begins a track keeps the number of the track it covers most when that
    // track began here of the same parent (the larger cell, should two cover one): the
    // cells a correction left as they were keep their numbers, as the canvas showed them.
    let mut kept: Vec<(u32, usize)> = Vec::new();
    for k in 0..cells.len() {
        let Some(parent) = begins[k] else { continue };
        let Some(own) = covers(k) else { continue };
        if lineage
            .get(own)
            .is_some_and(|tr| tr.first == t && tr.parent == parent)
        {
            match kept.iter_mut().find(|(l, _)| *l == own) {
                Some(e) if cells[e.1].area < cells[k].area => e.1 = k,
                Some(_) => {}
                None => kept.push((own, k)),
            }
        }
    }
    kept.sort_unstable();
    for &(label, k) in &kept {
        // Began at t, so not among the tracks before it; labels need not rise with
        // birth once a correction kept numbers.
        label_of[k] = new.start_at(label, t, begins[k].unwrap_or(0));
    }
    // The others numbered on, left to right, after every track of the run: the tracks
    // begun after this frame keep their numbers when tracked again.
    new.reserve(lineage.last_label());
    for k in 0..cells.len() {
        if let (Some(parent), 0) = (begins[k], label_of[k]) {
            label_of[k] = new.start(t, parent);
        }
    }
    for (p, [a, b]) in divided {
        let mut children = [label_of[a], label_of[b]];
        children.sort_unstable();
        frame.divisions.push(Division {
            frame: t,
            parent: p,
            children,
        });
    }
    for (mut c, label) in cells.into_iter().zip(label_of) {
        c.track = label;
        frame.objects.push(c);
    }
    frame.objects.sort_by_key(|o| o.track);
    frame.divisions.sort_by_key(|d| d.parent);
    (frame, new)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::Track;

    fn square(track: u32, x: f64) -> TrackedObject {
        let ring = vec![
            Point::new(x, 10.0),
            Point::new(x + 8.0, 10.0),
            Point::new(x + 8.0, 18.0),
            Point::new(x, 18.0),
        ];
        TrackedObject {
            track,
            ring,
            area: 64.0,
            centroid: Point::new(x + 4.0, 14.0),
        }
    }

    /// After a first correction labels no longer rise with birth: a cell begun at the
    /// corrected frame keeps its number though a larger one (a cell a correction added
    /// earlier) began before it (numbered on, track 4 became 10).
    #[test]
    fn a_second_correction_keeps_the_numbers_the_first_kept() {
        let track = |label, first, parent| Track {
            label,
            first,
            last: 6,
            parent,
        };
        let lineage =
            Lineage::from_tracks(vec![track(1, 0, 0), track(4, 5, 0), track(9, 2, 0)], 7).unwrap();
        let old = TrackedFrame {
            frame: 5,
            objects: vec![square(1, 4.0), square(4, 24.0), square(9, 44.0)],
            divisions: Vec::new(),
            undone: Vec::new(),
            earlier: Vec::new(),
            evolution_frames: 0,
        };
        let cells: Vec<TrackedObject> =
            old.objects.iter().map(|o| square(0, o.ring[0].x)).collect();
        let (frame, new) = corrected(&old, &lineage, cells, 64, 32);
        let tracks: Vec<u32> = frame.objects.iter().map(|o| o.track).collect();
        assert_eq!(tracks, [1, 4, 9]);
        assert_eq!(new.get(4).map(|t| (t.first, t.parent)), Some((5, 0)));
        assert!(Lineage::from_tracks(new.tracks().to_vec(), 7).is_ok());
    }
}
