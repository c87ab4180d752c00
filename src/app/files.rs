//! Files the app writes and reads: images, exports of the frame on screen and sessions,
//! with the errors a user can meet.

use super::command::Command;
use super::path_prompt::PathPurpose;
use super::{Document, Run, TopoApp};
use crate::io::export::Format;
use crate::io::{OutputFiles, Outputs};
use std::path::{Path, PathBuf};

/// What can go wrong in the app, as the status bar says it.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// A run needs an image.
    #[error("open an image first")]
    NoImage,
    /// Sessions refer to an image file; the bundled sample has none.
    #[error("a session needs an image file: open one first (the sample has none)")]
    SampleHasNoFile,
    /// Nothing has run yet.
    #[error("nothing to export yet: run the evolution first")]
    NothingToExport,
    /// An output could not be rendered (too many labels).
    #[error(transparent)]
    Export(#[from] crate::io::export::ExportError),
    /// The session's image is not the one it was saved with.
    #[error("{} changed since the session was saved", .0.display())]
    ImageChanged(PathBuf),
    /// The image could not be read.
    #[error(transparent)]
    Load(#[from] crate::io::LoadError),
    /// The run could not start.
    #[error(transparent)]
    Evolve(#[from] crate::evolution::EvolveError),
    /// A session's job could not start.
    #[error(transparent)]
    Job(#[from] crate::job::JobError),
    /// A session could not be read or written.
    #[error(transparent)]
    Session(#[from] crate::io::session::SessionError),
    /// An output could not be written.
    #[error(transparent)]
    Output(#[from] crate::io::OutputError),
    /// Teaching failed (the strokes or classifier do not fit), or a classifier file.
    #[error("{0}")]
    Teach(String),
    /// A movie could not be opened, read or tracked, or its result written.
    #[error("{0}")]
    Movie(String),
    /// Another I/O failure, with the file.
    #[error("{}: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
}

impl TopoApp {
    /// Opens page 1 of the image at `p` as a new document (settings reset: each image has
    /// its own kind, polarity and engine).
    fn open_image(&mut self, p: PathBuf) {
        match crate::io::load_image_page(&p, 0) {
            Ok((f, info)) => {
                self.view.movie_playing = false;
                self.view.prefs.last_dir = p.parent().map(Path::to_path_buf);
                self.reset_run();
                let mut doc = Document::of_image(f, crate::io::folder::file_name(&p));
                // A classifier loaded serves every image opened after it.
                if let Some(c) = self.doc.train.loaded.clone() {
                    doc.train.loaded = Some(c);
                    doc.train.revision = super::train::next_revision();
                }
                doc.image_path = Some(p);
                doc.stack.pages = info.pages;
                doc.stack.pixel = info.pixel_size;
                self.status.error = None;
                let bright = doc.params().polarity == crate::evolution::Polarity::Bright;
                self.status.notice = (info.pages > 1).then(|| {
                    format!(
                        "{} holds {} pages: page 1 is shown (choose another under Image; a time-lapse opens as a movie with Movie > Open movie)",
                        doc.image_name, info.pages
                    )
                });
                if bright && info.pages == 1 {
                    self.status.notice =
                        Some(format!("{}{}", doc.image_name, super::movie::BRIGHT_CHOSEN));
                }
                self.doc = doc;
                self.view.selected = None;
                self.view.selected_contour = None;
            }
            Err(e) => self.status.error = Some(e.into()),
        }
    }

    /// A file dialog opening in the folder of the last file opened.
    pub(super) fn dialog(&self) -> rfd::FileDialog {
        let d = rfd::FileDialog::new();
        match &self.view.prefs.last_dir {
            Some(dir) => d.set_directory(dir),
            None => d,
        }
    }

    /// Images, exports and sessions (files chosen in a dialog, or given).
    pub(super) fn files(&mut self, c: Command) {
        match c {
            Command::OpenImage(p) => self.open_image(p),
            Command::OpenDialog => {
                let d = self
                    .dialog()
                    .add_filter("images", &["png", "jpg", "jpeg", "tif", "tiff"]);
                match d.pick_file() {
                    Some(p) => self.apply_now(Command::OpenImage(p)),
                    None => self.prompt_path(PathPurpose::OpenImage, String::new()),
                }
            }
            Command::Export(kind, path) => match self.export(kind, &path) {
                Ok(()) => self.status.notify(format!("wrote {}", path.display())),
                Err(e) => self.status.error = Some(e),
            },
            Command::ExportDialog(kind) => {
                // A movie's frame is exported alone: its number is in the name; the
                // tracked movie's CSV holds every frame: "tracks".
                let mut stem = super::path_prompt::stem(&self.doc.image_name);
                if kind == Format::Csv && self.exports_by_track(kind) {
                    stem = format!("{stem}.tracks");
                } else if let Some(m) = &self.doc.movie {
                    let digits = (m.movie.len() - 1).to_string().len().max(3);
                    stem = format!("{stem}.frame{:0digits$}", m.frame);
                }
                let name = kind.file_name(&stem);
                let d = self
                    .dialog()
                    .add_filter(kind.extension(), &[kind.extension()])
                    .set_file_name(&name);
                match d.save_file() {
                    Some(p) => self.apply_now(Command::Export(kind, p)),
                    None => self.prompt_path(PathPurpose::Export(kind), name),
                }
            }
            Command::SessionDialog(save) => self.session_dialog(save),
            Command::ApplyToFolder(dir) => self.apply_to_folder(&dir),
            Command::ApplyToFolderDialog => match self.dialog().pick_folder() {
                Some(p) => self.apply_now(Command::ApplyToFolder(p)),
                None => self.prompt_path(PathPurpose::ApplyToFolder, String::new()),
            },
            Command::CancelFolder => {
                if let Some(f) = &self.jobs.folder {
                    f.cancel();
                }
            }
            Command::SaveSession(p) => match self.save_session(&p) {
                Ok(()) => {
                    // Saved, unless tracking still adds frames after it or a movie's
                    // session leaves something out.
                    self.unsaved &= self.jobs.track.is_some() || self.movie_session_leaves_out();
                    self.status
                        .notify(format!("session saved to {}", p.display()))
                }
                Err(e) => self.status.error = Some(e),
            },
            Command::OpenSession(p) => {
                if let Err(e) = self.open_session(&p) {
                    self.status.error = Some(e);
                }
            }
            _ => unreachable!("not a files command: {c:?}"),
        }
    }

    /// Chooses a session file in a dialog (or the path field), then saves or opens it.
    fn session_dialog(&mut self, save: bool) {
        let d = self.dialog().add_filter("sessions", &["json"]);
        let name = format!(
            "{}.session.json",
            super::path_prompt::stem(&self.doc.image_name)
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

    /// Closing the window with work not saved asks first ([`super::Question::Quit`]);
    /// "Quit without saving" closes it.
    pub(super) fn guard_close(&mut self, ctx: &egui::Context) {
        if !ctx.input(|i| i.viewport().close_requested()) || self.view.quit_confirmed {
            return;
        }
        if let Some(what) = self.unsaved_work() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.view.question = Some(super::Question::Quit(what));
        }
    }

    /// What closing now would lose, in a sentence or two; None when nothing.
    pub fn unsaved_work(&self) -> Option<String> {
        let replaced = self.doc.replaced.as_ref().map(|name| {
            format!("Your work before you opened {name} is not saved (Undo brings it back).")
        });
        match (self.own_unsaved_work(), replaced) {
            (Some(own), Some(before)) => Some(format!("{own} {before}")),
            (own, before) => own.or(before),
        }
    }

    /// What closing now would lose of the document on screen.
    pub(super) fn own_unsaved_work(&self) -> Option<String> {
        if !self.unsaved {
            return None;
        }
        let doc = &self.doc;
        if let Some(tr) = doc.movie.as_ref().and_then(|m| m.tracking.as_ref()) {
            let counted = crate::cli::counted;
            let corrected = match tr.corrected.len() {
                0 => String::new(),
                n => format!(" and your corrections on {}", counted(n, "frame")),
            };
            let verb = if corrected.is_empty() { "is" } else { "are" };
            return Some(format!(
                "The tracking of {}{corrected} {verb} not saved.",
                counted(tr.frames.len(), "frame")
            ));
        }
        let made = !doc.shapes.is_empty()
            || doc
                .run
                .as_ref()
                .is_some_and(|r| !r.evolver_at(doc.shown).edits().is_empty())
            || doc.train.painted();
        made.then(|| "Your seeds, shapes, edits and settings are not saved as a session.".into())
    }

    /// Writes the session of the frame on screen (of a movie: its tracking).
    fn save_session(&mut self, path: &Path) -> Result<(), AppError> {
        if self.doc.movie.is_some() {
            return self.save_tracking_session(path);
        }
        let doc = &self.doc;
        let (Some(image), Some(image_path)) = (&doc.image, &doc.image_path) else {
            return Err(AppError::SampleHasNoFile);
        };
        let abs = image_path.canonicalize().map_err(|source| AppError::Io {
            path: image_path.clone(),
            source,
        })?;
        let (frames, finished, params, edits) = match &doc.run {
            Some(run) => {
                // The evolver at the frame on screen: its edits are the ones that led here.
                let ev = run.evolver_at(doc.shown);
                let edits = ev.edits().to_vec();
                let mut params = ev.start_params().clone();
                if doc.taught.is_some() {
                    // A taught run read the map with the guide's polarity and kind; the
                    // session keeps the user's, which the replay's guide reads it with.
                    let p = doc.params();
                    (params.polarity, params.modality, params.local) =
                        (p.polarity, p.modality, p.local);
                }
                (ev.frames(), ev.is_finished(), params, edits)
            }
            None => (0, false, doc.params().clone(), Vec::new()),
        };
        let s = crate::io::session::Session::new(
            &abs,
            image,
            doc.shapes.clone(),
            params,
            frames,
            finished,
        )
        .map_err(|source| AppError::Io {
            path: abs.clone(),
            source,
        })?
        .with_edits(&edits)
        .with_page(doc.stack.page)
        .stored_at(path);
        let (strokes, classifier) = match self.session_teaching() {
            Some(super::train::Source::Strokes(st)) => (Some((*st).clone()), None),
            Some(super::train::Source::Loaded(c)) => (None, Some((*c).clone())),
            None => (None, None),
        };
        let s = crate::io::session::Session {
            pixel_size: doc.stack.pixel.clone(),
            strokes,
            classifier,
            ..s
        };
        OutputFiles::prepare(Some(&abs), &[path])?.commit(vec![s.to_json()?.into_bytes()])?;
        Ok(())
    }

    /// Opens a session: its image (checked unchanged), then its job — shapes, parameters,
    /// edits at their frames, where it stopped — driven through a run that records every
    /// frame ([`crate::job::Job::drive`], as `topocontour replay` runs it).
    fn open_session(&mut self, path: &Path) -> Result<(), AppError> {
        if let Some(t) =
            crate::io::tracking_session::TrackingSession::open(path).map_err(AppError::Movie)?
        {
            self.open_tracking_session(t);
            return Ok(());
        }
        let s = crate::io::session::Session::read(path)?;
        let job = s.job(path, None);
        self.open_image(job.image.clone());
        if let Some(e) = self.status.error.take() {
            return Err(e);
        }
        let crc = crate::io::session::file_crc32(&job.image).map_err(|source| AppError::Io {
            path: job.image.clone(),
            source,
        })?;
        if crc != s.image.crc32 {
            return Err(AppError::ImageChanged(job.image));
        }
        if job.page > 0 {
            self.set_page(job.page);
            if let Some(e) = self.status.error.take() {
                return Err(e);
            }
        }
        let doc = &mut self.doc;
        doc.settings.params = job.params.clone();
        doc.settings.mode_chosen = true;
        doc.shapes = job.shapes.clone();
        doc.train = match (&s.strokes, &s.classifier) {
            (Some(st), _) => super::Training::of_strokes(st),
            (None, Some(c)) => super::Training::of_classifier(c.clone()),
            (None, None) => std::mem::take(&mut doc.train),
        };
        if job.pixel_size.is_some() {
            doc.stack.pixel = job.pixel_size.clone();
        }
        let image = doc.image.clone().ok_or(AppError::NoImage)?;
        let (ev, _) = job.start(&image)?;
        let mut run = Run::new(ev);
        job.drive(&mut run)?;
        // The forces on screen are the last ones set on the way.
        let p = run.evolver.params();
        (doc.settings.params.weights, doc.settings.params.step) = (p.weights, p.step);
        doc.shown = run.last();
        doc.run = Some(run);
        // The run read the map of these strokes: its overlay, when it comes, is no change.
        self.doc.taught = job.teach.as_ref().and_then(|_| self.map_key());
        Ok(())
    }

    /// Whether `format` exports the tracked movie frame on screen by track: a tracked
    /// frame does; so too one open for correction (the correction is in the tracking),
    /// but for the outlines, which the run on screen gives.
    fn exports_by_track(&self, format: Format) -> bool {
        self.doc.movie.as_ref().is_some_and(|m| {
            m.tracked_frame().is_some()
                && (self.doc.run.is_none()
                    || (m.correcting.is_some() && matches!(format, Format::Csv | Format::Labels)))
        })
    }

    /// Writes the frame on screen (the evolver's state at it) to `path`.
    fn export(&mut self, format: Format, path: &Path) -> Result<(), AppError> {
        let doc = &self.doc;
        if let Some(m) = doc.movie.as_ref().filter(|_| self.exports_by_track(format)) {
            if let Some(bytes) = self.tracked_export(format, path)? {
                return super::movie::write_beside(&m.movie, path, bytes);
            }
        }
        let (Some(run), Some(image)) = (&doc.run, &doc.image) else {
            return Err(AppError::NothingToExport);
        };
        let ev = run.evolver_at(doc.shown);
        let set = ev.filtered_contours(doc.params().min_area);
        let out = Outputs::of(&ev, &set, &doc.image_name).with_pixel_size(doc.stack.pixel.clone());
        let bytes = format.render(&out, image, path)?;
        OutputFiles::prepare(doc.image_path.as_deref(), &[path])?.commit(vec![bytes])?;
        Ok(())
    }
}
