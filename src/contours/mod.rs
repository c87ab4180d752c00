//! `ContourSet`: closed polygonal rings over a vertex arena (DESIGN layer 2).
//!
//! Connectivity is kept apart from coordinates: each vertex has `prev`/`next` links, so
//! splicing two rings at a crossing (seed 003, §2.3) is O(1). Each vertex carries the id
//! of the ring it belongs to; after a split only one of the two rings is relabelled, the
//! "pseudo-local" tracking of seed 003, §2.4.
//!
//! Conventions (stated once, here):
//! - the region lies on the left of every ring, in the algebraic sense of
//!   [`crate::geometry::orient`] on image coordinates (x right, y down): outer rings have
//!   positive signed area, hole rings negative;
//! - rings are simple, have at least 3 vertices, and no two edges anywhere cross or touch;
//! - no edge is longer than [`ContourSet::reach`], which is what makes the broad-phase
//!   search local (seed 003, §3: "constraining the maximum edge length").

pub mod broad_phase;
mod invariants;
pub mod measure;
pub mod staggered_hash;
pub mod vertex_bins;

use crate::geometry::{edges_clash, orient, signed_area2, winding_number, Aabb, Point};

pub use broad_phase::{Broad, BroadPhase, BroadPhaseKind, Countable};
pub use staggered_hash::StaggeredHash;
pub use vertex_bins::VertexBins;

pub(crate) const NIL: u32 = u32::MAX;

/// Handle of a vertex in a [`ContourSet`].
pub type VertexId = u32;

/// Id of a ring. Ids are never reused within one set.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(transparent)]
pub struct ContourId(pub u32);

impl std::fmt::Display for ContourId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// Why a ring could not be added.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum RingError {
    /// Fewer than three vertices.
    #[error("a ring needs at least 3 vertices, got {0}")]
    TooFewVertices(usize),
    /// A coordinate is not finite.
    #[error("ring has a non-finite coordinate")]
    NotFinite,
    #[error("ring edge of length {len} exceeds the edge bound {bound}")]
    /// An edge longer than the bound.
    EdgeTooLong {
        /// The edge's length.
        len: f64,
        /// The bound.
        bound: f64,
    },
    /// The ring has no area.
    #[error("ring has zero area")]
    ZeroArea,
    /// The ring crosses or touches itself or another ring.
    #[error("ring crosses or touches itself or another ring")]
    Intersects,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Ring {
    /// Any live vertex of the ring.
    pub anchor: u32,
    pub len: u32,
    /// Twice the signed area, kept up to date incrementally.
    pub area2: f64,
}

/// A set of disjoint, simple, oriented polygonal rings bounding a region.
#[derive(Clone, Debug)]
pub struct ContourSet {
    pub(crate) pos: Vec<Point>,
    pub(crate) next: Vec<u32>,
    pub(crate) prev: Vec<u32>,
    /// Ring id of each vertex; `NIL` for a free slot.
    pub(crate) label: Vec<u32>,
    pub(crate) free: Vec<u32>,
    pub(crate) rings: Vec<Option<Ring>>,
    pub(crate) live_rings: usize,
    pub(crate) bins: Broad,
    pub(crate) max_edge: f64,
    /// Longest edge the bins must account for: `max_edge`, or more if an edge longer than
    /// it ever had to stay (never in practice; kept so correctness never depends on it).
    pub(crate) reach: f64,
    pub(crate) domain: Aabb,
    /// Per-vertex stamps for walks that must not visit twice.
    pub(crate) mark: Vec<u32>,
    pub(crate) stamp: u32,
    pub(crate) scratch: Vec<u32>,
}

impl ContourSet {
    /// An empty set whose rings are expected to live in `domain` (the image rectangle)
    /// with edges no longer than `max_edge` pixels.
    ///
    /// # Panics
    /// If `max_edge` is not a positive finite number (a programming error: callers
    /// validate user parameters first).
    pub fn new(domain: Aabb, max_edge: f64) -> Self {
        Self::with_broad_phase(domain, max_edge, BroadPhaseKind::Bins)
    }

