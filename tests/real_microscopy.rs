//! The real-image machinery on constructed images: the local decision level against a
//! brute-force reference, automatic seeds on touching disks of different brightness and
//! on nuclei side by side with no neck between them, a
//! phase-contrast wrap that ends on the cell, not on the halo, and one that separates
//! touching cells, and a wrap that opens the hole of a ring.

use proptest::prelude::*;
use topocontour::evolution::{
    find_seeds, Evolver, Field, IntensityModel, Modality, Params, Polarity, Shape,
};
use topocontour::geometry::{winding_number, Point};
use topocontour::image::filters::{box_extreme, box_mean};
use topocontour::image::local::{decision_field, LevelRule};

fn image(w: usize, h: usize, mut f: impl FnMut(f64, f64) -> f32) -> Field {
    let data = (0..w * h)
        .map(|i| f((i % w) as f64 + 0.5, (i / w) as f64 + 0.5))
        .collect();
    Field::new(w, h, data)
}

/// A wrap: the rectangle 4 px inside a `w` × `h` image.
fn wrap(w: usize, h: usize) -> [Shape; 1] {
    [Shape::Rect {
        min: Point::new(4.0, 4.0),
        max: Point::new(w as f64 - 4.0, h as f64 - 4.0),
    }]
}

/// `init` evolved on `img` with `params` until it settles.
fn settled(img: &Field, init: &[Shape], params: Params) -> Evolver {
    let mut ev = Evolver::new(img, init, params).unwrap();
    ev.run();
    ev
}

/// `seeds` grown on a fluorescence image in preserve mode (the instance run).
fn grown_instances(img: &Field, seeds: &[Shape]) -> Evolver {
    let params = Params {
        polarity: Polarity::Bright,
        mode: topocontour::evolution::Mode::Preserve,
        modality: Modality::Fluorescence,
        ..Params::default()
    };
    settled(img, seeds, params)
}

/// The (2r+1)² box around (x, y), cut to the image.
fn window(f: &Field, x: usize, y: usize, r: usize) -> Vec<f32> {
    let mut v = Vec::new();
    for yy in y.saturating_sub(r)..(y + r + 1).min(f.height) {
        for xx in x.saturating_sub(r)..(x + r + 1).min(f.width) {
            v.push(f.at(xx, yy));
        }
    }
    v
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    /// Every pixel of the decision level equals the module doc's formula evaluated by
    /// brute force over its boxes.
    #[test]
    fn decision_level_matches_brute_force(
        w in 1usize..24, h in 1usize..24, r in 1usize..5, seed in any::<u64>(),
        object in 0.0f64..1.0, background in 0.0f64..1.0, floor in 0.0f64..0.2,
        reach in 1.0f64..3.0, share in 0.3f64..0.6, background_box in prop::sample::select(vec![0.5, 1.0]),
    ) {
        let mut s = seed | 1;
        let f = image(w, h, |_, _| {
            s ^= s << 13; s ^= s >> 7; s ^= s << 17;
            (s % 1000) as f32 / 1000.0
        });
        let model = IntensityModel { object, background };
        let d = decision_field(&f, r, &model, &LevelRule { floor, reach, share, background_box });
        let bright = object >= background;
        let sign = if bright { 1.0 } else { -1.0 };
        // The background's boxes: half-side r, or ⌈r/2⌉.
        let rb = if background_box < 1.0 { r.div_ceil(2) } else { r };
        let mean = box_mean(&f, rb);
        // The object's extreme is taken over half the radius (rounded up), on the image
        // blurred once more by [1 2 1] / 4.
        let re = r.div_ceil(2);
        let fb = f.blur(&[0.25, 0.5, 0.25]);
        let extreme = box_extreme(&fb, re, bright);
        for y in 0..h {
            for x in 0..w {
                let win = window(&f, x, y, rb);
                let m = win.iter().map(|&v| v as f64).sum::<f64>() / win.len() as f64;
                prop_assert!((mean.at(x, y) as f64 - m).abs() < 1e-5);
                let e = window(&fb, x, y, re).iter().copied().fold(if bright { f32::MIN } else { f32::MAX },
                    |a, v| if bright { a.max(v) } else { a.min(v) });
                prop_assert_eq!(extreme.at(x, y), e);
                // Background: the emptiest box mean within 3r, never less object-like
                // than the global background.
                let means = window(&mean, x, y, 3 * r);
                let b = means.iter().copied().fold(if bright { f32::MAX } else { f32::MIN },
                    |a, v| if bright { a.min(v) } else { a.max(v) }) as f64;
                let b = if bright { b.max(background) } else { b.min(background) };
                let level = b + sign * (share * sign * (e as f64 - b)).max(floor);
                let tg = 0.5 * (object + background);
                let cap = b + reach * (tg - b);
                let level = if bright { level.min(cap) } else { level.max(cap) };
                prop_assert!((d.level.at(x, y) as f64 - level).abs() < 1e-5,
                    "{x},{y}: {} vs {level}", d.level.at(x, y));
                let half = (level - b).abs().max(floor);
                prop_assert!((d.half.at(x, y) as f64 - half).abs() < 1e-5);
            }
        }
    }
}

