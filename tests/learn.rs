//! The pixel classifier: features against a direct reference, normalisation, the
//! coarse-grid scales against direct ones, a forest that tells apart two textures of
//! one mean intensity, and bad strokes.

use proptest::prelude::*;
use topocontour::check::Rng;
use topocontour::learn::features::{eigenvalues, normalise};
use topocontour::learn::filters::{kernel, Order, Plane};
use topocontour::learn::{Classifier, FeatureSet, ForestParams, StrokeError, Strokes};

fn reflect(i: isize, n: usize) -> usize {
    let n = n as isize;
    let m = i.rem_euclid(2 * n);
    (if m < n { m } else { 2 * n - 1 - m }) as usize
}

/// Direct 2D correlation of `img` with the outer product ky ⊗ kx (reflected borders).
fn direct(img: &Plane, kx: &[f32], ky: &[f32]) -> Vec<f64> {
    let (w, h) = (img.width, img.height);
    let (rx, ry) = (kx.len() as isize / 2, ky.len() as isize / 2);
    let mut out = vec![0.0; w * h];
    for y in 0..h {
        for x in 0..w {
            let mut s = 0.0;
            for (j, &b) in ky.iter().enumerate() {
                let sy = reflect(y as isize + j as isize - ry, h);
                for (i, &a) in kx.iter().enumerate() {
                    let sx = reflect(x as isize + i as isize - rx, w);
                    s += a as f64 * b as f64 * img.data[sy * w + sx] as f64;
                }
            }
            out[y * w + x] = s;
        }
    }
    out
}

