//! The kind of image, as the user knows it ([`Modality`]), and the image the forces see
//! for it: phase contrast has its halo clipped ([`super::halo`]), every other kind is
//! taken as it is.

use super::field::Field;
use super::halo::{clip_halo, lift_narrow_halo};
use super::intensity::Polarity;

/// The kind of image, as the user knows it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Modality {
    /// No assumption beyond the object's polarity.
    #[default]
    Generic,
    /// Fluorescence: bright objects on dark background, of very different brightness.
    Fluorescence,
    /// Phase contrast: dark cells with a bright halo on grey background.
    PhaseContrast,
    /// Bright field: objects darker or brighter than an even background.
    Brightfield,
}

impl Modality {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Modality::Generic => "generic",
            Modality::Fluorescence => "fluorescence",
            Modality::PhaseContrast => "phase-contrast",
            Modality::Brightfield => "brightfield",
        }
    }
}

/// The image the forces see for `modality`: in phase contrast the halo clipped to the
/// background level `background` (the band a wrap shows), or else the image's median
/// (background dominates a phase-contrast field); any other image as it is.
pub fn for_modality(
    image: &Field,
    polarity: Polarity,
    modality: Modality,
    background: Option<f64>,
) -> std::borrow::Cow<'_, Field> {
    if modality != Modality::PhaseContrast {
        return std::borrow::Cow::Borrowed(image);
    }
    let b = background.unwrap_or_else(|| {
        let mut v = image.data.clone();
        let m = v.len() / 2;
        *v.select_nth_unstable_by(m, f32::total_cmp).1 as f64
    });
    let clipped = clip_halo(image, polarity, b);
    std::borrow::Cow::Owned(lift_narrow_halo(&clipped, polarity, b))
}

/// Dark cells whose band just outside them ([`HALO_BAND`] px) is brighter than the far
/// background by at least this share of the background's contrast over the cells wear
/// the bright halo of phase contrast. Measured on frame 0 of tracked movies: synthetic
/// phase-contrast rods 0.54, a real dense colony 0.57 (0.94 later in it); trpL, whose
/// halo lies further out, 0.01; dark cells with no halo read at or below 0.
pub const HALO_SHARE: f64 = 0.25;

/// How far out of the cells (pixels) their halo is looked for.
pub const HALO_BAND: f32 = 3.0;

/// Background lies at least this far (pixels) from every cell.
pub const HALO_CLEAR: f32 = 8.0;

/// An image whose median lies below this share of the way from its 1st to its 99th
/// percentile is mostly dark background: its cells are the bright objects. Measured on
/// the first image or frame of each case: bright objects (fluorescence nuclei and
/// bacteria, real and synthetic, the synthetic bright blobs) 0.03–0.25; dark objects
/// (phase-contrast colonies and rods, the synthetic dark shapes) 0.30–0.78.
pub const DARK_BACKGROUND_MEDIAN: f64 = 0.27;

/// Whether `image` looks like bright objects on a dark background
/// ([`DARK_BACKGROUND_MEDIAN`]): the polarity the app opens an image or movie with, so a
/// fluorescence movie is not tracked as dark objects (its background, then).
pub fn looks_bright_on_dark(image: &Field) -> bool {
    let mut v: Vec<f32> = (image.data.iter())
        .copied()
        .filter(|x| x.is_finite())
        .collect();
    if v.len() < 3 {
        return false;
    }
    let n = v.len() - 1;
    let mut at = |q: f64| {
        *v.select_nth_unstable_by((q * n as f64) as usize, f32::total_cmp)
            .1
    };
    let (lo, mid, hi) = (at(0.01) as f64, at(0.5) as f64, at(0.99) as f64);
    hi > lo && (mid - lo) / (hi - lo) < DARK_BACKGROUND_MEDIAN
}

/// Whether the dark cells of `labels` (non-zero, one per pixel of `image`) look wrapped
/// in a bright halo ([`HALO_SHARE`]): an image the user did not say was phase contrast
/// that likely is, where the generic modality reads the halo as a rim of cell and keeps
/// specks a phase-contrast run drops.
pub fn looks_haloed(image: &Field, labels: &[u32]) -> bool {
    let (w, h) = (image.width, image.height);
    if labels.len() != w * h {
        return false;
    }
    let outside: Vec<bool> = labels.iter().map(|&l| l == 0).collect();
    let far = super::distance::distance_transform(&outside, w, h);
    let (mut cell, mut band, mut ground) = (Vec::new(), Vec::new(), Vec::new());
    for (k, &v) in image.data.iter().enumerate() {
        let d = far.data[k];
        if !outside[k] {
            cell.push(v as f64);
        } else if d <= HALO_BAND {
            band.push(v as f64);
        } else if d > HALO_CLEAR {
            ground.push(v as f64);
        }
    }
    // Too few of any to tell.
    if [&cell, &band, &ground].iter().any(|v| v.len() < 50) {
        return false;
    }
    let median = |v: &mut Vec<f64>| super::hints::median(v).unwrap_or(0.0);
    let (c, r, b) = (median(&mut cell), median(&mut band), median(&mut ground));
    b > c && r - b >= HALO_SHARE * (b - c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 64² frame: a dark disk (0.2) on grey (0.5), with a band of `rim` 1–3 px out.
    fn disk_with_rim(rim: f32) -> (Field, Vec<u32>) {
        let (w, h) = (64, 64);
        let mut data = vec![0.5f32; w * h];
        let mut labels = vec![0u32; w * h];
        for y in 0..h {
            for x in 0..w {
                let d = (x as f32 + 0.5 - 32.0).hypot(y as f32 + 0.5 - 32.0);
                let k = y * w + x;
                if d < 12.0 {
                    data[k] = 0.2;
                    labels[k] = 1;
                } else if d < 15.0 {
                    data[k] = rim;
                }
            }
        }
        (Field::new(w, h, data), labels)
    }

    #[test]
    fn bright_cells_on_dark_ground_are_told_from_dark_cells_on_grey() {
        // A dark disk on grey ground, and the same inverted: a bright disk on darker
        // ground (the median is the ground's either way, at the bottom or the top).
        let (dark, _) = disk_with_rim(0.5);
        let bright = Field::new(64, 64, dark.data.iter().map(|v| 1.0 - v).collect());
        assert!(!looks_bright_on_dark(&dark));
        assert!(looks_bright_on_dark(&bright));
        let mut spots = vec![0.1f32; 64 * 64];
        for k in (0..64 * 64).step_by(7) {
            spots[k] = 0.9;
        }
        assert!(looks_bright_on_dark(&Field::new(64, 64, spots)));
        assert!(
            !looks_bright_on_dark(&Field::new(8, 8, vec![0.3; 64])),
            "flat"
        );
    }

    #[test]
    fn a_bright_rim_around_dark_cells_reads_as_a_halo_and_none_does_not() {
        for (rim, haloed) in [(0.9, true), (0.5, false), (0.3, false)] {
            let (image, labels) = disk_with_rim(rim);
            assert_eq!(looks_haloed(&image, &labels), haloed, "rim {rim}");
        }
    }
}
