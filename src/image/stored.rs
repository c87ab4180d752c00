//! [`Stored`]: an image's values kept beside a run once its model is prepared, in the
//! fewest bits that hold them exactly.
//!
//! After [`super::ImageModel::prepare`] the engines read only the model; the image itself
//! is wanted again only by outputs that draw or measure it (the overlay, the summary's
//! mean intensity). As 32-bit floats it is a fifth of a run's peak memory (67 MB of
//! 4096²). Images decoded from 8- and 16-bit files hold values k / 65535 (an 8-bit
//! TIFF's k / 255 is the same float) for integer k, so they are kept as those integers:
//! a byte or two per pixel instead of four, and [`Stored::value`] gives back the very float that was decoded (the
//! computation the loader did, not an approximation). Anything else (float TIFFs, a
//! caller's own field) stays as floats.

use super::field::Field;

/// The samples an output reads: the image as decoded ([`Field`]) or as kept ([`Stored`]).
pub trait Gray {
    /// Width and height in pixels.
    fn size(&self) -> (usize, usize);
    /// The value of pixel `i` (row by row).
    fn value(&self, i: usize) -> f32;
}

impl Gray for Field {
    fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }
    fn value(&self, i: usize) -> f32 {
        self.data[i]
    }
}

/// An output reads a shared image as the image itself (the app holds `Arc<Field>`).
impl<T: Gray + ?Sized> Gray for std::sync::Arc<T> {
    fn size(&self) -> (usize, usize) {
        (**self).size()
    }
    fn value(&self, i: usize) -> f32 {
        (**self).value(i)
    }
}

/// An image's values in the fewest bits that reproduce them exactly (module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Stored {
    width: usize,
    height: usize,
    values: Values,
}

#[derive(Clone, Debug, PartialEq)]
enum Values {
    /// `(k · mul) as f32 / scale` for the bytes k packed four to a float's place: 8-bit
    /// values of either loader.
    Bytes {
        packed: Vec<f32>,
        mul: u16,
        scale: f32,
    },
    /// `k as f32 / scale` for the 16-bit k packed two to a place.
    Words { packed: Vec<f32>, scale: f32 },
    /// Anything else.
    Floats(Vec<f32>),
}

/// The divisor of the loaders' 16-bit values (`crate::io::load`); an 8-bit TIFF's b / 255
/// is the same float as 257·b / 65535 (one rational, correctly rounded).
const SCALE: f32 = 65535.0;

