//! The implicit engine (seed 000) on random images: whatever the image, seeds and wrap,
//! every frame's contours are valid rings (the contour set's invariants), their number
//! and kinds never change (one outer ring per initial component, no holes), and they
//! bound exactly the pixels the fast marching owns.

use proptest::prelude::*;
use topocontour::check::Rng;
use topocontour::evolution::{Evolver, Field, Mode, Params, Polarity, Shape};
use topocontour::geometry::winding_number;
use topocontour::Point;

fn random_image(rng: &mut Rng, w: usize, h: usize) -> Field {
    let blobs: Vec<(f64, f64, f64)> = (0..6)
        .map(|_| {
            (
                rng.range(0.0, w as f64),
                rng.range(0.0, h as f64),
                rng.range(4.0, 18.0),
            )
        })
        .collect();
    let data = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
            let inside = blobs
                .iter()
                .any(|&(cx, cy, r)| (x - cx).powi(2) + (y - cy).powi(2) < r * r);
            let noise = ((i * 2_654_435_761) % 97) as f32 / 97.0 - 0.5;
            (if inside { 0.3 } else { 0.7 }) + 0.3 * noise
        })
        .collect();
    Field::new(w, h, data)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn implicit_frames_keep_topology_and_match_the_pixels(seed in any::<u64>(), wrap in any::<bool>()) {
        let mut rng = Rng(seed);
        let (w, h) = (96, 72);
        let img = random_image(&mut rng, w, h);
        let mut init: Vec<Shape> = Vec::new();
        if wrap {
            init.push(Shape::Rect { min: Point::new(3.0, 3.0), max: Point::new(w as f64 - 3.0, h as f64 - 3.0) });
        } else {
            // Seeds far enough apart to be separate components.
            while init.len() < 4 {
                let c = Point::new(rng.range(6.0, w as f64 - 6.0), rng.range(6.0, h as f64 - 6.0));
                if init.iter().all(|s| s.center().dist(c) > 12.0) {
                    init.push(Shape::Disk { center: c, radius: 3.0 });
                }
            }
        }
        let params = Params { mode: Mode::Implicit, polarity: Polarity::Dark, ..Params::default() };
        let mut ev = Evolver::new(&img, &init, params).unwrap();
        let labels = ev.implicit().unwrap().label_count() as usize;
        prop_assert_eq!(labels, init.len());
        for _ in 0..200 {
            let f = ev.step();
            let set = ev.contours();
            set.sanity_check().map_err(TestCaseError::fail)?;
            prop_assert_eq!(set.contour_count(), labels, "frame {}", f.index);
            prop_assert!(set.contour_ids().all(|id| !set.is_hole(id)));
            let rings: Vec<Vec<Point>> = set.contour_ids().map(|id| set.ring_points(id)).collect();
            let imp = ev.implicit().unwrap();
            for y in 0..h {
                for x in 0..w {
                    let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                    let inside = rings.iter().map(|r| winding_number(r, p)).sum::<i32>() != 0;
                    prop_assert_eq!(inside, imp.owned(x, y), "frame {} pixel {},{}", f.index, x, y);
                }
            }
            if f.converged {
                break;
            }
        }
    }
}
