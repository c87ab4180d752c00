//! The cases of seed 003's Figure 2, (a)–(g), as polygon moves with hand-computed
//! results. Each asserts the rings (count, holes), the events and the area.

use topocontour::{Aabb, ContourSet, MoveError, Point, TopologyEvent};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn set_with(rings: &[&[(f64, f64)]]) -> ContourSet {
    let dom = Aabb {
        min: p(-20.0, -20.0),
        max: p(80.0, 80.0),
    };
    let mut s = ContourSet::new(dom, 70.0);
    for r in rings {
        let pts: Vec<Point> = r.iter().map(|&(x, y)| p(x, y)).collect();
        s.add_ring(&pts).expect("valid ring");
    }
    s.sanity_check().unwrap();
    s
}

/// The vertex at exactly `at`.
fn vertex_at(s: &ContourSet, at: (f64, f64)) -> u32 {
    s.vertices()
        .find(|&v| s.position(v) == p(at.0, at.1))
        .expect("vertex exists")
}

fn shoelace(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len();
    0.5 * (0..n)
        .map(|i| pts[i].0 * pts[(i + 1) % n].1 - pts[(i + 1) % n].0 * pts[i].1)
        .sum::<f64>()
}

fn holes(s: &ContourSet) -> usize {
    s.contour_ids().filter(|&id| s.is_hole(id)).count()
}

fn moved(s: &mut ContourSet, from: (f64, f64), to: (f64, f64)) -> Vec<TopologyEvent> {
    let v = vertex_at(s, from);
    let ev = s.move_vertex(v, p(to.0, to.1)).expect("move accepted");
    s.sanity_check().unwrap();
    ev
}

const SQUARE: &[(f64, f64)] = &[(10.0, 10.0), (30.0, 10.0), (30.0, 30.0), (10.0, 30.0)];

#[test]
fn figure_2a_additive_motion_grows_the_region() {
    let mut s = set_with(&[SQUARE]);
    let ev = moved(&mut s, (30.0, 10.0), (40.0, 0.0));
    assert!(ev.is_empty());
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(s.region_area(), 600.0);
}

#[test]
fn figure_2b_subtractive_motion_shrinks_the_region() {
    let mut s = set_with(&[SQUARE]);
    let ev = moved(&mut s, (30.0, 10.0), (20.0, 20.0));
    assert!(ev.is_empty());
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(s.region_area(), 200.0);
}

#[test]
fn figure_2c_bow_tie_adds_and_subtracts_at_once() {
    let mut s = set_with(&[SQUARE]);
    let mr = topocontour::MotionRegion::new(
        p(10.0, 10.0),
        p(30.0, 10.0),
        p(30.0, 30.0),
        Some(p(40.0, 25.0)),
    );
    assert!(mr.is_bow_tie());
    let ev = moved(&mut s, (30.0, 10.0), (40.0, 25.0));
    assert!(ev.is_empty());
    // 400 − triangle (p, z, o) of 100 + triangle (z, q, n) of 50.
    assert_eq!(s.region_area(), 350.0);
    assert!(!s.region_contains(p(29.0, 11.0)));
    assert!(s.region_contains(p(32.0, 25.0)));
}

#[test]
fn figure_2d_crossing_splits_a_contour() {
    // A block with a notch from the top; its tip is pulled down through the bottom edge.
    let mut s = set_with(&[&[
        (0.0, 0.0),
        (60.0, 0.0),
        (60.0, 20.0),
        (35.0, 20.0),
        (30.0, 11.0),
        (25.0, 20.0),
        (0.0, 20.0),
    ]]);
    let id = s.contour_ids().next().unwrap();
    let ev = moved(&mut s, (30.0, 11.0), (30.0, -5.0));
    assert_eq!((s.contour_count(), holes(&s)), (2, 0));
    assert_eq!(ev.len(), 1);
    assert!(matches!(ev[0], TopologyEvent::Split { from, .. } if from == id));
    assert!((s.region_area() - 1080.0).abs() < 1e-9);
    for c in s.contour_ids() {
        assert!((s.signed_area(c) - 540.0).abs() < 1e-9);
    }
}

