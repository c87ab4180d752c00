//! `topocontour track MOVIE …`: cells tracked through a movie (see [`crate::track`]),
//! written as the Cell Tracking Challenge result layout and, if asked, JSON, a CSV of
//! cells per frame and overlays.
//!
//! The movie is read whole once before anything is written (a bad movie: one line, exit
//! 2, no output); then frame by frame, each frame's mask written once the next frame is
//! tracked (which may revise the one before: take back its divisions,
//! [`crate::track::TrackedFrame::undone`], or date one there,
//! [`crate::track::TrackedFrame::earlier`]), so memory holds two frames, not the movie
//! (the JSON, when asked, keeps every frame's contours until the end).

use super::run::{init_shapes, params_for, RunSettings};
use super::segment::counted;
use super::{bad, note, Failure};
use crate::evolution::Field;
use crate::evolution::{Modality, Polarity};
use crate::io::export::ctc;
use crate::io::movie::Movie;
use crate::io::{write_atomic, OutputFiles};
use crate::track::{revise_labels, Lineage, TrackSettings, TrackedFrame, Tracker};
use clap::Args;
use std::path::{Path, PathBuf};

/// The arguments of `track`.
#[derive(Args, Debug, Clone)]
pub struct TrackArgs {
    /// A multi-page TIFF (one page per time point, 8 or 16 bit) or a folder of images
    /// (frames in natural name order: frame_2 before frame_10).
    pub movie: PathBuf,
    /// Whether cells are darker or brighter than the background.
    #[arg(long, value_enum)]
    pub object: Polarity,
    /// The kind of image: phase contrast treats the bright halo as background.
    #[arg(long, value_enum, default_value = "generic")]
    pub modality: Modality,
    /// A seed disk at X,Y with radius R on frame 0; repeat for more (default: automatic
    /// seeds).
    #[arg(
        long = "seed",
        value_name = "X,Y,R",
        value_parser = super::run::parse_seed,
        allow_hyphen_values = true
    )]
    pub seeds: Vec<(f64, f64, f64)>,
    /// A rectangle MARGIN pixels inside the border on frame 0, to shrink-wrap everything.
    #[arg(long, value_name = "MARGIN", allow_negative_numbers = true)]
    pub wrap: Option<f64>,
    /// A rectangle X0,Y0,X1,Y1 on frame 0.
    #[arg(
        long,
        value_name = "X0,Y0,X1,Y1",
        value_parser = super::run::parse_rect,
        allow_hyphen_values = true
    )]
    pub rect: Vec<(f64, f64, f64, f64)>,
    /// Automatic seeds on frame 0 as well as the shapes given (the default without any).
    #[arg(long)]
    pub auto_seeds: bool,
    /// Do not pick up cells that enter or appear after frame 0.
    #[arg(long)]
    pub no_new_cells: bool,
    /// Radius of the local intensity statistics in pixels (default: from each frame).
    #[arg(long, value_name = "PX")]
    pub local_radius: Option<f64>,
    /// Drop cells smaller than this (square pixels).
    #[arg(long, value_name = "PX", allow_negative_numbers = true)]
    pub min_area: Option<f64>,
    /// How far a contour moves in before the next frame starts from it (pixels).
    #[arg(
        long,
        value_name = "PX",
        default_value_t = 2.0,
        allow_negative_numbers = true
    )]
    pub shrink: f64,
    /// Pyramid levels each frame after the first evolves through (coarse to fine; one
    /// more level follows a move twice as large).
    #[arg(long, value_name = "N", default_value_t = 2)]
    pub levels: usize,
    /// Write the Cell Tracking Challenge result: OUT/maskTTT.tif and OUT/res_track.txt.
    #[arg(long, value_name = "OUT")]
    pub ctc: Option<PathBuf>,
    /// Write every frame's contours with their tracks, and the divisions, as JSON.
    #[arg(long, value_name = "OUT")]
    pub json: Option<PathBuf>,
    /// Write one CSV row per cell per frame: track, frame, area, centroid, parent.
    #[arg(long, value_name = "OUT")]
    pub tracks_csv: Option<PathBuf>,
    /// Write the frames with outlines and track labels as PNG: the frame --overlay-frame
    /// names, else one PNG per frame (OUT with the frame number before its extension).
    #[arg(long, value_name = "OUT.png")]
    pub overlay: Option<PathBuf>,
    /// The frame (from 0) that --overlay draws.
    #[arg(long, value_name = "T", requires = "overlay")]
    pub overlay_frame: Option<usize>,
}

