//! What a TIFF says beyond its first image: how many pages (images) it holds — a stack
//! or a time series from a microscope — and the size of a pixel. Pages after the first
//! are decoded here (the image crate reads the first only).
//!
//! Pixel size: ImageJ writes XResolution as pixels per unit and the unit in the
//! ImageDescription (`unit=micron`); other writers use ResolutionUnit (inch or cm). A
//! resolution without a unit means nothing physical and is ignored.
//!
//! Pages are counted by following the chain of image directories alone: loading each
//! page's strip table as well made a file of 20,000 directories sharing one table of
//! 60,000 strips cost 20 s before it was refused. Floating-point pages (32 or 64 bit)
//! are scaled from their own finite range to [0, 1], whatever page they are; a NaN sample
//! (no data) takes the mean of the finite ones, so it reads as neither object nor
//! background, and ±∞ the range's ends: no non-finite value ever reaches the engine.
//! Colour pages stored as planes one after the other (PlanarConfiguration 2, as
//! tifffile writes a (3, H, W) array) are read whole, not as their first plane.

use super::load::LoadError;
use crate::evolution::Field;
use std::io::Cursor;
use tiff::decoder::ifd::Value;
use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::{IfdPointer, Tag};
use tiff::ColorType;

/// Pages read at most when counting (a malformed chain of images must not loop).
const MAX_PAGES: usize = 100_000;

/// The physical size of a pixel.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PixelSize {
    /// Side of a pixel, in `unit`.
    pub size: f64,
    /// The unit, as written (µm, mm, cm, …).
    pub unit: String,
}

/// Pages and pixel size of a TIFF file's bytes (`None`: not a TIFF).
pub fn tiff_info(bytes: &[u8]) -> Option<(usize, Option<PixelSize>)> {
    let mut dec = Decoder::new(Cursor::new(bytes)).ok()?;
    let pixel = pixel_size(&mut dec);
    Some((count_pages(&mut dec), pixel))
}

/// Directories in the chain from the first, read without their images' strip tables;
/// the walk stops at a directory seen before (a cycle), an unreadable one or
/// [`MAX_PAGES`].
fn count_pages<R: std::io::Read + std::io::Seek>(dec: &mut Decoder<R>) -> usize {
    let mut seen = std::collections::HashSet::new();
    let mut at: Option<IfdPointer> = dec.ifd_pointer();
    while let Some(ptr) = at {
        if seen.len() >= MAX_PAGES || !seen.insert(ptr.0) {
            break;
        }
        at = match dec.read_directory(ptr) {
            Ok(dir) => dir.next(),
            Err(_) => None,
        };
    }
    seen.len().max(1)
}

/// Floating-point samples scaled from their finite range to [0, 1] (left as they are when
/// already inside it); NaN becomes the finite samples' mean, ±∞ the high or low end.
pub(crate) fn float_samples(v: impl Iterator<Item = f64> + Clone) -> Vec<f32> {
    let (lo, hi, sum, n) = v.clone().filter(|x| x.is_finite()).fold(
        (f64::INFINITY, f64::NEG_INFINITY, 0.0, 0usize),
        |(lo, hi, sum, n), x| (lo.min(x), hi.max(x), sum + x, n + 1),
    );
    let (lo, hi, mean) = if n == 0 {
        (0.0, 1.0, 0.5)
    } else {
        (lo, hi, sum / n as f64)
    };
    let (offset, scale) = if lo >= 0.0 && hi <= 1.0 {
        (0.0, 1.0)
    } else if hi > lo {
        (lo, 1.0 / (hi - lo))
    } else {
        // One value everywhere: a flat image.
        (lo, 0.0)
    };
    v.map(|x| {
        let x = if x.is_nan() { mean } else { x.clamp(lo, hi) };
        ((x - offset) * scale).clamp(0.0, 1.0) as f32
    })
    .collect()
}

fn pixel_size(dec: &mut Decoder<Cursor<&[u8]>>) -> Option<PixelSize> {
    let per_unit = match dec.find_tag(Tag::XResolution).ok()?? {
        Value::Rational(n, d) if d != 0 => n as f64 / d as f64,
        Value::Double(v) => v,
        Value::Float(v) => v as f64,
        _ => return None,
    };
    if !(per_unit.is_finite() && per_unit > 0.0) {
        return None;
    }
    let described = dec
        .get_tag_ascii_string(Tag::ImageDescription)
        .ok()
        .and_then(|d| {
            d.lines()
                .find_map(|l| l.strip_prefix("unit=").map(|u| u.trim().to_string()))
        });
    let unit = match described.as_deref() {
        Some("micron" | "um" | "\\u00B5m" | "µm") => "µm".to_string(),
        Some(u) if !u.is_empty() && u != "pixel" => u.to_string(),
        _ => match dec.find_tag_unsigned::<u16>(Tag::ResolutionUnit).ok()? {
            Some(2) => "inch".into(),
            Some(3) => "cm".into(),
            _ => return None,
        },
    };
    Some(PixelSize {
        size: 1.0 / per_unit,
        unit,
    })
}

