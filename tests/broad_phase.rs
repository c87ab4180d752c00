//! The two broad phases — vertex bins (seed 003) and staggered hashing (seed 001) —
//! against each other and against brute force.
//!
//! - Vertex queries: after random inserts, moves and removals, each answer holds every
//!   vertex in the box, no duplicates, and once cut to the box both answers equal brute
//!   force.
//! - Edge queries on ring sets: the edges offered near a box, cut to the edges that meet
//!   it, are the same for both and equal brute force.
//! - Counted regions (the quiet-move certificate): a region covers every vertex lying in
//!   its box, its exact count equals brute force (hash collisions included), and the fast
//!   count is never less.
//! - Whole motions: the same random moves run on a bins set and a hash set give the same
//!   rings and the same events, move after move.

use proptest::prelude::*;
use std::collections::BTreeSet;
use topocontour::check::{draw_target, random_rings_in, segment_meets_box, snapshot, MoveMix, Rng};
use topocontour::contours::{BroadPhase, BroadPhaseKind, Countable, StaggeredHash, VertexBins};
use topocontour::{Aabb, Point};

fn domain() -> Aabb {
    Aabb {
        min: Point::new(0.0, 0.0),
        max: Point::new(100.0, 100.0),
    }
}

fn in_box(b: &Aabb, p: Point) -> bool {
    p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y && p.y <= b.max.y
}

fn random_box(rng: &mut Rng) -> Aabb {
    let c = Point::new(rng.range(-10.0, 110.0), rng.range(-10.0, 110.0));
    // Mostly move-sized boxes, sometimes large ones (long moves, Directive 2 boxes).
    let s = if rng.below(4) == 0 {
        rng.range(5.0, 80.0)
    } else {
        rng.range(0.0, 6.0)
    };
    let (w, h) = (rng.range(0.0, s), rng.range(0.0, s));
    Aabb {
        min: c,
        max: Point::new(c.x + w, c.y + h),
    }
}

/// Rings as point lists, each started at its least point, sorted: equal geometry compares
/// equal whatever vertex a ring is anchored at.
fn canonical(set: &topocontour::ContourSet) -> Vec<Vec<(f64, f64)>> {
    let mut rings: Vec<Vec<(f64, f64)>> = snapshot(set)
        .pts
        .into_iter()
        .map(|r| {
            let mut r: Vec<(f64, f64)> = r.iter().map(|p| (p.x, p.y)).collect();
            let k = (0..r.len())
                .min_by(|&i, &j| r[i].partial_cmp(&r[j]).unwrap())
                .unwrap();
            r.rotate_left(k);
            r
        })
        .collect();
    rings.sort_by(|a, b| a.partial_cmp(b).unwrap());
    rings
}

/// Checks the region counted for box `bx` against brute force over the live vertices.
fn check_region<B: Countable>(
    name: &str,
    b: &B,
    bx: &Aabb,
    pos: &[Option<Point>],
) -> Result<(), TestCaseError> {
    let Some((r, held)) = b.region(bx) else {
        return Ok(());
    };
    let mut inside = 0;
    for (v, p) in pos.iter().enumerate() {
        let Some(p) = p else { continue };
        let registered = b.in_region(v as u32, &r);
        prop_assert!(
            registered || !in_box(bx, *p),
            "{}: vertex {} in the box, not in its region",
            name,
            v
        );
        inside += registered as u32;
    }
    prop_assert_eq!(b.exact_count(&r), inside, "{}: exact count", name);
    prop_assert!(
        held >= inside,
        "{}: fast count {} below {}",
        name,
        held,
        inside
    );
    Ok(())
}

