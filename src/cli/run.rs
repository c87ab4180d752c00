//! What every subcommand that segments shares: the initialisation and parameter flags
//! ([`RunSettings`]), their checks against the image, and the [`Job`] they describe.

use super::{bad, Failure};
use crate::contours::BroadPhaseKind;
use crate::evolution::{Field, Modality, Mode, Params, Polarity, Shape};
use crate::geometry::Point;
use crate::io::{ImageInfo, PixelSize};
use crate::job::{Job, JobRun};
use crate::learn::{Strokes, Teach};
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

/// How to initialise and evolve: the flags `segment` and `batch` share.
#[derive(Args, Debug, Clone)]
pub struct RunSettings {
    /// A seed disk at X,Y with radius R (pixels); repeat for more.
    #[arg(long = "seed", value_name = "X,Y,R", value_parser = parse_seed, allow_hyphen_values = true)]
    pub seeds: Vec<(f64, f64, f64)>,
    /// A rectangle MARGIN pixels inside the image border, to shrink-wrap everything.
    #[arg(long, value_name = "MARGIN", allow_negative_numbers = true)]
    pub wrap: Option<f64>,
    /// One seed per object, found by the tool (distance-transform maxima of the local
    /// threshold); adds to any other shapes.
    #[arg(long)]
    pub auto_seeds: bool,
    /// Strokes painted on the image, a PNG of its size (0 none, 1 background, 2 object,
    /// 3 boundary between touching objects): a pixel classifier learns them and the
    /// contours follow its probabilities (--auto-seeds then seeds its objects).
    #[arg(long, value_name = "STROKES.png", conflicts_with = "classifier")]
    pub train: Option<PathBuf>,
    /// A trained pixel classifier (from `train` or `segment --save-classifier`): the
    /// contours follow its probabilities, as with --train.
    #[arg(long, value_name = "FILE")]
    pub classifier: Option<PathBuf>,
    /// A rectangle X0,Y0,X1,Y1.
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_rect, allow_hyphen_values = true)]
    pub rect: Vec<(f64, f64, f64, f64)>,
    /// Whether objects are darker or brighter than the background.
    #[arg(long, value_enum)]
    pub object: Polarity,
    /// What may happen to the objects' shapes as the contours move [default: track for a
    /// run taught by --train or --classifier, else adaptive].
    #[arg(long, value_parser = choices::<Mode>(MODES))]
    pub mode: Option<Mode>,
    /// The kind of image: phase contrast treats the bright halo as background.
    #[arg(long, value_enum, default_value = "generic")]
    pub modality: Modality,
    /// Radius of the local intensity statistics in pixels (default: from the image's
    /// object scale).
    #[arg(long, value_name = "PX")]
    pub local_radius: Option<f64>,
    /// Adaptive mode: do not open holes where a region covers clear background (holes
    /// then come only from fronts that meet).
    #[arg(long)]
    pub no_new_holes: bool,
    /// Stop after this many frames.
    #[arg(long, value_name = "N")]
    pub max_frames: Option<usize>,
    /// Drop regions and holes smaller than this (square pixels).
    #[arg(long, value_name = "PX", allow_negative_numbers = true)]
    pub min_area: Option<f64>,
    /// How the crossing search finds nearby edges (same result either way).
    #[arg(long, default_value = "bins", value_parser = choices::<BroadPhaseKind>(BROAD_PHASES))]
    pub broad_phase: BroadPhaseKind,
    /// The page of a multi-page TIFF (a stack) to segment, from 1.
    #[arg(long, value_name = "N")]
    pub page: Option<usize>,
    /// Side of a pixel in --unit (default: from the TIFF's resolution, if it has one);
    /// the CSV then gives calibrated areas and perimeters too.
    #[arg(long, value_name = "SIZE")]
    pub pixel_size: Option<f64>,
    /// The unit of --pixel-size.
    #[arg(long, value_name = "UNIT", default_value = "µm")]
    pub unit: String,
}

impl RunSettings {
    /// Settings with the given polarity and every other flag at its default.
    pub fn new(object: Polarity) -> Self {
        RunSettings {
            seeds: Vec::new(),
            wrap: None,
            auto_seeds: false,
            train: None,
            classifier: None,
            rect: Vec::new(),
            object,
            mode: None,
            modality: Modality::Generic,
            local_radius: None,
            no_new_holes: false,
            max_frames: None,
            min_area: None,
            broad_phase: BroadPhaseKind::Bins,
            page: None,
            pixel_size: None,
            unit: "µm".into(),
        }
    }
}

/// The engines in the user's words (the library's docs name the papers instead).
pub(super) const MODES: &[(&str, &str)] = &[
    (
        "adaptive",
        "contours merge where objects touch, split where one pinches off, and open or close holes",
    ),
    (
        "preserve",
        "each contour keeps its topology: touching objects stay apart, no hole opens or closes",
    ),
    (
        "implicit",
        "as preserve, computed on a pixel grid (fast marching) instead of moving the polygon",
    ),
    (
        "track",
        "one object per seed that may divide: contours never merge or make holes, but one that pinches splits",
    ),
];

/// The broad phases in the user's words.
pub(super) const BROAD_PHASES: &[(&str, &str)] = &[
    ("bins", "a grid of bins over the image"),
    ("hash", "four staggered hash grids"),
];

/// A parser of `T`'s values that shows `help` for each (name, what it does).
pub(super) fn choices<T: ValueEnum + Clone + Send + Sync + 'static>(
    help: &'static [(&'static str, &'static str)],
) -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(
        help.iter()
            .map(|&(name, h)| PossibleValue::new(name).help(h)),
    )
    .map(|name| T::from_str(&name, false).expect("every listed name is a value"))
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

