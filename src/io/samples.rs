//! Pixels handed over in memory (a NumPy array from the Python bindings) as the same
//! [`Field`] a file with those samples gives: 8 and 16 bit scaled by their full range as
//! PNG and TIFF decoding scale them, floating point through the TIFF reader's rule (its
//! finite range to [0, 1], NaN the finite mean, ±∞ the range's ends), and the size
//! limits of a file. So one image segments the same from its file and from its array.

use super::load::{check_size, LoadError};
use crate::evolution::Field;

/// Samples row by row, in one of the types an image file holds.
#[derive(Clone, Copy, Debug)]
pub enum Samples<'a> {
    /// 8 bit: 0 black, 255 white.
    U8(&'a [u8]),
    /// 16 bit: 0 black, 65,535 white.
    U16(&'a [u16]),
    /// Floating point (any range; NaN means no data).
    F32(&'a [f32]),
}

impl Samples<'_> {
    /// How many samples.
    pub fn len(&self) -> usize {
        match self {
            Samples::U8(v) => v.len(),
            Samples::U16(v) => v.len(),
            Samples::F32(v) => v.len(),
        }
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The luminance field of a `width` × `height` image given as `samples` row by row;
/// `name` names it in messages. Refused as a file would be: no pixels, or more than
/// [`super::load::MAX_PIXELS`].
pub fn field_from_samples(
    name: &str,
    width: usize,
    height: usize,
    samples: Samples,
) -> Result<Field, LoadError> {
    let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    check_size(name, side(width), side(height))?;
    assert_eq!(samples.len(), width * height, "samples for the size");
    let data = match samples {
        Samples::U8(v) => v.iter().map(|&x| x as f32 / 255.0).collect(),
        Samples::U16(v) => v.iter().map(|&x| x as f32 / 65535.0).collect(),
        Samples::F32(v) => super::tiff_info::float_samples(v.iter().map(|&x| x as f64)),
    };
    let mut field = Field::new(width, height, data);
    // As a file's image is read ([`super::movie::widen_narrow`]).
    super::movie::widen_narrow(&mut field);
    Ok(field)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 8-bit samples read as a PNG's do (through 16 bits: v·257 / 65535).
    #[test]
    fn eight_bit_as_png_decoding() {
        let v: Vec<u8> = (0..=255).collect();
        let f = field_from_samples("a", 16, 16, Samples::U8(&v)).unwrap();
        for (&x, &y) in v.iter().zip(&f.data) {
            assert_eq!(y, (x as u16 * 257) as f32 / 65535.0);
        }
    }

    #[test]
    fn nan_reads_as_the_finite_mean_and_empty_is_refused() {
        let f = field_from_samples("a", 3, 1, Samples::F32(&[0.0, f32::NAN, 2.0])).unwrap();
        assert_eq!(f.data, vec![0.0, 0.5, 1.0]);
        let e = field_from_samples("arr", 0, 4, Samples::U8(&[])).unwrap_err();
        assert_eq!(e.to_string(), "arr has no pixels (0×4)");
    }
}