    /// Like [`ContourSet::new`], with the broad phase of `kind`.
    pub fn with_broad_phase(domain: Aabb, max_edge: f64, kind: BroadPhaseKind) -> Self {
        assert!(
            max_edge.is_finite() && max_edge > 0.0,
            "edge bound must be positive, got {max_edge}"
        );
        ContourSet {
            pos: Vec::new(),
            next: Vec::new(),
            prev: Vec::new(),
            label: Vec::new(),
            free: Vec::new(),
            rings: Vec::new(),
            live_rings: 0,
            bins: Broad::new(kind, domain, max_edge),
            max_edge,
            reach: max_edge,
            domain,
            mark: Vec::new(),
            stamp: 0,
            scratch: Vec::new(),
        }
    }

    /// The edge-length bound every edge respects.
    pub fn max_edge(&self) -> f64 {
        self.max_edge
    }

    /// Which broad phase the set uses.
    pub fn broad_phase(&self) -> BroadPhaseKind {
        self.bins.kind()
    }

    /// The domain the bins cover.
    pub fn domain(&self) -> Aabb {
        self.domain
    }

    /// The distance the broad phase searches around a motion (≥ `max_edge`).
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// Rebuilds the bins for a new edge bound (a pyramid level change). Existing edges
    /// longer than the new bound stay, and the search reach grows to cover them, until
    /// remeshing splits them.
    pub fn set_max_edge(&mut self, max_edge: f64) {
        assert!(
            max_edge.is_finite() && max_edge > 0.0,
            "edge bound must be positive, got {max_edge}"
        );
        self.max_edge = max_edge;
        let longest = self
            .vertices()
            .map(|v| self.pos[v as usize].dist(self.pos[self.next[v as usize] as usize]))
            .fold(0.0, f64::max);
        self.reach = max_edge.max(longest);
        self.bins = Broad::new(self.bins.kind(), self.domain, self.reach);
        for v in 0..self.pos.len() as u32 {
            if self.label[v as usize] != NIL {
                self.bins.insert(v, self.pos[v as usize]);
            }
        }
    }

    /// Adds a ring through `points` in order, keeping their orientation: counter-clockwise
    /// in the algebraic sense (positive area) for an outer ring, the other way for a hole.
    pub fn add_ring(&mut self, points: &[Point]) -> Result<ContourId, RingError> {
        let n = points.len();
        if n < 3 {
            return Err(RingError::TooFewVertices(n));
        }
        if points.iter().any(|p| !p.is_finite()) {
            return Err(RingError::NotFinite);
        }
        for i in 0..n {
            let len = points[i].dist(points[(i + 1) % n]);
            if len > self.max_edge {
                return Err(RingError::EdgeTooLong {
                    len,
                    bound: self.max_edge,
                });
            }
        }
        let area2 = signed_area2(points);
        if area2 == 0.0 {
            return Err(RingError::ZeroArea);
        }
        let id = self.rings.len() as u32;
        let first = self.alloc(points[0], id);
        let mut last = first;
        for &p in &points[1..] {
            let v = self.alloc(p, id);
            self.next[last as usize] = v;
            self.prev[v as usize] = last;
            last = v;
        }
        self.next[last as usize] = first;
        self.prev[first as usize] = last;
        if self.new_ring_intersects(first) {
            // Undo: the slots go back to the free list, the id is not used.
            let ring: Vec<VertexId> = self.walk(first).collect();
            for w in ring {
                self.release(w);
            }
            return Err(RingError::Intersects);
        }
        self.rings.push(Some(Ring {
            anchor: first,
            len: n as u32,
            area2,
        }));
        self.live_rings += 1;
        Ok(ContourId(id))
    }

    /// Whether the ring just linked at `first` (already in the broad phase) crosses or
    /// touches itself or another ring: each edge against the edges the broad phase offers
    /// near it, so the check is O(n) rather than O(n²).
    fn new_ring_intersects(&self, first: u32) -> bool {
        let mut cand = Vec::new();
        for a in self.walk(first) {
            let b = self.next[a as usize];
            let (a0, a1) = (self.pos[a as usize], self.pos[b as usize]);
            if a0 == a1 {
                return true;
            }
            self.edges_near(&Aabb::of(&[a0, a1]), &mut cand);
            for &c in &cand {
                if c == a {
                    continue;
                }
                let cn = self.next[c as usize];
                let (c0, c1) = (self.pos[c as usize], self.pos[cn as usize]);
                // Neighbouring edges share one vertex and must not fold onto each other.
                if edges_clash([(a, a0), (b, a1)], [(c, c0), (cn, c1)]) {
                    return true;
                }
            }
        }
        // A ring with no crossing may still enclose or sit inside another one: that is
        // fine as long as orientations nest, which `sanity_check` verifies; callers that
        // build nested rings state holes explicitly.
        false
    }

