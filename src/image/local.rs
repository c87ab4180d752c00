//! Local decision levels for the region force.
//!
//! One global two-class model (Otsu plus the means under the initialisation) misses dim
//! objects next to bright ones (the global level lies above them) and follows uneven
//! light. The region term therefore compares the intensity with a decision level T(x)
//! that adapts to the neighbourhood: a share q (a half, or less for microscopy's
//! bodies: [`share`]) of the way from the local background b(x) to the
//! most object-like value e(x) near x, bounded on both sides,
//!
//!   T(x) = b(x) + s · max(floor, q · s · (e(x) − b(x))),
//!   then  s·(T(x) − b(x)) ≤ k · s·(T_g − b(x)),
//!
//! with s = +1 for bright objects and −1 for dark ones and T_g the global model's level
//! (halfway between its means). The pieces:
//! - e(x) is the maximum (bright objects; the minimum for dark ones) over the box of
//!   half-side ⌈r/2⌉ around x, of the image blurred once more by [1 2 1] / 4 (the
//!   extreme of raw noise would lift the level). At the edge of an object, e is the object's own level,
//!   so T is the midpoint of *its* contrast: a dim nucleus gets the level halfway to its
//!   own brightness, and a clean object of the global contrast gets exactly T_g (no
//!   change on our synthetic cases, where the global midpoint is the edge of a blurred
//!   step). Inside a large object e is the object itself, so nothing inside reads as
//!   background (a local *mean* would put half of a large object's interior below its
//!   own level).
//! - b(x) is the emptiest (2ρ+1)² box mean within 3r of x, never less object-like than
//!   the global background: uneven light raises it, a halo beside an object does not
//!   lower it. The box mean keeps the noise from biasing the minimum. Its half-side ρ is
//!   r, or ⌈r/2⌉ in phase contrast and bright field ([`background_box`]), where crowded
//!   cells leave only thin lines of background between them.
//! - floor: [`FLOOR_SIGMAS`] deviations of the pixel noise (flat background never reads
//!   as object), and a share of the global contrast that depends on the modality (see
//!   [`floor`]).
//! - The cap, k global half contrasts from the local background (k = 1: T_g itself when
//!   b is the global background), keeps very bright objects whole where their
//!   neighbourhood is brighter still; k depends on the modality (see [`reach`]).
//!
//! The region score is (I − T) / |T − b| (clamped to ±1), so a dim object's edge pulls
//! as hard as a bright one's and a wrap over background far from any object shrinks at
//! full speed instead of retreating for a thousand frames.
//!
//! Known limit: a dim object touching a brighter one loses the strip within ⌈r/2⌉ of
//! its bright partner, whose brightness sets e there (tests/real_microscopy.rs measures
//! it). The boxes are separable filters ([`super::filters`]), computed once per pyramid
//! level; a sample is two bilinear reads.
//!
//! We chose this over localized region means (Lankton & Tannenbaum, "Localizing
//! region-based active contours", 2008), whose means depend on the moving contour and
//! would need new box sums every frame, and over region-scalable fitting (Li et al.,
//! "Minimization of region-scalable fitting energy for image segmentation", 2008),
//! which needs two convolutions per iteration: both cost O(pixels) per frame, ours once
//! per level. A local *mean* also moves the edge of a blurred step off its midpoint. The
//! figures are in `docs/decisions.md`.

use super::field::Field;
use super::filters::{box_extreme_in, box_mean};
use super::intensity::{IntensityModel, MIN_CONTRAST};
use super::modality::Modality;
use super::noise::noise_sigma;

/// How many noise standard deviations the local level keeps from the background. A
/// background pixel passes four with odds of 3 in 10⁵, and a stray vertex there is
/// pulled back by its neighbours; six lost the dim nuclei of noisy images, three costs
/// frames (`docs/decisions.md`).
pub const FLOOR_SIGMAS: f64 = 4.0;

/// The smallest distance of the local level from the background: [`FLOOR_SIGMAS`]
/// noise deviations, at least [`MIN_CONTRAST`], and at least a share of the global
/// contrast that depends on the kind of image: none in fluorescence, where objects
/// range from saturated to barely above the noise; a quarter in phase contrast and
/// bright field, whose textured background (mottle, debris) is far above the pixel noise
/// while the cells are high-contrast; a tenth when the kind is not said.
pub fn floor(fine: &Field, model: &IntensityModel, modality: Modality) -> f64 {
    let share = match modality {
        Modality::Fluorescence => 0.0,
        Modality::PhaseContrast | Modality::Brightfield => 0.25,
        Modality::Generic => 0.1,
    };
    let contrast = (model.object - model.background).abs();
    (FLOOR_SIGMAS * noise_sigma(fine))
        .max(MIN_CONTRAST)
        .max(share * contrast)
}

