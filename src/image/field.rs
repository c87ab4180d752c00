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
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Values row by row.
    pub data: Vec<f32>,
}

impl Field {
    /// A field from its values row by row.
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Self {
        assert_eq!(data.len(), width * height, "field size");
        assert!(width > 0 && height > 0, "empty field");
        Field {
            width,
            height,
            data,
        }
    }

    /// The value of pixel (x, y).
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
    /// The coarse pixel covers fine pixels 2x, 2x+1 (and rows 2y, 2y+1): it is the average
    /// of their blur. Blur and average are both separable, so each axis is blurred and
    /// averaged in turn, and only the rows the average needs are blurred vertically.
    pub fn reduce(&self) -> Field {
        let (w, h) = (self.width, self.height);
        let (w2, h2) = (w.div_ceil(2), h.div_ceil(2));
        let pair = |i: usize, n: usize| (2 * i, (2 * i + 1).min(n - 1));
        let mut tmp = vec![0f32; w2 * h];
        let mut row = vec![0f32; w];
        let mut padded = vec![0f32; w + 4];
        for y in 0..h {
            blur_row(
                &self.data[y * w..(y + 1) * w],
                &BINOMIAL5,
                &mut padded,
                &mut row,
            );
            for (x, t) in tmp[y * w2..(y + 1) * w2].iter_mut().enumerate() {
                let (x0, x1) = pair(x, w);
                *t = 0.5 * (row[x0] + row[x1]);
            }
        }
        let mut data = vec![0f32; w2 * h2];
        let mut lines = [vec![0f32; w2], vec![0f32; w2]];
        for y in 0..h2 {
            let (y0, y1) = pair(y, h);
            for (line, yk) in lines.iter_mut().zip([y0, y1]) {
                blur_column(&tmp, w2, yk, &BINOMIAL5, line);
            }
            for (x, d) in data[y * w2..(y + 1) * w2].iter_mut().enumerate() {
                *d = 0.5 * (lines[0][x] + lines[1][x]);
            }
        }
        Field::new(w2, h2, data)
    }

    /// Separable 1/16 [1 4 6 4 1] blur with clamped borders.
    pub fn blur5(&self) -> Field {
        self.blur(&BINOMIAL5)
    }

    /// Separable blur with an odd symmetric kernel, clamped borders.
    pub fn blur<const N: usize>(&self, k: &[f32; N]) -> Field {
        let r = N / 2;
        let (w, h) = (self.width, self.height);
        let mut tmp = vec![0f32; w * h];
        let mut padded = vec![0f32; w + 2 * r];
        for y in 0..h {
            let (src, dst) = (&self.data[y * w..(y + 1) * w], &mut tmp[y * w..(y + 1) * w]);
            blur_row(src, k, &mut padded, dst);
        }
        let mut out = vec![0f32; w * h];
        for (y, dst) in out.chunks_exact_mut(w).enumerate() {
            blur_column(&tmp, w, y, k, dst);
        }
        Field::new(w, h, out)
    }
}

/// The 4-connected neighbours of pixel `i` on a `w` × `h` grid (those inside it).
pub fn neighbours4(i: usize, w: usize, h: usize) -> impl Iterator<Item = usize> {
    let (x, y) = (i % w, i / w);
    [
        (x > 0).then(|| i - 1),
        (x + 1 < w).then(|| i + 1),
        (y > 0).then(|| i - w),
        (y + 1 < h).then(|| i + w),
    ]
    .into_iter()
    .flatten()
}

/// The 8-connected neighbours of pixel `i` on a `w` × `h` grid (those inside it).
pub fn neighbours8(i: usize, w: usize, h: usize) -> impl Iterator<Item = usize> {
    const D: [(isize, isize); 8] = [
        (-1, -1),
        (0, -1),
        (1, -1),
        (-1, 0),
        (1, 0),
        (-1, 1),
        (0, 1),
        (1, 1),
    ];
    let (x, y) = ((i % w) as isize, (i / w) as isize);
    D.into_iter().filter_map(move |(dx, dy)| {
        let (nx, ny) = (x + dx, y + dy);
        (nx >= 0 && ny >= 0 && nx < w as isize && ny < h as isize)
            .then(|| ny as usize * w + nx as usize)
    })
}

/// The pyramid's kernel, 1/16 [1 4 6 4 1].
const BINOMIAL5: [f32; 5] = [1.0 / 16.0, 4.0 / 16.0, 6.0 / 16.0, 4.0 / 16.0, 1.0 / 16.0];

/// Row `y` of the vertical blur of `src` (rows of `w`) with kernel `k`, the border rows
/// continuing, into `out`: whole rows times one weight, in kernel order.
fn blur_column<const N: usize>(src: &[f32], w: usize, y: usize, k: &[f32; N], out: &mut [f32]) {
    let (r, h) = (N / 2, src.len() / w);
    out.fill(0.0);
    for (i, &kv) in k.iter().enumerate() {
        let yi = (y + i).saturating_sub(r).min(h - 1);
        for (d, &v) in out.iter_mut().zip(&src[yi * w..(yi + 1) * w]) {
            *d += kv * v;
        }
    }
}

/// Blurs one row with kernel `k`, the border value continuing (`padded`: scratch of
/// `row.len() + N - 1`). Adds whole shifted rows times one weight: loops the compiler
/// vectorises (one tap at a time, in kernel order, as a scalar sum would).
fn blur_row<const N: usize>(row: &[f32], k: &[f32; N], padded: &mut [f32], out: &mut [f32]) {
    let (r, w) = (N / 2, row.len());
    padded[r..r + w].copy_from_slice(row);
    for i in 0..r {
        padded[i] = row[0];
        padded[r + w + i] = row[w - 1];
    }
    out.fill(0.0);
    for (i, &kv) in k.iter().enumerate() {
        for (d, &v) in out.iter_mut().zip(&padded[i..i + w]) {
            *d += kv * v;
        }
    }
}