    pub(crate) fn alloc(&mut self, p: Point, label: u32) -> u32 {
        let v = if let Some(v) = self.free.pop() {
            self.pos[v as usize] = p;
            self.label[v as usize] = label;
            v
        } else {
            self.pos.push(p);
            self.next.push(NIL);
            self.prev.push(NIL);
            self.label.push(label);
            self.mark.push(0);
            (self.pos.len() - 1) as u32
        };
        self.bins.insert(v, p);
        v
    }

    /// Frees a vertex slot (links are the caller's business).
    pub(crate) fn release(&mut self, v: u32) {
        self.bins.remove(v);
        self.label[v as usize] = NIL;
        self.free.push(v);
    }

    #[inline]
    pub(crate) fn ring(&self, id: u32) -> &Ring {
        self.rings[id as usize].as_ref().expect("live ring")
    }
    #[inline]
    pub(crate) fn ring_mut(&mut self, id: u32) -> &mut Ring {
        self.rings[id as usize].as_mut().expect("live ring")
    }

    pub(crate) fn next_stamp(&mut self) -> u32 {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.stamp
    }

    // ---- read access -------------------------------------------------------------------
    // The fields are private to the crate (the topology core writes them); this is the
    // read API. Vertex ids index the arena: the accessors below panic on an id the arena
    // never held, and return stale data for a freed slot (check `is_alive` first when in
    // doubt). Ring ids likewise (`contains`).

