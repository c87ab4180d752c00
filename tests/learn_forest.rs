//! Our random forest against smartcore's, grown alike (the default trees and depth, √F
//! features per split, bootstrap) on the same data: the predicted classes agree, both learn the
//! rule, and ours is deterministic in its seed.

use smartcore::ensemble::random_forest_classifier::{
    RandomForestClassifier, RandomForestClassifierParameters,
};
use smartcore::linalg::basic::matrix::DenseMatrix;
use topocontour::check::Rng;
use topocontour::learn::{Forest, ForestParams};

const NF: usize = 6;

/// `n` samples of NF features in [−1, 1]: class 0 inside a disc in (x0, x1), else 1 or 2
/// by the sign of x2 − 0.3; x3..x5 are noise; 5 % of the labels are flipped.
fn data(n: usize, seed: u64, noisy: bool) -> (Vec<f32>, Vec<u8>) {
    let mut rng = Rng(seed);
    let mut x = Vec::with_capacity(n * NF);
    let mut y = Vec::with_capacity(n);
    for _ in 0..n {
        let v: Vec<f32> = (0..NF).map(|_| rng.range(-1.0, 1.0) as f32).collect();
        let mut c = if v[0] * v[0] + v[1] * v[1] < 0.5 {
            0
        } else if v[2] > 0.3 {
            1
        } else {
            2
        };
        if noisy && rng.unit() < 0.05 {
            c = rng.below(3) as u8;
        }
        x.extend(v);
        y.push(c);
    }
    (x, y)
}

fn argmax(p: &[f32]) -> u8 {
    (0..p.len()).fold(0, |b, k| if p[k] > p[b] { k } else { b }) as u8
}

#[test]
fn predictions_agree_with_smartcore() {
    let (x, y) = data(2000, 1, true);
    let (tx, ty) = data(5000, 2, false);
    let p = ForestParams::default();
    let ours = Forest::train(&x, &y, NF, 3, &p);
    let dm = |x: &[f32], n: usize| {
        DenseMatrix::new(n, NF, x.iter().map(|&v| v as f64).collect(), false).unwrap()
    };
    let labels: Vec<u32> = y.iter().map(|&c| c as u32).collect();
    let params = RandomForestClassifierParameters::default()
        .with_n_trees(p.trees as u16)
        .with_max_depth(p.max_depth as u16)
        .with_seed(0);
    let theirs = RandomForestClassifier::fit(&dm(&x, 2000), &labels, params).unwrap();
    let their_labels: Vec<u32> = theirs.predict(&dm(&tx, 5000)).unwrap();
    let (mut agree, mut ours_right, mut theirs_right) = (0, 0, 0);
    for i in 0..5000 {
        let mine = argmax(&ours.predict_one(&tx[i * NF..(i + 1) * NF]));
        agree += (mine as u32 == their_labels[i]) as usize;
        ours_right += (mine == ty[i]) as usize;
        theirs_right += (their_labels[i] == ty[i] as u32) as usize;
    }
    let share = |k: usize| k as f64 / 5000.0;
    eprintln!(
        "agreement {:.3}, accuracy ours {:.3}, smartcore {:.3}",
        share(agree),
        share(ours_right),
        share(theirs_right)
    );
    assert!(share(agree) >= 0.95, "agreement {}", share(agree));
    assert!(share(ours_right) >= 0.93, "ours {}", share(ours_right));
    assert!(share(ours_right) >= share(theirs_right) - 0.01);
}

#[test]
fn probabilities_are_distributions() {
    let (x, y) = data(500, 3, true);
    let f = Forest::train(&x, &y, NF, 3, &ForestParams::default());
    let (tx, _) = data(200, 4, false);
    for s in tx.chunks(NF) {
        let p = f.predict_one(s);
        assert!(p.iter().all(|&v| (0.0..=1.0).contains(&v)));
        assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-4);
    }
}

#[test]
fn the_seed_decides_the_forest() {
    let (x, y) = data(800, 5, true);
    let p = ForestParams::default();
    let a = Forest::train(&x, &y, NF, 3, &p);
    let b = Forest::train(&x, &y, NF, 3, &p);
    assert_eq!(a, b);
    let c = Forest::train(&x, &y, NF, 3, &ForestParams { seed: 9, ..p });
    assert_ne!(a, c);
}

/// The walk indexes without bounds checks: a node that no walk reaches may hold any
/// index (a damaged file `misfit` passes, since it only follows the walks), and the
/// prediction is still the reachable leaves' distribution, with no panic.
#[test]
fn an_unreachable_damaged_node_changes_nothing() {
    use topocontour::learn::forest::Node;
    let leaf = |at: u32| Node {
        feature: 0,
        threshold: 0.0,
        left: at,
        right: at,
    };
    let forest = Forest {
        classes: 2,
        features: 1,
        nodes: vec![
            Node {
                feature: 0,
                threshold: 0.5,
                left: 1,
                right: 2,
            },
            leaf(1),
            leaf(2),
            // Unreachable: children, feature and distribution all out of range.
            Node {
                feature: 7,
                threshold: 0.0,
                left: 99,
                right: 3,
            },
            leaf(4),
        ],
        roots: vec![(0, 1)],
        leaf_of: vec![u32::MAX, 0, 2, u32::MAX, 1000],
        leaf_values: vec![0.25, 0.75, 1.0, 0.0],
    };
    assert_eq!(forest.misfit(1, 2), None);
    assert_eq!(forest.predict_one(&[0.0]), vec![0.25, 0.75]);
    assert_eq!(forest.predict_one(&[1.0]), vec![1.0, 0.0]);
    assert_eq!(forest.predict_one(&[f32::NAN]), vec![1.0, 0.0]);
}
