//! The quiet move: the common case of seed 003's correction, certified cheaply.
//!
//! Most moves of an evolving contour change nothing but the vertex: c' crosses nothing
//! and M holds no ring (§3: "usually less than five edges" are near). The general path
//! gathers those edges from the broad phase; this one proves first that the only geometry
//! near the move is the moving ring's own chain through p, o and n, and then tests only
//! that chain.
//!
//! The certificate: let B be the box of p, o, q and n grown by half the edge reach, and
//! R the part of the broad phase that a query for B reads (a rectangle of bins, or of
//! boxes of one hash system, [`Countable`]), holding `k` registered vertices (a per-cell or
//! per-bucket counter gives k at once; a hash bucket's counter may include other boxes
//! hashed to it, and then the bucket's list is counted box by box before giving up).
//! Walking from o backwards through p and forwards through n while the vertices are
//! registered in R, we meet some of them. If we meet all `k`, every vertex lying in B is
//! on the walked chain, so every edge with an endpoint in B is a chain edge (or one of the
//! two edges leaving it), which are the candidates the broad phase would return. The new
//! edges are tested against those; should any test find a crossing, a touch or a
//! fold-back, or the walk not meet all `k`, the general path decides (nothing changed).
//!
//! Directive 2 then has nothing to do: a ring inside M has its vertices in M's box ⊂ B,
//! so it would be on the walked chain, i.e. be the moving ring, and the moving ring's
//! chain n → … → p reaches a vertex outside R (outside B, outside M̄) without crossing
//! ∂M, so it lies outside M.

use crate::contours::{Broad, BroadPhase, ContourSet, Countable};
use crate::geometry::SegmentIntersection;
use crate::geometry::{fmax, fmin, folds_back, segment_intersection, Aabb, Point};

/// Longest walk each way before the general path takes over (a move near a tight fold).
const MAX_WALK: u32 = 24;
/// Rings this short go the general way (a walk could wrap around them).
const MIN_RING: u32 = 8;

impl ContourSet {
    /// Moves `v` (at o, between p and n) to `q` if the move is certified quiet: no
    /// crossing, no ring in M, no edge over the bound. Returns whether it moved.
    pub(crate) fn quiet_move(&mut self, v: u32, q: Point) -> bool {
        // One dispatch, then a walk specialised to the broad phase.
        let delta2 = match &self.bins {
            Broad::Bins(b) => self.certify(b, v, q),
            Broad::Hash(h) => self.certify(h, v, q),
        };
        let Some(delta2) = delta2 else {
            return false;
        };
        let label = self.label[v as usize];
        self.ring_mut(label).area2 += delta2;
        self.pos[v as usize] = q;
        // Per arm, so each broad phase's update can be inlined here.
        match &mut self.bins {
            Broad::Bins(b) => b.update(v, q),
            Broad::Hash(h) => h.update(v, q),
        }
        true
    }

