//! [`Job`]: "segment one image", written once. A job names the image and its page, the
//! shapes to start from and/or automatic seeds, the [`Params`], the user's edits at their
//! frames and where to stop; [`Job::run`] loads, seeds, evolves, replays the edits and
//! filters the clutter (seed 003 §4), and returns what the run produced ([`JobRun`]).
//!
//! `segment`, `batch`, `replay` and a folder run ([`crate::io::folder`]) all go through
//! it, so pages, pixel size and automatic seeds mean the same everywhere. A front end
//! that shows every frame (the app) builds the evolver with [`Job::start`] and lets
//! [`Job::drive`] step its own [`Steps`] (which records history) through the same edits
//! and stop rule.
//!
//! A job over many images is a template: [`Job::with_image`] points it at each one, and
//! with `auto_seeds` the seeds are found in *that* image (never carried over from
//! another one: objects differ, and so may the size). The engine is deterministic, so
//! the same job on the same image gives the same contours frame by frame; a session
//! ([`crate::io::session`]) is a job plus a checked reference to its image.

use crate::evolution::{find_seeds, Edit, EvolveError, Evolver, Field, Params, Polarity, Shape};
use crate::image::Stored;
use crate::io::{load_image_page, ImageInfo, LoadError, PixelSize};
use crate::learn::guide::{self, Guide};
use crate::learn::{Taught, Teach, TeachError};
use std::borrow::Cow;
use std::path::PathBuf;
use std::sync::Arc;

/// What [`Job::start_from`] returns: the evolver, the shapes it started from, what
/// taught it, and the image kept compactly when it was given.
type Started = (Evolver, Vec<Shape>, Option<Taught>, Option<Stored>);

/// Where a run stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// At its end: converged, or out of frames (`Params::max_frames`).
    Finished,
    /// After this many frames (or earlier, at its end): a run the user paused.
    AtFrame(usize),
}

/// One segmentation of one image, everything that decides its result.
#[derive(Clone, Debug)]
pub struct Job {
    /// The image file.
    pub image: PathBuf,
    /// The page of a multi-page TIFF (0-based).
    pub page: usize,
    /// The shapes the evolution starts from (clipped to the image).
    pub shapes: Vec<Shape>,
    /// Add one seed per object found in the image (distance-transform maxima of the local
    /// threshold, [`find_seeds`]).
    pub auto_seeds: bool,
    /// The parameters the run starts with.
    pub params: Params,
    /// The user's edits, in order, each made again at its frame.
    pub edits: Vec<Edit>,
    /// Where to stop.
    pub stop: Stop,
    /// The physical size of a pixel; `None`: what the file records, if anything.
    pub pixel_size: Option<PixelSize>,
    /// Strokes painted on the image, or a trained pixel classifier: the run reads the
    /// classifier's probabilities instead of the intensity ([`crate::learn::guide`]).
    pub teach: Option<Teach>,
}

/// What a job produced.
pub struct JobRun {
    /// The evolver at the stop, small regions and holes dropped (`Params::min_area`).
    pub ev: Evolver,
    /// The image (the job's page), kept compactly once the model is prepared.
    pub image: Stored,
    /// The shapes the evolution started from, automatic seeds included.
    pub shapes: Vec<Shape>,
    /// The pixel size: the job's, or the file's.
    pub pixel: Option<PixelSize>,
    /// The page segmented (0-based).
    pub page: usize,
    /// Pages in the file.
    pub pages: usize,
    /// With a [`Job::teach`]: the classifier and its probabilities on the image.
    pub taught: Option<Taught>,
    /// Objects dropped as smaller than `Params::min_area`.
    pub dropped: usize,
}

/// Why a job cannot run.
#[derive(Debug, thiserror::Error)]
pub enum JobError {
    /// The image cannot be read.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// Automatic seeds were the only initialisation and found nothing.
    #[error("automatic seeds found no {} object in {}", polarity_word(*.polarity), .path.display())]
    NoSeeds {
        /// The image.
        path: PathBuf,
        /// The objects looked for.
        polarity: Polarity,
    },
    /// The evolution refused the shapes, parameters or an edit.
    #[error(transparent)]
    Evolve(#[from] EvolveError),
    /// The strokes or the classifier cannot be used.
    #[error(transparent)]
    Teach(#[from] TeachError),
}

fn polarity_word(p: Polarity) -> &'static str {
    match p {
        Polarity::Dark => "dark",
        Polarity::Bright => "bright",
    }
}

/// What [`Job::drive`] steps: the evolver itself, or a front end's run that records
/// every frame it steps.
pub trait Steps {
    /// Frames done.
    fn frames(&self) -> usize;
    /// Converged or out of frames.
    fn is_finished(&self) -> bool;
    /// One frame.
    fn step(&mut self);
    /// On to the end.
    fn run(&mut self);
    /// Makes `edit` again, at the current frame.
    fn edit(&mut self, edit: &Edit) -> Result<(), EvolveError>;
}

impl Steps for Evolver {
    fn frames(&self) -> usize {
        Evolver::frames(self)
    }
    fn is_finished(&self) -> bool {
        Evolver::is_finished(self)
    }
    fn step(&mut self) {
        Evolver::step(self);
    }
    fn run(&mut self) {
        Evolver::run(self)
    }
    fn edit(&mut self, edit: &Edit) -> Result<(), EvolveError> {
        self.redo_edit(edit)
    }
}

impl Job {
    /// A job on `image` (page 0) from `shapes` with `params`, run to its end, no edits.
    pub fn new(image: impl Into<PathBuf>, shapes: Vec<Shape>, params: Params) -> Self {
        Job {
            image: image.into(),
            page: 0,
            shapes,
            auto_seeds: false,
            params,
            edits: Vec::new(),
            stop: Stop::Finished,
            pixel_size: None,
            teach: None,
        }
    }

