//! The headless command line: `topocontour segment …` with the contract of DESIGN.md,
//! and `topocontour bench …` that times the whole pipeline in-process.

use crate::contours::BroadPhaseKind;
use crate::evolution::{find_seeds, Evolver, Field, Modality, Mode, Params, Polarity, Shape};
use crate::geometry::Point;
use crate::io::{load_image, OutputFiles, Outputs};
use clap::{Args, Parser, Subcommand, ValueEnum};
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
    #[command(subcommand)]
    pub command: Option<Command>,
    /// An image to open in the desktop app.
    pub image: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Segment an image headless and write the results.
    Segment(Box<SegmentArgs>),
    /// Time the whole pipeline (load, evolve, export) on case folders.
    Bench(BenchArgs),
}

#[derive(Args, Debug, Clone)]
pub struct SegmentArgs {
    /// PNG, JPEG or TIFF image (8 or 16 bit, gray or colour).
    pub image: PathBuf,
    /// A seed disk at X,Y with radius R (pixels); repeat for more.
    #[arg(long = "seed", value_name = "X,Y,R", value_parser = parse_seed)]
    pub seeds: Vec<(f64, f64, f64)>,
    /// A rectangle MARGIN pixels inside the image border, to shrink-wrap everything.
    #[arg(long, value_name = "MARGIN", allow_negative_numbers = true)]
    pub wrap: Option<f64>,
    /// One seed per object, found by the tool (distance-transform maxima of the local
    /// threshold); adds to any other shapes.
    #[arg(long)]
    pub auto_seeds: bool,
    /// A rectangle X0,Y0,X1,Y1.
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_rect)]
    pub rect: Vec<(f64, f64, f64, f64)>,
    /// Whether objects are darker or brighter than the background.
    #[arg(long, value_enum)]
    pub object: Polarity,
    #[arg(long, value_enum, default_value = "adaptive")]
    pub mode: Mode,
    /// The kind of image: phase contrast treats the bright halo as background.
    #[arg(long, value_enum, default_value = "generic")]
    pub modality: Modality,
    /// Radius of the local intensity statistics in pixels (default: from the image's
    /// object scale).
    #[arg(long, value_name = "PX")]
    pub local_radius: Option<f64>,
    /// Write contours and events as JSON.
    #[arg(long, value_name = "OUT")]
    pub json: Option<PathBuf>,
    /// Write a mask PNG (255 inside).
    #[arg(long, value_name = "OUT.png")]
    pub mask: Option<PathBuf>,
    /// Write an SVG of the regions.
    #[arg(long, value_name = "OUT")]
    pub svg: Option<PathBuf>,
    /// Write GeoJSON polygons.
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
    /// Stop after this many frames.
    #[arg(long, value_name = "N")]
    pub max_frames: Option<usize>,
    /// Drop regions and holes smaller than this (square pixels).
    #[arg(long, value_name = "PX", allow_negative_numbers = true)]
    pub min_area: Option<f64>,
    /// Broad phase of the crossing search: vertex bins or staggered hashing (same result).
    #[arg(long, value_enum, default_value = "bins")]
    pub broad_phase: BroadPhaseKind,
}

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Case folders (image.png + case.json), or folders of them.
    pub cases: Vec<PathBuf>,
    /// Runs per case.
    #[arg(long, default_value_t = 10)]
    pub runs: usize,
    /// Broad phase of the crossing search.
    #[arg(long, value_enum, default_value = "bins")]
    pub broad_phase: BroadPhaseKind,
    /// Engine to time.
    #[arg(long, value_enum, default_value = "adaptive")]
    pub mode: Mode,
}

fn parse_numbers<const N: usize>(s: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != N {
        return Err(format!("expected {N} comma-separated numbers, got '{s}'"));
    }
    let mut out = [0.0; N];
    for (o, p) in out.iter_mut().zip(parts) {
        *o = p
            .trim()
            .parse::<f64>()
            .map_err(|_| format!("'{p}' is not a number"))?;
        if !o.is_finite() {
            return Err(format!("'{p}' is not a finite number"));
        }
    }
    Ok(out)
}

fn parse_seed(s: &str) -> Result<(f64, f64, f64), String> {
    let [x, y, r] = parse_numbers::<3>(s)?;
    if r <= 0.0 {
        return Err(format!("seed radius must be positive, got {r}"));
    }
    Ok((x, y, r))
}

fn parse_rect(s: &str) -> Result<(f64, f64, f64, f64), String> {
    let [x0, y0, x1, y1] = parse_numbers::<4>(s)?;
    if x1 <= x0 || y1 <= y0 {
        return Err(format!("rectangle needs X0 < X1 and Y0 < Y1, got {s}"));
    }
    Ok((x0, y0, x1, y1))
}

