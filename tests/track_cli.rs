//! `topocontour track` on small 16-bit TIFF movies made here: the Cell Tracking Challenge
//! layout it writes, and bad movies refused with one line, exit 2 and no output.

mod common;

use std::path::Path;
use std::process::Command;
use tiff::encoder::{colortype::Gray16, TiffEncoder};

/// The path `name` in a fresh folder of its own, removed with the returned guard.
fn tmp(name: &str) -> common::Scratch {
    common::Scratch::file(name)
}

/// A 16-bit movie in a narrow range (100 background, 260 cells, as a dim camera gives):
/// page t holds a disk at x = 30 + 2t of size `sizes[t]`.
fn movie(path: &Path, sizes: &[(u32, u32)]) {
    let mut enc = TiffEncoder::new(std::fs::File::create(path).unwrap()).unwrap();
    for (t, &(w, h)) in sizes.iter().enumerate() {
        let cx = 30.0 + 2.0 * t as f64;
        let data: Vec<u16> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                if (x - cx).hypot(y - 32.0) < 12.0 {
                    260
                } else {
                    100
                }
            })
            .collect();
        enc.write_image::<Gray16>(w, h, &data).unwrap();
    }
}

/// A 16-bit TIFF movie of `frames` pages of `w`×`h`, pixel (x, y) of page t drawn
/// `value(t, x, y)` at its centre.
fn drawn_movie(
    path: &Path,
    (w, h): (u32, u32),
    frames: usize,
    value: impl Fn(usize, f64, f64) -> u16,
) {
    let mut enc = TiffEncoder::new(std::fs::File::create(path).unwrap()).unwrap();
    for t in 0..frames {
        let data: Vec<u16> = (0..w * h)
            .map(|i| value(t, (i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
            .collect();
        enc.write_image::<Gray16>(w, h, &data).unwrap();
    }
}

fn track(movie: &Path, out: &Path) -> std::process::Output {
    track_with(movie, out, &[])
}

/// `track MOVIE --object bright --ctc OUT` and `more`.
fn track_with(movie: &Path, out: &Path, more: &[&Path]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_topocontour"))
        .args([
            "track",
            &movie.display().to_string(),
            "--object",
            "bright",
            "--ctc",
        ])
        .arg(out)
        .args(more)
        .output()
        .unwrap()
}

/// `track MOVIE --object bright --overlay OVERLAY`.
fn overlaid(movie: &Path, overlay: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_topocontour"))
        .args([
            "track",
            movie.to_str().unwrap(),
            "--object",
            "bright",
            "--overlay",
        ])
        .arg(overlay)
        .output()
        .unwrap()
}

/// Checks that `run` succeeded and wrote `tracks` as OUT/res_track.txt.
fn tracked(run: &std::process::Output, out: &Path, tracks: &str) {
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(out.join("res_track.txt")).unwrap(),
        tracks
    );
}

#[test]
fn a_sixteen_bit_movie_gives_the_ctc_layout() {
    let (m, out) = (tmp("ok.tif"), tmp("ok-res"));
    movie(&m, &[(80, 64); 4]);
    tracked(&track(&m, &out), &out, "1 0 3 0\n");
    for t in 0..4 {
        let mask = image::open(out.join(format!("mask{t:03}.tif")))
            .unwrap()
            .into_luma16();
        assert_eq!(mask.dimensions(), (80, 64));
        let cx = 30 + 2 * t;
        assert_eq!(mask.get_pixel(cx, 32).0[0], 1, "frame {t}");
        assert_eq!(mask.get_pixel(2, 2).0[0], 0);
    }
}

#[test]
fn bad_movies_are_refused_before_any_output() {
    for (name, sizes, says) in [
        ("one", vec![(80, 64)], "holds 1 frame: a movie needs at least two"),
        (
            "sizes",
            vec![(80, 64), (80, 64), (64, 64)],
            // Frames count from 0 here as in the masks; the page, as Fiji counts it.
            "frame 2 (page 3) is 64×64 but frame 0 is 80×64; every frame of a movie must have the same size",
        ),
    ] {
        let (m, out) = (tmp(&format!("{name}.tif")), tmp(&format!("{name}-res")));
        movie(&m, &sizes);
        let run = track(&m, &out);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(says), "{err}");
        assert!(!out.exists(), "{name}: output written");
    }
    // A page that does not decode: the file cut in the middle of the second page's data.
    let (m, out) = (tmp("cut.tif"), tmp("cut-res"));
    movie(&m, &[(80, 64); 3]);
    let bytes = std::fs::read(&m).unwrap();
    std::fs::write(&m, &bytes[..bytes.len() * 5 / 12]).unwrap();
    let run = track(&m, &out);
    assert_eq!(run.status.code(), Some(2));
    assert!(!out.exists());
}

/// Six 80×64 pages of a disk moving right, the first described as ImageJ does
/// (`description`).
fn imagej_movie(path: &Path, description: &str) {
    let mut enc = TiffEncoder::new(std::fs::File::create(path).unwrap()).unwrap();
    for t in 0..6 {
        let cx = 30.0 + 2.0 * t as f64;
        let data: Vec<u16> = (0..80 * 64)
            .map(|i| {
                let (x, y) = ((i % 80) as f64 + 0.5, (i / 80) as f64 + 0.5);
                if (x - cx).hypot(y - 32.0) < 12.0 {
                    260
                } else {
                    100
                }
            })
            .collect();
        let mut page = enc.new_image::<Gray16>(80, 64).unwrap();
        if t == 0 {
            page.encoder()
                .write_tag(tiff::tags::Tag::ImageDescription, description)
                .unwrap();
        }
        page.write_data(&data).unwrap();
    }
}

#[test]
fn an_overlay_named_in_another_format_or_a_device_is_refused() {
    let (m, out) = (tmp("ovl.tif"), tmp("ovl-res"));
    movie(&m, &[(80, 64); 3]);
    for (name, says) in [
        ("o.jpg", "an overlay is written as PNG, not .jpg"),
        ("/dev/null", "not a file name"),
    ] {
        let run = overlaid(&m, Path::new(name));
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(says), "{err}");
    }
    assert!(!Path::new("/dev/null.000.png").exists());
    assert!(!out.exists());
}

