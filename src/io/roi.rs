//! ImageJ ROI sets: a zip of `.roi` files that Fiji's ROI Manager opens (File ▸ Open, or
//! drag and drop), one ROI per region, named after the region.
//!
//! The format is ImageJ's `RoiEncoder` (version 228, big-endian): a 64-byte header, then
//! the coordinates. A region without holes is a polygon ROI with sub-pixel coordinates
//! (option `SUB_PIXEL_RESOLUTION`: integer coordinates relative to the bounding box,
//! then the same as absolute floats). A region with holes is a composite ("shape") ROI:
//! the header of a rectangle with `shapeRoiSize` floats of a path (move-to 0, line-to 1,
//! close 4, absolute coordinates), outer ring and holes as sub-paths; the holes run the
//! other way round, so Java's non-zero fill leaves them empty. ImageJ's pixel
//! coordinates are ours: the origin at the top-left corner of the top-left pixel.

use crate::contours::{ContourId, ContourSet};
use crate::evolution::regions;
use crate::geometry::Point;
use crate::io::ExportError;
use std::io::Write;

const VERSION: u16 = 228;
const TYPE_POLYGON: u8 = 0;
const TYPE_RECT: u8 = 1;
const SUB_PIXEL_RESOLUTION: u16 = 128;

/// The largest coordinate ImageJ's 16-bit ROI header and integer coordinates hold.
pub const MAX_ROI_COORDINATE: f64 = i16::MAX as f64;

/// The ROI set of every region of `set` as zip bytes; refused when a region reaches past
/// [`MAX_ROI_COORDINATE`] (the header would clamp and the coordinates wrap).
pub fn roi_zip(set: &ContourSet) -> Result<Vec<u8>, ExportError> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (k, r) in regions(set).iter().enumerate() {
        let rings: Vec<Vec<Point>> = std::iter::once(r.id)
            .chain(r.holes.iter().copied())
            .map(|id: ContourId| set.ring_points(id))
            .collect();
        let far = rings
            .iter()
            .flatten()
            .map(|p| p.x.max(p.y))
            .fold(0.0, f64::max);
        if far >= MAX_ROI_COORDINATE {
            return Err(ExportError::RoiTooFar(far.ceil() as u64));
        }
        let bytes = if rings.len() == 1 {
            polygon_roi(&rings[0])
        } else {
            shape_roi(&rings)
        };
        let number = crate::io::export::object_number(k);
        zip.start_file(format!("object-{number:05}.roi"), options)
            .expect("zip entry in memory");
        zip.write_all(&bytes).expect("zip write in memory");
    }
    Ok(zip.finish().expect("zip in memory").into_inner())
}

/// The 64-byte header with the bounding box of `rings`.
fn header(kind: u8, rings: &[Vec<Point>], n: u16, options: u16, shape_size: u32) -> Vec<u8> {
    let pts = rings.iter().flatten();
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in pts {
        (x0, y0, x1, y1) = (x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y));
    }
    let mut h = vec![0u8; 64];
    h[0..4].copy_from_slice(b"Iout");
    h[4..6].copy_from_slice(&VERSION.to_be_bytes());
    h[6] = kind;
    let short = |v: f64| (v.floor() as i64).clamp(i16::MIN as i64, i16::MAX as i64) as i16;
    h[8..10].copy_from_slice(&short(y0).to_be_bytes()); // top
    h[10..12].copy_from_slice(&short(x0).to_be_bytes()); // left
    h[12..14].copy_from_slice(&short(y1.ceil()).to_be_bytes()); // bottom
    h[14..16].copy_from_slice(&short(x1.ceil()).to_be_bytes()); // right
    h[16..18].copy_from_slice(&n.to_be_bytes());
    h[36..40].copy_from_slice(&shape_size.to_be_bytes());
    h[50..52].copy_from_slice(&options.to_be_bytes());
    h
}

/// A polygon ROI with sub-pixel coordinates. ImageJ counts polygon vertices in 16 bits;
/// a longer ring is written as a shape ROI instead.
fn polygon_roi(ring: &[Point]) -> Vec<u8> {
    let Ok(n) = u16::try_from(ring.len()) else {
        return shape_roi(&[ring.to_vec()]);
    };
    let rings = [ring.to_vec()];
    let mut b = header(TYPE_POLYGON, &rings, n, SUB_PIXEL_RESOLUTION, 0);
    let (left, top) = (
        i16::from_be_bytes([b[10], b[11]]),
        i16::from_be_bytes([b[8], b[9]]),
    );
    for p in ring {
        b.extend_from_slice(&((p.x.floor() as i64 - left as i64) as i16).to_be_bytes());
    }
    for p in ring {
        b.extend_from_slice(&((p.y.floor() as i64 - top as i64) as i16).to_be_bytes());
    }
    for p in ring {
        b.extend_from_slice(&(p.x as f32).to_be_bytes());
    }
    for p in ring {
        b.extend_from_slice(&(p.y as f32).to_be_bytes());
    }
    b
}

/// A composite ROI: each ring a closed sub-path.
fn shape_roi(rings: &[Vec<Point>]) -> Vec<u8> {
    let mut path: Vec<f32> = Vec::new();
    for ring in rings {
        for (i, p) in ring.iter().enumerate() {
            path.extend([if i == 0 { 0.0 } else { 1.0 }, p.x as f32, p.y as f32]);
        }
        path.push(4.0);
    }
    let mut b = header(TYPE_RECT, rings, 0, 0, path.len() as u32);
    for v in path {
        b.extend_from_slice(&v.to_be_bytes());
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;

    fn set_with(ring: &[Point]) -> ContourSet {
        let domain = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(40_000.0, 100.0),
        };
        let mut set = ContourSet::new(domain, 4.0);
        set.add_ring(ring).unwrap();
        set
    }

    /// Issue 24.17: a region past x = 32,767 is refused, not written with a clamped
    /// header and wrapped coordinates.
    #[test]
    fn regions_past_the_16_bit_range_are_refused() {
        let square = |x: f64| {
            [(0.0, 0.0), (3.0, 0.0), (3.0, 3.0), (0.0, 3.0)]
                .map(|(dx, dy)| Point::new(x + dx, 10.0 + dy))
        };
        assert!(roi_zip(&set_with(&square(100.0))).is_ok());
        assert_eq!(
            roi_zip(&set_with(&square(33_000.0))),
            Err(ExportError::RoiTooFar(33_003))
        );
    }
}
