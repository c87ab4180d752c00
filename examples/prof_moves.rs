use topocontour::check::Rng;
use topocontour::{Aabb, ContourSet, Point};
fn main() {
    let mut set = ContourSet::new(
        Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(600.0, 600.0),
        },
        2.5,
    );
    for i in 0..100 {
        let c = Point::new((i % 10) as f64 * 60.0 + 30.0, (i / 10) as f64 * 60.0 + 30.0);
        let pts: Vec<Point> = (0..100)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 100.0;
                Point::new(c.x + 25.0 * a.cos(), c.y + 25.0 * a.sin())
            })
            .collect();
        set.add_ring(&pts).unwrap();
    }
    let verts: Vec<u32> = set.vertices().collect();
    let home: Vec<Point> = verts.iter().map(|&v| set.position(v)).collect();
    let mut rng = Rng(1);
    let t = std::time::Instant::now();
    let n = 2_000_000;
    for i in 0..n {
        let k = (i / 2) % verts.len();
        let to = if i % 2 == 0 {
            home[k] + Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2))
        } else {
            home[k]
        };
        set.move_vertex(verts[k], to).unwrap();
    }
    println!("{:.1} ns/move", t.elapsed().as_nanos() as f64 / n as f64);
}
