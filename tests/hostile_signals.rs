//! Interrupted runs (issue 24.15, 24.16): SIGINT, SIGTERM and SIGHUP leave no temporary
//! behind; a batch asked to stop writes a summary of what it did; a killed batch leaves
//! no summary of an earlier run beside its new outputs; a bench case whose case.json is
//! not a file is an error, not skipped.
#![cfg(unix)]

mod common;

use common::{bin, disks_png, names, refused, run_ok, s};
use std::path::Path;
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

/// Waits until `dir` holds a name that `pred` accepts (the run is under way).
fn wait_for(dir: &Path, pred: impl Fn(&str) -> bool) {
    let t = Instant::now();
    while !names(dir).iter().any(|n| pred(n)) {
        assert!(
            t.elapsed() < Duration::from_secs(60),
            "never saw it in {dir:?}"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
}

fn signal(child: &Child, sig: i32) {
    // SAFETY: kill only sends a signal to our own child.
    assert_eq!(unsafe { libc::kill(child.id() as i32, sig) }, 0);
}

fn is_temporary(n: &str) -> bool {
    n.starts_with(".topocontour-")
}

/// A 1536² image of 64 dark disks: long enough a run to be interrupted.
fn big_image(path: &Path) {
    let disks: Vec<(f64, f64, f64)> = (0..64)
        .map(|k| {
            (
                96.0 + 192.0 * (k % 8) as f64,
                96.0 + 192.0 * (k / 8) as f64,
                60.0,
            )
        })
        .collect();
    disks_png(path, 1536, 1536, &disks);
}

#[test]
fn a_signal_during_segment_leaves_no_temporary() {
    let d = common::workdir("signals", "segment");
    let image = d.join("in.png");
    big_image(&image);
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();
    for sig in [libc::SIGINT, libc::SIGTERM, libc::SIGHUP] {
        // The signal is sent while the outputs are written, a short window: on a loaded
        // machine the run may finish before it arrives. Then it wrote its outputs whole,
        // and is run again.
        let mut interrupted = false;
        for _ in 0..ATTEMPTS {
            let mut child = bin()
                .args(["segment", s(&image), "--wrap", "4", "--object", "dark"])
                .args([
                    "--json",
                    s(&out.join("o.json")),
                    "--svg",
                    s(&out.join("o.svg")),
                ])
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            wait_for(&out, is_temporary);
            signal(&child, sig);
            let status = child.wait().unwrap();
            if status.code() == Some(0) {
                assert_eq!(names(&out), ["o.json", "o.svg"], "signal {sig}, finished");
                for n in names(&out) {
                    std::fs::remove_file(out.join(n)).unwrap();
                }
                continue;
            }
            assert_eq!(status.code(), Some(130), "signal {sig}");
            assert!(names(&out).is_empty(), "signal {sig}: {:?}", names(&out));
            interrupted = true;
            break;
        }
        assert!(interrupted, "signal {sig}: every run finished first");
    }
}

/// How many times a run is started to be interrupted before the test gives up (each
/// that finishes first is checked as a whole run).
const ATTEMPTS: usize = 5;

/// A folder of `n` small images.
fn folder(d: &Path, n: usize) -> std::path::PathBuf {
    let input = d.join("in");
    std::fs::create_dir_all(&input).unwrap();
    for k in 0..n {
        let disks: Vec<(f64, f64, f64)> = (0..16)
            .map(|j| {
                (
                    40.0 + 60.0 * (j % 4) as f64,
                    40.0 + 60.0 * (j / 4) as f64,
                    20.0,
                )
            })
            .collect();
        disks_png(&input.join(format!("img{k:03}.png")), 256, 256, &disks);
    }
    input
}

fn batch(input: &Path, out: &Path) -> std::process::Command {
    let mut c = bin();
    c.args([
        "batch",
        s(input),
        "--out",
        s(out),
        "--wrap",
        "3",
        "--object",
        "dark",
    ])
    .args(["--formats", "json", "--jobs", "1"]);
    c
}

#[test]
fn a_batch_asked_to_stop_summarises_what_it_did() {
    let d = common::workdir("signals", "gentle");
    let input = folder(&d, 60);
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();
    let child = batch(&input, &out).stderr(Stdio::piped()).spawn().unwrap();
    wait_for(&out, |n| n.ends_with(".json"));
    signal(&child, libc::SIGTERM);
    let result = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&result.stderr);
    assert_eq!(result.status.code(), Some(1), "{err}");
    assert!(err.contains("interrupted"), "{err}");
    let listed = names(&out);
    assert!(!listed.iter().any(|n| is_temporary(n)), "{listed:?}");
    let jsons = listed.iter().filter(|n| n.ends_with(".json")).count();
    assert!(jsons < 60, "the run stopped early: {jsons} outputs");
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    for k in 0..60 {
        let done = listed.contains(&format!("img{k:03}.json"));
        assert_eq!(
            summary.contains(&format!("img{k:03}.png")),
            done,
            "img{k:03}"
        );
    }
}

#[test]
fn a_track_asked_to_stop_writes_the_frames_it_tracked_as_a_whole_result() {
    let d = common::workdir("signals", "track");
    let movie = d.join("movie");
    std::fs::create_dir(&movie).unwrap();
    // Many frames of 16 dark disks drifting: long enough to be interrupted.
    let frames = 400;
    for t in 0..frames {
        let disks: Vec<(f64, f64, f64)> = (0..16)
            .map(|k| {
                let drift = (t % 40) as f64 * 0.5;
                (
                    40.0 + 60.0 * (k % 4) as f64 + drift,
                    40.0 + 60.0 * (k / 4) as f64,
                    14.0,
                )
            })
            .collect();
        disks_png(&movie.join(format!("f{t:03}.png")), 260, 240, &disks);
    }
    let out = d.join("res");
    // On a loaded machine the run may finish before the signal arrives: it is run again.
    let mut attempts = 0;
    let (result, err) = loop {
        attempts += 1;
        let child = bin()
            .args([
                "track",
                s(&movie),
                "--object",
                "dark",
                "--auto-seeds",
                "--ctc",
                s(&out),
            ])
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        wait_for(&d, |n| n == "res");
        wait_for(&out, |n| n == "mask005.tif");
        signal(&child, libc::SIGINT);
        let result = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&result.stderr).to_string();
        if result.status.code() == Some(0) && attempts < ATTEMPTS {
            assert!(err.contains(&format!("tracked {frames} frames")), "{err}");
            std::fs::remove_dir_all(&out).unwrap();
            continue;
        }
        break (result, err);
    };
    assert_eq!(result.status.code(), Some(130), "{err}");
    assert!(err.contains("interrupted: frames 0 to"), "{err}");
    let listed = names(&out);
    assert!(!listed.iter().any(|n| is_temporary(n)), "{listed:?}");
    let masks = listed.iter().filter(|n| n.starts_with("mask")).count();
    assert!((6..frames).contains(&masks), "{masks} masks");
    for t in 0..masks {
        assert!(
            listed.contains(&format!("mask{t:03}.tif")),
            "frames from 0 on"
        );
    }
    // res_track.txt describes exactly the frames written.
    let res = std::fs::read_to_string(out.join("res_track.txt")).unwrap();
    let last = res
        .lines()
        .map(|l| l.split(' ').nth(2).unwrap().parse::<usize>().unwrap())
        .max()
        .unwrap();
    assert_eq!(last, masks - 1, "{res}");
}

