//! Staggered spatial hashing: the second broad phase, after seed 001, §2 (Scheme 2,
//! equations 1–2 and Theorem 3), in 2D.
//!
//! Four systems of square boxes of side `l` cover the plane, offset by 0 or l/2 along
//! each axis: system (i, j) puts a point in box (⌊x/l + i/2⌋, ⌊y/l + j/2⌋) (equation 1).
//! Theorem 3, 2D: two points closer than l/2 along each axis share a box in at least one
//! system. Applied to a query box's two corners: **a query box whose sides are at most l/2
//! lies inside a single box of some system**, so it reads one hash bucket. Every vertex
//! is stored once per system. A larger box reads a rectangle of boxes of the system whose
//! offsets fit it best, chosen per axis (the four systems are the four pairs of offsets):
//! a box spanning m + 1 half-boxes along an axis needs ⌊m/2⌋ + 1 boxes there.
//!
//! Box size rule. Theorem 4's reasoning in 2D: two crossing edges of length at most s
//! have endpoints closer than s/√2, so l > √2·s would do for pair search. Our queries are
//! boxes instead — c' grown by s/2, sides about |p − n| + s — and we take l = 3s: a move
//! whose c' spans at most s/2 per axis reads one box, one spanning up to 2s at most two
//! boxes per axis. Smaller boxes make the quiet move's region tighter (a shorter walk),
//! larger ones make it one box more often; 3s took the fewest instructions per move
//! (`docs/decisions.md`).
//!
//! Table size: one table per system of at least twice the vertex count (the paper's
//! measured optimum), a power of two, doubled as vertices are added. The four systems'
//! buckets of one hash value sit side by side (bucket `4h + s`): boxes of the four systems
//! around one place share cache lines. An entry's box follows from its
//! vertex's half-box, so hash collisions are filtered exactly and answers never hold
//! duplicates.
//!
//! Hash function: where equation 2 multiplies the box indices by large primes, we wrap
//! the plane onto a torus of 2^⌈b/2⌉ × 2^⌊b/2⌋ boxes (b = log2 of the table size) and
//! take the box's position on it. A move reads a few neighbouring boxes, which land in
//! neighbouring buckets instead of random ones, and boxes collide only when a whole
//! torus side apart — never for contours within 2^⌊b/2⌋ boxes (1,024 at 10⁶ vertices),
//! so a move meets far fewer cache misses than with equation 2's multipliers
//! (`docs/decisions.md`).

use super::broad_phase::BroadPhase;
use crate::geometry::{Aabb, Point};

mod region;

pub use region::HashRegion;

const NIL: u32 = u32::MAX;
/// Box side in units of the edge bound (see the module doc).
pub const BOX_PER_EDGE: f64 = 3.0;
const MIN_TABLE: usize = 1024;

/// Four staggered hash grids of vertex lists (intrusive, so updates allocate nothing).
#[derive(Clone, Debug)]
pub struct StaggeredHash {
    inv_l: f64,
    torus: Torus,
    /// `4 << bits` bucket heads: system s of hash value h at `4h + s`.
    head: Vec<u32>,
    /// Nodes per bucket (the quiet-move certificate counts them, see [`crate::contours::Countable`]).
    fill: Vec<u32>,
    /// Per node `4 v + s`: list links and its bucket (`NIL` when absent).
    link_next: Vec<u32>,
    link_prev: Vec<u32>,
    bucket: Vec<u32>,
    /// Per vertex: its half-box, which fixes its box in every system (no per-node copy:
    /// a quarter of the memory a move and a query touch).
    half: Vec<[i32; 2]>,
    count: usize,
}

/// What a query box reads: a rectangle of boxes `lo ..= hi` of one system (one box
/// when the query's sides are at most l/2).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Reach {
    sys: usize,
    lo: [i32; 2],
    hi: [i32; 2],
}

impl Reach {
    fn boxes(&self) -> i64 {
        (self.hi[0] as i64 - self.lo[0] as i64 + 1) * (self.hi[1] as i64 - self.lo[1] as i64 + 1)
    }
}

#[inline]
fn floor_i32(f: f64) -> i32 {
    // ⌊f⌋ by truncating f + 2³¹ (one saturating cast: no fix-up for negatives, no libm
    // call on baseline x86_64). Within 2⁻²¹ below an integer the sum rounds up to it, so
    // this is ⌊f⌋ or ⌊f⌋ + 1 there; what every use needs is a monotone map, which it is.
    ((f + 2_147_483_648.0) as u32 ^ 0x8000_0000) as i32
}

