//! Where the line between two touching cells falls: on the image, each frame.
//!
//! Under the tracking policy two carried contours that meet are held apart where their
//! fronts collide (seed 003, Directive 1 refused: [`crate::topology::TopologyPolicy::TRACKING`]),
//! and the next frame starts from each, shrunk about its centre — across a rod's width
//! that is under a pixel, so the line between rods lying side by side stays where the
//! fronts first met while the rods slide past each other, and ends across both cells
//! (`docs/decisions.md`, 2026-12-03: 98 of 103 missed cells of a colony were so cut).
//! The papers leave open where two held-apart fronts settle; a user expects the line
//! the image shows. So each frame, the cells of a touching group are divided again by a
//! marker watershed of the frame's own region score: the markers are the cores of the
//! cells as they evolved (their pixels at least [`CORE`] of their deepest inside), the
//! union of the group is flooded from them, most object-like pixels first, so the line
//! between two cells comes to lie along the brighter seam between them (phase contrast
//! draws one) or the darker valley of fluorescence, where the score is lowest. Each
//! basin becomes the cell's ring, one pixel in from its neighbours
//! ([`crate::image::outline`]). A cell that touches no other keeps its evolved ring.

use crate::geometry::Point;
use crate::image::distance::distance_transform;
use crate::image::field::{neighbours4, Field};
use crate::image::outline::basin_outline;
use crate::image::ImageModel;
use crate::track::{carry::label_raster, carry::labels_of, object, TrackedObject};

/// A marker is the part of a cell at least this share of its deepest inside distance.
pub const CORE: f32 = 0.5;

/// Frame 0: two touching cells are one when the score along their contact is at least
/// this share of their cores' (no seam between them: one cell its seeds cut in two).
pub const JOIN_SHARE: f64 = 0.7;

/// Frame 0: and when their contact runs at least this share of the thinner one's width.
pub const JOIN_CONTACT: f64 = 0.8;

/// The cells of a label raster (`w`×`h`, labels 1..=n, 0 outside every cell) against
/// one frame's region score.
struct Cells<'a> {
    labels: &'a [u32],
    w: usize,
    h: usize,
    /// Per label: touches another.
    touching: Vec<bool>,
    /// Inside distance of each pixel of a touching cell: to the nearest other pixel.
    dist: Field,
    /// Per label: the deepest inside distance and its pixel.
    deepest: Vec<(f32, usize)>,
    /// The region score, lightly smoothed so noise does not steer the flood.
    score: Field,
}

impl<'a> Cells<'a> {
    fn new(labels: &'a [u32], model: &ImageModel) -> Option<Self> {
        let (w, h) = model.size();
        let n = labels.iter().copied().max().unwrap_or(0) as usize;
        if n < 2 || labels.len() != w * h {
            return None;
        }
        let mut touching = vec![false; n + 1];
        for (i, j) in contacts(labels, w, h) {
            touching[labels[i] as usize] = true;
            touching[labels[j] as usize] = true;
        }
        if !touching.iter().any(|&t| t) {
            return None;
        }
        let touches = |l: u32| l != 0 && touching[l as usize];
        let interior: Vec<bool> = (0..w * h)
            .map(|i| {
                let l = labels[i];
                touches(l) && neighbours4(i, w, h).all(|j| labels[j] == l)
            })
            .collect();
        let dist = distance_transform(&interior, w, h);
        let mut deepest = vec![(0f32, usize::MAX); n + 1];
        for (i, &l) in labels.iter().enumerate() {
            let d = dist.data[i];
            if touches(l) && d > deepest[l as usize].0 {
                deepest[l as usize] = (d, i);
            }
        }
        let view = model.level(0);
        let score = Field::new(
            w,
            h,
            (0..w * h)
                .map(|i| {
                    if touches(labels[i]) {
                        view.pixel_score(i) as f32
                    } else {
                        0.0
                    }
                })
                .collect(),
        )
        .blur(&[0.25, 0.5, 0.25]);
        Some(Cells {
            labels,
            w,
            h,
            touching,
            dist,
            deepest,
            score,
        })
    }

