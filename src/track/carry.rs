//! What carries contours from one frame to the next: the shrunk copy a contour starts
//! the next frame from, which initial ring came from which shape, which of a frame's
//! automatic seeds no tracked cell covers, and the label raster.

use crate::contours::ContourSet;
use crate::evolution::Shape;
use crate::geometry::{fill_even_odd, Point};
use crate::image::ImageModel;
use crate::track::{TrackedObject, MIN_CLAIMED_SHARE};

/// The ring `pts` (an outer ring, region on the left) scaled about its area centroid so
/// its boundary moves in by about `by` pixels (at most to half its size): the start of
/// the next frame. A similarity keeps the ring simple, and a cell that moved less than
/// `by` is still under it.
pub fn shrunk(pts: &[Point], by: f64) -> Shape {
    let (a2, c) = crate::geometry::area2_centroid(pts);
    if a2 < 1e-9 {
        return Shape::Polygon(pts.to_vec());
    }
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
    let at = |p: Point| label_at(p, labels, width, height);
    at(shape.center()) == 0 && shape.ring(1.0).into_iter().all(|p| at(p) == 0)
}

/// The label raster of `objects` (label, outer ring): a pixel takes the label of the ring
/// its centre lies in, 0 outside all. Larger rings are drawn first, so should one ring
/// lie inside another (a cell the watershed of [`super::partition`] closed in), the
/// inner cell keeps its pixels and every listed cell shows in the label image (the
/// Cell Tracking Challenge's validator refuses a track with a frame of no pixels).
pub fn label_raster(objects: &[(u32, &[Point])], width: usize, height: usize) -> Vec<u32> {
    let mut labels = vec![0u32; width * height];
    let mut order: Vec<(f64, usize)> = objects
        .iter()
        .enumerate()
        .map(|(k, &(_, ring))| (crate::geometry::signed_area(ring).abs(), k))
        .collect();
    order.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    for (_, k) in order {
        let (label, ring) = objects[k];
        fill_even_odd(&[ring.to_vec()], width, height, |i| labels[i] = label);
    }
    labels
}

