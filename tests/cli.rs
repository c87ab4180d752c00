//! The real binary on the public cases and on bad input (DESIGN's CLI contract).

mod common;

use common::{bin, read_json, run_ok};
use std::path::{Path, PathBuf};

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cases")
}

/// The path `name` in a fresh folder of its own, removed with the returned guard.
fn tmp(name: &str) -> common::Scratch {
    common::Scratch::file(name)
}

fn gray_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path).unwrap().to_luma8();
    (img.width(), img.height(), img.into_raw())
}

fn dice(a: &[u8], b: &[u8]) -> f64 {
    let (mut inter, mut sa, mut sb) = (0usize, 0usize, 0usize);
    for (&x, &y) in a.iter().zip(b) {
        let (x, y) = (x > 127, y > 127);
        inter += (x && y) as usize;
        sa += x as usize;
        sb += y as usize;
    }
    2.0 * inter as f64 / (sa + sb).max(1) as f64
}

/// Runs a case as score_cases.py does; returns the JSON and the mask path.
fn run_case(name: &str, extra: &[&str]) -> (serde_json::Value, common::Scratch) {
    static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let run = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = cases_dir().join(name);
    let meta = read_json(&dir.join("case.json"));
    let init = &meta["init"];
    let mut args: Vec<String> = vec![
        "segment".into(),
        dir.join("image.png").display().to_string(),
    ];
    for s in init["seeds"].as_array().into_iter().flatten() {
        args.extend(["--seed".into(), format!("{},{},{}", s[0], s[1], s[2])]);
    }
    if let Some(m) = init["border_margin"].as_f64() {
        args.extend(["--wrap".into(), m.to_string()]);
    }
    args.extend([
        "--object".into(),
        init["object"].as_str().unwrap().to_string(),
    ]);
    let (mask, json) = (
        // Tests run in parallel and may run the same case with other flags: every run
        // gets its own output names.
        tmp(&format!("{name}-{run}-mask.png")),
        tmp(&format!("{name}-{run}.json")),
    );
    args.extend([
        "--mask".into(),
        mask.display().to_string(),
        "--json".into(),
        json.display().to_string(),
    ]);
    args.extend(extra.iter().map(|s| s.to_string()));
    run_ok(bin().args(&args));
    (read_json(&json), mask)
}

#[test]
fn public_cases_get_topology_and_dice() {
    let mut total = 0.0;
    let names = [
        "blobs_wrap",
        "bridge_merge",
        "cheese_holes",
        "noisy_blobs",
        "phase_cells",
        "ring_seed",
        "slot_concavity",
        "spiral_grow",
    ];
    for name in names {
        let (doc, mask) = run_case(name, &[]);
        let meta = read_json(&cases_dir().join(name).join("case.json"));
        let contours = doc["contours"].as_array().unwrap();
        let holes = contours.iter().filter(|c| c["hole"] == true).count();
        let outer = contours.len() - holes;
        assert_eq!(
            outer as u64,
            meta["expect"]["components"].as_u64().unwrap(),
            "{name} components"
        );
        assert_eq!(
            holes as u64,
            meta["expect"]["holes"].as_u64().unwrap(),
            "{name} holes"
        );
        // Holes name an outer parent; outer rings have none here.
        for c in contours {
            assert_eq!(c["hole"] == true, !c["parent"].is_null(), "{name}: {c}");
        }
        let (w, h, m) = gray_png(&mask);
        let (tw, th, t) = gray_png(&cases_dir().join(name).join("truth.png"));
        assert_eq!((w, h), (tw, th));
        let d = dice(&m, &t);
        assert!(d >= 0.95, "{name}: dice {d}");
        total += d;
    }
    assert!(
        total / names.len() as f64 >= 0.98,
        "mean dice {}",
        total / names.len() as f64
    );
}

