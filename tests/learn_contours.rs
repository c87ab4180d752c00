//! Contours that follow a classifier trained from strokes: touching rods with no
//! intensity step between them (only a faint ridge) come apart, one object per rod,
//! when the user paints the boundary class — and not without it; bad strokes are
//! refused with one line.

mod common;

use common::{bin, refused, run_ok, s, workdir};
use std::path::Path;
use topocontour::check::{strokes_for, touching_rods};
use topocontour::contours::measure::regions;
use topocontour::evolution::{Mode, Params, Polarity, Shape};
use topocontour::geometry::Point;
use topocontour::job::Job;
use topocontour::learn::{Strokes, Teach};

const W: usize = 160;
const H: usize = 120;

fn write_gray(path: &Path, data: Vec<u8>) {
    image::GrayImage::from_raw(W as u32, H as u32, data)
        .unwrap()
        .save(path)
        .unwrap();
}

/// Rods with exactly one region whose centroid lies in them, of all rods, after an
/// instance run (seeds from the classifier, preserve mode) on strokes with or without
/// the boundary class.
fn rods_found(boundary: bool, name: &str) -> (usize, usize) {
    rods_found_by(boundary, name, Mode::Preserve, None)
}

/// [`rods_found`] in `mode`, from a wrap `margin` px inside the border (none: the
/// classifier's seeds).
fn rods_found_by(boundary: bool, name: &str, mode: Mode, wrap: Option<f64>) -> (usize, usize) {
    let dir = workdir("learn", name);
    let (img, labels) = touching_rods(W, H, 24, 8);
    let image = dir.join("rods.png");
    write_gray(
        &image,
        img.iter()
            .map(|v| (v * 255.0).round().clamp(0.0, 255.0) as u8)
            .collect(),
    );
    let strokes = dir.join("strokes.png");
    write_gray(&strokes, strokes_for(&labels, W, H, 8, boundary));
    let params = Params {
        mode,
        polarity: Polarity::Dark,
        ..Params::default()
    };
    let shapes = wrap.map_or(Vec::new(), |m| {
        vec![Shape::Rect {
            min: Point::new(m, m),
            max: Point::new(W as f64 - m, H as f64 - m),
        }]
    });
    let job = Job {
        auto_seeds: wrap.is_none(),
        teach: Some(Teach::strokes(Strokes::read(&strokes, W, H).unwrap())),
        ..Job::new(&image, shapes, params)
    };
    let run = job.run().unwrap();
    let rods = labels.iter().copied().max().unwrap() as usize;
    let mut hits = vec![0usize; rods + 1];
    for r in regions(run.ev.contours()) {
        let (x, y) = (r.centroid.x as usize, r.centroid.y as usize);
        if x < W && y < H {
            hits[labels[y * W + x] as usize] += 1;
        }
    }
    let one = hits[1..].iter().filter(|&&k| k == 1).count();
    (one, rods)
}

#[test]
fn boundary_strokes_split_touching_rods() {
    let (with, rods) = rods_found(true, "with");
    let (without, _) = rods_found(false, "without");
    eprintln!("one object per rod: {with} of {rods} with boundary strokes, {without} without");
    assert!(with * 10 >= rods * 9, "{with} of {rods}");
    assert!(without * 2 <= rods, "{without} of {rods}");
}

/// A wrap taught with boundary strokes splits the colony into its rods: the wrap starts
/// from the classifier's objects (a front shrinking from the rectangle cannot follow
/// the boundary band between touching rods, and gave one object for the colony).
#[test]
fn a_taught_wrap_splits_touching_rods() {
    let (with, rods) = rods_found_by(true, "wrap", Mode::Adaptive, Some(2.0));
    eprintln!("one object per rod: {with} of {rods} from a wrap");
    assert!(with * 10 >= rods * 7, "{with} of {rods}");
}

#[test]
fn bad_strokes_get_one_line_and_exit_2() {
    let dir = workdir("learn", "bad");
    let (img, labels) = touching_rods(W, H, 24, 8);
    let image = dir.join("rods.png");
    write_gray(&image, img.iter().map(|v| (v * 255.0) as u8).collect());
    let run = |strokes: &Path, needle: &str| {
        refused(
            bin()
                .args(["segment", s(&image), "--wrap", "2", "--object", "dark"])
                .args(["--train", s(strokes)]),
            needle,
        );
    };
    let small = dir.join("small.png");
    image::GrayImage::from_raw(4, 4, vec![2; 16])
        .unwrap()
        .save(&small)
        .unwrap();
    run(&small, "the strokes are 4×4 but the image is 160×120");
    let only_bg = dir.join("bg.png");
    write_gray(&only_bg, vec![1; W * H]);
    run(&only_bg, "no object pixel");
    let only_obj = dir.join("obj.png");
    write_gray(
        &only_obj,
        labels.iter().map(|&l| if l > 0 { 2 } else { 0 }).collect(),
    );
    run(&only_obj, "only one class");
    let odd = dir.join("odd.png");
    write_gray(&odd, vec![9; W * H]);
    run(&odd, "the value 9");
    run(&dir.join("missing.png"), "cannot read the strokes");
}

/// A taught run with no `--mode` gets the engine that keeps objects apart
/// (`Mode::default_for`): from a wrap or from found seeds, every rod comes out alone, where
/// the adaptive engine merges some; a `--mode` given wins, and an untaught run stays
/// adaptive.
#[test]
fn a_taught_run_keeps_objects_apart_by_default() {
    let dir = workdir("learn", "default");
    let (img, labels) = touching_rods(W, H, 24, 8);
    let image = dir.join("rods.png");
    write_gray(
        &image,
        img.iter().map(|v| (v * 255.0).round() as u8).collect(),
    );
    let strokes = dir.join("strokes.png");
    write_gray(&strokes, strokes_for(&labels, W, H, 8, true));
    let rods = labels.iter().copied().max().unwrap() as usize;
    let run = |init: &[&str], extra: &[&str]| -> (String, usize) {
        let json = dir.join("o.json");
        run_ok(
            bin()
                .args(["segment", s(&image), "--object", "dark"])
                .args(init)
                .args(extra)
                .args(["--json", s(&json)]),
        );
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        let outer = doc["contours"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| !c["hole"].as_bool().unwrap())
            .count();
        (doc["mode"].as_str().unwrap().to_string(), outer)
    };
    let train = ["--train", s(&strokes)];
    for init in [&["--wrap", "2"][..], &["--auto-seeds"][..]] {
        let (mode, outer) = run(init, &train);
        eprintln!("{init:?}: {outer} objects for {rods} rods in mode {mode}");
        assert_eq!(mode, "track");
        assert!(
            outer * 10 >= rods * 9 && outer <= rods + 2,
            "{outer} of {rods}"
        );
    }
    let (mode, _) = run(
        &["--wrap", "2"],
        &[&train[..], &["--mode", "adaptive"]].concat(),
    );
    assert_eq!(mode, "adaptive");
    let (mode, _) = run(&["--wrap", "2"], &[]);
    assert_eq!(mode, "adaptive");
}