impl TrackArgs {
    fn run_settings(&self) -> RunSettings {
        RunSettings {
            seeds: self.seeds.clone(),
            wrap: self.wrap,
            rect: self.rect.clone(),
            auto_seeds: true,
            modality: self.modality,
            local_radius: self.local_radius,
            min_area: self.min_area,
            ..RunSettings::new(self.object)
        }
    }
}

/// Where each output goes, checked before the movie is tracked.
struct Plan {
    files: OutputFiles,
    ctc: Option<PathBuf>,
    overlay: Option<PathBuf>,
}

/// `--shrink` checked: a number ≥ 0.
fn check_shrink(a: &TrackArgs) -> Result<(), Failure> {
    if !(a.shrink.is_finite() && a.shrink >= 0.0) {
        return Err(bad(format!(
            "--shrink must be a number ≥ 0, got {}",
            a.shrink
        )));
    }
    Ok(())
}

/// The tracker the flags describe for a movie of `w` × `h` frames, its shapes checked
/// against that size: what `track` runs and the Python bindings' `track` too.
pub fn tracker_for(a: &TrackArgs, w: usize, h: usize) -> Result<Tracker, Failure> {
    check_shrink(a)?;
    let run = a.run_settings();
    let init = init_shapes(&run, w, h)?;
    let mut settings = TrackSettings::new(params_for(&run)?);
    settings.shrink = a.shrink;
    settings.auto_seeds = a.auto_seeds || init.is_empty();
    settings.new_cells = !a.no_new_cells;
    if !(1..=crate::image::model::PYRAMID_LEVELS).contains(&a.levels) {
        return Err(bad(format!(
            "--levels {}: give 1 to {} (the pyramid's levels)",
            a.levels,
            crate::image::model::PYRAMID_LEVELS
        )));
    }
    if w.min(h) < 8 {
        return Err(bad(format!(
            "frames of {w}×{h} px are too small to track: at least 8 px a side"
        )));
    }
    settings.levels = a.levels;
    Ok(Tracker::new(settings, init))
}

/// The note for frame 0's `labels` when its cells cover most of the frame
/// ([`crate::track::CROWDED_SHARE`]), with the other `--object` as the likely fix.
fn object_hint(labels: &[u32], object: Polarity) -> Option<String> {
    let covered = labels.iter().filter(|&&l| l != 0).count() as f64 / labels.len().max(1) as f64;
    let (given, other) = match object {
        Polarity::Dark => ("darker", "bright"),
        Polarity::Bright => ("brighter", "dark"),
    };
    (covered > crate::track::CROWDED_SHARE).then(|| {
        format!(
            "note: frame 0's cells cover {:.0}% of it; if the cells are not {given} than their background, give --object {other}",
            100.0 * covered
        )
    })
}

/// The note when a later frame's cells cover most of it (the first such frame, once):
/// the background is being cut into cells, as a phase-contrast movie tracked as generic
/// does once its halo spreads.
fn crowded_hint(frame: &TrackedFrame, w: usize, h: usize) -> Option<String> {
    let covered = frame.covered(w, h);
    (covered > crate::track::CROWDED_SHARE).then(|| {
        let check = "--object and --modality (phase contrast: --modality phase-contrast)";
        format!(
            "note: {}",
            crate::track::crowded_note(frame.frame, covered, check)
        )
    })
}

