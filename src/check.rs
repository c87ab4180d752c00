//! Independent checks of the topology core, shared by the property tests, the fuzz
//! target and the `bench` command's self-test.
//!
//! The oracle never calls the core's predicates: it decides "is this point in the region"
//! with a plain floating-point crossing count over the rings, and only at sample points
//! farther than [`NEAR`] from every edge, where rounding cannot change the answer. After a
//! move it checks that every sample in the motion region's box obeys equation 2 of seed
//! 003 — in the region iff M's winding is +1, or it is 0 and the point was in R before —
//! and that a bitmap of the whole domain, updated by the same rule move after move,
//! still matches (so nothing changed outside the motion region either).
//!
//! Set `TOPO_TRACE=1` to print the rings before and after a failing move.

use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{point_segment_distance, Aabb, Point};
use crate::topology::{MoveError, TopologyEvent};

/// Samples closer than this to an edge are skipped.
pub const NEAR: f64 = 1e-6;

/// SplitMix64: a tiny deterministic generator, so a failing seed replays exactly.
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}

/// Rings as point lists with their bounding boxes.
#[derive(Clone, Debug, PartialEq)]
pub struct Rings {
    pub pts: Vec<Vec<Point>>,
    boxes: Vec<Aabb>,
}

/// Crossing-number membership of `x` in the region bounded by `rings` (plain floats).
pub fn region_has(rings: &Rings, x: Point) -> bool {
    let mut inside = false;
    for (r, b) in rings.pts.iter().zip(&rings.boxes) {
        if x.y < b.min.y || x.y > b.max.y || x.x > b.max.x {
            continue;
        }
        let n = r.len();
        for i in 0..n {
            let (a, b) = (r[i], r[(i + 1) % n]);
            if (a.y > x.y) != (b.y > x.y) {
                let xc = a.x + (x.y - a.y) * (b.x - a.x) / (b.y - a.y);
                if xc > x.x {
                    inside = !inside;
                }
            }
        }
    }
    inside
}

/// Plain winding number of a closed polygon around `x` (floats; `x` far from it).
fn loop_winding(pts: &[Point], x: Point) -> i32 {
    let mut w = 0;
    let n = pts.len();
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        let side = (b.x - a.x) * (x.y - a.y) - (x.x - a.x) * (b.y - a.y);
        if a.y <= x.y && b.y > x.y && side > 0.0 {
            w += 1;
        } else if a.y > x.y && b.y <= x.y && side < 0.0 {
            w -= 1;
        }
    }
    w
}

fn near_any(rings: &Rings, x: Point) -> bool {
    rings
        .pts
        .iter()
        .zip(&rings.boxes)
        .any(|(r, b)| b.expand(NEAR).contains(x) && near_loop(r, x))
}

fn near_loop(pts: &[Point], x: Point) -> bool {
    (0..pts.len()).any(|i| point_segment_distance(x, pts[i], pts[(i + 1) % pts.len()]) < NEAR)
}

/// Whether segment a–b meets box `r` (brute force, for checking the broad phase).
pub fn segment_meets_box(a: Point, b: Point, r: &Aabb) -> bool {
    if r.contains(a) || r.contains(b) {
        return true;
    }
    let c = [
        r.min,
        Point::new(r.max.x, r.min.y),
        r.max,
        Point::new(r.min.x, r.max.y),
    ];
    (0..4).any(|i| {
        crate::geometry::segment_intersection(a, b, c[i], c[(i + 1) % 4])
            != crate::geometry::SegmentIntersection::None
    })
}

/// Every ring's points.
pub fn snapshot(set: &ContourSet) -> Rings {
    rings_of(
        &set.contour_ids()
            .map(|id| set.ring_points(id))
            .collect::<Vec<_>>(),
    )
}

/// Rings from point lists.
pub fn rings_of(pts: &[Vec<Point>]) -> Rings {
    let boxes = pts.iter().map(|p| Aabb::of(p)).collect();
    Rings {
        pts: pts.to_vec(),
        boxes,
    }
}

/// Numbers of outer and hole rings.
pub fn ring_kinds(set: &ContourSet) -> (i64, i64) {
    let holes = set.contour_ids().filter(|&id| set.is_hole(id)).count() as i64;
    (set.contour_count() as i64 - holes, holes)
}

/// Tracks the expected region on a grid across many moves, and checks each move.
pub struct Oracle {
    domain: Aabb,
    n: usize,
    /// Expected membership per grid sample; `None` when it was too close to an edge to say.
    grid: Vec<Option<bool>>,
    moves_since_full: u32,
    pub moves_checked: u64,
    pub samples_checked: u64,
}