    /// The certificate of the module doc for moving `v` to `q`: `Some` (twice the change
    /// of its ring's area) when the move is quiet, `None` when the general path decides.
    #[inline(always)]
    fn certify<B: Countable>(&self, bins: &B, v: u32, q: Point) -> Option<f64> {
        let (pid, nid) = (self.prev[v as usize], self.next[v as usize]);
        if self.ring(self.label[v as usize]).len < MIN_RING {
            return None;
        }
        let (p, o, n) = (
            self.pos[pid as usize],
            self.pos[v as usize],
            self.pos[nid as usize],
        );
        let bound2 = self.max_edge * self.max_edge;
        if q == p
            || q == n
            || folds_back(q, p, n)
            || (q - p).norm2() > bound2
            || (n - q).norm2() > bound2
        {
            return None;
        }
        let path = Aabb::of(&[p, q, n]);
        let b = Aabb {
            min: Point::new(fmin(path.min.x, o.x), fmin(path.min.y, o.y)),
            max: Point::new(fmax(path.max.x, o.x), fmax(path.max.y, o.y)),
        }
        .expand(0.5 * self.reach);
        let (region, held) = bins.region(&b)?;
        // The chain's edges other than the two at p and n must not meet c' = [p, q, n].
        // Most are nowhere near it: one box test clears both new edges.
        let clear = |a: Point, b: Point| {
            let far = fmax(a.x, b.x) < path.min.x
                || fmin(a.x, b.x) > path.max.x
                || fmax(a.y, b.y) < path.min.y
                || fmin(a.y, b.y) > path.max.y;
            far || (segment_intersection(p, q, a, b) == SegmentIntersection::None
                && segment_intersection(q, n, a, b) == SegmentIntersection::None)
        };
        // o, p and n lie in B, hence in R. Walk on from the vertices beyond p and n (along
        // prev, then next) while they are registered in R, testing each walked vertex's
        // edge away from p (or n) on the way; give up on reaching the other end (the walk
        // went round the ring) or meeting more than `limit` vertices.
        let (c2, d2) = (self.prev[pid as usize], self.next[nid as usize]);
        let mut met = 3;
        for (start, link, stop, limit) in [
            (c2, &self.prev, nid, MAX_WALK),
            (d2, &self.next, pid, 2 * MAX_WALK),
        ] {
            let (mut w, mut pw) = (start, self.pos[start as usize]);
            while bins.in_region(w, &region) {
                if w == stop || met > limit {
                    return None;
                }
                met += 1;
                let u = link[w as usize];
                let pu = self.pos[u as usize];
                if !clear(pw, pu) {
                    return None;
                }
                (w, pw) = (u, pu);
            }
        }
        // A hash bucket's count includes other boxes hashed to it: count exactly then.
        if met != held && met != bins.exact_count(&region) {
            return None;
        }
        // The two chain edges that share p or n with c' must not fold onto it there, nor
        // meet its other edge.
        let apart = |c0: Point, c1: Point, e0: Point, e1: Point| {
            segment_intersection(c0, c1, e0, e1) == SegmentIntersection::None
        };
        let (pc, pd) = (self.pos[c2 as usize], self.pos[d2 as usize]);
        if folds_back(p, q, pc)
            || folds_back(n, q, pd)
            || !apart(q, n, pc, p)
            || !apart(p, q, n, pd)
        {
            return None;
        }
        Some(p.cross(q) + q.cross(n) - p.cross(o) - o.cross(n))
    }
}

#[cfg(test)]
mod tests {
    use crate::check::{random_rings_in, Rng};
    use crate::contours::BroadPhaseKind;
    use crate::Point;

    /// Whenever the certificate accepts a move, the general path agrees: no event, and
    /// exactly the same rings afterwards.
    #[test]
    fn certified_moves_match_the_general_path() {
        for kind in [BroadPhaseKind::Bins, BroadPhaseKind::Hash] {
            let mut rng = Rng(11);
            let (mut quiet, mut tried) = (0, 0);
            for _ in 0..30 {
                let mut set = random_rings_in(&mut rng, 6, 6.0, kind);
                for _ in 0..400 {
                    let verts: Vec<u32> = set.vertices().collect();
                    let v = verts[rng.below(verts.len())];
                    let r = [0.1, 0.5, 2.0, 8.0][rng.below(4)];
                    let to = set.position(v) + Point::new(rng.range(-r, r), rng.range(-r, r));
                    let mut general = set.clone();
                    tried += 1;
                    if set.quiet_move(v, to) {
                        quiet += 1;
                        let ev = general.replace_vertex(v, Some(to));
                        assert_eq!(ev, Ok(Vec::new()), "{kind:?}: move of {v} to {to:?}");
                        for id in set.contour_ids() {
                            assert_eq!(set.ring_points(id), general.ring_points(id));
                            assert_eq!(set.signed_area(id), general.signed_area(id));
                        }
                        assert_eq!(set.contour_count(), general.contour_count());
                        set.sanity_check().unwrap();
                    } else {
                        let _ = set.move_vertex(v, to);
                    }
                }
            }
            // Not vacuous: many moves are quiet, many are not.
            assert!(
                quiet > tried / 10 && quiet < tried,
                "{kind:?}: {quiet} of {tried}"
            );
        }
    }
}
