//! A movie in the app: its frames behind a slider of their own (apart from the
//! evolution's timeline), tracking on a background thread ([`crate::track::Tracker`],
//! one frame after another, each started from the contours of the frame before) with
//! progress and Cancel, and the result: tracks drawn in one colour per track across
//! frames, divisions in the event log, the lineage view, the Cell Tracking Challenge
//! export. The window stays responsive while tracking: the thread sends each frame as it
//! is done and wakes the window; nothing repaints once it ends. Hand corrections of a
//! tracked frame track the frames after it again ([`super::correct`]).

use super::{Command, Document, TopoApp};
use crate::evolution::{Field, Modality, Polarity};
use crate::io::export::ctc;
use crate::io::movie::Movie;
use crate::track::{Division, Lineage, Memory, TrackSettings, TrackedFrame, Tracker};
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{channel, Receiver};
use std::sync::Arc;

/// Seconds a frame of a playing movie stays on screen: five frames a second, slow
/// enough to follow a cell from frame to frame.
const MOVIE_FRAME_S: f64 = 0.2;

/// The movie of a document: its frames, the one on screen, what tracking found.
#[derive(Clone, Debug)]
pub struct MovieDoc {
    /// The movie (frames are read from it when shown).
    pub movie: Movie,
    /// The frame on screen (0-based).
    pub frame: usize,
    /// What tracking found so far (none before Track).
    pub tracking: Option<Tracking>,
    /// The run on screen holds the contours of this tracked frame for hand correction,
    /// and this many of its edits are in the tracking already.
    pub correcting: Option<(usize, usize)>,
}

/// A tracking result: the frames tracked (from frame 0 on) and their lineage.
#[derive(Clone, Debug, Default)]
pub struct Tracking {
    /// Unique to this result: a tracking job writes only into the result it was started
    /// for (Undo may have brought back another).
    pub id: u64,
    /// The tracked frames, in order (frame `t` at index `t`).
    pub frames: Vec<Arc<TrackedFrame>>,
    /// The tracks.
    pub lineage: Lineage,
    /// Every frame of the movie was tracked.
    pub complete: bool,
    /// How it was tracked (the frames after a correction are tracked so again).
    pub settings: Option<TrackSettings>,
    /// The frames the user corrected by hand.
    pub corrected: BTreeSet<usize>,
    /// A job was tracking into it (Undo back to it takes tracking up again).
    pub running: bool,
    /// What the tracker remembered after each frame it tracked, by frame
    /// ([`crate::track::Memory`]): a correction resumes tracking with it (not in a
    /// session: a reopened one resumes without).
    pub memory: HashMap<usize, Arc<Memory>>,
    /// What frame 0 suggests of the settings (dark cells in a bright halo on a generic
    /// image: phase contrast), said with the tracking's summary.
    pub hint: Option<(usize, String)>,
    /// The tracker as Cancel stopped it after the last frame: Continue goes on with it,
    /// so a cancelled and continued tracking is the one that ran on. None after a
    /// correction (the frames after it start from the corrected contours).
    pub stopped: Option<Arc<Tracker>>,
    /// The run the last correction replaced (its frames after the corrected one, its
    /// tracks): tracking resumed without the stopped tracker (Undo back to a re-tracking
    /// in progress, a second correction before the first is tracked to the end) numbers
    /// its cells as that run did ([`Tracker::keeping_numbers`]).
    pub replaced: Option<Arc<Replaced>>,
}

/// The frames a correction replaced and their tracks.
#[derive(Clone, Debug)]
pub struct Replaced {
    /// The frames after the corrected one, in order.
    pub frames: Vec<Arc<TrackedFrame>>,
    /// Their tracks.
    pub lineage: Lineage,
}

impl Replaced {
    /// `tracker`, numbering the cells it begins as this run did.
    pub fn numbering(&self, tracker: Tracker) -> Tracker {
        tracker.keeping_numbers(self.frames.iter().cloned(), &self.lineage)
    }
}

/// A new [`Tracking::id`].
pub(super) fn next_tracking_id() -> u64 {
    static IDS: AtomicU64 = AtomicU64::new(1);
    IDS.fetch_add(1, Ordering::Relaxed)
}

