//! Phase contrast (`Modality::PhaseContrast`): cells are dark, wrapped in a bright halo,
//! on grey background. Values brighter than the background are clipped to it before the
//! pyramid is built, so the halo reads as background for every force: the wrap stops at
//! the halo's outside, keeps shrinking through it, and settles where the dark cell
//! meets the bright rim (the steepest edge left after clipping). For bright objects in
//! phase contrast the mirror rule clips the dark side.

use super::field::Field;
use super::filters::{box_extreme, box_extreme_in};
use super::intensity::{IntensityModel, Polarity};
use super::scale::half_width;

/// The image with the phase-contrast halo clipped to the background level `b` (values
/// beyond `b` on the side away from the objects' polarity).
pub fn clip_halo(image: &Field, polarity: Polarity, b: f64) -> Field {
    let b = b as f32;
    let data = match polarity {
        Polarity::Dark => image.data.iter().map(|&v| v.min(b)).collect(),
        Polarity::Bright => image.data.iter().map(|&v| v.max(b)).collect(),
    };
    Field::new(image.width, image.height, data)
}

/// How far a narrow halo is lifted: its height above the opening, times this.
pub const HALO_LIFT: f32 = 2.5;

/// Half-side of the opening's square, in object radii.
pub const HALO_REACH: f64 = 0.2;

/// The clipped phase-contrast image with the halo *between* touching cells lifted to
/// the background level `b`. Where cells touch, the halo is a ridge too narrow to reach
/// the background grey (the optics blur it into the cells on both sides), and it would
/// read as cell: a wrap kept touching bacteria as one. The white top-hat I − open(I) of the lightly blurred image (open = the
/// max filter of the min filter over a square of half-side h = [`HALO_REACH`] · r, r the
/// objects' mean half-width, [`half_width`]) is large only on bright structures narrower
/// than 2h + 1 between dark ones — the channels and the pockets between cell tips — and
/// zero on the halo around a lone cell (its bright side is wide). Adding [`HALO_LIFT`]
/// times it, clipped at `b`, moves those ridges to the background side, and the
/// adaptive engine opens holes there (`explicit::nucleate`): the wrap parts the cells. A
/// wider square or a stronger lift also eats into the cells' flanks along the channel
/// (`docs/decisions.md`).
pub fn lift_narrow_halo(image: &Field, polarity: Polarity, b: f64) -> Field {
    let model = IntensityModel::learn(image, polarity, None, None);
    // The scale unclamped: the channels widen with the pixel size like the cells.
    let h = (HALO_REACH * half_width(image, &model)).round().max(1.0) as usize;
    let bright = polarity == Polarity::Bright;
    let smooth = image.blur(&[0.25, 0.5, 0.25]);
    // Dark cells: open the bright side (min, then max); bright cells the mirror.
    let opened = box_extreme_in(box_extreme(&smooth, h, bright), h, !bright);
    let b = b as f32;
    let data = image
        .data
        .iter()
        .zip(&smooth.data)
        .zip(&opened.data)
        .map(|((&v, &m), &o)| {
            let lifted = v + HALO_LIFT * (m - o);
            if bright {
                lifted.max(b)
            } else {
                lifted.min(b)
            }
        })
        .collect();
    Field::new(image.width, image.height, data)
}