#[test]
fn figure_2e_wrap_around_makes_a_hole() {
    // A "C" open to the right; its lower tip swings up across the upper arm.
    let mut s = set_with(&[&[
        (0.0, 0.0),
        (40.0, 0.0),
        (40.0, 10.0),
        (10.0, 10.0),
        (10.0, 30.0),
        (40.0, 30.0),
        (40.0, 40.0),
        (0.0, 40.0),
    ]]);
    let ev = moved(&mut s, (40.0, 10.0), (42.0, 32.0));
    // Two rings: the outer one and the new hole.
    assert_eq!((s.contour_count(), holes(&s)), (2, 1));
    assert_eq!(ev.len(), 1);
    assert!(matches!(ev[0], TopologyEvent::HoleMade { .. }));
    // q→n meets x = 40 at y = 30.625 and y = 30 at x = 42 − 64/22.
    let x1 = 42.0 - 64.0 / 22.0;
    let outer = shoelace(&[
        (0.0, 0.0),
        (40.0, 0.0),
        (42.0, 32.0),
        (40.0, 30.625),
        (40.0, 40.0),
        (0.0, 40.0),
    ]);
    let hole = shoelace(&[(10.0, 10.0), (10.0, 30.0), (x1, 30.0)]);
    assert!(hole < 0.0);
    assert!((s.region_area() - (outer + hole)).abs() < 1e-9);
    assert!(!s.region_contains(p(15.0, 25.0)));
    assert!(
        s.region_contains(p(39.9, 30.2)),
        "the cut-off corner of the arm stays in the region"
    );
}

#[test]
fn figure_2e_crossing_merges_two_contours() {
    let mut s = set_with(&[
        &[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)],
        &[(20.0, 0.0), (30.0, 0.0), (30.0, 10.0), (20.0, 10.0)],
    ]);
    let ev = moved(&mut s, (10.0, 0.0), (25.0, 5.0));
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(ev.len(), 1);
    assert!(matches!(ev[0], TopologyEvent::Merge { .. }));
    let expect = shoelace(&[
        (0.0, 0.0),
        (20.0, 4.0),
        (20.0, 0.0),
        (30.0, 0.0),
        (30.0, 10.0),
        (20.0, 10.0),
        (20.0, 20.0 / 3.0),
        (10.0, 10.0),
        (0.0, 10.0),
    ]);
    assert!((s.region_area() - expect).abs() < 1e-9);
}

#[test]
fn figure_2e_crossing_into_a_hole_removes_it() {
    // Square annulus; the middle of the bottom side is pushed up through the hole's floor.
    let mut s = set_with(&[
        &[
            (0.0, 0.0),
            (15.0, 0.0),
            (30.0, 0.0),
            (30.0, 30.0),
            (0.0, 30.0),
        ],
        &[(10.0, 10.0), (10.0, 20.0), (20.0, 20.0), (20.0, 10.0)],
    ]);
    assert_eq!(holes(&s), 1);
    let ev = moved(&mut s, (15.0, 0.0), (15.0, 14.0));
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(ev.len(), 1);
    assert!(matches!(
        ev[0],
        TopologyEvent::HoleGone { into: Some(_), .. }
    ));
    // 800 − (triangle of 210 minus its part already in the hole, 0.5 · 8.5714… · 4).
    let in_hole = 0.5 * (30.0 - 2.0 * 150.0 / 14.0) * 4.0;
    assert!((s.region_area() - (800.0 - 210.0 + in_hole)).abs() < 1e-9);
}

#[test]
fn figure_2f_single_point_crossing_changes_no_topology() {
    // o swings so that q→n crosses the edge before p once: one crossing, a twisted loop
    // that Directive 1 deletes, and still one contour.
    let mut s = set_with(&[&[
        (0.0, 0.0),
        (20.0, 0.0),
        (20.0, 20.0),
        (10.0, 20.0),
        (0.0, 20.0),
    ]]);
    let ev = moved(&mut s, (20.0, 20.0), (10.0, -10.0));
    assert!(ev.is_empty());
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert!((s.region_area() - 200.0).abs() < 1e-9);
    assert!(!s.region_contains(p(12.0, -2.0)));
}

#[test]
fn figure_2g_hole_passing_through_itself_disappears() {
    let mut s = set_with(&[
        &[(0.0, 0.0), (30.0, 0.0), (30.0, 30.0), (0.0, 30.0)],
        &[(10.0, 10.0), (15.0, 18.0), (20.0, 10.0)],
    ]);
    let hole = s.contour_ids().find(|&id| s.is_hole(id)).unwrap();
    let ev = moved(&mut s, (15.0, 18.0), (15.0, 2.0));
    assert_eq!(ev, vec![TopologyEvent::HoleGone { hole, into: None }]);
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(s.region_area(), 900.0);
}

#[test]
fn figure_2g_larger_hole_reversing_without_crossing() {
    // A four-vertex hole whose tip passes through to the far side of the whole hole.
    let mut s = set_with(&[
        &[(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)],
        &[(10.0, 20.0), (20.0, 30.0), (30.0, 20.0), (20.0, 22.0)],
    ]);
    let ev = moved(&mut s, (20.0, 30.0), (20.0, 5.0));
    assert!(matches!(ev[..], [TopologyEvent::HoleGone { .. }]));
    assert_eq!(s.contour_count(), 1);
    assert_eq!(s.region_area(), 1600.0);
}

