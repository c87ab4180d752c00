//! Cost of one `move_vertex` on ring sets of 10³ … 10⁶ vertices, with each broad phase
//! (vertex bins, seed 003 §3; staggered hash, seed 001 §2). Both make the crossing search
//! O(1), so the cost should be flat in N.
//!
//! Rings of 100 vertices (edges ≈ 1.6 px, bound 2.5 px) on a grid; each iteration moves one
//! vertex by a seeded jitter of up to 0.2 px and the next iteration moves it back, like
//! an evolving contour. The bench asserts that no move changed the topology.
//! `TOPO_BENCH_MAX=100000` stops at 10⁵ vertices.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use topocontour::check::{ring_grid, Rng};
use topocontour::contours::BroadPhaseKind;
use topocontour::Point;

/// Distinct jitters (a power of two: the index wraps by a mask).
const JITTERS: usize = 4096;

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
            let mut rng = Rng(7);
            let verts: Vec<u32> = set.vertices().collect();
            let jitter: Vec<Point> = (0..JITTERS)
                .map(|_| Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)))
                .collect();
            let home: Vec<Point> = verts.iter().map(|&v| set.position(v)).collect();
            group.throughput(Throughput::Elements(1));
            group.bench_function(BenchmarkId::from_parameter(n), |b| {
                // Out on one step, back home on the next: the set stays as built. The
                // vertex index advances by a compare, not a division (a 64-bit division
                // alone costs tens of cycles, a good part of what is measured).
                let (mut k, mut out) = (0usize, true);
                b.iter(|| {
                    let to = if out {
                        home[k] + jitter[k % JITTERS]
                    } else {
                        home[k]
                    };
                    let ev = set.move_vertex(verts[k], black_box(to)).unwrap();
                    assert!(ev.is_empty());
                    if !out {
                        k += 1;
                        if k == verts.len() {
                            k = 0;
                        }
                    }
                    out = !out;
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