/// Six disks of brightness 0.25 to 1.0 on dark background, touching in pairs: one seed
/// inside each disk, none elsewhere.
#[test]
fn auto_seeds_find_each_of_touching_disks() {
    let r = 12.0;
    let mut disks = Vec::new();
    for (k, row) in [40.0, 100.0, 160.0].iter().enumerate() {
        // Two disks 1.7 r apart: they overlap, the neck is narrower than either.
        disks.push((60.0, *row, 0.25 + 0.15 * k as f32));
        disks.push((60.0 + 1.7 * r, *row, 0.5 + 0.25 * k as f32));
    }
    let img = image(200, 200, |x, y| {
        let mut v = 0.05;
        for &(cx, cy, b) in &disks {
            if (x - cx).hypot(y - cy) < r {
                v = f32::max(v, b);
            }
        }
        // Light texture, as a camera gives.
        v + 0.01 * (((x * 7.0 + y * 13.0) as i64 % 5) as f32 / 5.0)
    });
    let seeds = find_seeds(&img, Polarity::Bright, Modality::Fluorescence);
    assert_eq!(seeds.len(), disks.len(), "{seeds:?}");
    for &(cx, cy, _) in &disks {
        let inside = seeds
            .iter()
            .filter(|s| s.center().dist(Point::new(cx, cy)) < r)
            .count();
        assert_eq!(inside, 1, "disk at {cx},{cy}: {seeds:?}");
    }
    // Grown in preserve mode, the seeds stay six objects, each near its disk's area.
    let ev = grown_instances(&img, &seeds);
    let set = ev.contours();
    assert_eq!(set.contour_count(), 6);
    // A dim disk loses the strip next to its bright partner, whose brightness sets the
    // local level there (see the module doc of `local`): half a disk at least.
    for id in set.contour_ids() {
        let a = set.signed_area(id);
        assert!(
            a > 0.5 * std::f64::consts::PI * r * r,
            "a disk grew to {a} only"
        );
    }
    let total = set.region_area();
    // Six disks less three lenses of 31 px² where the pairs overlap.
    let expected = std::f64::consts::PI * r * r * 6.0 - 3.0 * 31.0;
    assert!(
        (total - expected).abs() < 0.2 * expected,
        "area {total}, about {expected}"
    );
}