#[test]
fn outer_triangle_turned_inside_out_vanishes() {
    let mut s = set_with(&[&[(10.0, 10.0), (20.0, 10.0), (15.0, 18.0)]]);
    let ev = moved(&mut s, (15.0, 18.0), (15.0, 2.0));
    assert!(matches!(ev[..], [TopologyEvent::Vanished { .. }]));
    assert_eq!(s.contour_count(), 0);
    assert_eq!(s.vertex_count(), 0);
}

#[test]
fn ring_inside_an_additive_region_is_swallowed() {
    // Directive 2: a small island lies in the region swept by a growing vertex.
    let mut s = set_with(&[SQUARE, &[(34.0, 18.0), (36.0, 18.0), (35.0, 20.0)]]);
    let ev = moved(&mut s, (30.0, 30.0), (50.0, 20.0));
    assert!(matches!(ev[..], [TopologyEvent::Merge { .. }]));
    assert_eq!(s.contour_count(), 1);
}

#[test]
fn degenerate_moves_are_refused_and_change_nothing() {
    let mut s = set_with(&[
        SQUARE,
        &[(40.0, 10.0), (50.0, 10.0), (50.0, 30.0), (40.0, 30.0)],
    ]);
    let before: Vec<_> = s.contour_ids().map(|id| s.ring_points(id)).collect();
    let v = vertex_at(&s, (30.0, 10.0));
    for to in [
        p(40.0, 20.0), // exactly on an edge of the other ring
        p(40.0, 10.0), // exactly on a vertex
        p(10.0, 10.0), // onto its neighbour
        p(20.0, 30.0), // new edge q→n folds back over n's next edge
        p(45.0, 0.0),  // new edge q→n runs exactly through the vertex (40, 10)
    ] {
        let r = s.move_vertex(v, to);
        assert!(matches!(r, Err(MoveError::Degenerate(_))), "{to:?}: {r:?}");
        let now: Vec<_> = s.contour_ids().map(|id| s.ring_points(id)).collect();
        assert_eq!(now, before);
    }
    s.sanity_check().unwrap();
}

#[test]
fn long_moves_are_corrected_in_one_step_and_their_edges_split() {
    let dom = Aabb {
        min: p(0.0, 0.0),
        max: p(100.0, 100.0),
    };
    let mut s = ContourSet::new(dom, 5.0);
    let sq: Vec<Point> = (0..16)
        .map(|i| {
            let (side, t) = (i / 4, (i % 4) as f64 * 4.0);
            match side {
                0 => p(10.0 + t, 10.0),
                1 => p(26.0, 10.0 + t),
                2 => p(26.0 - t, 26.0),
                _ => p(10.0, 26.0 - t),
            }
        })
        .collect();
    s.add_ring(&sq).unwrap();
    let v = vertex_at(&s, (26.0, 10.0));
    s.move_vertex(v, p(80.0, 60.0)).unwrap();
    s.sanity_check().unwrap();
    assert!(s
        .vertices()
        .all(|w| s.position(w).dist(s.position(s.next(w))) <= 5.0));
    assert_eq!(s.reach(), 5.0);
}

#[test]
fn insert_and_remove_vertex_keep_the_region() {
    let mut s = set_with(&[SQUARE]);
    let a = vertex_at(&s, (10.0, 10.0));
    let x = s.insert_vertex(a, 0.25).unwrap();
    assert_eq!(s.position(x), p(15.0, 10.0));
    assert_eq!(s.region_area(), 400.0);
    assert_eq!(s.vertex_count(), 5);
    // Removing a vertex is the motion of it onto the chord: here it cuts a corner.
    let c = vertex_at(&s, (30.0, 30.0));
    assert!(s.remove_vertex(c).unwrap().is_empty());
    assert_eq!(s.region_area(), 200.0);
    s.sanity_check().unwrap();
    assert_eq!(s.remove_vertex(x), Ok(vec![]));
    assert!(matches!(s.remove_vertex(a), Err(MoveError::TooFewVertices)));
    assert!(matches!(
        s.insert_vertex(a, 1.0),
        Err(MoveError::BadParameter)
    ));
}

#[test]
fn removal_can_change_topology_too() {
    // Removing the apex of a roof is a subtractive motion over the roof, which holds a
    // small hole: Directive 2 deletes the hole with it.
    let mut s = set_with(&[
        &[
            (0.0, 0.0),
            (20.0, 0.0),
            (20.0, 20.0),
            (10.0, 30.0),
            (0.0, 20.0),
        ],
        &[(9.0, 22.0), (10.0, 25.0), (11.0, 22.0)],
    ]);
    assert_eq!(holes(&s), 1);
    let apex = vertex_at(&s, (10.0, 30.0));
    let ev = s.remove_vertex(apex).unwrap();
    s.sanity_check().unwrap();
    assert!(matches!(ev[..], [TopologyEvent::HoleGone { .. }]));
    assert_eq!((s.contour_count(), holes(&s)), (1, 0));
    assert_eq!(s.region_area(), 400.0);
}
