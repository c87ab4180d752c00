//! Cost of one `move_vertex` on ring sets of 10³, 10⁴ and 10⁵ vertices (seed 003, §3:
//! the vertex bins make the crossing search O(1), so the cost should be flat in N).
//!
//! Rings of 100 vertices (edges ≈ 1.6 px, bound 2.5 px) on a grid; each iteration moves one
//! vertex by a seeded jitter of up to 0.2 px and the next iteration moves it back, like
//! an evolving contour. The bench asserts that no move changed the topology.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use topocontour::check::Rng;
use topocontour::{Aabb, ContourSet, Point};

fn ring_grid(rings: usize) -> ContourSet {
    let side = (rings as f64).sqrt().ceil() as usize;
    let pitch = 60.0;
    let extent = side as f64 * pitch;
    let mut set = ContourSet::new(
        Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(extent, extent),
        },
        2.5,
    );
    for i in 0..rings {
        let c = Point::new(
            (i % side) as f64 * pitch + 30.0,
            (i / side) as f64 * pitch + 30.0,
        );
        let pts: Vec<Point> = (0..100)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 100.0;
                Point::new(c.x + 25.0 * a.cos(), c.y + 25.0 * a.sin())
            })
            .collect();
        set.add_ring(&pts).unwrap();
    }
    set
}

fn bench_moves(c: &mut Criterion) {
    let mut group = c.benchmark_group("move_vertex");
    for n in [1_000usize, 10_000, 100_000] {
        let mut set = ring_grid(n / 100);
        let mut rng = Rng(7);
        let verts: Vec<u32> = set.vertices().collect();
        let jitter: Vec<Point> = (0..4096)
            .map(|_| Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)))
            .collect();
        let home: Vec<Point> = verts.iter().map(|&v| set.position(v)).collect();
        group.throughput(Throughput::Elements(1));
        group.bench_function(BenchmarkId::from_parameter(n), |b| {
            let mut i = 0usize;
            b.iter(|| {
                // Out on even steps, back home on odd ones: the set stays as built.
                let k = (i / 2) % verts.len();
                let to = if i % 2 == 0 {
                    home[k] + jitter[k % jitter.len()]
                } else {
                    home[k]
                };
                let ev = set.move_vertex(verts[k], black_box(to)).unwrap();
                assert!(ev.is_empty());
                i = i.wrapping_add(1);
            })
        });
        assert_eq!(set.contour_count(), n / 100);
        assert_eq!(set.vertex_count(), n);
    }
    group.finish();
}

criterion_group!(benches, bench_moves);
criterion_main!(benches);
