//! What a widget can ask for ([`Command`]) and the one place commands change the app
//! ([`TopoApp::apply`] → `apply_now`), each group of commands in its own handler.

use super::path_prompt::PathPurpose;
use super::{auto_contrast, Settings, TopoApp};
use crate::contours::BroadPhaseKind;
use crate::evolution::{find_seeds, ForceWeights, Modality, Mode, Polarity, Shape};
use crate::geometry::Point;
use std::path::{Path, PathBuf};

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
    /// Push contours with a disc: from inside a region its boundary moves out, from
    /// outside it moves in (merges, splits and holes happen exactly).
    Brush,
}

/// What an export writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportKind {
    /// Scalable vector graphics of the contours.
    Svg,
    /// GeoJSON as QuPath reads it.
    GeoJson,
    /// Binary mask (PNG).
    Mask,
    /// One row per contour: measurements.
    Csv,
    /// 16-bit label image (TIFF).
    Labels,
    /// ImageJ ROI set (zip) for Fiji's ROI Manager.
    Roi,
}

impl ExportKind {
    /// The file name an export of image `image` gets by default.
    pub fn default_name(self, image: &str) -> String {
        let stem = super::path_prompt::stem(image);
        match self {
            ExportKind::Mask => format!("{stem}.mask.png"),
            ExportKind::Labels => format!("{stem}.labels.tif"),
            ExportKind::Roi => format!("{stem}.rois.zip"),
            _ => format!("{stem}.{}", self.extension()),
        }
    }

