//! Replays random-move checks: `replay SEED RINGS LATTICE(0|1) MOVES [COUNT]` checks COUNT
//! consecutive seeds from SEED and prints the first failure. `TOPO_BROAD=hash` uses the
//! staggered hash.
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let seed: u64 = a[1].parse().unwrap();
    let rings: usize = a[2].parse().unwrap();
    let lattice = a[3] == "1";
    let moves: usize = a[4].parse().unwrap();
    let count: u64 = a.get(5).map_or(1, |c| c.parse().unwrap());
    let broad = match std::env::var("TOPO_BROAD").as_deref() {
        Ok("hash") => topocontour::contours::BroadPhaseKind::Hash,
        _ => topocontour::contours::BroadPhaseKind::Bins,
    };
    let mut events = 0;
    for s in seed..seed + count {
        let r = (rings + s as usize) % 6 + 1;
        match topocontour::check::run_random_moves(
            s,
            r,
            moves,
            topocontour::check::MoveMix {
                lattice: lattice || s % 3 == 0,
                broad,
                wall: s % 4 == 1,
            },
        ) {
            Ok(e) => events += e,
            Err(e) => {
                println!("seed {s} rings {r}: {e}");
                std::process::exit(1);
            }
        }
    }
    println!("ok: {} moves, {events} events", count as usize * moves);
}