/// `--ctc` naming a file, the movie file itself or a link to nothing says what is wrong
/// and leaves it be.
#[test]
fn a_ctc_result_that_is_a_file_or_the_movie_is_refused_as_such() {
    let (m, file) = (tmp("ctcfile.tif"), tmp("ctcfile"));
    movie(&m, &[(80, 64); 3]);
    std::fs::write(&file, b"keep").unwrap();
    let before = std::fs::read(&m).unwrap();
    let link = tmp("ctclink");
    std::os::unix::fs::symlink(tmp("nowhere"), &link).unwrap();
    for (out, says) in [
        (&file, "ctcfile: not a folder"),
        (&m, "ctcfile.tif: that is the movie itself"),
        (&link, "ctclink: a symbolic link to nothing"),
    ] {
        let run = track(&m, out);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{err}");
        assert!(err.contains(says), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    assert_eq!(std::fs::read(&file).unwrap(), b"keep");
    assert_eq!(std::fs::read(&m).unwrap(), before);
}

/// A sequence of overlays written over a longer one leaves none of the earlier frames
/// (also for a name without an extension, whose frames are PNG); files not named as its
/// frames, with another digit count included, stay.
#[test]
fn an_overlay_sequence_over_a_longer_one_leaves_no_frame_of_it() {
    let d = tmp("ovlseq");
    std::fs::create_dir_all(&d).unwrap();
    let (long, short) = (d.join("long.tif"), d.join("short.tif"));
    movie(&long, &[(80, 64); 5]);
    movie(&short, &[(80, 64); 3]);
    for (given, prefix) in [("o.png", "o"), ("p", "p")] {
        let overlay = d.join(given);
        let run = |m: &Path| overlaid(m, &overlay);
        assert!(run(&long).status.success());
        for keep in ["keep", "12", "0009", "2024"] {
            std::fs::write(d.join(format!("{prefix}.{keep}.png")), b"mine").unwrap();
        }
        let out = run(&short);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let mut names: Vec<String> = std::fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(&format!("{prefix}.")))
            .collect();
        names.sort();
        let want = ["000", "0009", "001", "002", "12", "2024", "keep"];
        let want: Vec<String> = want.iter().map(|k| format!("{prefix}.{k}.png")).collect();
        assert_eq!(names, want);
        // Drawn four times the movie's size, so a label does not hide a small cell.
        let frame = image::open(d.join(format!("{prefix}.001.png"))).unwrap();
        assert_eq!((frame.width(), frame.height()), (320, 256));
    }
}

/// A movie named as a frame of the overlay sequence would be replaced (or cleared as an
/// earlier frame): refused before anything is written.
#[test]
fn a_movie_named_as_an_overlay_frame_is_refused() {
    let d = tmp("ovlmovie");
    std::fs::create_dir_all(&d).unwrap();
    let m = d.join("o.007.png");
    movie(&m, &[(80, 64); 3]);
    let before = std::fs::read(&m).unwrap();
    let run = overlaid(&m, &d.join("o.png"));
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("named like the movie's file"), "{err}");
    assert_eq!(std::fs::read(&m).unwrap(), before);
    assert!(!d.join("o.000.png").exists());
}

