//! What a taught run keeps: classifier files (`--save-classifier`, `--classifier`,
//! `train`, `batch --classifier`) that round-trip and are refused when they do not fit,
//! sessions that replay a run taught by strokes byte for byte, and the in-memory
//! teaching of a `Job`.

mod common;

use common::{bin, refused, run_ok, s, workdir};
use std::path::{Path, PathBuf};
use topocontour::check::{strokes_for, touching_rods};
use topocontour::evolution::{Mode, Params, Polarity};
use topocontour::io::classifier;
use topocontour::job::Job;
use topocontour::learn::{Strokes, Teach};

const W: usize = 160;
const H: usize = 120;

fn write_gray(path: &Path, w: usize, h: usize, data: Vec<u8>) {
    image::GrayImage::from_raw(w as u32, h as u32, data)
        .unwrap()
        .save(path)
        .unwrap();
}

/// A rods image and its strokes (with boundary strokes) in `dir`, `w` × `h`.
fn rods(dir: &Path, name: &str, w: usize, h: usize) -> (PathBuf, PathBuf) {
    let (img, labels) = touching_rods(w, h, 24, 8);
    let image = dir.join(format!("{name}.png"));
    let bytes = img
        .iter()
        .map(|v| (v * 255.0).round().clamp(0.0, 255.0) as u8);
    write_gray(&image, w, h, bytes.collect());
    let strokes = dir.join(format!("{name}-strokes.png"));
    write_gray(&strokes, w, h, strokes_for(&labels, w, h, 8, true));
    (image, strokes)
}

const RUN: [&str; 5] = ["--object", "dark", "--auto-seeds", "--mode", "preserve"];

#[test]
fn a_classifier_file_round_trips() {
    let dir = workdir("learn-files", "round");
    let (image, strokes) = rods(&dir, "rods", W, H);
    let (clf, a, b) = (dir.join("c.json"), dir.join("a.json"), dir.join("b.json"));
    run_ok(bin().args(["segment", s(&image)]).args(RUN).args([
        "--train",
        s(&strokes),
        "--save-classifier",
        s(&clf),
        "--json",
        s(&a),
    ]));
    let read = classifier::read(&clf).unwrap();
    assert_eq!(read.images, ["rods.png"]);
    assert_eq!(read.labels, [1, 2, 3]);
    assert_eq!(classifier::to_bytes(&read), std::fs::read(&clf).unwrap());
    run_ok(bin().args(["segment", s(&image)]).args(RUN).args([
        "--classifier",
        s(&clf),
        "--json",
        s(&b),
    ]));
    assert_eq!(
        std::fs::read(&a).unwrap(),
        std::fs::read(&b).unwrap(),
        "the saved classifier gives the run it was trained in"
    );
    // --save-classifier with nothing that teaches.
    refused(
        bin()
            .args(["segment", s(&image)])
            .args(RUN)
            .args(["--save-classifier", s(&b)]),
        "--save-classifier saves what --train",
    );
}

/// `text` of a classifier file with `from` replaced by `to` (once, and it must occur).
fn edited(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from} in the file");
    text.replacen(from, to, 1)
}

#[test]
fn a_mismatched_classifier_is_refused() {
    let dir = workdir("learn-files", "mismatch");
    let (image, strokes) = rods(&dir, "rods", W, H);
    let clf = dir.join("c.json");
    run_ok(bin().args(["train", s(&image), s(&strokes), "--out", s(&clf)]));
    let text = std::fs::read_to_string(&clf).unwrap();
    let cases = [
        (
            "\"feature_version\":1",
            "\"feature_version\":7",
            "features of version 7",
        ),
        (
            "\"channels\":1",
            "\"channels\":3",
            "trained on 3-channel images",
        ),
        (
            "\"version\":1",
            "\"version\":2",
            "expected topocontour-classifier version 1",
        ),
        ("\"labels\":[1,2,3]", "\"labels\":[1,3,3]", "its classes"),
        (
            "\"channels\":1",
            "\"channels\":1,\"colour\":true",
            "unknown field `colour`",
        ),
        (
            "\"nodes\":[{\"feature\":",
            "\"nodes\":[{\"feature\":49000",
            "damaged",
        ),
        (
            "\"format\":\"topocontour-classifier\"",
            "\"format\":\"x\"",
            "format x",
        ),
    ];
    for (k, (from, to, needle)) in cases.iter().enumerate() {
        let bad = dir.join(format!("bad{k}.json"));
        std::fs::write(&bad, edited(&text, from, to)).unwrap();
        let line = refused(
            bin()
                .args(["segment", s(&image)])
                .args(RUN)
                .args(["--classifier", s(&bad)]),
            needle,
        );
        assert!(line.contains(s(&bad)), "{line}");
    }
    let junk = dir.join("junk.json");
    std::fs::write(&junk, "not json").unwrap();
    refused(
        bin()
            .args(["segment", s(&image)])
            .args(RUN)
            .args(["--classifier", s(&junk)]),
        "not a topocontour classifier",
    );
    refused(
        bin().args(["segment", s(&image)]).args(RUN).args([
            "--train",
            s(&strokes),
            "--classifier",
            s(&clf),
        ]),
        "cannot be used with",
    );
}

