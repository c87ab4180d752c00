//! The map in two parts (preview, then the rest): together byte for byte the map
//! `Classifier::predict` makes, the preview its values at even x and y, and a stop
//! asked for gives no map. Odd and even sizes, so the last column and row count.

use topocontour::check::Rng;
use topocontour::learn::{Classifier, FeatureSet, ForestParams, Strokes};

fn taught(w: usize, h: usize) -> (Classifier, topocontour::learn::Features) {
    let mut rng = Rng(5);
    let img: Vec<f32> = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32, (i / w) as f32);
            let disk = ((x - w as f32 / 3.0).powi(2) + (y - h as f32 / 2.0).powi(2)).sqrt() < 9.0;
            (if disk { 0.8 } else { 0.2 }) + 0.1 * rng.unit() as f32
        })
        .collect();
    let mut s = vec![0u8; w * h];
    let (cx, cy) = (w / 3, h / 2);
    for d in 0..5 {
        s[cy * w + cx + d] = 2;
        s[2 * w + 2 + d] = 1;
        s[(cy + 9) * w + cx + d] = 3;
    }
    let strokes = Strokes::new(w, h, s).unwrap();
    let features = FeatureSet::default().compute(w, h, &img);
    let c = Classifier::train(&features, &strokes, &ForestParams::default());
    (c, features)
}

#[test]
fn preview_and_rest_make_the_map_predict_makes() {
    for (w, h) in [(40, 30), (41, 33)] {
        let (c, f) = taught(w, h);
        let full = c.predict(&f);
        let go = || false;
        let preview = c.predict_preview(&f, &go).expect("not stopped");
        assert_eq!(
            (preview.width, preview.height),
            (w.div_ceil(2), h.div_ceil(2))
        );
        let k = c.labels.len();
        for y in (0..h).step_by(2) {
            for x in (0..w).step_by(2) {
                let p = ((y / 2) * preview.width + x / 2) * k;
                assert_eq!(
                    preview.data[p..p + k],
                    full.data[(y * w + x) * k..(y * w + x + 1) * k],
                    "preview at ({x}, {y})"
                );
            }
        }
        let rest = c.predict_rest(&f, &preview, &go).expect("not stopped");
        assert_eq!(rest, full, "{w}x{h}");
    }
}

#[test]
fn a_stop_gives_no_map() {
    let (c, f) = taught(40, 30);
    let stop = || true;
    assert!(c.predict_preview(&f, &stop).is_none());
    let preview = c.predict_preview(&f, &|| false).unwrap();
    assert!(c.predict_rest(&f, &preview, &stop).is_none());
}
