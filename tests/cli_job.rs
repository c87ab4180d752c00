//! One pipeline for every front end (issue 23): seeds found per image in a folder, sessions
//! that survive a move, labels numbered as the CSV ids, a clean `--help`, the summary
//! line. Each test makes its own small images.

mod common;

use common::{bin, disks_png, read_json, run_ok, s};
use std::path::PathBuf;

fn workdir(name: &str) -> common::Scratch {
    common::workdir("job", name)
}

/// Centroids of the outer contours of a segment JSON.
fn outer_centroids(doc: &serde_json::Value) -> Vec<(f64, f64)> {
    doc["contours"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["hole"] == false)
        .map(|c| {
            let pts = c["points"].as_array().unwrap();
            let n = pts.len() as f64;
            let sx: f64 = pts.iter().map(|p| p[0].as_f64().unwrap()).sum();
            let sy: f64 = pts.iter().map(|p| p[1].as_f64().unwrap()).sum();
            (sx / n, sy / n)
        })
        .collect()
}

/// Two images of different sizes in one folder with automatic seeds: each gets the seeds
/// found in it, so the wide image's objects right of the narrow one's edge are found.
#[test]
fn batch_finds_seeds_per_image() {
    let d = workdir("per-image");
    let input = d.join("in");
    std::fs::create_dir_all(&input).unwrap();
    disks_png(&input.join("a_narrow.png"), 96, 96, &[(30.0, 48.0, 12.0)]);
    let wide = [(30.0, 48.0, 12.0), (150.0, 48.0, 12.0), (230.0, 40.0, 10.0)];
    disks_png(&input.join("b_wide.png"), 260, 96, &wide);
    let out = d.join("out");
    run_ok(bin().args([
        "batch",
        s(&input),
        "--out",
        s(&out),
        "--auto-seeds",
        "--object",
        "dark",
        "--jobs",
        "1",
    ]));
    let found = outer_centroids(&read_json(&out.join("b_wide.json")));
    assert_eq!(found.len(), 3, "{found:?}");
    for (x, y, _) in wide {
        assert!(
            found.iter().any(|c| (c.0 - x).hypot(c.1 - y) < 3.0),
            "no object at {x},{y}: {found:?}"
        );
    }
    assert_eq!(
        outer_centroids(&read_json(&out.join("a_narrow.json"))).len(),
        1
    );
}

/// The folder job of the library (the app's "Apply to folder…") is a job template: with
/// automatic seeds it finds them in each image, not once for all.
#[test]
fn folder_job_finds_seeds_per_image() {
    use topocontour::evolution::{Params, Polarity};
    use topocontour::io::folder::FolderJob;
    use topocontour::job::Job;
    let d = workdir("folder-job");
    let (narrow, wide) = (d.join("narrow.png"), d.join("wide.png"));
    disks_png(&narrow, 96, 96, &[(30.0, 48.0, 12.0)]);
    disks_png(&wide, 260, 96, &[(30.0, 48.0, 12.0), (200.0, 48.0, 12.0)]);
    let params = Params {
        polarity: Polarity::Dark,
        ..Params::default()
    };
    let job = FolderJob {
        job: Job {
            auto_seeds: true,
            ..Job::new(PathBuf::new(), Vec::new(), params)
        },
        out: d.to_path_buf(),
    };
    assert_eq!(job.run_one(&narrow).unwrap().len(), 1);
    assert_eq!(
        job.run_one(&wide).unwrap().len(),
        2,
        "both objects of the wide image"
    );
}

/// A folder of an image and its session moves as a whole and still replays; an image
/// moved elsewhere is found with `--image`, and a different image is still refused.
#[test]
fn a_session_in_a_moved_folder_replays() {
    let d = workdir("moved");
    let before = d.join("before");
    std::fs::create_dir_all(before.join("images")).unwrap();
    std::fs::create_dir_all(before.join("sessions")).unwrap();
    let img = before.join("images/cells.png");
    disks_png(&img, 80, 64, &[(25.0, 30.0, 10.0), (55.0, 34.0, 9.0)]);
    let session = before.join("sessions/cells.session");
    let (a, b, c) = (d.join("a.json"), d.join("b.json"), d.join("c.json"));
    run_ok(bin().args([
        "segment",
        s(&img),
        "--auto-seeds",
        "--object",
        "dark",
        "--json",
        s(&a),
        "--save-session",
        s(&session),
    ]));
    let stored = read_json(&session)["image"]["path"]
        .as_str()
        .unwrap()
        .to_string();
    assert_eq!(
        stored, "../images/cells.png",
        "relative to the session's folder"
    );
    let after = d.join("after");
    std::fs::rename(&before, &after).unwrap();
    let session = after.join("sessions/cells.session");
    run_ok(bin().args(["replay", s(&session), "--json", s(&b)]));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    // The image moves away from the session: --image points at it.
    let elsewhere = d.join("cells-moved.png");
    std::fs::rename(after.join("images/cells.png"), &elsewhere).unwrap();
    let out = bin().args(["replay", s(&session)]).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    run_ok(bin().args([
        "replay",
        s(&session),
        "--image",
        s(&elsewhere),
        "--json",
        s(&c),
    ]));
    let (mut want, got) = (read_json(&a), read_json(&c));
    want["image"] = "cells-moved.png".into();
    assert_eq!(want, got, "the same run on the image under its new name");
    // Another image under that name: refused.
    disks_png(&elsewhere, 80, 64, &[(25.0, 30.0, 11.0)]);
    let out = bin()
        .args(["replay", s(&session), "--image", s(&elsewhere)])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("changed"));
}

