//! What teaches a run, in memory: the user's strokes on the image (a classifier is
//! trained on them when the run starts), or a classifier already trained (on other
//! images, read from a file or kept from an earlier run). A [`crate::job::Job`] holds
//! one, so a front end passes what its user painted or loaded without writing files, and
//! a session records it ([`crate::io::session`]).
//!
//! Both are behind an `Arc`: a batch shares one classifier among its images and threads,
//! and an app keeps its strokes while a run reads them.

use super::{Classifier, FeatureSet, ForestParams, Probabilities, StrokeError, Strokes};
use crate::image::Field;
use std::sync::Arc;

/// What a run learns its pixel classes from.
#[derive(Clone, Debug, PartialEq)]
pub enum Teach {
    /// Strokes painted on the run's image (its size): a seeded forest is trained on
    /// them, so the same strokes always give the same classifier.
    Strokes(Arc<Strokes>),
    /// A trained classifier, applied as it is.
    Classifier(Arc<Classifier>),
}

/// Why a run cannot be taught.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum TeachError {
    /// The strokes do not fit the image.
    #[error(transparent)]
    Strokes(#[from] StrokeError),
    /// The classifier does not fit this build.
    #[error("the classifier does not fit: {0}")]
    Misfit(String),
}

/// What teaching gave: the classifier and its probabilities on the run's image.
#[derive(Clone, Debug)]
pub struct Taught {
    /// The classifier (trained on the strokes, or the one given).
    pub classifier: Arc<Classifier>,
    /// Its class probabilities on every pixel of the image.
    pub probabilities: Probabilities,
}

impl Teach {
    /// Trains on `strokes` (checked: values, an object class and one more).
    pub fn strokes(strokes: Strokes) -> Self {
        Teach::Strokes(Arc::new(strokes))
    }

    /// Applies `classifier`.
    pub fn classifier(classifier: Classifier) -> Self {
        Teach::Classifier(Arc::new(classifier))
    }

    /// The classifier for `image` (named `name`, recorded as its training image when
    /// it is trained here) and its probabilities there.
    pub fn apply(&self, image: &Field, name: &str) -> Result<Taught, TeachError> {
        let set = match self {
            Teach::Strokes(s) => {
                s.check_size(image.width, image.height)?;
                FeatureSet::default()
            }
            Teach::Classifier(c) => {
                if let Some(why) = c.misfit() {
                    return Err(TeachError::Misfit(why));
                }
                c.features.clone()
            }
        };
        let features = set.compute(image.width, image.height, &image.data);
        let classifier = match self {
            Teach::Strokes(s) => {
                let mut c = Classifier::train_with(set, &features, s, &ForestParams::default());
                c.images = vec![name.to_string()];
                Arc::new(c)
            }
            Teach::Classifier(c) => c.clone(),
        };
        let probabilities = classifier.predict(&features);
        Ok(Taught {
            classifier,
            probabilities,
        })
    }
}