/// One pyramid level. A sample is the bilinear blend of four texels (intensity, ∂x, ∂y,
/// |∇|) computed from the pixels around it on the fly: storing texels would take four
/// times the image's memory (a quarter of a gigabyte for a 4096² image), and writing it
/// costs more than the few samples an evolution takes where its contours pass.
#[derive(Clone, Debug)]
pub struct Level {
    /// The level's image.
    pub image: Field,
}

/// What [`Level::sample`] returns at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texel {
    /// Bilinear value.
    pub value: f64,
    /// Gradient (central differences, bilinear).
    pub gradient: Point,
    /// Gradient magnitude.
    pub gmag: f64,
}

impl Level {
    /// A level over `image` with its gradient.
    pub fn new(image: Field) -> Self {
        Level { image }
    }

    /// Bilinear texel at `p` (pixel-centre convention, clamped at the borders).
    #[inline]
    pub fn sample(&self, p: Point) -> Texel {
        let [v, gx, gy, gm] = self.bilinear(p);
        Texel {
            value: v,
            gradient: Point::new(gx, gy),
            gmag: gm,
        }
    }

    /// Bilinear gradient magnitude at `p`.
    #[inline]
    pub fn gmag(&self, p: Point) -> f64 {
        self.bilinear(p)[3]
    }

    /// The texel of pixel (x, y): central differences, one-sided at the border.
    #[inline(always)]
    fn texel(&self, x: usize, y: usize) -> [f32; 4] {
        let (w, h) = (self.image.width, self.image.height);
        let d = &self.image.data;
        let row = y * w;
        let dx = 0.5 * (d[row + (x + 1).min(w - 1)] - d[row + x.saturating_sub(1)]);
        let dy = 0.5 * (d[(y + 1).min(h - 1) * w + x] - d[y.saturating_sub(1) * w + x]);
        [d[row + x], dx, dy, (dx * dx + dy * dy).sqrt()]
    }

    #[inline(always)]
    fn bilinear(&self, p: Point) -> [f64; 4] {
        let (w, h) = (self.image.width, self.image.height);
        let fx = (p.x - 0.5).clamp(0.0, (w - 1) as f64);
        let fy = (p.y - 0.5).clamp(0.0, (h - 1) as f64);
        let (x0, y0) = (fx as usize, fy as usize);
        let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
        // Weights in f32, like the texels: four lanes at once.
        let (tx, ty) = ((fx - x0 as f64) as f32, (fy - y0 as f64) as f32);
        let (a, b) = (self.texel(x0, y0), self.texel(x1, y0));
        let (c, d) = (self.texel(x0, y1), self.texel(x1, y1));
        let mut out = [0.0; 4];
        for k in 0..4 {
            let top = a[k] + (b[k] - a[k]) * tx;
            let bottom = c[k] + (d[k] - c[k]) * tx;
            out[k] = (top + (bottom - top) * ty) as f64;
        }
        out
    }
}

/// The Gaussian pyramid: level 0 is the (lightly smoothed) image, level l has 2^-l of its
/// resolution.
#[derive(Clone, Debug)]
pub struct Pyramid {
    /// Levels, finest (0) first.
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
            .all(|l| l.gmag(Point::new(3.3, 2.7)).abs() < 1e-6));
        let ramp = Level::new(Field::new(4, 1, vec![0.0, 1.0, 2.0, 3.0]));
        assert_eq!(ramp.sample(Point::new(2.0, 0.5)).gradient.x, 1.0);
        assert_eq!(ramp.sample(Point::new(2.0, 0.5)).value, 1.5);
        // The blur's fast interior agrees with the clamped border formula.
        let noisy = Field::new(9, 3, (0..27).map(|i| ((i * 7) % 5) as f32).collect());
        let b = noisy.blur5();
        let direct = |x: usize, y: usize| -> f32 {
            let k = [1.0, 4.0, 6.0, 4.0, 1.0];
            let mut s = 0.0;
            for (j, &ky) in k.iter().enumerate() {
                for (i, &kx) in k.iter().enumerate() {
                    let xi = (x as isize + i as isize - 2).clamp(0, 8) as usize;
                    let yi = (y as isize + j as isize - 2).clamp(0, 2) as usize;
                    s += kx * ky * noisy.at(xi, yi);
                }
            }
            s / 256.0
        };
        for y in 0..3 {
            for x in 0..9 {
                assert!((b.at(x, y) - direct(x, y)).abs() < 1e-5, "{x},{y}");
            }
        }
        // The separable reduction equals the blur averaged over each coarse pixel's 2×2
        // fine pixels (odd sizes: the last pixel pairs with itself).
        let odd = Field::new(9, 7, (0..63).map(|i| ((i * 13) % 11) as f32).collect());
        let (r, b) = (odd.reduce(), odd.blur5());
        assert_eq!((r.width, r.height), (5, 4));
        for y in 0..4 {
            for x in 0..5 {
                let (x1, y1) = ((2 * x + 1).min(8), (2 * y + 1).min(6));
                let avg =
                    0.25 * (b.at(2 * x, 2 * y) + b.at(x1, 2 * y) + b.at(2 * x, y1) + b.at(x1, y1));
                assert!((r.at(x, y) - avg).abs() < 1e-5, "{x},{y}");
            }
        }
    }
}