    /// The same job on another image (a template applied to each image of a folder).
    pub fn with_image(&self, image: impl Into<PathBuf>) -> Self {
        Job {
            image: image.into(),
            ..self.clone()
        }
    }

    /// Reads the job's page of its image, with what the file says about it.
    pub fn load(&self) -> Result<(Field, ImageInfo), JobError> {
        Ok(load_image_page(&self.image, self.page)?)
    }

    /// The evolver at frame 0 on `image` (the job's page, loaded), and the shapes it
    /// starts from: the job's, then the seeds found in this image when asked for.
    pub fn start(&self, image: &Field) -> Result<(Evolver, Vec<Shape>), JobError> {
        self.start_taught(image).map(|(ev, shapes, _)| (ev, shapes))
    }

    /// [`Job::start`], and what teaching gave when the job is taught: with strokes the
    /// classifier trained here (seeded: the same strokes give the same forest), else
    /// the one given; the run reads its probabilities, and automatic seeds are the
    /// connected interiors of its object class ([`guide::seeds`]). In a run whose
    /// topology adapts, a rectangle or disk holding two or more of those interiors
    /// gives way to them ([`guide::start_shapes`]).
    pub fn start_taught(
        &self,
        image: &Field,
    ) -> Result<(Evolver, Vec<Shape>, Option<Taught>), JobError> {
        let (ev, shapes, taught, _) = self.start_from(Cow::Borrowed(image))?;
        Ok((ev, shapes, taught))
    }

    /// [`Job::start_taught`]; given the image itself, it also returns it kept compactly
    /// ([`Evolver::keeping`]).
    fn start_from(&self, image: Cow<Field>) -> Result<Started, JobError> {
        let mut shapes = self.shapes.clone();
        let taught = match &self.teach {
            Some(t) => Some(t.apply(&image, &crate::io::folder::file_name(&self.image))?),
            None => None,
        };
        let guide = taught
            .as_ref()
            .map(|t| Guide::new(t.probabilities.clone(), &self.params));
        let found = match &guide {
            Some(g) if self.auto_seeds || guide::gives_way(self.params.mode) => {
                guide::interiors(&g.probabilities)
            }
            _ => Vec::new(),
        };
        let mut taken = vec![false; found.len()];
        if guide.is_some() && guide::gives_way(self.params.mode) {
            (shapes, taken) = guide::start_shapes(&shapes, &found);
        }
        if self.auto_seeds {
            let found = match &guide {
                // Those a wrap gave way to are there already.
                Some(_) => found
                    .into_iter()
                    .zip(taken)
                    .filter_map(|((s, _), t)| (!t).then_some(s))
                    .collect(),
                None => find_seeds(&image, self.params.polarity, self.params.modality),
            };
            if found.is_empty() && shapes.is_empty() {
                return Err(JobError::NoSeeds {
                    path: self.image.clone(),
                    polarity: self.params.polarity,
                });
            }
            shapes.extend(found);
        }
        let (ev, kept) = match (&guide, image) {
            (Some(g), image) => {
                let ev = g.evolver(Arc::new(image.as_ref().clone()), &shapes, g.params.mode)?;
                // The run reads the probabilities: the image is kept as it is.
                let kept = match image {
                    Cow::Owned(i) => Some(Stored::new(i)),
                    Cow::Borrowed(_) => None,
                };
                (ev, kept)
            }
            (None, Cow::Owned(image)) => {
                let (ev, kept) = Evolver::keeping(image, &shapes, self.params.clone())?;
                (ev, Some(kept))
            }
            (None, Cow::Borrowed(image)) => {
                (Evolver::new(image, &shapes, self.params.clone())?, None)
            }
        };
        Ok((ev, shapes, taught, kept))
    }

    /// Steps `s` through the job: each edit at its frame (or at the run's end if it ended
    /// before), then to the stop.
    pub fn drive(&self, s: &mut impl Steps) -> Result<(), EvolveError> {
        for edit in &self.edits {
            while s.frames() < edit.frame() && !s.is_finished() {
                s.step();
            }
            s.edit(edit)?;
        }
        match self.stop {
            Stop::Finished => s.run(),
            Stop::AtFrame(n) => {
                while s.frames() < n && !s.is_finished() {
                    s.step();
                }
            }
        }
        Ok(())
    }

    /// Runs the job on its image, already loaded (`image`, `info`: [`Job::load`]).
    pub fn run_on(&self, image: Field, info: ImageInfo) -> Result<JobRun, JobError> {
        let (mut ev, shapes, taught, image) = self.start_from(Cow::Owned(image))?;
        let image = image.expect("an owned image is kept");
        ev.free_coarse_levels();
        self.drive(&mut ev)?;
        let dropped = ev.filter_clutter();
        Ok(JobRun {
            ev,
            image,
            shapes,
            pixel: self.pixel_size.clone().or(info.pixel_size),
            page: self.page,
            pages: info.pages,
            taught,
            dropped,
        })
    }

    /// Loads the image and runs the job.
    pub fn run(&self) -> Result<JobRun, JobError> {
        let (image, info) = self.load()?;
        self.run_on(image, info)
    }
}
