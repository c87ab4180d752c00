//! A taught run's final objects are cut where the boundary class crosses them
//! ([`cut_set_at_necks`]): two rods touching end to end over their full width have no
//! neck in their outline (the tracker's rule alone leaves them whole), but the
//! classifier's boundary band across the contact shows the septum.

use std::sync::Arc;
use topocontour::contours::ContourSet;
use topocontour::evolution::{Evolver, Modality, Mode, Params, Polarity, Shape};
use topocontour::geometry::{signed_area, Aabb, Point};
use topocontour::image::field::Field;
use topocontour::learn::guide::ONE_LEVEL;
use topocontour::track::neck::{cut_set_at_necks, neck_cut};

const W: usize = 96;
const H: usize = 64;

/// A capsule from `x0` to `x1` at height `y`, radius `r`, vertices about 1 px apart,
/// region on the left (positive area).
fn capsule(x0: f64, x1: f64, y: f64, r: f64) -> Vec<Point> {
    let mut pts = Vec::new();
    let steps = (x1 - x0).ceil() as usize;
    for k in 0..steps {
        pts.push(Point::new(x0 + (x1 - x0) * k as f64 / steps as f64, y - r));
    }
    for k in 0..16 {
        let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
        pts.push(Point::new(x1 + r * a.cos(), y + r * a.sin()));
    }
    for k in 0..steps {
        pts.push(Point::new(x1 - (x1 - x0) * k as f64 / steps as f64, y + r));
    }
    for k in 0..16 {
        let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
        pts.push(Point::new(x0 + r * a.cos(), y + r * a.sin()));
    }
    if signed_area(&pts) < 0.0 {
        pts.reverse();
    }
    pts
}

/// P(boundary) as a forest gives it: low inside and outside, high on every rim (within
/// 1.5 px of a capsule's outline), and, with `band`, across the contact at x = 48.
fn boundary(caps: &[(f64, f64, f64, f64)], band: bool) -> Field {
    let mut data = vec![0.05f32; W * H];
    for y in 0..H {
        for x in 0..W {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            for &(x0, x1, cy, r) in caps {
                let dx = (px - px.clamp(x0, x1)).abs();
                let d = dx.hypot(py - cy) - r;
                if d.abs() < 1.5 {
                    data[y * W + x] = 0.7;
                } else if d < 0.0 && band && (px - 48.0).abs() < 2.0 && (cy - 24.0).abs() < 1e-9 {
                    data[y * W + x] = 0.9;
                }
            }
        }
    }
    Field::new(W, H, data)
}

fn set_of(rings: &[Vec<Point>]) -> ContourSet {
    let domain = Aabb {
        min: Point::new(0.0, 0.0),
        max: Point::new(W as f64, H as f64),
    };
    let mut set = ContourSet::new(domain, 2.0);
    for r in rings {
        set.add_ring(r).expect("a simple ring");
    }
    set
}