/// A failure to report: exit code 2 for bad input, 1 for internal errors.
#[derive(Debug)]
pub struct Failure {
    pub code: i32,
    pub message: String,
}

fn bad(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}

/// The shapes a segment command asks for, checked against the image size.
pub fn init_shapes(a: &SegmentArgs, width: usize, height: usize) -> Result<Vec<Shape>, Failure> {
    let (w, h) = (width as f64, height as f64);
    let mut shapes = Vec::new();
    let diagonal = w.hypot(h);
    for &(x, y, r) in &a.seeds {
        if !(0.0..=w).contains(&x) || !(0.0..=h).contains(&y) {
            return Err(bad(format!(
                "seed {x},{y} lies outside the {width}×{height} image"
            )));
        }
        if r > diagonal {
            return Err(bad(format!(
                "seed radius {r} is larger than the image's diagonal ({diagonal:.0} px)"
            )));
        }
        shapes.push(Shape::Disk {
            center: Point::new(x, y),
            radius: r,
        });
    }
    if let Some(m) = a.wrap {
        if !m.is_finite() || m < 0.0 || 2.0 * m + 2.0 > w.min(h) {
            return Err(bad(format!(
                "wrap margin must be between 0 and {} for a {width}×{height} image, got {m}",
                ((w.min(h) - 2.0) / 2.0).max(0.0)
            )));
        }
        shapes.push(Shape::Rect {
            min: Point::new(m, m),
            max: Point::new(w - m, h - m),
        });
    }
    for &(x0, y0, x1, y1) in &a.rect {
        if x0 < 0.0 || y0 < 0.0 || x1 > w || y1 > h {
            return Err(bad(format!(
                "rectangle {x0},{y0},{x1},{y1} is not inside the {width}×{height} image"
            )));
        }
        shapes.push(Shape::Rect {
            min: Point::new(x0, y0),
            max: Point::new(x1, y1),
        });
    }
    if shapes.is_empty() && !a.auto_seeds {
        return Err(bad(
            "no initialisation: give --seed X,Y,R, --wrap MARGIN, --rect X0,Y0,X1,Y1 or --auto-seeds",
        ));
    }
    Ok(shapes)
}

/// Params for a segment command.
pub fn params_for(a: &SegmentArgs) -> Result<Params, Failure> {
    let mut p = Params {
        mode: a.mode,
        polarity: a.object,
        modality: a.modality,
        broad_phase: a.broad_phase,
        ..Params::default()
    };
    if let Some(r) = a.local_radius {
        if !(r.is_finite() && r >= 1.0) {
            return Err(bad(format!("--local-radius must be a number ≥ 1, got {r}")));
        }
        p.local_radius = Some(r);
    }
    if let Some(n) = a.max_frames {
        if n == 0 {
            return Err(bad("--max-frames must be at least 1"));
        }
        p.max_frames = n;
    }
    if let Some(m) = a.min_area {
        if !m.is_finite() || m < 0.0 {
            return Err(bad(format!("--min-area must be a number ≥ 0, got {m}")));
        }
        p.min_area = m;
    }
    Ok(p)
}

/// The output paths a segment command asks for, in a fixed order.
fn output_paths(a: &SegmentArgs) -> Vec<&Path> {
    [
        &a.json, &a.mask, &a.svg, &a.geojson, &a.csv, &a.overlay, &a.labels,
    ]
    .into_iter()
    .flatten()
    .map(PathBuf::as_path)
    .collect()
}

/// The outputs' bytes once the run is done, in the order of [`output_paths`].
fn render(a: &SegmentArgs, out: &Outputs, image: &Field) -> Result<Vec<Vec<u8>>, Failure> {
    let mut files = Vec::new();
    if a.json.is_some() {
        files.push(out.json().into_bytes());
    }
    if a.mask.is_some() {
        files.push(out.mask_png());
    }
    if a.svg.is_some() {
        files.push(out.svg().into_bytes());
    }
    if a.geojson.is_some() {
        files.push(out.geojson().into_bytes());
    }
    if a.csv.is_some() {
        files.push(out.csv().into_bytes());
    }
    if a.overlay.is_some() {
        files.push(out.overlay_png(image));
    }
    if let Some(p) = &a.labels {
        let tiff = p
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("tif") || e.eq_ignore_ascii_case("tiff"));
        files.push(out.labels_image(tiff).ok_or_else(|| {
            bad(format!(
                "cannot write {}: more than 65,535 objects for a 16-bit label image",
                p.display()
            ))
        })?);
    }
    Ok(files)
}