/// The (channels, slices, frames) a TIFF's first description states, 1 for each one not
/// stated: ImageJ's (`channels=`, `slices=`, `frames=`), OME-XML's (`SizeC`, `SizeZ`,
/// `SizeT`) or tifffile's (`{"shape": [...], "axes": "TCYX"}`; without axes, the
/// dimensions before the plane's, as frames and channels). None for a TIFF whose
/// description states none, or no TIFF.
pub fn stack_dimensions(path: &std::path::Path) -> Option<(usize, usize, usize)> {
    let file = std::fs::File::open(path).ok()?;
    let mut dec = Decoder::new(std::io::BufReader::new(file)).ok()?;
    let d = dec.get_tag_ascii_string(Tag::ImageDescription).ok()?;
    if d.starts_with("ImageJ=") {
        let get = |key: &str| {
            d.lines()
                .find_map(|l| l.strip_prefix(key)?.trim().parse().ok())
                .unwrap_or(1)
        };
        return Some((get("channels="), get("slices="), get("frames=")));
    }
    if d.contains("<OME") {
        let get = |key: &str| {
            let at = d.find(&format!("{key}=\""))? + key.len() + 2;
            d[at..].split('"').next()?.parse().ok()
        };
        let size = |key| get(key).unwrap_or(1);
        return Some((size("SizeC"), size("SizeZ"), size("SizeT")));
    }
    let shaped: serde_json::Value = serde_json::from_str(&d).ok()?;
    let shape: Vec<usize> = shaped
        .get("shape")?
        .as_array()?
        .iter()
        .map(|v| v.as_u64().map(|n| n as usize))
        .collect::<Option<_>>()?;
    match shaped.get("axes").and_then(|a| a.as_str()) {
        Some(axes) if axes.len() == shape.len() => {
            let size = |c: char| {
                axes.chars()
                    .zip(&shape)
                    .filter(|(a, _)| *a == c)
                    .map(|(_, &n)| n)
                    .product()
            };
            Some((size('C'), size('Z'), size('T')))
        }
        // Without axes: planes are the last two (three for colour samples) dimensions.
        _ => {
            let planes = if shape.last().is_some_and(|&n| n == 3 || n == 4) {
                3
            } else {
                2
            };
            let lead: Vec<usize> = shape.iter().rev().skip(planes).rev().copied().collect();
            let (t, c) = match lead.as_slice() {
                [] => (1, 1),
                [t] => (*t, 1),
                [t, rest @ ..] => (*t, rest.iter().product()),
            };
            Some((c, 1, t))
        }
    }
}

/// Pages of the TIFF at `path` (1 for any other image).
pub fn pages_of(path: &std::path::Path) -> usize {
    if !crate::io::export::is_tiff(path) {
        return 1;
    }
    let Ok(file) = std::fs::File::open(path) else {
        return 1;
    };
    Decoder::new(std::io::BufReader::new(file)).map_or(1, |mut dec| count_pages(&mut dec))
}

/// Samples per pixel of the first page of the TIFF at `path` (3 for RGB), if it reads.
pub fn first_page_samples(path: &std::path::Path) -> Option<usize> {
    let file = std::fs::File::open(path).ok()?;
    let mut dec = Decoder::new(std::io::BufReader::new(file)).ok()?;
    samples_per_pixel(dec.colortype().ok()?)
}

/// Samples per pixel of the pixel kinds read here: grey, RGB and RGBA.
fn samples_per_pixel(colour: ColorType) -> Option<usize> {
    match colour {
        ColorType::Gray(_) => Some(1),
        ColorType::RGB(_) => Some(3),
        ColorType::RGBA(_) => Some(4),
        _ => None,
    }
}

/// Decodes page `page` (0-based) of a TIFF as luminance in [0, 1].
pub fn decode_page(bytes: &[u8], name: &str, page: usize) -> Result<Field, LoadError> {
    let err = |reason: String| LoadError::Decode {
        path: name.to_string(),
        reason,
    };
    let mut dec = Decoder::new(Cursor::new(bytes))
        .map_err(|e| err(e.to_string()))?
        .with_limits(Limits::default());
    dec.seek_to_image(page)
        .map_err(|e| err(format!("page {} of the file: {e}", page + 1)))?;
    decode_current(&mut dec, name, page)
}

