//! The headless command line (feature `cli`): `topocontour segment …` with the contract
//! of DESIGN.md, `topocontour batch …` over a folder, and `topocontour bench …` that times
//! the whole pipeline in-process. One module per subcommand; `run` holds what they share
//! (the initialisation and parameter flags, and one evolution).

mod batch;
mod bench;
mod run;
mod segment;
pub mod signals;
mod track;
mod train;

pub use crate::io::Format;
pub use batch::{batch, BatchArgs};
pub use bench::{bench, BenchArgs};
pub use run::{
    classifier_for, init_shapes, job_for, mode_of, params_for, run_loaded, teach_for, RunSettings,
};
#[cfg(feature = "gui")]
pub(crate) use segment::counted; // the app words its counts alike
pub use segment::{replay, segment, OutputArgs, ReplayArgs, SegmentArgs};
pub use track::{track, tracker_for, TrackArgs};
pub use train::{classifier_of, train, TrainArgs};

use clap::{Parser, Subcommand};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Polygonal active contours that change topology correctly.
#[derive(Parser, Debug)]
#[command(
    name = "topocontour",
    version,
    about,
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    /// The subcommand; none opens the desktop app.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// An image, or a session saved from the app (`.json`), to open in the desktop app.
    pub image: Option<PathBuf>,
}

/// The headless subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Segment an image headless and write the results.
    Segment(Box<SegmentArgs>),
    /// Run a saved session again, headless, and write its outputs.
    Replay(Box<ReplayArgs>),
    /// Segment every image of a folder with the same settings, in parallel.
    Batch(Box<BatchArgs>),
    /// Time the whole pipeline (load, evolve, export) on case folders.
    Bench(BenchArgs),
    /// Train a pixel classifier on strokes painted on one or more images, for
    /// `segment --classifier` and `batch --classifier`.
    Train(Box<TrainArgs>),
    /// Track cells through a movie (divisions as split events); write the Cell Tracking
    /// Challenge result.
    Track(Box<TrackArgs>),
}

/// A usage error as one line: clap's message spans 3–7 lines (the error with its
/// details, then usage and tips after a blank line); scripts read one.
pub fn usage_line(e: &clap::Error) -> String {
    let rendered = e.to_string();
    let head: Vec<&str> = rendered
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .map(str::trim)
        .collect();
    let text = head.join(" ");
    format!("{} (see --help)", text.trim_start_matches("error: "))
}

/// A failure to report: exit code 2 for bad input, 1 for internal errors.
#[derive(Debug)]
pub struct Failure {
    /// The process exit code.
    pub code: i32,
    /// One line for stderr.
    pub message: String,
}

fn bad(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}

/// Makes the output folder `dir` (`flag` names it in messages) unless it exists; its own
/// folder must exist, as a file output's must: a mistyped path is an error, not a new
/// tree of folders.
fn output_folder(flag: &str, dir: &Path) -> Result<(), Failure> {
    if dir.is_dir() {
        return Ok(());
    }
    let parent = dir
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(bad(format!(
            "{flag} {}: folder {} does not exist",
            dir.display(),
            parent.display()
        )));
    }
    std::fs::create_dir(dir).map_err(|e| {
        bad(format!(
            "{flag} {}: cannot make the folder: {e}",
            dir.display()
        ))
    })
}

/// Writes a line to stderr; a full or closed stderr loses the line, never the run.
/// Control characters (from file names: escape sequences, newlines) are shown escaped,
/// never sent to the terminal raw.
pub fn note(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "topocontour: {}", printable(line));
}

/// `text` with every control character written as `\u{..}`.
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_unicode().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}
