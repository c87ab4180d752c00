//! What an evolution is asked to do: the engine ([`Mode`]), its [`Params`] and why a run
//! could not start ([`EvolveError`]), with the checks made before anything moves.

use super::forces::ForceWeights;
use crate::contours::BroadPhaseKind;
use crate::geometry::Point;
use crate::image::{Modality, ModelParams, Polarity};
use crate::shape::Shape;

/// How topology may change.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Mode {
    /// Contours split, merge, make and lose holes (seed 003).
    Adaptive,
    /// Topology stays as initialised: moves that would cross are shortened to keep a gap
    /// and nearby parts repel (seed 004).
    Preserve,
    /// Topology stays as initialised, implicitly: fast marching on a cut-edge grid
    /// (seed 000; see [`super::implicit`]).
    Implicit,
    /// One object per seed that may divide: contours never merge and make no hole, but a
    /// contour that pinches splits (seed 003 under
    /// [`crate::topology::TopologyPolicy::TRACKING`]); what tracking cells needs.
    Track,
}

impl Mode {
    /// The name used on the command line and in exports.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Adaptive => "adaptive",
            Mode::Preserve => "preserve",
            Mode::Implicit => "implicit",
            Mode::Track => "track",
        }
    }

    /// The engine a run gets when the user names none: [`Mode::Track`] when a pixel
    /// classifier drives it, else [`Mode::Adaptive`].
    ///
    /// Why: with a classifier the user has painted where touching objects part (the
    /// boundary class), and a wrap gives way to the classifier's objects
    /// ([`crate::learn::guide::start_shapes`]), so each front stands for one object and
    /// two fronts that meet are two cells — they must not merge, though one may still
    /// part at a pinch. Without a classifier, fronts that meet are as often one object
    /// seeded twice (two clicks in one cell, found seeds on one cell's lobes) and a wrap
    /// encloses objects not yet counted: adaptive merges, splits and opens holes.
    /// Measured on the public cases, docs/decisions.md (2026-12-02): taught, mean SEG
    /// with automatic seeds 0.589 adaptive, 0.733 track; untaught, track would lose the
    /// topology of 4 of the 8 synthetic cases that adaptive gets right.
    pub fn default_for(taught: bool) -> Mode {
        if taught {
            Mode::Track
        } else {
            Mode::Adaptive
        }
    }
}

/// Parameters of an evolution. `Params::default()` is the one set that serves every
/// public case.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Params {
    /// Whether objects are darker or brighter than the background.
    pub polarity: Polarity,
    /// The engine: how topology may change.
    #[serde(default = "default_mode")]
    pub mode: Mode,
    /// Weights of the forces (region, balloon, edge, stretch, bend).
    pub weights: ForceWeights,
    /// Largest step per frame, as a fraction of the level's grid spacing.
    pub step: f64,
    /// Frames allowed in all.
    pub max_frames: usize,
    /// Outer regions and holes smaller than this many square pixels are dropped at the end.
    pub min_area: f64,
    /// Share of active vertices below which a level counts as converged.
    pub converged_share: f64,
    /// Coarsest pyramid level's short side, pixels.
    pub coarsest_side: usize,
    /// Broad phase of the crossing search (same results, different speed and memory).
    #[serde(default)]
    pub broad_phase: BroadPhaseKind,
    /// The kind of image (phase contrast clips the halo; see [`crate::image::local`]).
    #[serde(default)]
    pub modality: Modality,
    /// Compare with a local decision level (see [`crate::image::local`]) instead of the global one.
    #[serde(default = "default_local")]
    pub local: bool,
    /// Radius of the local statistics in pixels; `None`: from the seeds or the image.
    #[serde(default)]
    pub local_radius: Option<f64>,
    /// In the adaptive engine, open holes where a region covers clear background (see
    /// [`super::explicit::nucleate`]).
    #[serde(default = "default_open_holes")]
    pub open_holes: bool,
    /// The initialisation's polygons outline objects: the median inside them gives the
    /// object's intensity, as under a seed (tracking's carried contours: a few cells in a
    /// wide field are too few pixels for Otsu's split; see [`crate::image::hints`]).
    #[serde(default)]
    pub outline_hints: bool,
}

