//! The desktop app (DESIGN layer 6): state structs, their `ui`, and a [`Command`] enum
//! applied once per frame. The engine does all geometry; this module only draws it and
//! turns input into commands.

mod canvas;
mod fill;
mod history;
mod keys;
mod panels;

use crate::contours::BroadPhaseKind;
use crate::evolution::{
    find_seeds, Evolver, Field, ForceWeights, Modality, Mode, Params, Polarity, Shape,
};
use crate::geometry::Point;
use crate::io::{load_image, OutputFiles, Outputs};
use crate::topology::TopologyEvent;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The bundled sample shown on first start.
pub const SAMPLE_PNG: &[u8] = include_bytes!("../../assets/cells.png");

/// What a click on the canvas does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Tool {
    /// Click for a seed disk, drag to set its radius.
    Seed,
    /// Drag a rectangle.
    Rect,
    /// Click polygon corners; double-click (or click the first corner) to close.
    Polygon,
    /// Select, drag or delete seeds and shapes.
    Select,
    /// Edit the contours by hand: drag a vertex (through the topology core), click to
    /// select a contour, Delete removes it.
    Edit,
}

/// What an export writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportKind {
    Svg,
    GeoJson,
    Mask,
    Csv,
    /// 16-bit label image (TIFF).
    Labels,
    /// ImageJ ROI set (zip) for Fiji's ROI Manager.
    Roi,
}

impl ExportKind {
    pub fn extension(self) -> &'static str {
        match self {
            ExportKind::Svg => "svg",
            ExportKind::GeoJson => "geojson",
            ExportKind::Mask => "png",
            ExportKind::Csv => "csv",
            ExportKind::Labels => "tif",
            ExportKind::Roi => "zip",
        }
    }
}

/// Everything a widget can ask for; applied in one place, [`TopoApp::apply`].
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    OpenImage(PathBuf),
    /// Open a file dialog and then the chosen image.
    OpenDialog,
    AddShape(Shape),
    MoveShape {
        index: usize,
        by: Point,
    },
    DeleteShape(usize),
    Select(Option<usize>),
    SetTool(Tool),
    WrapBorder(f64),
    /// Place one seed per object found in the image (automatic seeds), as editable shapes.
    FindSeeds,
    /// The kind of image (phase contrast treats the halo as background).
    SetModality(Modality),
    Play,
    Pause,
    Step(usize),
    /// Step until a frame with a topology event (or convergence).
    StepToEvent,
    Reset,
    /// Show recorded frame `n` (0: the initialisation).
    SeekFrame(usize),
    Export(ExportKind, PathBuf),
    ExportDialog(ExportKind),
    SetPolarity(Polarity),
    SetMode(Mode),
    SetBroadPhase(BroadPhaseKind),
    /// Run a second engine beside the first, on the same image and shapes (or stop).
    SetCompare(Option<Mode>),
    ResetParameters,
    /// Save the image reference, shapes, parameters and the frame on screen as a session.
    SaveSession(PathBuf),
    /// Open a session: its image, shapes and parameters, run to its frame.
    OpenSession(PathBuf),
    /// Choose a file in a dialog, then save (true) or open (false) a session there.
    SessionDialog(bool),
    /// Hand edit: move contour vertex `vertex` of the frame on screen to `to`, through the
    /// topology core (merges, splits and holes happen exactly, logged as events).
    HandMove {
        vertex: u32,
        to: Point,
    },
    /// Hand edit: delete the contour `id` of the frame on screen (with its holes).
    DeleteContour(u32),
    /// Select a contour of the frame on screen to see its measurements (or none).
    SelectContour(Option<u32>),
    /// Undo the last change of the document (Ctrl+Z).
    Undo,
    /// Redo what Undo undid (Ctrl+Shift+Z, Ctrl+Y).
    Redo,
}

