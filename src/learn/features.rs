//! The pixel features of ilastik's standard set (Sommer et al. 2011, "ilastik:
//! Interactive learning and segmentation toolkit", §2; the filters as vigra computes
//! them): at each scale σ ∈ {0.7, 1, 1.6, 3.5, 5, 10}, the Gaussian smoothing, the
//! gradient magnitude, the Laplacian of Gaussian, the difference of Gaussians G_σ −
//! G_0.66σ, the two eigenvalues of the structure tensor (gradient at σ, averaged at
//! σ/2) and the two eigenvalues of the Hessian of Gaussian; and the raw image: 49
//! planes, f32.
//!
//! The image is first mapped linearly so that its 0.5th and 99.5th percentiles become
//! 0 and 1 ([`normalise`]): an 8-bit and a 16-bit copy, or two exposures of one sample,
//! give the same features, and a forest trained on one applies to the other.
//!
//! Coarse scales are computed on a reduced copy (see [`level_for`]): σ = 3.5 on the
//! half-size grid, 5 on the quarter, 10 on the eighth, with the grain the reductions
//! already put in subtracted from σ², then bilinearly upsampled. docs/decisions.md
//! records what that costs in accuracy and saves in time.

use super::filters::{along_columns, along_columns_many, along_rows, kernel, reduce};
use super::filters::{for_rows_many, upsample, Order, Plane, REDUCE_VARIANCE};

/// The scales of ilastik's default feature selection, pixels.
pub const SCALES: [f64; 6] = [0.7, 1.0, 1.6, 3.5, 5.0, 10.0];

/// Features per scale: smoothing, gradient magnitude, LoG, DoG, two structure-tensor and
/// two Hessian eigenvalues.
pub const PER_SCALE: usize = 8;

/// Version of the feature definitions: a saved classifier records it, and one trained
/// on other features is refused.
pub const FEATURE_VERSION: u32 = 1;

/// A coarse grid's σ (in its own pixels) is at least this: finer kernels on a coarse grid
/// would alias.
pub const MIN_COARSE_SIGMA: f64 = 1.0;

/// The feature planes of one image, each the image's size.
#[derive(Clone, Debug)]
pub struct Features {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// One plane per feature, in [`FeatureSet::names`] order.
    pub planes: Vec<Vec<f32>>,
}

/// Which scales, and whether coarse ones may use reduced grids.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct FeatureSet {
    /// The scales σ, pixels.
    pub scales: Vec<f64>,
    /// Compute coarse scales on reduced grids ([`level_for`]).
    pub pyramid: bool,
}

impl Default for FeatureSet {
    fn default() -> Self {
        FeatureSet {
            scales: SCALES.to_vec(),
            pyramid: true,
        }
    }
}

impl FeatureSet {
    /// How many planes [`FeatureSet::compute`] makes.
    pub fn len(&self) -> usize {
        1 + PER_SCALE * self.scales.len()
    }

    /// Never empty: the raw image is always a feature.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The planes' names, in order.
    pub fn names(&self) -> Vec<String> {
        let kinds = [
            "smooth", "gradient", "log", "dog", "st_max", "st_min", "hess_max", "hess_min",
        ];
        let mut names = vec!["raw".to_string()];
        for s in &self.scales {
            names.extend(kinds.iter().map(|k| format!("{k}@{s}")));
        }
        names
    }

    /// The features of a gray image (`width` × `height`, any range: it is normalised).
    pub fn compute(&self, width: usize, height: usize, image: &[f32]) -> Features {
        assert_eq!(image.len(), width * height, "image size");
        let raw = normalise(&Plane {
            width,
            height,
            data: image.to_vec(),
        });
        // The reduced grids, made once: level l has the grain `grain[l]` (fine px²).
        let mut levels = vec![raw.clone()];
        let mut grain = vec![0.0];
        let mut planes = vec![raw.data.clone()];
        for &sigma in &self.scales {
            let l = if self.pyramid {
                level_for(sigma, width.min(height))
            } else {
                0
            };
            while levels.len() <= l {
                let k = levels.len() - 1;
                let next = reduce(&levels[k]);
                grain.push(grain[k] + 4f64.powi(k as i32) * REDUCE_VARIANCE);
                levels.push(next);
            }
            let at = scale_features(&levels[l], sigma, l as u32, grain[l]);
            for p in at {
                planes.push(if l == 0 {
                    p.data
                } else {
                    upsample(&p, l as u32, width, height).data
                });
            }
        }
        Features {
            width,
            height,
            planes,
        }
    }
}

/// The grid to compute scale `sigma` on: the coarsest level l (half size per level) whose
/// remaining σ, √(σ² − grain_l) / 2^l, is still [`MIN_COARSE_SIGMA`], and whose short
/// side keeps 16 pixels.
pub fn level_for(sigma: f64, short_side: usize) -> usize {
    let mut grain = 0.0;
    let mut l = 0;
    loop {
        let next_grain = grain + 4f64.powi(l as i32) * REDUCE_VARIANCE;
        let f = 2f64.powi(l as i32 + 1);
        let rest = (sigma * sigma - next_grain).max(0.0).sqrt() / f;
        if rest < MIN_COARSE_SIGMA || short_side >> (l + 1) < 16 {
            return l;
        }
        grain = next_grain;
        l += 1;
    }
}

