//! `topocontour batch INPUT_DIR --out OUTPUT_DIR …`: every image of a folder with the same
//! settings, in parallel (rayon), with a progress bar on a terminal (indicatif).
//!
//! Each image gets its outputs named after it (`cells.tif` → `cells.json`, …; the whole
//! file name where stems collide, see [`output_stems`]), written all or none as
//! `segment` writes them; a failing image is reported on its own line and
//! the others go on. `summary.csv` gets one row per object of every image that
//! succeeded. Ctrl-C stops starting new images; those already running finish and are
//! written, the summary lists them, and the exit code is 1. Images are the folder's
//! regular files ending in .png, .jpg, .jpeg, .tif or .tiff (not its subfolders), in
//! natural name order. The output folder may be the input folder only when no output is an
//! image (mask, labels, overlay), which the next run would segment.

use super::run::{classifier_for, evolve, RunSettings};
use super::segment::{counted, write_outputs};
use super::{bad, note, Failure, Format};
use crate::io::folder::{file_name, list_images, output_stems, summary_rows, SUMMARY_HEADER};
use crate::io::{OutputFiles, Outputs};
use crate::learn::Teach;
use clap::Args;
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// The arguments of `batch`.
#[derive(Args, Debug, Clone)]
pub struct BatchArgs {
    /// A folder of images (PNG, JPEG, TIFF).
    pub input: PathBuf,
    /// The folder for the outputs (created if missing).
    #[arg(long, value_name = "OUTPUT_DIR")]
    pub out: PathBuf,
    /// Initialisation and parameters, the same for every image.
    #[command(flatten)]
    pub run: RunSettings,
    /// Outputs per image, comma-separated.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "json")]
    pub formats: Vec<Format>,
    /// Images segmented at once (default, and at most: one per core).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
}

/// What one image gave: its summary rows, or why it failed.
type ImageResult = Result<Vec<String>, Failure>;

/// The progress bar of a batch of `n` images.
fn progress_bar(n: usize) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(n as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} images, {elapsed} ({eta} left)",
        )
        .expect("a valid template"),
    );
    bar
}

/// The summary's text from the images' results, with the images done and failed and the
/// objects found; each failure is noted on stderr.
fn collate(results: &[(PathBuf, Option<ImageResult>)]) -> (String, usize, usize, usize) {
    let mut rows = String::from(SUMMARY_HEADER);
    let (mut done, mut failed, mut objects) = (0, 0, 0);
    for (img, r) in results {
        match r {
            Some(Ok(lines)) => {
                done += 1;
                objects += lines.len();
                lines.iter().for_each(|l| rows.push_str(l));
            }
            Some(Err(f)) => {
                failed += 1;
                note(&format!("{}: {}", img.display(), f.message));
            }
            None => {}
        }
    }
    (rows, done, failed, objects)
}

