//! Directive 1 of seed 003, §2.3: splice at every crossing of the new portion c' with the
//! rest of the boundary, and delete what lies between crossings on the wrong side.
//!
//! At a crossing x of c' with an edge d, the directive keeps d before x and c' after x
//! when d enters M there, and c' before x and d after x when d leaves M. It does not
//! depend on whether M is additive or subtractive, only on the side of c' that M lies on
//! at x ([`MotionRegion::side`]).
//!
//! Implementation: each crossing becomes two vertices at x, one inserted in c' and one in
//! d. Swapping their `next` links separates the curves into disjoint loops (what the
//! paper calls separating δ'R into simple closed curves); at each crossing one of the two
//! vertices sits on the kept link and the other on the deleted one, and Lemma 1 makes
//! every loop either wholly kept or wholly deleted. Deleting a loop costs its length, the
//! O(m + 1) of §3.
//!
//! Crossing positions are rounded; a crossing closer than `eps` to another vertex, edge or
//! crossing, or between nearly parallel edges, is refused as degenerate before anything
//! changes, so rounding can never make the spliced rings touch.

use super::motion_region::MotionRegion;
use super::Degeneracy;
use crate::contours::ContourSet;
use crate::geometry::{
    fmax, fmin, folds_back, point_segment_distance, segment_intersection, shared_endpoint, Aabb,
    Point, SegmentIntersection,
};

/// One proper crossing of new edge `k` (at parameter `t`) with the edge starting at vertex
/// `edge` (at parameter `u`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossing {
    pub k: u8,
    pub t: f64,
    pub edge: u32,
    pub u: f64,
    pub at: Point,
    /// Whether d enters M here (Directive 1's "otherwise" case).
    pub enters: bool,
}

/// The new portion's edges as (start id, start, end id, end). The moving vertex `v`
/// appears by id with its new position.
pub(crate) type NewEdge = (u32, Point, u32, Point);

/// Finds every crossing of the new edges with the candidate edges (`cand` holds edge
/// start vertices), or says why the move is degenerate. `skip` are the start vertices of
/// the old edges p→o and o→n, which the move replaces.
pub(crate) fn find_crossings(
    set: &ContourSet,
    mr: &MotionRegion,
    new_edges: &[NewEdge],
    cand: &[u32],
    skip: [u32; 2],
    out: &mut Vec<Crossing>,
) -> Result<(), Degeneracy> {
    out.clear();
    let (path, len) = mr.new_path();
    let reach = Aabb::of(&path[..len]);
    for &a in cand {
        if a == skip[0] || a == skip[1] {
            continue;
        }
        let b = set.next[a as usize];
        let (pa, pb) = (set.pos[a as usize], set.pos[b as usize]);
        // Most candidates are nowhere near c': one box test rejects both new edges.
        let shares = b == path_ids(new_edges).0 || a == path_ids(new_edges).1;
        if !shares
            && (fmax(pa.x, pb.x) < reach.min.x
                || fmin(pa.x, pb.x) > reach.max.x
                || fmax(pa.y, pb.y) < reach.min.y
                || fmin(pa.y, pb.y) > reach.max.y)
        {
            continue;
        }
        for (k, &(s0id, s0, s1id, s1)) in new_edges.iter().enumerate() {
            // Edges sharing a vertex meet there; they must not also overlap.
            let shared = shared_endpoint([(s0id, s0), (s1id, s1)], [(a, pa), (b, pb)]);
            if let Some((at, s_other, e_other)) = shared {
                if folds_back(at, s_other, e_other) {
                    return Err(Degeneracy::Overlap);
                }
                continue;
            }
            match segment_intersection(s0, s1, pa, pb) {
                SegmentIntersection::None => {}
                SegmentIntersection::Proper {
                    t,
                    u,
                    at,
                    second_from_left,
                } => {
                    let side = mr.side(k, t);
                    if side == 0 {
                        return Err(Degeneracy::FlatRegion);
                    }
                    // d enters M when it comes from the side of c' that M is not on.
                    let enters = (side > 0) != second_from_left;
                    out.push(Crossing {
                        k: k as u8,
                        t,
                        edge: a,
                        u,
                        at,
                        enters,
                    });
                }
                SegmentIntersection::Touch => return Err(Degeneracy::Touch),
                SegmentIntersection::Overlap => return Err(Degeneracy::Overlap),
            }
        }
    }
    Ok(())
}

/// Ids of c's end vertices p and n.
#[inline]
fn path_ids(new_edges: &[NewEdge]) -> (u32, u32) {
    (new_edges[0].0, new_edges[new_edges.len() - 1].2)
}