/// Automatic seeds ordered by their centres, left to right: new tracks are numbered so.
pub fn ordered(mut seeds: Vec<Shape>) -> Vec<Shape> {
    seeds.sort_by(|a, b| {
        let (a, b) = (a.center(), b.center());
        (a.x, a.y)
            .partial_cmp(&(b.x, b.y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    seeds
}

/// The label raster of a frame's pieces (labels 1, 2, … in order; which label is which
/// piece does not matter to its readers, only covered or not).
pub fn labels_of(pieces: &[Vec<TrackedObject>], width: usize, height: usize) -> Vec<u32> {
    let rings: Vec<(u32, &[Point])> = pieces
        .iter()
        .flatten()
        .enumerate()
        .map(|(k, o)| (k as u32 + 1, o.ring.as_slice()))
        .collect();
    label_raster(&rings, width, height)
}

/// The label most of `shape`'s outline and centre lie on in `labels` (0 when most lie
/// on none).
pub fn majority(shape: &Shape, labels: &[u32], width: usize, height: usize) -> u32 {
    let mut counts: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    let mut points = shape.ring(1.0);
    points.push(shape.center());
    for p in &points {
        *counts
            .entry(label_at(*p, labels, width, height))
            .or_default() += 1;
    }
    counts
        .into_iter()
        .max_by_key(|&(l, n)| (n, std::cmp::Reverse(l)))
        .map_or(0, |(l, _)| l)
}

/// Object pixels of the model's finest level that no label covers, counted only where
/// the four neighbours are uncovered object too: what the cells of a frame left over,
/// without the one-pixel band where a contour and the pixel grid disagree, or single
/// noisy pixels.
pub fn free_object(model: &ImageModel, labels: &[u32]) -> usize {
    let (w, h) = model.size();
    let view = model.level(0);
    let free: Vec<bool> = (0..w * h)
        .map(|i| labels[i] == 0 && view.pixel_score(i) > 0.0)
        .collect();
    (1..h.saturating_sub(1))
        .flat_map(|y| (1..w.saturating_sub(1)).map(move |x| y * w + x))
        .filter(|&i| free[i] && free[i - 1] && free[i + 1] && free[i - w] && free[i + w])
        .count()
}

fn label_at(p: Point, labels: &[u32], width: usize, height: usize) -> u32 {
    let (x, y) = (p.x.floor(), p.y.floor());
    if x < 0.0 || y < 0.0 || x >= width as f64 || y >= height as f64 {
        return 0;
    }
    labels[y as usize * width + x as usize]
}

/// Where a shape of a frame's evolution came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Origin {
    /// The contour of this track in the frame before.
    Carried(u32),
    /// A shape of frame 0 or an automatic seed where no cell was the frame before.
    New,
    /// An automatic seed where this track's cell was the frame before, which its contour
    /// has left: a daughter that came apart from it (see [`claim`]).
    Daughter(u32),
}

/// The cells of a first evolution as the shapes of a second: each piece its own shape,
/// with its origin.
pub fn settled(origins: &[Origin], pieces: &[Vec<TrackedObject>]) -> (Vec<Shape>, Vec<Origin>) {
    origins
        .iter()
        .zip(pieces)
        .flat_map(|(&o, g)| g.iter().map(move |p| (Shape::Polygon(p.ring.clone()), o)))
        .unzip()
}

/// The pieces of shapes of one origin in one group (largest first, shreds under `share`
/// of the largest dropped: [`drop_shreds`]), shapes of other origins as they are.
pub fn regroup(
    origins: Vec<Origin>,
    pieces: Vec<Vec<TrackedObject>>,
    share: f64,
) -> (Vec<Origin>, Vec<Vec<TrackedObject>>) {
    let (mut out_o, mut out_p): (Vec<Origin>, Vec<Vec<TrackedObject>>) = (Vec::new(), Vec::new());
    for (o, g) in origins.into_iter().zip(pieces) {
        match out_o
            .iter()
            .position(|&k| k == o && matches!(o, Origin::Carried(_)))
        {
            Some(k) => out_p[k].extend(g),
            None => {
                out_o.push(o);
                out_p.push(g);
            }
        }
    }
    out_p.iter_mut().for_each(|g| drop_shreds(g, share));
    (out_o, out_p)
}

/// Sorts one shape's pieces largest first and drops those under `share` of the largest
/// (shreds, not daughters: [`crate::track::MIN_DAUGHTER_SHARE`], or
/// [`crate::track::SISTER_SHARE`] in transmitted light).
pub fn drop_shreds(g: &mut Vec<TrackedObject>, share: f64) {
    g.sort_by(|a, b| b.area.total_cmp(&a.area));
    if let Some(big) = g.first().map(|o| o.area) {
        g.retain(|o| o.area >= share * big);
    }
}

/// Each shape's pieces with the track they belong to (`None`: new tracks). A daughter
/// seed's largest piece joins its mother's when the mother's contour came through whole
/// and the smaller of the two is at least [`MIN_CLAIMED_SHARE`] of the larger: the
/// mother divided, one daughter under its contour and one that came apart from it (its
/// contour let go of the part that pinched off dimly, as nuclei do when they condense).
/// Otherwise the seed starts tracks of its own.
pub fn claim(
    origins: &[Origin],
    mut pieces: Vec<Vec<TrackedObject>>,
) -> Vec<(Option<u32>, Vec<TrackedObject>)> {
    let carried: std::collections::HashMap<u32, usize> = origins
        .iter()
        .enumerate()
        .filter_map(|(i, o)| match o {
            Origin::Carried(x) => Some((*x, i)),
            _ => None,
        })
        .collect();
    for i in 0..origins.len() {
        let Origin::Daughter(x) = origins[i] else {
            continue;
        };
        let Some(&m) = carried.get(&x) else { continue };
        let (Some(mother), Some(child)) = (pieces[m].first(), pieces[i].first()) else {
            continue;
        };
        let (a, b) = (mother.area, child.area);
        if pieces[m].len() == 1 && a.min(b) >= MIN_CLAIMED_SHARE * a.max(b) {
            let child = pieces[i].remove(0);
            pieces[m].push(child);
            pieces[m].sort_by(|a, b| b.area.total_cmp(&a.area));
        }
    }
    origins
        .iter()
        .zip(pieces)
        .map(|(o, g)| match o {
            Origin::Carried(x) => (Some(*x), g),
            _ => (None, g),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::track::MIN_DAUGHTER_SHARE;

    fn piece(area: f64) -> TrackedObject {
        TrackedObject {
            track: 0,
            ring: Vec::new(),
            area,
            centroid: Point::new(0.0, 0.0),
        }
    }

    fn areas(groups: &[(Option<u32>, Vec<TrackedObject>)]) -> Vec<(Option<u32>, Vec<f64>)> {
        groups
            .iter()
            .map(|(o, g)| (*o, g.iter().map(|p| p.area).collect()))
            .collect()
    }

    #[test]
    fn a_daughter_seed_joins_its_whole_mother() {
        let origins = [Origin::Carried(4), Origin::Daughter(4), Origin::New];
        let pieces = vec![vec![piece(900.0)], vec![piece(120.0)], vec![piece(500.0)]];
        assert_eq!(
            areas(&claim(&origins, pieces)),
            [
                (Some(4), vec![900.0, 120.0]),
                (None, vec![]),
                (None, vec![500.0])
            ]
        );
    }

    #[test]
    fn a_daughter_seed_of_a_split_mother_or_a_speck_stays_new() {
        // The mother split by herself: the seed is a cell of its own.
        let origins = [Origin::Carried(4), Origin::Daughter(4)];
        let pieces = vec![vec![piece(500.0), piece(400.0)], vec![piece(300.0)]];
        assert_eq!(
            areas(&claim(&origins, pieces)),
            [(Some(4), vec![500.0, 400.0]), (None, vec![300.0])]
        );
        // Under MIN_CLAIMED_SHARE of the mother: not a daughter.
        let pieces = vec![vec![piece(1000.0)], vec![piece(40.0)]];
        assert_eq!(
            areas(&claim(&origins, pieces)),
            [(Some(4), vec![1000.0]), (None, vec![40.0])]
        );
    }

    #[test]
    fn regrouped_pieces_of_one_track_lose_their_shreds() {
        let origins = vec![Origin::Carried(2), Origin::New, Origin::Carried(2)];
        let pieces = vec![
            vec![piece(300.0)],
            vec![piece(50.0)],
            vec![piece(1000.0), piece(100.0)],
        ];
        let (o, p) = regroup(origins, pieces, MIN_DAUGHTER_SHARE);
        assert_eq!(o, [Origin::Carried(2), Origin::New]);
        let a: Vec<Vec<f64>> = p
            .iter()
            .map(|g| g.iter().map(|x| x.area).collect())
            .collect();
        assert_eq!(a, [vec![1000.0, 300.0], vec![50.0]]);
        // In transmitted light a piece under 0.55 of its sister is a cap torn off, not a
        // daughter; one of 0.6 is a daughter.
        for (small, kept) in [(500.0, vec![1000.0]), (600.0, vec![1000.0, 600.0])] {
            let mut g = vec![piece(small), piece(1000.0)];
            drop_shreds(&mut g, crate::track::SISTER_SHARE);
            assert_eq!(g.iter().map(|x| x.area).collect::<Vec<_>>(), kept);
        }
    }

    #[test]
    fn a_ring_inside_another_keeps_its_pixels_whatever_the_order() {
        let square = |x0: f64, x1: f64| {
            vec![
                Point::new(x0, x0),
                Point::new(x1, x0),
                Point::new(x1, x1),
                Point::new(x0, x1),
            ]
        };
        let (outer, inner) = (square(2.0, 18.0), square(8.0, 12.0));
        for objects in [
            [(1, outer.as_slice()), (2, inner.as_slice())],
            [(2, inner.as_slice()), (1, outer.as_slice())],
        ] {
            let labels = label_raster(&objects, 20, 20);
            let count = |l: u32| labels.iter().filter(|&&x| x == l).count();
            assert_eq!((count(1), count(2)), (16 * 16 - 16, 16));
        }
    }

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