/// Runs `batch`.
pub fn batch(a: &BatchArgs) -> Result<(), Failure> {
    let images = list_images(&a.input)
        .map_err(|e| bad(format!("cannot read {}: {e}", a.input.display())))?;
    if images.is_empty() {
        return Err(bad(format!(
            "{} holds no PNG, JPEG or TIFF image",
            a.input.display()
        )));
    }
    let stems = output_stems(&images).map_err(bad)?;
    if a.run.train.is_some() {
        return Err(bad(
            "--train strokes belong to one image; train a classifier (topocontour train, or segment --save-classifier) and give batch --classifier",
        ));
    }
    // One model for the whole folder, read and checked once (ilastik's batch mode).
    let teach = classifier_for(&a.run)?;
    if let Some(f) = a
        .formats
        .iter()
        .enumerate()
        .find_map(|(i, f)| a.formats[..i].contains(f).then_some(f))
    {
        return Err(bad(format!("--formats names {} twice", f.name())));
    }
    if a.out.is_symlink() && !a.out.exists() {
        return Err(bad(format!(
            "--out {}: a symbolic link to nothing; give a folder",
            a.out.display()
        )));
    }
    if a.out.exists() && !a.out.is_dir() {
        return Err(bad(format!(
            "--out {}: not a folder (batch writes a folder of outputs)",
            a.out.display()
        )));
    }
    super::output_folder("--out", &a.out)?;
    refuse_out_in_input(a)?;
    // The summary is prepared like every output: checked before any work.
    let summary_path = a.out.join("summary.csv");
    let summary = OutputFiles::prepare(None, &[&summary_path]).map_err(|e| bad(e.to_string()))?;
    // A summary left by an earlier run would describe other outputs than the ones this
    // run writes (or, if it is killed, half of them); it goes now and comes back at the end.
    remove_old_summary(&summary_path)?;
    super::signals::stop_gently();
    let bar = progress_bar(images.len());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.jobs.map_or(0, |n| n.min(cores())))
        .build()
        .map_err(|e| Failure {
            code: 1,
            message: format!("cannot start worker threads: {e}"),
        })?;
    let results: Vec<(PathBuf, Option<ImageResult>)> = pool.install(|| {
        images
            .par_iter()
            .zip(&stems)
            .map(|(img, stem)| {
                if super::signals::stop_asked() {
                    return (img.clone(), None);
                }
                let r = one_image(img, stem, a, teach.as_ref());
                bar.inc(1);
                (img.clone(), Some(r))
            })
            .collect()
    });
    bar.finish_and_clear();
    let (rows, done, failed, objects) = collate(&results);
    summary
        .commit(vec![rows.into_bytes()])
        .map_err(|e| bad(e.to_string()))?;
    let skipped = results.iter().filter(|(_, r)| r.is_none()).count();
    if skipped > 0 {
        return Err(Failure {
            code: 1,
            message: format!(
                "interrupted: {done} of {} images done, {failed} failed",
                images.len()
            ),
        });
    }
    if failed > 0 {
        return Err(bad(format!("{failed} of {} images failed", images.len())));
    }
    note(&format!(
        "{} segmented, {}; outputs and summary.csv in {}",
        counted(done, "image"),
        counted(objects, "object"),
        a.out.display()
    ));
    Ok(())
}

/// Removes the summary of an earlier run (prepared outputs are regular files or absent).
fn remove_old_summary(path: &Path) -> Result<(), Failure> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            Err(bad(format!("cannot replace {}: {e}", path.display())))
        }
        _ => Ok(()),
    }
}

/// The cores this process may use (more threads only wait for them).
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Refuses an output folder that is the input folder when an output is an image: the
/// next run would segment it as an input.
fn refuse_out_in_input(a: &BatchArgs) -> Result<(), Failure> {
    let images = [Format::Mask, Format::Labels, Format::Overlay];
    let same = match (a.out.canonicalize(), a.input.canonicalize()) {
        (Ok(o), Ok(i)) => o == i,
        _ => false,
    };
    match a.formats.iter().find(|f| images.contains(f)) {
        Some(f) if same => Err(bad(format!(
            "--out is the input folder, and the {} outputs are images a later run would read as inputs: choose another folder",
            f.name()
        ))),
        _ => Ok(()),
    }
}

/// Segments one image and writes its outputs, named after `stem`; returns its summary
/// rows.
fn one_image(img: &Path, stem: &str, a: &BatchArgs, teach: Option<&Teach>) -> ImageResult {
    let paths: Vec<PathBuf> = a
        .formats
        .iter()
        .map(|f| a.out.join(f.file_name(stem)))
        .collect();
    let refs: Vec<&Path> = paths.iter().map(PathBuf::as_path).collect();
    let files = OutputFiles::prepare(Some(img), &refs).map_err(|e| bad(e.to_string()))?;
    let (_, run) = evolve(img, &a.run, teach)?;
    let (ev, image) = (&run.ev, &run.image);
    let name = file_name(img);
    let out = Outputs::of(ev, ev.contours(), &name).with_pixel_size(run.pixel.clone());
    let wanted: Vec<(Format, &Path)> = a.formats.iter().copied().zip(refs).collect();
    write_outputs(files, &wanted, &out, image, Vec::new())?;
    Ok(summary_rows(&name, &out, image))
}
