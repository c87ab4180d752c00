//! Planning a move (seed 003 §2.3): everything [`ContourSet::move_vertex`] decides
//! before anything changes — the motion region, Directive 1's crossings of c',
//! Directive 2's rings inside M, and the rings whose labels may change.

use super::directive1::{self, find_crossings, guard_crossings, NewEdge};
use super::events::OldRing;
use super::{Degeneracy, MotionRegion, MoveError};
use crate::contours::ContourSet;
use crate::geometry::{folds_back, Aabb, Point};

/// What [`ContourSet::replace_vertex`] decided before changing anything.
pub(super) struct MovePlan {
    pub(super) pid: u32,
    pub(super) nid: u32,
    pub(super) p: Point,
    pub(super) o: Point,
    pub(super) n: Point,
    /// The moving vertex's ring.
    pub(super) label: u32,
    /// Directive 1's crossings of c', sorted along it.
    pub(super) crossings: Vec<directive1::Crossing>,
    /// Directive 2: rings inside M with M's winding over them.
    pub(super) inside: Vec<(u32, i32)>,
    /// The moving ring itself inside M (a ring swept away), with M's winding.
    pub(super) moving_inside: Option<i32>,
    /// The rings whose labels may change, as they were.
    pub(super) old: Vec<OldRing>,
}

impl ContourSet {
    /// Everything a move decides before anything changes: the motion region, the
    /// crossings of c' (Directive 1), the rings inside M (Directive 2), the rings whose
    /// labels may change.
    #[inline(always)]
    pub(super) fn plan_move(&mut self, v: u32, to: Option<Point>) -> Result<MovePlan, MoveError> {
        let (pid, nid) = (self.prev[v as usize], self.next[v as usize]);
        let (p, o, n) = (
            self.pos[pid as usize],
            self.pos[v as usize],
            self.pos[nid as usize],
        );
        let label = self.label[v as usize];
        if let Some(q) = to {
            if q == p || q == n {
                return Err(Degeneracy::OnNeighbour.into());
            }
            // The two new edges must not fold onto each other at q.
            if folds_back(q, p, n) {
                return Err(Degeneracy::Overlap.into());
            }
        }
        let mr = MotionRegion::new(p, o, n, to);
        let new_edges_buf: [NewEdge; 2];
        let new_edges: &[NewEdge] = match to {
            Some(q) => {
                new_edges_buf = [(pid, p, v, q), (v, q, nid, n)];
                &new_edges_buf
            }
            None => {
                new_edges_buf = [(pid, p, nid, n), (pid, p, nid, n)];
                &new_edges_buf[..1]
            }
        };
        let (path, k) = mr.new_path();
        let mut cand = std::mem::take(&mut self.scratch);
        self.edges_near(&Aabb::of(&path[..k]), &mut cand);

        // Crossings are rare (a topology event or a refused move): an empty Vec costs
        // nothing until one is found.
        let mut crossings = Vec::new();
        let mut found = find_crossings(self, &mr, new_edges, &cand, [pid, v], &mut crossings);
        if found.is_ok() && !crossings.is_empty() {
            found = guard_crossings(self, new_edges, &crossings, v, &mr);
            // Candidates come in a broad-phase-specific order; the result must not.
            crossings.sort_unstable_by(|a, b| (a.k, a.t).partial_cmp(&(b.k, b.t)).unwrap());
        }
        if let Err(e) = found {
            self.scratch = cand;
            return Err(e.into());
        }

        let (inside, moving_inside, old) =
            self.plan_inside(&mr, &path[..k], &crossings, label, v, &mut cand);
        self.scratch = cand;
        Ok(MovePlan {
            pid,
            nid,
            p,
            o,
            n,
            label,
            crossings,
            inside,
            moving_inside,
            old,
        })
    }

    /// Directive 2 of a planned move, decided before anything changes: the rings inside
    /// the motion region `mr` (c' is `path`) with its winding over them, the moving ring
    /// itself if it is inside, and the rings whose labels may change, as they were.
    /// `cand` holds the edges near c' (the broad phase's answer).
    #[inline(always)]
    fn plan_inside(
        &self,
        mr: &MotionRegion,
        path: &[Point],
        crossings: &[directive1::Crossing],
        label: u32,
        v: u32,
        cand: &mut Vec<u32>,
    ) -> (Vec<(u32, i32)>, Option<i32>, Vec<OldRing>) {
        // Directive 2 candidates, decided before anything changes.
        let mut involved_buf: Vec<u32> = Vec::new();
        let involved: &[u32] = if crossings.is_empty() {
            std::slice::from_ref(&label)
        } else {
            involved_buf.push(label);
            for c in crossings {
                let l = self.label[c.edge as usize];
                if !involved_buf.contains(&l) {
                    involved_buf.push(l);
                }
            }
            &involved_buf
        };
        let mut inside: Vec<(u32, i32)> = Vec::new();
        // A ring inside M has every vertex in M's box; the edge query saw all vertices
        // within half the reach of c', which holds that box unless the move was long.
        let m_box = mr.bounds();
        let searched = Aabb::of(path).expand(0.5 * self.reach);
        if !(searched.contains(m_box.min) && searched.contains(m_box.max)) {
            self.vertices_near(&m_box, cand);
        }
        self.rings_inside(mr, &m_box, cand, involved, &mut inside);
        inside.sort_unstable();
        let moving_inside = if crossings.is_empty() {
            self.moving_ring_inside(mr, &m_box, v, self.ring(label).len)
        } else {
            None
        };
        let old: Vec<OldRing> = if crossings.is_empty() && moving_inside.is_none() {
            Vec::new() // the common case: nothing to relabel
        } else {
            involved
                .iter()
                .map(|&id| {
                    let r = self.ring(id);
                    OldRing {
                        id,
                        len: r.len,
                        outer: self.loop_is_outer(r.anchor, r.area2),
                    }
                })
                .collect()
        };
        (inside, moving_inside, old)
    }
}
