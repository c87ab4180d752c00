//! The desktop app (DESIGN layer 6): state structs, their `ui`, and a [`Command`] enum
//! applied once per frame. The engine does all geometry; this module only draws it and
//! turns input into commands.

mod canvas;
mod command;
mod files;
mod fill;
mod folder;
mod history;
mod keys;
mod objects;
mod panels;
mod path_prompt;
mod run;
mod settings;

pub use command::{Command, ExportKind, Tool};
pub use files::AppError;
pub use folder::FolderRun;
pub use path_prompt::{PathPrompt, PathPurpose};
pub use run::{FrameRecord, RingView, Run};
pub use settings::{auto_contrast, Settings};

use crate::evolution::{Evolver, Field, Params, Shape};
use crate::geometry::Point;
use crate::topology::TopologyEvent;
use std::path::PathBuf;
use std::sync::Arc;

/// The bundled sample shown on first start.
pub const SAMPLE_PNG: &[u8] = include_bytes!("../../assets/cells.png");

/// The whole app state.
pub struct TopoApp {
    /// The image's name as the title shows it.
    pub image_name: String,
    /// The file the image came from (none for the bundled sample): exports never replace it.
    pub image_path: Option<PathBuf>,
    /// The image.
    pub image: Option<Arc<Field>>,
    texture: Option<egui::TextureHandle>,
    texture_contrast: (f32, f32),
    /// The initialisation: the user's shapes.
    pub shapes: Vec<Shape>,
    /// The selected shape.
    pub selected: Option<usize>,
    /// The settings of the run and the view.
    pub settings: Settings,
    /// The run on screen.
    pub run: Option<Run>,
    /// The second engine's run in the side-by-side view (same frames as `run`).
    pub run_b: Option<Run>,
    /// The recorded frame on screen.
    pub shown: usize,
    /// Playback is running.
    pub playing: bool,
    play_clock: f64,
    /// The topology events so far, with their frame.
    pub log: Vec<(usize, TopologyEvent)>,
    /// The last error, shown in the status bar until the next one or a success.
    pub error: Option<AppError>,
    /// The last notice (what just happened), shown in the status bar.
    pub notice: Option<String>,
    /// Time of the last frame step, ms.
    pub step_ms: f64,
    /// Time spent drawing the canvas last frame, ms.
    pub draw_ms: f64,
    /// Commands queued this frame, applied at its end.
    pub commands: Vec<Command>,
    canvas: canvas::CanvasState,
    /// Undo and redo steps.
    history: history::History,
    /// The help window is open.
    pub show_help: bool,
    /// The contour selected with the Edit tool or in the object table (its measurements
    /// show in the status bar, its row in the table).
    pub selected_contour: Option<u32>,
    /// The object table's rows, measured once per frame shown.
    objects: objects::ObjectTable,
    /// The built-in path field, when a file dialog gave no path.
    pub path_prompt: Option<PathPrompt>,
    /// The page of a stack on screen, and the pixel size.
    pub stack: ImageStack,
    /// A folder being segmented in the background ("Apply to folder…").
    pub folder: Option<FolderRun>,
    /// A run being prepared in the background (large images).
    pub preparing: Option<Preparing>,
    /// The shapes are the sample's wrap rectangle, as it opened: labelled on the canvas,
    /// replaced by the first seed the user adds.
    pub sample_wrap: bool,
}

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

/// Where the image on screen sits in its file, and how large its pixels are.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImageStack {
    /// Pages in the file (1 for most images; a TIFF stack holds several).
    pub pages: usize,
    /// The page on screen (0-based).
    pub page: usize,
    /// The physical size of a pixel: from the file, or set by the user (exports give
    /// calibrated measurements with it).
    pub pixel: Option<crate::io::PixelSize>,
}

impl Default for TopoApp {
    fn default() -> Self {
        TopoApp {
            image_name: String::new(),
            image_path: None,
            image: None,
            texture: None,
            texture_contrast: (0.0, 1.0),
            shapes: Vec::new(),
            selected: None,
            settings: Settings::default(),
            run: None,
            run_b: None,
            shown: 0,
            playing: false,
            play_clock: 0.0,
            log: Vec::new(),
            error: None,
            notice: None,
            step_ms: 0.0,
            draw_ms: 0.0,
            commands: Vec::new(),
            canvas: canvas::CanvasState::default(),
            history: history::History::default(),
            show_help: false,
            selected_contour: None,
            objects: objects::ObjectTable::default(),
            path_prompt: None,
            stack: ImageStack::default(),
            folder: None,
            preparing: None,
            sample_wrap: false,
        }
    }
}

impl TopoApp {
    /// The app with the bundled sample loaded and a wrap rectangle ready.
    pub fn with_sample() -> Self {
        let mut app = TopoApp::default();
        let field =
            crate::io::decode_image(SAMPLE_PNG, "cells.png").expect("bundled sample decodes");
        app.set_image(field, "cells.png (sample)".into());
        app.stack.pages = 1;
        app.apply_now(Command::WrapBorder(6.0));
        app.sample_wrap = true;
        app
    }

