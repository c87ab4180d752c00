//! Vertex bins: the broad phase of seed 003, §3 ("the edges in this area can be
//! efficiently retrieved by storing the vertices in bins indexed by their location").
//!
//! A dense uniform grid over a domain (the image, usually) whose cells are at least as
//! large as the edge-length bound; each cell holds an intrusive doubly linked list of its
//! vertices, so moving a vertex between cells is O(1) and a query allocates nothing.
//! Positions outside the domain are clamped into the border cells: such vertices are
//! still found (the clamp is monotone), only less efficiently.
//!
//! Because every edge is at most `reach` long, an edge that meets a box B starts at a
//! vertex inside B grown by `reach`: querying that grown box and taking each found
//! vertex's outgoing edge yields every edge that can meet B.

use super::broad_phase::{push_outside_prevs, BroadPhase, Countable};
use crate::geometry::{Aabb, Point};

const NIL: u32 = u32::MAX;
const ABSENT: [i32; 2] = [-1, -1];
/// Upper bound on the number of cells, so a tiny edge bound on a huge image stays small.
const MAX_CELLS: usize = 1 << 22;
/// Widest region, in cells per axis, a quiet move certifies by counting (a small move
/// covers 2 to 3). `fill` has that many spare rows and columns, so a region's count
/// always reads a whole square of cells.
const REGION_SIDE: usize = 4;

/// Uniform grid of vertex lists.
#[derive(Clone, Debug)]
pub struct VertexBins {
    origin: Point,
    inv_cell: f64,
    nx: usize,
    ny: usize,
    head: Vec<u32>,
    /// Vertices per cell (the quiet-move certificate counts them, see [`Countable`]).
    fill: Vec<u32>,
    link_next: Vec<u32>,
    link_prev: Vec<u32>,
    /// Cell column and row of each vertex (`ABSENT` when not registered).
    at: Vec<[i32; 2]>,
    count: usize,
}

impl VertexBins {
    /// Bins over `domain` with cells of at least `min_cell` (the edge-length bound).
    pub fn new(domain: Aabb, min_cell: f64) -> Self {
        let w = (domain.max.x - domain.min.x).max(1.0);
        let h = (domain.max.y - domain.min.y).max(1.0);
        let mut cell = min_cell.max(1e-9);
        while (w / cell).ceil() * (h / cell).ceil() > MAX_CELLS as f64 {
            cell *= 1.5;
        }
        let nx = ((w / cell).ceil() as usize).max(1);
        let ny = ((h / cell).ceil() as usize).max(1);
        VertexBins {
            origin: domain.min,
            inv_cell: 1.0 / cell,
            nx,
            ny,
            head: vec![NIL; nx * ny],
            fill: vec![0; (nx + REGION_SIDE) * (ny + REGION_SIDE)],
            link_next: Vec::new(),
            link_prev: Vec::new(),
            at: Vec::new(),
            count: 0,
        }
    }

    /// Side of one cell, pixels.
    pub fn cell_size(&self) -> f64 {
        1.0 / self.inv_cell
    }

    // Truncation is floor for the non-negative values that reach it; the saturating cast
    // to u32 is cheaper than one to usize (and avoids a libm call on baseline x86_64).
    #[inline]
    fn ix(&self, x: f64) -> usize {
        (((x - self.origin.x) * self.inv_cell) as u32).min(self.nx as u32 - 1) as usize
    }
    #[inline]
    fn iy(&self, y: f64) -> usize {
        (((y - self.origin.y) * self.inv_cell) as u32).min(self.ny as u32 - 1) as usize
    }
    #[inline]
    fn cell(&self, p: Point) -> [i32; 2] {
        [self.ix(p.x) as i32, self.iy(p.y) as i32]
    }

    #[inline]
    fn index(&self, c: [i32; 2]) -> usize {
        c[1] as usize * self.nx + c[0] as usize
    }

    /// The cells a box overlaps: columns `x0..=x1`, rows `y0..=y1`.
    #[inline]
    fn span(&self, b: &Aabb) -> ([usize; 2], [usize; 2]) {
        (
            [self.ix(b.min.x), self.iy(b.min.y)],
            [self.ix(b.max.x), self.iy(b.max.y)],
        )
    }

    /// Calls `f` with every vertex registered in a cell that `b` overlaps.
    #[inline]
    fn for_each_near(&self, b: &Aabb, mut f: impl FnMut(u32)) {
        let (lo, hi) = self.span(b);
        for y in lo[1]..=hi[1] {
            for &h in &self.head[y * self.nx + lo[0]..=y * self.nx + hi[0]] {
                let mut v = h;
                while v != NIL {
                    f(v);
                    v = self.link_next[v as usize];
                }
            }
        }
    }

    fn link(&mut self, v: u32, c: [i32; 2]) {
        let i = self.index(c);
        let h = self.head[i];
        self.link_next[v as usize] = h;
        self.link_prev[v as usize] = NIL;
        if h != NIL {
            self.link_prev[h as usize] = v;
        }
        self.head[i] = v;
        self.fill[i] += 1;
        self.at[v as usize] = c;
    }

    fn unlink(&mut self, v: u32) {
        let i = self.index(self.at[v as usize]);
        let (n, p) = (self.link_next[v as usize], self.link_prev[v as usize]);
        if p != NIL {
            self.link_next[p as usize] = n;
        } else {
            self.head[i] = n;
        }
        if n != NIL {
            self.link_prev[n as usize] = p;
        }
        self.fill[i] -= 1;
        self.at[v as usize] = ABSENT;
    }
}