impl Oracle {
    pub fn new(set: &ContourSet, domain: Aabb, n: usize) -> Self {
        let mut o = Oracle {
            domain,
            n,
            grid: vec![None; n * n],
            moves_since_full: 0,
            moves_checked: 0,
            samples_checked: 0,
        };
        o.resync(set);
        o
    }

    fn grid_point(&self, i: usize) -> Point {
        let (ix, iy) = (i % self.n, i / self.n);
        // Irrational-ish offsets keep samples off lattice-aligned geometry.
        let fx = (ix as f64 + 0.5 + 0.123_456_7) / self.n as f64;
        let fy = (iy as f64 + 0.5 + 0.234_567_8) / self.n as f64;
        Point::new(
            self.domain.min.x + fx * (self.domain.max.x - self.domain.min.x),
            self.domain.min.y + fy * (self.domain.max.y - self.domain.min.y),
        )
    }

    /// Re-reads unknown grid entries from the set (after rings were added, say).
    pub fn resync(&mut self, set: &ContourSet) {
        let rings = snapshot(set);
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            self.grid[i] = (!near_any(&rings, x)).then(|| region_has(&rings, x));
        }
    }

    /// Compares the whole grid with `rings`: nothing may have changed outside the motion
    /// regions. Entries unknown so far are learned where they are clear of every edge.
    pub fn compare_grid(&mut self, rings: &Rings) -> Result<(), String> {
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            if near_any(rings, x) {
                self.grid[i] = None;
                continue;
            }
            let now = region_has(rings, x);
            match self.grid[i] {
                Some(expect) if expect != now => {
                    return Err(format!(
                        "grid sample {x:?} is {now} but every motion since says {expect}"
                    ));
                }
                Some(_) => self.samples_checked += 1,
                None => self.grid[i] = Some(now),
            }
        }
        Ok(())
    }

    /// Checks one move of a vertex with neighbours `p`, `n` from `o` to `q` (`None`:
    /// removal), given the rings `before` it and its result.
    #[allow(clippy::too_many_arguments)]
    pub fn check_move(
        &mut self,
        set: &ContourSet,
        before: &Rings,
        kinds_before: (i64, i64),
        (p, o, n, q): (Point, Point, Point, Option<Point>),
        result: &Result<Vec<TopologyEvent>, MoveError>,
        rng: &mut Rng,
    ) -> Result<(), String> {
        if let Err(e) = set.sanity_check() {
            if std::env::var("TOPO_TRACE").is_ok() {
                eprintln!("move p {p:?} o {o:?} n {n:?} q {q:?} result {result:?}");
                for (i, r) in before.pts.iter().enumerate() {
                    eprintln!("before {i}: {r:?}");
                }
                for id in set.contour_ids() {
                    eprintln!(
                        "after {id} hole {} {:?}",
                        set.is_hole(id),
                        set.ring_points(id)
                    );
                }
            }
            return Err(e);
        }
        self.moves_checked += 1;
        let after = snapshot(set);
        let mloop: Vec<Point> = match q {
            Some(q) => vec![p, q, n, o],
            None => vec![p, n, o],
        };
        let events = match result {
            Err(_) => {
                if after != *before {
                    return Err("a refused move changed the rings".into());
                }
                return Ok(());
            }
            Ok(ev) => ev,
        };
        // Event bookkeeping matches the change in outer and hole counts.
        let (mut d_outer, mut d_holes) = (0i64, 0i64);
        for e in events {
            match e {
                TopologyEvent::Split { .. } => d_outer += 1,
                TopologyEvent::Merge { .. } | TopologyEvent::Vanished { .. } => d_outer -= 1,
                TopologyEvent::HoleMade { .. } => d_holes += 1,
                TopologyEvent::HoleGone { .. } => d_holes -= 1,
            }
        }
        let kinds_after = ring_kinds(set);
        if (
            kinds_after.0 - kinds_before.0,
            kinds_after.1 - kinds_before.1,
        ) != (d_outer, d_holes)
        {
            return Err(format!(
                "events {events:?} do not explain rings {kinds_before:?} -> {kinds_after:?}"
            ));
        }
        // Random samples in M's box: equation 2.
        let b = Aabb::of(&mloop);
        for _ in 0..24 {
            let x = Point::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y));
            if near_loop(&mloop, x) || near_any(before, x) || near_any(&after, x) {
                continue;
            }
            self.samples_checked += 1;
            let w = loop_winding(&mloop, x);
            let expect = match w {
                1 => true,
                -1 => false,
                _ => region_has(before, x),
            };
            if region_has(&after, x) != expect {
                return Err(format!(
                    "sample {x:?}: winding {w}, expected in-region {expect}"
                ));
            }
        }
        // The grid: entries inside M's box follow the same rule.
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            if b.contains(x) {
                self.grid[i] = match (near_loop(&mloop, x), loop_winding(&mloop, x)) {
                    (true, _) => None,
                    (false, 1) => Some(true),
                    (false, -1) => Some(false),
                    (false, _) => self.grid[i],
                };
            }
        }
        self.moves_since_full += 1;
        if self.moves_since_full >= 200 {
            self.moves_since_full = 0;
            self.compare_grid(&after)?;
        }
        Ok(())
    }
}