/// Events in a fixed order (candidates arrive in a broad-phase-specific order).
fn sorted(ev: Vec<topocontour::TopologyEvent>) -> Vec<String> {
    let mut s: Vec<String> = ev.iter().map(|e| format!("{e:?}")).collect();
    s.sort();
    s
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn vertex_queries_agree_with_brute_force(seed in any::<u64>(), cell in 0.5f64..8.0) {
        let mut rng = Rng(seed);
        let mut bins = VertexBins::new(domain(), cell);
        let mut hash = StaggeredHash::new(cell);
        let mut pos: Vec<Option<Point>> = Vec::new();
        let mut a = Vec::new();
        let mut b = Vec::new();
        for _ in 0..600 {
            let v = rng.below(pos.len() + 1);
            // Some positions outside the domain: bins clamp them, the hash has no domain.
            let p = Point::new(rng.range(-20.0, 120.0), rng.range(-20.0, 120.0));
            match (v == pos.len(), pos.get(v).copied().flatten()) {
                (true, _) => {
                    pos.push(Some(p));
                    bins.insert(v as u32, p);
                    hash.insert(v as u32, p);
                }
                (false, Some(_)) if rng.below(3) == 0 => {
                    pos[v] = None;
                    bins.remove(v as u32);
                    hash.remove(v as u32);
                }
                (false, Some(o)) => {
                    let q = if rng.below(2) == 0 { o + Point::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)) } else { p };
                    pos[v] = Some(q);
                    bins.update(v as u32, q);
                    hash.update(v as u32, q);
                }
                (false, None) => {
                    pos[v] = Some(p);
                    bins.insert(v as u32, p);
                    hash.insert(v as u32, p);
                }
            }
            let bx = random_box(&mut rng);
            check_region("bins", &bins, &bx, &pos)?;
            check_region("hash", &hash, &bx, &pos)?;
            bins.query(&bx, &mut a);
            hash.query(&bx, &mut b);
            let brute: BTreeSet<u32> = pos.iter().enumerate()
                .filter(|(_, p)| p.is_some_and(|p| in_box(&bx, p)))
                .map(|(i, _)| i as u32).collect();
            for (name, ans) in [("bins", &a), ("hash", &b)] {
                let set: BTreeSet<u32> = ans.iter().copied().collect();
                prop_assert_eq!(set.len(), ans.len(), "{} returned duplicates", name);
                prop_assert!(set.iter().all(|&v| pos[v as usize].is_some()), "{} returned a removed vertex", name);
                let cut: BTreeSet<u32> = set.into_iter().filter(|&v| in_box(&bx, pos[v as usize].unwrap())).collect();
                prop_assert_eq!(&cut, &brute, "{} differs from brute force", name);
            }
        }
        let live = pos.iter().filter(|p| p.is_some()).count();
        prop_assert_eq!(bins.len(), live);
        prop_assert_eq!(hash.len(), live);
        for (v, p) in pos.iter().enumerate() {
            if let Some(p) = p {
                prop_assert!(bins.finds(v as u32, *p) && hash.finds(v as u32, *p));
            }
        }
    }

    #[test]
    fn edge_queries_agree_with_brute_force(seed in any::<u64>(), rings in 1usize..7) {
        let sets: Vec<_> = [BroadPhaseKind::Bins, BroadPhaseKind::Hash]
            .into_iter()
            .map(|k| random_rings_in(&mut Rng(seed), rings, 6.0, k))
            .collect();
        let mut rng = Rng(seed ^ 0xB0C5);
        let mut near = Vec::new();
        for _ in 0..200 {
            let bx = random_box(&mut rng);
            let brute: BTreeSet<u32> = sets[0].vertices()
                .filter(|&w| segment_meets_box(sets[0].position(w), sets[0].position(sets[0].next(w)), &bx))
                .collect();
            for set in &sets {
                set.edges_near(&bx, &mut near);
                let cut: BTreeSet<u32> = near.iter().copied()
                    .filter(|&w| segment_meets_box(set.position(w), set.position(set.next(w)), &bx))
                    .collect();
                prop_assert_eq!(&cut, &brute, "{:?}", set.broad_phase());
            }
        }
    }

    #[test]
    fn motions_are_identical_with_either_broad_phase(seed in any::<u64>(), rings in 1usize..7) {
        let mut sets: Vec<_> = [BroadPhaseKind::Bins, BroadPhaseKind::Hash]
            .into_iter()
            .map(|k| random_rings_in(&mut Rng(seed), rings, 6.0, k))
            .collect();
        let mut rng = Rng(seed ^ 0x4A5B);
        let mix = MoveMix { lattice: seed % 3 == 0, broad: BroadPhaseKind::Bins, wall: seed % 4 == 1 };
        for step in 0..400 {
            if sets[0].vertex_count() < 12 {
                break;
            }
            let v = loop {
                let v = rng.below(sets[0].vertex_capacity()) as u32;
                if sets[0].is_alive(v) {
                    break v;
                }
            };
            let q = draw_target(&sets[0], v, &mut rng, mix);
            // Refusals may name a different first degeneracy; that they refuse must agree.
            let a = sets[0].move_vertex(v, q).map(sorted).map_err(|_| ());
            let b = sets[1].move_vertex(v, q).map(sorted).map_err(|_| ());
            prop_assert_eq!(&a, &b, "step {}", step);
            prop_assert_eq!(canonical(&sets[0]), canonical(&sets[1]), "step {}", step);
        }
        sets[1].sanity_check().map_err(TestCaseError::fail)?;
    }
}
