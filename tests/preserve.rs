//! The topology-keeping engines — preserve (seed 004) and implicit (seed 000) — against
//! the adaptive one on constructed images.

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

/// A wide ellipse-like slab, and seeds at x = 40 and `x2` on its axis.
fn slab_and_seeds(x2: f64) -> (Field, [Shape; 2]) {
    let img = image(160, 80, |x, y| {
        ((x - 80.0) / 70.0).powi(2) + ((y - 40.0) / 28.0).powi(2) < 1.0
    });
    let seed = |x: f64| Shape::Disk {
        center: Point::new(x, 40.0),
        radius: 4.0,
    };
    (img, [seed(40.0), seed(x2)])
}

/// Vertices of the first contour within a pixel of the second: the contact line.
fn contact(ev: &Evolver) -> Vec<Point> {
    let s = ev.contours();
    let ids: Vec<_> = s.contour_ids().collect();
    let (a, b) = (s.ring_points(ids[0]), s.ring_points(ids[1]));
    a.iter()
        .copied()
        .filter(|p| b.iter().any(|q| p.dist(*q) < 1.0))
        .collect()
}

#[test]
fn two_seeds_in_one_object_merge_or_stop_apart() {
    let (img, seeds) = slab_and_seeds(120.0);
    assert_eq!(counts(&run(&img, &seeds, Mode::Adaptive)), (1, 0));
    let kept = run(&img, &seeds, Mode::Preserve);
    assert_eq!(counts(&kept), (2, 0));
    assert!(kept.events().is_empty());
    let gap = min_gap(&kept);
    assert!(gap > 0.0 && gap <= 1.0, "gap {gap}");

    let imp = run(&img, &seeds, Mode::Implicit);
    assert_eq!(counts(&imp), (2, 0));
    assert!(imp.events().is_empty());
    let gap = min_gap(&imp);
    assert!(gap > 0.0 && gap <= 1.0, "implicit gap {gap}");
    // The contact line lies on the true midline x = 80 (equal seeds, symmetric object)
    // within half a pixel.
    let line = contact(&imp);
    assert!(line.len() >= 20, "contact line of {} vertices", line.len());
    let worst = line.iter().map(|p| (p.x - 80.0).abs()).fold(0.0, f64::max);
    assert!(worst <= 0.5, "contact line {worst} px off the midline");
}

#[test]
fn implicit_contact_line_follows_arrival_times() {
    // Seeds at different distances from the middle: the fronts meet where their arrival
    // times are equal, halfway between the seeds' edges (x = (44 + 100) / 2 = 72).
    let (img, seeds) = slab_and_seeds(104.0);
    let imp = run(&img, &seeds, Mode::Implicit);
    assert_eq!(counts(&imp), (2, 0));
    // On the axis y = 40 the contact point is where the distances from both seed edges
    // agree; away from it the line bends, so look near the axis only.
    let on_axis: Vec<f64> = contact(&imp)
        .iter()
        .filter(|p| (p.y - 40.0).abs() < 1.0)
        .map(|p| p.x)
        .collect();
    assert!(!on_axis.is_empty());
    for x in on_axis {
        assert!((x - 72.0).abs() <= 1.0, "contact at x = {x}");
    }
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
    let imp = run(&img, &seed, Mode::Implicit);
    assert_eq!(counts(&imp), (1, 0));
    assert!(
        imp.held_contacts() > 0,
        "the slit is where the ring would have closed"
    );
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
    assert!(
        kept.held_contacts() > 0,
        "preserve says where it held fronts apart"
    );
    let imp = run(&img, &wrap, Mode::Implicit);
    assert_eq!(counts(&imp), (1, 0));
    assert!(imp.held_contacts() > 0);
    // The one contour still hugs both blobs: most of its area is theirs.
    let blobs = 2.0 * std::f64::consts::PI * 400.0;
    let area = imp.contours().region_area();
    assert!(
        area > 0.9 * blobs && area < 1.3 * blobs,
        "area {area} vs {blobs}"
    );
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
                    wall: seed % 3 == 0,
                },
            );
            set.move_vertex_preserving(v, to, 0.1).unwrap();
            set.sanity_check().unwrap();
            assert_eq!(ring_kinds(&set), kinds, "seed {seed}");
        }
    }
}