    fn touches(&self, l: u32) -> bool {
        l != 0 && self.touching[l as usize]
    }

    /// Whether pixel `i` is in its cell's core (a marker).
    fn in_core(&self, i: usize) -> bool {
        let l = self.labels[i];
        let (d, _) = self.deepest[l as usize];
        self.touches(l) && d > 0.0 && self.dist.data[i] >= CORE * d
    }

    /// The marker watershed of the touching cells (see the module doc).
    fn basins(&self) -> Vec<u32> {
        let mut basin = vec![0u32; self.w * self.h];
        let mut heap = std::collections::BinaryHeap::new();
        for (i, &l) in self.labels.iter().enumerate() {
            if self.in_core(i) {
                basin[i] = l;
                heap.push((ordered_bits(self.score.data[i]), i));
            }
        }
        while let Some((_, i)) = heap.pop() {
            for j in neighbours4(i, self.w, self.h) {
                if basin[j] == 0 && self.touches(self.labels[j]) {
                    basin[j] = basin[i];
                    heap.push((ordered_bits(self.score.data[j]), j));
                }
            }
        }
        basin
    }

    /// The ring of basin `l` of `basin`, region on the left (positive area, as evolved).
    fn ring(&self, basin: &[u32], l: u32) -> Option<Vec<Point>> {
        let (d, at) = self.deepest[l as usize];
        if d <= 0.0 {
            return None;
        }
        let mut ring = basin_outline(basin, l, at, self.w, self.h)?;
        if crate::geometry::signed_area(&ring) < 0.0 {
            ring.reverse();
        }
        Some(ring)
    }
}

/// 4-neighbouring pixel pairs `(i, j)` of two different cells.
fn contacts(labels: &[u32], w: usize, h: usize) -> impl Iterator<Item = (usize, usize)> + '_ {
    (0..w * h).flat_map(move |i| {
        let (x, y) = (i % w, i / w);
        let right = (x + 1 < w).then_some(i + 1);
        let below = (y + 1 < h).then_some(i + w);
        [right, below].into_iter().flatten().filter_map(move |j| {
            let (a, b) = (labels[i], labels[j]);
            (a != 0 && b != 0 && a != b).then_some((i, j))
        })
    })
}

/// `objects` (one frame's cells, by track) with those that touch another divided again
/// by the watershed of `model`'s finest region score ([`repartition`]).
pub fn divide_again(objects: &mut [TrackedObject], model: &ImageModel) {
    let (w, h) = model.size();
    let rings: Vec<(u32, &[Point])> = objects
        .iter()
        .map(|o| (o.track, o.ring.as_slice()))
        .collect();
    let mut new: std::collections::HashMap<u32, Vec<Point>> =
        repartition(&label_raster(&rings, w, h), model)
            .into_iter()
            .collect();
    for o in objects.iter_mut() {
        if let Some(ring) = new.remove(&o.track) {
            *o = TrackedObject {
                track: o.track,
                ..object(ring)
            };
        }
    }
}

/// Frame 0's `pieces` (per shape) with the touching ones that are one cell ([`joins`])
/// joined: the group's first piece takes the outline of their union, the others go.
pub fn join_pieces(pieces: &mut [Vec<TrackedObject>], model: &ImageModel) {
    let (w, h) = model.size();
    let labels = labels_of(pieces, w, h);
    let roots = joins(&labels, model);
    let mut rings: std::collections::HashMap<u32, Vec<Point>> =
        joined_rings(&labels, &roots, model).into_iter().collect();
    let mut k = 0u32;
    for g in pieces.iter_mut() {
        g.retain_mut(|o| {
            k += 1;
            if roots[k as usize] != k {
                return false;
            }
            if let Some(ring) = rings.remove(&k) {
                *o = object(ring);
            }
            true
        });
        g.sort_by(|a, b| b.area.total_cmp(&a.area));
    }
}

