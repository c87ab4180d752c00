//! What is not the document: how it is looked at ([`ViewState`]: tool, selection,
//! playback, zoom, caches of what is drawn), the preferences kept between launches
//! ([`Prefs`]), and the status bar's messages ([`Status`]). None of it is undone.

use super::command::Tool;
use super::path_prompt::PathPrompt;
use super::{canvas, objects};
use std::path::PathBuf;

/// Preferences kept between launches (eframe persistence). What a run does is the
/// document's ([`super::Settings`]), reset for each image.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Prefs {
    /// Frames per second while playing.
    pub speed: f32,
    /// The canvas tool.
    pub tool: Tool,
    /// Fill regions on the canvas.
    pub show_fill: bool,
    /// Radius of the brush, image pixels.
    pub brush_radius: f64,
    /// The folder of the last file opened.
    pub last_dir: Option<PathBuf>,
    /// The label the Train tool paints: 1 background, 2 object, 3 boundary, 0 erase.
    pub train_label: u8,
    /// The probability map shows over the image.
    pub show_probabilities: bool,
}

impl Default for Prefs {
    fn default() -> Self {
        Prefs {
            speed: 30.0,
            tool: Tool::Seed,
            show_fill: true,
            brush_radius: 8.0,
            last_dir: None,
            train_label: crate::learn::OBJECT,
            show_probabilities: true,
        }
    }
}

/// The smallest and largest brush radius, image pixels.
pub const BRUSH_RADIUS: std::ops::RangeInclusive<f64> = 1.0..=100.0;

/// How the document is looked at.
#[derive(Default)]
pub struct ViewState {
    /// The preferences.
    pub prefs: Prefs,
    /// The selected shape.
    pub selected: Option<usize>,
    /// The contour selected with the Edit tool or in the object table (its measurements
    /// show in the status bar, its row in the table).
    pub selected_contour: Option<u32>,
    /// Playback is running.
    pub playing: bool,
    /// The movie's frames are playing (apart from the evolution's playing).
    pub movie_playing: bool,
    /// Seconds since the movie's last frame advanced.
    pub(super) movie_clock: f64,
    pub(super) play_clock: f64,
    /// The help window is open.
    pub show_help: bool,
    /// The built-in path field, when a file dialog gave no path.
    pub path_prompt: Option<PathPrompt>,
    pub(super) canvas: canvas::CanvasState,
    /// The image as a texture, and the image and contrast window it shows.
    pub(super) texture: Option<Texture>,
    /// The object table's rows, measured once per frame shown.
    pub(super) objects: objects::ObjectTable,
    /// The tracks of a correction's cells, measured once per frame shown.
    pub(super) correction_tracks: super::correct::CorrectionTracks,
    /// The window title last sent.
    pub(super) title: String,
    /// The track selected in the lineage view or the division log.
    pub selected_track: Option<u32>,
    /// While tracking, the movie slider follows the frame just tracked (until the user
    /// moves it).
    pub follow_tracking: bool,
    /// A question the user must answer before work of theirs is replaced.
    pub question: Option<Question>,
    /// The user chose to quit without saving: the window closes without asking again.
    pub quit_confirmed: bool,
    /// The file asked to be opened over work not saved ([`Question::Open`]): opened if
    /// the user answers Open without saving; after Save session… it is asked for again.
    pub pending_open: Option<super::Command>,
    /// The user chose to open it without saving.
    pub open_confirmed: bool,
    /// Frames of the movie read so far.
    pub(super) frames: super::movie::FrameCache,
    /// The window's context, to wake it from background threads.
    pub(super) egui_ctx: Option<egui::Context>,
}

/// The image on the GPU.
pub(super) struct Texture {
    pub handle: egui::TextureHandle,
    /// The image it was made from (by address) and the contrast window.
    pub of: (usize, (f32, f32)),
}

/// A question asked before work of the user's is replaced (nothing is lost without
/// asking).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Question {
    /// The correction of frame `frame` tracks the frames after it again, which replaces
    /// the corrections on frames `later`.
    Retrack {
        /// The frame corrected.
        frame: usize,
        /// Later frames the user corrected.
        later: Vec<usize>,
    },
    /// Tracking again from frame 0 replaces the corrections on these frames.
    TrackAgain(Vec<usize>),
    /// The window was asked to close with work not saved (what, in a sentence).
    Quit(String),
    /// A file was asked to be opened over work not saved (what, in a sentence): Undo
    /// would bring the work back, but a user need not know that.
    Open(String),
}

/// What the status bar says.
#[derive(Default)]
pub struct Status {
    /// The last error, shown until the next one or a success.
    pub error: Option<super::AppError>,
    /// The last notice (what just happened).
    pub notice: Option<String>,
    /// Time of the last frame step, ms.
    pub step_ms: f64,
    /// Time spent drawing the canvas last frame, ms.
    pub draw_ms: f64,
    /// The hint on keeping touching objects apart was given (it is given once).
    pub(super) merge_hint_given: bool,
}

impl Status {
    /// Says what just happened; an earlier error gives way to it (the newest message
    /// is the one shown, so a success after a failure is not hidden behind it).
    pub fn notify(&mut self, text: String) {
        self.error = None;
        self.notice = Some(text);
    }
}
