//! Playing, stepping and seeking: runs are started (large images are prepared on a
//! background thread), frames are shown from the recording or computed, and in adaptive
//! mode the first merge of two seeds' contours says how to keep them apart.

use super::{AppError, Command, Run, TopoApp};
use crate::evolution::{Evolver, Mode, Params};
use crate::topology::TopologyEvent;

/// Images with more pixels than this are prepared on a background thread.
pub const PREPARE_IN_BACKGROUND: usize = 2_000_000;

/// An evolver as prepared, or why it could not start.
type Prepared = Result<Evolver, crate::evolution::EvolveError>;

/// A run being prepared on a background thread, and what was asked meanwhile.
pub struct Preparing {
    handle: std::thread::JoinHandle<(Prepared, Option<Prepared>)>,
    /// Frames to step once ready.
    steps: usize,
    /// Play once ready.
    play: bool,
}

impl TopoApp {
    /// Drops the runs on screen (and one being prepared: its thread ends on its own).
    pub(super) fn reset_run(&mut self) {
        self.jobs.preparing = None;
        self.doc.drop_runs();
        self.view.playing = false;
        if let Some(m) = self.doc.movie.as_mut() {
            m.correcting = None;
        }
    }

    /// Starts a run from the current shapes if there is none; false while it is being
    /// prepared or when it cannot start.
    pub(super) fn ensure_run(&mut self) -> bool {
        if self.doc.run.is_some() {
            return true;
        }
        if self.jobs.preparing.is_some() {
            return false;
        }
        let Some(image) = self.doc.image.clone() else {
            self.status.error = Some(AppError::NoImage);
            return false;
        };
        // A taught run is made as a taught job makes it (the guide's evolver), from the
        // shapes a taught job starts from.
        let guide = self.guide_for_run();
        let shapes = match &guide {
            Some(g) => crate::learn::guide::taught_shapes(&self.doc.shapes, g),
            None => self.doc.shapes.clone(),
        };
        let params = self.doc.params().clone();
        let compare = self.doc.settings.compare;
        let large = image.width * image.height > PREPARE_IN_BACKGROUND;
        let build = move || {
            let start = |mode| match &guide {
                Some(g) => g.evolver(image.clone(), &shapes, mode),
                None => {
                    let p = Params {
                        mode,
                        ..params.clone()
                    };
                    Evolver::new(&image, &shapes, p)
                }
            };
            (start(params.mode), compare.map(start))
        };
        if large {
            // The pyramid and local statistics of a large image take seconds: the
            // window stays responsive, and what was asked meanwhile happens after.
            self.jobs.preparing = Some(Preparing {
                handle: std::thread::spawn(build),
                steps: 0,
                play: false,
            });
            self.status
                .notify("preparing the image (pyramid and local statistics)…".into());
            return false;
        }
        let (first, second) = build();
        self.install_run(first, second)
    }

    /// Makes a prepared evolver (and the side-by-side one) the run on screen.
    fn install_run(&mut self, first: Prepared, second: Option<Prepared>) -> bool {
        match first {
            Ok(ev) => {
                self.doc.run = Some(Run::new(ev));
                self.doc.run_b = second.and_then(Result::ok).map(Run::new);
                self.doc.shown = 0;
                true
            }
            Err(e) => {
                self.status.error = Some(e.into());
                self.view.playing = false;
                false
            }
        }
    }

    /// Takes a run prepared in the background, then does what was asked meanwhile.
    pub(super) fn poll_preparing(&mut self, ctx: &egui::Context) {
        let Some(p) = &self.jobs.preparing else {
            return;
        };
        if !p.handle.is_finished() {
            ctx.request_repaint_after(std::time::Duration::from_millis(50));
            return;
        }
        let p = self.jobs.preparing.take().expect("checked");
        let Ok((first, second)) = p.handle.join() else {
            self.status.notify("preparing the image failed".into());
            return;
        };
        if self.install_run(first, second) {
            self.status.notice = None;
            if p.steps > 0 {
                self.step_frames(p.steps);
            }
            self.view.playing |= p.play;
        }
    }

    /// Shows `n` more frames from the frame on screen: recorded ones as they are (with
    /// every edit made in them), then new ones computed.
    pub(super) fn step_frames(&mut self, n: usize) {
        if !self.ensure_run() {
            if let Some(p) = self.jobs.preparing.as_mut() {
                p.steps += n;
            }
            return;
        }
        let t = std::time::Instant::now();
        for _ in 0..n {
            if !self.doc.advance() {
                self.view.playing = false;
                break;
            }
            self.merge_hint();
        }
        self.status.step_ms = t.elapsed().as_secs_f64() * 1e3 / n.max(1) as f64;
    }

    /// In adaptive mode, the first merge of two seeds' contours says (once) how to keep
    /// touching objects apart.
    fn merge_hint(&mut self) {
        if self.status.merge_hint_given
            || self.doc.params().mode != Mode::Adaptive
            || self.doc.shapes.len() < 2
        {
            return;
        }
        let Some(rec) = self.doc.shown_record() else {
            return;
        };
        if rec
            .events
            .iter()
            .any(|e| matches!(e, TopologyEvent::Merge { .. }))
        {
            self.status.notify(format!(
                "frame {}: two seeds merged into one object; Preserve keeps touching objects apart",
                rec.index
            ));
            self.status.merge_hint_given = true;
        }
    }

    /// Advances playback by the time since the last frame.
    pub(super) fn tick(&mut self, dt: f64) {
        if !self.view.playing {
            return;
        }
        let view = &mut self.view;
        view.play_clock += dt * view.prefs.speed as f64;
        let n = (view.play_clock.floor() as usize).clamp(1, 50);
        view.play_clock = (view.play_clock - n as f64).max(0.0);
        // At most a tenth of a second of frames per repaint: large images play slower
        // instead of freezing the window.
        let t = std::time::Instant::now();
        for _ in 0..n {
            self.step_frames(1);
            if !self.view.playing || t.elapsed() > std::time::Duration::from_millis(100) {
                self.view.play_clock = 0.0;
                break;
            }
        }
    }

    /// Playing, stepping and seeking.
    pub(super) fn playback(&mut self, c: Command) {
        let correcting = self
            .doc
            .movie
            .as_ref()
            .is_some_and(|m| m.correcting.is_some());
        if correcting && matches!(c, Command::Play | Command::Step(_) | Command::StepToEvent) {
            self.status.notify(
                "this tracked frame's contours are open for correction (Edit, Brush); Track again re-runs the evolution"
                    .into(),
            );
            return;
        }
        match c {
            Command::Play => {
                self.view.movie_playing = false;
                if self.ensure_run() {
                    self.view.playing = true;
                } else if let Some(p) = self.jobs.preparing.as_mut() {
                    p.play = true;
                }
            }
            Command::Pause => self.view.playing = false,
            Command::Step(n) => self.step_frames(n),
            Command::StepToEvent => {
                for _ in 0..5000 {
                    let before = self.doc.shown;
                    self.step_frames(1);
                    let stuck = self.doc.run.is_none() || self.doc.shown == before;
                    if stuck
                        || self
                            .doc
                            .shown_record()
                            .is_some_and(|r| !r.events.is_empty())
                    {
                        break;
                    }
                }
            }
            Command::Reset => self.reset_run(),
            Command::SeekFrame(n) => {
                if self.doc.run.is_some() {
                    self.doc.shown = n.min(self.doc.last_frame());
                    self.view.playing = false;
                }
            }
            _ => unreachable!("not a playback command: {c:?}"),
        }
    }
}