/// The eight features of scale `sigma` at full resolution, computed directly.
fn reference(img: &Plane, sigma: f64) -> Vec<Vec<f64>> {
    let (g, d, dd) = (
        kernel(sigma, Order::Smooth),
        kernel(sigma, Order::First),
        kernel(sigma, Order::Second),
    );
    let smooth = direct(img, &g, &g);
    let (ix, iy) = (direct(img, &d, &g), direct(img, &g, &d));
    let (ixx, iyy, ixy) = (
        direct(img, &dd, &g),
        direct(img, &g, &dd),
        direct(img, &d, &d),
    );
    let g66 = kernel(0.66 * sigma, Order::Smooth);
    let narrow = direct(img, &g66, &g66);
    let outer = kernel(0.5 * sigma, Order::Smooth);
    let avg = |v: Vec<f64>| {
        let p = Plane {
            width: img.width,
            height: img.height,
            data: v.iter().map(|&x| x as f32).collect(),
        };
        direct(&p, &outer, &outer)
    };
    let n = ix.len();
    let sxx = avg((0..n).map(|i| ix[i] * ix[i]).collect());
    let sxy = avg((0..n).map(|i| ix[i] * iy[i]).collect());
    let syy = avg((0..n).map(|i| iy[i] * iy[i]).collect());
    let eig = |a: f64, b: f64, c: f64| {
        let m = 0.5 * (a + c);
        let r = (0.25 * (a - c) * (a - c) + b * b).sqrt();
        (m + r, m - r)
    };
    let mut out = vec![Vec::new(); 8];
    for i in 0..n {
        let st = eig(sxx[i], sxy[i], syy[i]);
        let he = eig(ixx[i], ixy[i], iyy[i]);
        let row = [
            smooth[i],
            ix[i].hypot(iy[i]),
            ixx[i] + iyy[i],
            smooth[i] - narrow[i],
            st.0,
            st.1,
            he.0,
            he.1,
        ];
        for (o, v) in out.iter_mut().zip(row) {
            o.push(v);
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn features_match_a_direct_reference(
        w in 5usize..14, h in 5usize..14, seed in any::<u64>(), s in 0usize..3
    ) {
        let mut rng = Rng(seed);
        let data: Vec<f32> = (0..w * h).map(|_| rng.unit() as f32).collect();
        let sigma = [0.7, 1.0, 1.6][s];
        let set = FeatureSet { scales: vec![sigma], pyramid: false };
        let f = set.compute(w, h, &data);
        let raw = normalise(&Plane { width: w, height: h, data: data.clone() });
        prop_assert_eq!(&f.planes[0], &raw.data);
        let want = reference(&raw, sigma);
        for (k, plane) in want.iter().enumerate() {
            for (i, &v) in plane.iter().enumerate() {
                let got = f.planes[1 + k][i] as f64;
                prop_assert!((got - v).abs() <= 2e-4 * (1.0 + v.abs()),
                    "feature {} pixel {}: {} vs {}", k, i, got, v);
            }
        }
    }
}

#[test]
fn eigenvalues_of_a_diagonal_and_a_rotated_matrix() {
    assert_eq!(eigenvalues(3.0, 0.0, -1.0), (3.0, -1.0));
    // [[2, 1], [1, 2]] has eigenvalues 3 and 1.
    let (a, b) = eigenvalues(2.0, 1.0, 2.0);
    assert!((a - 3.0).abs() < 1e-6 && (b - 1.0).abs() < 1e-6);
}

fn test_image(w: usize, h: usize) -> Vec<f32> {
    let (img, _) = topocontour::check::touching_rods(w, h, 24, 8);
    img
}

#[test]
fn exposure_and_bit_depth_do_not_change_the_features() {
    let (w, h) = (64, 48);
    let img = test_image(w, h);
    let set = FeatureSet::default();
    let a = set.compute(w, h, &img);
    // Half the exposure with an offset, and the 16-bit quantisation of it.
    let dim: Vec<f32> = img.iter().map(|v| 0.5 * v + 0.1).collect();
    let deep: Vec<f32> = dim
        .iter()
        .map(|v| (v * 65535.0).round() / 65535.0)
        .collect();
    for other in [dim, deep] {
        let b = set.compute(w, h, &other);
        for (pa, pb) in a.planes.iter().zip(&b.planes) {
            for (x, y) in pa.iter().zip(pb) {
                assert!((x - y).abs() < 1e-3 * (1.0 + x.abs()), "{x} vs {y}");
            }
        }
    }
}

/// The coarse scales computed on reduced grids stay close to the direct ones: RMS
/// difference at most 0.3 of the plane's spread (measured on this image: 0.01–0.28, the
/// second derivatives and structure tensor at σ 5 worst).
#[test]
fn coarse_scales_on_reduced_grids_follow_the_direct_ones() {
    let (w, h) = (160, 128);
    let img = test_image(w, h);
    let scales = vec![3.5, 5.0, 10.0];
    let fast = FeatureSet {
        scales: scales.clone(),
        pyramid: true,
    }
    .compute(w, h, &img);
    let slow = FeatureSet {
        scales,
        pyramid: false,
    }
    .compute(w, h, &img);
    let mut worst: f64 = 0.0;
    for (k, (a, b)) in fast.planes.iter().zip(&slow.planes).enumerate().skip(1) {
        let n = a.len() as f64;
        let mean = b.iter().map(|&v| v as f64).sum::<f64>() / n;
        let spread = (b.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n).sqrt();
        let rms = (a
            .iter()
            .zip(b)
            .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        eprintln!("plane {k}: rms / spread {:.3}", rms / spread);
        worst = worst.max(rms / spread);
    }
    assert!(worst <= 0.3, "worst plane: rms / spread {worst}");
}

/// Two textures of the same mean intensity, side by side: a global or local intensity
/// level cannot tell them apart, the forest on the features can.
#[test]
fn the_forest_separates_textures_of_one_mean() {
    let (w, h) = (96, 64);
    let mut rng = Rng(11);
    let img: Vec<f32> = (0..w * h)
        .map(|i| {
            let x = i % w;
            let amp = if x < w / 2 { 0.25 } else { 0.02 };
            0.5 + amp * (rng.unit() as f32 - 0.5) * 2.0
        })
        .collect();
    let mut s = vec![0u8; w * h];
    for y in [10, 30, 50] {
        for x in 8..20 {
            s[y * w + x] = 2;
            s[y * w + x + w / 2 + 20] = 1;
        }
    }
    let strokes = Strokes::new(w, h, s).unwrap();
    let set = FeatureSet::default();
    let features = set.compute(w, h, &img);
    let clf = Classifier::train(&features, &strokes, &ForestParams::default());
    let best = clf.predict(&features).argmax();
    let (mut right, mut total) = (0, 0);
    for y in 0..h {
        for x in (0..w).filter(|&x| x.abs_diff(w / 2) > 8) {
            total += 1;
            let want = if x < w / 2 { 2 } else { 1 };
            right += (best[y * w + x] == want) as usize;
        }
    }
    assert!(right * 100 >= 95 * total, "{right} of {total}");
}

#[test]
fn bad_strokes_are_refused() {
    assert_eq!(Strokes::new(2, 1, vec![1, 1]), Err(StrokeError::NoObject));
    assert_eq!(Strokes::new(2, 1, vec![2, 2]), Err(StrokeError::OneClass));
    assert_eq!(Strokes::new(2, 1, vec![2, 0]), Err(StrokeError::OneClass));
    assert_eq!(
        Strokes::new(3, 1, vec![2, 1, 7]),
        Err(StrokeError::Value {
            value: 7,
            x: 2,
            y: 0
        })
    );
    assert!(Strokes::new(2, 1, vec![2, 3]).is_ok());
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("s.png");
    image::GrayImage::from_raw(3, 2, vec![0, 1, 2, 0, 0, 0])
        .unwrap()
        .save(&path)
        .unwrap();
    assert!(Strokes::read(&path, 3, 2).is_ok());
    assert_eq!(
        Strokes::read(&path, 4, 2),
        Err(StrokeError::Size {
            got_w: 3,
            got_h: 2,
            want_w: 4,
            want_h: 2
        })
    );
}