/// The topology-keeping engines from the command line: each case ends with the topology
/// it started with (seeds: one outer ring per seed; a wrap: one), no events, the mode
/// and the held contacts in the JSON, and a note on stderr where fronts were held apart.
#[test]
fn preserve_and_implicit_keep_the_initial_topology() {
    for mode in ["preserve", "implicit"] {
        for (name, outer) in [("bridge_merge", 2), ("ring_seed", 1), ("blobs_wrap", 1)] {
            let (doc, mask) = run_case(name, &["--mode", mode]);
            let contours = doc["contours"].as_array().unwrap();
            let holes = contours.iter().filter(|c| c["hole"] == true).count();
            assert_eq!((contours.len() - holes, holes), (outer, 0), "{mode} {name}");
            assert!(
                doc["events"].as_array().unwrap().is_empty(),
                "{mode} {name}"
            );
            assert_eq!(doc["mode"], mode);
            assert!(
                doc["held"].as_u64().unwrap() > 0,
                "{mode} {name}: fronts met"
            );
            let (_, _, m) = gray_png(&mask);
            let (_, _, t) = gray_png(&cases_dir().join(name).join("truth.png"));
            let d = dice(&m, &t);
            assert!(d >= 0.95, "{mode} {name}: dice {d}");
        }
    }
}

#[test]
fn events_are_reported_with_frames() {
    let (doc, _) = run_case("bridge_merge", &[]);
    let events = doc["events"].as_array().unwrap();
    assert!(
        events.iter().any(|e| e["kind"] == "merge"
            && e["contours"].as_array().unwrap().len() == 2
            && e["frame"].as_u64().unwrap() > 0),
        "{events:?}"
    );
    let (doc, _) = run_case("ring_seed", &[]);
    assert!(doc["events"]
        .as_array()
        .unwrap()
        .iter()
        .any(|e| e["kind"] == "hole_made"));
    assert_eq!(doc["converged"], true);
    assert_eq!(
        (doc["width"].as_u64(), doc["height"].as_u64()),
        (Some(256), Some(256))
    );
}

#[test]
fn svg_renders_like_the_mask_and_geojson_parses() {
    let svg_path = tmp("cheese.svg");
    let geo_path = tmp("cheese.geojson");
    let csv_path = tmp("cheese.csv");
    let (_, mask) = run_case(
        "cheese_holes",
        &[
            "--svg",
            svg_path.to_str().unwrap(),
            "--geojson",
            geo_path.to_str().unwrap(),
            "--csv",
            csv_path.to_str().unwrap(),
        ],
    );
    let (w, h, m) = gray_png(&mask);
    // Render the SVG with a real renderer and compare pixel coverage with the mask.
    let tree = resvg::usvg::Tree::from_str(
        &std::fs::read_to_string(&svg_path).unwrap(),
        &resvg::usvg::Options::default(),
    )
    .unwrap();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    // Fill alpha is 0.5: a pixel at least half covered is above 64.
    let rendered: Vec<bool> = pixmap.pixels().iter().map(|p| p.alpha() >= 64).collect();
    let (mut inter, mut union) = (0usize, 0usize);
    for (&a, &b) in rendered.iter().zip(&m) {
        let b = b > 127;
        inter += (a && b) as usize;
        union += (a || b) as usize;
    }
    let iou = inter as f64 / union as f64;
    assert!(iou >= 0.99, "svg vs mask IoU {iou}");
    let geo = read_json(&geo_path);
    let features = geo["features"].as_array().unwrap();
    assert_eq!(features.len(), 1);
    let rings = features[0]["geometry"]["coordinates"].as_array().unwrap();
    assert_eq!(rings.len(), 3, "one outer ring and two holes");
    for r in rings {
        let r = r.as_array().unwrap();
        assert_eq!(r.first(), r.last(), "closed ring");
    }
    let csv = std::fs::read_to_string(&csv_path).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,pixel_size,unit,area_calibrated,perimeter_calibrated,contour"
    );
    assert!(
        lines[1].starts_with("\"image.png\","),
        "the image named: {}",
        lines[1]
    );
    assert_eq!(lines.len(), 2);
    let fields: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(fields[7], "2", "two holes");
    assert_eq!(
        fields[8..12],
        ["", "", "", ""],
        "no pixel size: no calibration"
    );
}

