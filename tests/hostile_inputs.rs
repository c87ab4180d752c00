//! Inputs that once hung the engine or the loader (issue: no input may hang, crash or
//! exhaust memory, second round): each must finish within a deadline with a result or a
//! clear refusal.

mod common;

use std::sync::mpsc;
use std::time::Duration;
use topocontour::evolution::{Edit, Evolver, Field, Params, Shape};
use topocontour::io::load_image_page;
use topocontour::Point;

/// Runs `f` on a thread and fails the test when it takes longer than `secs`.
fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .unwrap_or_else(|_| panic!("still running after {secs} s"))
}

/// The path `name` in a fresh folder of its own, removed with the returned guard.
fn tmp(name: &str) -> common::Scratch {
    common::Scratch::file(name)
}

/// A 64² float image: a dark disc on a bright background, in arbitrary units.
fn float_page(nan_column: Option<usize>) -> Vec<f32> {
    (0..64 * 64)
        .map(|i| {
            let (x, y) = (i % 64, i / 64);
            if Some(x) == nan_column {
                return f32::NAN;
            }
            let inside = (x as f32 - 32.0).powi(2) + (y as f32 - 32.0).powi(2) < 200.0;
            if inside {
                1000.0
            } else {
                3000.0
            }
        })
        .collect()
}

#[test]
fn float_tiff_pages_decode_alike_and_nan_never_reaches_the_engine() {
    let path = tmp("float.tif");
    {
        let file = std::fs::File::create(&path).unwrap();
        let mut enc = tiff::encoder::TiffEncoder::new(file).unwrap();
        for nan in [None, Some(5)] {
            enc.write_image::<tiff::encoder::colortype::Gray32Float>(64, 64, &float_page(nan))
                .unwrap();
        }
    }
    for page in 0..2 {
        let (image, info) = load_image_page(&path, page).unwrap();
        assert_eq!(info.pages, 2);
        assert!(image
            .data
            .iter()
            .all(|v| v.is_finite() && (0.0..=1.0).contains(v)));
        // Scaled from the page's own range: the disc is 0, the background 1.
        assert_eq!(image.data[32 * 64 + 32], 0.0);
        assert_eq!(image.data[2 * 64 + 60], 1.0);
        let wrap = [Shape::Rect {
            min: Point::new(2.0, 2.0),
            max: Point::new(62.0, 62.0),
        }];
        let contours = within(20, move || {
            let mut ev = Evolver::new(&image, &wrap, Params::default()).unwrap();
            ev.run();
            ev.filter_clutter();
            ev.contours().contour_count()
        });
        // The NaN column reads as neither object nor background: one disc on each page.
        assert_eq!(contours, 1, "page {page}");
    }
}

/// A little-endian TIFF of `n` one-pixel-wide images whose directories all share one
/// strip table of `strips` entries.
fn many_directories(n: usize, strips: u32) -> Vec<u8> {
    let mut out = b"II*\0\0\0\0\0".to_vec();
    let data = out.len() as u32;
    out.push(0x80);
    let table = out.len() as u32;
    out.extend((0..strips).flat_map(|_| data.to_le_bytes()));
    let counts = out.len() as u32;
    out.extend((0..strips).flat_map(|_| 1u32.to_le_bytes()));
    let first = out.len() as u32;
    out[4..8].copy_from_slice(&first.to_le_bytes());
    let entries: [(u16, u16, u32, u32); 9] = [
        (256, 3, 1, 1),
        (257, 4, 1, strips),
        (258, 3, 1, 8),
        (259, 3, 1, 1),
        (262, 3, 1, 1),
        (273, 4, strips, table),
        (277, 3, 1, 1),
        (278, 3, 1, 1),
        (279, 4, strips, counts),
    ];
    for i in 0..n {
        common::tiff_directory(&mut out, &entries, i + 1 == n);
    }
    out
}

#[test]
fn thousands_of_directories_sharing_a_strip_table_are_counted_quickly() {
    // Counting pages by loading every strip table took 20 s for 20,000 directories of
    // 60,000 strips; the directories alone take milliseconds.
    let path = tmp("directories.tif");
    std::fs::write(&path, many_directories(20_000, 200_000)).unwrap();
    let info = within(10, move || load_image_page(&path, 0).map(|(_, info)| info));
    assert_eq!(info.unwrap().pages, 20_000);
}

fn two_disks() -> Evolver {
    let image = Field::new(256, 192, vec![0.5; 256 * 192]);
    let disk = |x: f64| Shape::Disk {
        center: Point::new(x, 96.0),
        radius: 30.0,
    };
    Evolver::new(&image, &[disk(70.0), disk(180.0)], Params::default()).unwrap()
}

