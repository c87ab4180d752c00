//! Topology correction by motion regions (seed 003; DESIGN layer 3).
//!
//! [`ContourSet::move_vertex`] moves one vertex and leaves the rings bounding exactly
//! (R ∪ M⁺) − M⁻ (Theorem 3): find the crossings of the new portion c' with the rest of
//! the boundary through the vertex bins (`directive1::find_crossings`), splice and
//! delete at them (Directive 1), delete rings inside the motion region (Directive 2), then
//! relabel pseudo-locally and report [`TopologyEvent`]s.
//!
//! Choices the paper leaves open, made here:
//! - **Degenerate moves are rejected.** The paper assumes c' never touches the boundary
//!   (§2.2, constraint 4). A move whose new edges would touch a vertex or an edge, overlap
//!   an edge collinearly, fold back on a neighbouring edge, put q on p or n, or whose
//!   crossings fall within a tiny distance (1e-9 × coordinate scale) of other geometry or
//!   between nearly parallel edges, returns [`MoveError::Degenerate`] and changes nothing.
//!   An evolving contour simply tries a slightly different move next frame (the evolver
//!   retries with a shortened step), which is what a user watching expects: nothing jumps.
//! - **Long moves are searched over their bounding box.** The broad phase is queried over
//!   the bounding box of c' grown by the edge bound, which contains the whole motion
//!   region, so a move of any length is corrected exactly in one step against the big
//!   quadrilateral. New edges longer than the bound are then split by inserting vertices,
//!   which changes no geometry.
//! - **Removing a vertex is a motion**: c' = p→n, M the triangle (p, o, n).

pub mod directive1;
pub mod directive2;
pub mod events;
pub mod motion_region;
mod plan;
pub mod policy;
pub mod preserve;
mod quiet;

use crate::contours::{ContourSet, Ring, VertexId, NIL};
use crate::geometry::{edges_clash, folds_back, Aabb, Point};
pub use events::TopologyEvent;
use events::{assign_ids, NewLoop, OldRing};
pub use motion_region::MotionRegion;
use plan::MovePlan;
pub use policy::TopologyPolicy;

/// Why a move was refused (the set is unchanged).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Degeneracy {
    /// The new position coincides with a neighbour.
    #[error("the new position coincides with a neighbour")]
    OnNeighbour,
    /// A new edge would touch the boundary.
    #[error("a new edge would touch the boundary")]
    Touch,
    /// A new edge would overlap an edge collinearly.
    #[error("a new edge would overlap an edge collinearly")]
    Overlap,
    /// The motion region is flat where a crossing lies.
    #[error("the motion region is flat where a crossing lies")]
    FlatRegion,
    /// A crossing between nearly parallel edges.
    #[error("a crossing between nearly parallel edges")]
    NearlyParallel,
    /// A crossing too close to other geometry.
    #[error("a crossing too close to other geometry")]
    Near,
}