/// Runs `track`.
pub fn track(a: &TrackArgs) -> Result<(), Failure> {
    check_shrink(a)?;
    let movie = Movie::open(&a.movie).map_err(|e| bad(e.to_string()))?;
    if let Some(t) = a.overlay_frame.filter(|&t| t >= movie.len()) {
        return Err(bad(format!(
            "--overlay-frame {t}: the movie has frames 0 to {}",
            movie.len() - 1
        )));
    }
    let (w, h) = movie.size();
    let mut tracker = tracker_for(a, w, h)?;
    let plan = prepare(a)?;
    let mut kept: Vec<TrackedFrame> = Vec::new();
    let mut csv = String::from(ctc::CSV_HEADER);
    // A frame is written once the next is tracked, which may revise it (sisters one cell
    // again, [`TrackedFrame::undone`]; a division dated there, [`TrackedFrame::earlier`]):
    // two frames are held, not the movie.
    let mut held: Option<Held> = None;
    let mut out = Out {
        a,
        plan: &plan,
        frames: movie.len(),
        size: (w, h),
        csv: &mut csv,
    };
    // A signal stops tracking after the frame in progress; the frames tracked are then
    // written as a whole result (masks with their res_track.txt), as a batch summarises.
    super::signals::stop_gently();
    let mut tracked = 0;
    // The note that the cells cover most of a frame is given once.
    let mut crowded_said = false;
    for image in movie.frames().map_err(|e| bad(e.to_string()))? {
        if super::signals::stop_asked() {
            break;
        }
        tracked += 1;
        let image = image.map_err(|e| bad(e.to_string()))?;
        let frame = tracker.step(&image).map_err(|e| bad(e.to_string()))?;
        if frame.frame == 0 {
            if let Some(hint) = object_hint(tracker.labels(), a.object) {
                note(&hint);
                crowded_said = true;
            }
            if (a.object, a.modality) == (Polarity::Dark, Modality::Generic)
                && crate::image::modality::looks_haloed(&image, tracker.labels())
            {
                note("note: the cells wear a bright halo, as in phase contrast; --modality phase-contrast reads the halo as background and drops specks far smaller than the cells");
            }
        }
        if !crowded_said && frame.frame > 0 {
            if let Some(hint) = crowded_hint(&frame, w, h) {
                note(&hint);
                crowded_said = true;
            }
        }
        if let Some(mut before) = held.take() {
            before.frame.revise(&frame);
            revise_labels(&mut before.labels, w, &frame);
            if let Some(last) = kept.last_mut() {
                last.revise(&frame);
            }
            out.write(&before, tracker.lineage())?;
        }
        if a.json.is_some() {
            kept.push(frame.clone());
        }
        held = Some(Held {
            labels: tracker.labels().to_vec(),
            frame,
            image,
        });
    }
    if tracked == 0 {
        // Stopped before frame 0: an earlier result in the folders stays as it was.
        return Err(Failure {
            code: 130,
            message: "interrupted before the first frame: nothing tracked or written".into(),
        });
    }
    if let Some(last) = held {
        out.write(&last, tracker.lineage())?;
    }
    let lineage = tracker.lineage();
    if let Some(dir) = &plan.ctc {
        let written: Vec<String> = (0..tracked)
            .map(|t| ctc::mask_name(t, movie.len()))
            .collect();
        let removed = ctc::remove_stale_masks(dir, &written).map_err(|e| {
            bad(format!(
                "cannot clear the old masks of {}: {e}",
                dir.display()
            ))
        })?;
        write(&dir.join("res_track.txt"), lineage.ctc_text().as_bytes())?;
        if removed > 0 {
            note(&format!(
                "note: removed {} of an earlier result from {}",
                counted(removed, "mask"),
                dir.display()
            ));
        }
    }
    if let (Some(out), None) = (&plan.overlay, a.overlay_frame) {
        let removed = remove_stale_overlays(out, tracked, movie.len(), &movie.files())?;
        if removed > 0 {
            note(&format!(
                "note: removed {} of an earlier sequence beside {}",
                counted(removed, "overlay frame"),
                out.display()
            ));
        }
    }
    let mut contents = Vec::new();
    if a.json.is_some() {
        contents.push(ctc::json(movie.name(), &kept, lineage).into_bytes());
    }
    if a.tracks_csv.is_some() {
        contents.push(csv.into_bytes());
    }
    plan.files
        .commit(contents)
        .map_err(|e| bad(e.to_string()))?;
    let divisions = lineage.tracks().iter().filter(|t| t.parent != 0).count() / 2;
    if tracked < movie.len() {
        return Err(Failure {
            code: 130,
            message: format!(
                "interrupted: frames 0 to {} of {} tracked and written ({}, {})",
                tracked - 1,
                movie.len(),
                counted(lineage.tracks().len(), "track"),
                counted(divisions, "division")
            ),
        });
    }
    note(&format!(
        "tracked {} frames of {}: {}, {}",
        movie.len(),
        movie.name(),
        counted(lineage.tracks().len(), "track"),
        counted(divisions, "division")
    ));
    Ok(())
}

