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

use crate::image::model::Probe;

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

/// Normal speed from what the image says at a vertex ([`Probe`]: the region score,
/// the edge stop and the edge attraction) under the weights `w`.
#[inline]
pub fn normal_speed(at: &Probe, w: &ForceWeights) -> NormalSpeed {
    let s = at.score;
    let region = s.clamp(-1.0, 1.0);
    // Balloon with the object's intensity window (scores 0 to 2.5): out inside it, in
    // outside, ramping over a quarter of the score at the window's edges so that it
    // never chatters across an edge; faded where the gradient says an edge is near.
    let window = ((s / 0.25).min((2.5 - s) / 0.25)).clamp(-1.0, 1.0);
    let balloon = window * at.stop;
    NormalSpeed {
        speed: w.region * region + w.balloon * balloon + w.edge * at.edge,
        region,
    }
}
