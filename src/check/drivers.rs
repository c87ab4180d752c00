//! Drivers: many random moves checked one by one (property tests), and fuzzer bytes
//! decoded into moves (the fuzz target and the regression tests of its finds).

use super::*;
use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{segment_intersection, Aabb, Point, SegmentIntersection};
use crate::topology::{MoveError, TopologyEvent, TopologyPolicy};

/// Runs `moves` random moves on a random ring set from `seed`, checking each one.
/// Returns the number of topology events seen.
pub fn run_random_moves(
    seed: u64,
    rings: usize,
    moves: usize,
    mix: MoveMix,
) -> Result<u64, String> {
    run_moves_under(seed, rings, moves, mix, TopologyPolicy::ADAPTIVE).map(|(events, _)| events)
}

/// [`run_random_moves`] with every move made under `policy`. Besides the oracle's checks,
/// each move is made on a copy without a policy too: where the policy allows all of that
/// move's events, the result and the rings must be the same; where it forbids one, the
/// move must be held ([`MoveError::Held`]) and change nothing. Where merges are held, a
/// move whose new edges meet another object's outline may be held whatever it causes.
/// Returns the events seen and the moves held.
pub fn run_moves_under(
    seed: u64,
    rings: usize,
    moves: usize,
    mix: MoveMix,
    policy: TopologyPolicy,
) -> Result<(u64, u64), String> {
    let mut rng = Rng(seed);
    let mut set = random_rings_in(&mut rng, rings.max(1), 6.0, mix.broad);
    let domain = set.domain();
    let mut oracle = Oracle::new(&set, domain, 40);
    let (mut events, mut held) = (0u64, 0u64);
    for step in 0..moves {
        if set.vertex_count() < 12 || set.contour_count() == 0 {
            let c = Point::new(rng.range(15.0, 85.0), rng.range(15.0, 85.0));
            add_star(&mut set, &mut rng, c);
            oracle.resync(&set);
            if set.vertex_count() == 0 {
                continue;
            }
        }
        let v = loop {
            let v = rng.below(set.vertex_capacity()) as u32;
            if set.is_alive(v) {
                break v;
            }
        };
        let before = snapshot(&set);
        let kinds = ring_kinds(&set);
        let (p, o, n) = (
            set.position(set.prev(v)),
            set.position(v),
            set.position(set.next(v)),
        );
        let remove = set.vertex_count() > 400 || rng.below(10) == 0;
        let q = if remove {
            None
        } else {
            let q = draw_target(&set, v, &mut rng, mix);
            broad_phase_offers_all(&set, Aabb::of(&[p, q, n]))
                .map_err(|w| format!("seed {seed} step {step}: broad phase missed edge {w}"))?;
            Some(q)
        };
        let layout_before = (policy != TopologyPolicy::ADAPTIVE).then(|| layout(&set));
        let meets_other = !policy.merge && new_edges_meet_another_object(&set, v, q);
        let free = (policy != TopologyPolicy::ADAPTIVE).then(|| {
            let mut copy = set.clone();
            let r = match q {
                Some(q) => copy.move_vertex(v, q),
                None => copy.remove_vertex(v),
            };
            (copy, r)
        });
        let result = match q {
            Some(q) => set.move_vertex_under(v, q, policy),
            None => set.remove_vertex_under(v, policy),
        };
        let at = |e: String| {
            format!(
                "seed {seed} step {step}: move of {v} from {o:?} to {q:?} (p {p:?}, n {n:?}): {e}"
            )
        };
        if let Some((copy, r)) = free {
            compare_with_free(&set, &result, &copy, &r, policy, meets_other).map_err(at)?;
        }
        if matches!(result, Err(MoveError::Held(_))) && layout_before != Some(layout(&set)) {
            return Err(at("a held move left the set's layout changed".into()));
        }
        match &result {
            Ok(ev) => events += ev.len() as u64,
            Err(MoveError::Held(_)) => held += 1,
            Err(_) => {}
        }
        oracle
            .check_move(&set, &before, kinds, (p, o, n, q), &result, &mut rng)
            .map_err(at)?;
    }
    Ok((events, held))
}

/// What a held move must leave exactly as it was, beyond the rings' points: each ring's
/// id, anchor and vertex ids in order, and which vertex slots are free.
type Layout = (Vec<(u32, Vec<u32>)>, Vec<u32>, usize);

fn layout(set: &ContourSet) -> Layout {
    let rings = set
        .contour_ids()
        .map(|id| {
            let r = set.rings[id.0 as usize].expect("live ring");
            (id.0, set.walk(r.anchor).collect())
        })
        .collect();
    let mut free = set.free.clone();
    free.sort_unstable();
    (rings, free, set.vertex_capacity())
}

/// Whether the broad phase offers every edge that brute force finds meeting `b` (`Err`:
/// the first edge it missed).
fn broad_phase_offers_all(set: &ContourSet, b: Aabb) -> Result<(), u32> {
    let mut near = Vec::new();
    set.edges_near(&b, &mut near);
    for w in set.vertices() {
        if segment_meets_box(set.position(w), set.position(set.next(w)), &b) && !near.contains(&w) {
            return Err(w);
        }
    }
    Ok(())
}

