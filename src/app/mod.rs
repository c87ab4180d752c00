//! The desktop app (DESIGN layer 6), as egui's demo and rerun structure theirs: the
//! [`Document`] (what Undo restores and a session saves), the [`ViewState`] (how it is
//! looked at), background jobs and the [`Status`] bar. Views read the document and send
//! [`Command`]s; [`TopoApp::apply`] applies them in one place at the end of the frame.
//! The engine does all geometry; this module only draws it and turns input into commands.

mod apply;
mod canvas;
mod command;
mod correct;
mod document;
mod files;
mod fill;
mod folder;
mod hand;
mod history;
mod keys;
mod movie;
mod objects;
mod panels;
mod path_prompt;
mod playback;
mod run;
mod train;
mod train_run;
mod view;

pub use crate::io::export::Format;
pub use command::{Command, Gesture, Group, Tool, UndoKey};
pub use document::{Document, ImageStack, Settings};
pub use files::AppError;
pub use folder::FolderRun;
pub use movie::{MovieDoc, TrackJob, Tracking};
pub use path_prompt::{PathPrompt, PathPurpose};
pub use playback::{Preparing, PREPARE_IN_BACKGROUND};
pub use run::{FrameRecord, RingView, Run};
pub use train::{Map, Trainer, Training};
pub use view::{Prefs, Question, Status, ViewState, BRUSH_RADIUS};

use crate::evolution::Field;
use crate::geometry::Point;
use std::path::PathBuf;

/// The bundled sample shown on first start.
pub const SAMPLE_PNG: &[u8] = include_bytes!("../../assets/cells.png");

/// The whole app.
#[derive(Default)]
pub struct TopoApp {
    /// What the user makes; changed only by commands.
    pub doc: Document,
    /// How it is looked at.
    pub view: ViewState,
    /// Work running in the background.
    pub jobs: Jobs,
    /// The status bar.
    pub status: Status,
    /// Commands queued this frame, applied at its end.
    commands: Vec<Command>,
    /// Undo and redo steps.
    history: history::History,
    /// The document changed since it was last saved (a session; a movie's CTC export).
    unsaved: bool,
}

/// Work running in the background.
#[derive(Default)]
pub struct Jobs {
    /// A folder being segmented ("Apply to folder…").
    pub folder: Option<FolderRun>,
    /// A run being prepared (large images).
    pub preparing: Option<Preparing>,
    /// A movie being tracked.
    pub track: Option<TrackJob>,
    /// The probability map of the training strokes, made in the background.
    pub trainer: train::Trainer,
}

/// What a view reads and where it sends its commands: the document only to read.
struct Ctx<'a> {
    pub doc: &'a Document,
    pub view: &'a mut ViewState,
    pub status: &'a Status,
    pub jobs: &'a Jobs,
    /// Whether Undo and Redo have something to do.
    pub can_undo_redo: (bool, bool),
    commands: &'a mut Vec<Command>,
}

impl Ctx<'_> {
    /// Queues a command for this frame's [`TopoApp::apply`].
    pub fn send(&mut self, c: Command) {
        self.commands.push(c);
    }
}

impl TopoApp {
    /// The app with the bundled sample loaded and a wrap rectangle ready.
    pub fn with_sample() -> Self {
        let mut app = TopoApp::default();
        let field =
            crate::io::decode_image(SAMPLE_PNG, "cells.png").expect("bundled sample decodes");
        app.doc = Document::of_image(field, "cells.png (sample)".into());
        app.apply_now(Command::WrapBorder(6.0));
        app.doc.sample_wrap = true;
        app.unsaved = false; // the sample's own wrap is no work of the user's
        app
    }

