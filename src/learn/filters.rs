//! Separable Gaussian filters on f32 planes: the smoothing, first- and second-derivative
//! kernels the features are made of, a 2 × 2 reduction for the coarse scales and the
//! bilinear way back up. Rows are filtered in parallel when the `cli` feature brings
//! rayon; without it, one after another (the same numbers either way).
//!
//! Kernels are sampled Gaussians on ⌈3σ⌉ + order taps each side (vigra's default window
//! is 3σ), normalised so that the smoothing keeps a constant, the first derivative
//! gives 1 on a unit ramp and the second 1 on x²/2, whatever the sampling does to
//! small σ. Borders reflect (d c b a | a b c d), so a derivative across the image edge
//! reads zero, as scipy's and vigra's `reflect` do.

/// A plane of `width` × `height` values, row by row.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Values row by row.
    pub data: Vec<f32>,
}

impl Plane {
    /// A plane of zeros.
    pub fn zeros(width: usize, height: usize) -> Self {
        Plane {
            width,
            height,
            data: written_zeros(width * height),
        }
    }
}

/// `n` zeros written to memory, not `vec![0.0; n]`: that asks the kernel for zeroed
/// pages, which a filter's first `+=` reads (mapping the shared zero page) and then
/// writes, a second page fault that flushes every core's TLB. perf put a quarter of
/// the features' and prediction's CPU time in those faults (docs/decisions.md,
/// 2026-12-02).
pub fn written_zeros(n: usize) -> Vec<f32> {
    let mut v = Vec::with_capacity(n);
    v.resize(n, 0.0);
    v
}

/// Which Gaussian: the smoothing, or its first or second derivative.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    /// G_σ.
    Smooth,
    /// dG_σ/dx.
    First,
    /// d²G_σ/dx².
    Second,
}

/// The correlation kernel (out(x) = Σ_t k(t) f(x + t), t = −r..=r) of `order` at `sigma`.
pub fn kernel(sigma: f64, order: Order) -> Vec<f32> {
    let extra = match order {
        Order::Smooth => 0,
        Order::First => 1,
        Order::Second => 2,
    };
    let r = (3.0 * sigma).ceil() as i64 + extra;
    let r = r.max(1);
    let s2 = sigma * sigma;
    let g: Vec<f64> = (-r..=r)
        .map(|t| (-(t * t) as f64 / (2.0 * s2)).exp())
        .collect();
    let t = |i: usize| i as f64 - r as f64;
    let k: Vec<f64> = match order {
        Order::Smooth => {
            let sum: f64 = g.iter().sum();
            g.iter().map(|v| v / sum).collect()
        }
        Order::First => {
            let d: Vec<f64> = g.iter().enumerate().map(|(i, v)| t(i) * v).collect();
            let moment: f64 = d.iter().enumerate().map(|(i, v)| t(i) * v).sum();
            d.iter().map(|v| v / moment).collect()
        }
        Order::Second => {
            let d: Vec<f64> = g
                .iter()
                .enumerate()
                .map(|(i, v)| (t(i) * t(i) / s2 - 1.0) * v)
                .collect();
            // No response to a constant, then 1 on x²/2.
            let mean = d.iter().sum::<f64>() / d.len() as f64;
            let d: Vec<f64> = d.iter().map(|v| v - mean).collect();
            let moment: f64 = d.iter().enumerate().map(|(i, v)| t(i) * t(i) * v).sum();
            d.iter().map(|v| 2.0 * v / moment).collect()
        }
    };
    k.into_iter().map(|v| v as f32).collect()
}

/// The index `i` (may be outside 0..n) reflected into 0..n (d c b a | a b c d).
#[inline]
fn reflect(i: isize, n: usize) -> usize {
    let n = n as isize;
    let period = 2 * n;
    let m = i.rem_euclid(period);
    (if m < n { m } else { period - 1 - m }) as usize
}

/// Calls `f(y, row)` for every row of `out` (rows of `width`), in parallel with rayon.
pub fn for_rows<F>(out: &mut [f32], width: usize, f: F)
where
    F: Fn(usize, &mut [f32]) + Sync + Send,
{
    #[cfg(feature = "cli")]
    {
        use rayon::prelude::*;
        // Bands of rows: one task per row would cost more than a narrow row's work.
        let band = (16_384 / width.max(1)).max(1);
        out.par_chunks_mut(width * band)
            .enumerate()
            .for_each(|(b, rows)| {
                for (k, row) in rows.chunks_mut(width).enumerate() {
                    f(b * band + k, row);
                }
            });
    }
    #[cfg(not(feature = "cli"))]
    for (y, row) in out.chunks_mut(width).enumerate() {
        f(y, row);
    }
}

