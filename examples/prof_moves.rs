//! Profiling aid for `move_vertex`: `prof_moves [bins|hash] [MOVES] [RINGS]` runs the
//! benchmark's moves ([`JitterMoves`]) on RINGS rings of 100 vertices (default 100), for
//! `valgrind --tool=callgrind` (instructions per move: the difference of two runs with
//! different MOVES, divided by the difference).
use topocontour::check::{ring_grid, JitterMoves};
use topocontour::contours::BroadPhaseKind;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kind = match a.get(1).map(String::as_str) {
        Some("hash") => BroadPhaseKind::Hash,
        _ => BroadPhaseKind::Bins,
    };
    let count: usize = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(1_000_000);
    let rings: usize = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(100);
    let mut set = ring_grid(rings, kind);
    let mut moves = JitterMoves::new(&set, 7);
    let t = std::time::Instant::now();
    for _ in 0..count {
        let (v, to) = moves.next_move();
        set.move_vertex(v, to).unwrap();
    }
    let ns = t.elapsed().as_secs_f64() * 1e9 / count as f64;
    println!("{}: {count} moves, {ns:.0} ns per move", kind.name());
}
