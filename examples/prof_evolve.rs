//! Profiling aid: evolves the 400-cell image to convergence, then runs 10 more frames.
use topocontour::evolution::{Evolver, Field, Params, Shape};
use topocontour::Point;
fn main() {
    let (w, h) = (1600usize, 1600usize);
    let data: Vec<f32> = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let (cx, cy) = ((x % 80) as f64 - 39.5, (y % 80) as f64 - 39.5);
            let noise = ((x * 7919 + y * 104_729) % 23) as f32 - 11.0;
            ((if cx * cx + cy * cy < 676.0 {
                70.0
            } else {
                180.0
            }) + noise)
                / 255.0
        })
        .collect();
    let img = Field::new(w, h, data);
    let mut ev = Evolver::new(
        &img,
        &[Shape::Rect {
            min: Point::new(4.0, 4.0),
            max: Point::new(1596.0, 1596.0),
        }],
        Params::default(),
    )
    .unwrap();
    let t = std::time::Instant::now();
    ev.run();
    println!(
        "converged in {} frames, {:.1} ms, {} vertices",
        ev.frames(),
        t.elapsed().as_secs_f64() * 1e3,
        ev.contours().vertex_count()
    );
    let t = std::time::Instant::now();
    for _ in 0..10 {
        ev.step();
    }
    println!(
        "10 frames at {} vertices: {:.2} ms per frame",
        ev.contours().vertex_count(),
        t.elapsed().as_secs_f64() * 1e2
    );
}
