//! Classifier files: a trained pixel classifier ([`Classifier`]) as compact JSON, so a
//! model taught on one image applies to a folder (`batch --classifier`, ilastik's batch
//! mode) or to the next experiment.
//!
//! The file names its format and version, and the classifier records what it reads: the
//! feature definitions' version and scales, the channel count, its classes and the
//! names of the images it was trained on. A file that does not fit this build (other
//! feature version or channel count, classes that are not ours, a damaged forest whose
//! walks would leave its tables) is refused with one line before any image is read
//! ([`Classifier::misfit`]). Unknown keys are refused, as in session files.

use crate::learn::Classifier;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The `format` field of every classifier file.
pub const FORMAT: &str = "topocontour-classifier";
/// The version this build writes and reads.
pub const VERSION: u32 = 1;
/// The largest classifier file read (a forest of a few hundred thousand nodes).
pub const MAX_CLASSIFIER_BYTES: u64 = 256 << 20;

/// A classifier file.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ClassifierFile {
    format: String,
    version: u32,
    classifier: Classifier,
}

/// What is read first: whether the file is one of ours, and of which version.
#[derive(Deserialize)]
struct Header {
    format: Option<String>,
    version: Option<u32>,
}

/// Why a classifier file cannot be used.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ClassifierFileError {
    /// Unreadable, or not a classifier file of this version.
    #[error("cannot read the classifier {path}: {why}")]
    Read {
        /// The file.
        path: String,
        /// What failed.
        why: String,
    },
    /// A classifier this build cannot apply.
    #[error("the classifier {path} does not fit: {why}")]
    Misfit {
        /// The file.
        path: String,
        /// What does not fit.
        why: String,
    },
}

/// The file's bytes for `classifier`.
pub fn to_bytes(classifier: &Classifier) -> Vec<u8> {
    let file = ClassifierFile {
        format: FORMAT.into(),
        version: VERSION,
        classifier: classifier.clone(),
    };
    let mut bytes = serde_json::to_vec(&file).expect("JSON of plain data");
    bytes.push(b'\n');
    bytes
}

/// Reads a classifier file and checks that this build can apply it.
pub fn read(path: &Path) -> Result<Classifier, ClassifierFileError> {
    use crate::io::load::{read_regular, Unread};
    let name = path.display().to_string();
    let refused = |why: String| ClassifierFileError::Read {
        path: name.clone(),
        why,
    };
    let bytes = read_regular(path, MAX_CLASSIFIER_BYTES).map_err(|e| match e {
        Unread::Io(e) => refused(e.to_string()),
        Unread::NotAFile => refused("not a regular file".into()),
        Unread::TooLarge(n) => refused(format!(
            "{n} bytes, more than any classifier ({MAX_CLASSIFIER_BYTES})"
        )),
    })?;
    let header: Header = serde_json::from_slice(&bytes)
        .map_err(|e| refused(format!("not a topocontour classifier ({e})")))?;
    if header.format.as_deref() != Some(FORMAT) || header.version != Some(VERSION) {
        return Err(refused(format!(
            "format {} version {}, expected {FORMAT} version {VERSION}",
            header.format.as_deref().unwrap_or("none"),
            header.version.map_or("none".into(), |v| v.to_string())
        )));
    }
    let file: ClassifierFile =
        serde_json::from_slice(&bytes).map_err(|e| refused(e.to_string()))?;
    match file.classifier.misfit() {
        Some(why) => Err(ClassifierFileError::Misfit { path: name, why }),
        None => Ok(file.classifier),
    }
}
