//! Session files: everything needed to reproduce a segmentation headless, identically —
//! the image (path, size and CRC-32 of its bytes, so a changed image is refused), the
//! shapes the evolution started from (automatic seeds as the seeds they became), the
//! parameters, the user's edits on the way (force changes, hand drags, deletions, each
//! at its frame), and how far it ran. JSON, versioned; a relative image path is relative to
//! the session file's folder, so a folder of images and sessions can move as a whole.
//!
//! The engine is deterministic: the same image, shapes and parameters give the same
//! contours frame by frame, so a replay equals the run that saved the session (the
//! JSON output is byte-identical; tests/cli.rs checks it).

use crate::evolution::{Edit, EvolveError, Evolver, Field, Params, Shape};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The `format` field of every session file.
pub const FORMAT: &str = "topocontour-session";
/// The version this build writes and reads.
pub const VERSION: u32 = 1;

/// The image a session was made on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ImageRef {
    /// As given when the session was saved (relative: to the session file's folder).
    pub path: PathBuf,
    /// Width and height in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// CRC-32 of the file's bytes.
    pub crc32: u32,
}

/// A saved segmentation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Session {
    /// Always [`FORMAT`].
    pub format: String,
    /// [`VERSION`] of the writer.
    pub version: u32,
    /// The image.
    pub image: ImageRef,
    /// The initial shapes.
    pub shapes: Vec<Shape>,
    /// The parameters.
    pub params: Params,
    /// Frames the evolution ran.
    pub frames: usize,
    /// The evolution ran to its end (converged or out of frames), not stopped at a
    /// frame chosen by the user.
    pub finished: bool,
    /// The user's interventions (force changes, hand drags, deletions) at their frames.
    #[serde(default)]
    pub edits: Vec<Edit>,
    /// The page of a multi-page TIFF the run segmented (0-based).
    #[serde(default)]
    pub page: usize,
}

/// Why a session cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// Not JSON of a session, or of another version.
    #[error("{0} is not a topocontour session: {1}")]
    Format(PathBuf, String),
    /// The image cannot be read.
    #[error("cannot read the session's image {0}: {1}")]
    Image(PathBuf, String),
    /// The image is not the one the session was made on.
    #[error("{0} changed since the session was saved (size or checksum differ)")]
    Changed(PathBuf),
    /// The evolution refused the saved shapes or parameters.
    #[error("the session cannot start: {0}")]
    Evolve(#[from] EvolveError),
}

/// CRC-32 of a file's bytes.
pub fn file_crc32(path: &Path) -> std::io::Result<u32> {
    Ok(crc32fast::hash(&std::fs::read(path)?))
}

impl Session {
    /// A session of a run from `shapes` with `params` on the image at `path`.
    pub fn new(
        path: &Path,
        image: &Field,
        shapes: Vec<Shape>,
        params: Params,
        frames: usize,
        finished: bool,
    ) -> std::io::Result<Self> {
        Ok(Session {
            format: FORMAT.into(),
            version: VERSION,
            image: ImageRef {
                path: path.to_path_buf(),
                width: image.width,
                height: image.height,
                crc32: file_crc32(path)?,
            },
            shapes,
            params,
            frames,
            finished,
            edits: Vec::new(),
            page: 0,
        })
    }

    /// The session with the user's `edits` (the parameters are the run's first ones).
    pub fn with_edits(mut self, edits: &[Edit]) -> Self {
        self.edits = edits.to_vec();
        self
    }

    /// The session of page `page` (0-based) of a multi-page TIFF.
    pub fn with_page(mut self, page: usize) -> Self {
        self.page = page;
        self
    }

    /// The session as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("JSON of plain data")
    }

    /// Reads a session file.
    pub fn read(path: &Path) -> Result<Self, SessionError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SessionError::Format(path.into(), e.to_string()))?;
        let s: Session = serde_json::from_str(&text)
            .map_err(|e| SessionError::Format(path.into(), e.to_string()))?;
        if s.format != FORMAT || s.version != VERSION {
            return Err(SessionError::Format(
                path.into(),
                format!(
                    "format {} version {}, expected {FORMAT} version {VERSION}",
                    s.format, s.version
                ),
            ));
        }
        Ok(s)
    }

    /// Where the image is, for a session read from `session_path`.
    pub fn image_path(&self, session_path: &Path) -> PathBuf {
        if self.image.path.is_absolute() {
            self.image.path.clone()
        } else {
            session_path
                .parent()
                .unwrap_or(Path::new("."))
                .join(&self.image.path)
        }
    }

    /// Loads the image (checking it is the session's) and runs the evolution as far as
    /// the session did; returns the evolver and the image.
    pub fn replay(&self, session_path: &Path) -> Result<(Evolver, Field), SessionError> {
        let path = self.image_path(session_path);
        let (image, _) = crate::io::load_image_page(&path, self.page)
            .map_err(|e| SessionError::Image(path.clone(), e.to_string()))?;
        let crc =
            file_crc32(&path).map_err(|e| SessionError::Image(path.clone(), e.to_string()))?;
        if crc != self.image.crc32
            || image.width != self.image.width
            || image.height != self.image.height
        {
            return Err(SessionError::Changed(path));
        }
        let mut ev = Evolver::new(&image, &self.shapes, self.params.clone())?;
        for edit in &self.edits {
            while ev.frames() < edit.frame() && !ev.is_finished() {
                ev.step();
            }
            ev.redo_edit(edit)?;
        }
        if self.finished {
            ev.run();
        } else {
            while ev.frames() < self.frames && !ev.is_finished() {
                ev.step();
            }
        }
        Ok((ev, image))
    }
}
