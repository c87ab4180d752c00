//! Tracking sessions: a tracked movie saved from the app and opened again where it was —
//! the movie (its path, relative to the session file as a still's image is, its frames
//! and size), the frame-0 shapes and the tracking settings, every tracked frame's cells
//! with their tracks, the lineage, the frames corrected by hand, and where cells were
//! deleted by hand (no new cell is taken there when the tracking goes on).
//!
//! The result is stored, not re-run: opening is instant, and the corrections, which no
//! re-run could make again, are kept as they were. A movie is not checksummed (a long
//! one is gigabytes); its frame count and size must match. Everything read is checked
//! before use — tracks that exist, frames in order, outlines of finite points inside the
//! frame, settings an evolution accepts — so a damaged or hostile file is one error,
//! never a panic later.

use crate::evolution::params::{check_params, check_shapes};
use crate::evolution::Shape;
use crate::io::movie::Movie;
use crate::track::{Lineage, Track, TrackSettings, TrackedFrame};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The `format` field of a tracking session.
pub const TRACKING_FORMAT: &str = "topocontour-tracking";
/// The version this build writes and reads.
pub const TRACKING_VERSION: u32 = 1;
/// The largest tracking session read: a long movie's outlines are large.
pub const MAX_TRACKING_BYTES: u64 = 1 << 30;

/// The movie a tracking session was made on.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MovieRef {
    /// A multi-page TIFF or a folder (relative: to the session file's folder).
    pub path: PathBuf,
    /// Frames.
    pub frames: usize,
    /// Width of a frame, pixels.
    pub width: usize,
    /// Height of a frame, pixels.
    pub height: usize,
}

/// A saved tracking.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrackingSession {
    /// Always [`TRACKING_FORMAT`].
    pub format: String,
    /// [`TRACKING_VERSION`] of the writer.
    pub version: u32,
    /// The movie.
    pub movie: MovieRef,
    /// The frame on screen (0-based).
    pub shown: usize,
    /// The shapes drawn on frame 0 (none: automatic seeds).
    pub shapes: Vec<Shape>,
    /// The document's parameters (its engine, kind of image, forces).
    pub params: crate::evolution::Params,
    /// How it was tracked (none: not tracked yet).
    pub settings: Option<TrackSettings>,
    /// The frames tracked, from frame 0 on.
    pub frames: Vec<TrackedFrame>,
    /// The tracks, by label.
    pub tracks: Vec<Track>,
    /// The frames corrected by hand.
    pub corrected: Vec<usize>,
    /// The outlines of the cells deleted by hand, where they lie after the last frame
    /// tracked ([`crate::track::Memory::unwanted`]); left out when none, so a session
    /// without deletions reads as before.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unwanted: Vec<Vec<crate::geometry::Point>>,
}

/// What a tracking session holds once checked against its movie.
#[derive(Debug)]
pub struct OpenedTracking {
    /// The movie, opened.
    pub movie: Movie,
    /// The session.
    pub session: TrackingSession,
    /// Its tracks.
    pub lineage: Lineage,
}

/// Whether `bytes` are a tracking session's (its `format` field says so), to tell one
/// from a still's session before parsing either.
pub fn is_tracking_session(bytes: &[u8]) -> bool {
    #[derive(Deserialize)]
    struct Format {
        format: String,
    }
    serde_json::from_slice::<Format>(bytes).is_ok_and(|f| f.format == TRACKING_FORMAT)
}

impl TrackingSession {
    /// The session as JSON written to `session_path` (the movie's path relative to
    /// it); refused when the movie path is not UTF-8.
    pub fn to_json(mut self, session_path: &Path) -> Result<String, String> {
        self.movie.path = super::session::stored_path(session_path, &self.movie.path);
        if self.movie.path.to_str().is_none() {
            return Err(format!(
                "cannot save a session of {}: its path is not valid UTF-8",
                self.movie.path.display()
            ));
        }
        // Compact: a long movie's outlines are many points.
        let json = serde_json::to_string(&self).expect("JSON of plain data with UTF-8 paths");
        if json.len() as u64 > MAX_TRACKING_BYTES {
            return Err(format!(
                "the tracking is {} bytes as a session, more than one can be read back ({MAX_TRACKING_BYTES}): export it (Export CTC…) instead",
                json.len()
            ));
        }
        Ok(json)
    }