    /// The app with preferences restored and `image` opened (or the sample).
    pub fn new(prefs: Option<Prefs>, image: Option<PathBuf>) -> Self {
        let mut app = TopoApp::with_sample();
        if let Some(p) = prefs {
            app.view.prefs = p;
        }
        if let Some(p) = image {
            // A session saved from the app is opened as one: its image, shapes, run or
            // tracking.
            let session = p
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("json"));
            app.apply_now(if session {
                Command::OpenSession(p)
            } else {
                Command::OpenImage(p)
            });
        }
        app
    }

    /// Queues a command for this frame's [`TopoApp::apply`].
    pub fn send(&mut self, c: Command) {
        self.commands.push(c);
    }

    /// Applies every queued command.
    pub fn apply(&mut self) {
        let cmds = std::mem::take(&mut self.commands);
        for c in cmds {
            self.apply_now(c);
        }
    }

    /// The record on screen, if a run exists.
    pub fn shown_record(&self) -> Option<&FrameRecord> {
        self.doc.shown_record()
    }

    /// Whether Undo and Redo have something to do.
    pub fn can_undo_redo(&self) -> (bool, bool) {
        self.history.can()
    }

    /// Where image point `p` is on the canvas (as of the last frame drawn).
    pub fn screen_from_image(&self, p: Point) -> egui::Pos2 {
        self.view.canvas.screen_from_image(p)
    }

    /// The window title.
    pub fn title(&self) -> String {
        if let Some(m) = &self.doc.movie {
            return format!(
                "topocontour — {} — movie frame {} of {}",
                self.doc.image_name,
                m.frame,
                m.movie.len()
            );
        }
        match &self.doc.run {
            Some(r) => format!(
                "topocontour — {} — frame {}",
                self.doc.image_name,
                self.doc.shown.min(r.last())
            ),
            None => format!("topocontour — {}", self.doc.image_name),
        }
    }

    /// The whole app in a `Ui` (the eframe window's, or a test harness's).
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let dt = ui.input(|i| i.stable_dt) as f64;
        let ctx = ui.ctx().clone();
        // The title only when it changes: a viewport command repaints, and one every frame
        // kept the idle app drawing (a third of a core).
        let title = self.title();
        if title != self.view.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.view.title = title;
        }
        self.poll_folder(&ctx);
        self.poll_preparing(&ctx);
        if self.view.egui_ctx.is_none() {
            self.view.egui_ctx = Some(ctx.clone());
        }
        self.guard_close(&ctx);
        self.poll_tracking();
        self.poll_map();
        self.begin_correction();
        let mut cx = Ctx {
            doc: &self.doc,
            view: &mut self.view,
            status: &self.status,
            jobs: &self.jobs,
            can_undo_redo: self.history.can(),
            commands: &mut self.commands,
        };
        keys::keyboard(&mut cx, ui);
        keys::help_ui(&mut cx, &ctx);
        path_prompt::path_prompt_ui(&mut cx, &ctx);
        panels::question_ui(&mut cx, &ctx);
        panels::top_bar(&mut cx, ui);
        panels::bottom_bar(&mut cx, ui);
        panels::side_panel(&mut cx, ui);
        let t = std::time::Instant::now();
        egui::CentralPanel::default().show(ui, |ui| canvas::canvas_ui(&mut cx, ui));
        self.status.draw_ms = t.elapsed().as_secs_f64() * 1e3;
        self.apply();
        self.poll_correction(ctx.input(|i| i.pointer.any_down()));
        self.request_map();
        self.tick(dt);
        self.tick_movie(dt);
        if self.view.playing || self.view.movie_playing {
            ctx.request_repaint();
        }
    }
}

/// The contrast window of an image: its 0.5th and 99.5th percentiles (a sample of at most
/// a million pixels), at least 1/255 apart.
pub fn auto_contrast(f: &Field) -> (f32, f32) {
    let step = (f.data.len() / 1_000_000).max(1);
    let mut v: Vec<f32> = f.data.iter().step_by(step).copied().collect();
    let n = v.len();
    let at = |v: &mut Vec<f32>, q: f64| {
        let k = ((n - 1) as f64 * q).round() as usize;
        *v.select_nth_unstable_by(k, f32::total_cmp).1
    };
    let (lo, hi) = (at(&mut v, 0.005), at(&mut v, 0.995));
    if hi - lo < 1.0 / 255.0 {
        ((lo - 0.5 / 255.0).max(0.0), (hi + 0.5 / 255.0).min(1.0))
    } else {
        (lo, hi)
    }
}

/// The eframe wrapper: persistence.
struct EframeApp {
    app: TopoApp,
}

/// The storage key of [`Prefs`].
const PREFS_KEY: &str = "prefs";

impl eframe::App for EframeApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.app.ui(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, PREFS_KEY, &self.app.view.prefs);
    }
}

/// Opens the desktop window (on `image`, or the bundled sample).
pub fn run_app(image: Option<PathBuf>) -> Result<(), String> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 820.0])
            .with_title("topocontour"),
        ..Default::default()
    };
    eframe::run_native(
        "topocontour",
        options,
        Box::new(move |cc| {
            let prefs = cc
                .storage
                .and_then(|s| eframe::get_value::<Prefs>(s, PREFS_KEY));
            Ok(Box::new(EframeApp {
                app: TopoApp::new(prefs, image),
            }))
        }),
    )
    .map_err(|e| e.to_string())
}
