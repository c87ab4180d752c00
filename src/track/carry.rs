//! What carries contours from one frame to the next: the shrunk copy a contour starts
//! the next frame from, which initial ring came from which shape, which of a frame's
//! automatic seeds no tracked cell covers, and the label raster.

use crate::contours::ContourSet;
use crate::evolution::Shape;
use crate::geometry::{fill_even_odd, Point};

/// The ring `pts` (an outer ring, region on the left) scaled about its area centroid so
/// its boundary moves in by about `by` pixels (at most to half its size): the start of
/// the next frame. A similarity keeps the ring simple, and a cell that moved less than
/// `by` is still under it.
pub fn shrunk(pts: &[Point], by: f64) -> Shape {
    let (mut a2, mut c) = (0.0, Point::default());
    for i in 0..pts.len() {
        let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
        let k = p.cross(q);
        a2 += k;
        c = c + (p + q) * k;
    }
    if a2 <= 0.0 {
        return Shape::Polygon(pts.to_vec());
    }
    let c = c * (1.0 / (3.0 * a2));
    let radius = (0.5 * a2 / std::f64::consts::PI).sqrt();
    let f = (1.0 - by / radius).max(0.5);
    Shape::Polygon(pts.iter().map(|&p| c + (p - c) * f).collect())
}

/// For each ring of `set` (as [`crate::evolution::Evolver::new`] built it from
/// `shapes`), the index of its shape: the shape whose ring starts where this ring does
/// (the evolver may have shrunk a shape to 1/2 or 1/4 to fit it in), else the nearest
/// shape centre.
pub fn ring_origins(set: &ContourSet, shapes: &[Shape]) -> Vec<(u32, usize)> {
    let starts: Vec<[Point; 3]> = shapes
        .iter()
        .map(|s| [1.0, 0.5, 0.25].map(|f| s.scaled(f).ring(f64::INFINITY)[0]))
        .collect();
    let centres: Vec<Point> = shapes.iter().map(Shape::center).collect();
    set.contour_ids()
        .map(|id| {
            let pts = set.ring_points(id);
            let p0 = pts[0];
            let exact = starts
                .iter()
                .position(|s| s.iter().any(|q| q.dist(p0) < 1e-6));
            let i = exact.unwrap_or_else(|| {
                let m = pts.iter().fold(Point::default(), |a, &p| a + p) * (1.0 / pts.len() as f64);
                (0..shapes.len())
                    .min_by(|&a, &b| centres[a].dist(m).total_cmp(&centres[b].dist(m)))
                    .unwrap_or(0)
            });
            (id.0, i)
        })
        .collect()
}

/// Whether no pixel under `shape` (its outline and centre) carries a label in `labels`:
/// a seed there is a cell no tracked contour covers (one that entered or appeared).
pub fn uncovered(shape: &Shape, labels: &[u32], width: usize, height: usize) -> bool {
    let at = |p: Point| {
        let (x, y) = (p.x.floor(), p.y.floor());
        if x < 0.0 || y < 0.0 || x >= width as f64 || y >= height as f64 {
            return 0;
        }
        labels[y as usize * width + x as usize]
    };
    at(shape.center()) == 0 && shape.ring(1.0).into_iter().all(|p| at(p) == 0)
}

/// The label raster of `objects` (label, outer ring): a pixel takes the label of the ring
/// its centre lies in, 0 outside all.
pub fn label_raster(objects: &[(u32, &[Point])], width: usize, height: usize) -> Vec<u32> {
    let mut labels = vec![0u32; width * height];
    for &(label, ring) in objects {
        fill_even_odd(&[ring.to_vec()], width, height, |i| labels[i] = label);
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shrunk_disk_moves_in_by_the_amount() {
        let ring: Vec<Point> = (0..64)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 64.0;
                Point::new(50.0 + 20.0 * a.cos(), 40.0 + 20.0 * a.sin())
            })
            .collect();
        let Shape::Polygon(s) = shrunk(&ring, 2.0) else {
            panic!("a polygon")
        };
        let r = s[0].dist(Point::new(50.0, 40.0));
        assert!((r - 18.0).abs() < 0.1, "{r}");
    }
}
