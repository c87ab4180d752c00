//! `topocontour segment IMAGE …`: one image, the outputs the flags name, all written or
//! none; and the evaluation case folders' `case.json`.

use super::run::{evolve, RunSettings};
use super::{bad, note, Failure};
use crate::evolution::{Evolver, Modality, Mode, Polarity};
use crate::io::folder::file_name;
use crate::io::session::Session;
use crate::io::{Format, OutputFiles, Outputs};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

/// A case file is a few seeds and settings; anything larger is not one.
const MAX_CASE_BYTES: u64 = 1 << 20;

/// The arguments of `segment`.
#[derive(Args, Debug, Clone)]
pub struct SegmentArgs {
    /// PNG, JPEG or TIFF image (8 or 16 bit, gray or colour).
    pub image: PathBuf,
    /// Initialisation and parameters.
    #[command(flatten)]
    pub run: RunSettings,
    /// The outputs.
    #[command(flatten)]
    pub out: OutputArgs,
    /// Write a session file that `topocontour replay` and the app reproduce this run from.
    #[arg(long, value_name = "OUT")]
    pub save_session: Option<PathBuf>,
    /// Write the pixel classifier the run was taught with (--train or --classifier), for
    /// `--classifier` on other images and `batch --classifier`.
    #[arg(long, value_name = "OUT")]
    pub save_classifier: Option<PathBuf>,
}

/// The output files a run can write, each optional.
#[derive(Args, Debug, Clone, Default)]
pub struct OutputArgs {
    /// Write contours and events as JSON.
    #[arg(long, value_name = "OUT")]
    pub json: Option<PathBuf>,
    /// Write the mask (255 inside): TIFF for a .tif name, else PNG.
    #[arg(long, value_name = "OUT.png|tif")]
    pub mask: Option<PathBuf>,
    /// Write an SVG of the regions.
    #[arg(long, value_name = "OUT")]
    pub svg: Option<PathBuf>,
    /// Write GeoJSON polygons (QuPath reads them, with their measurements).
    #[arg(long, value_name = "OUT")]
    pub geojson: Option<PathBuf>,
    /// Write per-region measurements as CSV.
    #[arg(long, value_name = "OUT")]
    pub csv: Option<PathBuf>,
    /// Write a 16-bit label image (one label per object, holes 0): TIFF for .tif/.tiff,
    /// else PNG.
    #[arg(long, value_name = "OUT.tif|png")]
    pub labels: Option<PathBuf>,
    /// Write the image with the contours drawn (each object its colour) as PNG.
    #[arg(long, value_name = "OUT.png")]
    pub overlay: Option<PathBuf>,
    /// Write an ImageJ ROI set (zip) that Fiji's ROI Manager opens.
    #[arg(long, value_name = "OUT.zip")]
    pub roi: Option<PathBuf>,
}

impl OutputArgs {
    /// The outputs the flags name, in a fixed order; an image output named in another
    /// image format (`--mask cells.jpg`) is refused.
    pub fn list(&self) -> Result<Vec<(Format, &Path)>, Failure> {
        let wanted: Vec<_> = [
            (Format::Json, &self.json),
            (Format::Mask, &self.mask),
            (Format::Svg, &self.svg),
            (Format::Geojson, &self.geojson),
            (Format::Csv, &self.csv),
            (Format::Overlay, &self.overlay),
            (Format::Labels, &self.labels),
            (Format::Roi, &self.roi),
        ]
        .into_iter()
        .filter_map(|(f, p)| p.as_deref().map(|p| (f, p)))
        .collect();
        for &(f, p) in &wanted {
            f.check_name(p)
                .map_err(|e| bad(format!("--{} {}: {e}", f.name(), p.display())))?;
        }
        Ok(wanted)
    }
}

/// Renders every output of a finished run and writes them all or none (`extra`: more
/// files' bytes, prepared after the outputs, such as a session).
pub(super) fn write_outputs(
    files: OutputFiles,
    wanted: &[(Format, &Path)],
    out: &Outputs,
    image: &dyn crate::image::Gray,
    extra: Vec<Vec<u8>>,
) -> Result<(), Failure> {
    let mut bytes = wanted
        .iter()
        .map(|&(f, p)| {
            f.render(out, image, p)
                .map_err(|e| bad(format!("cannot write {}: {e}", p.display())))
        })
        .collect::<Result<Vec<_>, _>>()?;
    bytes.extend(extra);
    files.commit(bytes).map_err(|e| bad(e.to_string()))
}