impl Tracking {
    /// Every division, in frame order.
    pub fn divisions(&self) -> impl Iterator<Item = &Division> {
        self.frames.iter().flat_map(|f| f.divisions.iter())
    }
}

impl MovieDoc {
    /// The tracked frame on screen, if tracking has reached it.
    pub fn tracked_frame(&self) -> Option<&TrackedFrame> {
        self.tracking.as_ref()?.frames.get(self.frame).map(|f| &**f)
    }
}

/// Tracking running in the background.
pub struct TrackJob {
    /// Frames in the movie.
    pub total: usize,
    /// Frames tracked so far.
    pub done: usize,
    /// The [`Tracking::id`] its frames go to.
    pub tracking: u64,
    cancel: Arc<AtomicBool>,
    rx: Receiver<Message>,
    handle: Option<std::thread::JoinHandle<()>>,
}

/// What the tracking thread sends.
enum Message {
    /// One more frame: its result, the lineage so far, the image, what the tracker
    /// remembers after it.
    Frame(Arc<TrackedFrame>, Lineage, Arc<Field>, Arc<Memory>),
    /// A frame could not be read or tracked.
    Failed(String),
    /// Cancel stopped the tracker (after the frame last sent).
    Stopped(Box<Tracker>),
}

/// Said when an image or movie opens with Bright objects chosen for it.
pub(super) const BRIGHT_CHOSEN: &str =
    " — bright cells on a dark background, so Bright objects (the tool bar changes it)";

/// Frames kept in memory for the slider, at most (about 0.5 GB of 512² frames): beyond,
/// a frame is read again from the movie when shown.
const CACHED_FRAMES: usize = 500;

/// Frames of the movie on screen already read, by index (not part of the document).
#[derive(Default)]
pub struct FrameCache {
    of: String,
    frames: HashMap<usize, Arc<Field>>,
}

impl FrameCache {
    fn get(&mut self, movie: &Movie, t: usize) -> Result<Arc<Field>, String> {
        if self.of != movie.name() {
            self.frames.clear();
            self.of = movie.name().to_string();
        }
        if let Some(f) = self.frames.get(&t) {
            return Ok(f.clone());
        }
        let f = movie
            .frames()
            .map_err(|e| e.to_string())?
            .nth(t)
            .ok_or_else(|| format!("{} has no frame {t}", movie.name()))?
            .map_err(|e| e.to_string())?;
        let f = Arc::new(f);
        self.put(t, f.clone());
        Ok(f)
    }

    fn put(&mut self, t: usize, f: Arc<Field>) {
        if self.frames.len() >= CACHED_FRAMES {
            self.frames.clear();
        }
        self.frames.insert(t, f);
    }
}

impl TopoApp {
    /// Movies and tracking.
    pub(super) fn movie_command(&mut self, c: Command) {
        match c {
            Command::OpenMovie(p) => self.open_movie(&p),
            Command::OpenMovieDialog(folder) => {
                let d = self.dialog();
                let chosen = if folder {
                    d.pick_folder()
                } else {
                    d.add_filter("TIFF movies", &["tif", "tiff"]).pick_file()
                };
                match chosen {
                    Some(p) => self.apply_now(Command::OpenMovie(p)),
                    None => self.prompt_path(super::PathPurpose::OpenMovie, String::new()),
                }
            }
            Command::SeekMovieFrame(t) => {
                self.view.follow_tracking = false;
                self.show_movie_frame(t);
            }
            Command::PlayMovie(on) => {
                let Some(m) = &self.doc.movie else { return };
                // Play from the start again once at the end.
                if on && m.frame + 1 >= m.movie.len() {
                    self.show_movie_frame(0);
                }
                self.view.playing = false;
                self.view.follow_tracking = false;
                (self.view.movie_playing, self.view.movie_clock) = (on, 0.0);
            }
            Command::Track => self.track_again(false),
            Command::TrackConfirmed => self.track_again(true),
            Command::ContinueTrack => self.continue_tracking(),
            Command::CancelTrack => {
                if let Some(j) = &self.jobs.track {
                    j.cancel.store(true, Ordering::SeqCst);
                }
            }
            Command::Retrack(t) => self.commit_correction(t, true),
            Command::CloseQuestion => self.view.question = None,
            Command::SelectTrack(t) => self.view.selected_track = t,
            Command::ExportCtc(dir) => match self.export_ctc(&dir) {
                Ok(n) => {
                    // What is exported is kept, unless tracking still adds frames to it.
                    self.unsaved &= self.jobs.track.is_some();
                    self.status.notify(format!(
                        "wrote {n} masks and res_track.txt to {}",
                        dir.display()
                    ))
                }
                Err(e) => self.status.error = Some(e),
            },
            Command::ExportCtcDialog => match self.dialog().pick_folder() {
                Some(p) => self.apply_now(Command::ExportCtc(p)),
                // Beside the movie, not into its folder: the challenge's own layout
                // keeps a sequence's result in `NAME_RES` next to it.
                None => {
                    let name = self.doc.movie.as_ref().map_or(String::new(), |m| {
                        let stem = m.movie.path().file_stem().unwrap_or_default();
                        format!("{}_RES", stem.to_string_lossy())
                    });
                    self.prompt_path(super::PathPurpose::ExportCtc, name)
                }
            },
            _ => unreachable!("not a movie command: {c:?}"),
        }
    }