fn default_open_holes() -> bool {
    true
}

fn default_local() -> bool {
    true
}

fn default_mode() -> Mode {
    Mode::Adaptive
}

impl Params {
    /// The image's part of the parameters: what [`crate::image::ImageModel::prepare`] reads.
    pub fn model_params(&self) -> ModelParams {
        ModelParams {
            polarity: self.polarity,
            modality: self.modality,
            local: self.local,
            local_radius: self.local_radius,
            coarsest_side: self.coarsest_side,
            outline_hints: self.outline_hints,
        }
    }
}

impl Default for Params {
    fn default() -> Self {
        Params {
            polarity: Polarity::Dark,
            mode: Mode::Adaptive,
            weights: ForceWeights::default(),
            step: 0.75,
            max_frames: 3000,
            min_area: 20.0,
            converged_share: 0.03,
            coarsest_side: 64,
            broad_phase: BroadPhaseKind::Bins,
            modality: Modality::Generic,
            local: true,
            local_radius: None,
            open_holes: true,
            outline_hints: false,
        }
    }
}

/// Why an evolution could not start.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum EvolveError {
    /// No shape, or none left inside the image.
    #[error("the initialisation is empty: give at least one seed, rectangle or polygon")]
    EmptyInit,
    /// A shape with a non-finite coordinate or a disk larger than the image.
    #[error("a shape of the initialisation is not usable: {0}")]
    BadShape(String),
    /// The run would need more memory than is left.
    #[error("a {width}×{height} image needs about {:.1} GB to segment, more than the {:.1} GB this process may use; crop it into tiles and segment each", *.needs as f64 / 1e9, *.limit as f64 / 1e9)]
    TooLarge {
        /// Width of the image.
        width: usize,
        /// Height of the image.
        height: usize,
        /// Bytes the run would need.
        needs: u64,
        /// Bytes left.
        limit: u64,
    },
    /// A parameter out of its range.
    #[error("parameter {name} must be {what}, got {}", shown(*.value))]
    BadParameter {
        /// The parameter's name as the command line spells it.
        name: &'static str,
        /// The range it must lie in.
        what: &'static str,
        /// The value given.
        value: f64,
    },
}

pub(crate) fn check_params(p: &Params) -> Result<(), EvolveError> {
    let w = &p.weights;
    for (name, value) in [
        ("region", w.region),
        ("balloon", w.balloon),
        ("edge", w.edge),
        ("stretch", w.stretch),
        ("bend", w.bend),
    ] {
        // The app's sliders reach 2; far larger weights only overflow the speeds.
        if !(value.is_finite() && (0.0..=MAX_WEIGHT).contains(&value)) {
            return Err(EvolveError::BadParameter {
                name,
                what: "a number in [0, 100]",
                value,
            });
        }
    }
    if !(p.converged_share.is_finite() && (0.0..=1.0).contains(&p.converged_share)) {
        return Err(EvolveError::BadParameter {
            name: "converged_share",
            what: "in [0, 1]",
            value: p.converged_share,
        });
    }
    if !(8..=1 << 16).contains(&p.coarsest_side) {
        return Err(EvolveError::BadParameter {
            name: "coarsest_side",
            what: "in [8, 65536]",
            value: p.coarsest_side as f64,
        });
    }
    if !(p.step.is_finite() && p.step > 0.0 && p.step <= 2.0) {
        return Err(EvolveError::BadParameter {
            name: "step",
            what: "in (0, 2]",
            value: p.step,
        });
    }
    if !(p.min_area.is_finite() && p.min_area >= 0.0) {
        return Err(EvolveError::BadParameter {
            name: "min_area",
            what: "a finite number ≥ 0",
            value: p.min_area,
        });
    }
    Ok(())
}

/// Corners of a polygon accepted (a user clicks a few dozen).
pub const MAX_CORNERS: usize = 1 << 20;

