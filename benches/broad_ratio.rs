//! The staggered hash against the vertex bins, paired: `cargo bench --bench broad_ratio`.
//!
//! The same moves as `benches/move_vertex.rs` ([`JitterMoves`], same seed) on two ring
//! sets built alike, one per broad phase, timed in alternating blocks of 100,000 moves
//! (bins first in even pairs, hash first in odd ones). On a shared machine the speed
//! drifts by tens of percent over seconds — more than the difference measured here — and
//! separate runs (criterion's) compare two different machines; the two blocks of a pair
//! see the same one. Prints per size the median ns per move of each and the median of
//! the per-pair ratios hash / bins, with its quartiles. `TOPO_BENCH_MAX=100000` stops at
//! 10⁵ vertices; `TOPO_PAIRS` sets the pairs per size (default 100).

use std::hint::black_box;
use std::time::Instant;
use topocontour::check::{ring_grid, JitterMoves};
use topocontour::contours::{BroadPhaseKind, ContourSet};

const BLOCK: usize = 100_000;

/// Nanoseconds per move over one block.
fn block(set: &mut ContourSet, moves: &mut JitterMoves) -> f64 {
    let t = Instant::now();
    for _ in 0..BLOCK {
        let (v, to) = moves.next_move();
        let ev = set.move_vertex(v, black_box(to)).unwrap();
        assert!(ev.is_empty());
    }
    t.elapsed().as_secs_f64() * 1e9 / BLOCK as f64
}

fn quantile(v: &mut [f64], q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

fn env(name: &str, default: usize) -> usize {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn main() {
    // `cargo bench` passes `--bench`; vertex counts after `--` pick sizes (`-- 1000000`).
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    let max = env("TOPO_BENCH_MAX", 1_000_000);
    let pairs = env("TOPO_PAIRS", 100).max(1);
    println!(
        "{:>9}  {:>12}  {:>12}  {:>11}  {:>13}",
        "vertices", "bins ns/move", "hash ns/move", "hash / bins", "quartiles"
    );
    for n in [1_000usize, 10_000, 100_000, 1_000_000] {
        if n > max || !(words.is_empty() || words.iter().any(|w| n.to_string() == *w)) {
            continue;
        }
        let mut sets = [BroadPhaseKind::Bins, BroadPhaseKind::Hash].map(|k| ring_grid(n / 100, k));
        let mut moves = [&sets[0], &sets[1]].map(|s| JitterMoves::new(s, 7));
        // Warm-up: a block each (page faults, caches, branch predictors).
        for i in 0..2 {
            block(&mut sets[i], &mut moves[i]);
        }
        let (mut ns, mut ratio) = ([vec![], vec![]], vec![]);
        for p in 0..pairs {
            let mut t = [0.0; 2];
            for i in [p % 2, 1 - p % 2] {
                t[i] = block(&mut sets[i], &mut moves[i]);
                ns[i].push(t[i]);
            }
            ratio.push(t[1] / t[0]);
        }
        for set in &sets {
            assert_eq!(set.contour_count(), n / 100);
        }
        println!(
            "{n:>9}  {:>12.1}  {:>12.1}  {:>11.3}  {:>6.3}–{:.3}",
            quantile(&mut ns[0], 0.5),
            quantile(&mut ns[1], 0.5),
            quantile(&mut ratio, 0.5),
            quantile(&mut ratio, 0.25),
            quantile(&mut ratio, 0.75),
        );
    }
}