impl BroadPhase for VertexBins {
    fn insert(&mut self, v: u32, p: Point) {
        let i = v as usize;
        if i >= self.at.len() {
            self.at.resize(i + 1, ABSENT);
            self.link_next.resize(i + 1, NIL);
            self.link_prev.resize(i + 1, NIL);
        }
        debug_assert_eq!(self.at[i], ABSENT, "vertex {v} inserted twice");
        let c = self.cell(p);
        self.link(v, c);
        self.count += 1;
    }

    fn remove(&mut self, v: u32) {
        debug_assert_ne!(self.at[v as usize], ABSENT);
        self.unlink(v);
        self.count -= 1;
    }

    #[inline]
    fn update(&mut self, v: u32, p: Point) {
        let c = self.cell(p);
        if self.at[v as usize] != c {
            self.unlink(v);
            self.link(v, c);
        }
    }

    fn query(&self, b: &Aabb, out: &mut Vec<u32>) {
        out.clear();
        self.for_each_near(b, |v| out.push(v));
    }

    // One pass over the cells, filtering exactly as it goes (no second pass to retain).
    fn query_edges(&self, b: &Aabb, prev: &[u32], pos: &[Point], out: &mut Vec<u32>) {
        out.clear();
        self.for_each_near(b, |v| {
            if b.contains(pos[v as usize]) {
                out.push(v);
            }
        });
        push_outside_prevs(b, prev, pos, out);
    }

    fn finds(&self, v: u32, p: Point) -> bool {
        let c = self.cell(p);
        if self.at.get(v as usize) != Some(&c) {
            return false;
        }
        let mut u = self.head[self.index(c)];
        while u != NIL {
            if u == v {
                return true;
            }
            u = self.link_next[u as usize];
        }
        false
    }

    fn len(&self) -> usize {
        self.count
    }
}

/// A rectangle of cells: columns `lo[0] ..= lo[0] + size[0]`, rows likewise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellRect {
    lo: [i32; 2],
    size: [u32; 2],
}

impl Countable for VertexBins {
    type Region = CellRect;

    fn region(&self, b: &Aabb) -> Option<(CellRect, u32)> {
        let (lo, hi) = self.span(b);
        let (w, h) = (hi[0] - lo[0] + 1, hi[1] - lo[1] + 1);
        if w > REGION_SIDE || h > REGION_SIDE {
            return None;
        }
        // A fixed 4×4 square of cells, those outside the region masked out arithmetically:
        // no branch on the region's size, and a vector load per row.
        let keep = |i: usize, n: usize| ((i as i32 - n as i32) >> 31) as u32;
        let cols: [u32; REGION_SIDE] = std::array::from_fn(|i| keep(i, w));
        let start = lo[1] * self.nx + lo[0];
        let square = &self.fill[start..start + (REGION_SIDE - 1) * self.nx + REGION_SIDE];
        let mut sum = [0u32; REGION_SIDE];
        for r in 0..REGION_SIDE {
            let row: &[u32; REGION_SIDE] = square[r * self.nx..][..REGION_SIDE].try_into().unwrap();
            let m = keep(r, h);
            for i in 0..REGION_SIDE {
                sum[i] += row[i] & cols[i] & m;
            }
        }
        let r = CellRect {
            lo: lo.map(|k| k as i32),
            size: [w as u32 - 1, h as u32 - 1],
        };
        Some((r, sum.iter().sum()))
    }

    fn exact_count(&self, r: &CellRect) -> u32 {
        let mut n = 0;
        for y in r.lo[1]..=r.lo[1] + r.size[1] as i32 {
            for x in r.lo[0]..=r.lo[0] + r.size[0] as i32 {
                n += self.fill[self.index([x, y])];
            }
        }
        n
    }

    #[inline]
    fn in_region(&self, v: u32, r: &CellRect) -> bool {
        // Unsigned offsets: one comparison per axis.
        let c = self.at[v as usize];
        (c[0].wrapping_sub(r.lo[0]) as u32) <= r.size[0]
            && (c[1].wrapping_sub(r.lo[1]) as u32) <= r.size[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_finds_inserted_and_moved_vertices() {
        let dom = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(100.0, 100.0),
        };
        let mut b = VertexBins::new(dom, 10.0);
        b.insert(0, Point::new(5.0, 5.0));
        b.insert(1, Point::new(55.0, 5.0));
        b.insert(2, Point::new(-50.0, 500.0)); // outside: clamped into a border cell
        let mut out = Vec::new();
        b.query(
            &Aabb {
                min: Point::new(0.0, 0.0),
                max: Point::new(9.0, 9.0),
            },
            &mut out,
        );
        assert_eq!(out, vec![0]);
        b.update(0, Point::new(57.0, 7.0));
        b.query(
            &Aabb {
                min: Point::new(50.0, 0.0),
                max: Point::new(59.0, 9.0),
            },
            &mut out,
        );
        out.sort();
        assert_eq!(out, vec![0, 1]);
        b.query(
            &Aabb {
                min: Point::new(-60.0, 450.0),
                max: Point::new(-40.0, 550.0),
            },
            &mut out,
        );
        assert_eq!(out, vec![2]);
        b.remove(1);
        assert!(!b.finds(1, Point::new(55.0, 5.0)));
        assert!(b.finds(0, Point::new(57.0, 7.0)));
        assert_eq!(b.len(), 2);
    }
}