/// Why a topology operation did nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MoveError {
    /// No such vertex.
    #[error("vertex {0} does not exist")]
    NoVertex(VertexId),
    /// A coordinate is not finite.
    #[error("position is not finite")]
    NotFinite,
    /// The motion is degenerate.
    #[error("degenerate motion: {0}")]
    Degenerate(#[from] Degeneracy),
    /// A ring would have fewer than three vertices.
    #[error("a ring cannot have fewer than 3 vertices")]
    TooFewVertices,
    /// An edge would exceed the edge bound.
    #[error("the resulting edge would exceed the edge bound")]
    EdgeTooLong,
    /// A parameter along an edge is not in (0, 1).
    #[error("parameter along the edge must lie strictly between 0 and 1")]
    BadParameter,
    /// The move would cause an event (named by its kind) that the topology policy holds
    /// back ([`TopologyPolicy`]).
    #[error("the topology policy holds back a {0}")]
    Held(&'static str),
}

impl ContourSet {
    /// Moves vertex `v` to `to` and corrects the rings (seed 003). Returns the topology
    /// events the move caused; on error nothing changed. `v` may be gone afterwards (its
    /// ring vanished, or it lay on a deleted stretch): check [`ContourSet::is_alive`].
    pub fn move_vertex(&mut self, v: VertexId, to: Point) -> Result<Vec<TopologyEvent>, MoveError> {
        if self.settled_without_correction(v, to)? {
            return Ok(Vec::new());
        }
        self.replace_vertex(v, Some(to))
    }

    /// Checks a move of `v` to `to` and makes it at once when it needs no correction (no
    /// motion at all, or a quiet move that meets only its own chain): `true` then, `false`
    /// when the motion region must be corrected.
    pub(crate) fn settled_without_correction(
        &mut self,
        v: VertexId,
        to: Point,
    ) -> Result<bool, MoveError> {
        if !self.is_alive(v) {
            return Err(MoveError::NoVertex(v));
        }
        if !to.is_finite() {
            return Err(MoveError::NotFinite);
        }
        Ok(to == self.pos[v as usize] || self.quiet_move(v, to))
    }

    /// Removes vertex `v`, joining its neighbours by a straight edge: the motion of `v`
    /// onto that edge, corrected like any other move.
    pub fn remove_vertex(&mut self, v: VertexId) -> Result<Vec<TopologyEvent>, MoveError> {
        self.check_removal(v)?;
        self.replace_vertex(v, None)
    }

    /// Why `v` cannot be removed, if it cannot: no such vertex, a triangle, or an edge
    /// over the bound would replace it.
    fn check_removal(&self, v: VertexId) -> Result<(), MoveError> {
        if !self.is_alive(v) {
            return Err(MoveError::NoVertex(v));
        }
        if self.ring(self.label[v as usize]).len <= 3 {
            return Err(MoveError::TooFewVertices);
        }
        let (p, n) = (
            self.pos[self.prev[v as usize] as usize],
            self.pos[self.next[v as usize] as usize],
        );
        if p.dist(n) > self.max_edge {
            return Err(MoveError::EdgeTooLong);
        }
        Ok(())
    }

    /// Inserts a vertex on the edge from `a` to its successor, at parameter `t` in (0, 1).
    /// The geometry does not change (up to rounding, which is checked).
    pub fn insert_vertex(&mut self, a: VertexId, t: f64) -> Result<VertexId, MoveError> {
        if !self.is_alive(a) {
            return Err(MoveError::NoVertex(a));
        }
        if !(t > 0.0 && t < 1.0) {
            return Err(MoveError::BadParameter);
        }
        let b = self.next[a as usize];
        let (pa, pb) = (self.pos[a as usize], self.pos[b as usize]);
        let m = pa.lerp(pb, t);
        if m == pa || m == pb || folds_back(m, pa, pb) {
            return Err(Degeneracy::OnNeighbour.into());
        }
        // The rounded point may sit a hair off the edge. That changes nothing for a ring of
        // real size, but could turn a sliver ring inside out: refuse to touch slivers.
        let scale = 1.0 + pa.x.abs().max(pa.y.abs()).max(pb.x.abs()).max(pb.y.abs());
        if self.ring(self.label[a as usize]).area2.abs() < 1e-6 * scale * scale {
            return Err(Degeneracy::Near.into());
        }
        let mut cand = std::mem::take(&mut self.scratch);
        self.edges_near(&Aabb::of(&[pa, pb]), &mut cand);
        let mut fault = None;
        for &c in &cand {
            if c == a {
                continue;
            }
            let cn = self.next[c as usize];
            let (c0, c1) = (self.pos[c as usize], self.pos[cn as usize]);
            for (s0id, s0, s1id, s1) in [(a, pa, NIL, m), (NIL, m, b, pb)] {
                if edges_clash([(s0id, s0), (s1id, s1)], [(c, c0), (cn, c1)]) {
                    fault = Some(Degeneracy::Near);
                }
            }
        }
        self.scratch = cand;
        if let Some(f) = fault {
            return Err(f.into());
        }
        let label = self.label[a as usize];
        let x = self.alloc(m, label);
        self.next[a as usize] = x;
        self.prev[x as usize] = a;
        self.next[x as usize] = b;
        self.prev[b as usize] = x;
        let r = self.ring_mut(label);
        r.len += 1;
        r.area2 += pa.cross(m) + m.cross(pb) - pa.cross(pb);
        Ok(x)
    }

    fn replace_vertex(
        &mut self,
        v: u32,
        to: Option<Point>,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        let mut plan = self.plan_move(v, to)?;
        let moved = self.commit_move(&plan, v, to);
        Ok(self.settle_move(&mut plan, moved))
    }

    /// The move itself: c' replaces c (the stored area follows). Returns the moved vertex,
    /// or `None` for a removal.
    #[inline(always)]
    fn commit_move(&mut self, plan: &MovePlan, v: u32, to: Option<Point>) -> Option<u32> {
        let MovePlan {
            pid, nid, p, o, n, ..
        } = *plan;
        let delta2 = match to {
            Some(q) => p.cross(q) + q.cross(n) - p.cross(o) - o.cross(n),
            None => p.cross(n) - p.cross(o) - o.cross(n),
        };
        {
            let r = self.ring_mut(plan.label);
            r.area2 += delta2;
            if to.is_none() {
                r.len -= 1;
                r.anchor = pid;
            }
        }
        match to {
            Some(q) => {
                self.pos[v as usize] = q;
                crate::contours::BroadPhase::update(&mut self.bins, v, q);
                Some(v)
            }
            None => {
                self.next[pid as usize] = nid;
                self.prev[nid as usize] = pid;
                self.release(v);
                None
            }
        }
    }

    /// After the move: splices at the crossings and settles the loops (Directive 1),
    /// splits edges left too long, deletes the rings inside M (Directive 2).
    #[inline(always)]
    fn settle_move(&mut self, plan: &mut MovePlan, moved: Option<u32>) -> Vec<TopologyEvent> {
        let (pid, p, n, label) = (plan.pid, plan.p, plan.n, plan.label);
        let mut events = Vec::new();
        if plan.crossings.is_empty() {
            if let Some(w) = plan.moving_inside {
                self.remove_ring(crate::contours::ContourId(label));
                events.push(deletion_event(label, plan.old[0].outer, w, None));
            } else if let Some(v) = moved {
                let q = self.pos[v as usize];
                let bound2 = self.max_edge * self.max_edge;
                if (q - p).norm2() > bound2 || (n - q).norm2() > bound2 {
                    self.split_long_edges(&[pid, v]);
                }
            } else {
                self.split_long_edges(&[pid]);
            }
        } else {
            let kept = self.splice_crossings(pid, moved, &mut plan.crossings, label);
            let loops = self.collect_loops(&kept);
            self.settle_loops(loops, &plan.old, &mut events);
            let mut fresh_edges: Vec<u32> = Vec::new();
            for &x in &kept {
                if self.is_alive(x) {
                    fresh_edges.extend([self.prev[x as usize], x]);
                }
            }
            if let Some(v) = moved.filter(|&v| self.is_alive(v)) {
                fresh_edges.extend([self.prev[v as usize], v]);
            }
            self.split_long_edges(&fresh_edges);
        }
        let survivor = moved
            .filter(|&v| self.is_alive(v))
            .map(|v| self.label[v as usize]);
        for &(l, w) in &plan.inside {
            let outer = !self.is_hole(crate::contours::ContourId(l));
            self.remove_ring(crate::contours::ContourId(l));
            events.push(deletion_event(l, outer, w, survivor));
        }
        events
    }

    /// Walks each loop holding a kept crossing vertex once.
    fn collect_loops(&mut self, kept: &[u32]) -> Vec<NewLoop> {
        let stamp = self.next_stamp();
        let mut loops = Vec::new();
        for &x in kept {
            if self.mark[x as usize] == stamp {
                continue;
            }
            let mut lp = NewLoop {
                anchor: x,
                len: 0,
                area2: 0.0,
                outer: true,
                labels: Vec::new(),
                id: NIL,
            };
            let mut w = x;
            loop {
                self.mark[w as usize] = stamp;
                let nw = self.next[w as usize];
                lp.len += 1;
                lp.area2 += self.pos[w as usize].cross(self.pos[nw as usize]);
                let l = self.label[w as usize];
                if !lp.labels.contains(&l) {
                    lp.labels.push(l);
                }
                w = nw;
                if w == x {
                    break;
                }
            }
            lp.outer = self.loop_is_outer(x, lp.area2);
            loops.push(lp);
        }
        loops
    }

    /// Replaces the ring entries of the rings that took part by the surviving loops.
    fn settle_loops(
        &mut self,
        mut loops: Vec<NewLoop>,
        old: &[OldRing],
        events: &mut Vec<TopologyEvent>,
    ) {
        for r in old {
            if self.rings[r.id as usize].take().is_some() {
                self.live_rings -= 1;
            }
        }
        let mut next_id = self.rings.len() as u32;
        assign_ids(
            &mut loops,
            old,
            || {
                next_id += 1;
                next_id - 1
            },
            events,
        );
        for lp in loops {
            if lp.id as usize >= self.rings.len() {
                self.rings.resize(lp.id as usize + 1, None);
            }
            if lp.labels != [lp.id] {
                let mut w = lp.anchor;
                loop {
                    self.label[w as usize] = lp.id;
                    w = self.next[w as usize];
                    if w == lp.anchor {
                        break;
                    }
                }
            }
            self.rings[lp.id as usize] = Some(Ring {
                anchor: lp.anchor,
                len: lp.len,
                area2: lp.area2,
            });
            self.live_rings += 1;
        }
    }

    /// Splits edges (given by start vertex) longer than the edge bound into equal parts.
    fn split_long_edges(&mut self, starts: &[u32]) {
        for &a in starts {
            if !self.is_alive(a) {
                continue;
            }
            let b = self.next[a as usize];
            let len = self.pos[a as usize].dist(self.pos[b as usize]);
            // A non-finite length (never from a checked input) must not mean endless
            // insertions: the loop is bounded whatever the coordinates.
            if !(len > self.max_edge && len.is_finite()) {
                continue;
            }
            self.split_edge(a, (len / self.max_edge).ceil().min(MAX_SPLIT) as usize);
            // Should a split be refused (rounding next to other geometry), the broad phase
            // widens its reach so that correctness never rests on the bound.
            let mut w = a;
            while w != b {
                let nw = self.next[w as usize];
                self.reach = self
                    .reach
                    .max(self.pos[w as usize].dist(self.pos[nw as usize]));
                w = nw;
            }
        }
    }

    /// Splits the edge from `a` into `parts` equal parts (fewer if an insertion is
    /// refused, which leaves the geometry as it was).
    pub fn split_edge(&mut self, a: VertexId, parts: usize) {
        let mut cursor = a;
        for i in 1..parts {
            // Each insertion splits the remaining stretch cursor→b.
            let t = 1.0 / (parts - i + 1) as f64;
            match self.insert_vertex(cursor, t) {
                Ok(x) => cursor = x,
                Err(_) => break,
            }
        }
    }
}

/// Parts one edge is split into at most: far more than an edge inside any accepted image
/// needs (its diagonal over the smallest edge bound).
const MAX_SPLIT: f64 = (1u32 << 20) as f64;

/// The event for ring `id` deleted by Directive 2 with M's winding `w` over it.
fn deletion_event(id: u32, outer: bool, w: i32, survivor: Option<u32>) -> TopologyEvent {
    use crate::contours::ContourId;
    match (outer, w > 0, survivor) {
        (true, true, Some(s)) if s != id => TopologyEvent::Merge {
            into: ContourId(s),
            absorbed: ContourId(id),
        },
        (true, _, _) => TopologyEvent::Vanished {
            contour: ContourId(id),
        },
        (false, _, _) => TopologyEvent::HoleGone {
            hole: ContourId(id),
            into: None,
        },
    }
}
