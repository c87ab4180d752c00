//! Directive 2 of seed 003, §2.3: delete every closed curve lying completely in the
//! closure of the motion region.
//!
//! A ring that c' does not cross lies wholly inside M or wholly outside it (rings never
//! touch ∂M: touching moves are refused), so one vertex decides, by M's exact winding
//! number. Its sign says how the ring went: swallowed by an additive region (+1) or carved
//! away by a subtractive one (−1). Such rings have all their vertices in M's bounding box,
//! so the broad-phase candidates of the move already contain them (§3: "using the vertex
//! bins to find contours completely contained in the motion region").
//!
//! The moving ring itself is c' plus the unchanged chain n → … → p; with no crossing the
//! chain is wholly in M or wholly out, and one point of it decides. This is how a hole
//! that passes completely through itself disappears without any crossing (Figure 2(g)).

use super::motion_region::MotionRegion;
use crate::contours::ContourSet;
use crate::geometry::{orient, Aabb};

impl ContourSet {
    /// Rings other than those in `exclude` that lie inside M, with M's winding there.
    pub(crate) fn rings_inside(
        &self,
        mr: &MotionRegion,
        bounds: &Aabb,
        cand: &[u32],
        exclude: &[u32],
        out: &mut Vec<(u32, i32)>,
    ) {
        out.clear();
        for &a in cand {
            let x = self.pos[a as usize];
            if !bounds.contains(x) {
                continue; // a vertex outside M: its ring is outside (or another vertex says)
            }
            // Any vertex of a ring decides it; rings found inside are not tested again.
            let l = self.label[a as usize];
            if exclude.contains(&l) || out.iter().any(|&(o, _)| o == l) {
                continue;
            }
            let w = mr.winding(x);
            if w != 0 {
                out.push((l, w));
            }
        }
    }

    /// With no crossing, whether the moving ring ends up inside M's closure, and M's
    /// winding there. `v` is the moving vertex, still at its old position.
    pub(crate) fn moving_ring_inside(
        &self,
        mr: &MotionRegion,
        bounds: &Aabb,
        v: u32,
        ring_len: u32,
    ) -> Option<i32> {
        let n = self.next[v as usize];
        if ring_len == 3 {
            // The chain is the single edge n→p: inside M̄ iff o and q lie on opposite sides.
            let q = mr.q?;
            let before = orient(mr.p, mr.o, mr.n);
            let after = orient(mr.p, q, mr.n);
            return ((before > 0.0) != (after > 0.0)).then_some(if before > 0.0 { -1 } else { 1 });
        }
        let x = self.pos[self.next[n as usize] as usize];
        if !bounds.contains(x) {
            return None;
        }
        let w = mr.winding(x);
        (w != 0).then_some(w)
    }
}