/// New rings for the cells of the label raster `labels` (`w`×`h`, 0 outside every cell)
/// that touch another, divided again by the watershed of `model`'s finest region score
/// (see the module doc): `(label, ring)`, in label order. Cells that touch none, and a
/// cell whose basin is too small for a ring, are not listed.
pub fn repartition(labels: &[u32], model: &ImageModel) -> Vec<(u32, Vec<Point>)> {
    let Some(cells) = Cells::new(labels, model) else {
        return Vec::new();
    };
    let basin = cells.basins();
    (1..cells.touching.len() as u32)
        .filter(|&l| cells.touches(l))
        .filter_map(|l| cells.ring(&basin, l).map(|r| (l, r)))
        .collect()
}

/// Frame 0's touching cells that are one cell cut in two by its seeds: pairs whose
/// contact runs at least [`JOIN_CONTACT`] of the thinner one's width with the score
/// along it at least [`JOIN_SHARE`] of the weaker core's (a seam between two cells —
/// phase contrast's bright line, fluorescence's dark valley — lowers it). Returns, per
/// label (index = label), the label it joins (itself when none), joined transitively.
pub fn joins(labels: &[u32], model: &ImageModel) -> Vec<u32> {
    let n = labels.iter().copied().max().unwrap_or(0) as usize;
    let mut root: Vec<u32> = (0..=n as u32).collect();
    let Some(cells) = Cells::new(labels, model) else {
        return root;
    };
    // Per label, its core's mean score; per pair, the contact's sum and pixels.
    let mut core = vec![(0f64, 0usize); n + 1];
    for i in 0..labels.len() {
        if cells.in_core(i) {
            let c = &mut core[labels[i] as usize];
            c.0 += cells.score.data[i] as f64;
            c.1 += 1;
        }
    }
    let mut pairs: std::collections::BTreeMap<(u32, u32), (f64, usize)> = Default::default();
    for (i, j) in contacts(labels, cells.w, cells.h) {
        let (a, b) = (labels[i], labels[j]);
        let e = pairs.entry((a.min(b), a.max(b))).or_default();
        e.0 += 0.5 * (cells.score.data[i] + cells.score.data[j]) as f64;
        e.1 += 1;
    }
    fn find(root: &mut [u32], mut l: u32) -> u32 {
        while root[l as usize] != l {
            root[l as usize] = root[root[l as usize] as usize];
            l = root[l as usize];
        }
        l
    }
    for ((a, b), (sum, count)) in pairs {
        let mean = |l: u32| {
            let (s, k) = core[l as usize];
            (k > 0).then(|| s / k as f64)
        };
        let (Some(ca), Some(cb)) = (mean(a), mean(b)) else {
            continue;
        };
        let weaker = ca.min(cb);
        let thinner = 2.0 * cells.deepest[a as usize].0.min(cells.deepest[b as usize].0) as f64;
        if weaker > 0.0
            && sum / count as f64 >= JOIN_SHARE * weaker
            && count as f64 >= JOIN_CONTACT * thinner
        {
            let (ra, rb) = (find(&mut root, a), find(&mut root, b));
            if ra != rb {
                root[ra.max(rb) as usize] = ra.min(rb);
            }
        }
    }
    for l in 0..=n as u32 {
        root[l as usize] = find(&mut root, l);
    }
    root
}