/// The boxes of half-box `k` in the four systems: with k = ⌊2x/l⌋, ⌊x/l⌋ = k >> 1 and
/// ⌊x/l + 1/2⌋ = (k + 1) >> 1, exactly.
#[inline]
fn cells_at([kx, ky]: [i32; 2]) -> [[i32; 2]; 4] {
    let (x0, x1) = (kx >> 1, kx.saturating_add(1) >> 1);
    let (y0, y1) = (ky >> 1, ky.saturating_add(1) >> 1);
    [[x0, y0], [x1, y0], [x0, y1], [x1, y1]]
}

/// The hash: the plane wrapped onto a torus of 2^bx × 2^by boxes (bx + by = `bits`, the
/// log2 of the per-system table size). Neighbouring boxes land in neighbouring buckets,
/// and boxes collide only 2^bx (or 2^by) boxes apart. The four systems interleave.
#[derive(Clone, Copy, Debug)]
struct Torus {
    bits: u32,
    bx: u32,
    mask: [u32; 2],
}

impl Torus {
    fn new(bits: u32) -> Self {
        let bx = bits.div_ceil(2);
        Torus {
            bits,
            bx,
            mask: [(1 << bx) - 1, (1 << (bits - bx)) - 1],
        }
    }

    #[inline]
    fn bucket(&self, cell: [i32; 2], sys: usize) -> u32 {
        let x = cell[0] as u32 & self.mask[0];
        let y = cell[1] as u32 & self.mask[1];
        (x | (y << self.bx)) << 2 | sys as u32
    }
}

impl StaggeredHash {
    /// A hash for edges no longer than `max_edge`.
    pub fn new(max_edge: f64) -> Self {
        let l = (max_edge * BOX_PER_EDGE).max(1e-9);
        let bits = MIN_TABLE.trailing_zeros();
        StaggeredHash {
            inv_l: 1.0 / l,
            torus: Torus::new(bits),
            head: vec![NIL; 4 << bits],
            fill: vec![0; 4 << bits],
            link_next: Vec::new(),
            link_prev: Vec::new(),
            bucket: Vec::new(),
            half: Vec::new(),
            count: 0,
        }
    }

    /// Buckets per system.
    pub fn table_size(&self) -> usize {
        1 << self.torus.bits
    }

    /// The half-box of `p`: k = (⌊2x/l⌋, ⌊2y/l⌋) as [`floor_i32`] rounds. It fixes the
    /// boxes of all four systems ([`cells_at`]), so a vertex whose half-box stays put keeps
    /// its boxes.
    #[inline]
    fn half_box(&self, p: Point) -> [i32; 2] {
        [
            floor_i32(2.0 * (p.x * self.inv_l)),
            floor_i32(2.0 * (p.y * self.inv_l)),
        ]
    }

    /// The box of node `4 v + s` in its system s.
    #[inline]
    fn node_cell(&self, node: usize) -> [i32; 2] {
        let [kx, ky] = self.half[node >> 2];
        let s = node & 3;
        [
            kx.saturating_add((s & 1) as i32) >> 1,
            ky.saturating_add((s >> 1) as i32) >> 1,
        ]
    }

    /// The boxes of `p` in all four systems, indexed by system.
    #[inline]
    fn cells_of(&self, p: Point) -> [[i32; 2]; 4] {
        cells_at(self.half_box(p))
    }

    #[inline]
    fn bucket_of(&self, cell: [i32; 2], sys: usize) -> u32 {
        self.torus.bucket(cell, sys)
    }

    /// Vertex `v` moved into half-box `k`: its nodes move to their new boxes.
    fn relink(&mut self, v: u32, k: [i32; 2]) {
        let old = cells_at(std::mem::replace(&mut self.half[v as usize], k));
        let base = 4 * v as usize;
        for (s, c) in cells_at(k).into_iter().enumerate() {
            if old[s] != c {
                self.unlink(base + s);
                self.link(base + s, c);
            }
        }
    }

