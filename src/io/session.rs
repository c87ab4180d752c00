//! Session files: everything needed to reproduce a segmentation headless, identically —
//! the image (path, size and CRC-32 of its bytes, so a changed image is refused), the
//! shapes the evolution started from (automatic seeds as the seeds they became), the
//! parameters, the user's edits on the way (force changes, hand drags, deletions, each
//! at its frame), and how far it ran: a [`Job`] plus a checked reference to its image.
//!
//! The image path is stored relative to the session file's folder (`../images/a.tif`), so a
//! folder of images and sessions can move as a whole; it is absolute only when the two
//! share no folder but the root (another drive, or `/tmp` against `/home/…`), where a
//! relative path would climb to the root and break on any move. `replay --image PATH`
//! points at a moved image; the size and checksum still refuse a changed one.
//!
//! JSON, versioned. Version 1 is still the only one: earlier builds wrote the same fields
//! with an absolute path, which reads as before, and they read relative paths the same
//! way, so no file needs converting. Unknown keys are refused (a typo is an error, not a
//! silent default).
//!
//! A taught run ([`crate::learn::Teach`]) stores what taught it: the strokes, as runs
//! ([`Strokes`]' serde form, a few kilobytes), from which the replay trains the same
//! seeded forest again; or the classifier it was given, whole (a classifier trained
//! elsewhere cannot be made again from this image).
//!
//! The engine is deterministic: the same image, shapes and parameters give the same
//! contours frame by frame, so a replay equals the run that saved the session (the
//! JSON output is byte-identical; tests/cli.rs checks it).

use crate::evolution::{Edit, EvolveError, Params, Shape};
use crate::image::Gray;
use crate::io::PixelSize;
use crate::job::{Job, JobError, JobRun, Stop};
use crate::learn::{Classifier, Strokes, Teach};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The `format` field of every session file.
pub const FORMAT: &str = "topocontour-session";
/// The version this build writes and reads.
pub const VERSION: u32 = 1;
/// The largest session file read (about half a million edits).
pub const MAX_SESSION_BYTES: u64 = 64 << 20;

/// The image a session was made on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
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
#[serde(deny_unknown_fields)]
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
    /// The pixel size the run was given (none: the file's, if it records one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pixel_size: Option<PixelSize>,
    /// The strokes a taught run was trained on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub strokes: Option<Strokes>,
    /// The classifier a taught run was given (not trained on `strokes`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub classifier: Option<Classifier>,
}

/// Why a session cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// Not JSON of a session, or of another version.
    #[error("{0} is not a topocontour session: {1}")]
    Format(PathBuf, String),
    /// The app's tracking of a movie, not a still image's session.
    #[error("{0} is the tracking of a movie: the app opens it (topocontour FILE); this takes the session of a still image")]
    Tracking(PathBuf),
    /// The image cannot be read.
    #[error("cannot read the session's image {0}: {1}")]
    Image(PathBuf, String),
    /// The image is not the one the session was made on.
    #[error("{0} changed since the session was saved (size or checksum differ)")]
    Changed(PathBuf),
    /// The evolution refused the saved shapes or parameters.
    #[error("the session cannot start: {0}")]
    Evolve(#[from] EvolveError),
    /// The strokes or classifier the session holds cannot teach the run.
    #[error("the session's {0}")]
    Teach(String),
    /// A session stores its image path as text (JSON).
    #[error("cannot save a session of {}: its path is not valid UTF-8", .0.display())]
    PathNotUtf8(PathBuf),
}

/// CRC-32 of a file's bytes.
pub fn file_crc32(path: &Path) -> std::io::Result<u32> {
    Ok(crc32fast::hash(&std::fs::read(path)?))
}

/// `target` relative to the folder `base` (both absolute), or `None` when they share no
/// folder but the root (or the drive differs): a relative path would climb to the root.
fn relative_to(base: &Path, target: &Path) -> Option<PathBuf> {
    use std::path::Component;
    let b: Vec<Component> = base.components().collect();
    let t: Vec<Component> = target.components().collect();
    let common = b.iter().zip(&t).take_while(|(x, y)| x == y).count();
    let root = b
        .iter()
        .take_while(|c| matches!(c, Component::Prefix(_) | Component::RootDir))
        .count();
    if common <= root {
        return None;
    }
    let mut rel: PathBuf = b[common..].iter().map(|_| Component::ParentDir).collect();
    rel.extend(&t[common..]);
    Some(rel)
}

/// `target` as a session file at `session_path` stores it: relative to the session
/// file's folder, or absolute where a relative path would climb to the root (see the
/// module docs). A path that cannot be resolved stays as it is.
pub(crate) fn stored_path(session_path: &Path, target: &Path) -> PathBuf {
    let folder = match session_path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    match (folder.canonicalize(), target.canonicalize()) {
        (Ok(base), Ok(t)) => relative_to(&base, &t).unwrap_or(t),
        _ => target.to_path_buf(),
    }
}

/// Where a path `stored` in the session file at `session_path` points.
pub(crate) fn resolved_path(session_path: &Path, stored: &Path) -> PathBuf {
    if stored.is_absolute() {
        stored.to_path_buf()
    } else {
        session_path.parent().unwrap_or(Path::new(".")).join(stored)
    }
}