/// A number as a message shows it: plain when short, in e-notation when huge or tiny.
fn shown(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Largest force weight accepted.
const MAX_WEIGHT: f64 = 100.0;

/// Bytes a run holds per pixel of its image at its peak (the image, the pyramid, the
/// local statistics and decision levels, and with automatic seeds their distance
/// transform and maxima): a wrap measures 22 on 4096² and 8000², automatic seeds 38 on
/// 4096² (docs/decisions.md, 2026-12-02); the larger, rounded up.
pub const BYTES_PER_PIXEL: u64 = 48;

/// The memory this process may still use: the smaller of what the system has available
/// and the address-space limit (`ulimit -v`), if either is known.
fn memory_limit() -> Option<u64> {
    let available = std::fs::read_to_string("/proc/meminfo").ok().and_then(|m| {
        m.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    #[cfg(unix)]
    let address_space = {
        let mut r = libc::rlimit {
            rlim_cur: 0,
            rlim_max: 0,
        };
        // SAFETY: getrlimit only writes the struct it is given.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
        // rlim_t is u64 here but not on every unix.
        #[allow(clippy::unnecessary_cast)]
        let limit = r.rlim_cur as u64;
        (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(limit)
    };
    #[cfg(not(unix))]
    let address_space = None;
    match (available, address_space) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// A run on a `width` × `height` image fits in the memory left (an image too large
/// aborted the process part-way instead of saying so).
pub(crate) fn check_memory(width: usize, height: usize) -> Result<(), EvolveError> {
    let needs = width as u64 * height as u64 * BYTES_PER_PIXEL;
    match memory_limit() {
        Some(limit) if needs > limit => Err(EvolveError::TooLarge {
            width,
            height,
            needs,
            limit,
        }),
        _ => Ok(()),
    }
}

/// The parameters that depend on the image: a local radius of at least a pixel and at
/// most the image's diagonal (its box filters allocate by the radius).
pub(crate) fn check_params_for(p: &Params, width: usize, height: usize) -> Result<(), EvolveError> {
    let diagonal = (width as f64).hypot(height as f64);
    if let Some(r) = p.local_radius {
        if !(r >= 1.0 && r <= diagonal) {
            return Err(EvolveError::BadParameter {
                name: "local_radius",
                what: "in [1, the image's diagonal]",
                value: r,
            });
        }
    }
    Ok(())
}

/// Shapes with finite coordinates no farther from the image than its diagonal, disks no
/// larger than the diagonal, and polygons of at most [`MAX_CORNERS`] corners (a ring has
/// a vertex every pixel or so: a huge shape would be a huge ring, clipped after).
pub(crate) fn check_shapes(init: &[Shape], width: usize, height: usize) -> Result<(), EvolveError> {
    let diagonal = (width as f64).hypot(height as f64);
    let near = |v: f64, side: usize| v >= -diagonal && v <= side as f64 + diagonal;
    let near_image = |q: &Point| near(q.x, width) && near(q.y, height);
    for s in init {
        let finite = match s {
            Shape::Disk { center, radius } => {
                if !(*radius > 0.0 && *radius <= diagonal) {
                    return Err(EvolveError::BadShape(format!(
                        "disk radius {radius} is not in (0, {diagonal:.0}], the image's diagonal"
                    )));
                }
                center.x.is_finite() && center.y.is_finite()
            }
            Shape::Rect { min, max } => [min.x, min.y, max.x, max.y].iter().all(|v| v.is_finite()),
            Shape::Polygon(pts) => pts.iter().all(|p| p.x.is_finite() && p.y.is_finite()),
        };
        if !finite {
            return Err(EvolveError::BadShape(format!(
                "{s:?} has a coordinate that is not finite"
            )));
        }
    }
    for s in init {
        let (corners, near) = match s {
            Shape::Disk { center, .. } => (1, near_image(center)),
            Shape::Rect { min, max } => (2, near_image(min) && near_image(max)),
            Shape::Polygon(pts) => (pts.len(), pts.iter().all(near_image)),
        };
        if corners > MAX_CORNERS {
            return Err(EvolveError::BadShape(format!(
                "a polygon of {corners} corners (at most {MAX_CORNERS})"
            )));
        }
        if !near {
            return Err(EvolveError::BadShape(format!(
                "a shape reaches farther than the image's diagonal ({diagonal:.0} px) from the {width}×{height} image"
            )));
        }
    }
    Ok(())
}
