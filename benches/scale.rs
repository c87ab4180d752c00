//! Scale benchmarks (issue: performance at the sizes real users bring), printing figures:
//!
//! - `wrap`: a deterministic 4096×4096 image with 400 dark cells on a noisy background,
//!   shrink-wrapped from the border to convergence;
//! - `seeds`: a 2048×2048 image with 1,000 cells, one seed in each, grown to convergence.
//!
//! Each runs with both broad phases (and the wrap with every engine), three times; the
//! median wall time of `Evolver::new` + `run` is printed with frames and vertices.
//! `cargo bench --bench scale` runs all; `-- wrap implicit` runs the lines whose label
//! holds every word given.

use std::time::Instant;
use topocontour::contours::BroadPhaseKind;
use topocontour::evolution::{Evolver, Field, Mode, Params, Polarity, Shape};
use topocontour::Point;

/// `n × n` cells of radius `r` (± a deterministic wobble) on a `side`-pixel square.
fn cells(side: usize, n: usize, r: f64) -> (Field, Vec<Point>) {
    let pitch = side as f64 / n as f64;
    let mut centres = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let k = (j * n + i) as f64;
            let jx = 0.15 * pitch * (k * 0.618_034).fract() - 0.075 * pitch;
            let jy = 0.15 * pitch * (k * 0.414_214).fract() - 0.075 * pitch;
            centres.push(Point::new(
                (i as f64 + 0.5) * pitch + jx,
                (j as f64 + 0.5) * pitch + jy,
            ));
        }
    }
    let mut data = vec![0f32; side * side];
    for (idx, v) in data.iter_mut().enumerate() {
        let (x, y) = (idx % side, idx / side);
        // Cheap deterministic noise, ±0.06.
        let h = (x as u64 * 73_856_093) ^ (y as u64 * 19_349_663);
        *v = 0.7 + ((h % 1000) as f32 / 1000.0 - 0.5) * 0.12;
    }
    for c in &centres {
        let rr = r.ceil() as i64 + 1;
        let (cx, cy) = (c.x as i64, c.y as i64);
        for y in (cy - rr).max(0)..(cy + rr).min(side as i64) {
            for x in (cx - rr).max(0)..(cx + rr).min(side as i64) {
                let d = Point::new(x as f64 + 0.5, y as f64 + 0.5).dist(*c);
                if d < r {
                    data[y as usize * side + x as usize] -= 0.4;
                }
            }
        }
    }
    (Field::new(side, side, data), centres)
}

fn time(label: &str, img: &Field, init: &[Shape], params: Params) {
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    if !words.iter().all(|w| label.contains(w.as_str())) {
        return;
    }
    let mut times = Vec::new();
    let (mut frames, mut vertices, mut contours, mut holes) = (0, 0, 0, 0);
    for _ in 0..3 {
        let t = Instant::now();
        let mut ev = Evolver::new(img, init, params.clone()).expect("valid set-up");
        ev.run();
        times.push(t.elapsed().as_secs_f64());
        frames = ev.frames();
        vertices = ev.contours().vertex_count();
        contours = ev.contours().contour_count();
        holes = ev
            .contours()
            .contour_ids()
            .filter(|&id| ev.contours().is_hole(id))
            .count();
    }
    times.sort_by(f64::total_cmp);
    println!(
        "{label:<28} median {:>7.3} s  (min {:.3})  frames {frames:>5}  contours {contours:>5} ({holes} holes)  vertices {vertices:>7}",
        times[1], times[0]
    );
}

fn main() {
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let want = |name: &str| {
        words.is_empty()
            || words.iter().any(|w| w == name)
            || !words.iter().any(|w| w == "wrap" || w == "seeds")
    };
    let dark = Params {
        polarity: Polarity::Dark,
        ..Params::default()
    };
    if want("wrap") {
        let (img, _) = cells(4096, 20, 70.0);
        let wrap = [Shape::Rect {
            min: Point::new(6.0, 6.0),
            max: Point::new(4090.0, 4090.0),
        }];
        for (mode, broad) in [
            (Mode::Adaptive, BroadPhaseKind::Bins),
            (Mode::Adaptive, BroadPhaseKind::Hash),
            (Mode::Preserve, BroadPhaseKind::Bins),
            (Mode::Implicit, BroadPhaseKind::Bins),
        ] {
            let p = Params {
                mode,
                broad_phase: broad,
                ..dark.clone()
            };
            time(
                &format!("wrap 4096² 400 {} {}", mode.name(), broad.name()),
                &img,
                &wrap,
                p,
            );
        }
    }
    if want("seeds") {
        let (img, centres) = cells(2048, 32, 22.0);
        let seeds: Vec<Shape> = centres
            .iter()
            .take(1000)
            .map(|&c| Shape::Disk {
                center: c,
                radius: 4.0,
            })
            .collect();
        for broad in [BroadPhaseKind::Bins, BroadPhaseKind::Hash] {
            let p = Params {
                broad_phase: broad,
                ..dark.clone()
            };
            time(
                &format!("seeds 2048² 1000 {}", broad.name()),
                &img,
                &seeds,
                p,
            );
        }
    }
}
