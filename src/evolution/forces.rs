//! The motion function of seed 003 §3 ("a motion function is used to determine a motion
//! vector for each vertex"), built from the forces of seed 004 §2: a region term, a
//! balloon with an intensity window and edge stopping, an edge attraction term, and
//! stretching/bending smoothing.
//!
//! Choices (the papers leave them open):
//! - The region term compares the local intensity with object and background means
//!   learned from the initialisation (the seeds' interior, or the band just inside a wrap
//!   rectangle) and the image's Otsu split, on the side the `--object` polarity names. It
//!   is zero halfway between the means, which for a blurred step is the edge itself, so
//!   contours settle with sub-pixel accuracy.
//! - The balloon pushes out inside the object's intensity window and in otherwise,
//!   faded by an edge-stopping factor so that it never moves the equilibrium off the edge.
//! - Smoothing is weak: a user expects contours to follow narrow slots and thin bridges.

use crate::geometry::Point;
use crate::image::field::Level;
use crate::image::local::Decision;
use crate::image::IntensityModel;

/// Weights of the forces (defaults serve every public case; see `Params`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ForceWeights {
    /// Weight of the region term: how strongly intensity pulls the contour towards the decision level.
    pub region: f64,
    /// Weight of the balloon force: a constant push outward inside objects.
    pub balloon: f64,
    /// Weight of the edge term: attraction to strong gradients.
    pub edge: f64,
    /// Weight of stretching: pull towards the neighbours' midpoint.
    pub stretch: f64,
    /// Weight of bending: smoothing of that pull.
    pub bend: f64,
}

impl Default for ForceWeights {
    fn default() -> Self {
        ForceWeights {
            region: 1.0,
            balloon: 0.3,
            edge: 0.3,
            stretch: 0.2,
            bend: 0.05,
        }
    }
}

/// What the image says at one vertex.
#[derive(Clone, Copy, Debug)]
pub struct NormalSpeed {
    /// Speed along the outward normal, in units of the level's step (about [-1.5, 1.5]).
    pub speed: f64,
    /// The region score alone (tells whether the vertex has settled).
    pub region: f64,
}

/// Normal speed at `x` (level coordinates) with outward unit normal `n`; `decision` is
/// the level's local decision level and contrast, if any.
#[inline]
pub fn normal_speed(
    level: &Level,
    decision: Option<&Decision>,
    model: &IntensityModel,
    w: &ForceWeights,
    x: Point,
    n: Point,
) -> NormalSpeed {
    let t = level.sample(x);
    // The score in units of half the contrast, and the contrast: local or global.
    let (s, contrast) = match decision {
        Some(d) => {
            let half = d.half.sample(x).max(1e-6);
            ((t.value - d.level.sample(x)) * d.sign / half, 2.0 * half)
        }
        None => (
            model.score(t.value),
            (model.object - model.background).abs().max(1e-6),
        ),
    };
    let region = s.clamp(-1.0, 1.0);
    // Balloon with the object's intensity window (scores 0 to 2.5): out inside it, in
    // outside, ramping over a quarter of the score at the window's edges so that it
    // never chatters across an edge; faded where the gradient says an edge is near.
    let window = ((s / 0.25).min((2.5 - s) / 0.25)).clamp(-1.0, 1.0);
    let gmag = t.gradient.norm() / contrast;
    let stop = 1.0 / (1.0 + 16.0 * gmag * gmag);
    let balloon = window * stop;
    // Edge attraction: climb the gradient magnitude along the normal (half a pixel each
    // way: halos and texture make wider differences chatter).
    let ahead = level.gmag(x + n * 0.5);
    let behind = level.gmag(x - n * 0.5);
    let edge = (2.0 * (ahead - behind) / contrast).clamp(-1.0, 1.0);
    NormalSpeed {
        speed: w.region * region + w.balloon * balloon + w.edge * edge,
        region,
    }
}
