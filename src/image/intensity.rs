//! The two-class intensity model: which side of the image is object ([`Polarity`]), and
//! the object and background means, learnt from Otsu's split of the histogram and the
//! medians under the user's shapes.

use super::field::Field;

/// Which objects to segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Polarity {
    /// Objects darker than the background.
    Dark,
    /// Objects brighter than the background.
    Bright,
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

/// How far past Otsu's object mean (in Otsu's contrasts) the median inside the objects'
/// outlines must lie for it to replace that mean ([`IntensityModel::beside_outlined`]).
pub const OUTLINED_BEYOND: f64 = 0.5;

impl IntensityModel {
    /// The model with the object's intensity taken from `outlined`, the median inside
    /// contours known to outline objects (a tracked frame's cells carried into the next),
    /// when Otsu's object class is far from it: a few cells in a wide field are too small
    /// a share of the pixels, and Otsu splits the background's own unevenness instead
    /// (a 512² phase-contrast frame of four rods: object 0.38 and background 0.54, the
    /// rods at 0.15). Where Otsu found the cells, it is kept: its mean and the median
    /// under shrunk outlines differ a little, and every tracked frame would move.
    pub fn beside_outlined(self, outlined: f64) -> Self {
        let s = if self.object >= self.background {
            1.0
        } else {
            -1.0
        };
        let contrast = (self.object - self.background).abs();
        if s * (outlined - self.object) > OUTLINED_BEYOND * contrast {
            IntensityModel {
                object: outlined,
                ..self
            }
        } else {
            self
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outlined_cells_replace_a_split_of_the_background_only() {
        // Dark rods: Otsu split the background (0.38 against 0.54), the rods are at 0.15.
        let missed = IntensityModel {
            object: 0.38,
            background: 0.54,
        };
        assert_eq!(missed.beside_outlined(0.15).object, 0.15);
        assert_eq!(missed.beside_outlined(0.15).background, 0.54);
        // Close to Otsu's object mean, or on the background's side: Otsu's kept.
        assert_eq!(missed.beside_outlined(0.33).object, 0.38);
        assert_eq!(missed.beside_outlined(0.45).object, 0.38);
        // Bright objects alike.
        let bright = IntensityModel {
            object: 0.6,
            background: 0.5,
        };
        assert_eq!(bright.beside_outlined(0.9).object, 0.9);
        assert_eq!(bright.beside_outlined(0.62).object, 0.6);
    }
}
