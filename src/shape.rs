//! The shapes a user draws to start a run: seed disks, a wrap rectangle (a margin inside
//! the border), any rectangle, a polygon. Each becomes an outer ring with vertices about
//! `spacing` apart.

use crate::geometry::{signed_area, Aabb, Point};

/// One shape of an initialisation, in image pixels.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub enum Shape {
    /// A seed disk.
    Disk {
        /// Its centre.
        center: Point,
        /// Its radius, pixels.
        radius: f64,
    },
    /// A rectangle.
    Rect {
        /// Lower corner.
        min: Point,
        /// Upper corner.
        max: Point,
    },
    /// A polygon through these corners.
    Polygon(Vec<Point>),
}

impl Shape {
    /// The ring for this shape, region on the left, vertices at most `spacing` apart.
    pub fn ring(&self, spacing: f64) -> Vec<Point> {
        match self {
            Shape::Disk { center, radius } => {
                let k = ((std::f64::consts::TAU * radius / spacing).ceil() as usize).max(6);
                (0..k)
                    .map(|i| {
                        let a = std::f64::consts::TAU * i as f64 / k as f64;
                        Point::new(center.x + radius * a.cos(), center.y + radius * a.sin())
                    })
                    .collect()
            }
            Shape::Rect { min, max } => {
                let corners = [
                    *min,
                    Point::new(max.x, min.y),
                    *max,
                    Point::new(min.x, max.y),
                ];
                densify(&corners, spacing)
            }
            Shape::Polygon(pts) => {
                let mut pts = thinned(pts, MIN_CORNER_GAP.min(0.5 * spacing));
                if signed_area(&pts) < 0.0 {
                    pts.reverse();
                }
                densify(&pts, spacing)
            }
        }
    }

    /// [`Shape::ring`] clipped to the box `within` (Sutherland–Hodgman; exact for disks
    /// and rectangles, which are convex), with edges at most `spacing` and no repeated
    /// points. Empty when the shape lies outside the box.
    pub fn ring_within(&self, spacing: f64, within: &Aabb) -> Vec<Point> {
        let ring = self.ring(spacing);
        if ring.iter().all(|&p| within.contains(p)) {
            return ring;
        }
        let clipped = clip_to_box(&ring, within);
        let mut out: Vec<Point> = Vec::with_capacity(clipped.len());
        for p in densify(&clipped, spacing) {
            if out.last().is_none_or(|&q| q.dist(p) > 1e-9) {
                out.push(p);
            }
        }
        while out.len() > 1 && out[0].dist(out[out.len() - 1]) <= 1e-9 {
            out.pop();
        }
        if out.len() < 3 || signed_area(&out).abs() < 1e-9 {
            return Vec::new();
        }
        out
    }

    /// A point inside the shape (its centre, for disks and rectangles).
    pub fn center(&self) -> Point {
        match self {
            Shape::Disk { center, .. } => *center,
            Shape::Rect { min, max } => min.lerp(*max, 0.5),
            Shape::Polygon(pts) => {
                pts.iter().fold(Point::default(), |a, &p| a + p) * (1.0 / pts.len() as f64)
            }
        }
    }

    /// The same shape scaled about its centre.
    pub fn scaled(&self, f: f64) -> Shape {
        let c = self.center();
        let s = |p: Point| c + (p - c) * f;
        match self {
            Shape::Disk { center, radius } => Shape::Disk {
                center: *center,
                radius: radius * f,
            },
            Shape::Rect { min, max } => Shape::Rect {
                min: s(*min),
                max: s(*max),
            },
            Shape::Polygon(pts) => Shape::Polygon(pts.iter().map(|&p| s(p)).collect()),
        }
    }
}

/// The part of a closed polygon inside `b`, one half-plane at a time.
fn clip_to_box(pts: &[Point], b: &Aabb) -> Vec<Point> {
    // Each side as a signed distance, inside ≥ 0.
    let sides: [fn(Point, &Aabb) -> f64; 4] = [
        |p, b| p.x - b.min.x,
        |p, b| b.max.x - p.x,
        |p, b| p.y - b.min.y,
        |p, b| b.max.y - p.y,
    ];
    let mut poly = pts.to_vec();
    for dist in sides {
        let input = std::mem::take(&mut poly);
        let n = input.len();
        for i in 0..n {
            let (a, c) = (input[i], input[(i + 1) % n]);
            let (da, dc) = (dist(a, b), dist(c, b));
            if da >= 0.0 {
                poly.push(a);
            }
            if (da >= 0.0) != (dc >= 0.0) {
                // Rounding may put the crossing a hair outside: clamp.
                poly.push(b.clamp(a.lerp(c, da / (da - dc))));
            }
        }
    }
    poly
}

/// Corners of a polygon closer than this to the previous corner add nothing at pixel
/// resolution (found seeds have corners on pixel corners, a pixel or more apart).
const MIN_CORNER_GAP: f64 = 0.25;

/// The corners of a polygon without those closer than `gap` to the last one kept: a
/// polygon of 100,000 corners on a circle of a few hundred pixels made a ring whose
/// crowded vertices made setting it up quadratic (9.7 s).
fn thinned(pts: &[Point], gap: f64) -> Vec<Point> {
    let mut out: Vec<Point> = Vec::with_capacity(pts.len().min(1 << 16));
    for &p in pts {
        if out.last().is_none_or(|&q| q.dist(p) >= gap) {
            out.push(p);
        }
    }
    while out.len() > 3 && out[0].dist(out[out.len() - 1]) < gap {
        out.pop();
    }
    out
}

/// Inserts points so that no edge of the closed polygon is longer than `spacing`.
pub fn densify(pts: &[Point], spacing: f64) -> Vec<Point> {
    let n = pts.len();
    let mut out = Vec::new();
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        let k = (a.dist(b) / spacing).ceil().max(1.0) as usize;
        for j in 0..k {
            out.push(a.lerp(b, j as f64 / k as f64));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shapes_make_outer_rings_with_short_edges() {
        for s in [
            Shape::Disk {
                center: Point::new(10.0, 10.0),
                radius: 5.0,
            },
            Shape::Rect {
                min: Point::new(1.0, 2.0),
                max: Point::new(30.0, 20.0),
            },
            Shape::Polygon(vec![
                Point::new(0.0, 0.0),
                Point::new(0.0, 10.0),
                Point::new(10.0, 0.0),
            ]),
        ] {
            let r = s.ring(1.5);
            assert!(signed_area(&r) > 0.0, "{s:?}");
            assert!((0..r.len()).all(|i| r[i].dist(r[(i + 1) % r.len()]) <= 1.5 + 1e-9));
        }
    }
}