/// Refuses crossings that rounding could turn into touches, or whose side of M rounding
/// could decide (see module doc).
pub(crate) fn guard_crossings(
    set: &ContourSet,
    new_edges: &[NewEdge],
    crossings: &[Crossing],
    moving: u32,
    mr: &MotionRegion,
) -> Result<(), Degeneracy> {
    let scale = new_edges
        .iter()
        .map(|e| {
            e.1.x
                .abs()
                .max(e.1.y.abs())
                .max(e.3.x.abs())
                .max(e.3.y.abs())
        })
        .fold(1.0, f64::max);
    let eps = 1e-9 * scale;
    let mut near = Vec::new();
    for (i, c) in crossings.iter().enumerate() {
        let (s0id, s0, s1id, s1) = new_edges[c.k as usize];
        let a = c.edge;
        let b = set.next[a as usize];
        let (e0, e1) = (set.pos[a as usize], set.pos[b as usize]);
        let (ds, de) = (s1 - s0, e1 - e0);
        if ds.cross(de).abs() < 1e-9 * ds.norm() * de.norm() {
            return Err(Degeneracy::NearlyParallel);
        }
        if [s0, s1, e0, e1].iter().any(|&p| p.dist(c.at) < eps) {
            return Err(Degeneracy::Near);
        }
        if crossings[i + 1..].iter().any(|o| o.at.dist(c.at) < eps) {
            return Err(Degeneracy::Near);
        }
        // Next to the old portion c the side of M at the crossing is decided by rounding
        // (a bow-tie's centre, or a spike of the old ring lying along d): refuse.
        if point_segment_distance(c.at, mr.p, mr.o) < eps
            || point_segment_distance(c.at, mr.o, mr.n) < eps
        {
            return Err(Degeneracy::Near);
        }
        set.vertices_near(&Aabb::of(&[s0, s1, e0, e1]).expand(eps), &mut near);
        for &w in &near {
            if w == a || w == b || w == s0id || w == s1id || w == moving {
                continue;
            }
            let pw = set.pos[w as usize];
            if point_segment_distance(pw, s0, s1) < eps || point_segment_distance(pw, e0, e1) < eps
            {
                return Err(Degeneracy::Near);
            }
        }
    }
    Ok(())
}

impl ContourSet {
    fn insert_after(&mut self, a: u32, x: u32) {
        let b = self.next[a as usize];
        self.next[a as usize] = x;
        self.prev[x as usize] = a;
        self.next[x as usize] = b;
        self.prev[b as usize] = x;
    }

    fn swap_next(&mut self, x: u32, y: u32) {
        let (nx, ny) = (self.next[x as usize], self.next[y as usize]);
        self.next[x as usize] = ny;
        self.prev[ny as usize] = x;
        self.next[y as usize] = nx;
        self.prev[nx as usize] = y;
    }

    /// Applies Directive 1 to the rings once c' is in place as `p → [v →] n`: inserts the
    /// crossing vertices, splices, deletes the loops on the deleted side and returns the
    /// kept crossing vertices (each surviving loop holds at least one).
    pub(crate) fn splice_crossings(
        &mut self,
        p: u32,
        v: Option<u32>,
        crossings: &mut [Crossing],
        moving_label: u32,
    ) -> Vec<u32> {
        let m = crossings.len();
        let mut on_c = vec![0u32; m];
        let mut on_d = vec![0u32; m];
        // Crossing vertices along c', in order.
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&i, &j| {
            (crossings[i].k, crossings[i].t)
                .partial_cmp(&(crossings[j].k, crossings[j].t))
                .unwrap()
        });
        let mut cursor = p;
        let mut on_second = false;
        for &i in &order {
            if crossings[i].k == 1 && !on_second {
                cursor = v.expect("a second new edge starts at the moved vertex");
                on_second = true;
            }
            let x = self.alloc(crossings[i].at, moving_label);
            self.insert_after(cursor, x);
            on_c[i] = x;
            cursor = x;
        }
        // Crossing vertices along each crossed edge, in order.
        order.sort_by(|&i, &j| {
            (crossings[i].edge, crossings[i].u)
                .partial_cmp(&(crossings[j].edge, crossings[j].u))
                .unwrap()
        });
        let mut last_edge = u32::MAX;
        for &i in &order {
            let e = crossings[i].edge;
            if e != last_edge {
                cursor = e;
                last_edge = e;
            }
            let x = self.alloc(crossings[i].at, self.label[e as usize]);
            self.insert_after(cursor, x);
            on_d[i] = x;
            cursor = x;
        }
        for i in 0..m {
            self.swap_next(on_c[i], on_d[i]);
        }
        // After the swap on_d[i] carries d-before → x → c'-after, on_c[i] the other link.
        let stamp = self.next_stamp();
        let mut kept = Vec::with_capacity(m);
        for (i, c) in crossings.iter().enumerate() {
            let k = if c.enters { on_d[i] } else { on_c[i] };
            self.mark[k as usize] = stamp;
            kept.push(k);
        }
        for (i, c) in crossings.iter().enumerate() {
            let dead = if c.enters { on_c[i] } else { on_d[i] };
            if self.label[dead as usize] == crate::contours::NIL {
                continue; // its loop is already gone
            }
            let mut w = dead;
            loop {
                let nw = self.next[w as usize];
                assert!(
                    self.mark[w as usize] != stamp,
                    "Directive 1: a deleted loop holds a kept crossing (bug)"
                );
                self.release(w);
                w = nw;
                if w == dead {
                    break;
                }
            }
        }
        kept
    }
}