pub(super) fn parse_seed(s: &str) -> Result<(f64, f64, f64), String> {
    let [x, y, r] = parse_numbers::<3>(s)?;
    if r <= 0.0 {
        return Err(format!("seed radius must be positive, got {r}"));
    }
    Ok((x, y, r))
}

pub(super) fn parse_rect(s: &str) -> Result<(f64, f64, f64, f64), String> {
    let [x0, y0, x1, y1] = parse_numbers::<4>(s)?;
    if x1 <= x0 || y1 <= y0 {
        return Err(format!("rectangle needs X0 < X1 and Y0 < Y1, got {s}"));
    }
    Ok((x0, y0, x1, y1))
}

/// The shapes the settings ask for, checked against the image size.
pub fn init_shapes(a: &RunSettings, width: usize, height: usize) -> Result<Vec<Shape>, Failure> {
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

/// The engine the settings ask for: `--mode`, else the default for a run taught by
/// strokes or a classifier, or not ([`Mode::default_for`]).
pub fn mode_of(a: &RunSettings) -> Mode {
    a.mode
        .unwrap_or_else(|| Mode::default_for(a.train.is_some() || a.classifier.is_some()))
}

/// Params for the settings.
pub fn params_for(a: &RunSettings) -> Result<Params, Failure> {
    let mut p = Params {
        mode: mode_of(a),
        polarity: a.object,
        modality: a.modality,
        broad_phase: a.broad_phase,
        open_holes: !a.no_new_holes,
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

/// The job the settings describe on the image at `path`, every flag checked; its shapes
/// come from [`init_shapes`] once the image's size is known.
pub fn job_for(path: &Path, a: &RunSettings) -> Result<Job, Failure> {
    let page = match a.page {
        Some(0) => return Err(bad("--page counts from 1")),
        Some(n) => n - 1,
        None => 0,
    };
    let pixel_size = match a.pixel_size {
        Some(size) if !(size.is_finite() && size > 0.0) => {
            return Err(bad(format!(
                "--pixel-size must be a number > 0, got {size}"
            )))
        }
        Some(size) => Some(PixelSize {
            size,
            unit: a.unit.clone(),
        }),
        None => None,
    };
    Ok(Job {
        page,
        auto_seeds: a.auto_seeds,
        pixel_size,
        ..Job::new(path, Vec::new(), params_for(a)?)
    })
}

/// The classifier `--classifier` names, read and checked once (a batch shares it).
pub fn classifier_for(a: &RunSettings) -> Result<Option<Teach>, Failure> {
    a.classifier
        .as_deref()
        .map(|p| {
            crate::io::classifier::read(p)
                .map(Teach::classifier)
                .map_err(|e| bad(e.to_string()))
        })
        .transpose()
}

/// Loads `path` (page `--page` of a stack) and runs the job the settings describe on it:
/// what `segment` and each image of `batch` do; `teach` is the `--classifier`
/// ([`classifier_for`]), `--train` is read here against the image. Returns the job too
/// (a session records it).
pub(super) fn evolve(
    path: &Path,
    a: &RunSettings,
    teach: Option<&Teach>,
) -> Result<(Job, JobRun), Failure> {
    let mut job = job_for(path, a)?;
    let (image, info) = job.load().map_err(|e| bad(e.to_string()))?;
    job.teach = teach_for(a, teach, &image)?;
    if a.page.is_none() && info.pages > 1 {
        super::note(&format!(
            "note: {} holds {} pages; segmenting page 1 (choose another with --page)",
            path.display(),
            info.pages
        ));
    }
    let run = run_loaded(&mut job, a, image, info)?;
    Ok((job, run))
}

/// What teaches the run on `image`: the `--train` strokes read against it, else
/// `teach` (the `--classifier`, [`classifier_for`], or one held in memory).
pub fn teach_for(
    a: &RunSettings,
    teach: Option<&Teach>,
    image: &Field,
) -> Result<Option<Teach>, Failure> {
    Ok(match &a.train {
        Some(p) => Some(Teach::strokes(
            Strokes::read(p, image.width, image.height).map_err(|e| bad(e.to_string()))?,
        )),
        None => teach.cloned(),
    })
}

/// Runs `job` (from [`job_for`]) on its image, already loaded, with the settings' shapes
/// checked against the image's size: what `segment` does after loading, which the
/// Python bindings share with an image handed over in memory.
pub fn run_loaded(
    job: &mut Job,
    a: &RunSettings,
    image: Field,
    info: ImageInfo,
) -> Result<JobRun, Failure> {
    if let Some(p) = &job.pixel_size {
        let area = p.size * p.size * (image.width * image.height) as f64;
        if !(area.is_finite() && p.size * p.size > 0.0) {
            return Err(bad(format!(
                "--pixel-size {} puts the image's area out of range; give it in another --unit",
                p.size
            )));
        }
    }
    job.shapes = init_shapes(a, image.width, image.height)?;
    job.run_on(image, info).map_err(|e| bad(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The user's words list every value of the enums, and only those.
    #[test]
    fn choices_name_every_value() {
        fn names<T: ValueEnum>() -> Vec<String> {
            T::value_variants()
                .iter()
                .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
                .collect()
        }
        let listed = |h: &[(&str, &str)]| h.iter().map(|(n, _)| n.to_string()).collect::<Vec<_>>();
        assert_eq!(names::<Mode>(), listed(MODES));
        assert_eq!(names::<BroadPhaseKind>(), listed(BROAD_PHASES));
    }
}
