//! Per-region measurements (area, perimeter, circularity, centroid) and the clutter
//! filter. A region is an outer ring with the holes directly inside it.

use crate::contours::{ContourId, ContourSet};
use crate::geometry::Point;

/// One region: an outer ring and its holes.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Region {
    /// The outer ring.
    pub id: ContourId,
    /// Its holes.
    pub holes: Vec<ContourId>,
    /// Area of the outer ring minus its holes, square pixels.
    pub area: f64,
    /// Length of all its rings, pixels.
    pub perimeter: f64,
    /// 4πA/P²: 1 for a disk.
    pub circularity: f64,
    /// Centroid of the region (holes excluded).
    pub centroid: Point,
}

fn ring_perimeter(pts: &[Point]) -> f64 {
    (0..pts.len())
        .map(|i| pts[i].dist(pts[(i + 1) % pts.len()]))
        .sum()
}

/// First moments of a ring (area-weighted centroid sums).
fn ring_moments(pts: &[Point]) -> (f64, Point) {
    let (mut a2, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for i in 0..pts.len() {
        let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
        let c = p.cross(q);
        a2 += c;
        cx += (p.x + q.x) * c;
        cy += (p.y + q.y) * c;
    }
    (0.5 * a2, Point::new(cx / 6.0, cy / 6.0))
}

/// All regions, outer rings in id order.
pub fn regions(set: &ContourSet) -> Vec<Region> {
    let parents = set.parents();
    parents
        .iter()
        .filter(|(id, _)| !set.is_hole(*id))
        .map(|&(id, _)| {
            let holes: Vec<ContourId> = parents
                .iter()
                .filter(|(h, p)| *p == Some(id) && set.is_hole(*h))
                .map(|(h, _)| *h)
                .collect();
            measure_region(id, holes, |r| set.ring_points(r))
        })
        .collect()
}

/// The regions bounded by `rings` (id, is a hole, points), as [`regions`] measures them:
/// each hole belongs to the smallest outer ring around it.
pub fn regions_of_rings(rings: &[(u32, bool, &[Point])]) -> Vec<Region> {
    let area = |pts: &[Point]| crate::geometry::signed_area(pts).abs();
    rings
        .iter()
        .filter(|(_, hole, _)| !hole)
        .map(|&(id, _, outer)| {
            let holes: Vec<ContourId> = rings
                .iter()
                .filter(|(_, hole, pts)| *hole && !pts.is_empty())
                .filter(|(_, _, pts)| {
                    // The smallest outer ring around the hole's first point is its parent.
                    let probe = pts[0];
                    let around = |o: &[Point]| crate::geometry::winding_number(o, probe) != 0;
                    around(outer)
                        && !rings
                            .iter()
                            .any(|&(j, h, o)| !h && j != id && around(o) && area(o) < area(outer))
                })
                .map(|&(h, _, _)| ContourId(h))
                .collect();
            let points = |r: ContourId| {
                rings
                    .iter()
                    .find(|(i, _, _)| *i == r.0)
                    .map_or(Vec::new(), |(_, _, p)| p.to_vec())
            };
            measure_region(ContourId(id), holes, points)
        })
        .collect()
}

/// Area, perimeter, circularity and centroid of outer ring `id` minus its `holes`.
fn measure_region(
    id: ContourId,
    holes: Vec<ContourId>,
    ring_points: impl Fn(ContourId) -> Vec<Point>,
) -> Region {
    let (mut area, mut m) = (0.0, Point::default());
    let mut perimeter = 0.0;
    for r in std::iter::once(id).chain(holes.iter().copied()) {
        let pts = ring_points(r);
        let (a, mr) = ring_moments(&pts);
        area += a;
        m = m + mr;
        perimeter += ring_perimeter(&pts);
    }
    let centroid = if area != 0.0 {
        m * (1.0 / area)
    } else {
        Point::default()
    };
    let circularity = if perimeter > 0.0 {
        4.0 * std::f64::consts::PI * area / (perimeter * perimeter)
    } else {
        0.0
    };
    Region {
        id,
        holes,
        area,
        perimeter,
        circularity,
        centroid,
    }
}

/// Removes outer rings whose region is smaller than `min_area` (with everything inside
/// them) and holes smaller than `min_area` (filling them). Returns how many objects (outer
/// rings) went.
pub fn drop_small(set: &mut ContourSet, min_area: f64) -> usize {
    if min_area <= 0.0 {
        return 0;
    }
    let parents = set.parents();
    let mut doomed: Vec<ContourId> = parents
        .iter()
        .map(|(id, _)| *id)
        .filter(|&id| set.signed_area(id).abs() < min_area)
        .collect();
    // Everything nested in a doomed ring goes with it.
    loop {
        let more: Vec<ContourId> = parents
            .iter()
            .filter(|(id, p)| p.is_some_and(|p| doomed.contains(&p)) && !doomed.contains(id))
            .map(|(id, _)| *id)
            .collect();
        if more.is_empty() {
            break;
        }
        doomed.extend(more);
    }
    let objects = doomed.iter().filter(|&&id| !set.is_hole(id)).count();
    for id in doomed {
        set.remove_ring(id);
    }
    objects
}
