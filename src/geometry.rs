//! Points, exact orientation predicates and segment intersection (DESIGN layer 1).
//!
//! Every decision the topology core takes — does this edge cross that one, is this point
//! in the motion region — goes through [`orient`], Shewchuk's adaptive exact `orient2d`
//! (the `robust` crate). Only the *position* of a crossing point is computed in plain
//! floating point; callers guard against the rounding that can cause (see
//! `topology::motion_region`).
//!
//! Coordinates are image pixels: x to the right, y down, origin at the top-left corner of
//! the top-left pixel. All signs are those of the ordinary formulas applied to (x, y):
//! `orient(a, b, c) > 0` means c lies "left" of a→b in that algebraic sense (which looks
//! clockwise on screen because y points down). The region bounded by a ring lies on this
//! left side, so outer rings have positive [`signed_area`] and hole rings negative.

use std::ops::{Add, Mul, Sub};

/// A point (or vector) in image coordinates, pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Point {
    /// Abscissa, pixels (to the right).
    pub x: f64,
    /// Ordinate, pixels (down).
    pub y: f64,
}

impl Point {
    /// The point (x, y).
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
    /// Dot product.
    pub fn dot(self, o: Point) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// z component of the 2D cross product.
    pub fn cross(self, o: Point) -> f64 {
        self.x * o.y - self.y * o.x
    }
    /// Squared length.
    #[inline]
    pub fn norm2(self) -> f64 {
        self.x * self.x + self.y * self.y
    }
    /// Length.
    pub fn norm(self) -> f64 {
        // Not hypot: coordinates are pixels, far from overflow, and this is on hot paths.
        (self.x * self.x + self.y * self.y).sqrt()
    }
    /// Distance to `o`.
    pub fn dist(self, o: Point) -> f64 {
        (self - o).norm()
    }
    /// The point at `t` from `self` (0) to `o` (1).
    pub fn lerp(self, o: Point, t: f64) -> Point {
        Point::new(self.x + (o.x - self.x) * t, self.y + (o.y - self.y) * t)
    }
    /// Both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

impl Add for Point {
    type Output = Point;
    fn add(self, o: Point) -> Point {
        Point::new(self.x + o.x, self.y + o.y)
    }
}
impl Sub for Point {
    type Output = Point;
    fn sub(self, o: Point) -> Point {
        Point::new(self.x - o.x, self.y - o.y)
    }
}
impl Mul<f64> for Point {
    type Output = Point;
    fn mul(self, s: f64) -> Point {
        Point::new(self.x * s, self.y * s)
    }
}

/// Exact sign-correct orientation determinant of (a, b, c): positive when c is left of
/// a→b, zero when collinear. The magnitude is twice the triangle's signed area.
#[inline]
pub fn orient(a: Point, b: Point, c: Point) -> f64 {
    robust::orient2d(
        robust::Coord { x: a.x, y: a.y },
        robust::Coord { x: b.x, y: b.y },
        robust::Coord { x: c.x, y: c.y },
    )
}

#[inline]
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// Smaller of two coordinates (a plain comparison: coordinates are never NaN here, and
/// `f64::min`'s NaN handling costs on the hottest path).
#[inline]
pub fn fmin(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// Larger of two coordinates (see [`fmin`]).
#[inline]
pub fn fmax(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// Axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lower corner.
    pub min: Point,
    /// Upper corner.
    pub max: Point,
}

impl Aabb {
    /// The smallest box holding `points`.
    #[inline]
    pub fn of(points: &[Point]) -> Aabb {
        let mut b = Aabb {
            min: points[0],
            max: points[0],
        };
        for &p in &points[1..] {
            b.min.x = fmin(b.min.x, p.x);
            b.min.y = fmin(b.min.y, p.y);
            b.max.x = fmax(b.max.x, p.x);
            b.max.y = fmax(b.max.y, p.y);
        }
        b
    }
    /// The box grown by `r` on every side.
    #[inline]
    pub fn expand(self, r: f64) -> Aabb {
        Aabb {
            min: Point::new(self.min.x - r, self.min.y - r),
            max: Point::new(self.max.x + r, self.max.y + r),
        }
    }
    /// Whether `p` lies in the box (borders included).
    #[inline]
    pub fn contains(&self, p: Point) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
    /// The point of the box nearest to `p` (`p` itself when inside).
    #[inline]
    pub fn clamp(&self, p: Point) -> Point {
        Point::new(
            fmin(fmax(p.x, self.min.x), self.max.x),
            fmin(fmax(p.y, self.min.y), self.max.y),
        )
    }
}

/// How two closed segments meet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegmentIntersection {
    /// They share no point.
    None,
    /// They cross at one point interior to both; `t` is the parameter along the first
    /// segment, `u` along the second, `at` the (rounded) crossing point, and
    /// `second_from_left` says the second segment starts on the left of the first.
    Proper {
        /// Parameter along the first segment.
        t: f64,
        /// Parameter along the second segment.
        u: f64,
        /// The crossing point.
        at: Point,
        /// The second segment comes from the left of the first.
        second_from_left: bool,
    },
    /// They share exactly one point, which is an endpoint of at least one of them.
    Touch,
    /// They are collinear and share more than one point.
    Overlap,
}

/// Classifies the intersection of segments a0–a1 and b0–b1 with exact predicates.
pub fn segment_intersection(a0: Point, a1: Point, b0: Point, b1: Point) -> SegmentIntersection {
    // Cheap rejection first: this runs for every candidate edge of every move.
    if fmax(a0.x, a1.x) < fmin(b0.x, b1.x)
        || fmax(b0.x, b1.x) < fmin(a0.x, a1.x)
        || fmax(a0.y, a1.y) < fmin(b0.y, b1.y)
        || fmax(b0.y, b1.y) < fmin(a0.y, a1.y)
    {
        return SegmentIntersection::None;
    }
    let d1 = orient(a0, a1, b0);
    let d2 = orient(a0, a1, b1);
    let (s1, s2) = (sign(d1), sign(d2));
    if s1 != 0 && s1 == s2 {
        return SegmentIntersection::None;
    }
    let d3 = orient(b0, b1, a0);
    let d4 = orient(b0, b1, a1);
    let (s3, s4) = (sign(d3), sign(d4));
    if s3 != 0 && s3 == s4 {
        return SegmentIntersection::None;
    }
    if s1 != 0 && s2 != 0 && s3 != 0 && s4 != 0 {
        // Opposite signs on both: a proper crossing.
        let u = d3 / (d3 - d4);
        let t_b = d1 / (d1 - d2);
        let at = b0.lerp(b1, t_b);
        return SegmentIntersection::Proper {
            t: u,
            u: t_b,
            at,
            second_from_left: s1 > 0,
        };
    }
    if s1 == 0 && s2 == 0 {
        // Collinear: compare projections on x, or on y when the common line is vertical.
        let use_x = a0.x != a1.x || b0.x != b1.x;
        let proj = |p: Point| if use_x { p.x } else { p.y };
        let (lo_a, hi_a) = (proj(a0).min(proj(a1)), proj(a0).max(proj(a1)));
        let (lo_b, hi_b) = (proj(b0).min(proj(b1)), proj(b0).max(proj(b1)));
        let lo = lo_a.max(lo_b);
        let hi = hi_a.min(hi_b);
        return if lo < hi {
            SegmentIntersection::Overlap
        } else if lo == hi {
            SegmentIntersection::Touch
        } else {
            SegmentIntersection::None
        };
    }
    // One endpoint lies on the other segment's line and the signs straddle: it is on the
    // segment itself (the boxes overlap and the other test straddles too).
    SegmentIntersection::Touch
}

/// The endpoint edges `s` and `e` (each two endpoints with their ids) share, if any:
/// the shared point, `s`'s other end and `e`'s other end. Ids are compared, not points:
/// a ring's neighbouring edges share a vertex, distinct vertices may coincide.
#[inline(always)]
pub fn shared_endpoint<I: PartialEq + Copy>(
    s: [(I, Point); 2],
    e: [(I, Point); 2],
) -> Option<(Point, Point, Point)> {
    let [(s0id, s0), (s1id, s1)] = s;
    let [(aid, pa), (bid, pb)] = e;
    if aid == s0id {
        Some((s0, s1, pb))
    } else if aid == s1id {
        Some((s1, s0, pb))
    } else if bid == s0id {
        Some((s0, s1, pa))
    } else if bid == s1id {
        Some((s1, s0, pa))
    } else {
        None
    }
}

/// Whether edges `s` and `e` meet where two edges of simple rings may not: edges sharing
/// an endpoint anywhere beyond it (they fold onto each other), others anywhere.
#[inline(always)]
pub fn edges_clash<I: PartialEq + Copy>(s: [(I, Point); 2], e: [(I, Point); 2]) -> bool {
    match shared_endpoint(s, e) {
        Some((at, s_other, e_other)) => folds_back(at, s_other, e_other),
        None => segment_intersection(s[0].1, s[1].1, e[0].1, e[1].1) != SegmentIntersection::None,
    }
}

/// Whether segments s0–s1 and s0–t (sharing the endpoint s0) overlap beyond s0.
#[inline]
pub fn folds_back(s0: Point, s1: Point, t: Point) -> bool {
    // The cheap test first (usually false); the conjunction is the same either way.
    (s1 - s0).dot(t - s0) > 0.0 && orient(s0, s1, t) == 0.0
}

/// Twice the signed area of a closed polygon (positive: region on the left of the ring).
pub fn signed_area2(pts: &[Point]) -> f64 {
    let n = pts.len();
    (0..n).map(|i| pts[i].cross(pts[(i + 1) % n])).sum()
}

/// Signed area of a closed polygon.
pub fn signed_area(pts: &[Point]) -> f64 {
    0.5 * signed_area2(pts)
}

/// Twice the signed area of a closed polygon and its area centroid (the origin when the
/// area is nil).
pub fn area2_centroid(pts: &[Point]) -> (f64, Point) {
    let n = pts.len();
    let (mut a2, mut c) = (0.0, Point::default());
    for i in 0..n {
        let (u, v) = (pts[i], pts[(i + 1) % n]);
        let k = u.cross(v);
        a2 += k;
        c = c + (u + v) * k;
    }
    if a2.abs() < 1e-9 {
        return (a2, Point::default());
    }
    (a2, c * (1.0 / (3.0 * a2)))
}

/// Winding number of the closed polygon `loop_pts` around `p`, exact as long as `p` is
/// not on the polygon (Sunday's crossing rule with exact orientation tests).
pub fn winding_number(loop_pts: &[Point], p: Point) -> i32 {
    let n = loop_pts.len();
    let mut w = 0;
    for i in 0..n {
        let a = loop_pts[i];
        let b = loop_pts[(i + 1) % n];
        if a.y <= p.y {
            if b.y > p.y && orient(a, b, p) > 0.0 {
                w += 1;
            }
        } else if b.y <= p.y && orient(a, b, p) < 0.0 {
            w -= 1;
        }
    }
    w
}

/// Distance from `p` to segment a–b.
pub fn point_segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let ab = b - a;
    let len2 = ab.dot(ab);
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.dist(a.lerp(b, t))
}