    /// Opens the movie at `path` as a new document on its first frame.
    fn open_movie(&mut self, path: &Path) {
        match Movie::open(path) {
            Ok(m) => self.show_movie(m),
            Err(e) => self.status.error = Some(super::AppError::Movie(e.to_string())),
        }
    }

    /// `movie`, opened, as a new document on its first frame.
    pub(super) fn show_movie(&mut self, movie: Movie) {
        self.view.movie_playing = false;
        let path = movie.path().to_path_buf();
        let path = path.as_path();
        let first = match self.view.frames.get(&movie, 0) {
            Ok(f) => f,
            Err(e) => {
                self.status.error = Some(super::AppError::Movie(e));
                return;
            }
        };
        self.reset_run();
        self.jobs.track = None;
        let name = crate::io::folder::file_name(path);
        let mut doc = Document::of_image((*first).clone(), name.clone());
        doc.image = Some(first);
        let bright = doc.params().polarity == crate::evolution::Polarity::Bright;
        self.status.notify(format!(
            "{name}: {} frames{}; draw seeds on frame 0 (or none: automatic seeds), then Track",
            movie.len(),
            if bright { BRIGHT_CHOSEN } else { "" }
        ));
        doc.movie = Some(MovieDoc {
            movie,
            frame: 0,
            tracking: None,
            correcting: None,
        });
        self.doc = doc;
        self.view.prefs.last_dir = path.parent().map(Path::to_path_buf);
        self.view.selected = None;
        self.view.selected_contour = None;
        self.view.selected_track = None;
    }

    /// Advances the playing movie a frame every [`MOVIE_FRAME_S`] seconds; stops at its
    /// last frame.
    pub(super) fn tick_movie(&mut self, dt: f64) {
        if !self.view.movie_playing {
            return;
        }
        let Some(m) = self.doc.movie.as_ref() else {
            self.view.movie_playing = false;
            return;
        };
        let (t, last) = (m.frame, m.movie.len() - 1);
        self.view.movie_clock += dt;
        if self.view.movie_clock < MOVIE_FRAME_S {
            return;
        }
        self.view.movie_clock = 0.0;
        self.show_movie_frame((t + 1).min(last));
        // It stops at the end, and where the frame could not be shown.
        let now = self.doc.movie.as_ref().map_or(t, |m| m.frame);
        self.view.movie_playing = now == t + 1 && now < last;
    }

    /// Shows frame `t` of the movie: its image (the shapes stay, the run starts again).
    fn show_movie_frame(&mut self, t: usize) {
        let Some(m) = self.doc.movie.as_ref() else {
            return;
        };
        let t = t.min(m.movie.len() - 1);
        if t == m.frame && self.doc.image.is_some() {
            return;
        }
        match self.view.frames.get(&m.movie, t) {
            Ok(f) => self.put_movie_frame(t, f),
            Err(e) => self.status.error = Some(super::AppError::Movie(e)),
        }
    }