/// Settings kept between runs (eframe persistence).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Settings {
    pub polarity: Polarity,
    pub modality: Modality,
    pub mode: Mode,
    pub broad_phase: BroadPhaseKind,
    /// The engine shown side by side with `mode`, if any.
    pub compare: Option<Mode>,
    pub weights: ForceWeights,
    pub step: f64,
    pub min_area: f64,
    /// Frames per second while playing.
    pub speed: f32,
    pub tool: Tool,
    pub contrast: (f32, f32),
    pub show_fill: bool,
    pub last_dir: Option<PathBuf>,
}

impl Default for Settings {
    fn default() -> Self {
        let p = Params::default();
        Settings {
            polarity: Polarity::Dark,
            modality: Modality::Generic,
            mode: Mode::Adaptive,
            broad_phase: p.broad_phase,
            compare: None,
            weights: p.weights,
            step: p.step,
            min_area: p.min_area,
            speed: 30.0,
            tool: Tool::Seed,
            contrast: (0.0, 1.0),
            show_fill: true,
            last_dir: None,
        }
    }
}

/// One ring as recorded for display.
#[derive(Clone, Debug)]
pub struct RingView {
    pub id: u32,
    pub hole: bool,
    pub points: Vec<Point>,
}

/// A recorded frame: enough to draw it and to plot its statistics.
#[derive(Clone, Debug)]
pub struct FrameRecord {
    pub index: usize,
    pub rings: Vec<RingView>,
    pub events: Vec<TopologyEvent>,
    pub motions: Vec<[Point; 4]>,
    pub area: f64,
    pub contours: usize,
    pub vertices: usize,
    pub energy: f64,
    pub converged: bool,
}

