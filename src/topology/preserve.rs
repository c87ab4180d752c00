//! Topology-preserving moves (seed 004, §2.4, the non-self-intersection constraint): a
//! move that would make contours cross, touch, or swallow a ring is shortened until its
//! new edges keep a small gap to every other edge, so fronts that meet stop side by side
//! instead of merging, and a contour wrapping around a hole keeps a thin slit.
//!
//! Choice: the gap is the caller's (the evolver uses 0.3 × the level's grid spacing);
//! shortening halves the step up to five times, then the vertex waits for the next frame.

use super::motion_region::MotionRegion;
use super::MoveError;
use crate::contours::{ContourSet, VertexId};
use crate::geometry::{
    point_segment_distance, segment_intersection, Aabb, Point, SegmentIntersection,
};

impl ContourSet {
    /// Whether replacing `v` by the path `p → q → n` (or `p → n` when `q` is `None`)
    /// keeps every other edge at least `gap` away, sweeps no other vertex, and does not
    /// turn the moving ring inside out.
    pub fn move_is_clear(&self, v: VertexId, q: Option<Point>, gap: f64) -> bool {
        let (pid, nid) = (self.prev[v as usize], self.next[v as usize]);
        let (p, o, n) = (
            self.pos[pid as usize],
            self.pos[v as usize],
            self.pos[nid as usize],
        );
        let path: Vec<Point> = match q {
            Some(q) => vec![p, q, n],
            None => vec![p, n],
        };
        let mr = MotionRegion::new(p, o, n, q);
        let mut cand = Vec::new();
        let mut region = Aabb::of(&path);
        let m = mr.bounds();
        region = Aabb::of(&[region.min, region.max, m.min, m.max]);
        self.edges_near(&region.expand(gap), &mut cand);
        for &a in &cand {
            if a == pid || a == v {
                continue; // the old edges p→o and o→n
            }
            let b = self.next[a as usize];
            let (pa, pb) = (self.pos[a as usize], self.pos[b as usize]);
            for w in path.windows(2) {
                let (s0, s1) = (w[0], w[1]);
                let adjacent = b == pid || a == nid;
                if adjacent {
                    // Neighbouring edges meet at p or n; their far ends must stay clear.
                    let far = if b == pid { pa } else { pb };
                    if point_segment_distance(far, s0, s1) < gap {
                        return false;
                    }
                    continue;
                }
                if segment_intersection(s0, s1, pa, pb) != SegmentIntersection::None {
                    return false;
                }
                let d = point_segment_distance(pa, s0, s1)
                    .min(point_segment_distance(pb, s0, s1))
                    .min(point_segment_distance(s0, pa, pb))
                    .min(point_segment_distance(s1, pa, pb));
                if d < gap {
                    return false;
                }
            }
            // A vertex inside the swept region would belong to a swallowed ring.
            if a != pid && a != nid && a != v && mr.winding(pa) != 0 {
                return false;
            }
        }
        // The moving ring itself must not end up inside the swept region.
        self.moving_ring_inside(&mr, &mr.bounds(), v, self.ring(self.label[v as usize]).len)
            .is_none()
    }

    /// Moves `v` towards `to` as far as [`ContourSet::move_is_clear`] allows (the full
    /// step, or a half, quarter … down to 1/32), never changing topology. Returns the
    /// distance moved.
    pub fn move_vertex_preserving(
        &mut self,
        v: VertexId,
        to: Point,
        gap: f64,
    ) -> Result<f64, MoveError> {
        if !self.is_alive(v) {
            return Err(MoveError::NoVertex(v));
        }
        if !to.is_finite() {
            return Err(MoveError::NotFinite);
        }
        let o = self.pos[v as usize];
        let mut f = 1.0;
        for _ in 0..6 {
            let q = o.lerp(to, f);
            if self.move_is_clear(v, Some(q), gap) {
                match self.move_vertex(v, q) {
                    Ok(ev) => {
                        debug_assert!(ev.is_empty(), "a clear move changed topology: {ev:?}");
                        return Ok(o.dist(q));
                    }
                    Err(MoveError::Degenerate(_)) => {}
                    Err(e) => return Err(e),
                }
            }
            f *= 0.5;
        }
        Ok(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, s: f64) -> Vec<Point> {
        vec![
            Point::new(x0, y0),
            Point::new(x0 + s, y0),
            Point::new(x0 + s, y0 + s),
            Point::new(x0, y0 + s),
        ]
    }

    #[test]
    fn fronts_stop_a_gap_apart_instead_of_merging() {
        let dom = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(100.0, 100.0),
        };
        let mut s = ContourSet::new(dom, 50.0);
        s.add_ring(&square(0.0, 0.0, 10.0)).unwrap();
        s.add_ring(&square(20.0, 0.0, 10.0)).unwrap();
        let v = s
            .vertices()
            .find(|&v| s.position(v) == Point::new(10.0, 0.0))
            .unwrap();
        // Straight into the other square: shortened to stay clear.
        let moved = s
            .move_vertex_preserving(v, Point::new(25.0, 5.0), 0.3)
            .unwrap();
        assert!(moved > 0.0 && moved < 15.0, "moved {moved}");
        assert_eq!(s.contour_count(), 2);
        s.sanity_check().unwrap();
        let q = s.position(v);
        assert!(q.x < 20.0 - 0.29, "{q:?}");
    }
}