/// How far from the local background b the level may lie, in global half contrasts
/// (the cap of the module doc). In fluorescence three: a bright nucleus is then cut at
/// its own share of its contrast rather than at the global level, which took its
/// out-of-focus glow (bright nuclei came out at twice their annotated area). One, the
/// global level itself, for every other kind: a looser cap lets the textured insides of
/// phase-contrast cells and of the synthetic cases read as background
/// (`docs/decisions.md`).
pub fn reach(modality: Modality) -> f64 {
    match modality {
        Modality::Fluorescence => 3.0,
        _ => 1.0,
    }
}

/// The background box reaches this many object radii: from inside an object of up to
/// three times the mean half-width it still reaches background.
pub const BACKGROUND_REACH: usize = 3;

/// The half-side of the boxes whose means b(x) is the emptiest of, as a share of the
/// object radius r: a whole radius, except in phase contrast and bright field, where it
/// is half. There a colony's cells crowd with only their bright halo lines, 2–3 px wide,
/// between them, so no box of a whole radius within reach is background: the level fell
/// to the global one while a crowded cell's inside is brighter (the colony's glow), and
/// the evolution kept only the cells' cores, thin pieces that split. The cap at the
/// global background bounds what the smaller box's noise can lift b by. On 140-cell
/// colonies and the real phase-contrast colonies (docs/decisions.md, 2026-12-05).
/// Fluorescence keeps the whole radius: its touching nuclei have glow, not background,
/// between them.
pub fn background_box(modality: Modality) -> f64 {
    match modality {
        Modality::PhaseContrast | Modality::Brightfield => 0.5,
        _ => 1.0,
    }
}

/// The local decision level T(x) of one pyramid level, with the local half contrast
/// |T(x) − b(x)| that scales the region score (so a dim object's edge pulls as hard as a
/// bright one's, and flat background far from the level shrinks a wrap at full speed).
#[derive(Clone, Debug)]
pub struct Decision {
    /// Per pixel, the decision level of the region term.
    pub level: Field,
    /// Per pixel, half the local contrast (scales the region score).
    pub half: Field,
    /// +1 for bright objects, −1 for dark ones.
    pub sign: f64,
}

/// How the decision level sits between the local background and the local object.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LevelRule {
    /// Smallest distance from the local background ([`floor`]).
    pub floor: f64,
    /// Largest distance from it, in global half contrasts ([`reach`]).
    pub reach: f64,
    /// Where between background and object the level lies, as a share of the local
    /// contrast ([`share`]).
    pub share: f64,
    /// The background boxes' half-side as a share of the object radius
    /// ([`background_box`]).
    pub background_box: f64,
}

impl LevelRule {
    /// The rule for `modality` on the image `fine` with global model `model`.
    pub fn new(fine: &Field, model: &IntensityModel, modality: Modality) -> Self {
        LevelRule {
            floor: floor(fine, model, modality),
            reach: reach(modality),
            share: share(modality),
            background_box: background_box(modality),
        }
    }
}

/// Where the level lies between the local background and the object's own extreme:
/// halfway for the generic kind, the edge of a blurred step. Microscopy objects are
/// bodies whose projected thickness, and so their signal, falls to nothing at the rim
/// (a nucleus's brightness, a cell's phase shift): on a lens-shaped profile half the
/// peak lies at 0.87 of the radius, 0.4 at 0.92, so 0.4 of the contrast in fluorescence,
/// phase contrast and bright field (`docs/decisions.md`); the generic kind keeps the
/// midpoint.
pub fn share(modality: Modality) -> f64 {
    match modality {
        Modality::Generic => 0.5,
        _ => 0.4,
    }
}

/// The decision level T(x) of the module doc for one pyramid level's image, `r` in that
/// level's pixels, placed by `rule`.
pub fn decision_field(
    image: &Field,
    r: usize,
    model: &IntensityModel,
    rule: &LevelRule,
) -> Decision {
    let LevelRule {
        floor,
        reach,
        share,
        background_box,
    } = *rule;
    let bright = model.object >= model.background;
    let s = if bright { 1.0 } else { -1.0 };
    let mut t = box_extreme_in(image.blur(&[0.25, 0.5, 0.25]), r.div_ceil(2), bright);
    // The emptiest ρ-box within reach: a mean first, so that noise does not bias it.
    let rb = ((r as f64 * background_box).ceil() as usize).max(1);
    let mut half = box_extreme_in(box_mean(image, rb), BACKGROUND_REACH * r, !bright);
    let tg = model.threshold();
    for (v, h) in t.data.iter_mut().zip(half.data.iter_mut()) {
        // Background may be raised by uneven light (more object-like than the global
        // background), never pushed the other way: a halo beside an object is not
        // background light.
        let b = if bright {
            (*h as f64).max(model.background)
        } else {
            (*h as f64).min(model.background)
        };
        let level = b + s * (share * s * (*v as f64 - b)).max(floor);
        // Never further from the background than `reach` global half contrasts: the
        // inside of a large object stays object.
        let cap = b + reach * (tg - b);
        let level = if bright {
            level.min(cap)
        } else {
            level.max(cap)
        };
        *v = level as f32;
        *h = (level - b).abs().max(floor) as f32;
    }
    Decision {
        level: t,
        half,
        sign: s,
    }
}
