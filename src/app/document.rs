//! The document: what the user makes and what Undo restores — the image (and its page),
//! the shapes, the run's settings (the engine's [`Params`] themselves), the runs with
//! their edits, and the frame on screen. Views read it; only commands change it
//! ([`super::TopoApp::apply`]), and an undo step is a whole `Document`.

use super::run::{FrameRecord, Run};
use crate::evolution::{Field, Mode, Params, Shape};
use std::path::PathBuf;
use std::sync::Arc;

/// The document.
#[derive(Clone, Default)]
pub struct Document {
    /// The image's name as the title shows it.
    pub image_name: String,
    /// The file the image came from (none for the bundled sample): exports never replace it.
    pub image_path: Option<PathBuf>,
    /// The image.
    pub image: Option<Arc<Field>>,
    /// The page of a stack on screen, and the pixel size.
    pub stack: ImageStack,
    /// The initialisation: the user's shapes.
    pub shapes: Vec<Shape>,
    /// The shapes are the sample's wrap rectangle, as it opened: labelled on the canvas,
    /// replaced by the first seed the user adds.
    pub sample_wrap: bool,
    /// Find seeds placed seeds on this image: Apply to folder finds them per image too.
    pub found_seeds: bool,
    /// The run's settings.
    pub settings: Settings,
    /// The run on screen.
    pub run: Option<Run>,
    /// The second engine's run in the side-by-side view (same frames as `run`).
    pub run_b: Option<Run>,
    /// The recorded frame on screen.
    pub shown: usize,
    /// The movie the image is a frame of, with what tracking found.
    pub movie: Option<super::MovieDoc>,
    /// The Train tool's strokes and the classifier loaded.
    pub train: super::Training,
    /// The probability map the run on screen reads (none: it reads the image).
    pub taught: Option<super::train::Key>,
    /// The file whose opening made this document over work not saved (that work is in
    /// Undo): closing says so, not only what this document lacks. Undo and Redo carry it
    /// with the document.
    pub replaced: Option<String>,
}

/// The settings of a document's run: reset for every image opened (each image has its own
/// kind, polarity and engine), kept with its undo steps and its sessions.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// The parameters of the run (engine, polarity, kind of image, forces, minimum area…).
    pub params: Params,
    /// The engine shown side by side with `params.mode`, if any.
    pub compare: Option<Mode>,
    /// Contrast window (low, high) of the image on screen.
    pub contrast: (f32, f32),
    /// Whether the user (or a session) chose the engine; until then a taught run takes
    /// the command line's default for it ([`Mode::default_for`]).
    pub mode_chosen: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            params: Params::default(),
            compare: None,
            contrast: (0.0, 1.0),
            mode_chosen: false,
        }
    }
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

impl Document {
    /// Whether the user's shapes are drawn: not on a tracked movie frame after frame 0,
    /// since they started frame 0 (drawn where the cells were then, they looked like
    /// cells that are not there).
    pub fn shapes_shown(&self) -> bool {
        self.movie
            .as_ref()
            .is_none_or(|m| m.frame == 0 || m.tracked_frame().is_none())
    }

    /// A document on `field` named `name`, with default settings and the image's own
    /// contrast window.
    pub fn of_image(field: Field, name: String) -> Self {
        // Each image opens with its own contrast window: 16-bit data that fills 12 bits
        // would otherwise open black.
        let mut settings = Settings {
            contrast: super::auto_contrast(&field),
            ..Settings::default()
        };
        // Mostly dark background: the cells are the bright objects (a fluorescence movie
        // tracked as dark objects tracked its background).
        if crate::image::modality::looks_bright_on_dark(&field) {
            settings.params.polarity = crate::evolution::Polarity::Bright;
        }
        Document {
            image: Some(Arc::new(field)),
            image_name: name,
            settings,
            stack: ImageStack {
                pages: 1,
                ..ImageStack::default()
            },
            ..Document::default()
        }
    }

    /// The parameters of the run.
    pub fn params(&self) -> &Params {
        &self.settings.params
    }

    /// The last frame either run recorded.
    pub fn last_frame(&self) -> usize {
        let last = |r: &Option<Run>| r.as_ref().map_or(0, Run::last);
        last(&self.run).max(last(&self.run_b))
    }

    /// The record on screen, if a run exists (the last one, once the run converged before
    /// the side-by-side engine).
    pub fn shown_record(&self) -> Option<&FrameRecord> {
        self.run
            .as_ref()
            .map(|r| &r.history[self.shown.min(r.last())])
    }

    /// The side-by-side engine's record for the frame on screen.
    pub fn shown_record_b(&self) -> Option<&FrameRecord> {
        self.run_b
            .as_ref()
            .map(|r| &r.history[self.shown.min(r.last())])
    }

    /// The event log: every topology event of the run's recorded frames, with its frame.
    pub fn events(&self) -> Vec<(usize, crate::topology::TopologyEvent)> {
        self.run
            .as_ref()
            .map_or(Vec::new(), |r| r.events().map(|(f, &e)| (f, e)).collect())
    }

    /// Drops the runs (the shapes or a parameter they started from changed).
    pub(super) fn drop_runs(&mut self) {
        self.run = None;
        self.run_b = None;
        self.shown = 0;
    }

    /// Shows the next frame: a recorded one, or one more computed by each run that has
    /// not finished. False when neither run has a frame after the one on screen.
    pub(super) fn advance(&mut self) -> bool {
        let next = self.shown + 1;
        let mut moved = false;
        for run in [self.run.as_mut(), self.run_b.as_mut()]
            .into_iter()
            .flatten()
        {
            if next <= run.last() {
                moved = true;
            } else if run.last() == self.shown && !run.evolver.is_finished() {
                run.step();
                moved = true;
            }
        }
        if moved {
            self.shown = next;
        }
        moved
    }
}
