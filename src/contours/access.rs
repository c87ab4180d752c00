//! Reading the arena: vertex positions and links, rings walked in order, areas and
//! nesting, and the broad phase's answers near a box; plus deleting whole rings.

use super::broad_phase::BroadPhase;
use super::{ContourId, ContourSet, VertexId, NIL};
use crate::geometry::{orient, winding_number, Aabb, Point};

impl ContourSet {
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