/// A run over an earlier result removes its res_track.txt before the first new mask and
/// writes its own last: killed between, the folder holds no res_track.txt describing
/// other masks than its own.
#[test]
fn a_killed_track_leaves_no_res_track_of_an_earlier_run() {
    let d = common::workdir("signals", "track-again");
    let movie = d.join("movie");
    std::fs::create_dir(&movie).unwrap();
    for t in 0..200 {
        let x = 40.0 + (t % 40) as f64;
        disks_png(
            &movie.join(format!("f{t:03}.png")),
            200,
            120,
            &[(x, 60.0, 14.0)],
        );
    }
    let out = d.join("res");
    let track = || {
        let mut c = bin();
        c.args(["track", s(&movie), "--object", "dark", "--ctc", s(&out)]);
        c
    };
    run_ok(&mut track());
    assert!(out.join("res_track.txt").is_file());
    let mut child = track().stderr(Stdio::null()).spawn().unwrap();
    wait_for(&d, |_| !out.join("res_track.txt").exists());
    signal(&child, libc::SIGKILL);
    child.wait().unwrap();
    assert!(
        !out.join("res_track.txt").exists(),
        "no res_track.txt of the run before"
    );
}

/// A run started with SIGINT ignored (a background job of a script) keeps ignoring it
/// and finishes its work.
#[test]
fn a_signal_the_run_was_started_ignoring_stays_ignored() {
    use std::os::unix::process::CommandExt;
    let d = common::workdir("signals", "ignored");
    let input = folder(&d, 40);
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();
    let mut c = batch(&input, &out);
    // SAFETY: only async-signal-safe calls between fork and exec.
    unsafe {
        c.pre_exec(|| {
            libc::signal(libc::SIGINT, libc::SIG_IGN);
            Ok(())
        })
    };
    let child = c.stderr(Stdio::null()).spawn().unwrap();
    wait_for(&out, |n| n.ends_with(".json"));
    signal(&child, libc::SIGINT);
    let status = child.wait_with_output().unwrap().status;
    assert!(status.success(), "{status:?}");
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(summary.contains("img039.png"), "{summary}");
}

#[test]
fn a_killed_batch_leaves_no_summary_of_an_earlier_run() {
    let d = common::workdir("signals", "stale");
    let input = folder(&d, 60);
    let out = d.join("out");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("summary.csv"), "image,id\nearlier.png,1\n").unwrap();
    let mut child = batch(&input, &out).stderr(Stdio::null()).spawn().unwrap();
    wait_for(&out, |n| n.ends_with(".json"));
    signal(&child, libc::SIGKILL);
    child.wait().unwrap();
    assert!(!out.join("summary.csv").exists(), "{:?}", names(&out));
    // A whole run writes it again.
    run_ok(&mut batch(&input, &out));
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(summary.contains("img059.png") && !summary.contains("earlier"));
}

#[test]
fn a_bench_case_whose_case_json_is_not_a_file_is_an_error() {
    let d = common::workdir("signals", "bench");
    let case = d.join("case");
    std::fs::create_dir(&case).unwrap();
    disks_png(&case.join("image.png"), 32, 32, &[(16.0, 16.0, 6.0)]);
    let fifo = std::ffi::CString::new(s(&case.join("case.json"))).unwrap();
    // SAFETY: a valid path; mkfifo only creates it.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
    refused(
        bin().args(["bench", s(&case), "--runs", "1"]),
        "not a regular file",
    );
    refused(
        bin().args(["bench", s(&d), "--runs", "1"]),
        "not a regular file",
    );
    std::fs::remove_file(case.join("case.json")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", case.join("case.json")).unwrap();
    refused(
        bin().args(["bench", s(&case), "--runs", "1"]),
        "not a regular file",
    );
}