/// Loads the image and evolves the contours to the end; returns the evolver and the
/// image.
fn evolve(a: &SegmentArgs) -> Result<(Evolver, Field), Failure> {
    let image = load_image(&a.image).map_err(|e| bad(e.to_string()))?;
    let mut shapes = init_shapes(a, image.width, image.height)?;
    let params = params_for(a)?;
    if a.auto_seeds {
        let found = find_seeds(&image, params.polarity, params.modality);
        if found.is_empty() && shapes.is_empty() {
            return Err(bad(format!(
                "--auto-seeds found no {} object in {}",
                match a.object {
                    Polarity::Dark => "dark",
                    Polarity::Bright => "bright",
                },
                a.image.display()
            )));
        }
        shapes.extend(found);
    }
    let mut ev = Evolver::new(&image, &shapes, params).map_err(|e| bad(e.to_string()))?;
    ev.run();
    ev.filter_clutter();
    Ok((ev, image))
}

fn outputs(ev: &Evolver, width: usize, height: usize) -> Outputs<'_> {
    Outputs {
        set: ev.contours(),
        width,
        height,
        frames: ev.frames(),
        converged: ev.is_converged(),
        events: ev.events(),
        mode: ev.params().mode.name(),
        held: ev.held_contacts(),
    }
}

/// Writes a line to stderr; a full or closed stderr loses the line, never the run.
pub fn note(line: &str) {
    let _ = writeln!(std::io::stderr().lock(), "topocontour: {line}");
}

/// Runs `segment` and writes its outputs; returns the finished evolver.
pub fn segment(a: &SegmentArgs) -> Result<Evolver, Failure> {
    // Every output is checked, and its temporary created, before any work.
    let files =
        OutputFiles::prepare(Some(&a.image), &output_paths(a)).map_err(|e| bad(e.to_string()))?;
    let (ev, image) = evolve(a)?;
    let out = outputs(&ev, image.width, image.height);
    if out.held > 0 {
        // The user asked for fixed topology; say where it mattered.
        note(&format!(
            "note: mode {} kept the initial topology ({} contours); fronts were held apart at {} places where adaptive mode would merge, split or close holes",
            out.mode,
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
    files
        .commit(render(a, &out, &image)?)
        .map_err(|e| bad(e.to_string()))?;
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
        Ok(SegmentArgs {
            image: dir.join("image.png"),
            seeds: init.seeds.iter().map(|&[x, y, r]| (x, y, r)).collect(),
            auto_seeds: false,
            wrap: init.border_margin,
            rect: Vec::new(),
            object: init.object,
            mode: Mode::Adaptive,
            modality: init.modality,
            json: None,
            mask: None,
            svg: None,
            geojson: None,
            csv: None,
            overlay: None,
            labels: None,
            local_radius: None,
            max_frames: None,
            min_area: None,
            broad_phase: BroadPhaseKind::Bins,
        })
    }
}

/// Times `segment` (in memory, without writing) on case folders.
pub fn bench(b: &BenchArgs) -> Result<(), Failure> {
    let mut dirs = Vec::new();
    for c in &b.cases {
        if c.join("case.json").is_file() {
            dirs.push(c.clone());
        } else if let Ok(rd) = std::fs::read_dir(c) {
            let mut sub: Vec<PathBuf> = rd
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.join("case.json").is_file())
                .collect();
            sub.sort();
            dirs.extend(sub);
        } else {
            return Err(bad(format!("{} is not a case folder", c.display())));
        }
    }
    let mut stdout = std::io::stdout().lock();
    // A closed pipe (`| head`) ends the output quietly instead of panicking.
    if writeln!(
        stdout,
        "{:<18} {:>8} {:>8} {:>8} {:>7} {:>9}",
        "case", "min ms", "median", "max ms", "frames", "contours"
    )
    .is_err()
    {
        return Ok(());
    }
    for d in dirs {
        let mut args = SegmentArgs::from_case(&d)?;
        args.broad_phase = b.broad_phase;
        args.mode = b.mode;
        let mut times = Vec::new();
        let (mut frames, mut contours) = (0, 0);
        for _ in 0..b.runs.max(1) {
            let t = std::time::Instant::now();
            let (ev, image) = evolve(&args)?;
            let out = outputs(&ev, image.width, image.height);
            std::hint::black_box((out.json(), out.mask_png()));
            times.push(t.elapsed().as_secs_f64() * 1e3);
            frames = ev.frames();
            contours = ev.contours().contour_count();
        }
        times.sort_by(f64::total_cmp);
        let name = d
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if writeln!(
            stdout,
            "{:<18} {:>8.1} {:>8.1} {:>8.1} {:>7} {:>9}",
            name,
            times[0],
            times[times.len() / 2],
            times[times.len() - 1],
            frames,
            contours
        )
        .is_err()
        {
            return Ok(());
        }
    }
    Ok(())
}