    fn put_movie_frame(&mut self, t: usize, f: Arc<Field>) {
        if self.correction_waiting() {
            self.status.notify(
                "the correction of this frame is not in the tracking yet: answer the question first".into(),
            );
            return;
        }
        self.reset_run();
        if let Some(m) = self.doc.movie.as_mut() {
            m.frame = t;
            m.correcting = None;
        }
        // Each frame is stretched on its own quantiles, and a colony's halo grows: frame
        // 0's window showed a later frame's ground black. A window the user set stays.
        let auto = (self.doc.image.as_deref())
            .is_some_and(|was| self.doc.settings.contrast == super::auto_contrast(was));
        if auto {
            self.doc.settings.contrast = super::auto_contrast(&f);
        }
        self.doc.image = Some(f);
    }

    /// Track (again) from frame 0: asks first when that would replace corrections.
    fn track_again(&mut self, confirmed: bool) {
        let corrected: Vec<usize> = self
            .doc
            .movie
            .as_ref()
            .and_then(|m| m.tracking.as_ref())
            .map_or(Vec::new(), |t| t.corrected.iter().copied().collect());
        if !confirmed && !corrected.is_empty() {
            self.view.question = Some(super::Question::TrackAgain(corrected));
            return;
        }
        self.view.question = None;
        if self.doc.movie.is_some() && self.jobs.track.is_none() {
            // Undo brings the tracking before back (tracking is started here, not by
            // `apply_now`, so a question asked is no undo step).
            self.history.push(self.doc.clone());
        }
        self.start_tracking();
    }

    /// Starts tracking the movie from frame 0 with the shapes on screen (none: automatic
    /// seeds) and the run's parameters under the tracking engine.
    fn start_tracking(&mut self) {
        let Some(m) = &self.doc.movie else {
            self.status
                .notify("open a movie first (Movie > Open movie…)".into());
            return;
        };
        if self.jobs.track.is_some() {
            self.status.notify("tracking is already running".into());
            return;
        }
        let init = self.doc.shapes.clone();
        let mut settings = TrackSettings::new(self.doc.params().clone());
        settings.auto_seeds = init.is_empty();
        let tracking = Tracking {
            id: next_tracking_id(),
            settings: Some(settings.clone()),
            running: true,
            ..Tracking::default()
        };
        let id = tracking.id;
        let total = m.movie.len();
        if let Some(m) = self.doc.movie.as_mut() {
            m.tracking = Some(tracking);
            m.correcting = None;
        }
        if self.doc.run.is_some() && self.doc.movie.as_ref().is_some_and(|m| m.frame != 0) {
            self.reset_run();
        }
        self.spawn_tracking(Tracker::new(settings, init), 0, id);
        self.status.notify(format!("tracking {total} frames…"));
    }

    /// Tracks on from the last frame tracked (after Cancel, or Undo back to a result
    /// that was still being tracked).
    fn continue_tracking(&mut self) {
        if self.jobs.track.is_some() {
            self.status.notify("tracking is already running".into());
            return;
        }
        let Some(m) = self.doc.movie.as_mut() else {
            return;
        };
        let (w, h) = m.movie.size();
        let Some(tr) = m.tracking.as_mut() else {
            return self.start_tracking();
        };
        let (Some(last), Some(settings)) = (tr.frames.last().cloned(), tr.settings.clone()) else {
            return self.start_tracking();
        };
        if last.frame + 1 >= m.movie.len() {
            tr.complete = true;
            tr.running = false;
            return;
        }
        tr.running = true;
        let (id, from) = (tr.id, last.frame + 1);
        // The stopped tracker goes on as if never stopped; without one (Undo back to a
        // result still being tracked, a partial tracking reopened from its session) it
        // resumes from the last frame's contours.
        let tracker = match tr.stopped.take().filter(|t| t.next_frame() == from) {
            Some(t) => Arc::unwrap_or_clone(t),
            None => {
                let memory = tr.memory.get(&last.frame).map(|m| Memory::clone(m));
                let t = Tracker::resume(settings.clone(), tr.lineage.clone(), &last, w, h, memory);
                match &tr.replaced {
                    Some(r) => r.numbering(t),
                    None => t,
                }
            }
        };
        let changed = TrackSettings::new(self.doc.params().clone()).params != settings.params;
        self.spawn_tracking(tracker, from, id);
        self.status.notify(if changed {
            format!("tracking on from frame {from} with the settings it started with (Track again uses the new ones)…")
        } else {
            format!("tracking on from frame {from}…")
        });
    }

