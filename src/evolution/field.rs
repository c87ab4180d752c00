//! An image as a field of f32 gray values with bilinear sampling and gradients
//! (DESIGN layer 4), and the Gaussian pyramid of seed 004 (kernel 1/16 [1 4 6 4 1],
//! factor 2) used for coarse-to-fine evolution.
//!
//! Sample positions are in the field's own pixel coordinates with the image convention:
//! pixel (i, j) covers [i, i+1) × [j, j+1), so its value sits at (i + 0.5, j + 0.5).
//! Outside the image the border value continues (clamping), so contours near the border
//! see no artificial edge.

use crate::geometry::Point;

/// A gray image, values in [0, 1].
#[derive(Clone, Debug)]
pub struct Field {
    pub width: usize,
    pub height: usize,
    pub data: Vec<f32>,
}

impl Field {
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Self {
        assert_eq!(data.len(), width * height, "field size");
        assert!(width > 0 && height > 0, "empty field");
        Field {
            width,
            height,
            data,
        }
    }

    #[inline]
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.data[y * self.width + x]
    }

    /// Bilinear value at `p` (pixel-centre convention, clamped at the borders).
    #[inline]
    pub fn sample(&self, p: Point) -> f64 {
        let fx = (p.x - 0.5).clamp(0.0, (self.width - 1) as f64);
        let fy = (p.y - 0.5).clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (fx as usize, fy as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
        let a = self.at(x0, y0) as f64 * (1.0 - tx) + self.at(x1, y0) as f64 * tx;
        let b = self.at(x0, y1) as f64 * (1.0 - tx) + self.at(x1, y1) as f64 * tx;
        a * (1.0 - ty) + b * ty
    }

    /// One pyramid step: blur with 1/16 [1 4 6 4 1] in x and y, keep every other pixel.
    pub fn reduce(&self) -> Field {
        let blurred = self.blur5();
        let (w, h) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let mut data = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                // The coarse pixel covers fine pixels 2x, 2x+1: average the pair's blur.
                let (x0, y0) = (2 * x, 2 * y);
                let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
                let v = blurred.at(x0, y0)
                    + blurred.at(x1, y0)
                    + blurred.at(x0, y1)
                    + blurred.at(x1, y1);
                data.push(0.25 * v);
            }
        }
        Field::new(w, h, data)
    }

    /// Separable 1/16 [1 4 6 4 1] blur with clamped borders.
    pub fn blur5(&self) -> Field {
        self.blur(&[1.0 / 16.0, 4.0 / 16.0, 6.0 / 16.0, 4.0 / 16.0, 1.0 / 16.0])
    }

    /// Separable blur with an odd symmetric kernel, clamped borders.
    pub fn blur(&self, k: &[f32]) -> Field {
        let r = (k.len() / 2) as isize;
        let (w, h) = (self.width, self.height);
        let mut tmp = vec![0f32; w * h];
        for y in 0..h {
            let row = &self.data[y * w..(y + 1) * w];
            for x in 0..w {
                let mut s = 0.0;
                for (i, &kv) in k.iter().enumerate() {
                    let xi = (x as isize + i as isize - r).clamp(0, w as isize - 1) as usize;
                    s += kv * row[xi];
                }
                tmp[y * w + x] = s;
            }
        }
        let mut out = vec![0f32; w * h];
        for y in 0..h {
            for (i, &kv) in k.iter().enumerate() {
                let yi = (y as isize + i as isize - r).clamp(0, h as isize - 1) as usize;
                let src = &tmp[yi * w..(yi + 1) * w];
                let dst = &mut out[y * w..(y + 1) * w];
                for x in 0..w {
                    dst[x] += kv * src[x];
                }
            }
        }
        Field::new(w, h, out)
    }
}

/// One pyramid level with its gradient fields, computed once so that a force evaluation
/// costs a handful of bilinear samples.
#[derive(Clone, Debug)]
pub struct Level {
    pub image: Field,
    /// Central differences per pixel, x and y.
    pub gx: Field,
    pub gy: Field,
    /// Gradient magnitude.
    pub gmag: Field,
}

impl Level {
    pub fn new(image: Field) -> Self {
        let (w, h) = (image.width, image.height);
        let (mut gx, mut gy, mut gm) = (vec![0f32; w * h], vec![0f32; w * h], vec![0f32; w * h]);
        for y in 0..h {
            for x in 0..w {
                let dx = 0.5 * (image.at((x + 1).min(w - 1), y) - image.at(x.saturating_sub(1), y));
                let dy = 0.5 * (image.at(x, (y + 1).min(h - 1)) - image.at(x, y.saturating_sub(1)));
                let i = y * w + x;
                gx[i] = dx;
                gy[i] = dy;
                gm[i] = (dx * dx + dy * dy).sqrt();
            }
        }
        Level {
            gx: Field::new(w, h, gx),
            gy: Field::new(w, h, gy),
            gmag: Field::new(w, h, gm),
            image,
        }
    }

    /// Gradient at `p` (bilinear in the precomputed differences).
    #[inline]
    pub fn gradient(&self, p: Point) -> Point {
        Point::new(self.gx.sample(p), self.gy.sample(p))
    }
}

/// The Gaussian pyramid: level 0 is the (lightly smoothed) image, level l has 2^-l of its
/// resolution.
#[derive(Clone, Debug)]
pub struct Pyramid {
    pub levels: Vec<Level>,
}

impl Pyramid {
    /// Builds levels down to the coarsest whose short side is still at least `min_side`
    /// pixels (at most `max_levels` levels in all).
    pub fn new(image: &Field, min_side: usize, max_levels: usize) -> Self {
        // Level 0 is smoothed lightly (1/4 [1 2 1]): enough against pixel noise, little
        // enough that halos next to an edge do not pull it inwards.
        let mut fields = vec![image.blur(&[0.25, 0.5, 0.25])];
        while fields.len() < max_levels {
            let last = fields.last().unwrap();
            if last.width.min(last.height) / 2 < min_side {
                break;
            }
            let next = last.reduce();
            fields.push(next);
        }
        Pyramid {
            levels: fields.into_iter().map(Level::new).collect(),
        }
    }

    /// Scale factor from level `l` pixels to full-resolution pixels.
    pub fn scale(l: usize) -> f64 {
        (1u64 << l) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sampling_and_reduction() {
        let f = Field::new(4, 2, vec![0.0, 1.0, 2.0, 3.0, 0.0, 1.0, 2.0, 3.0]);
        assert_eq!(f.sample(Point::new(0.5, 0.5)), 0.0);
        assert_eq!(f.sample(Point::new(1.0, 1.0)), 0.5);
        assert_eq!(f.sample(Point::new(-5.0, 1.0)), 0.0);
        let r = f.reduce();
        assert_eq!((r.width, r.height), (2, 1));
        // A constant image stays constant through the pyramid.
        let c = Field::new(9, 7, vec![0.25; 63]);
        let p = Pyramid::new(&c, 2, 5);
        assert!(p.levels.len() >= 2);
        assert!(p
            .levels
            .iter()
            .all(|l| l.image.data.iter().all(|&v| (v - 0.25).abs() < 1e-6)));
        assert!(p
            .levels
            .iter()
            .all(|l| l.gmag.data.iter().all(|&v| v.abs() < 1e-6)));
        let ramp = Level::new(Field::new(4, 1, vec![0.0, 1.0, 2.0, 3.0]));
        assert_eq!(ramp.gradient(Point::new(2.0, 0.5)).x, 1.0);
    }
}