fn expect_bad(args: &[&str], needle: &str) {
    let out = bin().args(args).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.to_lowercase().contains(needle), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn bad_input_is_one_clear_error_and_exit_2() {
    let img = cases_dir().join("ring_seed/image.png");
    let img = img.to_str().unwrap();
    let out = tmp("never.json");
    let out_s = out.to_str().unwrap();
    expect_bad(
        &[
            "segment",
            "/nonexistent/x.png",
            "--seed",
            "1,1,1",
            "--object",
            "dark",
        ],
        "cannot read",
    );
    let corrupt = tmp("corrupt.png");
    std::fs::write(&corrupt, b"\x89PNG\r\n\x1a\nthis is not a png").unwrap();
    expect_bad(
        &[
            "segment",
            corrupt.to_str().unwrap(),
            "--seed",
            "1,1,1",
            "--object",
            "dark",
        ],
        "not a readable",
    );
    // A PNG header that claims zero width.
    let mut zero = Vec::new();
    zero.extend_from_slice(b"\x89PNG\r\n\x1a\n");
    let ihdr = [0u8, 0, 0, 0, 0, 0, 0, 1, 8, 0, 0, 0, 0];
    zero.extend_from_slice(&13u32.to_be_bytes());
    zero.extend_from_slice(b"IHDR");
    zero.extend_from_slice(&ihdr);
    zero.extend_from_slice(&[0, 0, 0, 0]);
    let zero_path = tmp("zero.png");
    std::fs::write(&zero_path, &zero).unwrap();
    let z = bin()
        .args([
            "segment",
            zero_path.to_str().unwrap(),
            "--seed",
            "1,1,1",
            "--object",
            "dark",
        ])
        .output()
        .unwrap();
    assert_eq!(
        z.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&z.stderr)
    );
    expect_bad(
        &[
            "segment", img, "--seed", "900,10,5", "--object", "dark", "--json", out_s,
        ],
        "outside",
    );
    expect_bad(
        &["segment", img, "--seed", "10,10,NaN", "--object", "dark"],
        "finite",
    );
    expect_bad(
        &["segment", img, "--seed", "10,10,-3", "--object", "dark"],
        "positive",
    );
    expect_bad(
        &["segment", img, "--wrap", "-4", "--object", "dark"],
        "wrap",
    );
    expect_bad(&["segment", img, "--object", "dark"], "no initialisation");
    expect_bad(
        &[
            "segment",
            img,
            "--seed",
            "10,10,3",
            "--object",
            "dark",
            "--min-area",
            "-1",
        ],
        "min-area",
    );
    expect_bad(
        &[
            "segment",
            img,
            "--seed",
            "10,10,3",
            "--object",
            "dark",
            "--json",
            "/nonexistent-dir/out.json",
        ],
        "cannot write",
    );
    assert!(!out.exists(), "no output after a failed run");
}

