//! What the CLI test files share: the binary, a private folder per test, small synthetic
//! images, runs with a deadline.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_topocontour"))
}

mod scratch;
pub use scratch::Scratch;

/// A fresh folder of this test's own (`group` keeps test files apart), removed when the
/// returned guard is dropped.
pub fn workdir(group: &str, name: &str) -> Scratch {
    Scratch::folder(&format!("{group}-{name}"))
}

pub fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// Runs `cmd` and asserts it succeeded, showing its stderr if not.
pub fn run_ok(cmd: &mut Command) -> Output {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{:?}: {}",
        cmd.get_args().collect::<Vec<_>>(),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Runs with a deadline: a hang fails the test instead of blocking it.
pub fn run_within(cmd: &mut Command, limit: Duration) -> Output {
    let mut child = cmd
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t.elapsed() > limit {
            child.kill().unwrap();
            panic!("{cmd:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.wait_with_output().unwrap()
}

/// Exit 2 within five seconds, with exactly one line on stderr that contains `needle`;
/// returns that line.
pub fn refused(cmd: &mut Command, needle: &str) -> String {
    let out = run_within(cmd, Duration::from_secs(5));
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{cmd:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{cmd:?}: one line, got {err:?}");
    assert!(err.contains(needle), "{cmd:?}: {err}");
    err
}

/// The names in `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A `w`×`h` gray PNG: dark disks (centre x, y, radius) on a bright background.
pub fn disks_png(path: &Path, w: u32, h: u32, disks: &[(f64, f64, f64)]) {
    let img = image::GrayImage::from_fn(w, h, |x, y| {
        let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
        let inside = disks
            .iter()
            .any(|&(cx, cy, r)| (px - cx).hypot(py - cy) <= r);
        image::Luma([if inside { 40 } else { 210 }])
    });
    img.save_with_format(path, image::ImageFormat::Png).unwrap();
}

pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Appends a little-endian TIFF image directory to `out`: its `(tag, type, count,
/// value or offset)` entries and the offset of the next directory (0 for none).
pub fn tiff_directory(out: &mut Vec<u8>, entries: &[(u16, u16, u32, u32)], last: bool) {
    out.extend((entries.len() as u16).to_le_bytes());
    for &(tag, kind, count, value) in entries {
        out.extend(tag.to_le_bytes());
        out.extend(kind.to_le_bytes());
        out.extend(count.to_le_bytes());
        out.extend(value.to_le_bytes());
    }
    let next = if last { 0 } else { out.len() as u32 + 4 };
    out.extend(next.to_le_bytes());
}