    /// Tracks the movie's frames from `from` on with `tracker` on a thread, into the
    /// result `id`.
    pub(super) fn spawn_tracking(&mut self, mut tracker: Tracker, from: usize, id: u64) {
        self.stop_tracking();
        let Some(m) = &self.doc.movie else { return };
        let movie = m.movie.clone();
        let total = movie.len() - from.min(movie.len());
        let cancel = Arc::new(AtomicBool::new(false));
        let (tx, rx) = channel();
        let (stop, ctx) = (cancel.clone(), self.view.egui_ctx.clone());
        let handle = std::thread::spawn(move || {
            let wake = || {
                if let Some(c) = &ctx {
                    c.request_repaint();
                }
            };
            let frames = match movie.frames() {
                Ok(f) => f,
                Err(e) => return drop(tx.send(Message::Failed(e.to_string()))),
            };
            // The frame before `from` tells how far the field moves into it.
            let mut frames = frames.skip(from.saturating_sub(1));
            if from > 0 {
                if let Some(Ok(before)) = frames.next() {
                    tracker.set_previous(before);
                }
            }
            for image in frames {
                if stop.load(Ordering::SeqCst) {
                    let _ = tx.send(Message::Stopped(Box::new(tracker)));
                    return wake();
                }
                let step = image
                    .map_err(|e| e.to_string())
                    .and_then(|img| Ok((tracker.step(&img).map_err(|e| e.to_string())?, img)));
                let msg = match step {
                    Ok((f, img)) => Message::Frame(
                        Arc::new(f),
                        tracker.lineage().clone(),
                        Arc::new(img),
                        Arc::new(tracker.memory()),
                    ),
                    Err(e) => Message::Failed(e),
                };
                let failed = matches!(msg, Message::Failed(_));
                if tx.send(msg).is_err() || failed {
                    break;
                }
                wake();
            }
            wake();
        });
        self.jobs.track = Some(TrackJob {
            total,
            done: 0,
            tracking: id,
            cancel,
            rx,
            handle: Some(handle),
        });
        self.view.follow_tracking = from == 0;
    }

    /// Stops the tracking job (its thread ends after the frame in progress; what it
    /// sends after is dropped).
    pub(super) fn stop_tracking(&mut self) {
        if let Some(j) = self.jobs.track.take() {
            j.cancel.store(true, Ordering::SeqCst);
        }
    }