    /// Reads the session at `path` and opens its movie, every field checked; None when
    /// the file is no tracking session (a still's, say).
    pub fn open(path: &Path) -> Result<Option<OpenedTracking>, String> {
        let refused = |why: String| format!("{} is not a tracking session: {why}", path.display());
        // A file that cannot be read is left to the still session's reader to report.
        let Ok(bytes) = crate::io::load::read_regular(path, MAX_TRACKING_BYTES) else {
            return Ok(None);
        };
        if !is_tracking_session(&bytes) {
            return Ok(None);
        }
        let s: TrackingSession =
            serde_json::from_slice(&bytes).map_err(|e| refused(e.to_string()))?;
        if s.format != TRACKING_FORMAT || s.version != TRACKING_VERSION {
            return Err(refused(format!(
                "format {} version {}, expected {TRACKING_FORMAT} version {TRACKING_VERSION}",
                s.format, s.version
            )));
        }
        let at = super::session::resolved_path(path, &s.movie.path);
        let movie =
            Movie::open(&at).map_err(|e| format!("cannot open the session's movie: {e}"))?;
        let m = &s.movie;
        if movie.len() != m.frames || movie.size() != (m.width, m.height) {
            return Err(format!(
                "{} changed since the session was saved ({} frames of {}×{} then, {} of {}×{} now)",
                at.display(),
                m.frames,
                m.width,
                m.height,
                movie.len(),
                movie.size().0,
                movie.size().1
            ));
        }
        let lineage = s.check().map_err(refused)?;
        Ok(Some(OpenedTracking {
            movie,
            session: s,
            lineage,
        }))
    }

    /// Checks what the app will read; the tracks as a lineage.
    fn check(&self) -> Result<Lineage, String> {
        let (w, h, n) = (self.movie.width, self.movie.height, self.movie.frames);
        if self.shown >= n {
            return Err(format!("frame {} shown of {n}", self.shown));
        }
        check_shapes(&self.shapes, w, h).map_err(|e| e.to_string())?;
        check_params(&self.params).map_err(|e| e.to_string())?;
        if let Some(st) = &self.settings {
            check_params(&st.params).map_err(|e| e.to_string())?;
            let levels = 1..=crate::image::model::PYRAMID_LEVELS;
            if !levels.contains(&st.levels)
                || st.seed_every == 0
                || !(st.shrink.is_finite() && st.shrink >= 0.0)
            {
                return Err("its tracking settings are out of range".into());
            }
        } else if !self.frames.is_empty() {
            return Err("tracked frames without the settings they were tracked with".into());
        }
        if self.frames.len() > n {
            return Err(format!(
                "{} frames tracked of a movie of {n}",
                self.frames.len()
            ));
        }
        let lineage = Lineage::from_tracks(self.tracks.clone(), self.frames.len())?;
        let known = |label: u32, t: usize| {
            lineage
                .get(label)
                .is_some_and(|k| (k.first..=k.last).contains(&t))
        };
        let inside = |p: &crate::geometry::Point| {
            p.x.is_finite()
                && p.y.is_finite()
                && (0.0..=w as f64).contains(&p.x)
                && (0.0..=h as f64).contains(&p.y)
        };
        for (t, f) in self.frames.iter().enumerate() {
            if f.frame != t {
                return Err(format!("frame {} stored as frame {t}", f.frame));
            }
            for o in &f.objects {
                if !known(o.track, t) {
                    return Err(format!(
                        "frame {t} holds a cell of track {}, which no track lists there",
                        o.track
                    ));
                }
                if o.ring.len() < 3 || !o.ring.iter().all(inside) || !o.area.is_finite() {
                    return Err(format!(
                        "frame {t}: the outline of track {} is not a ring inside the frame",
                        o.track
                    ));
                }
            }
        }
        if let Some(c) = self.corrected.iter().find(|&&c| c >= self.frames.len()) {
            return Err(format!("frame {c} corrected but not tracked"));
        }
        if (self.unwanted.iter()).any(|r| r.len() < 3 || !r.iter().all(inside)) {
            return Err("the outline of a deleted cell is not a ring inside the frame".into());
        }
        Ok(lineage)
    }
}
