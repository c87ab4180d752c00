//! Profiling aid for `move_vertex`: `prof_moves [bins|hash] [MOVES] [RINGS]` runs the
//! benchmark's jitter-and-return moves on RINGS rings of 100 vertices (default 100) (for
//! `valgrind --tool=callgrind`).
use topocontour::check::{ring_grid, Rng};
use topocontour::contours::BroadPhaseKind;
use topocontour::Point;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kind = match a.get(1).map(String::as_str) {
        Some("hash") => BroadPhaseKind::Hash,
        _ => BroadPhaseKind::Bins,
    };
    let moves: usize = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(1_000_000);
    let rings: usize = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(100);
    let mut set = ring_grid(rings, kind);
    let mut rng = Rng(7);
    let verts: Vec<u32> = set.vertices().collect();
    let home: Vec<Point> = verts.iter().map(|&v| set.position(v)).collect();
    let t = std::time::Instant::now();
    let mut k = 0;
    for i in 0..moves {
        let to = if i % 2 == 0 {
            home[k] + Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2))
        } else {
            home[k]
        };
        set.move_vertex(verts[k], to).unwrap();
        // The next vertex by a compare, not a division (as in the benchmark).
        if i % 2 == 1 {
            k += 1;
            if k == verts.len() {
                k = 0;
            }
        }
    }
    let ns = t.elapsed().as_secs_f64() * 1e9 / moves as f64;
    println!("{}: {moves} moves, {ns:.0} ns per move", kind.name());
}