/// A tracked frame not yet written: its cells, label raster and image.
struct Held {
    frame: TrackedFrame,
    labels: Vec<u32>,
    image: Field,
}

/// Where the frames go as they are written.
struct Out<'a> {
    a: &'a TrackArgs,
    plan: &'a Plan,
    frames: usize,
    size: (usize, usize),
    csv: &'a mut String,
}

impl Out<'_> {
    /// Writes one frame: its mask, its overlay if asked, its CSV rows.
    fn write(&mut self, held: &Held, lineage: &Lineage) -> Result<(), Failure> {
        let (a, (w, h), t) = (self.a, self.size, held.frame.frame);
        // The masks, as the label images and the CSV give the cells.
        let labels = (self.plan.ctc.is_some() || a.tracks_csv.is_some())
            .then(|| crate::image::widen::to_edges(&held.labels, &held.image));
        if let (Some(dir), Some(labels)) = (&self.plan.ctc, &labels) {
            let bytes = ctc::label_image(labels, w, h, true)
                .ok_or_else(|| bad("more than 65,535 tracks for 16-bit label images"))?;
            // An earlier result's res_track.txt would describe masks this run replaces
            // one by one (and, killed, leaves mixed): it goes before the first mask and
            // comes back at the end, once the masks are this run's alone.
            let res = dir.join("res_track.txt");
            if t == 0 && res.is_file() {
                std::fs::remove_file(&res)
                    .map_err(|e| bad(format!("cannot replace {}: {e}", res.display())))?;
            }
            write(&dir.join(ctc::mask_name(t, self.frames)), &bytes)?;
        }
        if let Some(out) = &self.plan.overlay {
            if a.overlay_frame.is_none_or(|f| f == t) {
                let path = match a.overlay_frame {
                    Some(_) => out.clone(),
                    None => numbered(out, t, self.frames),
                };
                let (rgb, ow, oh) = ctc::overlay_rgb(&held.image, &held.frame);
                write(&path, &ctc::png(&rgb, ow, oh))?;
            }
        }
        if let (Some(_), Some(labels)) = (&a.tracks_csv, &labels) {
            self.csv.push_str(&ctc::csv_rows(t, labels, w, lineage));
        }
        Ok(())
    }
}

