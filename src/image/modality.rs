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