#[test]
fn levels_beyond_the_pyramid_are_refused() {
    let (m, out) = (tmp("levels.tif"), tmp("levels-res"));
    movie(&m, &[(80, 64); 3]);
    let run = track_with(&m, &out, &[Path::new("--levels"), Path::new("99")]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("--levels 99: give 1 to 4"), "{err}");
    assert!(!out.exists());
}

#[test]
fn hyperstacks_and_folders_of_stacks_are_refused_a_plain_imagej_stack_tracks() {
    let (m, out) = (tmp("hyper.tif"), tmp("hyper-res"));
    imagej_movie(
        &m,
        "ImageJ=1.54f\nimages=6\nslices=3\nframes=2\nhyperstack=true\n",
    );
    let run = track(&m, &out);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("hyperstack of 1 channel(s) × 3 slice(s) × 2 frame(s)"),
        "{err}"
    );
    assert!(!out.exists());
    // tifffile's and OME's descriptions say the same.
    for (name, description, says) in [
        (
            "shaped.tif",
            r#"{"shape": [3, 2, 64, 80]}"#,
            "2 channel(s) × 1 slice(s) × 3 frame(s)",
        ),
        (
            "axes.tif",
            r#"{"shape": [3, 2, 64, 80], "axes": "TZYX"}"#,
            "1 channel(s) × 2 slice(s) × 3 frame(s)",
        ),
        (
            "ome.tif",
            r#"<?xml version="1.0"?><OME><Image><Pixels SizeC="2" SizeT="3" SizeZ="1"/></Image></OME>"#,
            "2 channel(s) × 1 slice(s) × 3 frame(s)",
        ),
    ] {
        let (m, out) = (tmp(name), tmp(&format!("{name}-res")));
        imagej_movie(&m, description);
        let run = track(&m, &out);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(says), "{name}: {err}");
    }
    let (m, out) = (tmp("shaped-t.tif"), tmp("shaped-t-res"));
    imagej_movie(&m, r#"{"shape": [6, 64, 80]}"#);
    tracked(&track(&m, &out), &out, "1 0 5 0\n");
    // ImageJ states a plain stack's pages as slices: that is a movie.
    let (m, out) = (tmp("plain.tif"), tmp("plain-res"));
    imagej_movie(&m, "ImageJ=1.54f\nimages=6\nslices=6\n");
    tracked(&track(&m, &out), &out, "1 0 5 0\n");
    // A folder whose frames are stacks themselves.
    let dir = tmp("stacks");
    std::fs::create_dir_all(&dir).unwrap();
    for k in 0..2 {
        movie(
            &dir.join(format!("f{k}.tif")),
            &[(80, 64), (80, 64), (80, 64)],
        );
    }
    let out = tmp("stacks-res");
    let run = track(&dir, &out);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(
        err.contains("f0.tif holds 3 pages: a folder movie is one"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn outputs_are_checked_before_tracking_and_a_reused_folder_keeps_no_old_masks() {
    // An overlay into a folder that does not exist: refused before anything is written.
    let (m, out) = (tmp("checked.tif"), tmp("checked-res"));
    movie(&m, &[(80, 64); 4]);
    let nowhere = tmp("no-such-folder").join("o.png");
    for frame in [Some("3"), None] {
        let mut more: Vec<&Path> = vec![Path::new("--overlay"), &nowhere];
        if let Some(f) = frame {
            more.extend([Path::new("--overlay-frame"), Path::new(f)]);
        }
        let run = track_with(&m, &out, &more);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("does not exist"), "{err}");
        assert!(
            !out.exists(),
            "masks written before the overlay was refused"
        );
    }
    // A folder holding a longer earlier result: its masks past this movie's end go.
    let long = tmp("long.tif");
    movie(&long, &[(80, 64); 6]);
    tracked(&track(&long, &out), &out, "1 0 5 0\n");
    std::fs::write(out.join("notes.txt"), "kept").unwrap();
    tracked(&track(&m, &out), &out, "1 0 3 0\n");
    assert_eq!(
        common::names(&out),
        [
            "mask000.tif",
            "mask001.tif",
            "mask002.tif",
            "mask003.tif",
            "notes.txt",
            "res_track.txt"
        ]
    );
}

#[test]
fn negative_values_get_their_own_message_not_a_flag_error() {
    let (m, out) = (tmp("negative.tif"), tmp("negative-res"));
    movie(&m, &[(80, 64); 3]);
    for (flag, value, says) in [
        ("--shrink", "-1", "--shrink must be a number ≥ 0"),
        ("--seed", "-5,10,3", "lies outside"),
        ("--rect", "-1,0,10,10", "is not inside"),
    ] {
        let run = track_with(&m, &out, &[Path::new(flag), Path::new(value)]);
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{flag}: {err}");
        assert!(err.contains(says), "{flag}: {err}");
        assert!(!out.exists(), "{flag}: output written");
    }
    // --overlay-frame names a frame of --overlay: alone it is a usage error.
    let run = track_with(&m, &out, &[Path::new("--overlay-frame"), Path::new("1")]);
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("--overlay"));
}

/// A capsule: the ends of its axis and its radius (a disk when they meet).
type Capsule = ((f64, f64), (f64, f64), f64);

/// A 16-bit 96×64 movie, page t the capsules `pages[t]` (260) on a dim ground (100).
fn capsule_movie(path: &Path, pages: &[Vec<Capsule>]) {
    let (w, h) = (96u32, 64u32);
    let mut enc = TiffEncoder::new(std::fs::File::create(path).unwrap()).unwrap();
    for caps in pages {
        let data: Vec<u16> = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                let inside = caps.iter().any(|&((ax, ay), (bx, by), r)| {
                    let (dx, dy) = (bx - ax, by - ay);
                    let n2 = dx * dx + dy * dy;
                    let t = if n2 > 0.0 {
                        (((x - ax) * dx + (y - ay) * dy) / n2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    (x - ax - t * dx).hypot(y - ay - t * dy) <= r
                });
                if inside {
                    260
                } else {
                    100
                }
            })
            .collect();
        enc.write_image::<Gray16>(w, h, &data).unwrap();
    }
}

#[test]
fn a_division_the_next_frame_takes_back_is_written_as_one_cell() {
    // A nucleus parts in frame 3 (two lobes 6 px apart) and is one dumbbell again from
    // frame 4 on: no division, and frame 3's mask gives both lobes the mother's label.
    let disk = |x: f64, r: f64| ((x, 32.0), (x, 32.0), r);
    let mut pages: Vec<Vec<Capsule>> = [3.0, 4.0, 5.0]
        .map(|h| vec![((48.0 - h, 32.0), (48.0 + h, 32.0), 10.0)])
        .into();
    pages.push(vec![disk(37.0, 8.0), disk(59.0, 8.0)]);
    for _ in 0..3 {
        pages.push(vec![
            disk(40.0, 8.0),
            disk(56.0, 8.0),
            ((40.0, 32.0), (56.0, 32.0), 5.0),
        ]);
    }
    let (m, out, csv) = (tmp("parts.tif"), tmp("parts-res"), tmp("parts.csv"));
    capsule_movie(&m, &pages);
    let run = track_with(&m, &out, &[Path::new("--tracks-csv"), &csv]);
    tracked(&run, &out, "1 0 6 0\n");
    let mask = image::open(out.join("mask003.tif")).unwrap().into_luma16();
    assert_eq!(mask.get_pixel(37, 32).0[0], 1);
    assert_eq!(mask.get_pixel(59, 32).0[0], 1);
    assert_eq!(mask.get_pixel(48, 32).0[0], 0);
    // One row per cell and frame: the mother in two pieces is one row.
    let rows = std::fs::read_to_string(&csv).unwrap();
    let frame3: Vec<&str> = rows
        .lines()
        .filter(|l| l.split(',').nth(1) == Some("3"))
        .collect();
    assert_eq!(frame3.len(), 1, "{rows}");
    assert!(frame3[0].starts_with("1,3,"), "{rows}");
    // Its area is the mask's: the pixels labelled 1.
    let pixels = mask.pixels().filter(|p| p.0[0] == 1).count();
    assert_eq!(
        frame3[0].split(',').nth(2),
        Some(format!("{pixels}.00").as_str())
    );
}

/// A `--ctc` folder is made, but not a tree of them: its own folder must exist, as a file
/// output's must (a mistyped path is an error, not new folders).
#[test]
fn a_ctc_folder_in_a_missing_folder_is_refused() {
    let (m, out) = (tmp("tree.tif"), tmp("missing"));
    movie(&m, &[(80, 64); 2]);
    let run = track(&m, &out.join("a").join("res"));
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("missing/a does not exist"), "{err}");
    assert!(!out.exists());
    tracked(&track(&m, &out), &out, "1 0 1 0\n");
}

