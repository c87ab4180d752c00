//! The motion region of a single-vertex move (seed 003, §2.2 Definition 1 and §3).
//!
//! Vertex o with neighbours p and n moves to q. The old portion is c = p→o→n, the new
//! one c' = p→q→n, and the motion region M is the open region between them: the
//! quadrilateral loop (p, q, n, o). Traversed that way the loop runs along c' forwards, so
//! its winding number is +1 where M lies on the left of c' (an *additive* region: the
//! region grows there) and −1 where M lies on its right (*subtractive*). A simple quad has
//! one sign; a bow-tie (an old edge properly crossing a new one at z) is one additive and
//! one subtractive triangle, split at z. Removing o is the same with c' = p→n and the
//! triangle (p, n, o).
//!
//! The new region is (R ∪ M⁺) − M⁻ (equation 2): a point with winding +1 joins the
//! region, −1 leaves it, 0 keeps its old state.

use crate::geometry::{
    orient, segment_intersection, winding_number, Aabb, Point, SegmentIntersection,
};

/// Where, along c', the bow-tie's two triangles meet.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Bow {
    /// Simple (or flat) region: one sign along all of c'.
    Simple,
    /// Old edge o→n crosses new edge p→q at parameter `t` of p→q.
    OnFirst(f64),
    /// Old edge p→o crosses new edge q→n at parameter `t` of q→n.
    OnSecond(f64),
}

/// The quadrilateral (or triangle, for a removal) swept by one vertex move.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionRegion {
    /// The previous vertex.
    pub p: Point,
    /// The old position of the moving vertex.
    pub o: Point,
    /// The next vertex.
    pub n: Point,
    /// New position; `None` when the vertex is removed (c' = p→n).
    pub q: Option<Point>,
}

fn sign(v: f64) -> i8 {
    (v > 0.0) as i8 - (v < 0.0) as i8
}

impl MotionRegion {
    /// The region of moving `o` to `q` (`None`: deleting `o`) between `p` and `n`.
    pub fn new(p: Point, o: Point, n: Point, q: Option<Point>) -> Self {
        MotionRegion { p, o, n, q }
    }

    /// Classifies the quadrilateral. Only moves with crossings need it, so it is not
    /// computed up front.
    fn bow(&self) -> Bow {
        let Some(q) = self.q else { return Bow::Simple };
        let (p, o, n) = (self.p, self.o, self.n);
        if let SegmentIntersection::Proper { t, .. } = segment_intersection(p, q, o, n) {
            Bow::OnFirst(t)
        } else if let SegmentIntersection::Proper { t, .. } = segment_intersection(q, n, p, o) {
            Bow::OnSecond(t)
        } else {
            Bow::Simple
        }
    }

    /// Whether the quadrilateral is a bow-tie (one additive and one subtractive triangle).
    pub fn is_bow_tie(&self) -> bool {
        self.bow() != Bow::Simple
    }

    /// The closed loop bounding M: (p, q, n, o), or (p, n, o) for a removal.
    pub fn loop_points(&self) -> ([Point; 4], usize) {
        match self.q {
            Some(q) => ([self.p, q, self.n, self.o], 4),
            None => ([self.p, self.n, self.o, self.o], 3),
        }
    }

    /// The new portion c' as a polyline.
    pub fn new_path(&self) -> ([Point; 3], usize) {
        match self.q {
            Some(q) => ([self.p, q, self.n], 3),
            None => ([self.p, self.n, self.n], 2),
        }
    }

    /// Its bounding box.
    pub fn bounds(&self) -> Aabb {
        let (pts, k) = self.loop_points();
        Aabb::of(&pts[..k])
    }

    /// Winding number of M's loop around `x`: +1 in M⁺, −1 in M⁻, 0 outside. Exact for a
    /// point not on the loop.
    pub fn winding(&self, x: Point) -> i32 {
        let (pts, k) = self.loop_points();
        winding_number(&pts[..k], x)
    }

    /// Which side of c' the motion region lies on at parameter `t` of new edge `k`
    /// (0: p→q, 1: q→n; a removal has only edge 0): +1 left (additive), −1 right
    /// (subtractive), 0 when M is flat there.
    pub fn side(&self, k: usize, t: f64) -> i8 {
        let Some(q) = self.q else {
            return sign(orient(self.p, self.n, self.o));
        };
        let (p, o, n) = (self.p, self.o, self.n);
        match self.bow() {
            // The fan from p gives the quad's signed area; its sign is M's side. Near-flat
            // regions with a crossing are rejected by the caller's guard anyway.
            Bow::Simple => sign(orient(p, q, n) + orient(p, n, o)),
            // Triangles (p, z, o) before z and (z, q, n) after, z on p→q.
            Bow::OnFirst(tz) => {
                if k == 0 && t < tz {
                    sign(orient(p, q, o))
                } else {
                    sign(orient(p, q, n))
                }
            }
            // Triangles (p, q, z) before z and (z, n, o) after, z on q→n.
            Bow::OnSecond(tz) => {
                if k == 0 || t < tz {
                    sign(orient(p, q, n))
                } else {
                    sign(orient(q, n, o))
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn simple_additive_and_subtractive() {
        // Ring (0,0)→(2,0)→(2,2)… has the region on its left (y grows "up" algebraically).
        let grow = MotionRegion::new(p(0., 0.), p(1., 0.), p(2., 0.), Some(p(1., -1.)));
        assert_eq!(grow.side(0, 0.5), 1);
        assert_eq!(grow.winding(p(1., -0.5)), 1);
        let shrink = MotionRegion::new(p(0., 0.), p(1., 0.), p(2., 0.), Some(p(1., 1.)));
        assert_eq!(shrink.side(1, 0.5), -1);
        assert_eq!(shrink.winding(p(1., 0.5)), -1);
        assert!(!grow.is_bow_tie());
    }

    #[test]
    fn bow_tie_has_both_signs() {
        // o moves past n's far side: new edge p→q crosses old edge o→n.
        let m = MotionRegion::new(p(0., 0.), p(1., 1.), p(2., 0.), Some(p(3., 2.)));
        assert!(m.is_bow_tie());
        let signs = [m.side(0, 0.1), m.side(0, 0.9), m.side(1, 0.5)];
        assert_ne!(signs[0], signs[1]);
        assert_eq!(signs[1], signs[2]);
        assert_eq!(m.winding(p(0.8, 0.7)), signs[0] as i32);
    }
}