/// Calls `f(y, rows)` for every row index `y` of the planes `outs` (rows of `width`, all
/// of one size), `rows[k]` being row `y` of `outs[k]`; in parallel with rayon, as
/// [`for_rows`]. One pass writing several planes reads its inputs once.
pub fn for_rows_many<F>(outs: &mut [&mut [f32]], width: usize, f: F)
where
    F: Fn(usize, &mut [&mut [f32]]) + Sync + Send,
{
    let width = width.max(1);
    let height = outs.first().map_or(0, |o| o.len() / width);
    assert!(
        outs.iter().all(|o| o.len() == width * height),
        "plane sizes"
    );
    let band = (16_384 / width).max(1);
    // Per band of rows, each plane's part of it.
    let mut bands: Vec<Vec<&mut [f32]>> = (0..height.div_ceil(band))
        .map(|_| Vec::with_capacity(outs.len()))
        .collect();
    for o in outs.iter_mut() {
        for (b, part) in o.chunks_mut(width * band).enumerate() {
            bands[b].push(part);
        }
    }
    let run = |(b, mut parts): (usize, Vec<&mut [f32]>)| {
        let n = parts.first().map_or(0, |p| p.len() / width);
        for k in 0..n {
            let mut rows: Vec<&mut [f32]> = parts
                .iter_mut()
                .map(|p| &mut p[k * width..(k + 1) * width])
                .collect();
            f(b * band + k, &mut rows);
        }
    };
    #[cfg(feature = "cli")]
    {
        use rayon::prelude::*;
        bands.into_par_iter().enumerate().for_each(run);
    }
    #[cfg(not(feature = "cli"))]
    bands.into_iter().enumerate().for_each(run);
}

/// Whether kernel `k` is even (`Some(1.0)`: k(t) = k(−t)), odd (`Some(-1.0)`: k(t) =
/// −k(−t)) or neither. [`kernel`]'s are exactly one of the first two.
fn parity(k: &[f32]) -> Option<f32> {
    let n = k.len();
    if n.is_multiple_of(2) {
        return None;
    }
    [1.0f32, -1.0]
        .into_iter()
        .find(|&s| (0..n / 2).all(|t| k[n - 1 - t] == s * k[t]))
}

/// out = Σ_j k[j] · taps(j), element by element, over rows of equal length; with a
/// symmetric kernel the taps at ±t are added (or subtracted) first, so each pair costs
/// one multiply: Gaussians and their derivatives are, and the filters are the features'
/// main cost.
fn correlate<'a>(out: &mut [f32], k: &[f32], taps: impl Fn(usize) -> &'a [f32]) {
    let r = k.len() / 2;
    match parity(k) {
        Some(sign) => {
            let kc = k[r];
            for (o, &c) in out.iter_mut().zip(taps(r)) {
                *o = kc * c;
            }
            for t in 1..=r {
                let (kt, lo, hi) = (k[r + t], taps(r - t), taps(r + t));
                if sign > 0.0 {
                    for ((o, &a), &b) in out.iter_mut().zip(lo).zip(hi) {
                        *o += kt * (b + a);
                    }
                } else {
                    for ((o, &a), &b) in out.iter_mut().zip(lo).zip(hi) {
                        *o += kt * (b - a);
                    }
                }
            }
        }
        None => {
            out.fill(0.0);
            for (j, &kj) in k.iter().enumerate() {
                for (o, &p) in out.iter_mut().zip(taps(j)) {
                    *o += kj * p;
                }
            }
        }
    }
}

/// Correlates every row of `src` with `k` (reflected borders).
pub fn along_rows(src: &Plane, k: &[f32]) -> Plane {
    let (w, h) = (src.width, src.height);
    let r = k.len() / 2;
    let mut out = Plane::zeros(w, h);
    for_rows(&mut out.data, w, |y, row| {
        let line = &src.data[y * w..(y + 1) * w];
        // The row with its reflected margins: only the 2r margin pixels need `reflect`.
        let mut padded = Vec::with_capacity(w + 2 * r);
        padded.extend((0..r).map(|i| line[reflect(i as isize - r as isize, w)]));
        padded.extend_from_slice(line);
        padded.extend((0..r).map(|i| line[reflect((w + i) as isize, w)]));
        // Tap by tap over the whole row: the inner loops vectorise.
        correlate(row, k, |j| &padded[j..j + w]);
    });
    out
}

/// Correlates every column of `src` with `k` (reflected borders).
pub fn along_columns(src: &Plane, k: &[f32]) -> Plane {
    along_columns_many(src, &[k]).pop().expect("one kernel")
}

/// Correlates every column of `src` with each of `ks` (reflected borders), in one pass:
/// the source rows are read once for all kernels. Each result is [`along_columns`]'s.
pub fn along_columns_many(src: &Plane, ks: &[&[f32]]) -> Vec<Plane> {
    let (w, h) = (src.width, src.height);
    let mut out: Vec<Plane> = ks.iter().map(|_| Plane::zeros(w, h)).collect();
    let mut outs: Vec<&mut [f32]> = out.iter_mut().map(|p| p.data.as_mut_slice()).collect();
    for_rows_many(&mut outs, w, |y, rows| {
        for (row, k) in rows.iter_mut().zip(ks) {
            let r = k.len() as isize / 2;
            correlate(row, k, |j| {
                let sy = reflect(y as isize + j as isize - r, h);
                &src.data[sy * w..(sy + 1) * w]
            });
        }
    });
    out
}