impl Stored {
    /// Keeps `field`'s values in the fewest bits that give them back exactly. The
    /// integers are packed into the field's own buffer, which then shrinks: a copy
    /// beside it would be the run's peak.
    pub fn new(field: Field) -> Self {
        let (width, height, data) = (field.width, field.height, field.data);
        let scale = SCALE;
        let values = match fits(&data, scale) {
            None => Values::Floats(data),
            Some((true, _)) => Values::Bytes {
                packed: pack::<u8, 4>(data, |x| (integer(x, scale) / 257) as u8),
                mul: 257,
                scale,
            },
            Some((_, true)) => Values::Bytes {
                packed: pack::<u8, 4>(data, |x| integer(x, scale) as u8),
                mul: 1,
                scale,
            },
            Some(_) => Values::Words {
                packed: pack::<u16, 2>(data, |x| integer(x, scale)),
                scale,
            },
        };
        Stored {
            width,
            height,
            values,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The image as a field again.
    pub fn to_field(&self) -> Field {
        let n = self.width * self.height;
        Field::new(
            self.width,
            self.height,
            (0..n).map(|i| self.value(i)).collect(),
        )
    }
}

impl Gray for Stored {
    fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }
    #[inline]
    fn value(&self, i: usize) -> f32 {
        match &self.values {
            Values::Bytes { packed, mul, scale } => {
                let k: &[u8] = bytemuck::cast_slice(packed);
                (k[i] as u16 * mul) as f32 / scale
            }
            Values::Words { packed, scale } => {
                let k: &[u16] = bytemuck::cast_slice(packed);
                k[i] as f32 / scale
            }
            Values::Floats(data) => data[i],
        }
    }
}

/// The integer k of a value that [`fits`] `scale`.
fn integer(x: f32, scale: f32) -> u16 {
    (x * scale).round() as u16
}

/// Whether every value is `k as f32 / scale` bit for bit for an integer k in 0..=65535;
/// if so, whether every k is a multiple of 257 and whether every k is at most 255.
fn fits(data: &[f32], scale: f32) -> Option<(bool, bool)> {
    let (mut all_257, mut all_byte) = (true, true);
    for &x in data {
        let k = (x * scale).round();
        if !((0.0..=65535.0).contains(&k) && (k as u16 as f32 / scale).to_bits() == x.to_bits()) {
            return None;
        }
        all_257 &= (k as u16).is_multiple_of(257);
        all_byte &= k <= 255.0;
    }
    Some((all_257, all_byte))
}

/// `data`'s values as `T`s by `to`, `PER` to a float's place of the same buffer, which
/// is then shrunk. Place j takes the values of floats j·PER… , all read before it is
/// written, and j ≤ j·PER: no value is overwritten before it is read.
fn pack<T: bytemuck::Pod, const PER: usize>(mut data: Vec<f32>, to: impl Fn(f32) -> T) -> Vec<f32> {
    let n = data.len();
    let places = n.div_ceil(PER);
    for j in 0..places {
        let mut word = [T::zeroed(); PER];
        for (q, w) in word.iter_mut().enumerate() {
            if let Some(&x) = data.get(j * PER + q) {
                *w = to(x);
            }
        }
        let place: &mut [T] = bytemuck::cast_slice_mut(std::slice::from_mut(&mut data[j]));
        place.copy_from_slice(&word);
    }
    data.truncate(places);
    data.shrink_to_fit();
    data
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(data: Vec<f32>) -> Stored {
        let s = Stored::new(Field::new(data.len(), 1, data.clone()));
        for (i, &x) in data.iter().enumerate() {
            assert_eq!(s.value(i).to_bits(), x.to_bits(), "pixel {i}");
        }
        assert_eq!(s.to_field().data, data);
        s
    }

    #[test]
    fn loaded_values_come_back_bit_for_bit_in_fewer_bits() {
        let png8: Vec<f32> = (0..=255u16).map(|b| (b * 257) as f32 / 65535.0).collect();
        assert!(matches!(kept(png8).values, Values::Bytes { mul: 257, .. }));
        // Lengths that do not fill the last place.
        let odd: Vec<f32> = (0..7u16).map(|b| (b * 257) as f32 / 65535.0).collect();
        kept(odd);
        let odd: Vec<f32> = (0..5u16).map(|k| (k * 1000) as f32 / 65535.0).collect();
        assert!(matches!(kept(odd).values, Values::Words { .. }));
        // b / 255 and 257·b / 65535 are one rational, so one float.
        let tiff8: Vec<f32> = (0..=255u8).map(|b| b as f32 / 255.0).collect();
        assert!(matches!(kept(tiff8).values, Values::Bytes { mul: 257, .. }));
        let dim16: Vec<f32> = (0..=255u16).map(|k| k as f32 / 65535.0).collect();
        assert!(matches!(kept(dim16).values, Values::Bytes { mul: 1, .. }));
        let words: Vec<f32> = (0..=65535u16)
            .step_by(7)
            .map(|k| k as f32 / 65535.0)
            .collect();
        assert!(matches!(kept(words).values, Values::Words { .. }));
    }

    #[test]
    fn other_values_stay_floats() {
        for data in [
            vec![0.5, 0.1234567],
            vec![-0.25, 0.0],
            vec![1.5, 0.0],
            vec![f32::NAN],
        ] {
            let s = Stored::new(Field::new(data.len(), 1, data.clone()));
            assert!(matches!(s.values, Values::Floats(_)));
            assert_eq!(s.value(0).to_bits(), data[0].to_bits());
        }
    }
}