    /// Position of a live vertex.
    ///
    /// # Panics
    /// If `v` is not a slot of the arena.
    pub fn position(&self, v: VertexId) -> Point {
        self.pos[v as usize]
    }
    /// The vertex after `v` on its ring.
    ///
    /// # Panics
    /// If `v` is not a slot of the arena.
    pub fn next(&self, v: VertexId) -> VertexId {
        self.next[v as usize]
    }
    /// The vertex before `v` on its ring.
    ///
    /// # Panics
    /// If `v` is not a slot of the arena.
    pub fn prev(&self, v: VertexId) -> VertexId {
        self.prev[v as usize]
    }
    /// Whether `v` is a live vertex.
    pub fn is_alive(&self, v: VertexId) -> bool {
        (v as usize) < self.label.len() && self.label[v as usize] != NIL
    }
    /// The ring a live vertex belongs to.
    ///
    /// # Panics
    /// If `v` is not a slot of the arena.
    pub fn contour_of(&self, v: VertexId) -> ContourId {
        ContourId(self.label[v as usize])
    }
    /// Number of live vertices.
    pub fn vertex_count(&self) -> usize {
        self.pos.len() - self.free.len()
    }
    /// Number of rings.
    pub fn contour_count(&self) -> usize {
        self.live_rings
    }
    /// Upper bound (exclusive) of vertex ids ever handed out.
    pub fn vertex_capacity(&self) -> usize {
        self.pos.len()
    }
    /// All live vertices, in id order.
    pub fn vertices(&self) -> impl Iterator<Item = VertexId> + '_ {
        (0..self.pos.len() as u32).filter(move |&v| self.label[v as usize] != NIL)
    }
    /// Ids of all rings, ascending.
    pub fn contour_ids(&self) -> impl Iterator<Item = ContourId> + '_ {
        self.rings
            .iter()
            .enumerate()
            .filter(|(_, r)| r.is_some())
            .map(|(i, _)| ContourId(i as u32))
    }
    /// Whether ring `id` exists.
    pub fn contains(&self, id: ContourId) -> bool {
        matches!(self.rings.get(id.0 as usize), Some(Some(_)))
    }
    /// The vertices of a ring in order, starting anywhere.
    ///
    /// # Panics
    /// If ring `id` does not exist (see [`ContourSet::contains`]).
    pub fn ring_vertices(&self, id: ContourId) -> Vec<VertexId> {
        self.walk(self.ring(id.0).anchor).collect()
    }
    /// The vertices of `from`'s ring in order, starting at `from`, once round.
    ///
    /// # Panics
    /// If `from` is not a vertex of the set.
    pub fn walk(&self, from: VertexId) -> RingWalk<'_> {
        assert!((from as usize) < self.next.len(), "no vertex {from}");
        RingWalk {
            next: &self.next,
            from,
            at: Some(from),
            left: self.next.len(),
        }
    }
    /// Every live vertex, ring by ring in ring order (neighbours in space come one after
    /// the other: what a pass over all vertices wants for its memory accesses).
    pub fn vertices_in_ring_order(&self, out: &mut Vec<VertexId>) {
        out.clear();
        for r in self.rings.iter().flatten() {
            out.extend(self.walk(r.anchor));
        }
    }
    /// The positions of a ring in order.
    ///
    /// # Panics
    /// If ring `id` does not exist (see [`ContourSet::contains`]).
    pub fn ring_points(&self, id: ContourId) -> Vec<Point> {
        self.ring_vertices(id)
            .into_iter()
            .map(|v| self.pos[v as usize])
            .collect()
    }
    /// Signed area of a ring (negative for holes).
    ///
    /// # Panics
    /// If ring `id` does not exist (see [`ContourSet::contains`]).
    pub fn signed_area(&self, id: ContourId) -> f64 {
        0.5 * self.ring(id.0).area2
    }
    /// Number of vertices of a ring.
    ///
    /// # Panics
    /// If ring `id` does not exist (see [`ContourSet::contains`]).
    pub fn ring_len(&self, id: ContourId) -> usize {
        self.ring(id.0).len as usize
    }
    /// Whether a ring bounds a hole.
    ///
    /// # Panics
    /// If ring `id` does not exist (see [`ContourSet::contains`]).
    pub fn is_hole(&self, id: ContourId) -> bool {
        !self.loop_is_outer(self.ring(id.0).anchor, self.ring(id.0).area2)
    }

    /// Whether the loop through `anchor` (with twice-area `area2` summed in floats) runs
    /// with the region on its left around the outside, i.e. bounds an outer region. The
    /// float sum decides unless it is within rounding of zero (a sliver); then the exact
    /// orientation at the lowest-leftmost vertex does, which is never zero for a simple
    /// polygon.
    pub(crate) fn loop_is_outer(&self, anchor: u32, area2: f64) -> bool {
        let a = self.pos[anchor as usize];
        let scale = 1.0 + a.x.abs().max(a.y.abs());
        if area2.abs() > 1e-9 * scale * scale {
            return area2 > 0.0;
        }
        let mut best = anchor;
        for w in self.walk(anchor).skip(1) {
            let (pw, pb) = (self.pos[w as usize], self.pos[best as usize]);
            if (pw.x, pw.y) < (pb.x, pb.y) {
                best = w;
            }
        }
        let b = best as usize;
        orient(
            self.pos[self.prev[b] as usize],
            self.pos[b],
            self.pos[self.next[b] as usize],
        ) > 0.0
    }
    /// Total signed area of the region (outer areas minus holes).
    pub fn region_area(&self) -> f64 {
        self.rings.iter().flatten().map(|r| 0.5 * r.area2).sum()
    }
    /// Whether `p` lies in the region (sum of the rings' winding numbers is 1 inside).
    /// Exact unless `p` is on a ring.
    pub fn region_contains(&self, p: Point) -> bool {
        self.contour_ids()
            .map(|id| winding_number(&self.ring_points(id), p))
            .sum::<i32>()
            > 0
    }

    /// For every ring, the ring directly enclosing it (`None` for an outermost ring).
    /// Rings do not cross, so one vertex of a ring decides which rings contain it.
    pub fn parents(&self) -> Vec<(ContourId, Option<ContourId>)> {
        let ids: Vec<ContourId> = self.contour_ids().collect();
        let pts: Vec<Vec<Point>> = ids.iter().map(|&id| self.ring_points(id)).collect();
        let boxes: Vec<Aabb> = pts.iter().map(|p| Aabb::of(p)).collect();
        let areas: Vec<f64> = ids.iter().map(|&id| self.signed_area(id).abs()).collect();
        ids.iter()
            .enumerate()
            .map(|(i, &id)| {
                let probe = pts[i][0];
                let parent = (0..ids.len())
                    .filter(|&j| j != i && areas[j] > areas[i] && boxes[j].contains(probe))
                    .filter(|&j| winding_number(&pts[j], probe) != 0)
                    .min_by(|&a, &b| areas[a].total_cmp(&areas[b]))
                    .map(|j| ids[j]);
                (id, parent)
            })
            .collect()
    }

    /// Deletes a whole ring. Used by filters that drop regions; the caller keeps nesting
    /// consistent (drop a ring together with the rings inside it).
    pub fn remove_ring(&mut self, id: ContourId) {
        let Some(r) = self.rings.get_mut(id.0 as usize).and_then(|r| r.take()) else {
            return;
        };
        self.live_rings -= 1;
        let ring: Vec<VertexId> = self.walk(r.anchor).collect();
        for w in ring {
            self.release(w);
        }
    }

    /// Deletes an outer ring together with its holes (or one hole): a hand edit.
    pub fn remove_region(&mut self, id: ContourId) {
        let holes: Vec<_> = self
            .parents()
            .into_iter()
            .filter(|&(_, p)| p == Some(id))
            .map(|(h, _)| h)
            .collect();
        for h in holes {
            self.remove_ring(h);
        }
        self.remove_ring(id);
    }

    /// The live vertex nearest to `at` within `tol`, if any.
    pub fn nearest_vertex(&self, at: Point, tol: f64) -> Option<VertexId> {
        let mut near = Vec::new();
        self.vertices_near(&Aabb { min: at, max: at }.expand(tol), &mut near);
        near.into_iter()
            .map(|v| (v, self.position(v).dist(at)))
            .filter(|&(_, d)| d <= tol)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(v, _)| v)
    }

    /// Candidate edges (by start vertex, each once) that may meet box `b`, from the
    /// broad phase. An edge no longer than the reach L that meets `b` has an endpoint
    /// within L/2 of it, so the query covers `b` grown by L/2 only; each vertex found
    /// offers its outgoing edge, and its incoming one unless that edge's start was found
    /// too.
    pub fn edges_near(&self, b: &Aabb, out: &mut Vec<VertexId>) {
        self.bins
            .query_edges(&b.expand(0.5 * self.reach), &self.prev, &self.pos, out);
    }

    /// Live vertices that may lie in box `b`, from the broad phase (a superset).
    pub fn vertices_near(&self, b: &Aabb, out: &mut Vec<VertexId>) {
        self.bins.query(b, out);
    }
}

