//! Topology-preserving mode (seed 004) against the adaptive one on constructed images.

use topocontour::evolution::{Evolver, Field, Mode, Params, Polarity, Shape};
use topocontour::Point;

/// A dark image object (value 0.25 on 0.75) given by `inside(x, y)` at pixel centres,
/// lightly blurred.
fn image(w: usize, h: usize, inside: impl Fn(f64, f64) -> bool) -> Field {
    let data = (0..w * h)
        .map(|i| {
            if inside((i % w) as f64 + 0.5, (i / w) as f64 + 0.5) {
                0.25
            } else {
                0.75
            }
        })
        .collect();
    Field::new(w, h, data).blur5()
}

fn run(img: &Field, init: &[Shape], mode: Mode) -> Evolver {
    let mut ev = Evolver::new(
        img,
        init,
        Params {
            mode,
            polarity: Polarity::Dark,
            ..Params::default()
        },
    )
    .unwrap();
    ev.run();
    ev.contours().sanity_check().unwrap();
    ev
}

fn counts(ev: &Evolver) -> (usize, usize) {
    let s = ev.contours();
    let holes = s.contour_ids().filter(|&id| s.is_hole(id)).count();
    (s.contour_count() - holes, holes)
}

fn min_gap(ev: &Evolver) -> f64 {
    let s = ev.contours();
    let ids: Vec<_> = s.contour_ids().collect();
    let (a, b) = (s.ring_points(ids[0]), s.ring_points(ids[1]));
    a.iter()
        .flat_map(|&p| (0..b.len()).map(move |i| (p, i)))
        .map(|(p, i)| topocontour::geometry::point_segment_distance(p, b[i], b[(i + 1) % b.len()]))
        .fold(f64::MAX, f64::min)
}

#[test]
fn two_seeds_in_one_object_merge_or_stop_apart() {
    // A wide ellipse-like slab; two seeds near its ends.
    let img = image(160, 80, |x, y| {
        ((x - 80.0) / 70.0).powi(2) + ((y - 40.0) / 28.0).powi(2) < 1.0
    });
    let seeds = [
        Shape::Disk {
            center: Point::new(40.0, 40.0),
            radius: 4.0,
        },
        Shape::Disk {
            center: Point::new(120.0, 40.0),
            radius: 4.0,
        },
    ];
    assert_eq!(counts(&run(&img, &seeds, Mode::Adaptive)), (1, 0));
    let kept = run(&img, &seeds, Mode::Preserve);
    assert_eq!(counts(&kept), (2, 0));
    assert!(kept.events().is_empty());
    let gap = min_gap(&kept);
    assert!(gap > 0.0 && gap <= 1.0, "gap {gap}");
}

#[test]
fn a_seed_in_a_ring_makes_a_hole_only_when_adaptive() {
    let img = image(128, 128, |x, y| {
        let r = ((x - 64.0).powi(2) + (y - 64.0).powi(2)).sqrt();
        (20.0..44.0).contains(&r)
    });
    let seed = [Shape::Disk {
        center: Point::new(64.0, 32.0),
        radius: 4.0,
    }];
    assert_eq!(counts(&run(&img, &seed, Mode::Adaptive)), (1, 1));
    assert_eq!(counts(&run(&img, &seed, Mode::Preserve)), (1, 0));
}

#[test]
fn a_wrap_cannot_split_when_preserving() {
    let img = image(160, 100, |x, y| {
        ((x - 45.0).powi(2) + (y - 50.0).powi(2)).sqrt() < 20.0
            || ((x - 115.0).powi(2) + (y - 50.0).powi(2)).sqrt() < 20.0
    });
    let wrap = [Shape::Rect {
        min: Point::new(5.0, 5.0),
        max: Point::new(155.0, 95.0),
    }];
    assert_eq!(counts(&run(&img, &wrap, Mode::Adaptive)), (2, 0));
    let kept = run(&img, &wrap, Mode::Preserve);
    assert_eq!(counts(&kept), (1, 0));
    assert!(kept.events().is_empty());
}

/// Random moves through `move_vertex_preserving` never change the rings' topology and
/// keep every invariant.
#[test]
fn preserving_moves_never_change_topology() {
    use topocontour::check::{draw_target, random_rings, ring_kinds, MoveMix, Rng};
    use topocontour::contours::BroadPhaseKind;
    for seed in 0..20u64 {
        let mut rng = Rng(seed);
        let mut set = random_rings(&mut rng, 4, 6.0);
        let kinds = ring_kinds(&set);
        for _ in 0..500 {
            let v = loop {
                let v = rng.below(set.vertex_capacity()) as u32;
                if set.is_alive(v) {
                    break v;
                }
            };
            let to = draw_target(
                &set,
                v,
                &mut rng,
                MoveMix {
                    lattice: seed % 2 == 0,
                    broad: BroadPhaseKind::Bins,
                },
            );
            set.move_vertex_preserving(v, to, 0.1).unwrap();
            set.sanity_check().unwrap();
            assert_eq!(ring_kinds(&set), kinds, "seed {seed}");
        }
    }
}