    /// Takes the frames the tracking thread sent; ends the job when the thread ended.
    pub(super) fn poll_tracking(&mut self) {
        let Some(job) = self.jobs.track.as_mut() else {
            return;
        };
        // Looked at before draining: once the thread has ended, the drain gets all it sent.
        let finished = job.handle.as_ref().is_none_or(|h| h.is_finished());
        let (mut newest, mut failure) = (None, None);
        while let Ok(msg) = job.rx.try_recv() {
            match msg {
                Message::Frame(f, lineage, image, memory) => {
                    job.done += 1;
                    let t = f.frame;
                    self.view.frames.put(t, image.clone());
                    let p = self.doc.params();
                    let generic_dark =
                        (p.polarity, p.modality) == (Polarity::Dark, Modality::Generic);
                    if let Some(tr) = tracking_with(&mut self.doc, job.tracking) {
                        // A hint of this frame or a later one was of frames tracked
                        // again now (after a correction).
                        if tr.hint.as_ref().is_some_and(|(at, _)| *at >= t) {
                            tr.hint = None;
                        }
                        if t == 0 && generic_dark {
                            let labels = f.label_raster(image.width, image.height);
                            tr.hint = crate::image::modality::looks_haloed(&image, &labels).then(|| {
                                (0, "the cells wear a bright halo, as in phase contrast: choose image: phase-contrast and Track again".into())
                            });
                        }
                        // Cells over most of a frame: the background cut into cells.
                        let covered = f.covered(image.width, image.height);
                        if tr.hint.is_none() && covered > crate::track::CROWDED_SHARE {
                            tr.hint = Some((
                                t,
                                crate::track::crowded_note(
                                    t,
                                    covered,
                                    "Dark/Bright objects and the image kind (phase contrast?)",
                                ),
                            ));
                        }
                        tr.frames.truncate(t);
                        tr.memory.retain(|&k, _| k < t);
                        tr.memory.insert(t, memory);
                        // This frame may revise the one before (a division taken back or
                        // dated there).
                        if let Some(before) = tr
                            .frames
                            .last_mut()
                            .filter(|_| !(f.undone.is_empty() && f.earlier.is_empty()))
                        {
                            Arc::make_mut(before).revise(&f);
                        }
                        tr.frames.push(f);
                        tr.lineage = lineage;
                    }
                    newest = Some((t, image));
                }
                Message::Failed(e) => failure = Some(e),
                Message::Stopped(tracker) => {
                    if let Some(tr) = tracking_with(&mut self.doc, job.tracking) {
                        tr.stopped = Some(Arc::new(*tracker));
                    }
                }
            }
        }
        let (done, total) = (job.done, job.total);
        if finished {
            if let Some(h) = job.handle.take() {
                let _ = h.join();
            }
            let id = job.tracking;
            self.jobs.track = None;
            let movie = self.doc.movie.as_mut();
            let len = movie.as_ref().map_or(0, |m| m.movie.len());
            let tr = movie
                .and_then(|m| m.tracking.as_mut())
                .filter(|tr| tr.id == id);
            if let Some(tr) = tr {
                tr.complete = tr.frames.len() == len;
                tr.running = false;
            }
            self.status.notify(self.tracking_summary(done, total));
        }
        if let Some(e) = failure {
            self.status.error = Some(super::AppError::Movie(e));
        }
        if let Some((t, image)) = newest.filter(|_| self.view.follow_tracking) {
            if self.doc.movie.is_some() {
                self.put_movie_frame(t, image);
            }
        }
    }

    /// The status line of the tracking on screen (`done` of `total` frames without one).
    pub(super) fn tracking_summary(&self, done: usize, total: usize) -> String {
        let m = self.doc.movie.as_ref();
        let Some((tr, len)) = m.and_then(|m| m.tracking.as_ref().map(|t| (t, m.movie.len())))
        else {
            return format!("tracked {done} of {total} frames");
        };
        let divisions = tr.divisions().count();
        let n = tr.frames.len();
        let stopped = if n < len { " (stopped)" } else { "" };
        let tracks = tr.lineage.tracks().len();
        let s = |n: usize| if n == 1 { "" } else { "s" };
        let hint = tr
            .hint
            .as_ref()
            .map_or(String::new(), |(_, h)| format!("; {h}"));
        format!(
            "tracked {n} of {len} frames{stopped}: {tracks} track{}, {divisions} division{}{hint}",
            s(tracks),
            s(divisions)
        )
    }

    /// Writes `DIR/maskTTT.tif` per tracked frame and `DIR/res_track.txt`; the number of
    /// masks.
    fn export_ctc(&self, dir: &Path) -> Result<usize, super::AppError> {
        let tr = self
            .doc
            .movie
            .as_ref()
            .and_then(|m| m.tracking.as_ref().map(|t| (m, t)))
            .filter(|(_, t)| !t.frames.is_empty());
        let Some((m, tr)) = tr else {
            return Err(super::AppError::Movie(
                "nothing to export yet: Track first".into(),
            ));
        };
        if dir.exists() && !dir.is_dir() {
            return Err(super::AppError::Movie(format!(
                "{}: not a folder (the result is a folder of masks)",
                dir.display()
            )));
        }
        let io = |source| super::AppError::Io {
            path: dir.to_path_buf(),
            source,
        };
        std::fs::create_dir_all(dir).map_err(io)?;
        let mut written = Vec::with_capacity(tr.frames.len());
        // The frames read in order, each once: a mask climbs its frame's edges.
        let mut images = m
            .movie
            .frames()
            .map_err(|e| super::AppError::Movie(e.to_string()))?
            .enumerate();
        for f in &tr.frames {
            let image = images
                .find(|(t, _)| *t == f.frame)
                .ok_or_else(|| {
                    super::AppError::Movie(format!("{} has no frame {}", m.movie.name(), f.frame))
                })?
                .1
                .map_err(|e| super::AppError::Movie(e.to_string()))?;
            let bytes = track_labels(f, &image, true)?;
            let name = ctc::mask_name(f.frame, m.movie.len());
            crate::io::write_atomic(&dir.join(&name), &bytes)?;
            written.push(name);
        }
        crate::io::write_atomic(&dir.join("res_track.txt"), tr.lineage.ctc_text().as_bytes())?;
        ctc::remove_stale_masks(dir, &written).map_err(io)?;
        Ok(tr.frames.len())
    }