    fn link(&mut self, node: usize, cell: [i32; 2]) {
        let b = self.bucket_of(cell, node & 3);
        let h = self.head[b as usize];
        self.link_next[node] = h;
        self.link_prev[node] = NIL;
        if h != NIL {
            self.link_prev[h as usize] = node as u32;
        }
        self.head[b as usize] = node as u32;
        self.fill[b as usize] += 1;
        self.bucket[node] = b;
    }

    fn unlink(&mut self, node: usize) {
        let (n, p) = (self.link_next[node], self.link_prev[node]);
        if p != NIL {
            self.link_next[p as usize] = n;
        } else {
            self.head[self.bucket[node] as usize] = n;
        }
        if n != NIL {
            self.link_prev[n as usize] = p;
        }
        self.fill[self.bucket[node] as usize] -= 1;
        self.bucket[node] = NIL;
    }

    /// Doubles the tables until they hold at least twice the vertex count.
    fn grow(&mut self) {
        let mut bits = self.torus.bits;
        while self.count * 2 > (1 << bits) {
            bits += 1;
        }
        if bits == self.torus.bits {
            return;
        }
        self.torus = Torus::new(bits);
        self.head = vec![NIL; 4 << bits];
        self.fill = vec![0; 4 << bits];
        for node in 0..self.bucket.len() {
            if self.bucket[node] != NIL {
                let c = self.node_cell(node);
                self.link(node, c);
            }
        }
    }

    #[inline]
    fn reach(&self, b: &Aabb) -> Reach {
        let (lo, hi) = (self.half_box(b.min), self.half_box(b.max));
        // Per axis, the offset whose boxes start at the lowest half-box k (k even: offset
        // 0, k odd: offset 1/2) covers half-boxes k ..= k + m with ⌊m/2⌋ + 1 boxes, the
        // fewest any offset can: one box when the corners share a half-box or lie in
        // adjacent ones (Theorem 3). Each axis picks its own; the four systems are the four
        // pairs of offsets.
        let (ox, oy) = (lo[0] & 1, lo[1] & 1);
        Reach {
            sys: (ox | (oy << 1)) as usize,
            lo: [lo[0].saturating_add(ox) >> 1, lo[1].saturating_add(oy) >> 1],
            hi: [hi[0].saturating_add(ox) >> 1, hi[1].saturating_add(oy) >> 1],
        }
    }

    /// Whether the node's box is one the query `r` reads.
    #[inline]
    fn node_in(&self, node: usize, r: &Reach) -> bool {
        let c = self.node_cell(node);
        node & 3 == r.sys
            && c[0] >= r.lo[0]
            && c[0] <= r.hi[0]
            && c[1] >= r.lo[1]
            && c[1] <= r.hi[1]
    }

    fn read(&self, r: &Reach, out: &mut Vec<u32>) {
        out.clear();
        if r.boxes() as usize > self.count {
            // A huge box (a very long move): scanning every vertex is cheaper.
            for node in (r.sys..self.bucket.len()).step_by(4) {
                if self.bucket[node] != NIL && self.node_in(node, r) {
                    out.push((node / 4) as u32);
                }
            }
            return;
        }
        self.for_each_in(r, |v| out.push(v));
    }

    /// Calls `f` with every vertex registered in the boxes `r` reads, walking their
    /// buckets' lists (other boxes hashed alike are skipped).
    #[inline]
    fn for_each_in(&self, r: &Reach, mut f: impl FnMut(u32)) {
        for y in r.lo[1]..=r.hi[1] {
            for x in r.lo[0]..=r.hi[0] {
                let mut node = self.head[self.bucket_of([x, y], r.sys) as usize];
                while node != NIL {
                    let i = node as usize;
                    if i & 3 == r.sys && self.node_cell(i) == [x, y] {
                        f(node >> 2);
                    }
                    node = self.link_next[i];
                }
            }
        }
    }
}

impl BroadPhase for StaggeredHash {
    fn insert(&mut self, v: u32, p: Point) {
        let base = 4 * v as usize;
        if base >= self.bucket.len() {
            self.link_next.resize(base + 4, NIL);
            self.link_prev.resize(base + 4, NIL);
            self.bucket.resize(base + 4, NIL);
            self.half.resize(v as usize + 1, [0, 0]);
        }
        debug_assert_eq!(self.bucket[base], NIL, "vertex {v} inserted twice");
        let k = self.half_box(p);
        self.half[v as usize] = k;
        for (s, c) in cells_at(k).into_iter().enumerate() {
            self.link(base + s, c);
        }
        self.count += 1;
        if self.count * 2 > self.table_size() {
            self.grow();
        }
    }

