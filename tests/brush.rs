//! The brush: contour vertices inside a moving disc are pushed out to its rim through
//! the topology core, so strokes merge, split and open holes exactly.

use topocontour::evolution::{Evolver, Field, Mode, Params, Shape};
use topocontour::{Point, TopologyEvent};

fn evolver(shapes: &[Shape], mode: Mode) -> Evolver {
    let image = Field::new(128, 96, vec![0.5; 128 * 96]);
    Evolver::new(
        &image,
        shapes,
        Params {
            mode,
            ..Params::default()
        },
    )
    .unwrap()
}

fn disk(x: f64, y: f64, r: f64) -> Shape {
    Shape::Disk {
        center: Point::new(x, y),
        radius: r,
    }
}

#[test]
fn a_stroke_from_inside_pushes_the_boundary_out_and_merges() {
    let mut ev = evolver(
        &[disk(40.0, 48.0, 12.0), disk(74.0, 48.0, 12.0)],
        Mode::Adaptive,
    );
    assert_eq!(ev.contours().contour_count(), 2);
    let events = ev.brush(Point::new(40.0, 48.0), Point::new(58.0, 48.0), 8.0);
    assert!(
        events
            .iter()
            .any(|e| matches!(e, TopologyEvent::Merge { .. })),
        "{events:?}"
    );
    assert_eq!(ev.contours().contour_count(), 1);
    ev.contours().sanity_check().unwrap();
    assert!(ev
        .events()
        .iter()
        .any(|e| matches!(e.event, TopologyEvent::Merge { .. })));
    assert_eq!(ev.edits().len(), 1);
}

#[test]
fn a_stroke_from_outside_cuts_a_bar_in_two() {
    let bar = Shape::Rect {
        min: Point::new(20.0, 42.0),
        max: Point::new(108.0, 54.0),
    };
    let mut ev = evolver(&[bar], Mode::Adaptive);
    let area = ev.contours().region_area();
    let events = ev.brush(Point::new(64.0, 20.0), Point::new(64.0, 80.0), 6.0);
    assert!(
        events
            .iter()
            .any(|e| matches!(e, TopologyEvent::Split { .. })),
        "{events:?}"
    );
    assert_eq!(ev.contours().contour_count(), 2);
    assert!(
        ev.contours().region_area() < area - 100.0,
        "a channel was cut"
    );
    ev.contours().sanity_check().unwrap();
}

#[test]
fn preserve_keeps_the_contours_apart_under_the_brush() {
    let mut ev = evolver(
        &[disk(40.0, 48.0, 12.0), disk(74.0, 48.0, 12.0)],
        Mode::Preserve,
    );
    ev.brush(Point::new(40.0, 48.0), Point::new(62.0, 48.0), 8.0);
    assert_eq!(
        ev.contours().contour_count(),
        2,
        "no merge in preserve mode"
    );
    ev.contours().sanity_check().unwrap();
}

/// Random strokes over random seeds: every stroke leaves a valid set inside the image.
#[test]
fn random_strokes_keep_every_invariant() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..8 {
        let shapes: Vec<Shape> = (0..4)
            .map(|_| {
                disk(
                    10.0 + 108.0 * rnd(),
                    10.0 + 76.0 * rnd(),
                    4.0 + 10.0 * rnd(),
                )
            })
            .collect();
        let mut ev = evolver(&shapes, Mode::Adaptive);
        for _ in 0..25 {
            let from = Point::new(-10.0 + 148.0 * rnd(), -10.0 + 116.0 * rnd());
            let to = Point::new(from.x + 40.0 * (rnd() - 0.5), from.y + 40.0 * (rnd() - 0.5));
            ev.brush(from, to, 2.0 + 10.0 * rnd());
            let set = ev.contours();
            set.sanity_check().unwrap();
            for v in set.vertices() {
                let p = set.position(v);
                assert!(
                    (0.0..=128.0).contains(&p.x) && (0.0..=96.0).contains(&p.y),
                    "{p:?}"
                );
            }
        }
    }
}

/// A C-shaped region whose slit the brush closes: the region now surrounds its inside,
/// a hole is made.
#[test]
fn a_stroke_that_closes_a_slit_makes_a_hole() {
    let c: Vec<Point> = [
        (20.0, 20.0),
        (80.0, 20.0),
        (80.0, 47.0),
        (65.0, 47.0),
        (65.0, 35.0),
        (35.0, 35.0),
        (35.0, 65.0),
        (65.0, 65.0),
        (65.0, 53.0),
        (80.0, 53.0),
        (80.0, 80.0),
        (20.0, 80.0),
    ]
    .iter()
    .map(|&(x, y)| Point::new(x, y))
    .collect();
    let mut ev = evolver(&[Shape::Polygon(c)], Mode::Adaptive);
    assert_eq!(ev.contours().contour_count(), 1);
    let events = ev.brush(Point::new(72.0, 41.0), Point::new(72.0, 48.0), 8.0);
    assert!(
        events
            .iter()
            .any(|e| matches!(e, TopologyEvent::HoleMade { .. })),
        "{events:?}"
    );
    assert_eq!(ev.contours().contour_count(), 2, "outer ring and the hole");
    ev.contours().sanity_check().unwrap();
}

/// A brush down to 2 px cuts a bar wherever the stroke ends beyond it, and the cut is as
/// wide as the brush. A 2 px brush once slipped between vertices, its cut turned inside
/// out behind it and healed: the bar stayed whole for most stroke ends.
#[test]
fn a_narrow_brush_cuts_a_bar_as_wide_as_itself_wherever_the_stroke_ends() {
    for r in [2.0, 3.0, 6.0] {
        for k in 0..14 {
            let end = 53.0 + 0.5 * k as f64;
            let bar = Shape::Rect {
                min: Point::new(20.0, 42.0),
                max: Point::new(108.0, 54.0),
            };
            let mut ev = evolver(&[bar], Mode::Adaptive);
            ev.brush(Point::new(64.0, 20.0), Point::new(64.0, end), r);
            let set = ev.contours();
            set.sanity_check().unwrap();
            // Each piece's extent across the bar's middle (where the stroke ends, the
            // disc's rim narrows the cut).
            let mut pieces: Vec<(f64, f64)> = set
                .contour_ids()
                .map(|id| {
                    let pts = set.ring_points(id).into_iter();
                    let xs = pts.filter(|p| (44.0..=52.0).contains(&p.y)).map(|p| p.x);
                    xs.fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
                })
                .collect();
            pieces.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert_eq!(pieces.len(), 2, "radius {r}, stroke to y {end}: {pieces:?}");
            let (left, right) = (pieces[0].1, pieces[1].0);
            assert!(
                (left - (64.0 - r)).abs() < 0.5 && (right - (64.0 + r)).abs() < 0.5,
                "radius {r}, stroke to y {end}: the cut runs {left}..{right}"
            );
        }
    }
}
