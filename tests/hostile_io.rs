//! Inputs and outputs that must never hang the program, exhaust memory or destroy a file
//! (DESIGN's CLI contract): each case asserts the exit code, one line on stderr, the input
//! byte-identical afterwards, special files still special and no file left behind.
#![cfg(unix)]

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::{bin, run_within};

/// A fresh folder of this test's own, with a copy of a small case image as input.
fn workdir(name: &str) -> (common::Scratch, PathBuf) {
    let d = common::workdir("hostile", name);
    let input = d.join("input.png");
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cases/phase_cells/image.png"),
        &input,
    )
    .unwrap();
    (d, input)
}

/// Exit 2 with exactly one line on stderr that contains `needle`.
fn expect_refused(args: &[&str], needle: &str) {
    let out = run_within(bin().args(args), Duration::from_secs(5));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err:?}");
    assert!(err.to_lowercase().contains(needle), "{args:?}: {err}");
}

/// The files of `dir` other than `keep`.
fn others(dir: &Path, keep: &[&Path]) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !keep.contains(&p.as_path()))
        .collect()
}

/// `segment INPUT --wrap 4 --object dark` followed by `extra`.
fn wrapped<'a>(input: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["segment", input, "--wrap", "4", "--object", "dark"];
    v.extend_from_slice(extra);
    v
}