#[test]
fn rods_merged_end_to_end_are_cut_where_the_boundary_class_crosses_them() {
    // The merged pair (x 14–82 at y 24) and a neighbour 1 px below it.
    let caps = [(14.0, 82.0, 24.0, 6.0), (14.0, 82.0, 37.0, 6.0)];
    let rings: Vec<Vec<Point>> = caps
        .iter()
        .map(|&(a, b, y, r)| capsule(a, b, y, r))
        .collect();
    // The outline alone shows no neck: the tracker's rule keeps it whole.
    let flat = Field::new(W, H, vec![0.5; W * H]);
    assert!(neck_cut(&rings[0], &flat).is_none());

    // Rims only: no septum, nothing cut.
    let mut set = set_of(&rings);
    assert_eq!(cut_set_at_necks(&mut set, &boundary(&caps, false)), 0);
    assert_eq!(set.contour_count(), 2);

    // The band across the contact: the pair is cut there, the neighbour is not.
    let mut set = set_of(&rings);
    assert_eq!(cut_set_at_necks(&mut set, &boundary(&caps, true)), 1);
    assert_eq!(set.contour_count(), 3);
    set.sanity_check().expect("exact simple rings, apart");
    let mut pieces: Vec<(f64, f64, f64)> = set
        .contour_ids()
        .map(|id| {
            let p = set.ring_points(id);
            let (lo, hi) = p
                .iter()
                .fold((f64::MAX, f64::MIN), |(l, h), q| (l.min(q.x), h.max(q.x)));
            let cy = p.iter().map(|q| q.y).sum::<f64>() / p.len() as f64;
            (lo, hi, cy)
        })
        .collect();
    pieces.sort_by(|a, b| a.2.total_cmp(&b.2).then(a.0.total_cmp(&b.0)));
    // Left rod ends at the contact, right rod starts there, the neighbour spans both.
    assert!(
        (pieces[0].0 - 8.0).abs() < 0.5 && (pieces[0].1 - 48.0).abs() < 3.0,
        "{pieces:?}"
    );
    assert!(
        (pieces[1].0 - 48.0).abs() < 3.0 && (pieces[1].1 - 88.0).abs() < 0.5,
        "{pieces:?}"
    );
    assert!(
        pieces[0].1 < pieces[1].0,
        "the pieces are held apart: {pieces:?}"
    );
    assert!(
        (pieces[2].0 - 8.0).abs() < 0.5 && (pieces[2].1 - 88.0).abs() < 0.5,
        "{pieces:?}"
    );
}

/// The cut is made inside the run, in the frame it finishes
/// ([`Evolver::cut_when_finished`]): the app stepping frame by frame and the CLI running
/// to the end ([`Evolver::run`], as `Job::run` drives it) get the same cut objects.
#[test]
fn the_cut_comes_when_the_run_finishes_whether_stepped_or_run() {
    let caps = [(14.0, 82.0, 24.0, 6.0), (14.0, 82.0, 38.0, 5.0)];
    // The rods bright on dark, as a probability image reads.
    let mut data = vec![0.05f32; W * H];
    for y in 0..H {
        for x in 0..W {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            if caps
                .iter()
                .any(|&(x0, x1, cy, r)| (px - px.clamp(x0, x1)).abs().hypot(py - cy) < r)
            {
                data[y * W + x] = 0.95;
            }
        }
    }
    let image = Field::new(W, H, data);
    let seeds: Vec<Shape> = caps
        .iter()
        .map(|&(x0, x1, cy, r)| Shape::Disk {
            center: Point::new((x0 + x1) / 2.0, cy),
            radius: r - 2.0,
        })
        .collect();
    let params = Params {
        mode: Mode::Track,
        polarity: Polarity::Bright,
        modality: Modality::Generic,
        local: false,
        coarsest_side: ONE_LEVEL,
        ..Params::default()
    };
    let line = Arc::new(boundary(&caps, true));
    let rings = |ev: &Evolver| -> Vec<Vec<Point>> {
        let set = ev.contours();
        set.contour_ids().map(|id| set.ring_points(id)).collect()
    };
    let mut uncut = Evolver::new(&image, &seeds, params.clone()).unwrap();
    uncut.run();
    assert_eq!(uncut.contours().contour_count(), 2);

    let mut stepped = Evolver::new(&image, &seeds, params.clone()).unwrap();
    stepped.cut_when_finished(line.clone());
    while !stepped.is_finished() {
        assert_eq!(
            stepped.contours().contour_count(),
            2,
            "no cut before the end"
        );
        stepped.step();
    }
    assert_eq!(stepped.contours().contour_count(), 3, "cut at the contact");
    stepped
        .contours()
        .sanity_check()
        .expect("exact simple rings");

    let mut run = Evolver::new(&image, &seeds, params).unwrap();
    run.cut_when_finished(line);
    run.run();
    assert_eq!(rings(&run), rings(&stepped));
}