    fn remove(&mut self, v: u32) {
        let base = 4 * v as usize;
        debug_assert_ne!(self.bucket[base], NIL);
        for s in 0..4 {
            self.unlink(base + s);
        }
        self.count -= 1;
    }

    #[inline(always)]
    fn update(&mut self, v: u32, p: Point) {
        let k = self.half_box(p);
        if self.half[v as usize] != k {
            self.relink(v, k); // rare: the common small move keeps its half-box
        }
    }

    fn query(&self, b: &Aabb, out: &mut Vec<u32>) {
        self.read(&self.reach(b), out);
    }

    fn finds(&self, v: u32, p: Point) -> bool {
        let base = 4 * v as usize;
        if base >= self.bucket.len() {
            return false;
        }
        let cells = self.cells_of(p);
        (0..4).all(|s| {
            let c = cells[s];
            if self.bucket[base + s] == NIL || self.node_cell(base + s) != c {
                return false;
            }
            let mut node = self.head[self.bucket_of(c, s) as usize];
            while node != NIL {
                if node as usize == base + s {
                    return true;
                }
                node = self.link_next[node as usize];
            }
            false
        })
    }

    fn len(&self) -> usize {
        self.count
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bx(x0: f64, y0: f64, x1: f64, y1: f64) -> Aabb {
        Aabb {
            min: Point::new(x0, y0),
            max: Point::new(x1, y1),
        }
    }

    #[test]
    fn small_boxes_read_one_bucket_of_some_system() {
        let h = StaggeredHash::new(4.0 / BOX_PER_EDGE); // l = 4
        for &(x, y) in &[(0.0, 0.0), (3.9, 2.0), (-3.1, 11.7), (1.9, 1.9)] {
            let r = h.reach(&bx(x, y, x + 2.0, y + 2.0));
            assert_eq!(r.boxes(), 1, "{x},{y}: {r:?}");
        }
        // Half-boxes 0 ..= 2 along x need two boxes of either offset; along y the corners
        // share half-box 1, so the offset-1/2 system's one box holds them.
        let r = h.reach(&bx(0.0, 2.1, 4.5, 3.0));
        assert_eq!((r.sys, r.lo, r.hi), (2, [0, 1], [1, 1]));
    }

    #[test]
    fn finds_inserted_moved_and_negative_vertices() {
        let mut h = StaggeredHash::new(4.0 / BOX_PER_EDGE); // l = 4
        h.insert(0, Point::new(1.0, 1.0));
        h.insert(1, Point::new(-7.5, 4.0));
        h.insert(2, Point::new(40.0, 40.0));
        let mut out = Vec::new();
        h.query(&bx(0.0, 0.0, 2.0, 2.0), &mut out);
        assert_eq!(out, vec![0]);
        h.update(0, Point::new(-8.0, 3.0));
        h.query(&bx(-9.0, 2.0, -7.0, 5.0), &mut out);
        out.sort();
        assert_eq!(out, vec![0, 1]);
        h.query(&bx(-100.0, -100.0, 100.0, 100.0), &mut out);
        out.sort();
        assert_eq!(out, vec![0, 1, 2]);
        h.remove(1);
        assert!(!h.finds(1, Point::new(-7.5, 4.0)));
        assert!(h.finds(0, Point::new(-8.0, 3.0)));
        assert_eq!(h.len(), 2);
    }

    #[test]
    fn table_grows_to_twice_the_vertex_count() {
        let mut h = StaggeredHash::new(4.0 / BOX_PER_EDGE); // l = 4
        for v in 0..5000u32 {
            h.insert(v, Point::new((v % 70) as f64 * 0.9, (v / 70) as f64 * 0.9));
        }
        assert!(h.table_size() >= 10_000);
        let mut out = Vec::new();
        // Box [0, 4)² of system (0, 0): x and y in {0, 0.9, …, 3.6}, no collision leaks in.
        h.query(&bx(0.0, 0.0, 0.5, 0.5), &mut out);
        assert_eq!(out.len(), 25);
        for v in 0..5000u32 {
            assert!(h.finds(v, Point::new((v % 70) as f64 * 0.9, (v / 70) as f64 * 0.9)));
        }
    }
}