fn mkfifo(path: &Path) {
    let ok = Command::new("mkfifo").arg(path).status().unwrap().success();
    assert!(ok, "mkfifo {}", path.display());
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn a_fifo_as_input_is_refused_at_once() {
    let (d, _) = workdir("fifo-in");
    let fifo = d.join("image.png");
    mkfifo(&fifo);
    expect_refused(
        &["segment", s(&fifo), "--wrap", "4", "--object", "dark"],
        "not a regular file",
    );
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
}

#[test]
fn a_device_as_input_is_refused_at_once() {
    expect_refused(
        &["segment", "/dev/zero", "--wrap", "4", "--object", "dark"],
        "not a regular file",
    );
}

#[test]
fn an_output_naming_the_input_is_refused_before_anything_is_written() {
    let (d, input) = workdir("out-is-in");
    let before = std::fs::read(&input).unwrap();
    let sub = d.join("sub");
    std::fs::create_dir(&sub).unwrap();
    let link = d.join("link.png");
    std::os::unix::fs::symlink(&input, &link).unwrap();
    let hard = d.join("hard.png");
    std::fs::hard_link(&input, &hard).unwrap();
    let dotdot = sub.join("../input.png");
    for (flag, out) in [
        ("--json", input.clone()),
        ("--mask", dotdot),
        ("--svg", link.clone()),
        ("--csv", hard.clone()),
    ] {
        expect_refused(&wrapped(s(&input), &[flag, s(&out)]), "input image");
        assert_eq!(
            std::fs::read(&input).unwrap(),
            before,
            "{flag} {}",
            out.display()
        );
    }
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(
        others(&d, &[&input, &sub, &link, &hard]),
        Vec::<PathBuf>::new()
    );
}

#[test]
fn one_path_for_two_outputs_is_refused() {
    let (d, input) = workdir("twice");
    let out = d.join("out");
    expect_refused(
        &wrapped(s(&input), &["--json", s(&out), "--svg", s(&out)]),
        "two outputs",
    );
    // The same file spelled two ways.
    let other = d.join(".").join("out");
    expect_refused(
        &wrapped(s(&input), &["--json", s(&out), "--csv", s(&other)]),
        "two outputs",
    );
    assert_eq!(others(&d, &[&input]), Vec::<PathBuf>::new());
}

#[test]
fn an_image_output_named_in_another_format_is_refused_and_a_tif_mask_is_tiff() {
    let (d, input) = workdir("extension");
    let jpg = d.join("labels.jpg");
    expect_refused(
        &wrapped(s(&input), &["--labels", s(&jpg)]),
        "written as png or tiff, not .jpg",
    );
    expect_refused(
        &wrapped(s(&input), &["--overlay", s(&d.join("o.tif"))]),
        "written as png",
    );
    assert_eq!(others(&d, &[&input]), Vec::<PathBuf>::new());
    let mask = d.join("mask.tif");
    let out = run_within(
        bin().args(wrapped(s(&input), &["--mask", s(&mask)])),
        Duration::from_secs(60),
    );
    assert!(out.status.success(), "{out:?}");
    let read = image::open(&mask).unwrap();
    assert_eq!(
        image::ImageFormat::from_path(&mask).unwrap(),
        image::ImageFormat::Tiff
    );
    assert!(read.to_luma8().pixels().any(|p| p.0[0] == 255));
    let bytes = std::fs::read(&mask).unwrap();
    assert!(
        bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*"),
        "TIFF bytes"
    );
}

#[test]
fn special_files_as_outputs_stay_special() {
    let (d, input) = workdir("special-out");
    let fifo = d.join("out.json");
    mkfifo(&fifo);
    expect_refused(
        &wrapped(s(&input), &["--json", s(&fifo)]),
        "not a regular file",
    );
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    for dev in ["/dev/null", "/dev/full"] {
        expect_refused(&wrapped(s(&input), &["--json", dev]), "not a regular file");
        assert!(
            std::fs::metadata(dev).unwrap().file_type().is_char_device(),
            "{dev}"
        );
    }
    expect_refused(&wrapped(s(&input), &["--svg", s(&d)]), "not a regular file");
    assert_eq!(others(&d, &[&input, &fifo]), Vec::<PathBuf>::new());
}

#[test]
fn an_unwritable_second_output_leaves_no_first() {
    let (d, input) = workdir("second-fails");
    let first = d.join("first.json");
    for second in [d.join("missing-folder/out.svg"), d.join("sub")] {
        std::fs::create_dir_all(d.join("sub")).unwrap();
        expect_refused(
            &wrapped(s(&input), &["--json", s(&first), "--svg", s(&second)]),
            "cannot write",
        );
        assert!(!first.exists());
    }
    assert_eq!(others(&d, &[&input, &d.join("sub")]), Vec::<PathBuf>::new());
}

#[test]
fn huge_seed_radii_are_refused_at_once() {
    let (_dir, input) = workdir("radius");
    for r in ["1e6", "1e30"] {
        let t = Instant::now();
        expect_refused(
            &[
                "segment",
                s(&input),
                "--seed",
                &format!("100,100,{r}"),
                "--object",
                "dark",
            ],
            "radius",
        );
        assert!(
            t.elapsed() < Duration::from_secs(1),
            "{r}: {:?}",
            t.elapsed()
        );
    }
}

#[test]
fn a_seed_larger_than_the_image_is_clipped_to_it() {
    let (d, input) = workdir("big-seed");
    let json = d.join("out.json");
    // 400 px on a 200-odd px image: the whole image, clipped; the run ends quickly.
    let out = run_within(
        bin().args([
            "segment",
            s(&input),
            "--seed",
            "50,50,400",
            "--object",
            "dark",
            "--json",
            s(&json),
        ]),
        Duration::from_secs(5),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let (w, h) = (
        doc["width"].as_f64().unwrap(),
        doc["height"].as_f64().unwrap(),
    );
    for c in doc["contours"].as_array().unwrap() {
        for p in c["points"].as_array().unwrap() {
            let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            assert!((0.0..=w).contains(&x) && (0.0..=h).contains(&y), "{x},{y}");
        }
    }
}

#[test]
fn a_truncated_jpeg_is_refused() {
    let (d, _) = workdir("jpeg");
    let img =
        image::GrayImage::from_fn(64, 64, |x, y| image::Luma([((x * 7 + y * 3) % 256) as u8]));
    let full = d.join("full.jpg");
    img.save(&full).unwrap();
    let bytes = std::fs::read(&full).unwrap();
    let cut = d.join("cut.jpg");
    std::fs::write(&cut, &bytes[..bytes.len() * 2 / 3]).unwrap();
    expect_refused(
        &["segment", s(&cut), "--wrap", "4", "--object", "dark"],
        "truncated",
    );
    let out = run_within(
        bin().args(["segment", s(&full), "--wrap", "4", "--object", "dark"]),
        Duration::from_secs(5),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_full_or_closed_stderr_keeps_the_exit_codes() {
    let (d, input) = workdir("stderr");
    let json = d.join("out.json");
    let full = || {
        std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap()
    };
    let bad = wrapped(s(&input), &["--json", "/dev/full"]);
    let ok = wrapped(s(&input), &["--mode", "preserve", "--json", s(&json)]);
    let code = |args: &[&str], stderr: Stdio| {
        let st = bin()
            .args(args)
            .stdout(Stdio::null())
            .stderr(stderr)
            .status()
            .unwrap();
        st.code()
    };
    assert_eq!(code(&bad, Stdio::from(full())), Some(2));
    assert_eq!(code(&["segment", "--object"], Stdio::from(full())), Some(2));
    // The preserve note is written before the outputs: a full stderr must not stop them.
    assert_eq!(code(&ok, Stdio::from(full())), Some(0));
    assert!(json.exists());
    std::fs::remove_file(&json).unwrap();
    // Closed: the shell closes descriptor 2 before exec.
    let closed = |args: &[&str]| {
        let st = Command::new("sh")
            .arg("-c")
            .arg("exec \"$0\" \"$@\" 2>&-")
            .arg(env!("CARGO_BIN_EXE_topocontour"))
            .args(args)
            .stdout(Stdio::null())
            .status()
            .unwrap();
        st.code()
    };
    assert_eq!(closed(&bad), Some(2));
    assert_eq!(closed(&ok), Some(0));
    assert!(json.exists());
}

#[test]
fn usage_errors_are_one_line() {
    let (_dir, input) = workdir("usage");
    expect_refused(
        &["segment", s(&input), "--wrap", "4", "--object", "purple"],
        "possible values: dark, bright",
    );
    expect_refused(
        &["segment", s(&input), "--seed", "1,2", "--object", "dark"],
        "3 comma-separated",
    );
    expect_refused(&["segment", s(&input), "--wrap", "4"], "--object");
    expect_refused(&wrapped(s(&input), &["--frobnicate"]), "frobnicate");
    expect_refused(&["frobnicate"], "frobnicate");
}

/// A run killed at any moment leaves each output whole or absent, never half written.
#[test]
fn kill_9_never_leaves_a_corrupt_output() {
    let (d, input) = workdir("kill");
    let (json, mask) = (d.join("out.json"), d.join("out.png"));
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let (mut whole, mut absent) = (0, 0);
    for _ in 0..60 {
        for p in [&json, &mask] {
            let _ = std::fs::remove_file(p);
        }
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let delay = Duration::from_micros(seed % 15_000);
        let mut child = bin()
            .args(wrapped(
                s(&input),
                &["--json", s(&json), "--mask", s(&mask)],
            ))
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        match std::fs::read(&json) {
            Ok(b) => {
                serde_json::from_slice::<serde_json::Value>(&b).expect("whole JSON");
                whole += 1;
            }
            Err(_) => absent += 1,
        }
        if let Ok(b) = std::fs::read(&mask) {
            image::load_from_memory(&b).expect("whole PNG");
        }
    }
    assert_eq!(whole + absent, 60);
    // Whatever a kill left is a hidden temporary, never an output under another name.
    for p in others(&d, &[&input, &json, &mask]) {
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        assert!(
            name.starts_with(".topocontour-") && name.ends_with(".tmp"),
            "{name}"
        );
    }
}

#[test]
fn a_successful_run_leaves_only_its_outputs() {
    let (d, input) = workdir("clean");
    let long = "x".repeat(250);
    let json = d.join(format!("{long}.json"));
    let out = run_within(
        bin().args(wrapped(s(&input), &["--json", s(&json)])),
        Duration::from_secs(5),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(others(&d, &[&input, &json]), Vec::<PathBuf>::new());
}
