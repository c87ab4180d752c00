//! Property test of the topology core (seed 003, Theorem 3): random ring sets (several
//! outer rings, some with holes) under random single-vertex moves — small, large, towards
//! other rings, onto vertices and edges, on the integer lattice — and vertex removals.
//! After every move: `sanity_check()`, the broad phase (bins or staggered hash) against
//! brute force, the event counts
//! against the ring counts, and the region against (R ∪ M⁺) − M⁻ evaluated independently
//! (see `topocontour::check`).
//!
//! CI runs 100,000 moves. `TOPO_MOVES=10000000 cargo test --release --test random_motions
//! -- --ignored` runs ten million.

use proptest::prelude::*;
use topocontour::check::{run_moves_under, run_random_moves, MoveMix};
use topocontour::contours::BroadPhaseKind;
use topocontour::topology::TopologyPolicy;

const CASES: u32 = 100;
const MOVES_PER_CASE: usize = 1000;

proptest! {
    #![proptest_config(ProptestConfig { cases: CASES, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_moves_keep_rings_correct(seed in any::<u64>(), rings in 1usize..7, lattice in proptest::bool::weighted(0.3), hash in proptest::bool::weighted(0.3), wall in proptest::bool::weighted(0.3)) {
        let broad = if hash { BroadPhaseKind::Hash } else { BroadPhaseKind::Bins };
        let r = run_random_moves(seed, rings, MOVES_PER_CASE, MoveMix { lattice, broad, wall });
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}

#[test]
#[ignore = "long run: set TOPO_MOVES (default 10,000,000)"]
fn ten_million_random_moves() {
    let total: usize = std::env::var("TOPO_MOVES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000_000);
    let per = 5_000;
    let mut events = 0;
    for i in 0..total.div_ceil(per) {
        let seed = 0x5EED_0000 + i as u64;
        events += run_random_moves(
            seed,
            1 + i % 6,
            per,
            MoveMix {
                lattice: i % 3 == 0,
                broad: if i % 2 == 0 {
                    BroadPhaseKind::Bins
                } else {
                    BroadPhaseKind::Hash
                },
                wall: i % 5 == 2,
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
    }
    println!("{total} moves, {events} topology events");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, failure_persistence: None, ..ProptestConfig::default() })]

    /// The tracking policy (seed 003 with merges and new holes held back): no merge and no
    /// new hole ever happens, every split is reported (the oracle's event bookkeeping),
    /// `sanity_check` holds after every move, an allowed move is exactly the adaptive one
    /// and a held move changes nothing.
    #[test]
    fn random_moves_under_the_tracking_policy(seed in any::<u64>(), rings in 1usize..7, lattice in proptest::bool::weighted(0.3), hash in proptest::bool::weighted(0.3), wall in proptest::bool::weighted(0.3)) {
        let broad = if hash { BroadPhaseKind::Hash } else { BroadPhaseKind::Bins };
        let r = run_moves_under(seed, rings, MOVES_PER_CASE, MoveMix { lattice, broad, wall }, TopologyPolicy::TRACKING);
        prop_assert!(r.is_ok(), "{}", r.unwrap_err());
    }
}

/// Over many seeds the tracking policy both holds moves back and lets splits through, so
/// the property above is not vacuous.
#[test]
fn the_tracking_policy_holds_merges_and_lets_splits_through() {
    let (mut events, mut held) = (0, 0);
    for seed in 0..20u64 {
        let mix = MoveMix {
            lattice: false,
            broad: BroadPhaseKind::Bins,
            wall: false,
        };
        let (e, h) = run_moves_under(seed, 4, 1000, mix, TopologyPolicy::TRACKING).unwrap();
        events += e;
        held += h;
    }
    assert!(held > 50, "held {held}");
    assert!(events > 20, "events {events}");
}
