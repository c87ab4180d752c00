//! `topocontour segment IMAGE …`: one image, the outputs the flags name, all written or
//! none; and the evaluation case folders' `case.json`.

use super::run::{evolve, Evolved, RunSettings};
use super::{bad, note, Failure};
use crate::evolution::{Evolver, Modality, Polarity};
use crate::io::folder::file_name;
use crate::io::session::Session;
use crate::io::{OutputFiles, Outputs};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

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
}

/// The output files a run can write, each optional.
#[derive(Args, Debug, Clone, Default)]
pub struct OutputArgs {
    /// Write contours and events as JSON.
    #[arg(long, value_name = "OUT")]
    pub json: Option<PathBuf>,
    /// Write a mask PNG (255 inside).
    #[arg(long, value_name = "OUT.png")]
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

/// An output format.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Contours and events (the CLI contract).
    Json,
    /// Mask PNG, 255 inside.
    Mask,
    /// SVG of the regions.
    Svg,
    /// GeoJSON polygons as QuPath reads them.
    Geojson,
    /// Measurements, one row per region.
    Csv,
    /// 16-bit label image (TIFF).
    Labels,
    /// The image with the contours drawn (PNG).
    Overlay,
    /// ImageJ ROI set (zip).
    Roi,
}

impl Format {
    /// The output file name for an image with file stem `stem` (batch runs).
    pub fn file_name(self, stem: &str) -> String {
        match self {
            Format::Json => format!("{stem}.json"),
            Format::Mask => format!("{stem}.mask.png"),
            Format::Svg => format!("{stem}.svg"),
            Format::Geojson => format!("{stem}.geojson"),
            Format::Csv => format!("{stem}.csv"),
            Format::Labels => format!("{stem}.labels.tif"),
            Format::Overlay => format!("{stem}.overlay.png"),
            Format::Roi => format!("{stem}.roi.zip"),
        }
    }

    /// The bytes of this output; `path` chooses TIFF or PNG for labels.
    pub fn render(
        self,
        out: &Outputs,
        image: &crate::evolution::Field,
        path: &Path,
    ) -> Result<Vec<u8>, Failure> {
        Ok(match self {
            Format::Json => out.json().into_bytes(),
            Format::Mask => out.mask_png(),
            Format::Svg => out.svg().into_bytes(),
            Format::Geojson => out.geojson().into_bytes(),
            Format::Csv => out.csv().into_bytes(),
            Format::Overlay => out.overlay_png(image),
            Format::Roi => crate::io::roi::roi_zip(out.set),
            Format::Labels => {
                let tiff = path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                    e.eq_ignore_ascii_case("tif") || e.eq_ignore_ascii_case("tiff")
                });
                out.labels_image(tiff).ok_or_else(|| {
                    bad(format!(
                        "cannot write {}: more than 65,535 objects for a 16-bit label image",
                        path.display()
                    ))
                })?
            }
        })
    }
}

impl OutputArgs {
    /// The outputs the flags name, in a fixed order.
    pub fn list(&self) -> Vec<(Format, &Path)> {
        [
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
        .collect()
    }
}

/// Renders every output of a finished run and writes them all or none (`extra`: one
/// more file's bytes, prepared after the outputs, such as a session).
pub(super) fn write_outputs(
    files: OutputFiles,
    wanted: &[(Format, &Path)],
    out: &Outputs,
    image: &crate::evolution::Field,
    extra: Option<Vec<u8>>,
) -> Result<(), Failure> {
    let mut bytes = wanted
        .iter()
        .map(|&(f, p)| f.render(out, image, p))
        .collect::<Result<Vec<_>, _>>()?;
    bytes.extend(extra);
    files.commit(bytes).map_err(|e| bad(e.to_string()))
}

/// Runs `segment` and writes its outputs; returns the finished evolver.
pub fn segment(a: &SegmentArgs) -> Result<Evolver, Failure> {
    // Every output is checked, and its temporary created, before any work.
    let wanted = a.out.list();
    let mut paths: Vec<&Path> = wanted.iter().map(|&(_, p)| p).collect();
    paths.extend(a.save_session.as_deref());
    let files = OutputFiles::prepare(Some(&a.image), &paths).map_err(|e| bad(e.to_string()))?;
    let Evolved {
        ev,
        image,
        shapes,
        pixel,
        page,
    } = evolve(&a.image, &a.run)?;
    let name = file_name(&a.image);
    let out = Outputs::of(&ev, ev.contours(), &name).with_pixel_size(pixel);
    if out.held > 0 {
        // The user asked for fixed topology; say where it mattered.
        note(&format!(
            "note: mode {} kept the initial topology ({} contours); fronts were held apart at {} places where adaptive mode would merge, split or close holes",
            out.params.mode.name(),
            ev.contours().contour_count(),
            out.held
        ));
    }
    if !out.converged {
        note(&format!(
            "note: the contours had not settled after {} frames (limit {}); the result is where they stopped",
            out.frames,
            ev.params().max_frames
        ));
    }
    let session = match &a.save_session {
        Some(_) => {
            // The image by its absolute path: the session may be read from anywhere.
            let abs = a.image.canonicalize().unwrap_or_else(|_| a.image.clone());
            let s = Session::new(
                &abs,
                &image,
                shapes,
                ev.start_params().clone(),
                ev.frames(),
                true,
            )
            .map_err(|e| bad(format!("cannot read {}: {e}", a.image.display())))?
            .with_page(page);
            Some(s.to_json().into_bytes())
        }
        None => None,
    };
    write_outputs(files, &wanted, &out, &image, session)?;
    Ok(ev)
}

/// The arguments of `replay`.
#[derive(Args, Debug, Clone)]
pub struct ReplayArgs {
    /// A session file (from `segment --save-session` or the app).
    pub session: PathBuf,
    /// The outputs.
    #[command(flatten)]
    pub out: OutputArgs,
}

/// Runs `replay`: the session's run again, headless, and its outputs.
pub fn replay(a: &ReplayArgs) -> Result<Evolver, Failure> {
    let session = Session::read(&a.session).map_err(|e| bad(e.to_string()))?;
    let wanted = a.out.list();
    let paths: Vec<&Path> = wanted.iter().map(|&(_, p)| p).collect();
    let image_path = session.image_path(&a.session);
    let files = OutputFiles::prepare(Some(&image_path), &paths).map_err(|e| bad(e.to_string()))?;
    let (mut ev, image) = session.replay(&a.session).map_err(|e| bad(e.to_string()))?;
    ev.filter_clutter();
    let name = file_name(&image_path);
    let out = Outputs::of(&ev, ev.contours(), &name);
    write_outputs(files, &wanted, &out, &image, None)?;
    Ok(ev)
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
        let text = std::fs::read_to_string(dir.join("case.json"))
            .map_err(|e| bad(format!("{}: {e}", dir.display())))?;
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
        })
    }
}