/// The ring of each joined group of `labels` (`roots` from [`joins`]): `(root, ring)`
/// for every root that another label joined, the outline of their union.
pub fn joined_rings(labels: &[u32], roots: &[u32], model: &ImageModel) -> Vec<(u32, Vec<Point>)> {
    let (w, h) = model.size();
    let merged: Vec<u32> = labels.iter().map(|&l| roots[l as usize]).collect();
    let mut joined = vec![false; roots.len()];
    for (l, &r) in roots.iter().enumerate() {
        if r as usize != l {
            joined[r as usize] = true;
        }
    }
    // Each union's deepest pixel, where its outline is followed from.
    let inside: Vec<bool> = (0..w * h)
        .map(|i| merged[i] != 0 && neighbours4(i, w, h).all(|j| merged[j] == merged[i]))
        .collect();
    let dist = distance_transform(&inside, w, h);
    let mut deepest = vec![(0f32, usize::MAX); roots.len()];
    for (i, &l) in merged.iter().enumerate() {
        if dist.data[i] > deepest[l as usize].0 {
            deepest[l as usize] = (dist.data[i], i);
        }
    }
    (1..roots.len() as u32)
        .filter(|&l| joined[l as usize] && deepest[l as usize].0 > 0.0)
        .filter_map(|l| {
            let mut ring = basin_outline(&merged, l, deepest[l as usize].1, w, h)?;
            if crate::geometry::signed_area(&ring) < 0.0 {
                ring.reverse();
            }
            Some((l, ring))
        })
        .collect()
}

/// An order-preserving key for an `f32` (negative scores included).
fn ordered_bits(s: f32) -> u32 {
    let b = s.to_bits();
    if b >> 31 == 1 {
        !b
    } else {
        b | 1 << 31
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::model::ModelParams;
    use crate::image::{Modality, Polarity};

    /// A bright block (x 20..60, y 20..40) on a dark ground, with a column of `seam`
    /// brightness at x = 34 (1.0 is the block's own).
    fn block(seam: f32) -> ImageModel {
        let (w, h) = (80, 60);
        let data = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                match (x, y) {
                    (34, 20..40) => seam,
                    (20..60, 20..40) => 1.0,
                    _ => 0.2,
                }
            })
            .collect();
        let params = ModelParams::seeds(Polarity::Bright, Modality::Fluorescence);
        ImageModel::prepare(&Field::new(w, h, data), &params, &[])
    }

    /// The block's pixels as two cells divided at column `at` (label 1 left of it).
    fn divided(at: usize) -> Vec<u32> {
        (0..80 * 60)
            .map(|i| match (i % 80, i / 80) {
                (x @ 20..60, 20..40) => 1 + (x >= at) as u32,
                _ => 0,
            })
            .collect()
    }

    fn right_end(ring: &[Point]) -> f64 {
        ring.iter().map(|p| p.x).fold(f64::MIN, f64::max)
    }

    #[test]
    fn the_line_between_two_cells_moves_onto_the_seam() {
        let new = repartition(&divided(38), &block(0.5));
        assert_eq!(new.iter().map(|r| r.0).collect::<Vec<_>>(), [1, 2]);
        // The left cell ends one pixel short of the seam column (its basin's border
        // pixel next to the other's is left out), not at the old line.
        let end = right_end(&new[0].1);
        assert!((33.0..=35.0).contains(&end), "{end}");
        assert!(new
            .iter()
            .all(|(_, r)| crate::geometry::signed_area(r) > 0.0));
        // A cell touching none keeps its ring.
        let one: Vec<u32> = divided(38).iter().map(|&l| l.min(1)).collect();
        assert!(repartition(&one, &block(0.5)).is_empty());
    }

    #[test]
    fn a_cell_cut_in_two_without_a_seam_is_joined_and_two_with_one_are_not() {
        let labels = divided(40);
        assert_eq!(joins(&labels, &block(1.0)), [0, 1, 1]);
        let rings = joined_rings(&labels, &[0, 1, 1], &block(1.0));
        assert_eq!(rings.len(), 1);
        let area = crate::geometry::signed_area(&rings[0].1);
        assert!(area > 700.0 && area <= 800.0, "{area}");
        let labels = divided(34);
        assert_eq!(joins(&labels, &block(0.3)), [0, 1, 2]);
    }
}