#[test]
fn a_wide_brush_costs_about_what_a_narrow_one_does() {
    // Pushing vertices a whole radius at once cascaded: 40 px took 8 s, 60 px minutes.
    let events = within(20, || {
        let mut ev = two_disks();
        let events = ev.brush(Point::new(70.0, 96.0), Point::new(120.0, 96.0), 80.0);
        ev.contours().sanity_check().unwrap();
        events
    });
    assert!(
        !events.is_empty(),
        "the brush from inside merges the two disks"
    );
}

#[test]
fn a_brush_stroke_from_far_outside_is_clipped_to_the_image() {
    let count = within(20, || {
        let mut ev = two_disks();
        ev.brush(Point::new(-1e9, 96.0), Point::new(1e9, 96.0), 6.0);
        ev.contours().sanity_check().unwrap();
        ev.contours().contour_count()
    });
    // A stroke from outside across both disks cuts each in two.
    assert_eq!(count, 4);
}

#[test]
fn a_session_brush_no_user_could_make_is_refused() {
    let mut ev = two_disks();
    for radius in [1e9, f64::NAN, -1.0] {
        let edit = Edit::Brush {
            frame: 0,
            from: Point::new(10.0, 10.0),
            to: Point::new(20.0, 20.0),
            radius,
        };
        assert!(ev.redo_edit(&edit).is_err(), "radius {radius}");
    }
    let drag = Edit::Drag {
        frame: 0,
        vertex: 0,
        to: Point::new(f64::INFINITY, 0.0),
    };
    assert!(ev.redo_edit(&drag).is_err());
}

#[test]
fn a_polygon_of_200000_corners_is_set_up_in_near_linear_time() {
    // 100,000 corners on one circle took 9.7 s; 200,000 never finished.
    let count = within(20, || {
        let image = Field::new(256, 192, vec![0.5; 256 * 192]);
        let n = 200_000;
        let corners = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                Point::new(128.0 + 80.0 * a.cos(), 96.0 + 80.0 * a.sin())
            })
            .collect();
        let ev = Evolver::new(&image, &[Shape::Polygon(corners)], Params::default()).unwrap();
        ev.contours().sanity_check().unwrap();
        ev.contours().contour_count()
    });
    assert_eq!(count, 1);
}

#[test]
fn numbers_no_user_could_give_are_refused_before_anything_is_allocated() {
    let image = Field::new(64, 48, vec![0.5; 64 * 48]);
    let seed = [Shape::Disk {
        center: Point::new(32.0, 24.0),
        radius: 8.0,
    }];
    // A local radius of 1e300 panicked with a capacity overflow; 1e5 took 4.8 GB.
    for r in [1e300, 1e19, 1e5, 0.5] {
        let p = Params {
            local_radius: Some(r),
            ..Params::default()
        };
        let err = Evolver::new(&image, &seed, p).err().expect("refused");
        assert!(err.to_string().contains("local_radius"), "{err}");
    }
    // Weights of 1e308 never finished a frame.
    let mut p = Params::default();
    p.weights.region = 1e308;
    assert!(Evolver::new(&image, &seed, p).is_err());
    // A rectangle or polygon with a corner at 1e300 allocated without bound.
    let far = Point::new(1e300, 10.0);
    for shape in [
        Shape::Rect {
            min: Point::new(0.0, 0.0),
            max: far,
        },
        Shape::Polygon(vec![Point::new(0.0, 0.0), far, Point::new(0.0, 40.0)]),
    ] {
        let err = Evolver::new(&image, &[shape], Params::default()).err();
        assert!(err.unwrap().to_string().contains("farther"));
    }
}

#[cfg(unix)]
#[test]
fn an_image_too_large_for_the_memory_left_is_refused_in_one_line() {
    // A 16000² PNG aborted at 7.45 GB; the run is now estimated and refused before it
    // starts. Here the address space is limited to 1.5 GB and the image needs about 1.7.
    let path = tmp("large.png");
    image::GrayImage::from_pixel(6000, 6000, image::Luma([128u8]))
        .save(&path)
        .unwrap();
    let out = within(60, move || {
        std::process::Command::new("sh")
            .arg("-c")
            .arg("ulimit -v 1500000; exec \"$0\" \"$@\"")
            .arg(env!("CARGO_BIN_EXE_topocontour"))
            .args([
                "segment",
                path.to_str().unwrap(),
                "--wrap",
                "4",
                "--object",
                "dark",
            ])
            .output()
            .unwrap()
    });
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("crop it into tiles"), "{err}");
}