#[test]
fn batch_applies_one_classifier_to_a_folder() {
    let dir = workdir("learn-files", "batch");
    let (train_dir, input, out) = (dir.join("train"), dir.join("in"), dir.join("out"));
    for d in [&train_dir, &input] {
        std::fs::create_dir_all(d).unwrap();
    }
    let (image, strokes) = rods(&train_dir, "rods", W, H);
    let clf = dir.join("c.json");
    run_ok(bin().args(["train", s(&image), s(&strokes), "--out", s(&clf)]));
    // Held-out images of the family: other sizes, so other rods (never trained on).
    rods(&input, "wide", 200, 120);
    rods(&input, "tall", 160, 150);
    std::fs::remove_file(input.join("wide-strokes.png")).unwrap();
    std::fs::remove_file(input.join("tall-strokes.png")).unwrap();
    run_ok(
        bin()
            .args(["batch", s(&input), "--out", s(&out)])
            .args(RUN)
            .args(["--classifier", s(&clf)]),
    );
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    for name in ["wide.png", "tall.png"] {
        let quoted = format!("\"{name}\",");
        let objects = summary.lines().filter(|l| l.starts_with(&quoted)).count();
        assert!(objects >= 20, "{name}: {objects} objects\n{summary}");
    }
    refused(
        bin()
            .args(["batch", s(&input), "--out", s(&out)])
            .args(RUN)
            .args(["--train", s(&strokes)]),
        "--train strokes belong to one image",
    );
}

#[test]
fn train_takes_pairs_and_refuses_bad_ones() {
    let dir = workdir("learn-files", "train");
    let (a, sa) = rods(&dir, "a", W, H);
    let (b, sb) = rods(&dir, "b", 200, 100);
    let clf = dir.join("c.json");
    run_ok(bin().args(["train", s(&a), s(&sa), s(&b), s(&sb), "--out", s(&clf)]));
    assert_eq!(classifier::read(&clf).unwrap().images, ["a.png", "b.png"]);
    let other = dir.join("other.json");
    refused(
        bin().args(["train", s(&a), s(&sa), s(&b), "--out", s(&other)]),
        "is left without strokes",
    );
    refused(
        bin().args(["train", s(&a), s(&sb), "--out", s(&other)]),
        "the strokes are 200×100 but the image is 160×120",
    );
    let only_obj = dir.join("obj.png");
    write_gray(&only_obj, W, H, vec![2; W * H]);
    refused(
        bin().args(["train", s(&a), s(&only_obj), "--out", s(&other)]),
        "only one class",
    );
    assert!(!other.exists(), "nothing written on a refusal");
}

#[test]
fn a_session_taught_by_strokes_replays_identically() {
    let dir = workdir("learn-files", "session");
    let (image, strokes) = rods(&dir, "rods", W, H);
    let (session, a, b) = (dir.join("s.json"), dir.join("a.json"), dir.join("b.json"));
    run_ok(bin().args(["segment", s(&image)]).args(RUN).args([
        "--train",
        s(&strokes),
        "--save-session",
        s(&session),
        "--json",
        s(&a),
    ]));
    let text = std::fs::read_to_string(&session).unwrap();
    assert!(text.contains("\"runs\""), "strokes stored as runs");
    assert!(text.len() < 64 << 10, "{} bytes", text.len());
    run_ok(bin().args(["replay", s(&session), "--json", s(&b)]));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}

/// The strokes' runs read back as the strokes, on labels of every kind of run.
#[test]
fn stroke_runs_round_trip() {
    let (_, labels) = touching_rods(W, H, 24, 8);
    let mut raw = strokes_for(&labels, W, H, 8, true);
    raw[0] = 3; // a run at the first pixel
    *raw.last_mut().unwrap() = 1; // and at the last
    let st = Strokes::new(W, H, raw).unwrap();
    let text = serde_json::to_string(&st).unwrap();
    assert_eq!(serde_json::from_str::<Strokes>(&text).unwrap(), st);
    for bad in ["0 5 4", "0 0 2", "1 2", "19199 2 2", "0 9 2 x"] {
        let json = format!("{{\"width\":{W},\"height\":{H},\"runs\":\"{bad}\"}}");
        assert!(serde_json::from_str::<Strokes>(&json).is_err(), "{bad}");
    }
}

/// A job taught in memory by a classifier trained elsewhere gives the run its strokes
/// gave: no file in between.
#[test]
fn a_job_is_taught_in_memory() {
    let dir = workdir("learn-files", "memory");
    let (image, strokes) = rods(&dir, "rods", W, H);
    let params = Params {
        mode: Mode::Preserve,
        polarity: Polarity::Dark,
        ..Params::default()
    };
    let by_strokes = Job {
        auto_seeds: true,
        teach: Some(Teach::strokes(Strokes::read(&strokes, W, H).unwrap())),
        ..Job::new(&image, Vec::new(), params)
    };
    let first = by_strokes.run().unwrap();
    let taught = first.taught.as_ref().unwrap();
    let by_classifier = Job {
        teach: Some(Teach::Classifier(taught.classifier.clone())),
        ..by_strokes.clone()
    };
    let second = by_classifier.run().unwrap();
    assert_eq!(second.taught.unwrap().probabilities, taught.probabilities);
    assert_eq!(second.shapes, first.shapes);
    assert_eq!(
        format!("{:?}", second.ev.contours().contour_count()),
        format!("{:?}", first.ev.contours().contour_count())
    );
    let wrong = Strokes::new(4, 4, vec![1, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]).unwrap();
    let err = Job {
        teach: Some(Teach::strokes(wrong)),
        ..by_strokes
    }
    .run()
    .err()
    .unwrap();
    assert!(err.to_string().contains("the strokes are 4×4"), "{err}");
}
