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
    // A row of inside flags at a time, compared with its right neighbours and the row
    // above: whole-row loops, no per-pixel lookups.
    let (mut row, mut above) = (vec![false; w], vec![false; w]);
    let (mut area, mut perimeter) = (0u64, 0u64);
    for y in 0..h {
        for (a, &v) in row.iter_mut().zip(&image.data[y * w..(y + 1) * w]) {
            *a = (v > t) == bright;
        }
        area += row.iter().filter(|&&a| a).count() as u64;
        perimeter += row.windows(2).filter(|p| p[0] != p[1]).count() as u64;
        if y > 0 {
            perimeter += row.iter().zip(&above).filter(|(a, b)| a != b).count() as u64;
        }
        std::mem::swap(&mut row, &mut above);
    }
    // Pixel sides overestimate a smooth boundary's length by about 4/π.
    (2.0 * area as f64 / (perimeter.max(1) as f64 * std::f64::consts::FRAC_PI_4)).max(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_width_counts_the_area_and_the_pixel_sides_of_the_object_side() {
        // Two bright blocks, one at the image's edge (its sides there are not counted),
        // one inside with a dark pixel in it.
        let (w, h) = (9, 7);
        let mut data = vec![0.0f32; w * h];
        for y in 0..3 {
            for x in 0..2 {
                data[y * w + x] = 1.0;
            }
        }
        for y in 2..6 {
            for x in 4..8 {
                data[y * w + x] = 1.0;
            }
        }
        data[3 * w + 5] = 0.0;
        let model = IntensityModel {
            object: 1.0,
            background: 0.0,
        };
        // Area 6 + 15 = 21; sides 2 + 3 of the edge block, 16 + 4 of the other.
        let expected = 2.0 * 21.0 / (25.0 * std::f64::consts::FRAC_PI_4);
        assert!((half_width(&Field::new(w, h, data.clone()), &model) - expected).abs() < 1e-12);
        // Dark objects: the same count on the other side of the level.
        let dark = IntensityModel {
            object: 0.0,
            background: 1.0,
        };
        let expected = 2.0 * (63.0 - 21.0) / (25.0 * std::f64::consts::FRAC_PI_4);
        assert!((half_width(&Field::new(w, h, data.clone()), &dark) - expected).abs() < 1e-12);
        // The inner block moved into the far corner: its right and bottom sides, on the
        // last column and row, are not counted either (area 21; sides 5 + 8 + 4).
        let mut corner = vec![0.0f32; w * h];
        for y in 0..h {
            for x in 0..w {
                let edge_block = y < 3 && x < 2;
                let far_block = y >= 3 && x >= 5 && (x, y) != (6, 4);
                corner[y * w + x] = if edge_block || far_block { 1.0 } else { 0.0 };
            }
        }
        let expected = 2.0 * 21.0 / (17.0 * std::f64::consts::FRAC_PI_4);
        assert!((half_width(&Field::new(w, h, corner), &model) - expected).abs() < 1e-12);
    }
}
