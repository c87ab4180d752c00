//! The quiet move: the common case of seed 003's correction, certified cheaply.
//!
//! Most moves of an evolving contour change nothing but the vertex: c' crosses nothing
//! and M holds no ring (§3: "usually less than five edges" are near). The general path
//! gathers those edges from the broad phase; this one proves first that the only geometry
//! near the move is the moving ring's own chain through p, o and n, and then tests only
//! that chain.
//!
//! The certificate: let B be the box of p, o, q and n grown by half the edge reach, and
//! R the part of the broad phase that a query for B reads (a rectangle of bins, or one
//! hash bucket, [`Region`](crate::contours::Region)), holding `k` registered vertices.
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

use crate::contours::{BroadPhase, ContourSet};
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
        let (pid, nid) = (self.prev[v as usize], self.next[v as usize]);
        let label = self.label[v as usize];
        if self.ring(label).len < MIN_RING {
            return false;
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
            return false;
        }
        let path = Aabb::of(&[p, q, n]);
        let b = Aabb {
            min: Point::new(fmin(path.min.x, o.x), fmin(path.min.y, o.y)),
            max: Point::new(fmax(path.max.x, o.x), fmax(path.max.y, o.y)),
        }
        .expand(0.5 * self.reach);
        let Some((region, held)) = self.bins.region(&b) else {
            return false;
        };
        // o, p and n lie in B, hence in R. Walk on from the vertices beyond p and n.
        let (c2, d2) = (self.prev[pid as usize], self.next[nid as usize]);
        let mut met = 3;
        let mut back = c2;
        while self.bins.in_region(back, &region) {
            if back == nid || met > MAX_WALK {
                return false;
            }
            met += 1;
            back = self.prev[back as usize];
        }
        let mut fwd = d2;
        while self.bins.in_region(fwd, &region) {
            if met > 2 * MAX_WALK {
                return false;
            }
            met += 1;
            fwd = self.next[fwd as usize];
        }
        if met != held {
            return false;
        }
        // The chain's edges from `back` to p, then from n to `fwd`. The two that share p or
        // n with c' must not fold onto it there, nor meet its other edge; the others must
        // not meet c' at all.
        let (pc, pd) = (self.pos[c2 as usize], self.pos[d2 as usize]);
        let clear = |c0: Point, c1: Point, e0: Point, e1: Point| {
            segment_intersection(c0, c1, e0, e1) == SegmentIntersection::None
        };
        if folds_back(p, q, pc)
            || folds_back(n, q, pd)
            || !clear(q, n, pc, p)
            || !clear(p, q, n, pd)
        {
            return false;
        }
        let c = [p, q, n];
        if !self.chain_clear(back, c2, c, &path) || !self.chain_clear(d2, fwd, c, &path) {
            return false;
        }
        let r = self.ring_mut(label);
        r.area2 += p.cross(q) + q.cross(n) - p.cross(o) - o.cross(n);
        self.pos[v as usize] = q;
        self.bins.update(v, q);
        true
    }

    /// Whether every edge of the chain from `from` to `to` stays clear of c' = [p, q, n]
    /// (`path`: its box).
    #[inline(always)]
    fn chain_clear(&self, from: u32, to: u32, [p, q, n]: [Point; 3], path: &Aabb) -> bool {
        let mut a = from;
        while a != to {
            let an = self.next[a as usize];
            let (pa, pb) = (self.pos[a as usize], self.pos[an as usize]);
            // Most chain edges are nowhere near c': one box test clears both new edges.
            let far = fmax(pa.x, pb.x) < path.min.x
                || fmin(pa.x, pb.x) > path.max.x
                || fmax(pa.y, pb.y) < path.min.y
                || fmin(pa.y, pb.y) > path.max.y;
            if !far
                && (segment_intersection(p, q, pa, pb) != SegmentIntersection::None
                    || segment_intersection(q, n, pa, pb) != SegmentIntersection::None)
            {
                return false;
            }
            a = an;
        }
        true
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
