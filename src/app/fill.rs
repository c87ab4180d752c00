//! Filled regions with holes for the canvas: a constrained Delaunay triangulation (spade)
//! of all ring edges. Which triangles are inside follows by one walk over the faces from
//! the convex hull: crossing a ring edge (a constraint) flips inside and outside, since
//! rings never cross (even-odd equals the region).

use super::RingView;
use crate::geometry::Point;
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Triangles covering the region, in image coordinates.
pub struct FillMesh {
    triangles: Vec<[Point; 3]>,
}

impl FillMesh {
    pub fn of(rings: &[RingView]) -> Self {
        let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
            ConstrainedDelaunayTriangulation::new();
        for r in rings {
            let handles: Vec<_> = r
                .points
                .iter()
                .filter_map(|p| cdt.insert(Point2::new(p.x, p.y)).ok())
                .collect();
            for i in 0..handles.len() {
                let (a, b) = (handles[i], handles[(i + 1) % handles.len()]);
                // Rings never cross, so constraints never do; the check keeps rounding safe.
                if a != b && cdt.can_add_constraint(a, b) {
                    cdt.add_constraint(a, b);
                }
            }
        }
        // Parity per face index: -1 unseen, 0 outside, 1 inside.
        let mut parity = vec![-1i8; cdt.num_all_faces()];
        let mut stack = Vec::new();
        for h in cdt.convex_hull() {
            if let Some(f) = h.rev().face().as_inner() {
                let p = h.is_constraint_edge() as i8;
                if parity[f.fix().index()] < 0 {
                    parity[f.fix().index()] = p;
                    stack.push(f);
                }
            }
        }
        while let Some(f) = stack.pop() {
            let p = parity[f.fix().index()];
            for e in f.adjacent_edges() {
                if let Some(g) = e.rev().face().as_inner() {
                    let i = g.fix().index();
                    if parity[i] < 0 {
                        parity[i] = p ^ e.is_constraint_edge() as i8;
                        stack.push(g);
                    }
                }
            }
        }
        let triangles = cdt
            .inner_faces()
            .filter(|f| parity[f.fix().index()] == 1)
            .map(|f| {
                f.vertices()
                    .map(|v| Point::new(v.position().x, v.position().y))
            })
            .collect();
        FillMesh { triangles }
    }

    /// An egui mesh in screen coordinates.
    pub fn to_mesh(
        &self,
        screen_from_image: &impl Fn(Point) -> egui::Pos2,
        color: egui::Color32,
    ) -> egui::Mesh {
        let mut m = egui::Mesh::default();
        for t in &self.triangles {
            let base = m.vertices.len() as u32;
            for &p in t {
                m.colored_vertex(screen_from_image(p), color);
            }
            m.add_triangle(base, base + 1, base + 2);
        }
        m
    }

    #[cfg(test)]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_leaves_holes_open() {
        let p = |x: f64, y: f64| Point::new(x, y);
        let rings = vec![
            RingView {
                id: 0,
                hole: false,
                points: vec![p(0., 0.), p(10., 0.), p(10., 10.), p(0., 10.)],
            },
            RingView {
                id: 1,
                hole: true,
                points: vec![p(3., 3.), p(3., 6.), p(6., 6.), p(6., 3.)],
            },
        ];
        let m = FillMesh::of(&rings);
        let area: f64 = m
            .triangles
            .iter()
            .map(|t| 0.5 * ((t[1] - t[0]).cross(t[2] - t[0])).abs())
            .sum();
        assert!((area - 91.0).abs() < 1e-9, "area {area}");
        assert!(m.triangle_count() >= 8);
    }
}