/// Whether the new edges of moving `v` to `q` (removing it, for `None`) meet the outline
/// of another object, by brute force: an outer ring other than `v`'s, itself outer. Any
/// shared point counts, so the core's handling of touching edges is not second-guessed.
fn new_edges_meet_another_object(set: &ContourSet, v: u32, q: Option<Point>) -> bool {
    let own = set.contour_of(v);
    if set.is_hole(own) {
        return false;
    }
    let (p, n) = (set.position(set.prev(v)), set.position(set.next(v)));
    let edges: Vec<(Point, Point)> = match q {
        Some(q) => vec![(p, q), (q, n)],
        None => vec![(p, n)],
    };
    set.vertices().any(|w| {
        let ring = set.contour_of(w);
        ring != own
            && !set.is_hole(ring)
            && edges.iter().any(|&(a, b)| {
                !matches!(
                    segment_intersection(a, b, set.position(w), set.position(set.next(w))),
                    SegmentIntersection::None
                )
            })
    })
}

/// A move under a policy against the same move without one (`copy`, `free`).
fn compare_with_free(
    set: &ContourSet,
    result: &Result<Vec<TopologyEvent>, MoveError>,
    copy: &ContourSet,
    free: &Result<Vec<TopologyEvent>, MoveError>,
    policy: TopologyPolicy,
    meets_other: bool,
) -> Result<(), String> {
    match (free, result) {
        (Ok(ev), Err(MoveError::Held(_))) if ev.iter().any(|e| !policy.allows(e)) => Ok(()),
        // Where merges are held, a move into another object is held whatever it causes.
        (Ok(_), Err(MoveError::Held(_))) if meets_other => Ok(()),
        (Ok(ev), Ok(got)) if ev.iter().all(|e| policy.allows(e)) => {
            if got != ev || snapshot(set) != snapshot(copy) {
                return Err(format!("allowed move differs: {got:?} vs {ev:?}"));
            }
            Ok(())
        }
        (Err(e), Err(got)) if e == got => Ok(()),
        _ => Err(format!(
            "under {policy:?}: {result:?}, without a policy: {free:?}"
        )),
    }
}

/// Decodes fuzzer bytes into a ring set and a sequence of moves and removals, checking
/// every step like the property test. Input: 2 bytes of set-up, then 6 bytes per step
/// (vertex, kind, dx, dy, fraction). Used by `fuzz/` and by the regression tests of its
/// finds.
pub fn run_fuzz_bytes(data: &[u8]) -> Result<(), String> {
    if data.len() < 2 {
        return Ok(());
    }
    let mut rng = Rng(data[0] as u64);
    // The top bit of the second byte picks the broad phase.
    let broad = if data[1] & 0x80 != 0 {
        BroadPhaseKind::Hash
    } else {
        BroadPhaseKind::Bins
    };
    let mut set = random_rings_in(&mut rng, 1 + ((data[1] & 0x7f) % 6) as usize, 6.0, broad);
    let domain = set.domain();
    let mut oracle = Oracle::new(&set, domain, 24);
    for step in data[2..].chunks_exact(6) {
        if set.vertex_count() == 0 {
            return Ok(());
        }
        let alive: Vec<u32> = set.vertices().collect();
        let v = alive[u16::from_le_bytes([step[0], step[1]]) as usize % alive.len()];
        let (p, o, n) = (
            set.position(set.prev(v)),
            set.position(v),
            set.position(set.next(v)),
        );
        let before = snapshot(&set);
        let kinds = ring_kinds(&set);
        let (dx, dy) = ((step[3] as i8) as f64, (step[4] as i8) as f64);
        let frac = step[5] as f64 / 255.0;
        let (q, result) = match step[2] % 8 {
            0 => (None, set.remove_vertex(v)),
            // Onto another vertex, or onto a point of another edge: exact degeneracies.
            1 => {
                let w = alive[(step[3] as usize * 256 + step[4] as usize) % alive.len()];
                let q = set.position(w);
                (Some(q), set.move_vertex(v, q))
            }
            2 => {
                let w = alive[(step[3] as usize) % alive.len()];
                let q = set.position(w).lerp(set.position(set.next(w)), frac);
                (Some(q), set.move_vertex(v, q))
            }
            // On the integer lattice.
            3 => {
                let q = Point::new((o.x + dx / 8.0).round(), (o.y + dy / 8.0).round());
                (Some(q), set.move_vertex(v, q))
            }
            // Small and large displacements.
            4..=6 => {
                let s = [1.0 / 32.0, 1.0 / 8.0, 0.5][(step[2] % 8 - 4) as usize];
                let q = o + Point::new(dx * s, dy * s);
                (Some(q), set.move_vertex(v, q))
            }
            _ => {
                let q = n.lerp(p, frac * 2.0 - 0.5) + Point::new(dx / 64.0, dy / 64.0);
                (Some(q), set.move_vertex(v, q))
            }
        };
        oracle
            .check_move(&set, &before, kinds, (p, o, n, q), &result, &mut rng)
            .map_err(|e| format!("move of {v} from {o:?} to {q:?} (p {p:?}, n {n:?}): {e}"))?;
    }
    Ok(())
}