    /// The app with settings restored and `image` opened (or the sample).
    pub fn new(settings: Option<Settings>, image: Option<PathBuf>) -> Self {
        let mut app = TopoApp::with_sample();
        if let Some(s) = settings {
            app.settings = s;
        }
        if let Some(p) = image {
            app.apply_now(Command::OpenImage(p));
        }
        app
    }

    fn set_image(&mut self, field: Field, name: String) {
        // Each image opens with its own contrast window: 16-bit data that fills 12 bits
        // would otherwise open black.
        self.settings.contrast = auto_contrast(&field);
        self.image = Some(Arc::new(field));
        self.image_path = None;
        self.image_name = name;
        self.texture = None;
        self.shapes.clear();
        self.selected = None;
        self.sample_wrap = false;
        self.reset_run();
    }

    fn reset_run(&mut self) {
        // A run still being prepared is for what was on screen: dropped (its thread ends
        // on its own).
        self.preparing = None;
        self.run = None;
        self.run_b = None;
        self.shown = 0;
        self.playing = false;
        self.log.clear();
    }

    /// The run's parameters from the settings.
    pub fn params(&self) -> Params {
        Params {
            polarity: self.settings.polarity,
            modality: self.settings.modality,
            open_holes: self.settings.open_holes,
            mode: self.settings.mode,
            broad_phase: self.settings.broad_phase,
            weights: self.settings.weights,
            step: self.settings.step,
            min_area: self.settings.min_area,
            ..Params::default()
        }
    }

    /// Starts a run from the current shapes if there is none.
    fn ensure_run(&mut self) -> bool {
        if self.run.is_some() {
            return true;
        }
        if self.preparing.is_some() {
            return false;
        }
        let Some(image) = self.image.clone() else {
            self.error = Some(AppError::NoImage);
            return false;
        };
        let (shapes, params, compare) = (self.shapes.clone(), self.params(), self.settings.compare);
        let large = image.width * image.height > PREPARE_IN_BACKGROUND;
        let build = move || {
            let second = compare.map(|mode| {
                let p = Params {
                    mode,
                    ..params.clone()
                };
                Evolver::new(&image, &shapes, p)
            });
            (Evolver::new(&image, &shapes, params), second)
        };
        if large {
            // The pyramid and local statistics of a large image take seconds: the
            // window stays responsive, and what was asked meanwhile happens after.
            self.preparing = Some(Preparing {
                handle: std::thread::spawn(build),
                steps: 0,
                play: false,
            });
            self.notice = Some("preparing the image (pyramid and local statistics)…".into());
            return false;
        }
        let (first, second) = build();
        self.install_run(first, second)
    }

    /// Makes a prepared evolver (and the side-by-side one) the run on screen.
    fn install_run(&mut self, first: Prepared, second: Option<Prepared>) -> bool {
        match first {
            Ok(ev) => {
                self.run = Some(Run::new(ev));
                self.run_b = second.and_then(Result::ok).map(Run::new);
                self.shown = 0;
                self.log.clear();
                true
            }
            Err(e) => {
                self.error = Some(e.into());
                self.playing = false;
                false
            }
        }
    }

    /// Takes a run prepared in the background, then does what was asked meanwhile.
    fn poll_preparing(&mut self, ctx: &egui::Context) {
        let Some(p) = &self.preparing else { return };
        if !p.handle.is_finished() {
            ctx.request_repaint_after(std::time::Duration::from_millis(50));
            return;
        }
        let p = self.preparing.take().expect("checked");
        let Ok((first, second)) = p.handle.join() else {
            self.notice = Some("preparing the image failed".into());
            return;
        };
        if self.install_run(first, second) {
            self.notice = None;
            if p.steps > 0 {
                self.step_frames(p.steps);
            }
            self.playing |= p.play;
        }
    }

    /// Advances `n` frames (from the frame on screen), recording each.
    fn step_frames(&mut self, n: usize) {
        if !self.ensure_run() {
            if let Some(p) = self.preparing.as_mut() {
                p.steps += n;
            }
            return;
        }
        let run = self.run.as_mut().expect("ensured");
        if self.shown != run.head() {
            run.rewind(self.shown.min(run.history.len() - 1));
            self.log.retain(|(f, _)| *f <= self.shown);
        }
        if let Some(b) = self.run_b.as_mut() {
            b.rewind(self.shown.min(b.history.len() - 1));
        }
        let t = std::time::Instant::now();
        for _ in 0..n {
            let b_done = self.run_b.as_ref().is_none_or(|b| b.evolver.is_finished());
            if run.evolver.is_finished() && b_done {
                self.playing = false;
                break;
            }
            if !run.evolver.is_finished() {
                let rec = run.step();
                for &e in &rec.events {
                    self.log.push((rec.index, e));
                }
            }
            if let Some(b) = self.run_b.as_mut().filter(|_| !b_done) {
                b.step();
            }
        }
        self.step_ms = t.elapsed().as_secs_f64() * 1e3 / n.max(1) as f64;
        // Both engines advance frame by frame; the screen shows the further one's frame.
        self.shown = run.head().max(self.run_b.as_ref().map_or(0, Run::head));
    }