/// Pairs of nuclei side by side along their short axes, equal in brightness: the union's
/// distance transform peaks once, at the contact, so only the notches of the outline
/// tell two nuclei (see `image::declump`). Each pair gets two seeds, one in each
/// nucleus, and grows into two objects of about half the pair; lone nuclei, even one
/// as wide as a pair, get one seed each.
#[test]
fn auto_seeds_part_nuclei_side_by_side_without_a_neck() {
    let (a, b, gap) = (13.0, 7.5, 12.0);
    let pairs = [(40.0, 40.0), (110.0, 40.0), (40.0, 110.0)];
    // Lone nuclei, one of them as wide as a pair.
    let lone = [
        (110.0, 110.0, b + 0.5 * gap),
        (165.0, 40.0, b),
        (165.0, 110.0, b),
    ];
    let inside = |x: f64, y: f64, cx: f64, cy: f64, bx: f64| {
        ((x - cx) / bx).powi(2) + ((y - cy) / a).powi(2) <= 1.0
    };
    let img = image(190, 150, |x, y| {
        let nucleus = pairs.iter().any(|&(cx, cy)| {
            inside(x, y, cx - 0.5 * gap, cy, b) || inside(x, y, cx + 0.5 * gap, cy, b)
        }) || lone.iter().any(|&(cx, cy, bx)| inside(x, y, cx, cy, bx));
        let v = if nucleus { 0.6 } else { 0.08 };
        v + 0.02 * (((x * 7.0 + y * 13.0) as i64 % 5) as f32 / 5.0)
    });
    let seeds = find_seeds(&img, Polarity::Bright, Modality::Fluorescence);
    assert_eq!(seeds.len(), 2 * pairs.len() + lone.len(), "{seeds:?}");
    for &(cx, cy) in &pairs {
        for side in [-0.5 * gap, 0.5 * gap] {
            let centre = Point::new(cx + side, cy);
            let near = seeds.iter().filter(|s| s.center().dist(centre) < b).count();
            assert_eq!(near, 1, "nucleus at {centre:?}: {seeds:?}");
        }
    }
    let ev = grown_instances(&img, &seeds);
    let set = ev.contours();
    assert_eq!(set.contour_count(), 2 * pairs.len() + lone.len());
    // Each pair's nuclei share the lens between them: half of it each, less the gap.
    let half_pair = std::f64::consts::PI * a * b - 30.0;
    for &(cx, cy) in &pairs {
        for side in [-0.5 * gap, 0.5 * gap] {
            let centre = Point::new(cx + side, cy);
            let id = set
                .contour_ids()
                .find(|&id| winding_number(&set.ring_points(id), centre) != 0)
                .expect("a contour over each nucleus");
            let area = set.signed_area(id);
            assert!(
                (area - half_pair).abs() < 0.2 * half_pair,
                "{centre:?}: {area}"
            );
        }
    }
}

/// A dark cell with a bright halo on grey background: the phase-contrast wrap stops on
/// the cell boundary (area within 10 % of the cell's), where the generic model takes the
/// halo's inside or more.
#[test]
fn phase_contrast_wrap_ends_on_the_cell() {
    let (w, h) = (160usize, 160usize);
    // A rod: a capsule of half-width 7 from (50, 80) to (110, 80).
    let dist = |x: f64, y: f64| {
        let t = ((x - 50.0) / 60.0).clamp(0.0, 1.0);
        (x - (50.0 + 60.0 * t)).hypot(y - 80.0) - 7.0
    };
    let img = image(w, h, |x, y| {
        let d = dist(x, y);
        // Cell 0.1, a halo peaking at 0.95 just outside, grey 0.5 beyond; soft edges.
        let cell = 1.0 / (1.0 + (d / 0.7).exp());
        let halo = 0.45 * (-(d - 3.0).powi(2) / 8.0).exp();
        (0.5 - 0.4 * cell + halo * (1.0 - cell)) as f32
    });
    let wrap = wrap(w, h);
    let cell_area = 60.0 * 14.0 + std::f64::consts::PI * 49.0;
    let run = |modality| {
        let params = Params {
            polarity: Polarity::Dark,
            modality,
            ..Params::default()
        };
        let ev = settled(&img, &wrap, params);
        assert!(ev.frames() <= 300);
        (ev.contours().contour_count(), ev.contours().region_area())
    };
    let (n, area) = run(Modality::PhaseContrast);
    assert_eq!(n, 1);
    assert!(
        (area - cell_area).abs() < 0.1 * cell_area,
        "phase contrast: area {area}, cell {cell_area}"
    );
}

