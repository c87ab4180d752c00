//! The object scale: the mean half-width 2A/P (area over perimeter: the radius of a
//! disk, half the width of a long rod) of what the global level finds, clamped to
//! [`RADIUS_RANGE`]. It is the radius r of the local statistics ([`super::local`]) and
//! of the automatic seeds ([`super::seeds`]).

use super::field::Field;
use super::intensity::IntensityModel;

/// Smallest and largest local radius, full-resolution pixels.
pub const RADIUS_RANGE: (f64, f64) = (3.0, 24.0);

/// The object scale of an image whose [`half_width`] is `hw` (measured once, as the
/// pyramid's depth reads it too): `hw` clamped to [`RADIUS_RANGE`].
pub fn object_scale(hw: f64) -> f64 {
    hw.clamp(RADIUS_RANGE.0, RADIUS_RANGE.1)
}

/// The mean half-width 2A/P of what lies on the object side of the global level (A
/// counts pixels, P pixel sides between object and background), at least one pixel.
pub fn half_width(image: &Field, model: &IntensityModel) -> f64 {
    let (w, h) = (image.width, image.height);
    let t = model.threshold() as f32;
    let bright = model.object >= model.background;
    let inside = |x: usize, y: usize| (image.at(x, y) > t) == bright;
    let (mut area, mut perimeter) = (0u64, 0u64);
    for y in 0..h {
        for x in 0..w {
            let a = inside(x, y);
            area += a as u64;
            if x + 1 < w && a != inside(x + 1, y) {
                perimeter += 1;
            }
            if y + 1 < h && a != inside(x, y + 1) {
                perimeter += 1;
            }
        }
    }
    // Pixel sides overestimate a smooth boundary's length by about 4/π.
    (2.0 * area as f64 / (perimeter.max(1) as f64 * std::f64::consts::FRAC_PI_4)).max(1.0)
}