#[test]
fn unwritable_output_leaves_no_partial_file() {
    let img = cases_dir().join("ring_seed/image.png");
    let dir = tmp("readonly");
    std::fs::create_dir_all(&dir).unwrap();
    let mut perms = std::fs::metadata(&dir).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&dir, perms).unwrap();
    let target = dir.join("out.svg");
    let json = tmp("ok-before-fail.json");
    let out = bin()
        .args([
            "segment",
            img.to_str().unwrap(),
            "--seed",
            "136,70,5",
            "--object",
            "dark",
            "--json",
            json.to_str().unwrap(),
            "--svg",
            target.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let mut perms = std::fs::metadata(&dir).unwrap().permissions();
    #[allow(clippy::permissions_set_readonly_false)]
    perms.set_readonly(false);
    std::fs::set_permissions(&dir, perms).unwrap();
    // Root may write anyway; otherwise the failure must be clean.
    if !out.status.success() {
        assert_eq!(out.status.code(), Some(2));
        assert!(String::from_utf8_lossy(&out.stderr).contains("cannot write"));
        assert!(
            std::fs::read_dir(&dir).unwrap().next().is_none(),
            "no temporary or partial file left"
        );
    }
}

#[test]
fn huge_image_is_refused_before_decoding() {
    // A PNG header claiming 100,000 × 100,000 pixels and no pixel data.
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&100_000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 0, 0, 0, 0]);
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    let crc = crc32(&ihdr);
    png.extend_from_slice(&crc.to_be_bytes());
    // An empty IDAT and IEND so the header parses completely.
    for kind in [&b"IDAT"[..], &b"IEND"[..]] {
        png.extend_from_slice(&0u32.to_be_bytes());
        png.extend_from_slice(kind);
        png.extend_from_slice(&crc32(kind).to_be_bytes());
    }
    let path = tmp("huge.png");
    std::fs::write(&path, &png).unwrap();
    expect_bad(
        &[
            "segment",
            path.to_str().unwrap(),
            "--seed",
            "10,10,3",
            "--object",
            "dark",
        ],
        "too large",
    );
}

fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in data {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// `--labels` writes one 16-bit label per outer contour (PNG and TIFF), holes 0; the
/// GeoJSON carries QuPath's `classification` and `measurements`.
#[test]
fn labels_and_qupath_geojson() {
    for ext in ["png", "tif"] {
        let labels = tmp(&format!("cheese-labels.{ext}"));
        let geo = tmp(&format!("cheese-{ext}.geojson"));
        let (doc, mask) = run_case(
            "cheese_holes",
            &[
                "--labels",
                labels.to_str().unwrap(),
                "--geojson",
                geo.to_str().unwrap(),
            ],
        );
        let img = image::open(&labels).unwrap();
        assert!(
            matches!(img, image::DynamicImage::ImageLuma16(_)),
            "{ext}: 16-bit"
        );
        let l = img.to_luma16();
        let mut ids: Vec<u16> = l.pixels().map(|p| p.0[0]).filter(|&v| v > 0).collect();
        ids.sort_unstable();
        ids.dedup();
        let outer = doc["contours"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["hole"] == false)
            .count();
        assert_eq!(ids.len(), outer, "{ext}");
        // Labelled pixels are exactly the mask's (holes are 0).
        let (_, _, m) = gray_png(&mask);
        for (p, &mv) in l.pixels().zip(&m) {
            assert_eq!(p.0[0] > 0, mv > 127);
        }
        let g = read_json(&geo);
        let props = &g["features"][0]["properties"];
        assert_eq!(props["objectType"], "annotation");
        assert_eq!(props["classification"]["name"], "Object");
        let area = props["measurements"]["Area px^2"].as_f64().unwrap();
        assert!(area > 0.0);
        assert_eq!(props["measurements"]["Holes"], 2);
    }
}

/// `batch` over three images writes one JSON per image, named after it, and a summary
/// with one row per object of each.
#[test]
fn batch_writes_one_json_per_image_and_a_summary() {
    let input = tmp("batch-in");
    let out = tmp("batch-out");
    let _ = std::fs::remove_dir_all(&out);
    std::fs::create_dir_all(&input).unwrap();
    for name in ["blobs_wrap", "bridge_merge", "phase_cells"] {
        std::fs::copy(
            cases_dir().join(name).join("image.png"),
            input.join(format!("{name}.png")),
        )
        .unwrap();
    }
    std::fs::write(input.join("notes.txt"), "not an image").unwrap();
    run_ok(bin().args([
        "batch",
        input.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--wrap",
        "6",
        "--object",
        "dark",
        "--formats",
        "json,labels",
    ]));
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let mut lines = summary.lines();
    assert_eq!(
        lines.next().unwrap(),
        "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,mean_intensity,contour"
    );
    let rows: Vec<&str> = lines.collect();
    let mut total = 0;
    for name in ["blobs_wrap", "bridge_merge", "phase_cells"] {
        let doc = read_json(&out.join(format!("{name}.json")));
        let outer = doc["contours"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c["hole"] == false)
            .count();
        assert!(outer > 0, "{name}");
        let mine = rows
            .iter()
            .filter(|r| r.starts_with(&format!("\"{name}.png\",")))
            .count();
        assert_eq!(mine, outer, "{name}: one summary row per object");
        assert!(out.join(format!("{name}.labels.tif")).is_file());
        total += outer;
    }
    assert_eq!(rows.len(), total);
    let names = common::names(&out);
    assert_eq!(
        names.len(),
        7,
        "three JSON, three label images, the summary: {names:?}"
    );
}

/// `--roi` writes an ImageJ ROI set: read back by a small reader of ImageJ's format, one
/// ROI per region, a sub-pixel polygon without holes, a composite path with them, the
/// coordinates those of the JSON.
#[test]
fn roi_set_reads_back() {
    let be16 = |b: &[u8], o: usize| u16::from_be_bytes([b[o], b[o + 1]]);
    let be32 = |b: &[u8], o: usize| u32::from_be_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
    let f32at = |b: &[u8], o: usize| f32::from_bits(be32(b, o)) as f64;
    for (case, holes) in [("blobs_wrap", false), ("cheese_holes", true)] {
        let roi = tmp(&format!("{case}.roi.zip"));
        let (doc, _) = run_case(case, &["--roi", roi.to_str().unwrap()]);
        let contours = doc["contours"].as_array().unwrap();
        let outer: Vec<&serde_json::Value> =
            contours.iter().filter(|c| c["hole"] == false).collect();
        let mut zip = zip::ZipArchive::new(std::fs::File::open(&roi).unwrap()).unwrap();
        assert_eq!(zip.len(), outer.len(), "{case}: one ROI per region");
        for i in 0..zip.len() {
            let mut b = Vec::new();
            std::io::Read::read_to_end(&mut zip.by_index(i).unwrap(), &mut b).unwrap();
            assert_eq!(&b[0..4], b"Iout");
            assert!(be16(&b, 4) >= 222, "sub-pixel needs version 222 or later");
            let kind = b[6];
            if !holes {
                assert_eq!(kind, 0, "polygon");
                let n = be16(&b, 16) as usize;
                assert_ne!(be16(&b, 50) & 128, 0, "sub-pixel resolution");
                let xs: Vec<f64> = (0..n).map(|k| f32at(&b, 64 + 4 * n + 4 * k)).collect();
                let ys: Vec<f64> = (0..n).map(|k| f32at(&b, 64 + 8 * n + 4 * k)).collect();
                // The same ring as one of the JSON's outer contours.
                let found = outer.iter().any(|c| {
                    let pts = c["points"].as_array().unwrap();
                    pts.len() == n
                        && pts.iter().zip(xs.iter().zip(&ys)).all(|(p, (x, y))| {
                            (p[0].as_f64().unwrap() - x).abs() < 1e-3
                                && (p[1].as_f64().unwrap() - y).abs() < 1e-3
                        })
                });
                assert!(found, "{case}: ROI {i} is no contour of the JSON");
            } else {
                assert_eq!(kind, 1, "composite (shape) ROI");
                let size = be32(&b, 36) as usize;
                let path: Vec<f64> = (0..size).map(|k| f32at(&b, 64 + 4 * k)).collect();
                let closes = path.iter().filter(|&&v| v == 4.0).count();
                assert!(closes >= 3, "{case}: outer ring and two holes as sub-paths");
                let points: usize = contours
                    .iter()
                    .map(|c| c["points"].as_array().unwrap().len())
                    .sum();
                assert_eq!(
                    size,
                    3 * points + closes,
                    "{case}: every vertex in the path"
                );
            }
        }
    }
}

/// `segment --save-session` then `replay` gives byte-identical JSON, with automatic seeds
/// and in every engine; a changed image is refused.
#[test]
fn replay_equals_segment() {
    let img = tmp("replay-image.png");
    std::fs::copy(cases_dir().join("phase_cells/image.png"), &img).unwrap();
    let mut sessions = Vec::new();
    for mode in ["adaptive", "preserve", "implicit"] {
        for init in [&["--wrap", "6"][..], &["--auto-seeds"][..]] {
            let (a, b, s) = (
                tmp(&format!("replay-{mode}-{}-a.json", init.len())),
                tmp(&format!("replay-{mode}-{}-b.json", init.len())),
                tmp(&format!("replay-{mode}-{}.session", init.len())),
            );
            let mut args = vec![
                "segment",
                img.to_str().unwrap(),
                "--object",
                "dark",
                "--mode",
                mode,
            ];
            args.extend_from_slice(init);
            args.extend([
                "--json",
                a.to_str().unwrap(),
                "--save-session",
                s.to_str().unwrap(),
            ]);
            run_ok(bin().args(&args));
            run_ok(bin().args(["replay", s.to_str().unwrap(), "--json", b.to_str().unwrap()]));
            assert_eq!(
                std::fs::read(&a).unwrap(),
                std::fs::read(&b).unwrap(),
                "{mode} {init:?}: replay differs"
            );
            sessions.push(s);
        }
    }
    // The image changes: the session (adaptive, wrapped) refuses it.
    let s = &sessions[0];
    std::fs::copy(cases_dir().join("blobs_wrap/image.png"), &img).unwrap();
    let out = bin()
        .args(["replay", s.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("changed"));
    // The app's tracking of a movie is no still image's session: replay says what it is.
    let tracking = tmp("tracking.session.json");
    std::fs::write(&tracking, r#"{"format":"topocontour-tracking","movie":{}}"#).unwrap();
    let out = bin()
        .args(["replay", tracking.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("is the tracking of a movie: the app opens it"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// A three-page TIFF stack with a resolution of 2 pixels per µm (as ImageJ writes it):
/// the CLI says it holds three pages and segments page 1, `--page` picks another, a page
/// past the end is one clear error; the CSV gives the pixel size and calibrated areas.
#[test]
fn tiff_stacks_and_pixel_size() {
    use tiff::encoder::{colortype::Gray8, Rational, TiffEncoder};
    use tiff::tags::ResolutionUnit;
    let path = tmp("stack.tif");
    {
        let mut enc = TiffEncoder::new(std::fs::File::create(&path).unwrap()).unwrap();
        // Page k: a dark disk of radius 10 + 5k on a bright background.
        for k in 0..3u32 {
            let (w, h) = (96u32, 96u32);
            let r = 10.0 + 5.0 * k as f64;
            let data: Vec<u8> = (0..w * h)
                .map(|i| {
                    let (x, y) = ((i % w) as f64 + 0.5 - 48.0, (i / w) as f64 + 0.5 - 48.0);
                    if x.hypot(y) < r {
                        40
                    } else {
                        210
                    }
                })
                .collect();
            let mut img = enc.new_image::<Gray8>(w, h).unwrap();
            img.resolution(ResolutionUnit::None, Rational { n: 2, d: 1 });
            img.encoder()
                .write_tag(
                    tiff::tags::Tag::ImageDescription,
                    "ImageJ=1.54\nunit=micron\n",
                )
                .unwrap();
            img.write_data(&data).unwrap();
        }
    }
    let area = |page: Option<&str>| {
        let csv = tmp(&format!("stack-{}.csv", page.unwrap_or("none")));
        let mut args = vec![
            "segment".to_string(),
            path.display().to_string(),
            "--seed".into(),
            "48,48,4".into(),
            "--object".into(),
            "dark".into(),
            "--csv".into(),
            csv.display().to_string(),
        ];
        if let Some(p) = page {
            args.extend(["--page".into(), p.into()]);
        }
        let out = run_ok(bin().args(&args));
        let text = std::fs::read_to_string(&csv).unwrap();
        let row: Vec<String> = text
            .lines()
            .nth(1)
            .unwrap()
            .split(',')
            .map(String::from)
            .collect();
        (row, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (row, stderr) = area(None);
    assert!(stderr.contains("holds 3 pages"), "{stderr}");
    let a1: f64 = row[2].parse().unwrap();
    assert!(
        (a1 - std::f64::consts::PI * 100.0).abs() < 0.1 * std::f64::consts::PI * 100.0,
        "{a1}"
    );
    assert_eq!(row[8], "0.5");
    assert_eq!(row[9], "\"µm\"");
    let calibrated: f64 = row[10].parse().unwrap();
    assert!(
        (calibrated - a1 * 0.25).abs() < 1e-6 * a1,
        "{calibrated} vs {a1}"
    );
    let (row, stderr) = area(Some("3"));
    assert!(!stderr.contains("pages"), "{stderr}");
    let a3: f64 = row[2].parse().unwrap();
    assert!(
        (a3 - std::f64::consts::PI * 400.0).abs() < 0.1 * std::f64::consts::PI * 400.0,
        "{a3}"
    );
    let out = bin()
        .args([
            "segment",
            path.to_str().unwrap(),
            "--seed",
            "48,48,4",
            "--object",
            "dark",
            "--page",
            "4",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("no page 4"), "{err}");
}

/// A wrap over a bright ring: the adaptive engine opens the ring's hole (a `hole_made`
/// event, one hole in the JSON); `--no-new-holes` keeps it filled.
#[test]
fn wrap_opens_a_ring_hole_unless_told_not_to() {
    let img = topocontour::check::ring_image(128, 16.0, 40.0);
    let input = tmp("ring.png");
    img.save(&input).unwrap();
    let holes = |extra: &[&str]| {
        let json = tmp(&format!("ring{}.json", extra.len()));
        run_ok(
            bin()
                .arg("segment")
                .arg(&*input)
                .args(["--wrap", "4", "--object", "bright", "--json"])
                .arg(&*json)
                .args(extra),
        );
        let doc = read_json(&json);
        let contours = doc["contours"].as_array().unwrap();
        contours.iter().filter(|c| c["hole"] == true).count()
    };
    assert_eq!(holes(&[]), 1);
    assert_eq!(holes(&["--no-new-holes"]), 0);
}

/// Objects dropped as smaller than --min-area are said, not silently missing.
#[test]
fn objects_below_the_least_area_are_dropped_with_a_note() {
    let input = tmp("specks.png");
    let mut disks = vec![(60.0, 60.0, 16.0)];
    disks.extend((0..5).map(|k| (14.0 + 20.0 * k as f64, 110.0, 2.0)));
    common::disks_png(&input, 128, 128, &disks);
    let run = |extra: &[&str]| {
        let json = tmp(&format!("specks{}.json", extra.len()));
        let out = run_ok(
            bin()
                .arg("segment")
                .arg(&*input)
                .args([
                    "--object", "dark", "--seed", "60,60,6", "--seed", "14,110,1",
                ])
                .args(["--seed", "34,110,1", "--json"])
                .arg(&*json)
                .args(extra),
        );
        let objects = read_json(&json)["contours"].as_array().unwrap().len();
        (objects, String::from_utf8_lossy(&out.stderr).into_owned())
    };
    let (objects, err) = run(&[]);
    assert_eq!(objects, 1, "{err}");
    assert!(
        err.contains("smaller than --min-area 20 px² dropped"),
        "{err}"
    );
    let (objects, err) = run(&["--min-area", "4"]);
    assert_eq!(objects, 3, "{err}");
    assert!(!err.contains("dropped"), "{err}");
}
