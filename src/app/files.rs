//! Files the app writes and reads: exports of the frame on screen and sessions, with
//! the errors a user can meet.

use super::command::{Command, ExportKind};
use super::TopoApp;
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
    /// A 16-bit label image holds 65,535 labels.
    #[error("more than 65,535 objects for a 16-bit label image")]
    TooManyLabels,
    /// The session's image is not the one it was saved with.
    #[error("{} changed since the session was saved", .0.display())]
    ImageChanged(PathBuf),
    /// The image could not be read.
    #[error(transparent)]
    Load(#[from] crate::io::LoadError),
    /// The run could not start.
    #[error(transparent)]
    Evolve(#[from] crate::evolution::EvolveError),
    /// A session could not be read or written.
    #[error(transparent)]
    Session(#[from] crate::io::session::SessionError),
    /// An output could not be written.
    #[error(transparent)]
    Output(#[from] crate::io::OutputError),
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
    /// Writes the session of the frame on screen.
    pub(super) fn save_session(&mut self, path: &Path) -> Result<(), AppError> {
        let (Some(image), Some(image_path)) = (&self.image, &self.image_path) else {
            return Err(AppError::SampleHasNoFile);
        };
        let abs = image_path.canonicalize().map_err(|source| AppError::Io {
            path: image_path.clone(),
            source,
        })?;
        let shown = self.shown;
        let (frames, finished, params, edits) = match self.run.as_mut() {
            Some(run) => {
                // The evolver at the frame on screen: its edits are the ones that led here.
                run.rewind(shown.min(run.history.len() - 1));
                let ev = &run.evolver;
                (
                    ev.frames(),
                    ev.is_finished(),
                    ev.start_params().clone(),
                    ev.edits().to_vec(),
                )
            }
            None => (0, false, self.params(), Vec::new()),
        };
        let s = crate::io::session::Session::new(
            &abs,
            image,
            self.shapes.clone(),
            params,
            frames,
            finished,
        )
        .map_err(|source| AppError::Io {
            path: abs.clone(),
            source,
        })?
        .with_edits(&edits)
        .with_page(self.stack.page)
        .stored_at(path);
        OutputFiles::prepare(Some(&abs), &[path])?.commit(vec![s.to_json()?.into_bytes()])?;
        Ok(())
    }

    /// Opens a session: image, shapes, parameters, then steps to its frame.
    pub(super) fn open_session(&mut self, path: &Path) -> Result<(), AppError> {
        let s = crate::io::session::Session::read(path)?;
        let image_path = s.image_path(path);
        self.apply_now(Command::OpenImage(image_path.clone()));
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let crc = crate::io::session::file_crc32(&image_path).map_err(|source| AppError::Io {
            path: image_path.clone(),
            source,
        })?;
        if crc != s.image.crc32 {
            return Err(AppError::ImageChanged(image_path));
        }
        if s.page > 0 {
            self.apply_now(Command::SetPage(s.page));
            if let Some(e) = self.error.take() {
                return Err(e);
            }
        }
        let p = &s.params;
        self.settings.polarity = p.polarity;
        self.settings.mode = p.mode;
        self.settings.modality = p.modality;
        self.settings.open_holes = p.open_holes;
        self.settings.broad_phase = p.broad_phase;
        self.settings.weights = p.weights;
        self.settings.step = p.step;
        self.settings.min_area = p.min_area;
        self.shapes = s.shapes.clone();
        self.reset_run();
        if !self.ensure_run() {
            return Err(self.error.take().unwrap_or(AppError::NoImage));
        }
        // The edits at their frames, then on to where the session was.
        for edit in &s.edits {
            if edit.frame() > self.shown {
                self.step_frames(edit.frame() - self.shown);
            }
            let at = self.shown;
            let run = self.run.as_mut().expect("ensured");
            let mut failed = None;
            let events = run.edit_at(at, |ev| {
                let before = ev.events().len();
                failed = ev.redo_edit(edit).err();
                ev.events()[before..].iter().map(|e| e.event).collect()
            });
            if let Some(e) = failed {
                return Err(e.into());
            }
            self.log.extend(events.into_iter().map(|e| (at, e)));
            if let crate::evolution::Edit::Forces { weights, step, .. } = *edit {
                self.settings.weights = weights;
                self.settings.step = step;
            }
        }
        if s.frames > self.shown {
            self.step_frames(s.frames - self.shown);
        }
        Ok(())
    }

    /// Writes the frame on screen (the evolver's state at it) to `path`.
    pub(super) fn export(&mut self, kind: ExportKind, path: &Path) -> Result<(), AppError> {
        let Some(run) = self.run.as_mut() else {
            return Err(AppError::NothingToExport);
        };
        run.rewind(self.shown.min(run.history.len() - 1));
        let ev = &run.evolver;
        let set = ev.filtered_contours(self.settings.min_area);
        let out = Outputs::of(ev, &set, &self.image_name).with_pixel_size(self.stack.pixel.clone());
        let bytes = match kind {
            ExportKind::Svg => out.svg().into_bytes(),
            ExportKind::GeoJson => out.geojson().into_bytes(),
            ExportKind::Mask => out.mask_png(),
            ExportKind::Csv => out.csv().into_bytes(),
            ExportKind::Labels => out.labels_image(true).ok_or(AppError::TooManyLabels)?,
            ExportKind::Roi => crate::io::roi::roi_zip(out.set),
        };
        OutputFiles::prepare(self.image_path.as_deref(), &[path])?.commit(vec![bytes])?;
        Ok(())
    }
}