/// Runs `segment` and writes its outputs; returns the finished evolver.
pub fn segment(a: &SegmentArgs) -> Result<Evolver, Failure> {
    if a.save_classifier.is_some() && a.run.train.is_none() && a.run.classifier.is_none() {
        return Err(bad(
            "--save-classifier saves what --train STROKES.png (or --classifier) taught; give one",
        ));
    }
    // Every output is checked, and its temporary created, before any work.
    let wanted = a.out.list()?;
    let extras: Vec<&Path> = [&a.save_session, &a.save_classifier]
        .into_iter()
        .filter_map(|p| p.as_deref())
        .collect();
    let mut paths: Vec<&Path> = wanted.iter().map(|&(_, p)| p).collect();
    paths.extend(&extras);
    let mut inputs = vec![(a.image.as_path(), "input image")];
    inputs.extend(a.run.train.as_deref().map(|p| (p, "strokes file")));
    inputs.extend(a.run.classifier.as_deref().map(|p| (p, "classifier file")));
    let files = OutputFiles::prepare_for(&inputs, &paths).map_err(|e| bad(e.to_string()))?;
    let teach = super::run::classifier_for(&a.run)?;
    let (job, run) = evolve(&a.image, &a.run, teach.as_ref())?;
    let ev = &run.ev;
    let name = file_name(&a.image);
    let out = Outputs::of(ev, ev.contours(), &name).with_pixel_size(run.pixel.clone());
    if out.held > 0 {
        // The engine held topology (asked for, or the default for seeds); say where it
        // mattered.
        let what = match out.params.mode {
            Mode::Track => "kept the seeds' objects apart (splits allowed)",
            _ => "kept the initial topology",
        };
        note(&format!(
            "note: mode {} {what} ({} contours); fronts were held apart at {} places where adaptive mode would merge, split or close holes",
            out.params.mode.name(),
            ev.contours().contour_count(),
            out.held
        ));
    }
    if run.dropped > 0 {
        // Said, not silent: a field of specks smaller than the bound would otherwise end
        // as "0 objects" with no hint why.
        note(&format!(
            "note: {} smaller than --min-area {} px² dropped (a smaller --min-area keeps them)",
            counted(run.dropped, "object"),
            ev.params().min_area
        ));
    }
    if !out.converged {
        note(&format!(
            "note: the contours had not settled after {} frames (limit {}); the result is where they stopped",
            out.frames,
            ev.params().max_frames
        ));
    }
    let mut extra = Vec::new();
    if let Some(to) = &a.save_session {
        let s = Session::of_run(&job, &run)
            .map_err(|e| bad(format!("cannot read {}: {e}", a.image.display())))?
            .stored_at(to);
        extra.push(s.to_json().map_err(|e| bad(e.to_string()))?.into_bytes());
    }
    if a.save_classifier.is_some() {
        let taught = run
            .taught
            .as_ref()
            .expect("a run with --train or --classifier");
        extra.push(crate::io::classifier::to_bytes(&taught.classifier));
    }
    write_outputs(files, &wanted, &out, &run.image, extra)?;
    note(&done_line(&name, &out, &wanted, &extras));
    Ok(run.ev)
}

/// The one line a successful run ends with, on stderr (stdout stays for data): what was
/// found and what was written.
pub(super) fn done_line(
    name: &str,
    out: &Outputs,
    wanted: &[(Format, &Path)],
    extra: &[&Path],
) -> String {
    let regions = crate::evolution::regions(out.set);
    let holes: usize = regions.iter().map(|r| r.holes.len()).sum();
    let how = if out.converged { "settled" } else { "stopped" };
    let mut written: Vec<String> = wanted
        .iter()
        .map(|(_, p)| p.display().to_string())
        .collect();
    written.extend(extra.iter().map(|p| p.display().to_string()));
    let wrote = if written.is_empty() {
        "no output asked for (--json, --mask, --csv, …)".to_string()
    } else {
        format!("wrote {}", written.join(", "))
    };
    format!(
        "{name}: {}, {}, {how} after {} frames; {wrote}",
        counted(regions.len(), "object"),
        counted(holes, "hole"),
        out.frames
    )
}

