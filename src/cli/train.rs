//! `topocontour train IMAGE STROKES [IMAGE STROKES …] --out FILE`: one pixel classifier
//! from the strokes painted on several images, saved for `segment --classifier` and
//! `batch --classifier` (ilastik's workflow: train on a few images of an experiment,
//! apply to all of them). Each image's features are normalised per image
//! ([`crate::learn::features`]), so differently exposed images train one model.

use super::segment::counted;
use super::{bad, note, Failure};
use crate::io::folder::file_name;
use crate::io::{load_image_page, OutputFiles};
use crate::learn::{Classifier, FeatureSet, Features, ForestParams, Strokes};
use clap::Args;
use std::path::{Path, PathBuf};

/// The arguments of `train`.
#[derive(Args, Debug, Clone)]
pub struct TrainArgs {
    /// Pairs of an image and its strokes (a PNG of the image's size: 0 none,
    /// 1 background, 2 object, 3 boundary between touching objects).
    #[arg(value_name = "IMAGE STROKES", num_args = 2.., required = true)]
    pub pairs: Vec<PathBuf>,
    /// The classifier file to write.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
}

/// Runs `train`.
pub fn train(a: &TrainArgs) -> Result<(), Failure> {
    if !a.pairs.len().is_multiple_of(2) {
        return Err(bad(format!(
            "train takes pairs of an image and its strokes; {} is left without strokes",
            a.pairs[a.pairs.len() - 1].display()
        )));
    }
    let inputs: Vec<(&Path, &'static str)> = a
        .pairs
        .iter()
        .enumerate()
        .map(|(i, p)| {
            (
                p.as_path(),
                if i % 2 == 0 {
                    "input image"
                } else {
                    "strokes file"
                },
            )
        })
        .collect();
    let files =
        OutputFiles::prepare_for(&inputs, &[a.out.as_path()]).map_err(|e| bad(e.to_string()))?;
    let set = FeatureSet::default();
    let mut taught: Vec<(Features, Strokes)> = Vec::new();
    for pair in a.pairs.chunks_exact(2) {
        let (image, _) = load_image_page(&pair[0], 0).map_err(|e| bad(e.to_string()))?;
        let strokes = Strokes::read(&pair[1], image.width, image.height)
            .map_err(|e| bad(format!("{}: {e}", pair[0].display())))?;
        taught.push((set.compute(image.width, image.height, &image.data), strokes));
    }
    let images = a.pairs.iter().step_by(2).map(|p| file_name(p)).collect();
    let clf = classifier_of(set, &taught, images)?;
    files
        .commit(vec![crate::io::classifier::to_bytes(&clf)])
        .map_err(|e| bad(e.to_string()))?;
    let pixels: usize = taught
        .iter()
        .map(|(_, s)| s.labels.iter().filter(|&&l| l > 0).count())
        .sum();
    let names = ["background", "object", "boundary"];
    let classes: Vec<&str> = clf.labels.iter().map(|&l| names[l as usize - 1]).collect();
    note(&format!(
        "trained on {} ({} stroke pixels; classes {}); wrote {}",
        counted(taught.len(), "image"),
        pixels,
        classes.join(", "),
        a.out.display()
    ));
    Ok(())
}

/// The classifier the strokes of several images teach (each pair one image's features,
/// made by `set`, and its strokes), `images` their names: what `train` writes and the
/// Python bindings' `train` returns.
pub fn classifier_of(
    set: FeatureSet,
    taught: &[(Features, Strokes)],
    images: Vec<String>,
) -> Result<Classifier, Failure> {
    let pairs: Vec<(&Features, &Strokes)> = taught.iter().map(|(f, s)| (f, s)).collect();
    let mut clf = Classifier::train_many(set, &pairs, &ForestParams::default());
    clf.images = images;
    if clf.labels.len() < 2 {
        return Err(bad(
            "the strokes mark only one class in all; paint background (1) or boundary (3) too",
        ));
    }
    Ok(clf)
}