/// A star-shaped ring around `c` with radii in [r0, r1], `k` vertices, positive area
/// (outer) or reversed (hole).
pub fn star_ring(rng: &mut Rng, c: Point, r0: f64, r1: f64, k: usize, hole: bool) -> Vec<Point> {
    let mut pts: Vec<Point> = (0..k)
        .map(|i| {
            let a = std::f64::consts::TAU * (i as f64 + rng.range(-0.3, 0.3)) / k as f64;
            let r = rng.range(r0, r1);
            Point::new(c.x + r * a.cos(), c.y + r * a.sin())
        })
        .collect();
    if hole {
        pts.reverse();
    }
    pts
}

/// How moves are drawn.
#[derive(Clone, Copy, Debug)]
pub struct MoveMix {
    /// Snap every target to the integer lattice (makes exact degeneracies frequent).
    pub lattice: bool,
    /// The broad phase of the set under test.
    pub broad: BroadPhaseKind,
    /// Clamp every target to the domain, as the evolver does at the image border: many
    /// vertices and edges then lie on the walls, collinear with each other.
    pub wall: bool,
}

/// Draws a target for vertex `v`: small, medium, toward another vertex (topology events),
/// or deliberately degenerate (onto a vertex, an edge, a neighbour's line).
pub fn draw_target(set: &ContourSet, v: u32, rng: &mut Rng, mix: MoveMix) -> Point {
    let o = set.position(v);
    let other = loop {
        let w = rng.below(set.vertex_capacity()) as u32;
        if set.is_alive(w) {
            break w;
        }
    };
    let kind = rng.below(100);
    let mut q = match kind {
        0..=39 => o + Point::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0)),
        40..=59 => o + Point::new(rng.range(-8.0, 8.0), rng.range(-8.0, 8.0)),
        60..=79 => set.position(other) + Point::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)),
        80..=84 => set.position(other),
        85..=89 => set.position(other).lerp(set.position(set.next(other)), 0.5),
        90..=94 => {
            let (p, pp) = (
                set.position(set.prev(v)),
                set.position(set.prev(set.prev(v))),
            );
            p + (p - pp) * rng.range(0.2, 1.5)
        }
        _ => o.lerp(set.position(set.next(v)), rng.range(-0.5, 1.5)),
    };
    if mix.lattice {
        q = Point::new(q.x.round(), q.y.round());
    }
    if mix.wall {
        return set.domain().clamp(q);
    }
    set.domain().expand(10.0).clamp(q)
}

/// Builds a set of `k` star-shaped outer rings on a 3×3 layout, some with a hole.
pub fn random_rings(rng: &mut Rng, k: usize, max_edge: f64) -> ContourSet {
    random_rings_in(rng, k, max_edge, BroadPhaseKind::Bins)
}

/// [`random_rings`] with the broad phase of `kind`.
pub fn random_rings_in(rng: &mut Rng, k: usize, max_edge: f64, kind: BroadPhaseKind) -> ContourSet {
    let domain = Aabb {
        min: Point::new(0.0, 0.0),
        max: Point::new(100.0, 100.0),
    };
    let mut set = ContourSet::with_broad_phase(domain, max_edge, kind);
    let mut slots: Vec<usize> = (0..9).collect();
    for _ in 0..k.min(9) {
        let s = slots.swap_remove(rng.below(slots.len()));
        let c = Point::new(17.0 + 33.0 * (s % 3) as f64, 17.0 + 33.0 * (s / 3) as f64);
        add_star(&mut set, rng, c);
    }
    set
}