/// The label image's values are the CSV's ids: a table measured on the labels joins the
/// CSV row by row (area and centroid of each label's pixels against its row), also when
/// the run merged contours (adaptive mode, ids no longer consecutive).
#[test]
fn labels_join_the_csv_by_id() {
    let d = workdir("labels");
    let img = d.join("img.png");
    // Two disks that touch merge (with a third seed between them); three stay apart.
    // The first seed (contour 0) stays alone: its label must be its CSV id.
    let disks = [
        (80.0, 24.0, 10.0),
        (20.0, 20.0, 9.0),
        (36.0, 20.0, 9.0),
        (30.0, 60.0, 11.0),
        (85.0, 64.0, 8.0),
    ];
    disks_png(&img, 110, 84, &disks);
    let (csv, labels) = (d.join("o.csv"), d.join("o.labels.png"));
    let mut args = vec!["segment".to_string(), s(&img).into()];
    for (x, y, _) in disks {
        args.extend(["--seed".into(), format!("{x},{y},4")]);
    }
    args.extend(["--seed".into(), "28,20,3".into()]);
    args.extend(["--object", "dark", "--csv", s(&csv), "--labels", s(&labels)].map(String::from));
    run_ok(bin().args(&args));
    let lab = image::open(&labels).unwrap().to_luma16();
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 4, "{text}");
    let contours: Vec<&str> = rows.iter().map(|r| r[12]).collect();
    assert_ne!(
        contours,
        ["0", "1", "2", "3"],
        "the merge left a gap in contour ids"
    );
    for r in &rows {
        let id: u16 = r[1].parse().unwrap();
        let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for (x, y, p) in lab.enumerate_pixels() {
            if p.0[0] == id {
                n += 1.0;
                sx += x as f64 + 0.5;
                sy += y as f64 + 0.5;
            }
        }
        let area: f64 = r[2].parse().unwrap();
        let (cx, cy): (f64, f64) = (r[5].parse().unwrap(), r[6].parse().unwrap());
        assert!(
            (n - area).abs() < 0.05 * area + 8.0,
            "label {id}: {n} px vs {area}"
        );
        assert!(
            (sx / n - cx).hypot(sy / n - cy) < 1.0,
            "label {id} centroid"
        );
    }
}

/// `--help` of every subcommand speaks the user's language: no internal paper numbers,
/// no rustdoc link syntax.
#[test]
fn help_is_clean() {
    for sub in [&[][..], &["segment"], &["replay"], &["batch"], &["bench"]] {
        for flag in ["-h", "--help"] {
            let out = run_ok(bin().args(sub).arg(flag));
            let text = String::from_utf8_lossy(&out.stdout);
            for bad in ["seed 00", "[`", "`]", "super::", "crate::"] {
                assert!(!text.contains(bad), "{sub:?} {flag}: {bad:?} in\n{text}");
            }
        }
    }
}

/// A successful run ends with one line on stderr saying what it found and wrote; the
/// calibrated CSV columns are plain decimals.
#[test]
fn success_prints_one_summary_line_and_plain_decimals() {
    let d = workdir("summary");
    let img = d.join("img.png");
    disks_png(&img, 64, 64, &[(32.0, 32.0, 12.0)]);
    let csv = d.join("o.csv");
    let out = run_ok(bin().args([
        "segment",
        s(&img),
        "--wrap",
        "4",
        "--object",
        "dark",
        "--csv",
        s(&csv),
        "--pixel-size",
        "0.0001",
        "--unit",
        "mm",
    ]));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("img.png: 1 object") && err.contains("o.csv"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
    let text = std::fs::read_to_string(&csv).unwrap();
    let row: Vec<&str> = text.lines().nth(1).unwrap().split(',').collect();
    for cell in &row[10..12] {
        assert!(!cell.contains('e') && !cell.is_empty(), "{cell} in {row:?}");
        assert!(cell.parse::<f64>().unwrap() > 0.0);
    }
}

/// `batch` says what it did once its progress bar is gone.
#[test]
fn batch_prints_a_summary() {
    let d = workdir("batch-summary");
    let input = d.join("in");
    std::fs::create_dir_all(&input).unwrap();
    disks_png(&input.join("one.png"), 64, 64, &[(32.0, 32.0, 12.0)]);
    disks_png(
        &input.join("two.png"),
        64,
        64,
        &[(20.0, 20.0, 8.0), (44.0, 44.0, 8.0)],
    );
    let out = run_ok(bin().args([
        "batch",
        s(&input),
        "--out",
        s(&d.join("out")),
        "--wrap",
        "3",
        "--object",
        "dark",
    ]));
    let err = String::from_utf8_lossy(&out.stderr);
    let last = err.lines().last().unwrap_or_default();
    assert!(last.contains("2 images segmented, 3 objects"), "{err}");
}
