//! The invariants of a [`ContourSet`], checked from scratch: what the property tests,
//! the fuzz target and debug builds hold the topology core to.

use super::{BroadPhase, ContourId, ContourSet};
use crate::geometry::{
    folds_back, segment_intersection, shared_endpoint, signed_area2, winding_number, Aabb, Point,
    SegmentIntersection,
};

impl ContourSet {
    /// Checks every invariant of the set and says which one fails: links, ring lengths,
    /// labels, stored areas, edge bound, bins against positions, no two edges crossing or
    /// touching, and orientations that nest (outer rings at even depth, holes at odd).
    pub fn sanity_check(&self) -> Result<(), String> {
        let seen = self.check_rings()?;
        self.check_edges(seen)?;
        self.check_nesting()
    }

    /// Links, lengths, labels and stored areas of every ring; returns the vertices seen.
    fn check_rings(&self) -> Result<usize, String> {
        let mut seen = 0usize;
        let mut ring_count = 0usize;
        for (id, r) in self.rings.iter().enumerate() {
            let Some(r) = r else { continue };
            ring_count += 1;
            if r.len < 3 {
                return Err(format!("ring {id} has {} vertices", r.len));
            }
            let mut v = r.anchor;
            let mut pts = Vec::with_capacity(r.len as usize);
            loop {
                if self.label.get(v as usize) != Some(&(id as u32)) {
                    return Err(format!(
                        "vertex {v} in ring {id} labelled {:?}",
                        self.label.get(v as usize)
                    ));
                }
                let n = self.next[v as usize];
                if self.prev[n as usize] != v {
                    return Err(format!("prev(next({v})) != {v}"));
                }
                pts.push(self.pos[v as usize]);
                v = n;
                if v == r.anchor {
                    break;
                }
                if pts.len() > r.len as usize {
                    return Err(format!("ring {id} longer than its stored length {}", r.len));
                }
            }
            if pts.len() != r.len as usize {
                return Err(format!(
                    "ring {id} has {} vertices, stored {}",
                    pts.len(),
                    r.len
                ));
            }
            seen += pts.len();
            let a2 = signed_area2(&pts);
            let scale = pts
                .iter()
                .map(|p| p.x.abs().max(p.y.abs()))
                .fold(1.0, f64::max);
            if (a2 - r.area2).abs() > 1e-7 * scale * scale * (1.0 + pts.len() as f64).sqrt() {
                return Err(format!("ring {id} area2 {a2} but stored {}", r.area2));
            }
        }
        if ring_count != self.live_rings {
            return Err(format!("{ring_count} rings, counted {}", self.live_rings));
        }
        Ok(seen)
    }

    /// Vertex count, the broad phase against positions, the reach, and no two edges
    /// crossing or touching.
    fn check_edges(&self, seen: usize) -> Result<(), String> {
        if seen != self.vertex_count() {
            return Err(format!(
                "{} live vertices but rings hold {seen}",
                self.vertex_count()
            ));
        }
        if self.bins.len() != seen {
            return Err(format!(
                "bins hold {} vertices, rings {seen}",
                self.bins.len()
            ));
        }
        let mut cand = Vec::new();
        for v in self.vertices() {
            let (a0, a1) = (
                self.pos[v as usize],
                self.pos[self.next[v as usize] as usize],
            );
            if !self.bins.finds(v, a0) {
                return Err(format!("vertex {v} not in the bin of its position"));
            }
            if a0.dist(a1) > self.reach {
                return Err(format!(
                    "edge {v} longer ({}) than the reach {}",
                    a0.dist(a1),
                    self.reach
                ));
            }
            self.edges_near(&Aabb::of(&[a0, a1]), &mut cand);
            for &c in &cand {
                if c <= v {
                    continue;
                }
                let cn = self.next[c as usize];
                let (b0, b1) = (self.pos[c as usize], self.pos[cn as usize]);
                if let Some(why) = edge_pair_fault(v, self.next[v as usize], a0, a1, c, cn, b0, b1)
                {
                    return Err(format!("edges {v} and {c}: {why}"));
                }
            }
        }
        Ok(())
    }

    /// Orientation: a ring inside an odd number of others must be a hole.
    fn check_nesting(&self) -> Result<(), String> {
        let ids: Vec<ContourId> = self.contour_ids().collect();
        let pts: Vec<Vec<Point>> = ids.iter().map(|&id| self.ring_points(id)).collect();
        for (i, &id) in ids.iter().enumerate() {
            let probe = pts[i][0];
            let depth = (0..ids.len())
                .filter(|&j| j != i && winding_number(&pts[j], probe) != 0)
                .count();
            if self.is_hole(id) != (depth % 2 == 1) {
                let kind = if self.is_hole(id) {
                    "hole"
                } else {
                    "outer ring"
                };
                return Err(format!("ring {id} is a {kind} at nesting depth {depth}"));
            }
        }
        Ok(())
    }
}

/// What is wrong with two distinct edges a0→a1 (start `va`, end `na`) and b0→b1, if
/// anything: edges sharing a vertex may meet only there; others may not meet at all.
#[allow(clippy::too_many_arguments)]
pub(crate) fn edge_pair_fault(
    va: u32,
    na: u32,
    a0: Point,
    a1: Point,
    vb: u32,
    nb: u32,
    b0: Point,
    b1: Point,
) -> Option<&'static str> {
    if na == vb && nb == va {
        return Some("two-vertex ring");
    }
    if let Some((at, x, y)) = shared_endpoint([(va, a0), (na, a1)], [(vb, b0), (nb, b1)]) {
        // They meet at the shared vertex; anything more is an overlap.
        folds_back(at, x, y).then_some("adjacent edges overlap")
    } else {
        match segment_intersection(a0, a1, b0, b1) {
            SegmentIntersection::None => None,
            SegmentIntersection::Proper { .. } => Some("cross"),
            SegmentIntersection::Touch => Some("touch"),
            SegmentIntersection::Overlap => Some("overlap"),
        }
    }
}