/// The separable filter: `kx` along rows, then `ky` along columns.
pub fn separable(src: &Plane, kx: &[f32], ky: &[f32]) -> Plane {
    along_columns(&along_rows(src, kx), ky)
}

/// Half the size: each pixel the mean of a 2 × 2 block of `src` smoothed at σ = 1
/// (so the coarse grid does not alias). The result's grain is [`REDUCE_VARIANCE`].
pub fn reduce(src: &Plane) -> Plane {
    let k = kernel(REDUCE_SIGMA, Order::Smooth);
    let s = separable(src, &k, &k);
    let (w2, h2) = (src.width.div_ceil(2), src.height.div_ceil(2));
    let mut out = Plane::zeros(w2, h2);
    let (w, h) = (src.width, src.height);
    for_rows(&mut out.data, w2, |y, row| {
        let (y0, y1) = (2 * y, (2 * y + 1).min(h - 1));
        for (x, o) in row.iter_mut().enumerate() {
            let (x0, x1) = (2 * x, (2 * x + 1).min(w - 1));
            *o = 0.25
                * (s.data[y0 * w + x0]
                    + s.data[y0 * w + x1]
                    + s.data[y1 * w + x0]
                    + s.data[y1 * w + x1]);
        }
    });
    out
}

/// The smoothing [`reduce`] applies before it averages, in its input's pixels.
pub const REDUCE_SIGMA: f64 = 1.0;

/// The variance one [`reduce`] adds, in its input's pixels²: the smoothing's σ² and the
/// 2-pixel box's 1/4.
pub const REDUCE_VARIANCE: f64 = REDUCE_SIGMA * REDUCE_SIGMA + 0.25;

/// `src`, a plane reduced `levels` times from a `width` × `height` one, bilinearly back
/// to that size (pixel centres aligned, borders clamped).
pub fn upsample(src: &Plane, levels: u32, width: usize, height: usize) -> Plane {
    let f = (1usize << levels) as f64;
    // Per output column (row): the two source columns (rows) and the weight of the second.
    let taps = |n: usize, m: usize| -> Vec<(usize, usize, f32)> {
        (0..n)
            .map(|x| {
                let u = ((x as f64 + 0.5) / f - 0.5).clamp(0.0, (m - 1) as f64);
                let i = u.floor() as usize;
                (i, (i + 1).min(m - 1), (u - i as f64) as f32)
            })
            .collect()
    };
    let (tx, ty) = (taps(width, src.width), taps(height, src.height));
    let sw = src.width;
    let mut out = Plane::zeros(width, height);
    for_rows(&mut out.data, width, |y, row| {
        let (a, b, t) = ty[y];
        let (ra, rb) = (
            &src.data[a * sw..(a + 1) * sw],
            &src.data[b * sw..(b + 1) * sw],
        );
        for (o, &(i, j, s)) in row.iter_mut().zip(&tx) {
            let top = ra[i] + s * (ra[j] - ra[i]);
            let bottom = rb[i] + s * (rb[j] - rb[i]);
            *o = top + t * (bottom - top);
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernels_have_their_moments() {
        for sigma in [0.3, 0.7, 1.0, 2.5] {
            let moment = |k: &[f32], p: i32| -> f64 {
                let r = (k.len() / 2) as i32;
                k.iter()
                    .enumerate()
                    .map(|(i, &v)| (i as i32 - r).pow(p as u32) as f64 * v as f64)
                    .sum()
            };
            let g = kernel(sigma, Order::Smooth);
            assert!((moment(&g, 0) - 1.0).abs() < 1e-6);
            let d = kernel(sigma, Order::First);
            assert!(moment(&d, 0).abs() < 1e-6 && (moment(&d, 1) - 1.0).abs() < 1e-5);
            let dd = kernel(sigma, Order::Second);
            assert!(moment(&dd, 0).abs() < 1e-5 && moment(&dd, 1).abs() < 1e-5);
            assert!((moment(&dd, 2) - 2.0).abs() < 1e-4);
        }
    }

    #[test]
    fn reflection_stays_inside() {
        let got: Vec<usize> = (-3..8).map(|i| reflect(i, 4)).collect();
        assert_eq!(got, [2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0]);
        assert_eq!(reflect(-1, 1), 0);
    }

    #[test]
    fn upsampling_a_ramp_keeps_it_a_ramp() {
        // Coarse pixel x sits at fine position 2x + 1: a ramp stays the same ramp inside.
        let coarse = Plane {
            width: 8,
            height: 1,
            data: (0..8).map(|x| 2.0 * x as f32 + 1.0).collect(),
        };
        let fine = upsample(&coarse, 1, 16, 2);
        for x in 1..15 {
            assert!((fine.data[x] - (x as f32 + 0.5)).abs() < 1e-5, "{x}");
            assert_eq!(fine.data[x], fine.data[16 + x]);
        }
    }
}