/// `n` and the word, plural unless one.
pub(crate) fn counted(n: usize, word: &str) -> String {
    format!("{n} {word}{}", if n == 1 { "" } else { "s" })
}

/// The arguments of `replay`.
#[derive(Args, Debug, Clone)]
pub struct ReplayArgs {
    /// A session file (from `segment --save-session` or the app).
    pub session: PathBuf,
    /// The session's image, where it is now (it moved); its size and checksum must
    /// still match.
    #[arg(long, value_name = "PATH")]
    pub image: Option<PathBuf>,
    /// The outputs.
    #[command(flatten)]
    pub out: OutputArgs,
}

/// Runs `replay`: the session's run again, headless, and its outputs.
pub fn replay(a: &ReplayArgs) -> Result<Evolver, Failure> {
    let session = Session::read(&a.session).map_err(|e| bad(e.to_string()))?;
    let wanted = a.out.list()?;
    let paths: Vec<&Path> = wanted.iter().map(|&(_, p)| p).collect();
    let image_path = a
        .image
        .clone()
        .unwrap_or_else(|| session.image_path(&a.session));
    // The session file is an input too: never written over (also through a hard link).
    let inputs = [
        (image_path.as_path(), "input image"),
        (a.session.as_path(), "session file"),
    ];
    let files = OutputFiles::prepare_for(&inputs, &paths).map_err(|e| bad(e.to_string()))?;
    let run = session
        .replay(&a.session, Some(&image_path))
        .map_err(|e| bad(e.to_string()))?;
    let name = file_name(&image_path);
    let out = Outputs::of(&run.ev, run.ev.contours(), &name).with_pixel_size(run.pixel.clone());
    write_outputs(files, &wanted, &out, &run.image, Vec::new())?;
    note(&done_line(&name, &out, &wanted, &[]));
    Ok(run.ev)
}

/// The part of an evaluation case's `case.json` that says how to run it; other keys of
/// the file (name, expectations, notes) are not ours to read.
#[derive(serde::Deserialize)]
struct CaseFile {
    init: CaseInit,
}

/// A case's initialisation: what a user knows. Unknown keys are refused, so a typo is an
/// error rather than a silent default.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct CaseInit {
    #[serde(default)]
    seeds: Vec<[f64; 3]>,
    border_margin: Option<f64>,
    #[serde(deserialize_with = "value_enum")]
    object: Polarity,
    #[serde(default, deserialize_with = "value_enum")]
    modality: Modality,
}

/// A clap value name ("bright", "phase-contrast") as the enum it names.
fn value_enum<'de, D, T>(d: D) -> Result<T, D::Error>
where
    D: serde::Deserializer<'de>,
    T: ValueEnum,
{
    let s = <String as serde::Deserialize>::deserialize(d)?;
    T::from_str(&s, false).map_err(serde::de::Error::custom)
}

impl SegmentArgs {
    /// The arguments an evaluation case folder (image.png + case.json) asks for, with no
    /// outputs.
    pub fn from_case(dir: &Path) -> Result<SegmentArgs, Failure> {
        use crate::io::load::{read_regular, Unread};
        let file = dir.join("case.json");
        let bytes = read_regular(&file, MAX_CASE_BYTES).map_err(|e| {
            bad(match e {
                Unread::Io(e) => format!("{}: {e}", file.display()),
                Unread::NotAFile => format!("{} is not a regular file", file.display()),
                Unread::TooLarge(n) => format!(
                    "{}: {n} bytes, more than any case file ({MAX_CASE_BYTES})",
                    file.display()
                ),
            })
        })?;
        let text = String::from_utf8(bytes)
            .map_err(|_| bad(format!("{}: not UTF-8 text", file.display())))?;
        let case: CaseFile = serde_json::from_str(&text)
            .map_err(|e| bad(format!("{}/case.json: {e}", dir.display())))?;
        let init = case.init;
        let mut run = RunSettings::new(init.object);
        run.seeds = init.seeds.iter().map(|&[x, y, r]| (x, y, r)).collect();
        run.wrap = init.border_margin;
        run.modality = init.modality;
        Ok(SegmentArgs {
            image: dir.join("image.png"),
            run,
            out: OutputArgs::default(),
            save_session: None,
            save_classifier: None,
        })
    }
}