    /// The file extension of this kind.
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
    /// Open the image at a path.
    OpenImage(PathBuf),
    /// Open a file dialog and then the chosen image.
    OpenDialog,
    /// Add a shape to the initialisation.
    AddShape(Shape),
    /// Move shape `index` by a vector.
    MoveShape {
        /// The shape.
        index: usize,
        /// By how much, in image pixels.
        by: Point,
    },
    /// Delete shape `index`.
    DeleteShape(usize),
    /// Select a shape (or none).
    Select(Option<usize>),
    /// Choose the canvas tool.
    SetTool(Tool),
    /// Add a wrap rectangle this many pixels inside the border.
    WrapBorder(f64),
    /// Place one seed per object found in the image (automatic seeds), as editable shapes.
    FindSeeds,
    /// The kind of image (phase contrast treats the halo as background).
    SetModality(Modality),
    /// Whether the adaptive engine opens holes in clear background inside a region.
    SetOpenHoles(bool),
    /// Play the evolution.
    Play,
    /// Pause playback.
    Pause,
    /// Step this many frames.
    Step(usize),
    /// Step until a frame with a topology event (or convergence).
    StepToEvent,
    /// Throw the run away (undoable) and show the initialisation.
    Reset,
    /// Show recorded frame `n` (0: the initialisation).
    SeekFrame(usize),
    /// Write the frame on screen to a file.
    Export(ExportKind, PathBuf),
    /// Choose a file in a dialog, then export.
    ExportDialog(ExportKind),
    /// Objects darker or brighter than the background.
    SetPolarity(Polarity),
    /// The engine.
    SetMode(Mode),
    /// The broad phase of the crossing search.
    SetBroadPhase(BroadPhaseKind),
    /// Run a second engine beside the first, on the same image and shapes (or stop).
    SetCompare(Option<Mode>),
    /// New force weights and step: a run goes on from the frame on screen with them.
    SetForces {
        /// The weights.
        weights: ForceWeights,
        /// The step, in grid spacings.
        step: f64,
    },
    /// Segment every image of a folder with the shapes and parameters on screen, in the
    /// background; outputs go to its `topocontour` subfolder.
    ApplyToFolder(PathBuf),
    /// Choose the folder in a dialog, then apply to it.
    ApplyToFolderDialog,
    /// Stop the folder run after the image in progress.
    CancelFolder,
    /// Show page `n` (0-based) of a multi-page image; shapes stay.
    SetPage(usize),
    /// The physical size of a pixel (none: unknown).
    SetPixelSize(Option<crate::io::PixelSize>),
    /// Put the force weights, step and minimum area back to their defaults.
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
        /// The vertex (of the frame on screen).
        vertex: u32,
        /// Where to, in image pixels.
        to: Point,
    },
    /// Hand edit begins: the run goes back to the frame on screen (later frames start
    /// from the edit) and the contour vertex nearest to `at` within `tol` is grabbed.
    GrabVertex {
        /// Where the press was, in image pixels.
        at: Point,
        /// How far a vertex may be, in image pixels.
        tol: f64,
    },
    /// Hand edit: a brush stroke of `radius` from `from` to `to` on the frame on screen.
    Brush {
        /// Where the brush's centre was.
        from: Point,
        /// Where it is now.
        to: Point,
        /// The brush's radius, pixels.
        radius: f64,
        /// Which stroke (press) this is part of: each stroke is one undo step.
        stroke: u32,
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

impl TopoApp {
    /// New forces for the runs on screen: each goes on from the frame shown (later frames
    /// are dropped; the change is one of the run's edits, saved with a session).
    fn set_forces(&mut self, weights: ForceWeights, step: f64) {
        self.settings.weights = weights;
        self.settings.step = step;
        let shown = self.shown;
        let mut failed = None;
        for run in [self.run.as_mut(), self.run_b.as_mut()]
            .into_iter()
            .flatten()
        {
            let at = shown.min(run.history.len() - 1);
            run.edit_at(at, |ev| {
                failed = ev.set_forces(weights, step).err();
                Vec::new()
            });
        }
        if let Some(e) = failed {
            self.error = Some(e.into());
        } else if self.run.is_some() {
            self.log.retain(|(f, _)| *f <= shown);
            self.notice = Some(format!(
                "forces changed at frame {shown}: the run goes on from here with them"
            ));
        }
    }

    /// A file dialog opening in the folder of the last file opened.
    fn dialog(&self) -> rfd::FileDialog {
        let d = rfd::FileDialog::new();
        match &self.settings.last_dir {
            Some(dir) => d.set_directory(dir),
            None => d,
        }
    }

    /// The one place the document changes: records an undo step when the command starts
    /// one, then hands the command to its group's handler.
    pub(super) fn apply_now(&mut self, c: Command) {
        if self.history.starts_step(&c) {
            let before = self.snapshot();
            self.history.push(before);
        }
        match c {
            Command::HandMove { .. }
            | Command::Brush { .. }
            | Command::GrabVertex { .. }
            | Command::DeleteContour(..)
            | Command::SelectContour(..) => self.hand_edit(c),
            Command::Undo | Command::Redo => self.undo_redo(c),
            Command::AddShape(..)
            | Command::MoveShape { .. }
            | Command::DeleteShape(..)
            | Command::Select(..)
            | Command::WrapBorder(..)
            | Command::FindSeeds => self.edit_shapes(c),
            Command::Play
            | Command::Pause
            | Command::Step(..)
            | Command::StepToEvent
            | Command::Reset
            | Command::SeekFrame(..) => self.playback(c),
            Command::SetTool(..)
            | Command::SetModality(..)
            | Command::SetOpenHoles(..)
            | Command::SetPolarity(..)
            | Command::SetMode(..)
            | Command::SetCompare(..)
            | Command::SetBroadPhase(..)
            | Command::SetForces { .. }
            | Command::SetPage(..)
            | Command::SetPixelSize(..)
            | Command::ResetParameters => self.set_parameter(c),
            Command::OpenImage(..)
            | Command::OpenDialog
            | Command::Export(..)
            | Command::ExportDialog(..)
            | Command::SessionDialog(..)
            | Command::SaveSession(..)
            | Command::OpenSession(..)
            | Command::ApplyToFolder(..)
            | Command::ApplyToFolderDialog
            | Command::CancelFolder => self.files(c),
        }
    }

    /// Hand edits of the frame on screen, through the engine.
    fn hand_edit(&mut self, c: Command) {
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
            Command::Brush {
                from, to, radius, ..
            } => {
                if self.ensure_run() {
                    let at = self.shown;
                    let run = self.run.as_mut().expect("ensured");
                    let events = run.edit_at(at, |ev| ev.brush(from, to, radius));
                    self.log.retain(|(f, _)| *f <= at);
                    self.log.extend(events.into_iter().map(|e| (at, e)));
                }
            }
            Command::GrabVertex { at, tol } => {
                let shown = self.shown;
                let grabbed = self.run.as_mut().and_then(|run| {
                    run.rewind(shown.min(run.history.len() - 1));
                    run.evolver.vertex_near(at, tol)
                });
                self.canvas.set_drag_lead(grabbed);
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
            _ => unreachable!("not a hand edit command: {c:?}"),
        }
    }

    /// Undo and redo.
    fn undo_redo(&mut self, c: Command) {
        match c {
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
            _ => unreachable!("not a undo redo command: {c:?}"),
        }
    }

    /// The user's shapes (the initialisation).
    fn edit_shapes(&mut self, c: Command) {
        match c {
            Command::AddShape(s) => {
                // The sample's wrap would swallow a seed clicked inside it: it makes way
                // (Undo brings it back).
                if self.sample_wrap && matches!(s, Shape::Disk { .. }) {
                    self.shapes.clear();
                    self.notice = Some(
                        "the sample's wrap rectangle made way for your seed (Undo brings it back)"
                            .into(),
                    );
                }
                self.sample_wrap = false;
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
            _ => unreachable!("not a edit shapes command: {c:?}"),
        }
    }

    /// Playing, stepping and seeking.
    fn playback(&mut self, c: Command) {
        match c {
            Command::Play => {
                if self.ensure_run() {
                    self.playing = true;
                } else if let Some(p) = self.preparing.as_mut() {
                    p.play = true;
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
            _ => unreachable!("not a playback command: {c:?}"),
        }
    }

    /// The tool and the parameters of the run.
    fn set_parameter(&mut self, c: Command) {
        match c {
            Command::SetTool(t) => self.settings.tool = t,
            Command::SetModality(_)
            | Command::SetOpenHoles(_)
            | Command::SetPolarity(_)
            | Command::SetMode(_)
            | Command::SetCompare(_)
            | Command::SetBroadPhase(_) => {
                let s = &mut self.settings;
                match c {
                    Command::SetModality(m) => s.modality = m,
                    Command::SetOpenHoles(on) => s.open_holes = on,
                    Command::SetPolarity(p) => s.polarity = p,
                    Command::SetMode(mode) => s.mode = mode,
                    Command::SetCompare(mode) => s.compare = mode,
                    Command::SetBroadPhase(kind) => s.broad_phase = kind,
                    _ => unreachable!(),
                }
                // A parameter the run was started with: it starts again.
                self.reset_run();
            }
            Command::SetForces { weights, step } => self.set_forces(weights, step),
            Command::SetPixelSize(p) => self.stack.pixel = p,
            Command::SetPage(n) => {
                let Some(path) = self.image_path.clone() else {
                    return;
                };
                match crate::io::load_image_page(&path, n) {
                    Ok((f, _)) => {
                        // Same file, another page: the shapes and contrast stay.
                        self.image = Some(std::sync::Arc::new(f));
                        self.texture = None;
                        self.stack.page = n;
                        self.reset_run();
                    }
                    Err(e) => self.error = Some(e.into()),
                }
            }
            Command::ResetParameters => {
                if let Some(img) = &self.image {
                    self.settings.contrast = auto_contrast(img);
                }
                let d = Settings::default();
                self.settings.min_area = d.min_area;
                self.set_forces(d.weights, d.step);
            }
            _ => unreachable!("not a set parameter command: {c:?}"),
        }
    }

    /// Images, exports and sessions (files chosen in a dialog, or given).
    fn files(&mut self, c: Command) {
        match c {
            Command::OpenImage(p) => match crate::io::load_image_page(&p, 0) {
                Ok((f, info)) => {
                    let name = crate::io::folder::file_name(&p);
                    self.settings.last_dir = p.parent().map(Path::to_path_buf);
                    self.set_image(f, name);
                    self.image_path = Some(p);
                    self.error = None;
                    if info.pages > 1 {
                        self.notice = Some(format!(
                            "{} holds {} pages: page 1 is shown (choose another under Image)",
                            self.image_name, info.pages
                        ));
                    }
                    self.stack = super::ImageStack {
                        pages: info.pages,
                        page: 0,
                        pixel: info.pixel_size,
                    };
                }
                Err(e) => self.error = Some(e.into()),
            },
            Command::OpenDialog => {
                let d = self
                    .dialog()
                    .add_filter("images", &["png", "jpg", "jpeg", "tif", "tiff"]);
                match d.pick_file() {
                    Some(p) => self.apply_now(Command::OpenImage(p)),
                    None => self.prompt_path(PathPurpose::OpenImage, String::new()),
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
                let name = kind.default_name(&self.image_name);
                let d = self
                    .dialog()
                    .add_filter(kind.extension(), &[kind.extension()])
                    .set_file_name(&name);
                match d.save_file() {
                    Some(p) => self.apply_now(Command::Export(kind, p)),
                    None => self.prompt_path(PathPurpose::Export(kind), name),
                }
            }
            Command::SessionDialog(save) => {
                let d = self.dialog().add_filter("sessions", &["json"]);
                let name = format!(
                    "{}.session.json",
                    super::path_prompt::stem(&self.image_name)
                );
                let chosen = if save {
                    d.set_file_name(&name).save_file()
                } else {
                    d.pick_file()
                };
                match (chosen, save) {
                    (Some(p), true) => self.apply_now(Command::SaveSession(p)),
                    (Some(p), false) => self.apply_now(Command::OpenSession(p)),
                    (None, true) => self.prompt_path(PathPurpose::SaveSession, name),
                    (None, false) => self.prompt_path(PathPurpose::OpenSession, String::new()),
                }
            }
            Command::ApplyToFolder(dir) => self.apply_to_folder(&dir),
            Command::ApplyToFolderDialog => match self.dialog().pick_folder() {
                Some(p) => self.apply_now(Command::ApplyToFolder(p)),
                None => self.prompt_path(PathPurpose::ApplyToFolder, String::new()),
            },
            Command::CancelFolder => {
                if let Some(f) = &self.folder {
                    f.cancel();
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
            _ => unreachable!("not a files command: {c:?}"),
        }
    }
}
