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

use super::field::{Field, Level};
use super::local::Decision;
use crate::geometry::Point;

/// Which objects to segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Polarity {
    /// Objects darker than the background.
    Dark,
    /// Objects brighter than the background.
    Bright,
}

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

/// Object and background intensities.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntensityModel {
    /// Mean intensity of objects.
    pub object: f64,
    /// Mean intensity of the background.
    pub background: f64,
}

impl IntensityModel {
    /// The decision level, halfway between the means.
    pub fn threshold(&self) -> f64 {
        0.5 * (self.object + self.background)
    }

    /// Normalised position of `i` between the means: +1 at the object mean, −1 at the
    /// background mean.
    #[inline]
    pub fn score(&self, i: f64) -> f64 {
        self.score_at(i, self.threshold())
    }

    /// [`IntensityModel::score`] against the decision level `level` instead of the
    /// midpoint (a local level, see [`super::local`]), in units of half the contrast.
    #[inline]
    pub fn score_at(&self, i: f64, level: f64) -> f64 {
        let half = 0.5 * (self.object - self.background);
        if half == 0.0 {
            0.0
        } else {
            (i - level) / half
        }
    }

    /// Learns the model: Otsu's split of the image gives the dark and bright class
    /// means; `object_hint` / `background_hint` (medians under the initialisation)
    /// replace them where they lie on the expected side. A model with less contrast than
    /// [`MIN_CONTRAST`] (a flat image, or hints that contradict the split) keeps the
    /// background the user showed and puts the object [`MIN_CONTRAST`] beyond it, so that
    /// a wrap over nothing collapses instead of taking the image as object.
    pub fn learn(
        image: &Field,
        polarity: Polarity,
        object_hint: Option<f64>,
        background_hint: Option<f64>,
    ) -> Self {
        let (dark, bright) = otsu_means(image);
        let (mut object, mut background) = match polarity {
            Polarity::Dark => (dark, bright),
            Polarity::Bright => (bright, dark),
        };
        let sign = match polarity {
            Polarity::Dark => -1.0,
            Polarity::Bright => 1.0,
        };
        let t = 0.5 * (dark + bright);
        let on_object_side = |v: f64| sign * (v - t) > 0.0;
        if let Some(o) = object_hint.filter(|&o| on_object_side(o)) {
            object = o;
        }
        match background_hint {
            Some(b) if !on_object_side(b) => background = b,
            Some(b) if object_hint.is_none() => {
                // The band the user wrapped reads as object: there is no object brighter
                // (darker) than it that Otsu could see.
                background = b;
            }
            _ => {}
        }
        if sign * (object - background) < MIN_CONTRAST {
            if object_hint.is_some() && background_hint.is_none() {
                background = object - sign * MIN_CONTRAST;
            } else {
                object = background + sign * MIN_CONTRAST;
            }
        }
        IntensityModel { object, background }
    }
}

/// Smallest object–background difference a model may have (intensities in [0, 1]): two
/// 8-bit grey levels and a half.
pub const MIN_CONTRAST: f64 = 0.01;

/// Means of the two classes of Otsu's threshold over a 256-bin histogram.
pub fn otsu_means(image: &Field) -> (f64, f64) {
    // Four partial histograms: neighbouring pixels often share a bin, and one histogram
    // would make every increment wait for the previous one.
    let mut part = [[0u32; 256]; 4];
    let bin = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as usize; // round half up, no libm
    let mut quads = image.data.chunks_exact(4);
    for q in &mut quads {
        for k in 0..4 {
            part[k][bin(q[k])] += 1;
        }
    }
    for &v in quads.remainder() {
        part[0][bin(v)] += 1;
    }
    let hist: [u64; 256] = std::array::from_fn(|i| part.iter().map(|h| h[i] as u64).sum());
    let total: u64 = hist.iter().sum();
    let sum_all: f64 = hist
        .iter()
        .enumerate()
        .map(|(i, &h)| i as f64 * h as f64)
        .sum();
    let (mut w0, mut s0, mut best, mut best_t) = (0u64, 0f64, -1f64, 127usize);
    for (t, &h) in hist.iter().enumerate() {
        w0 += h;
        s0 += t as f64 * h as f64;
        let w1 = total - w0;
        if w0 == 0 || w1 == 0 {
            continue;
        }
        let (m0, m1) = (s0 / w0 as f64, (sum_all - s0) / w1 as f64);
        let between = w0 as f64 * w1 as f64 * (m0 - m1) * (m0 - m1);
        if between > best {
            best = between;
            best_t = t;
        }
    }
    let (mut w0, mut s0) = (0u64, 0f64);
    for (t, &h) in hist.iter().enumerate().take(best_t + 1) {
        w0 += h;
        s0 += t as f64 * h as f64;
    }
    let w1 = total - w0;
    let m0 = if w0 > 0 { s0 / w0 as f64 } else { 0.0 };
    let m1 = if w1 > 0 {
        (sum_all - s0) / w1 as f64
    } else {
        255.0
    };
    (m0 / 255.0, m1 / 255.0)
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