impl Session {
    /// A session of a run from `shapes` with `params` on the image at `path` (stored as
    /// given; [`Session::stored_at`] makes it relative to the session file).
    pub fn new(
        path: &Path,
        image: &dyn Gray,
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
                width: image.size().0,
                height: image.size().1,
                crc32: file_crc32(path)?,
            },
            shapes,
            params,
            frames,
            finished,
            edits: Vec::new(),
            page: 0,
            pixel_size: None,
            strokes: None,
            classifier: None,
        })
    }

    /// The session of `job`'s run: the shapes it started from (automatic seeds as the
    /// seeds they became), its first parameters (a taught run: the job's, which the
    /// replay reads the probabilities with again), its edits, where it stopped, what
    /// taught it.
    pub fn of_run(job: &Job, run: &JobRun) -> std::io::Result<Self> {
        let ev = &run.ev;
        let params = match job.teach {
            Some(_) => job.params.clone(),
            None => ev.start_params().clone(),
        };
        let (strokes, classifier) = match &job.teach {
            Some(Teach::Strokes(s)) => (Some(Strokes::clone(s)), None),
            Some(Teach::Classifier(c)) => (None, Some(Classifier::clone(c))),
            None => (None, None),
        };
        let s = Session::new(
            &job.image,
            &run.image,
            run.shapes.clone(),
            params,
            ev.frames(),
            job.stop == Stop::Finished,
        )?;
        Ok(Session {
            edits: ev.edits().to_vec(),
            page: run.page,
            pixel_size: job.pixel_size.clone(),
            strokes,
            classifier,
            ..s
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

    /// The session as it is written to `session_path`: the image path relative to the
    /// session file's folder, or absolute where a relative one would climb to the root
    /// (see the module docs). A path that cannot be resolved stays as it is.
    pub fn stored_at(mut self, session_path: &Path) -> Self {
        self.image.path = stored_path(session_path, &self.image.path);
        self
    }

    /// The session as pretty JSON (refused when the image path is not UTF-8).
    pub fn to_json(&self) -> Result<String, SessionError> {
        if self.image.path.to_str().is_none() {
            return Err(SessionError::PathNotUtf8(self.image.path.clone()));
        }
        Ok(serde_json::to_string_pretty(self).expect("JSON of plain data with UTF-8 paths"))
    }

    /// Reads a session file.
    pub fn read(path: &Path) -> Result<Self, SessionError> {
        use crate::io::load::{read_regular, Unread};
        let refused = |why: String| SessionError::Format(path.into(), why);
        let bytes = read_regular(path, MAX_SESSION_BYTES).map_err(|e| match e {
            Unread::Io(e) => refused(e.to_string()),
            Unread::NotAFile => refused("not a regular file".into()),
            Unread::TooLarge(n) => refused(format!(
                "{n} bytes, more than any session ({MAX_SESSION_BYTES})"
            )),
        })?;
        Self::parse(&bytes, path)
    }

    /// A session from the bytes of a file (`path` names it in errors): UTF-8 JSON of
    /// this format and version, no unknown keys.
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, SessionError> {
        let refused = |why: String| SessionError::Format(path.into(), why);
        let text = std::str::from_utf8(bytes).map_err(|_| refused("not UTF-8 text".into()))?;
        let s: Session = serde_json::from_str(text).map_err(|e| {
            // The app saves the tracking of a movie as a session of its own.
            let movie = serde_json::from_str::<serde_json::Value>(text)
                .is_ok_and(|v| v.get("movie").is_some());
            if movie {
                SessionError::Tracking(path.into())
            } else {
                refused(e.to_string())
            }
        })?;
        if s.format != FORMAT || s.version != VERSION {
            return Err(SessionError::Format(
                path.into(),
                format!(
                    "format {} version {}, expected {FORMAT} version {VERSION}",
                    s.format, s.version
                ),
            ));
        }
        if s.strokes.is_some() && s.classifier.is_some() {
            return Err(refused(
                "it holds both strokes and a classifier; a run is taught by one".into(),
            ));
        }
        Ok(s)
    }

    /// Where the image is, for a session read from `session_path`.
    pub fn image_path(&self, session_path: &Path) -> PathBuf {
        resolved_path(session_path, &self.image.path)
    }

    /// The job this session records, on the image at `image` (a moved image) or, with
    /// `None`, where the session says it is.
    pub fn job(&self, session_path: &Path, image: Option<&Path>) -> Job {
        Job {
            image: image.map_or_else(|| self.image_path(session_path), Path::to_path_buf),
            page: self.page,
            shapes: self.shapes.clone(),
            auto_seeds: false,
            params: self.params.clone(),
            edits: self.edits.clone(),
            stop: if self.finished {
                Stop::Finished
            } else {
                Stop::AtFrame(self.frames)
            },
            pixel_size: self.pixel_size.clone(),
            teach: match (&self.strokes, &self.classifier) {
                (Some(s), _) => Some(Teach::strokes(s.clone())),
                (None, Some(c)) => Some(Teach::classifier(c.clone())),
                (None, None) => None,
            },
        }
    }

    /// Loads the image (checking it is the session's) and runs the session's job as far
    /// as the session did.
    pub fn replay(
        &self,
        session_path: &Path,
        image: Option<&Path>,
    ) -> Result<JobRun, SessionError> {
        let job = self.job(session_path, image);
        let path = job.image.clone();
        let unreadable = |e: String| SessionError::Image(path.clone(), e);
        let (field, info) = job.load().map_err(|e| unreadable(e.to_string()))?;
        let crc = file_crc32(&path).map_err(|e| unreadable(e.to_string()))?;
        if crc != self.image.crc32
            || field.width != self.image.width
            || field.height != self.image.height
        {
            return Err(SessionError::Changed(path));
        }
        job.run_on(field, info).map_err(|e| match e {
            JobError::Evolve(e) => SessionError::Evolve(e),
            JobError::Teach(e) => SessionError::Teach(match self.strokes {
                Some(_) => format!("strokes cannot be used: {e}"),
                None => format!("classifier cannot be used: {e}"),
            }),
            other => SessionError::Image(path.clone(), other.to_string()),
        })
    }
}
