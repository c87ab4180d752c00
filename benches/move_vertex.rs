//! Cost of one `move_vertex` on ring sets of 10³ … 10⁶ vertices, with each broad phase
//! (vertex bins, seed 003 §3; staggered hash, seed 001 §2). Both make the crossing search
//! O(1), so the cost should be flat in N.
//!
//! Rings of 100 vertices (edges ≈ 1.6 px, bound 2.5 px) on a grid; each iteration moves one
//! vertex by a seeded jitter of up to 0.2 px and the next iteration moves it back, like
//! an evolving contour ([`JitterMoves`]). The bench asserts that no move changed the
//! topology. `TOPO_BENCH_MAX=100000` stops at 10⁵ vertices.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use topocontour::check::{ring_grid, JitterMoves};
use topocontour::contours::BroadPhaseKind;

fn bench_moves(c: &mut Criterion) {
    let max: usize = std::env::var("TOPO_BENCH_MAX")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    for kind in [BroadPhaseKind::Bins, BroadPhaseKind::Hash] {
        let mut group = c.benchmark_group(format!("move_vertex/{}", kind.name()));
        for n in [1_000usize, 10_000, 100_000, 1_000_000] {
            if n > max {
                break;
            }
            let mut set = ring_grid(n / 100, kind);
            let mut moves = JitterMoves::new(&set, 7);
            group.throughput(Throughput::Elements(1));
            group.bench_function(BenchmarkId::from_parameter(n), |b| {
                b.iter(|| {
                    let (v, to) = moves.next_move();
                    let ev = set.move_vertex(v, black_box(to)).unwrap();
                    assert!(ev.is_empty());
                })
            });
            assert_eq!(set.contour_count(), n / 100);
            assert_eq!(set.vertex_count(), n);
        }
        group.finish();
    }
}

criterion_group!(benches, bench_moves);
criterion_main!(benches);
