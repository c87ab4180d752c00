//! The pixel noise of an image, read from the median absolute deviation of its high-pass
//! residual (robust to the edges of objects, which are few pixels).

use super::field::Field;

/// The standard deviation of the pixel noise in `fine` (pyramid level 0): the median
/// absolute deviation of its high-pass residual (the image less its [1 2 1] blur),
/// × 1.4826 for a Gaussian, × 2.64 to undo the residual filter's gain on white noise
/// (σ of level 0 over σ of its residual, measured on simulated white noise). The median
/// ignores the edges of objects, which are few pixels. Read on at most
/// [`NOISE_SAMPLES`] pixels spread evenly over the image: the median of that many is
/// within a percent of the whole image's, at a fraction of the cost.
pub fn noise_sigma(fine: &Field) -> f64 {
    let (w, h) = (fine.width, fine.height);
    let n = w * h;
    let step = n.div_ceil(NOISE_SAMPLES).max(1);
    let at = |x: usize, y: usize| fine.data[y * w + x];
    let mut hp: Vec<f32> = (0..n)
        .step_by(step)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let (xl, xr) = (x.saturating_sub(1), (x + 1).min(w - 1));
            let (yu, yd) = (y.saturating_sub(1), (y + 1).min(h - 1));
            let row = |y: usize| 0.25 * at(xl, y) + 0.5 * at(x, y) + 0.25 * at(xr, y);
            at(x, y) - (0.25 * row(yu) + 0.5 * row(y) + 0.25 * row(yd))
        })
        .collect();
    let mid = hp.len() / 2;
    let med = *hp.select_nth_unstable_by(mid, f32::total_cmp).1;
    let mut dev: Vec<f32> = hp.iter().map(|v| (v - med).abs()).collect();
    let mad = *dev.select_nth_unstable_by(mid, f32::total_cmp).1;
    mad as f64 * 1.4826 * 2.64
}

/// Most pixels [`noise_sigma`] reads.
pub const NOISE_SAMPLES: usize = 1 << 15;