    /// The record on screen, if a run exists (the last one, once the run converged before
    /// the side-by-side engine).
    pub fn shown_record(&self) -> Option<&FrameRecord> {
        self.run
            .as_ref()
            .and_then(|r| r.history.get(self.shown.min(r.history.len() - 1)))
    }

    /// The side-by-side engine's record for the frame on screen.
    pub fn shown_record_b(&self) -> Option<&FrameRecord> {
        self.run_b
            .as_ref()
            .and_then(|r| r.history.get(self.shown.min(r.history.len() - 1)))
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

    /// Whether Undo and Redo have something to do.
    pub fn can_undo_redo(&self) -> (bool, bool) {
        self.history.can()
    }

    /// The document as an undo step restores it.
    fn snapshot(&self) -> history::Snapshot {
        history::Snapshot {
            image: self.image.clone(),
            image_name: self.image_name.clone(),
            image_path: self.image_path.clone(),
            stack: self.stack.clone(),
            sample_wrap: self.sample_wrap,
            shapes: self.shapes.clone(),
            selected: self.selected,
            settings: self.settings.clone(),
            run: self.run.clone(),
            run_b: self.run_b.clone(),
            shown: self.shown,
            log: self.log.clone(),
        }
    }

    fn restore(&mut self, s: history::Snapshot) {
        let same_image = match (&self.image, &s.image) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if !same_image {
            self.texture = None;
        }
        self.image = s.image;
        self.image_name = s.image_name;
        self.image_path = s.image_path;
        self.stack = s.stack;
        self.sample_wrap = s.sample_wrap;
        self.shapes = s.shapes;
        self.selected = s.selected;
        self.settings = s.settings;
        self.run = s.run;
        self.run_b = s.run_b;
        self.shown = s.shown;
        self.log = s.log;
        self.playing = false;
        self.preparing = None;
    }

    /// Advances playback by the time since the last frame.
    fn tick(&mut self, dt: f64) {
        if !self.playing {
            return;
        }
        self.play_clock += dt * self.settings.speed as f64;
        let n = (self.play_clock.floor() as usize).clamp(1, 50);
        self.play_clock = (self.play_clock - n as f64).max(0.0);
        // At most a tenth of a second of frames per repaint: large images play slower
        // instead of freezing the window.
        let t = std::time::Instant::now();
        for _ in 0..n {
            self.step_frames(1);
            if !self.playing || t.elapsed() > std::time::Duration::from_millis(100) {
                self.play_clock = 0.0;
                break;
            }
        }
    }

    /// Where image point `p` is on the canvas (as of the last frame drawn).
    pub fn screen_from_image(&self, p: Point) -> egui::Pos2 {
        self.canvas.screen_from_image(p)
    }

    /// The window title.
    pub fn title(&self) -> String {
        match &self.run {
            Some(r) => format!(
                "topocontour — {} — frame {}",
                self.image_name,
                self.shown.min(r.history.len() - 1)
            ),
            None => format!("topocontour — {}", self.image_name),
        }
    }

    /// The whole app in a `Ui` (the eframe window's, or a test harness's).
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        let dt = ui.input(|i| i.stable_dt) as f64;
        self.keyboard(ui);
        self.help_ui(&ui.ctx().clone());
        self.path_prompt_ui(&ui.ctx().clone());
        self.poll_folder(&ui.ctx().clone());
        self.poll_preparing(&ui.ctx().clone());
        panels::top_bar(self, ui);
        panels::bottom_bar(self, ui);
        panels::side_panel(self, ui);
        egui::CentralPanel::default().show(ui, |ui| {
            let t = std::time::Instant::now();
            canvas::canvas_ui(self, ui);
            self.draw_ms = t.elapsed().as_secs_f64() * 1e3;
        });
        self.apply();
        self.tick(dt);
        if self.playing {
            ui.ctx().request_repaint();
        }
    }
}

/// The eframe wrapper: persistence and the window title.
struct EframeApp {
    app: TopoApp,
}

impl eframe::App for EframeApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        let title = self.app.title();
        ui.ctx()
            .send_viewport_cmd(egui::ViewportCommand::Title(title));
        self.app.ui(ui);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, eframe::APP_KEY, &self.app.settings);
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
            let settings = cc
                .storage
                .and_then(|s| eframe::get_value::<Settings>(s, eframe::APP_KEY));
            Ok(Box::new(EframeApp {
                app: TopoApp::new(settings, image),
            }))
        }),
    )
    .map_err(|e| e.to_string())
}
