//! Raster exports: the binary mask, the label image (16-bit PNG or TIFF), the overlay
//! of the contours on the image — all by one even-odd scanline fill of the rings.

use super::{object_number, Outputs, PALETTE};
use crate::evolution::regions;
use crate::geometry::{fill_even_odd, Point};

impl Outputs<'_> {
    /// Inside (255) where a pixel's centre lies in the region, by scanline over all rings
    /// (even-odd, which equals the region for non-crossing rings).
    pub fn mask(&self) -> Vec<u8> {
        let rings: Vec<Vec<Point>> = self
            .set
            .contour_ids()
            .map(|id| self.set.ring_points(id))
            .collect();
        let mut mask = vec![0u8; self.width * self.height];
        fill_even_odd(&rings, self.width, self.height, |i| mask[i] = 255);
        mask
    }

    /// One label per region (outer ring less its holes): its [`object_number`], 1, 2, …
    /// in the order of [`regions`]; 0 outside.
    pub fn labels(&self) -> Vec<u32> {
        let mut labels = vec![0u32; self.width * self.height];
        for (k, r) in regions(self.set).iter().enumerate() {
            let rings: Vec<Vec<Point>> = std::iter::once(r.id)
                .chain(r.holes.iter().copied())
                .map(|id| self.set.ring_points(id))
                .collect();
            let label = object_number(k);
            fill_even_odd(&rings, self.width, self.height, |i| labels[i] = label);
        }
        labels
    }

    /// The label image as a 16-bit PNG, or a 16-bit TIFF when `tiff` is true, as Fiji
    /// and QuPath read label images. `None` when there are more regions than 16 bits
    /// can label.
    pub fn labels_image(&self, tiff: bool) -> Option<Vec<u8>> {
        super::ctc::label_image(&self.labels(), self.width, self.height, tiff)
    }

    /// The image in gray with each region tinted in its own colour and every ring (holes
    /// too) drawn on top, as PNG bytes.
    pub fn overlay_png(&self, image: &dyn crate::image::Gray) -> Vec<u8> {
        let (w, h) = (self.width, self.height);
        let labels = self.labels();
        let colour = |k: u32| PALETTE[(k as usize - 1) % PALETTE.len()];
        let mut rgb = vec![0u8; w * h * 3];
        for i in 0..w * h {
            let g = image.value(i).clamp(0.0, 1.0) * 255.0;
            let px = if labels[i] == 0 {
                [g; 3]
            } else {
                let c = colour(labels[i]);
                std::array::from_fn(|k| 0.7 * g + 0.3 * c[k] as f32)
            };
            for k in 0..3 {
                rgb[3 * i + k] = px[k] as u8;
            }
        }
        for (k, r) in regions(self.set).iter().enumerate() {
            let c = colour(object_number(k));
            for id in std::iter::once(r.id).chain(r.holes.iter().copied()) {
                let pts = self.set.ring_points(id);
                for i in 0..pts.len() {
                    draw_segment(&mut rgb, w, h, pts[i], pts[(i + 1) % pts.len()], c);
                }
            }
        }
        let mut out = Vec::new();
        let enc = image::codecs::png::PngEncoder::new(&mut out);
        image::ImageEncoder::write_image(
            enc,
            &rgb,
            w as u32,
            h as u32,
            image::ExtendedColorType::Rgb8,
        )
        .expect("PNG encoding into memory");
        out
    }

    /// Mask as TIFF (`tiff`) or PNG bytes.
    pub fn mask_image(&self, tiff: bool) -> Vec<u8> {
        if !tiff {
            return self.mask_png();
        }
        let img = image::GrayImage::from_raw(self.width as u32, self.height as u32, self.mask())
            .expect("one value per pixel");
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Tiff)
            .expect("TIFF encoding into memory");
        out.into_inner()
    }

    /// Mask as PNG bytes.
    pub fn mask_png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let enc = image::codecs::png::PngEncoder::new(&mut out);
        image::ImageEncoder::write_image(
            enc,
            &self.mask(),
            self.width as u32,
            self.height as u32,
            image::ExtendedColorType::L8,
        )
        .expect("PNG encoding into memory");
        out
    }
}

/// A one-pixel line from `a` to `b` (pixel coordinates), sampled every half pixel.
pub(super) fn draw_segment(rgb: &mut [u8], w: usize, h: usize, a: Point, b: Point, c: [u8; 3]) {
    let n = (a.dist(b) * 2.0).ceil().max(1.0) as usize;
    for i in 0..=n {
        let p = a.lerp(b, i as f64 / n as f64);
        let (x, y) = (p.x.floor(), p.y.floor());
        if x >= 0.0 && y >= 0.0 && (x as usize) < w && (y as usize) < h {
            let k = 3 * (y as usize * w + x as usize);
            rgb[k..k + 3].copy_from_slice(&c);
        }
    }
}