/// The vertices of one ring in order, once round: [`ContourSet::walk`]. Bounded by the
/// arena's size, so even broken links (which `sanity_check` reports) cannot loop forever.
#[derive(Clone, Debug)]
pub struct RingWalk<'a> {
    next: &'a [VertexId],
    from: VertexId,
    at: Option<VertexId>,
    left: usize,
}

impl Iterator for RingWalk<'_> {
    type Item = VertexId;
    #[inline]
    fn next(&mut self) -> Option<VertexId> {
        let v = self.at?;
        self.left = self.left.checked_sub(1)?;
        let n = self.next[v as usize];
        self.at = (n != self.from).then_some(n);
        Some(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn set() -> ContourSet {
        ContourSet::new(
            Aabb {
                min: p(0.0, 0.0),
                max: p(100.0, 100.0),
            },
            20.0,
        )
    }

    #[test]
    fn add_ring_refuses_crossings_and_touches_without_using_an_id() {
        let mut s = set();
        // A figure eight crosses itself.
        let eight = [p(10., 10.), p(22., 22.), p(22., 10.), p(10., 18.)];
        assert_eq!(s.add_ring(&eight), Err(RingError::Intersects));
        // A spike folding back onto its own edge.
        let fold = [p(10., 10.), p(20., 10.), p(15., 10.), p(15., 15.)];
        assert_eq!(s.add_ring(&fold), Err(RingError::Intersects));
        let a = s.add_ring(&[p(10., 10.), p(20., 10.), p(20., 20.), p(10., 20.)]);
        assert_eq!(a, Ok(ContourId(0)));
        // Crossing the first ring, and touching it at a vertex.
        let cross = [p(15., 15.), p(30., 15.), p(30., 30.), p(15., 30.)];
        assert_eq!(s.add_ring(&cross), Err(RingError::Intersects));
        let touch = [p(20., 20.), p(30., 20.), p(30., 30.), p(20., 30.)];
        assert_eq!(s.add_ring(&touch), Err(RingError::Intersects));
        // Refusals left nothing behind: the next ring gets id 1 and the set is sound.
        let b = s.add_ring(&[p(40., 40.), p(50., 40.), p(50., 50.), p(40., 50.)]);
        assert_eq!(b, Ok(ContourId(1)));
        assert_eq!(s.vertex_count(), 8);
        s.sanity_check().unwrap();
    }
}