/// Checks the outputs: the CTC folder is made if missing (it must not be a file, and its
/// own folder must exist), the JSON and CSV get their temporaries.
fn prepare(a: &TrackArgs) -> Result<Plan, Failure> {
    if a.ctc.is_none() && a.json.is_none() && a.tracks_csv.is_none() && a.overlay.is_none() {
        return Err(bad(
            "no output: give --ctc OUT, --json OUT, --tracks-csv OUT or --overlay OUT.png",
        ));
    }
    let files: Vec<&Path> = [&a.json, &a.tracks_csv]
        .into_iter()
        .filter_map(|p| p.as_deref())
        .collect();
    let frames = movie_frames(a)?;
    let inputs: Vec<(&Path, &'static str)> = std::iter::once((a.movie.as_path(), "movie"))
        .chain(frames.iter().map(|f| (f.as_path(), "movie frame")))
        .collect();
    let files = OutputFiles::prepare_for(&inputs, &files).map_err(|e| bad(e.to_string()))?;
    apart_from_movie(a)?;
    if let Some(out) = &a.overlay {
        crate::io::Format::Overlay
            .check_name(out)
            .map_err(|e| bad(format!("--overlay {}: {e}", out.display())))?;
        // A sequence's files are named after it: a special file (/dev/null) names none.
        if a.overlay_frame.is_none() && out.exists() && !out.is_file() {
            return Err(bad(format!(
                "--overlay {}: not a file name (one PNG per frame is named after it)",
                out.display()
            )));
        }
        // A movie file named as one of the sequence's frames would be replaced by it.
        if a.overlay_frame.is_none() {
            for &(input, _) in &inputs {
                let name = input.file_name().map(|n| n.to_string_lossy().into_owned());
                if folder_of(input) == folder_of(out)
                    && name.is_some_and(|n| sequence_index(out, &n).is_some())
                {
                    return Err(bad(format!(
                        "--overlay {}: its frames are named like the movie's file {}; give another name",
                        out.display(),
                        input.display()
                    )));
                }
            }
        }
        // Its folder, name and kind checked now, not after the frames before it are
        // tracked (a sequence by its first file; its temporaries go with the check).
        let first = match a.overlay_frame {
            Some(_) => out.clone(),
            None => numbered(out, 0, 1),
        };
        let mut all: Vec<&Path> = vec![&first];
        all.extend(a.json.as_deref());
        all.extend(a.tracks_csv.as_deref());
        OutputFiles::prepare_for(&inputs, &all).map_err(|e| bad(format!("--overlay: {e}")))?;
    }
    if let Some(dir) = &a.ctc {
        // An existing --ctc that is not a folder was refused by `apart_from_movie`.
        super::output_folder("--ctc", dir)?;
    }
    Ok(Plan {
        files,
        ctc: a.ctc.clone(),
        overlay: a.overlay.clone(),
    })
}

/// The frame files of a movie that is a folder (none for a TIFF).
fn movie_frames(a: &TrackArgs) -> Result<Vec<PathBuf>, Failure> {
    if !a.movie.is_dir() {
        return Ok(Vec::new());
    }
    crate::io::folder::list_images(&a.movie)
        .map_err(|e| bad(format!("cannot read {}: {e}", a.movie.display())))
}

/// The canonical folder `p` lies in (the current one for a bare name), if it exists.
fn folder_of(p: &Path) -> Option<PathBuf> {
    let dir = p
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    dir.canonicalize().ok()
}

/// Outputs that would land among the movie's frames or the CTC result's own files:
/// refused before anything is tracked. A file output inside a folder movie would be read
/// as a frame next time (or replace one); a file output or a TIFF movie named as a mask
/// or `res_track.txt` inside the `--ctc` folder would be overwritten or cleared by it.
fn apart_from_movie(a: &TrackArgs) -> Result<(), Failure> {
    let named: Vec<(&str, &Path)> = [
        ("--json", a.json.as_deref()),
        ("--tracks-csv", a.tracks_csv.as_deref()),
        ("--overlay", a.overlay.as_deref()),
    ]
    .into_iter()
    .filter_map(|(f, p)| Some((f, p?)))
    .collect();
    if a.movie.is_dir() {
        let movie = a.movie.canonicalize().ok();
        for &(flag, p) in &named {
            if movie.is_some() && folder_of(p) == movie {
                return Err(bad(format!(
                    "{flag} {}: inside the movie's folder, where it would be read as a frame; write it elsewhere",
                    p.display()
                )));
            }
        }
    }
    if let Some(d) = a.ctc.as_deref().filter(|d| d.is_symlink() && !d.exists()) {
        return Err(bad(format!(
            "--ctc {}: a symbolic link to nothing; give a folder",
            d.display()
        )));
    }
    let Some((given, ctc)) = a
        .ctc
        .as_deref()
        .and_then(|d| Some((d, d.canonicalize().ok()?)))
    else {
        return Ok(());
    };
    if a.movie.canonicalize().ok().as_ref() == Some(&ctc) {
        let what = if a.movie.is_dir() {
            "the movie's own folder"
        } else {
            "the movie itself"
        };
        return Err(bad(format!(
            "--ctc {}: that is {what}; give another folder for the result",
            given.display()
        )));
    }
    if !ctc.is_dir() {
        return Err(bad(format!(
            "--ctc {}: not a folder (the result is a folder of masks)",
            given.display()
        )));
    }
    let name = |p: &Path| {
        p.file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    if !a.movie.is_dir()
        && folder_of(&a.movie).as_ref() == Some(&ctc)
        && ctc::is_result_name(&name(&a.movie))
    {
        return Err(bad(format!(
            "--ctc {}: the movie {} is named as a file of the result, which would replace it",
            ctc.display(),
            a.movie.display()
        )));
    }
    for &(flag, p) in &named {
        if folder_of(p).as_ref() == Some(&ctc) && ctc::is_result_name(&name(p)) {
            return Err(bad(format!(
                "{flag} {}: a file of the --ctc result; give another name",
                p.display()
            )));
        }
    }
    // What the result will write or clear must be regular files where they exist.
    let entries =
        std::fs::read_dir(&ctc).map_err(|e| bad(format!("cannot read {}: {e}", ctc.display())))?;
    for e in entries.flatten() {
        let n = e.file_name().to_string_lossy().into_owned();
        if ctc::is_result_name(&n) && !e.file_type().is_ok_and(|t| t.is_file()) {
            return Err(bad(format!(
                "--ctc {}: {n} there is not a regular file",
                ctc.display()
            )));
        }
    }
    Ok(())
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    write_atomic(path, bytes).map_err(|e| bad(e.to_string()))
}

/// Removes the overlays of an earlier sequence beside `out`'s: regular files named as
/// this run numbers its frames (`frames` of them, the same digit count), from frame
/// `tracked` on. As for the CTC masks: a sequence written over a longer one, or stopped
/// early, would otherwise go on with frames of another run. Files of other names or
/// digit counts, links, and the movie's own `inputs` are left alone. Returns how many
/// it removed.
fn remove_stale_overlays(
    out: &Path,
    tracked: usize,
    frames: usize,
    inputs: &[&Path],
) -> Result<usize, Failure> {
    let Some(dir) = folder_of(out) else {
        return Ok(0);
    };
    let mut removed = 0;
    let digits = frame_digits(frames);
    let failed = |e: std::io::Error| {
        bad(format!(
            "cannot clear the old overlays beside {}: {e}",
            out.display()
        ))
    };
    let inputs: Vec<PathBuf> = inputs
        .iter()
        .filter_map(|p| p.canonicalize().ok())
        .collect();
    for entry in std::fs::read_dir(dir).map_err(failed)? {
        let entry = entry.map_err(failed)?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let stale = sequence_index(out, &name).is_some_and(|(t, d)| d == digits && t >= tracked);
        if stale
            && entry.file_type().map_err(failed)?.is_file()
            && !entry
                .path()
                .canonicalize()
                .is_ok_and(|p| inputs.contains(&p))
        {
            std::fs::remove_file(entry.path()).map_err(failed)?;
            removed += 1;
        }
    }
    Ok(removed)
}

/// `out`'s stem and extension, as a sequence's file names use them (`overlay`, `png`
/// for a name without).
fn sequence_parts(out: &Path) -> (&str, &str) {
    let stem = out
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("overlay");
    (
        stem,
        out.extension().and_then(|s| s.to_str()).unwrap_or("png"),
    )
}

/// Digits of a sequence's frame numbers for a movie of `frames` frames (three at least).
fn frame_digits(frames: usize) -> usize {
    frames.saturating_sub(1).to_string().len().max(3)
}

/// The frame number and its digit count of `name` if it is named as a frame of `out`'s
/// sequence ([`numbered`]).
fn sequence_index(out: &Path, name: &str) -> Option<(usize, usize)> {
    let (stem, ext) = sequence_parts(out);
    let d = name
        .strip_prefix(stem)?
        .strip_prefix('.')?
        .strip_suffix(ext)?
        .strip_suffix('.')?;
    let digits = d.len() >= 3 && d.bytes().all(|b| b.is_ascii_digit());
    digits.then(|| Some((d.parse().ok()?, d.len()))).flatten()
}

/// `out` with frame `t` before its extension: `a.png` → `a.007.png`.
fn numbered(out: &Path, t: usize, frames: usize) -> PathBuf {
    let digits = frame_digits(frames);
    let (stem, ext) = sequence_parts(out);
    out.with_file_name(format!("{stem}.{t:0digits$}.{ext}"))
}