/// Two rods touching side by side under phase-contrast optics: between them the halo is
/// a ridge blurred into both cells, darker than halfway to the background. The wrap ends
/// on two cells (the narrow halo is lifted to background and a hole opens there), each
/// within 15 % of the area the same rod gets when it lies apart.
#[test]
fn phase_contrast_wrap_separates_touching_cells() {
    let (w, h) = (160usize, 160usize);
    // Two capsules of half-width 7 whose axes are `gap` apart, blurred by the optics
    // (about 2.5 px).
    let rods = |gap: f64| {
        let rod = |x: f64, y: f64, cy: f64| {
            let t = ((x - 50.0) / 60.0).clamp(0.0, 1.0);
            (x - (50.0 + 60.0 * t)).hypot(y - cy) - 7.0
        };
        let mut img = image(w, h, |x, y| {
            let d = rod(x, y, 80.0 - gap / 2.0).min(rod(x, y, 80.0 + gap / 2.0));
            let cell = 1.0 / (1.0 + (d / 0.7).exp());
            let halo = 0.45 * (-(d - 3.0).powi(2) / 8.0).exp();
            (0.5 - 0.4 * cell + halo * (1.0 - cell)) as f32
        });
        for _ in 0..6 {
            img = img.blur5();
        }
        img
    };
    let wrap = wrap(w, h);
    let areas = |img: &Field| {
        let params = Params {
            polarity: Polarity::Dark,
            modality: Modality::PhaseContrast,
            ..Params::default()
        };
        let ev = settled(img, &wrap, params);
        assert!(ev.frames() <= 300, "{} frames", ev.frames());
        let set = ev.contours();
        set.contour_ids()
            .map(|id| set.signed_area(id))
            .collect::<Vec<f64>>()
    };
    // Axes 16 px apart: a 2 px channel between the rims, which by intensity alone
    // reads as cell (halfway between cell 0.1 and background 0.5 is 0.3).
    let touching = rods(16.0);
    let channel = touching.at(80, 80);
    assert!(channel < 0.3, "the channel is {channel}");
    let apart = areas(&rods(40.0));
    assert_eq!(apart.len(), 2, "apart: {apart:?}");
    let together = areas(&touching);
    assert_eq!(together.len(), 2, "touching: {together:?}");
    for a in together {
        assert!(
            (a - apart[0]).abs() < 0.15 * apart[0],
            "a touching cell of {a} px², alone {}",
            apart[0]
        );
    }
}

/// A bright ring on dark background, wrapped from the border: the adaptive engine
/// opens the ring's hole (nucleation) and ends on one region with one hole of the
/// right size; the topology-keeping engine keeps the wrap without a hole.
#[test]
fn wrap_opens_the_hole_of_a_ring() {
    let (w, h) = (128usize, 128usize);
    let (r_out, r_in) = (40.0, 16.0);
    let img = image(w, h, |x, y| {
        let d = (x - 64.0).hypot(y - 64.0);
        let s = |e: f64| 1.0 / (1.0 + (e / 0.7).exp());
        (0.1 + 0.7 * s(d - r_out) * (1.0 - s(d - r_in))) as f32
    });
    let wrap = wrap(w, h);
    let run = |mode| {
        let params = Params {
            polarity: Polarity::Bright,
            mode,
            ..Params::default()
        };
        let ev = settled(&img, &wrap, params);
        let set = ev.contours().clone();
        let holes = set.contour_ids().filter(|&id| set.is_hole(id)).count();
        (
            set.contour_count() - holes,
            holes,
            set.region_area(),
            ev.frames(),
        )
    };
    let (outer, holes, area, frames) = run(topocontour::evolution::Mode::Adaptive);
    let ring = std::f64::consts::PI * (r_out * r_out - r_in * r_in);
    assert_eq!((outer, holes), (1, 1), "adaptive");
    assert!(frames <= 300, "{frames} frames");
    assert!(
        (area - ring).abs() < 0.05 * ring,
        "area {area}, ring {ring}"
    );
    let (outer, holes, _, _) = run(topocontour::evolution::Mode::Preserve);
    assert_eq!((outer, holes), (1, 0), "preserve keeps the wrap's topology");
}