/// `image` mapped linearly so its 0.5th and 99.5th percentiles become 0 and 1 (a flat
/// image becomes 0).
pub fn normalise(image: &Plane) -> Plane {
    let n = image.data.len();
    // An even sample of at most 65,536 values holds the percentiles to a fraction of
    // a percent.
    let step = n.div_ceil(65_536).max(1);
    let mut sample: Vec<f32> = image.data.iter().step_by(step).copied().collect();
    sample.sort_by(f32::total_cmp);
    let at =
        |q: f64| sample[((q * (sample.len() - 1) as f64).round() as usize).min(sample.len() - 1)];
    let (lo, hi) = (at(0.005), at(0.995));
    let scale = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
    Plane {
        width: image.width,
        height: image.height,
        data: image.data.iter().map(|&v| (v - lo) * scale).collect(),
    }
}

/// The eigenvalues (larger first) of the symmetric matrix [[a, b], [b, c]].
#[inline]
pub fn eigenvalues(a: f32, b: f32, c: f32) -> (f32, f32) {
    let mean = 0.5 * (a + c);
    let d = (0.25 * (a - c) * (a - c) + b * b).sqrt();
    (mean + d, mean - d)
}

/// The [`PER_SCALE`] planes of scale `sigma` (fine pixels) on `base`, a grid reduced
/// `level` times whose grain is `grain` fine px²; derivatives per fine pixel.
fn scale_features(base: &Plane, sigma: f64, level: u32, grain: f64) -> Vec<Plane> {
    let f = (1u32 << level) as f64;
    let on_grid = |s: f64| ((s * s - grain).max(0.0).sqrt() / f).max(0.3);
    let sc = on_grid(sigma);
    let (g, d, dd) = (
        kernel(sc, Order::Smooth),
        kernel(sc, Order::First),
        kernel(sc, Order::Second),
    );
    let rows_g = along_rows(base, &g);
    let rows_d = along_rows(base, &d);
    let rows_dd = along_rows(base, &dd);
    // The column passes that read one row-filtered plane, together.
    let [smooth, iy, iyy] = planes(along_columns_many(&rows_g, &[&g, &d, &dd]));
    let [ix, ixy] = planes(along_columns_many(&rows_d, &[&g, &d]));
    let ixx = along_columns(&rows_dd, &g);
    let dog_k = kernel(on_grid(0.66 * sigma), Order::Smooth);
    let narrow = along_columns(&along_rows(base, &dog_k), &dog_k);
    let (s1, s2) = ((1.0 / f) as f32, (1.0 / (f * f)) as f32);
    let (w, h) = (base.width, base.height);
    // The structure tensor: products of the gradient at σ, averaged at σ/2 (vigra's
    // inner and outer scales as ilastik passes them).
    let outer = kernel((0.5 * sigma / f).max(0.3), Order::Smooth);
    let mut products = [Plane::zeros(w, h), Plane::zeros(w, h), Plane::zeros(w, h)];
    per_row(&mut products, |y, rows| {
        let [xx, xy, yy] = rows else {
            unreachable!("three planes")
        };
        let (a, b) = (&ix.data[y * w..(y + 1) * w], &iy.data[y * w..(y + 1) * w]);
        for x in 0..w {
            xx[x] = a[x] * a[x] * s2;
            xy[x] = a[x] * b[x] * s2;
            yy[x] = b[x] * b[x] * s2;
        }
    });
    let [sxx, sxy, syy] = products.map(|p| along_columns(&along_rows(&p, &outer), &outer));
    let mut out: [Plane; PER_SCALE - 1] = std::array::from_fn(|_| Plane::zeros(w, h));
    // Every plane but the smoothing, in one pass over the filtered planes.
    per_row(&mut out, |y, rows| {
        let [gradient, log, dog, st_max, st_min, hess_max, hess_min] = rows else {
            unreachable!("seven planes")
        };
        let (ix, iy, ixx, ixy, iyy) = (
            row(&ix, y),
            row(&iy, y),
            row(&ixx, y),
            row(&ixy, y),
            row(&iyy, y),
        );
        let (sm, na) = (row(&smooth, y), row(&narrow, y));
        let (sxx, sxy, syy) = (row(&sxx, y), row(&sxy, y), row(&syy, y));
        for x in 0..w {
            gradient[x] = s1 * (ix[x] * ix[x] + iy[x] * iy[x]).sqrt();
            log[x] = s2 * (ixx[x] + iyy[x]);
            dog[x] = sm[x] - na[x];
            (st_max[x], st_min[x]) = eigenvalues(sxx[x], sxy[x], syy[x]);
            (hess_max[x], hess_min[x]) = eigenvalues(ixx[x] * s2, ixy[x] * s2, iyy[x] * s2);
        }
    });
    let mut all = vec![smooth];
    all.extend(out);
    all
}

/// Row `y` of `p`.
fn row(p: &Plane, y: usize) -> &[f32] {
    &p.data[y * p.width..(y + 1) * p.width]
}

/// The planes of a `Vec` of known length as an array.
fn planes<const N: usize>(v: Vec<Plane>) -> [Plane; N] {
    v.try_into().expect("one plane per kernel")
}

/// Calls `f(y, rows)` for every row of the (equal-sized) planes `out`.
fn per_row<F>(out: &mut [Plane], f: F)
where
    F: Fn(usize, &mut [&mut [f32]]) + Sync + Send,
{
    let w = out.first().map_or(1, |p| p.width);
    let mut rows: Vec<&mut [f32]> = out.iter_mut().map(|p| p.data.as_mut_slice()).collect();
    for_rows_many(&mut rows, w, f);
}
