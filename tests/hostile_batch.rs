//! Batch folders that must never lose an output or an input, and the CLI's resources
//! (issue 24: 3, 4, 10, 16, 17): each case asserts the exit code, one line on stderr, the
//! inputs byte-identical and no file left behind.
#![cfg(unix)]

mod common;

use common::{bin, disks_png, names, refused, run_ok, s};
use std::path::{Path, PathBuf};

/// A folder `in` holding one small image under each of `names`.
fn inputs(test: &str, names: &[&str]) -> (common::Scratch, PathBuf) {
    let d = common::workdir("batch", test);
    let input = d.join("in");
    std::fs::create_dir_all(&input).unwrap();
    for (k, n) in names.iter().enumerate() {
        let r = 6.0 + k as f64;
        disks_png(&input.join(n), 48, 48, &[(24.0, 24.0, r)]);
    }
    (d, input)
}

fn batch(input: &Path, out: &Path, formats: &str) -> std::process::Command {
    let mut c = bin();
    c.args(["batch", s(input), "--out", s(out), "--wrap", "3"])
        .args(["--object", "dark", "--formats", formats]);
    c
}

/// Issue 24.3: images whose stems collide get their whole file name as stem; the summary
/// names each by its file name; `summary.png` keeps its own CSV apart from summary.csv.
#[test]
fn colliding_stems_get_unique_outputs() {
    let (d, input) = inputs("stems", &["a.png", "a.tif", "summary.png"]);
    let out = d.join("out");
    run_ok(&mut batch(&input, &out, "json,csv"));
    assert_eq!(
        names(&out),
        [
            "a.png.csv",
            "a.png.json",
            "a.tif.csv",
            "a.tif.json",
            "summary.csv",
            "summary.png.csv",
            "summary.png.json"
        ]
    );
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    for name in ["a.png", "a.tif", "summary.png"] {
        let rows = summary
            .lines()
            .filter(|l| l.starts_with(&format!("\"{name}\",")));
        assert_eq!(rows.count(), 1, "{name} in\n{summary}");
    }
    let own = common::read_json(&out.join("a.tif.json"));
    assert_eq!(own["image"], "a.tif");
}

/// Issue 24.3: names that differ only in case are refused up front (many file systems
/// would make them one output), before any output exists.
#[test]
fn names_equal_but_for_case_are_refused() {
    let (d, input) = inputs("case", &["a.png", "a.PNG"]);
    let out = d.join("out");
    refused(&mut batch(&input, &out, "json"), "a.PNG and a.png");
    assert!(!out.exists() || names(&out).is_empty());
}

/// Issue 24.4: `--out` = the input folder is refused when an output is an image (the
/// next run would segment it); with only JSON it is fine and touches no input.
#[test]
fn out_in_the_input_folder_never_feeds_back() {
    let (_dir, input) = inputs("feedback", &["x.png", "y.png"]);
    let before: Vec<Vec<u8>> = ["x.png", "y.png"]
        .iter()
        .map(|n| std::fs::read(input.join(n)).unwrap())
        .collect();
    refused(&mut batch(&input, &input, "json,mask"), "input folder");
    assert_eq!(names(&input), ["x.png", "y.png"]);
    run_ok(&mut batch(&input, &input, "json"));
    assert_eq!(
        names(&input),
        ["summary.csv", "x.json", "x.png", "y.json", "y.png"]
    );
    for (n, b) in ["x.png", "y.png"].iter().zip(&before) {
        assert_eq!(&std::fs::read(input.join(n)).unwrap(), b, "{n}");
    }
}

/// Issue 24.17: a format named twice is one refusal, not one error per image.
#[test]
fn a_format_named_twice_is_one_refusal() {
    let (d, input) = inputs("twice", &["a.png", "b.png", "c.png"]);
    let out = d.join("out");
    refused(&mut batch(&input, &out, "json,json"), "json twice");
    assert!(!out.exists());
}

/// `--out` naming a file or a device is refused as not a folder (it said "File exists").
#[test]
fn out_that_is_not_a_folder_is_refused_as_such() {
    let (d, input) = inputs("notdir", &["a.png"]);
    let file = d.join("file");
    std::fs::write(&file, b"keep").unwrap();
    for out in [file.as_path(), Path::new("/dev/null")] {
        refused(&mut batch(&input, out, "json"), "not a folder");
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"keep");
}

/// `--out` is made if missing, but not a tree of folders: a mistyped path is refused.
#[test]
fn out_in_a_missing_folder_is_refused() {
    let (d, input) = inputs("tree", &["a.png"]);
    let out = d.join("missing").join("out");
    refused(&mut batch(&input, &out, "json"), "missing does not exist");
    assert!(!d.join("missing").exists());
}

/// `--out` naming a symbolic link to nothing says so (it said "File exists").
#[test]
fn out_that_is_a_dangling_link_is_refused_as_such() {
    let (d, input) = inputs("dangling", &["a.png"]);
    let link = d.join("link");
    std::os::unix::fs::symlink(d.join("nowhere"), &link).unwrap();
    refused(
        &mut batch(&input, &link, "json"),
        "a symbolic link to nothing",
    );
    assert!(!d.join("nowhere").exists());
}

/// Issue 24.10: `--jobs 100000` runs at most one thread per core (it used to spawn
/// threads without end).
#[test]
fn jobs_are_capped_at_the_cores() {
    let (d, input) = inputs("jobs", &["a.png"]);
    let mut c = batch(&input, &d.join("out"), "json");
    c.args(["--jobs", "100000"]);
    let out = common::run_within(&mut c, std::time::Duration::from_secs(10));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Issue 24.16: `bench > /dev/full` fails with one line (it used to exit 0).
#[test]
fn bench_to_a_full_disk_fails() {
    let case = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cases/blobs_wrap");
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = bin()
        .args(["bench", s(&case), "--runs", "1"])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("cannot write the table"), "{err}");
}
