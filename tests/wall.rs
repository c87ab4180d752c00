//! The image rectangle is a wall for every engine: no contour point ever lies outside
//! [0, W] × [0, H], a wrap over nothing collapses, an object cut by the border ends on it,
//! and `converged` is only said of a run that settled.

use topocontour::evolution::{Evolver, Field, Mode, Params, Polarity, Shape};
use topocontour::geometry::Point;

const MODES: [Mode; 3] = [Mode::Adaptive, Mode::Preserve, Mode::Implicit];

fn image(w: usize, h: usize, f: impl Fn(f64, f64) -> f32) -> Field {
    let data = (0..w * h)
        .map(|i| f((i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
        .collect();
    Field::new(w, h, data)
}

fn wrap(w: usize, h: usize, m: f64) -> Shape {
    Shape::Rect {
        min: Point::new(m, m),
        max: Point::new(w as f64 - m, h as f64 - m),
    }
}

/// Runs to the end, checking the wall after every frame; returns the final evolver.
fn run_inside(img: &Field, init: &[Shape], mode: Mode, polarity: Polarity) -> Evolver {
    let params = Params {
        mode,
        polarity,
        ..Params::default()
    };
    let mut ev = Evolver::new(img, init, params).unwrap();
    let (w, h) = (img.width as f64, img.height as f64);
    while !ev.is_finished() {
        ev.step();
        let set = ev.contours();
        for id in set.contour_ids() {
            for p in set.ring_points(id) {
                assert!(
                    (0.0..=w).contains(&p.x) && (0.0..=h).contains(&p.y),
                    "{mode:?}: point {p:?} outside {w}×{h} at frame {}",
                    ev.frames()
                );
            }
        }
        assert!(ev.contours().region_area() <= w * h + 1e-6, "{mode:?}");
    }
    ev
}

#[test]
fn a_wrap_over_a_constant_image_collapses() {
    for polarity in [Polarity::Dark, Polarity::Bright] {
        let img = image(256, 256, |_, _| 0.5);
        for mode in MODES {
            let ev = run_inside(&img, &[wrap(256, 256, 4.0)], mode, polarity);
            assert!(ev.frames() <= 300, "{mode:?}: {} frames", ev.frames());
            assert!(ev.is_converged(), "{mode:?}");
            // The topology-keeping engines keep the one contour they started with
            // (vanishing is a topology change): it collapses to a speck instead.
            let set = ev.contours();
            let kept = usize::from(mode != Mode::Adaptive);
            assert!(set.contour_count() <= kept, "{mode:?} {polarity:?}");
            assert!(
                set.region_area() < 100.0,
                "{mode:?} {polarity:?}: area {}",
                set.region_area()
            );
        }
    }
}

#[test]
fn an_object_cut_by_the_border_ends_on_it() {
    // A dark disk centred 10 px from the left border, radius 60: the part inside the
    // image has area r²(π − acos(d/r)) + d·√(r² − d²).
    let (w, h, cx, cy, r) = (256usize, 256usize, 10.0, 128.0, 60.0);
    let img = image(w, h, |x, y| {
        if (x - cx).hypot(y - cy) < r {
            0.25
        } else {
            0.75
        }
    });
    let inside = r * r * (std::f64::consts::PI - (cx / r).acos()) + cx * (r * r - cx * cx).sqrt();
    for mode in MODES {
        let ev = run_inside(&img, &[wrap(w, h, 4.0)], mode, Polarity::Dark);
        assert!(ev.frames() <= 300, "{mode:?}: {} frames", ev.frames());
        let set = ev.contours();
        assert_eq!(set.contour_count(), 1, "{mode:?}");
        let area = set.region_area();
        assert!(
            (area - inside).abs() < 0.03 * inside,
            "{mode:?}: area {area}, expected {inside}"
        );
        // The contour runs along the border where the disk is cut.
        let id = set.contour_ids().next().unwrap();
        let on_border = set.ring_points(id).iter().filter(|p| p.x < 0.5).count();
        assert!(
            on_border >= 20,
            "{mode:?}: {on_border} points on the border"
        );
    }
}

#[test]
fn a_seed_growing_over_everything_stops_at_the_wall() {
    // Bright everywhere: a bright seed grows until it fills the image, never beyond.
    let img = image(128, 96, |x, y| if x < 8.0 && y < 8.0 { 0.0 } else { 1.0 });
    let seed = [Shape::Disk {
        center: Point::new(64.0, 48.0),
        radius: 6.0,
    }];
    for mode in MODES {
        let ev = run_inside(&img, &seed, mode, Polarity::Bright);
        assert!(ev.frames() <= 300, "{mode:?}: {} frames", ev.frames());
        let area = ev.contours().region_area();
        assert!(area > 0.9 * 128.0 * 96.0, "{mode:?}: area {area}");
    }
}

#[test]
fn a_run_out_of_frames_is_not_converged() {
    let img = image(128, 128, |x, y| {
        if (x - 64.0).hypot(y - 64.0) < 30.0 {
            0.2
        } else {
            0.8
        }
    });
    let params = Params {
        max_frames: 5,
        ..Params::default()
    };
    let mut ev = Evolver::new(&img, &[wrap(128, 128, 2.0)], params).unwrap();
    ev.run();
    assert_eq!(ev.frames(), 5);
    assert!(ev.is_finished() && !ev.is_converged());
}

#[test]
fn huge_or_non_finite_shapes_are_refused_at_once() {
    let img = image(64, 64, |_, _| 0.5);
    for radius in [1e6, 1e30, f64::INFINITY, f64::NAN] {
        let disk = Shape::Disk {
            center: Point::new(32.0, 32.0),
            radius,
        };
        assert!(
            Evolver::new(&img, &[disk], Params::default()).is_err(),
            "{radius}"
        );
    }
    let rect = Shape::Rect {
        min: Point::new(f64::NAN, 0.0),
        max: Point::new(10.0, 10.0),
    };
    assert!(Evolver::new(&img, &[rect], Params::default()).is_err());
}

/// Random hand edits (long drags anywhere, beyond the border too) keep the rings valid
/// and inside the image, in both explicit engines.
#[test]
fn random_hand_edits_keep_rings_valid_and_inside() {
    let img = image(96, 80, |x, y| {
        if (x - 48.0).hypot(y - 40.0) < 20.0 {
            0.2
        } else {
            0.8
        }
    });
    let seeds = [
        Shape::Disk {
            center: Point::new(30.0, 40.0),
            radius: 8.0,
        },
        Shape::Disk {
            center: Point::new(66.0, 40.0),
            radius: 8.0,
        },
        Shape::Rect {
            min: Point::new(10.0, 60.0),
            max: Point::new(86.0, 72.0),
        },
    ];
    for mode in [Mode::Adaptive, Mode::Preserve] {
        let params = Params {
            mode,
            ..Params::default()
        };
        let mut ev = Evolver::new(&img, &seeds, params).unwrap();
        let start = ev.contours().contour_count();
        let mut s = 0x2545_F491_4F6C_DD1Du64;
        for _ in 0..300 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let vs: Vec<u32> = ev.contours().vertices().collect();
            if vs.is_empty() {
                break;
            }
            let v = vs[(s % vs.len() as u64) as usize];
            let to = Point::new(
                (s >> 8) as f64 % 130.0 - 17.0,
                (s >> 24) as f64 % 110.0 - 15.0,
            );
            ev.hand_move(v, to);
            let set = ev.contours();
            set.sanity_check()
                .unwrap_or_else(|e| panic!("{mode:?}: {e}"));
            if mode == Mode::Preserve {
                assert_eq!(set.contour_count(), start, "preserve keeps the topology");
            }
            for id in set.contour_ids() {
                for p in set.ring_points(id) {
                    assert!(
                        (0.0..=96.0).contains(&p.x) && (0.0..=80.0).contains(&p.y),
                        "{p:?}"
                    );
                }
            }
        }
    }
}
