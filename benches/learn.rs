//! The pixel classifier's speed, in CPU seconds (all threads) and wall seconds: the
//! features, training on the strokes, and prediction, against smartcore's forest grown
//! alike on the same features.
//!
//!   cargo bench --bench learn                       # a seeded 512² colony of rods
//!   cargo bench --bench learn -- IMAGE STROKES …    # real images with their strokes
//!
//! Each figure is the median of five runs (smartcore's: one). The bench asserts that the
//! forest reproduces its own strokes (≥ 95 % of stroke pixels).

use std::path::Path;
use std::time::Instant;
use topocontour::learn::{Classifier, FeatureSet, Features, ForestParams, Strokes};

/// CPU seconds of this process so far (user + system, every thread).
fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes the struct we pass and nothing else.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// Median (CPU, wall) seconds of `runs` calls of `f`, and its last result.
fn timed<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let mut cpu = Vec::new();
    let mut wall = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let (c, w) = (cpu_seconds(), Instant::now());
        last = Some(std::hint::black_box(f()));
        cpu.push(cpu_seconds() - c);
        wall.push(w.elapsed().as_secs_f64());
    }
    cpu.sort_by(f64::total_cmp);
    wall.sort_by(f64::total_cmp);
    (cpu[runs / 2], wall[runs / 2], last.expect("runs ≥ 1"))
}

/// FNV-1a of the values' bits: equal digests, identical results (byte for byte).
fn digest<'a>(values: impl IntoIterator<Item = &'a f32>) -> u64 {
    values.into_iter().fold(0xcbf2_9ce4_8422_2325, |h, v| {
        (h ^ v.to_bits() as u64).wrapping_mul(0x0100_0000_01b3)
    })
}

fn smartcore_predict(features: &Features, strokes: &Strokes, p: &ForestParams) -> (f64, f64) {
    use smartcore::ensemble::random_forest_classifier::{
        RandomForestClassifier, RandomForestClassifierParameters,
    };
    use smartcore::linalg::basic::matrix::DenseMatrix;
    let nf = features.planes.len();
    let n = features.width * features.height;
    let (mut x, mut y) = (Vec::new(), Vec::new());
    for (i, &l) in strokes.labels.iter().enumerate() {
        if l > 0 {
            x.extend(features.planes.iter().map(|pl| pl[i] as f64));
            y.push(l as u32);
        }
    }
    let x = DenseMatrix::new(y.len(), nf, x, false).expect("shape");
    let params = RandomForestClassifierParameters::default()
        .with_n_trees(p.trees as u16)
        .with_max_depth(p.max_depth as u16)
        .with_seed(p.seed);
    let forest = RandomForestClassifier::fit(&x, &y, params).expect("fit");
    let all: Vec<f64> = (0..n)
        .flat_map(|i| features.planes.iter().map(move |pl| pl[i] as f64))
        .collect();
    let all = DenseMatrix::new(n, nf, all, false).expect("shape");
    let (c, w, labels) = timed(1, || forest.predict(&all).expect("predict"));
    std::hint::black_box(labels);
    (c, w)
}

fn bench_one(name: &str, width: usize, height: usize, image: &[f32], strokes: &Strokes) {
    let set = FeatureSet::default();
    let direct = FeatureSet {
        pyramid: false,
        ..FeatureSet::default()
    };
    let p = ForestParams::default();
    let (fc, fw, features) = timed(5, || set.compute(width, height, image));
    let (dc, dw, _) = timed(5, || direct.compute(width, height, image));
    let (tc, tw, clf) = timed(5, || Classifier::train(&features, strokes, &p));
    let (pc, pw, prob) = timed(5, || clf.predict(&features));
    let best = prob.argmax();
    let (mut hit, mut total) = (0usize, 0usize);
    for (i, &l) in strokes.labels.iter().enumerate() {
        if l > 0 {
            total += 1;
            hit += (best[i] == l) as usize;
        }
    }
    assert!(
        hit * 100 >= 95 * total,
        "{name}: {hit}/{total} stroke pixels"
    );
    let labelled = total as f64 / (width * height) as f64;
    let scale = (512.0 * 512.0) / (width * height) as f64;
    println!(
        "{name} {width}x{height}, {} features, {total} stroke px ({:.2} %)",
        features.planes.len(),
        100.0 * labelled
    );
    println!("  features (pyramid)   cpu {fc:.3} s  wall {fw:.3} s");
    println!("  features (direct)    cpu {dc:.3} s  wall {dw:.3} s");
    println!(
        "  train ({} trees)     cpu {tc:.3} s  wall {tw:.3} s",
        p.trees
    );
    println!("  predict              cpu {pc:.3} s  wall {pw:.3} s");
    println!(
        "  digests: features {:016x}, probabilities {:016x}",
        digest(features.planes.iter().flatten()),
        digest(&prob.data)
    );
    println!(
        "  per 512²: features + predict cpu {:.3} s, wall {:.3} s",
        (fc + pc) * scale,
        (fw + pw) * scale
    );
    if std::env::var_os("LEARN_BENCH_SMARTCORE").is_some() {
        let (sc, sw) = smartcore_predict(&features, strokes, &p);
        println!("  smartcore 0.7 predict cpu {sc:.3} s  wall {sw:.3} s (labels only)");
    }
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    if args.is_empty() {
        let (w, h) = (512, 512);
        let (image, labels) = topocontour::check::touching_rods(w, h, 40, 10);
        let s = topocontour::check::strokes_for(&labels, w, h, 8, true);
        let strokes = Strokes::new(w, h, s).expect("strokes");
        bench_one("rods", w, h, &image, &strokes);
        return;
    }
    for pair in args.chunks(2) {
        let [img, st] = pair else {
            panic!("give IMAGE STROKES pairs");
        };
        let image = topocontour::io::load_image(Path::new(img)).expect("image");
        let strokes = Strokes::read(Path::new(st), image.width, image.height).expect("strokes");
        let name = Path::new(img)
            .parent()
            .and_then(|p| p.file_name())
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        bench_one(&name, image.width, image.height, &image.data, &strokes);
    }
}