impl FrameRecord {
    fn of(
        ev: &Evolver,
        index: usize,
        events: Vec<TopologyEvent>,
        motions: Vec<[Point; 4]>,
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
    pub evolver: Evolver,
    /// Frame 0 is the initialisation.
    pub history: Vec<FrameRecord>,
    /// Evolver states every few frames, to continue from any recorded frame.
    checkpoints: Vec<(usize, Evolver)>,
}

const CHECKPOINT_EVERY: usize = 10;

impl Run {
    fn new(evolver: Evolver) -> Self {
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

    fn step(&mut self) -> &FrameRecord {
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
        if f.index % CHECKPOINT_EVERY == 0 {
            self.checkpoints.retain(|(i, _)| *i < f.index);
            self.checkpoints.push((f.index, self.evolver.clone()));
        }
        self.history.last().expect("just pushed")
    }

    /// Puts the evolver back at recorded frame `n`, so stepping continues from there.
    fn rewind(&mut self, n: usize) {
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
    fn edit_at(
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

/// The whole app state.
pub struct TopoApp {
    pub image_name: String,
    /// The file the image came from (none for the bundled sample): exports never replace it.
    pub image_path: Option<PathBuf>,
    pub image: Option<Arc<Field>>,
    texture: Option<egui::TextureHandle>,
    texture_contrast: (f32, f32),
    pub shapes: Vec<Shape>,
    pub selected: Option<usize>,
    pub settings: Settings,
    pub run: Option<Run>,
    /// The second engine's run in the side-by-side view (same frames as `run`).
    pub run_b: Option<Run>,
    /// The recorded frame on screen.
    pub shown: usize,
    pub playing: bool,
    play_clock: f64,
    pub log: Vec<(usize, TopologyEvent)>,
    pub error: Option<String>,
    pub notice: Option<String>,
    /// Time of the last frame step, ms.
    pub step_ms: f64,
    /// Time spent drawing the canvas last frame, ms.
    pub draw_ms: f64,
    pub commands: Vec<Command>,
    canvas: canvas::CanvasState,
    /// Undo and redo steps.
    history: history::History,
    /// The help window is open.
    pub show_help: bool,
    /// The contour selected with the Edit tool (its measurements show in the status bar).
    pub selected_contour: Option<u32>,
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
        app.apply_now(Command::WrapBorder(6.0));
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
        self.reset_run();
    }

    fn reset_run(&mut self) {
        self.run = None;
        self.run_b = None;
        self.shown = 0;
        self.playing = false;
        self.log.clear();
    }

    pub fn params(&self) -> Params {
        Params {
            polarity: self.settings.polarity,
            modality: self.settings.modality,
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
        let Some(image) = &self.image else {
            self.error = Some("open an image first".into());
            return false;
        };
        let second = self.settings.compare.map(|mode| {
            Evolver::new(
                image,
                &self.shapes,
                Params {
                    mode,
                    ..self.params()
                },
            )
        });
        match Evolver::new(image, &self.shapes, self.params()) {
            Ok(ev) => {
                self.run = Some(Run::new(ev));
                self.run_b = second.and_then(Result::ok).map(Run::new);
                self.shown = 0;
                self.log.clear();
                true
            }
            Err(e) => {
                self.error = Some(e.to_string());
                self.playing = false;
                false
            }
        }
    }

    /// Advances `n` frames (from the frame on screen), recording each.
    fn step_frames(&mut self, n: usize) {
        if !self.ensure_run() {
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
        self.shapes = s.shapes;
        self.selected = s.selected;
        self.settings = s.settings;
        self.run = s.run;
        self.run_b = s.run_b;
        self.shown = s.shown;
        self.log = s.log;
        self.playing = false;
    }

    fn apply_now(&mut self, c: Command) {
        if self.history.starts_step(&c) {
            let before = self.snapshot();
            self.history.push(before);
        }
        match c {
            Command::HandMove { vertex, to } => {
                if self.ensure_run() {
                    let at = self.shown;
                    let run = self.run.as_mut().expect("ensured");
                    let mut lead = None;
                    let events = run.edit_at(at, |ev| {
                        let (events, l) = ev.hand_drag(vertex, to);
                        lead = l;
                        events
                    });
                    // The drag goes on with the vertex that leads now.
                    self.canvas.set_drag_lead(lead);
                    self.log.retain(|(f, _)| *f <= at);
                    self.log.extend(events.into_iter().map(|e| (at, e)));
                }
            }
            Command::DeleteContour(id) => {
                if self.ensure_run() {
                    let at = self.shown;
                    let run = self.run.as_mut().expect("ensured");
                    run.edit_at(at, |ev| {
                        ev.delete_contour(crate::contours::ContourId(id));
                        Vec::new()
                    });
                    self.selected_contour = None;
                }
            }
            Command::SelectContour(id) => self.selected_contour = id,
            Command::Undo => {
                let now = self.snapshot();
                match self.history.undo(now) {
                    Some(s) => self.restore(s),
                    None => self.notice = Some("nothing to undo".into()),
                }
            }
            Command::Redo => {
                let now = self.snapshot();
                match self.history.redo(now) {
                    Some(s) => self.restore(s),
                    None => self.notice = Some("nothing to redo".into()),
                }
            }
            Command::OpenImage(p) => match load_image(&p) {
                Ok(f) => {
                    let name = p
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    self.settings.last_dir = p.parent().map(Path::to_path_buf);
                    self.set_image(f, name);
                    self.image_path = Some(p);
                    self.error = None;
                }
                Err(e) => self.error = Some(e.to_string()),
            },
            Command::OpenDialog => {
                let mut d = rfd::FileDialog::new()
                    .add_filter("images", &["png", "jpg", "jpeg", "tif", "tiff"]);
                if let Some(dir) = &self.settings.last_dir {
                    d = d.set_directory(dir);
                }
                match d.pick_file() {
                    Some(p) => self.apply_now(Command::OpenImage(p)),
                    None => {
                        self.notice = Some("no file chosen (is a desktop portal running?)".into())
                    }
                }
            }
            Command::AddShape(s) => {
                self.shapes.push(s);
                self.selected = Some(self.shapes.len() - 1);
                self.reset_run();
            }
            Command::MoveShape { index, by } => {
                if let Some(s) = self.shapes.get_mut(index) {
                    *s = match s.clone() {
                        Shape::Disk { center, radius } => Shape::Disk {
                            center: center + by,
                            radius,
                        },
                        Shape::Rect { min, max } => Shape::Rect {
                            min: min + by,
                            max: max + by,
                        },
                        Shape::Polygon(p) => {
                            Shape::Polygon(p.into_iter().map(|q| q + by).collect())
                        }
                    };
                    self.reset_run();
                }
            }
            Command::DeleteShape(i) => {
                if i < self.shapes.len() {
                    self.shapes.remove(i);
                    self.selected = None;
                    self.reset_run();
                }
            }
            Command::Select(i) => self.selected = i,
            Command::SetTool(t) => self.settings.tool = t,
            Command::WrapBorder(m) => {
                if let Some(img) = &self.image {
                    let (w, h) = (img.width as f64, img.height as f64);
                    let m = m.min(0.25 * w.min(h));
                    self.shapes.push(Shape::Rect {
                        min: Point::new(m, m),
                        max: Point::new(w - m, h - m),
                    });
                    self.reset_run();
                }
            }
            Command::FindSeeds => {
                if let Some(img) = &self.image {
                    let found = find_seeds(img, self.settings.polarity, self.settings.modality);
                    self.notice = Some(format!("found {} objects: seeds placed", found.len()));
                    self.shapes.extend(found);
                    self.reset_run();
                }
            }
            Command::SetModality(m) => {
                self.settings.modality = m;
                self.reset_run();
            }
            Command::Play => {
                if self.ensure_run() {
                    self.playing = true;
                }
            }
            Command::Pause => self.playing = false,
            Command::Step(n) => self.step_frames(n),
            Command::StepToEvent => {
                for _ in 0..5000 {
                    self.step_frames(1);
                    let done = self.run.as_ref().is_none_or(|r| r.evolver.is_finished());
                    if done || self.shown_record().is_some_and(|r| !r.events.is_empty()) {
                        break;
                    }
                }
            }
            Command::Reset => self.reset_run(),
            Command::SeekFrame(n) => {
                if let Some(r) = &self.run {
                    let last = (r.history.len() - 1)
                        .max(self.run_b.as_ref().map_or(0, |b| b.history.len() - 1));
                    self.shown = n.min(last);
                    self.playing = false;
                }
            }
            Command::Export(kind, path) => {
                if let Err(e) = self.export(kind, &path) {
                    self.error = Some(e);
                } else {
                    self.notice = Some(format!("wrote {}", path.display()));
                }
            }
            Command::ExportDialog(kind) => {
                let mut d = rfd::FileDialog::new()
                    .add_filter(kind.extension(), &[kind.extension()])
                    .set_file_name(format!("contours.{}", kind.extension()));
                if let Some(dir) = &self.settings.last_dir {
                    d = d.set_directory(dir);
                }
                match d.save_file() {
                    Some(p) => self.apply_now(Command::Export(kind, p)),
                    None => self.notice = Some("export cancelled (no file chosen)".into()),
                }
            }
            Command::SetPolarity(p) => {
                self.settings.polarity = p;
                self.reset_run();
            }
            Command::SetMode(mode) => {
                self.settings.mode = mode;
                self.reset_run();
            }
            Command::SetCompare(mode) => {
                self.settings.compare = mode;
                self.reset_run();
            }
            Command::SetBroadPhase(kind) => {
                self.settings.broad_phase = kind;
                self.reset_run();
            }
            Command::ResetParameters => {
                if let Some(img) = &self.image {
                    self.settings.contrast = auto_contrast(img);
                }
                let d = Settings::default();
                self.settings.weights = d.weights;
                self.settings.step = d.step;
                self.settings.min_area = d.min_area;
                self.reset_run();
            }
            Command::SessionDialog(save) => {
                let mut d = rfd::FileDialog::new().add_filter("sessions", &["json"]);
                if let Some(dir) = &self.settings.last_dir {
                    d = d.set_directory(dir);
                }
                let chosen = if save {
                    d.set_file_name(format!("{}.session.json", self.image_name))
                        .save_file()
                } else {
                    d.pick_file()
                };
                match (chosen, save) {
                    (Some(p), true) => self.apply_now(Command::SaveSession(p)),
                    (Some(p), false) => self.apply_now(Command::OpenSession(p)),
                    (None, _) => {
                        self.notice = Some("no file chosen (is a desktop portal running?)".into())
                    }
                }
            }
            Command::SaveSession(p) => match self.save_session(&p) {
                Ok(()) => self.notice = Some(format!("session saved to {}", p.display())),
                Err(e) => self.error = Some(e),
            },
            Command::OpenSession(p) => {
                if let Err(e) = self.open_session(&p) {
                    self.error = Some(e);
                }
            }
        }
    }

    /// Writes the session of the frame on screen.
    fn save_session(&mut self, path: &Path) -> Result<(), String> {
        let (Some(image), Some(image_path)) = (&self.image, &self.image_path) else {
            return Err(
                "a session needs an image file: open one first (the sample has none)".into(),
            );
        };
        let abs = image_path.canonicalize().map_err(|e| e.to_string())?;
        let (frames, finished) = match &self.run {
            Some(run) => (
                self.shown,
                self.shown == run.head() && run.evolver.is_finished(),
            ),
            None => (0, false),
        };
        let s = crate::io::session::Session::new(
            &abs,
            image,
            self.shapes.clone(),
            self.params(),
            frames,
            finished,
        )
        .map_err(|e| e.to_string())?;
        OutputFiles::prepare(Some(&abs), &[path])
            .and_then(|f| f.commit(vec![s.to_json().into_bytes()]))
            .map_err(|e| e.to_string())
    }

    /// Opens a session: image, shapes, parameters, then steps to its frame.
    fn open_session(&mut self, path: &Path) -> Result<(), String> {
        let s = crate::io::session::Session::read(path).map_err(|e| e.to_string())?;
        let image_path = s.image_path(path);
        self.apply_now(Command::OpenImage(image_path.clone()));
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let crc = crate::io::session::file_crc32(&image_path).map_err(|e| e.to_string())?;
        if crc != s.image.crc32 {
            return Err(format!(
                "{} changed since the session was saved",
                image_path.display()
            ));
        }
        let p = &s.params;
        self.settings.polarity = p.polarity;
        self.settings.mode = p.mode;
        self.settings.modality = p.modality;
        self.settings.broad_phase = p.broad_phase;
        self.settings.weights = p.weights;
        self.settings.step = p.step;
        self.settings.min_area = p.min_area;
        self.shapes = s.shapes.clone();
        self.reset_run();
        if s.frames > 0 {
            self.step_frames(s.frames);
        }
        Ok(())
    }

    /// Writes the frame on screen (the evolver's state at it) to `path`.
    fn export(&mut self, kind: ExportKind, path: &Path) -> Result<(), String> {
        let Some(run) = self.run.as_mut() else {
            return Err("nothing to export yet: run the evolution first".into());
        };
        run.rewind(self.shown.min(run.history.len() - 1));
        let ev = &run.evolver;
        let (w, h) = ev.size();
        let mut set = ev.contours().clone();
        crate::evolution::measure::drop_small(&mut set, self.settings.min_area);
        let out = Outputs {
            set: &set,
            width: w,
            height: h,
            frames: ev.frames(),
            converged: ev.is_converged(),
            events: ev.events(),
            image: &self.image_name,
            params: ev.params(),
            held: ev.held_contacts(),
        };
        let bytes = match kind {
            ExportKind::Svg => out.svg().into_bytes(),
            ExportKind::GeoJson => out.geojson().into_bytes(),
            ExportKind::Mask => out.mask_png(),
            ExportKind::Csv => out.csv().into_bytes(),
            ExportKind::Labels => out
                .labels_image(true)
                .ok_or("more than 65,535 objects for a 16-bit label image")?,
            ExportKind::Roi => crate::io::roi::roi_zip(out.set),
        };
        OutputFiles::prepare(self.image_path.as_deref(), &[path])
            .and_then(|f| f.commit(vec![bytes]))
            .map_err(|e| e.to_string())
    }

    /// Advances playback by the time since the last frame.
    fn tick(&mut self, dt: f64) {
        if !self.playing {
            return;
        }
        self.play_clock += dt * self.settings.speed as f64;
        let n = (self.play_clock.floor() as usize).clamp(1, 50);
        self.play_clock = (self.play_clock - n as f64).max(0.0);
        self.step_frames(n);
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
