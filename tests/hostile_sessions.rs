//! Session files and outputs that must never destroy data or hang (issue 24: 1, 2, 5, 6,
//! 8, 12, 17): each case asserts the exit code, one line on stderr, the inputs
//! byte-identical and no file left behind.
#![cfg(unix)]

mod common;

use common::{bin, disks_png, names, refused, run_ok, s};
use std::path::{Path, PathBuf};

/// A folder with `img.png` and its session `s.json` (from `segment --save-session`).
fn with_session(name: &str) -> (common::Scratch, PathBuf, PathBuf) {
    let d = common::workdir("sessions", name);
    let img = d.join("img.png");
    disks_png(&img, 64, 48, &[(20.0, 24.0, 9.0), (44.0, 24.0, 8.0)]);
    let session = d.join("s.json");
    run_ok(bin().args([
        "segment",
        s(&img),
        "--wrap",
        "3",
        "--object",
        "dark",
        "--save-session",
        s(&session),
    ]));
    (d, img, session)
}

fn replay(session: &Path, extra: &[&str]) -> std::process::Command {
    let mut c = bin();
    c.arg("replay").arg(session).args(extra);
    c
}

/// Issue 24.1: `replay s.json --json s.json` (or a hard link to it) is refused and the
/// session stays as it was.
#[test]
fn replay_never_writes_over_its_session() {
    let (d, _, session) = with_session("own");
    let before = std::fs::read(&session).unwrap();
    refused(
        &mut replay(&session, &["--json", s(&session)]),
        "session file",
    );
    let link = d.join("link.json");
    std::fs::hard_link(&session, &link).unwrap();
    refused(&mut replay(&session, &["--csv", s(&link)]), "session file");
    assert_eq!(std::fs::read(&session).unwrap(), before);
    assert_eq!(names(&d), ["img.png", "link.json", "s.json"]);
}

/// Issue 24.2: an output name the file system cannot take is refused before anything is
/// replaced (it used to fail at its rename, after the JSON was already replaced).
#[test]
fn an_over_long_name_replaces_nothing() {
    let (d, img, _) = with_session("long");
    let json = d.join("o.json");
    std::fs::write(&json, "old").unwrap();
    let long = d.join(format!("{}.zip", "r".repeat(300)));
    let seg = |flag: &str| {
        let mut c = bin();
        c.args(["segment", s(&img), "--wrap", "3", "--object", "dark"])
            .args(["--json", s(&json), flag, s(&long)]);
        c
    };
    refused(&mut seg("--roi"), "too long");
    refused(&mut seg("--save-session"), "too long");
    assert_eq!(std::fs::read(&json).unwrap(), b"old");
    assert_eq!(names(&d), ["img.png", "o.json", "s.json"]);
}

/// Issue 24.6: a replaced output keeps its permissions.
#[test]
fn a_replaced_output_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let (d, _, session) = with_session("mode");
    let json = d.join("private.json");
    std::fs::write(&json, "old").unwrap();
    std::fs::set_permissions(&json, std::fs::Permissions::from_mode(0o600)).unwrap();
    run_ok(&mut replay(&session, &["--json", s(&json)]));
    assert_ne!(std::fs::read(&json).unwrap(), b"old");
    let mode = std::fs::metadata(&json).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o600);
}

/// Issue 24.8: a session path that is a FIFO, or a link to an endless device, is refused
/// at once (it used to block, or read until memory ran out).
#[test]
fn special_session_files_are_refused_at_once() {
    let d = common::workdir("sessions", "special");
    let fifo = d.join("fifo.json");
    let ok = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success();
    assert!(ok);
    refused(&mut replay(&fifo, &[]), "not a regular file");
    for dev in ["/dev/zero", "/dev/urandom"] {
        let link = d.join(format!("{}.json", &dev[5..]));
        std::os::unix::fs::symlink(dev, &link).unwrap();
        refused(&mut replay(&link, &[]), "not a regular file");
    }
}

/// Issue 24.17: a session with a key this build does not know is refused, not read with
/// the key ignored.
#[test]
fn unknown_session_keys_are_refused() {
    let (d, _, session) = with_session("keys");
    let mut doc = common::read_json(&session);
    doc["max_frame"] = 10.into();
    let typo = d.join("typo.json");
    std::fs::write(&typo, serde_json::to_string(&doc).unwrap()).unwrap();
    refused(&mut replay(&typo, &[]), "unknown field");
}

/// Issue 24.12: an image whose name is not UTF-8 cannot be named in a session: one
/// clear line, exit 2, nothing written (it used to panic).
#[test]
fn a_non_utf8_image_name_with_a_session_is_refused() {
    use std::os::unix::ffi::OsStrExt;
    let d = common::workdir("sessions", "utf8");
    let img = d.join(std::ffi::OsStr::from_bytes(b"bad\xff.png"));
    disks_png(&img, 48, 48, &[(24.0, 24.0, 9.0)]);
    let mut c = bin();
    c.arg("segment")
        .arg(&img)
        .args(["--wrap", "3", "--object", "dark", "--json"])
        .arg(d.join("o.json"))
        .arg("--save-session")
        .arg(d.join("s.json"));
    refused(&mut c, "not valid UTF-8");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1, "only the image");
}

/// Issue 24.5: names and units that start like a formula reach the CSV as text, and a
/// file name's escape sequence is never echoed raw.
#[test]
fn csv_cells_are_never_formulas_and_errors_never_escape() {
    let d = common::workdir("sessions", "inject");
    let img = d.join("=HYPERLINK(1).png");
    disks_png(&img, 48, 48, &[(24.0, 24.0, 9.0)]);
    let csv = d.join("o.csv");
    run_ok(bin().arg("segment").arg(&img).args([
        "--wrap",
        "3",
        "--object",
        "dark",
        "--pixel-size",
        "0.5",
        "--unit",
        "+1",
        "--csv",
        s(&csv),
    ]));
    let text = std::fs::read_to_string(&csv).unwrap();
    let row = text.lines().nth(1).unwrap();
    assert!(row.starts_with("\"'=HYPERLINK(1).png\","), "{row}");
    assert!(row.contains(",\"'+1\","), "{row}");
    let err = refused(
        bin().args([
            "segment",
            "\u{1b}[31mred.png",
            "--wrap",
            "3",
            "--object",
            "dark",
        ]),
        "red.png",
    );
    assert!(!err.contains('\u{1b}'), "raw escape in {err:?}");
}

/// Issue 24.17: a pixel size whose calibrated area overflows is refused (it used to put
/// `inf` in the CSV).
#[test]
fn pixel_sizes_out_of_range_are_refused() {
    let (d, img, _) = with_session("inf");
    let csv = d.join("o.csv");
    let mut c = bin();
    c.args(["segment", s(&img), "--wrap", "3", "--object", "dark"])
        .args(["--pixel-size", "1e300", "--csv", s(&csv)]);
    refused(&mut c, "--pixel-size");
    assert!(!csv.exists());
}