/// Adds a star-shaped ring (with a hole half the time) centred at `c` if it fits: it must
/// neither cross nor enclose nor sit inside what is there (add_ring only refuses
/// crossings; a star around small leftover rings would nest outer in outer).
pub fn add_star(set: &mut ContourSet, rng: &mut Rng, c: Point) -> bool {
    let max_edge = set.max_edge();
    let r1 = rng.range(7.0, 13.0);
    let k = ((std::f64::consts::TAU * r1 * 1.35 / max_edge).ceil() as usize).max(5) + rng.below(6);
    let outer = star_ring(rng, c, r1 * 0.6, r1, k, false);
    let fits = |set: &mut ContourSet, id| {
        let ok = set.sanity_check().is_ok();
        if !ok {
            set.remove_ring(id);
        }
        ok
    };
    match set.add_ring(&outer) {
        Ok(id) if fits(set, id) => {}
        _ => return false,
    }
    if rng.below(2) == 0 {
        let hr = r1 * 0.45;
        let kh =
            ((std::f64::consts::TAU * hr * 1.35 / max_edge).ceil() as usize).max(3) + rng.below(3);
        let hole = star_ring(rng, c, hr * 0.6, hr, kh, true);
        if let Ok(id) = set.add_ring(&hole) {
            fits(set, id);
        }
    }
    true
}

/// `rings` circles of 100 vertices (radius 25, edges ≈ 1.6 px, bound 2.5 px) on a square
/// grid of pitch 60 px: the benchmark and profiling set-up.
pub fn ring_grid(rings: usize, kind: BroadPhaseKind) -> ContourSet {
    let side = (rings as f64).sqrt().ceil() as usize;
    let pitch = 60.0;
    let extent = side as f64 * pitch;
    let mut set = ContourSet::with_broad_phase(
        Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(extent, extent),
        },
        2.5,
        kind,
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
        set.add_ring(&pts).expect("grid rings are disjoint");
    }
    set
}

/// The benchmark's moves on a [`ring_grid`]: each vertex in turn steps out by a seeded
/// jitter of up to 0.2 px, then back home on the next move, like an evolving contour;
/// the set stays as built. The same seed on two sets built alike gives the same moves.
pub struct JitterMoves {
    verts: Vec<u32>,
    home: Vec<Point>,
    jitter: Vec<Point>,
    k: usize,
    out: bool,
}

/// Distinct jitters (a power of two: the index wraps by a mask).
const JITTERS: usize = 4096;

impl JitterMoves {
    pub fn new(set: &ContourSet, seed: u64) -> Self {
        let mut rng = Rng(seed);
        let verts: Vec<u32> = set.vertices().collect();
        let home = verts.iter().map(|&v| set.position(v)).collect();
        let jitter = (0..JITTERS)
            .map(|_| Point::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)))
            .collect();
        JitterMoves {
            verts,
            home,
            jitter,
            k: 0,
            out: true,
        }
    }

    /// The next move: which vertex, and where to.
    #[inline]
    pub fn next_move(&mut self) -> (u32, Point) {
        let k = self.k;
        let to = if self.out {
            self.home[k] + self.jitter[k & (JITTERS - 1)]
        } else {
            self.home[k]
        };
        // The next vertex by a compare, not a division: a 64-bit division alone costs
        // tens of cycles, a good part of what the benchmarks measure.
        if !self.out {
            self.k = if k + 1 == self.verts.len() { 0 } else { k + 1 };
        }
        self.out = !self.out;
        (self.verts[k], to)
    }
}

/// Runs `moves` random moves on a random ring set from `seed`, checking each one.
/// Returns the number of topology events seen.
pub fn run_random_moves(
    seed: u64,
    rings: usize,
    moves: usize,
    mix: MoveMix,
) -> Result<u64, String> {
    let mut rng = Rng(seed);
    let mut set = random_rings_in(&mut rng, rings.max(1), 6.0, mix.broad);
    let domain = set.domain();
    let mut oracle = Oracle::new(&set, domain, 40);
    let mut events = 0u64;
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
        let (q, result) = if remove {
            (None, set.remove_vertex(v))
        } else {
            let q = draw_target(&set, v, &mut rng, mix);
            // The broad phase must offer every edge that brute force finds near the move.
            let b = Aabb::of(&[p, q, n]);
            let mut near = Vec::new();
            set.edges_near(&b, &mut near);
            for w in set.vertices() {
                if segment_meets_box(set.position(w), set.position(set.next(w)), &b)
                    && !near.contains(&w)
                {
                    return Err(format!(
                        "seed {seed} step {step}: broad phase missed edge {w}"
                    ));
                }
            }
            (Some(q), set.move_vertex(v, q))
        };
        if let Ok(ev) = &result {
            events += ev.len() as u64;
        }
        oracle
            .check_move(&set, &before, kinds, (p, o, n, q), &result, &mut rng)
            .map_err(|e| format!("seed {seed} step {step}: move of {v} from {o:?} to {q:?} (p {p:?}, n {n:?}): {e}"))?;
    }
    Ok(events)
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