    /// Writes the movie's session: its tracking as it is (a correction still waiting for
    /// its question is not in it: refused until answered).
    pub(super) fn save_tracking_session(&self, path: &Path) -> Result<(), super::AppError> {
        use crate::io::tracking_session::{
            MovieRef, TrackingSession, TRACKING_FORMAT, TRACKING_VERSION,
        };
        if self.correction_waiting() {
            return Err(super::AppError::Movie(
                "the correction of this frame is not in the tracking yet: answer the question first".into(),
            ));
        }
        let m = self.doc.movie.as_ref().expect("a movie document");
        let tr = m.tracking.as_ref();
        let (width, height) = m.movie.size();
        let s = TrackingSession {
            format: TRACKING_FORMAT.into(),
            version: TRACKING_VERSION,
            movie: MovieRef {
                path: m
                    .movie
                    .path()
                    .canonicalize()
                    .map_err(|source| super::AppError::Io {
                        path: m.movie.path().to_path_buf(),
                        source,
                    })?,
                frames: m.movie.len(),
                width,
                height,
            },
            shown: m.frame,
            shapes: self.doc.shapes.clone(),
            params: self.doc.params().clone(),
            settings: tr.and_then(|t| t.settings.clone()),
            frames: tr.map_or(Vec::new(), |t| {
                t.frames.iter().map(|f| (**f).clone()).collect()
            }),
            tracks: tr.map_or(Vec::new(), |t| t.lineage.tracks().to_vec()),
            corrected: tr.map_or(Vec::new(), |t| t.corrected.iter().copied().collect()),
            unwanted: (tr.and_then(|t| t.memory.get(&t.frames.len().checked_sub(1)?)))
                .map_or(Vec::new(), |m| m.unwanted().to_vec()),
        };
        let json = s.to_json(path).map_err(super::AppError::Movie)?;
        write_beside(&m.movie, path, json.into_bytes())
    }

    /// Whether a movie's session leaves out work on screen: a frame's own run edited by
    /// hand (not a tracked frame's correction, which is in the tracking), or strokes.
    pub(super) fn movie_session_leaves_out(&self) -> bool {
        let Some(m) = &self.doc.movie else {
            return false;
        };
        let edited = self
            .doc
            .run
            .as_ref()
            .is_some_and(|r| !r.edits().is_empty() && m.correcting.is_none());
        edited || self.doc.train.painted()
    }

    /// Opens a movie's session: the movie, its frame-0 shapes and settings, and its
    /// tracking as it was saved (Continue tracking goes on from a partial one).
    pub(super) fn open_tracking_session(&mut self, t: crate::io::tracking_session::OpenedTracking) {
        let s = t.session;
        self.show_movie(t.movie);
        if self.status.error.is_some() {
            return;
        }
        self.doc.shapes = s.shapes;
        self.doc.settings.params = s.params;
        self.doc.settings.mode_chosen = true;
        let Some(m) = self.doc.movie.as_mut() else {
            return;
        };
        if s.settings.is_some() {
            // Where cells were deleted is saved as it lay after the last frame; it holds
            // for the frames from the last correction on, every deletion made by then (a
            // drifting stage's shift since aside).
            let mut memory = HashMap::new();
            if !s.unwanted.is_empty() {
                let from = s.corrected.iter().max().copied().unwrap_or(0);
                let m = Arc::new(Memory::with_unwanted(s.unwanted));
                memory.extend((from..s.frames.len()).map(|t| (t, m.clone())));
            }
            m.tracking = Some(Tracking {
                id: next_tracking_id(),
                complete: s.frames.len() == m.movie.len(),
                frames: s.frames.into_iter().map(Arc::new).collect(),
                lineage: t.lineage,
                settings: s.settings,
                corrected: s.corrected.into_iter().collect(),
                running: false,
                stopped: None,
                replaced: None,
                memory,
                hint: None,
            });
            // Not "draw seeds on frame 0", as a movie just opened: it is tracked.
            let len = m.movie.len();
            let done = m.tracking.as_ref().map_or(0, |t| t.frames.len());
            let summary = self.tracking_summary(done, len);
            let more = if done < len {
                "; Continue tracking goes on"
            } else {
                ""
            };
            self.status
                .notify(format!("session opened: {summary}{more}"));
        }
        self.show_movie_frame(s.shown);
        self.unsaved = false;
    }