/// What `track MOVIE ARGS --ctc OUT` says on stderr (it must succeed).
fn notes_of(movie: &Path, args: &[&str]) -> String {
    let out = tmp("notes");
    let run = Command::new(env!("CARGO_BIN_EXE_topocontour"))
        .arg("track")
        .arg(movie)
        .args(args)
        .arg("--ctc")
        .arg(&*out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&run.stderr).into_owned();
    assert!(run.status.success(), "{err}");
    err
}

/// Cells tracked with the wrong `--object` are the background cut into regions: the run
/// says so, and says nothing when the polarity is right.
#[test]
fn cells_covering_most_of_frame_0_suggest_the_other_object() {
    let m = tmp("polarity.tif");
    movie(&m, &[(80, 64); 2]);
    let run = |object: &str| notes_of(&m, &["--object", object]);
    let wrong = run("dark");
    assert!(
        wrong.contains("if the cells are not darker than their background, give --object bright"),
        "{wrong}"
    );
    let right = run("bright");
    assert!(!right.contains("note"), "{right}");
    assert!(right.contains("1 track, 0 divisions"), "{right}");
}

/// A later frame whose cells cover most of it is said once, with what to check: a bright
/// cell that spreads over the frame from frame 2 on.
#[test]
fn cells_covering_most_of_a_later_frame_are_said() {
    let m = tmp("crowded.tif");
    drawn_movie(&m, (80, 64), 4, |t, x, y| {
        let inside = if t < 2 {
            (x - 40.0).hypot(y - 32.0) < 12.0
        } else {
            x > 2.0 && x < 78.0 && y > 2.0 && y < 62.0
        };
        if inside {
            260
        } else {
            100
        }
    });
    let notes = notes_of(&m, &["--object", "bright"]);
    assert!(
        notes.contains("note: frame 2's cells cover")
            && notes
                .contains("the background is being cut into cells; check --object and --modality"),
        "{notes}"
    );
    assert_eq!(
        notes.matches("cells cover").count(),
        1,
        "said once: {notes}"
    );
}

/// Dark cells in a bright halo tracked as generic images: the run says they look like
/// phase contrast; told so, it says nothing.
#[test]
fn dark_cells_in_a_bright_halo_suggest_phase_contrast() {
    let m = tmp("halo.tif");
    drawn_movie(&m, (96, 80), 3, |t, x, y| {
        let d = [(30.0 + t as f64, 30.0), (64.0, 50.0 - t as f64)]
            .iter()
            .map(|&(cx, cy)| (x - cx).hypot(y - cy))
            .fold(f64::INFINITY, f64::min);
        match d {
            d if d < 9.0 => 300,
            d if d < 11.0 => 1500,
            _ => 1000,
        }
    });
    let run = |modality: &str| notes_of(&m, &["--object", "dark", "--modality", modality]);
    let generic = run("generic");
    assert!(
        generic.contains("as in phase contrast; --modality phase-contrast"),
        "{generic}"
    );
    let phase = run("phase-contrast");
    assert!(!phase.contains("note"), "{phase}");
    assert!(phase.contains("2 tracks"), "{phase}");
}