/// Decodes the page `dec` stands at (page `page`, 0-based, for messages) as luminance in
/// [0, 1]; a movie reads its pages one after the other through this.
pub(crate) fn decode_current<R: std::io::Read + std::io::Seek>(
    dec: &mut Decoder<R>,
    name: &str,
    page: usize,
) -> Result<Field, LoadError> {
    let err = |reason: String| LoadError::Decode {
        path: name.to_string(),
        reason,
    };
    let (w, h) = dec.dimensions().map_err(|e| err(e.to_string()))?;
    super::load::check_size(name, w, h)?;
    let colour = dec.colortype().map_err(|e| err(e.to_string()))?;
    let channels = samples_per_pixel(colour).ok_or_else(|| {
        err(format!(
            "page {}: {colour:?} pixels are not supported",
            page + 1
        ))
    })?;
    // Planes stored one after the other (PlanarConfiguration 2, as tifffile writes a
    // (3, H, W) array): `read_image` would return the first plane only.
    let planar = dec
        .find_tag_unsigned::<u16>(Tag::PlanarConfiguration)
        .ok()
        .flatten()
        == Some(2);
    let mut decoded = DecodingResult::U8(Vec::new());
    dec.read_image_to_buffer(&mut decoded)
        .map_err(|e| err(e.to_string()))?;
    let values: Vec<f32> = match decoded {
        DecodingResult::U8(v) => v.iter().map(|&x| x as f32 / 255.0).collect(),
        DecodingResult::U16(v) => v.iter().map(|&x| x as f32 / 65535.0).collect(),
        // Signed 8 and 16 bit: their type's range, as the unsigned ones.
        DecodingResult::I8(v) => v.iter().map(|&x| (x as f32 + 128.0) / 255.0).collect(),
        DecodingResult::I16(v) => v.iter().map(|&x| (x as f32 + 32768.0) / 65535.0).collect(),
        // Wider integers: their own range, as floats (no camera fills 32 bits).
        DecodingResult::U32(v) => float_samples(v.iter().map(|&x| x as f64)),
        DecodingResult::U64(v) => float_samples(v.iter().map(|&x| x as f64)),
        DecodingResult::I32(v) => float_samples(v.iter().map(|&x| x as f64)),
        DecodingResult::I64(v) => float_samples(v.iter().map(|&x| x as f64)),
        DecodingResult::F16(v) => float_samples(v.iter().map(|&x| x.to_f64())),
        DecodingResult::F32(v) => float_samples(v.iter().map(|&x| x as f64)),
        DecodingResult::F64(v) => float_samples(v.iter().copied()),
    };
    let n = w as usize * h as usize;
    if values.len() < n * channels {
        return Err(err(format!(
            "page {} holds fewer samples than its size",
            page + 1
        )));
    }
    // Rec. 709 luma, as the first page gets from the image crate.
    let sample = |i: usize, c: usize| match planar {
        true => values[c * n + i],
        false => values[i * channels + c],
    };
    let data = (0..n)
        .map(|i| match channels {
            1 => values[i],
            _ => 0.2126 * sample(i, 0) + 0.7152 * sample(i, 1) + 0.0722 * sample(i, 2),
        })
        .collect();
    Ok(Field::new(w as usize, h as usize, data))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tiff::encoder::{colortype, TiffEncoder};

    /// A 4 × 2 page of `T`'s samples `v` as TIFF bytes.
    fn page<T: colortype::ColorType>(v: &[T::Inner]) -> Vec<u8>
    where
        [T::Inner]: tiff::encoder::TiffValue,
    {
        let mut bytes = Cursor::new(Vec::new());
        TiffEncoder::new(&mut bytes)
            .unwrap()
            .write_image::<T>(4, 2, v)
            .unwrap();
        bytes.into_inner()
    }

    #[test]
    fn signed_and_wide_integer_pages_decode_into_the_unit_range() {
        let read = |bytes: Vec<u8>| decode_page(&bytes, "page.tif", 0).unwrap().data;
        // Signed 16 bit: the type's range, its lowest value black, its highest white.
        let v = read(page::<colortype::GrayI16>(&[
            i16::MIN,
            -1,
            0,
            100,
            4095,
            i16::MAX,
            0,
            0,
        ]));
        assert_eq!(v[0], 0.0);
        assert_eq!(v[5], 1.0);
        assert!(v[2] > v[1] && v[3] > v[2] && v[4] > v[3]);
        let v = read(page::<colortype::GrayI8>(&[-128, 0, 127, 0, 0, 0, 0, 0]));
        assert_eq!((v[0], v[2]), (0.0, 1.0));
        // 32 bit: the page's own range.
        let v = read(page::<colortype::Gray32>(&[
            100, 200, 300, 100, 100, 100, 100, 100,
        ]));
        assert_eq!((v[0], v[1], v[2]), (0.0, 0.5, 1.0));
        let v = read(page::<colortype::GrayI32>(&[-5, 5, 0, 0, 0, 0, 0, 0]));
        assert_eq!((v[0], v[1], v[2]), (0.0, 1.0, 0.5));
        let v = read(page::<colortype::Gray64>(&[0, 1 << 40, 0, 0, 0, 0, 0, 0]));
        assert_eq!((v[0], v[1]), (0.0, 1.0));
    }
}