    /// On a tracked frame (no run on screen), what Export writes: Measurements CSV the
    /// tracks' rows of every frame tracked (as `track --tracks-csv`), a label image the
    /// frame's cells by track number (as its CTC mask). None when not a tracked frame.
    pub(super) fn tracked_export(
        &self,
        format: crate::io::Format,
        path: &Path,
    ) -> Result<Option<Vec<u8>>, super::AppError> {
        let Some(m) = &self.doc.movie else {
            return Ok(None);
        };
        let (Some(f), Some(tr)) = (m.tracked_frame(), m.tracking.as_ref()) else {
            return Ok(None);
        };
        match format {
            crate::io::Format::Csv => {
                // By the masks, as the label images give the cells: each frame's image
                // is read again for the cells' edges.
                let mut csv = String::from(ctc::CSV_HEADER);
                let frames = m.movie.frames().map_err(|e| super::AppError::Movie(e.to_string()))?;
                for (f, image) in tr.frames.iter().zip(frames) {
                    let image = image.map_err(|e| super::AppError::Movie(e.to_string()))?;
                    let labels = tracked_mask(f, &image);
                    csv.push_str(&ctc::csv_rows(f.frame, &labels, image.width, &tr.lineage));
                }
                Ok(Some(csv.into_bytes()))
            }
            crate::io::Format::Labels => {
                format.check_name(path)?;
                let image = m
                    .movie
                    .frames()
                    .map_err(|e| super::AppError::Movie(e.to_string()))?
                    .nth(f.frame)
                    .ok_or_else(|| super::AppError::Movie(format!("{} has no frame {}", m.movie.name(), f.frame)))?
                    .map_err(|e| super::AppError::Movie(e.to_string()))?;
                Ok(Some(track_labels(f, &image, crate::io::export::is_tiff(path))?))
            }
            _ => Err(super::AppError::Movie(format!(
                "a tracked frame exports as Measurements CSV (every frame's cells by track) or a label image (this frame's cells by track); {} needs the frame's run: Edit it or Step",
                format.name()
            ))),
        }
    }
}

/// The cells of `f` as a 16-bit label image by track number (TIFF or PNG), as `track
/// --ctc` writes its masks: up to the edges of `image`, the frame's
/// ([`crate::image::widen::to_edges`]).
fn track_labels(f: &TrackedFrame, image: &Field, tiff: bool) -> Result<Vec<u8>, super::AppError> {
    ctc::label_image(&tracked_mask(f, image), image.width, image.height, tiff)
        .ok_or_else(|| super::AppError::Movie("more than 65,535 tracks".into()))
}

/// The cells of `f` as the mask `track --ctc` writes: track labels up to the edges of
/// `image`, the frame's.
fn tracked_mask(f: &TrackedFrame, image: &Field) -> Vec<u32> {
    crate::image::widen::to_edges(&f.label_raster(image.width, image.height), image)
}

/// The tracking result `id` of `doc`, if it is still the one on screen.
fn tracking_with(doc: &mut Document, id: u64) -> Option<&mut Tracking> {
    doc.movie
        .as_mut()
        .and_then(|m| m.tracking.as_mut())
        .filter(|tr| tr.id == id)
}

/// Writes `bytes` to `path` atomically, never over one of `movie`'s files.
pub(super) fn write_beside(
    movie: &Movie,
    path: &Path,
    bytes: Vec<u8>,
) -> Result<(), super::AppError> {
    let inputs: Vec<_> = movie
        .files()
        .into_iter()
        .map(|p| (p, "movie frame"))
        .collect();
    crate::io::OutputFiles::prepare_for(&inputs, &[path])?.commit(vec![bytes])?;
    Ok(())
}