/// Calls `set` for every pixel whose centre lies inside `rings` by the even-odd rule,
/// scanline by scanline; edges are bucketed by the rows they span, so the cost is linear
/// in the output size.
pub fn fill_even_odd(rings: &[Vec<Point>], w: usize, h: usize, mut set: impl FnMut(usize)) {
    let mut rows: Vec<Vec<(Point, Point)>> = vec![Vec::new(); h];
    for r in rings {
        for i in 0..r.len() {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            let (y0, y1) = (a.y.min(b.y), a.y.max(b.y));
            let lo = (y0 - 0.5).ceil().max(0.0) as usize;
            let hi = ((y1 - 0.5).floor()).min(h as f64 - 1.0);
            if hi < 0.0 {
                continue;
            }
            for row in rows.iter_mut().take(hi as usize + 1).skip(lo) {
                row.push((a, b));
            }
        }
    }
    let mut xs: Vec<f64> = Vec::new();
    for (y, row) in rows.iter().enumerate() {
        let yc = y as f64 + 0.5;
        xs.clear();
        for &(a, b) in row {
            if (a.y > yc) != (b.y > yc) {
                xs.push(a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y));
            }
        }
        xs.sort_by(f64::total_cmp);
        for pair in xs.chunks_exact(2) {
            // Pixels whose centre x + 0.5 lies in [x0, x1).
            let x0 = (pair[0] - 0.5).ceil().max(0.0) as usize;
            let x1 = ((pair[1] - 0.5).ceil().max(0.0) as usize).min(w);
            for x in x0..x1 {
                set(y * w + x);
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
    fn classifies_intersections() {
        use SegmentIntersection::*;
        assert!(matches!(
            segment_intersection(p(0., 0.), p(2., 2.), p(0., 2.), p(2., 0.)),
            Proper { .. }
        ));
        if let Proper {
            t,
            u,
            at,
            second_from_left,
        } = segment_intersection(p(0., 0.), p(2., 2.), p(0., 2.), p(2., 0.))
        {
            assert_eq!((t, u, at, second_from_left), (0.5, 0.5, p(1., 1.), true));
        }
        assert_eq!(
            segment_intersection(p(0., 0.), p(1., 0.), p(0., 1.), p(1., 1.)),
            None
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(1., 0.), p(1., 1.)),
            Touch
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(2., 0.), p(3., 0.)),
            Touch
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(1., 0.), p(3., 0.)),
            Overlap
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(0., 2.), p(0., 1.), p(0., 3.)),
            Overlap
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(3., 0.), p(4., 0.)),
            None
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(3., -1.), p(3., 1.)),
            None
        );
        assert_eq!(
            segment_intersection(p(0., 0.), p(2., 0.), p(2., -1.), p(2., 1.)),
            Touch
        );
    }

    #[test]
    fn winding_and_area() {
        let sq = [p(0., 0.), p(2., 0.), p(2., 2.), p(0., 2.)];
        assert_eq!(signed_area(&sq), 4.0);
        assert_eq!(winding_number(&sq, p(1., 1.)), 1);
        assert_eq!(winding_number(&sq, p(3., 1.)), 0);
        let bow = [p(0., 0.), p(2., 2.), p(2., 0.), p(0., 2.)];
        assert_eq!(winding_number(&bow, p(1.5, 1.)), -1);
        assert_eq!(winding_number(&bow, p(0.5, 1.)), 1);
        assert!(folds_back(p(0., 0.), p(1., 0.), p(2., 0.)));
        assert!(!folds_back(p(0., 0.), p(1., 0.), p(-2., 0.)));
    }
}
