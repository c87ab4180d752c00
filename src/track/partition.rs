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
use crate::track::{carry::labels_of, object, TrackedObject};
use rustc_hash::FxHashMap;

/// Which touching pieces [`joins`] may join.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Join {
    /// Every rule: a seamless contact, one round body, one straight rod (frame 0).
    Any,
    /// One straight rod only ([`JOIN_ROD_SOLIDITY`]): new cells on later frames, whose
    /// uncovered ground holds debris that the seamless-contact rule would join into
    /// blobs large enough to pass for cells (docs/decisions.md, 2026-12-07, eleventh session).
    Rods,
}

/// A marker is the part of a cell at least this share of its deepest inside distance.
pub const CORE: f32 = 0.5;

/// Frame 0: two touching cells are one when the score along their contact is at least
/// this share of their cores' (no seam between them: one cell its seeds cut in two).
pub const JOIN_SHARE: f64 = 0.7;

/// Frame 0: and when their contact runs at least this share of the thinner one's width.
pub const JOIN_CONTACT: f64 = 0.8;

/// Frame 0: two touching cells whose union fills at least this share of its convex hull
/// and is rounder than a rod ([`crate::track::neck::MIN_LOBE_ASPECT`]) are one body its
/// seeds cut in two, seam or not: a nucleus's darker nucleoli can run along the cut and
/// read as a seam, while two round cells that touch leave a notch at each end of their
/// contact (two disks pressed 0.4 radii into each other fill 0.94 of their hull).
pub const JOIN_SOLIDITY: f64 = 0.94;

/// Frame 0 and new cells: two touching cells whose union is one straight rod — it
/// fills at least this share of its convex hull and is at least [`JOIN_ROD_ASPECT`]
/// times as long as wide — are one rod its seeds cut in two on a shorter contact
/// ([`JOIN_ROD_CONTACT`]) and a fainter middle ([`JOIN_ROD_SHARE`]) than [`JOIN_CONTACT`]
/// and [`JOIN_SHARE`] ask. A mottled rod's seeds settle on its darker spots, and their
/// fronts meet rounded, with a paler band between; two rods that touch at an angle or
/// side by side leave notches their union's hull fills (docs/decisions.md, 2026-12-07,
/// eleventh session).
pub const JOIN_ROD_SOLIDITY: f64 = 0.85;

/// The least aspect (major over minor axis) of a rod's union ([`JOIN_ROD_SOLIDITY`]).
pub const JOIN_ROD_ASPECT: f64 = 2.0;

/// The least contact of a rod's two pieces, as a share of the thinner one's width.
pub const JOIN_ROD_CONTACT: f64 = 0.5;

/// The least score along a rod's two pieces' contact, as a share of the weaker core's.
pub const JOIN_ROD_SHARE: f64 = 0.6;

/// Sisters that came apart and meet again the next frame are one cell again when their
/// contact runs at least this share of the thinner one's width (and shows object
/// between them: [`REJOIN_SHARE`]).
pub const REJOIN_CONTACT: f64 = 0.3;

/// The widest gap (pixels) between two cells' rasters that still counts as their contact
/// when sisters are judged one cell again ([`rejoined`]): fronts held apart where the
/// image is dimmer than either cell's body settle two or three pixels apart.
pub const REJOIN_GAP: usize = 3;

/// Sisters meet with object between them when the score where they meet (their rims
/// and the gap) is at least this share of the weaker core's: well above the decision
/// level, where a background gap reads below it. Bacteria sisters a frame old, which
/// touch across their forming septum, score from −0.2 to 0.8 there, so the test holds
/// only for sisters that came apart ([`crate::track::Tracker`]).
pub const REJOIN_SHARE: f64 = 0.25;

/// One group of touching cells of a label raster (labels 1..=n, 0 outside every cell)
/// against one frame's region score, in the window that holds the group: the work is
/// the touching cells' area, not the frame's.
struct Cells {
    /// The window's labels (other cells read as 0), its size and where its top-left
    /// pixel lies in the frame.
    labels: Vec<u32>,
    w: usize,
    h: usize,
    origin: (usize, usize),
    /// Inside distance of each pixel of a cell: to the nearest pixel of another.
    dist: Field,
    /// Per label of the group: the deepest inside distance and its pixel.
    deepest: FxHashMap<u32, (f32, usize)>,
    /// The region score, lightly smoothed so noise does not steer the flood.
    score: Field,
}

/// The groups of touching cells of `frame` (`w`×`h`): per group its labels and the box
/// (x0, y0, x1, y1, inclusive) of their pixels.
fn groups(frame: &[u32], w: usize, h: usize) -> Vec<(Vec<u32>, [usize; 4])> {
    let n = frame.iter().copied().max().unwrap_or(0) as usize;
    let mut root: Vec<u32> = (0..=n as u32).collect();
    let mut touching = vec![false; n + 1];
    for (i, j) in contacts(frame, w, h) {
        let (a, b) = (frame[i], frame[j]);
        touching[a as usize] = true;
        touching[b as usize] = true;
        let (ra, rb) = (find(&mut root, a), find(&mut root, b));
        root[ra.max(rb) as usize] = ra.min(rb);
    }
    let mut boxes: FxHashMap<u32, [usize; 4]> = FxHashMap::default();
    for (i, &l) in frame.iter().enumerate() {
        if l != 0 && touching[l as usize] {
            let (x, y) = (i % w, i / w);
            let b = boxes.entry(l).or_insert([x, y, x, y]);
            *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        }
    }
    let mut out: FxHashMap<u32, (Vec<u32>, [usize; 4])> = FxHashMap::default();
    for l in 1..=n as u32 {
        let Some(b) = boxes.get(&l) else { continue };
        let r = find(&mut root, l);
        let g = out.entry(r).or_insert((Vec::new(), *b));
        g.0.push(l);
        g.1 = [
            g.1[0].min(b[0]),
            g.1[1].min(b[1]),
            g.1[2].max(b[2]),
            g.1[3].max(b[3]),
        ];
    }
    let mut out: Vec<(Vec<u32>, [usize; 4])> = out.into_values().collect();
    out.sort_by_key(|g| g.0[0]);
    out
}

fn find(root: &mut [u32], mut l: u32) -> u32 {
    while root[l as usize] != l {
        root[l as usize] = root[root[l as usize] as usize];
        l = root[l as usize];
    }
    l
}

impl Cells {
    /// The group `members` of `frame`, in the box `b` of their pixels.
    fn new(frame: &[u32], model: &ImageModel, members: &[u32], b: [usize; 4]) -> Self {
        let (fw, fh) = model.size();
        // Two pixels of margin: the outline follower and the blur read one beyond.
        let (x0, y0) = (b[0].saturating_sub(2), b[1].saturating_sub(2));
        let (x1, y1) = ((b[2] + 3).min(fw), (b[3] + 3).min(fh));
        let (w, h) = (x1 - x0, y1 - y0);
        let at = |i: usize| (y0 + i / w) * fw + x0 + i % w;
        let labels: Vec<u32> = (0..w * h)
            .map(|i| match frame[at(i)] {
                l if members.binary_search(&l).is_ok() => l,
                _ => 0,
            })
            .collect();
        let interior: Vec<bool> = (0..w * h)
            .map(|i| labels[i] != 0 && neighbours4(i, w, h).all(|j| labels[j] == labels[i]))
            .collect();
        let dist = distance_transform(&interior, w, h);
        let mut deepest: FxHashMap<u32, (f32, usize)> =
            members.iter().map(|&l| (l, (0.0, usize::MAX))).collect();
        for (i, &l) in labels.iter().enumerate() {
            if l != 0 {
                let d = deepest.entry(l).or_insert((0.0, usize::MAX));
                if dist.data[i] > d.0 {
                    *d = (dist.data[i], i);
                }
            }
        }
        let view = model.level(0);
        let raw = (0..w * h)
            .map(|i| {
                if labels[i] != 0 {
                    view.pixel_score(at(i)) as f32
                } else {
                    0.0
                }
            })
            .collect();
        let score = Field::new(w, h, raw).blur(&[0.25, 0.5, 0.25]);
        Cells {
            labels,
            w,
            h,
            origin: (x0, y0),
            dist,
            deepest,
            score,
        }
    }

    /// Whether cells `a` and `b` together are one convex round body ([`JOIN_SOLIDITY`]).
    fn one_body(&self, a: u32, b: u32) -> bool {
        self.union_shape(a, b).is_some_and(|(solidity, aspect)| {
            aspect < crate::track::neck::MIN_LOBE_ASPECT && solidity >= JOIN_SOLIDITY
        })
    }

    /// Whether cells `a` and `b` together are one straight rod ([`JOIN_ROD_SOLIDITY`]).
    fn one_rod(&self, a: u32, b: u32) -> bool {
        self.union_shape(a, b).is_some_and(|(solidity, aspect)| {
            aspect >= JOIN_ROD_ASPECT && solidity >= JOIN_ROD_SOLIDITY
        })
    }

    /// The union of cells `a` and `b`: the share of its convex hull it fills, and its
    /// aspect (major over minor axis of its second moments). `None` under three pixels.
    fn union_shape(&self, a: u32, b: u32) -> Option<(f64, f64)> {
        let mut pts = Vec::new();
        let (mut n, mut sx, mut sy, mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for (i, &l) in self.labels.iter().enumerate() {
            if l != a && l != b {
                continue;
            }
            let (x, y) = ((i % self.w) as f64 + 0.5, (i / self.w) as f64 + 0.5);
            // Each pixel as the midpoints of its sides, so the hull holds whole pixels.
            pts.extend([
                Point::new(x - 0.5, y),
                Point::new(x + 0.5, y),
                Point::new(x, y - 0.5),
                Point::new(x, y + 0.5),
            ]);
            n += 1.0;
            (sx, sy) = (sx + x, sy + y);
            (sxx, syy, sxy) = (sxx + x * x, syy + y * y, sxy + x * y);
        }
        if n < 3.0 {
            return None;
        }
        let (mx, my) = (sx / n, sy / n);
        let (vx, vy, c) = (sxx / n - mx * mx, syy / n - my * my, sxy / n - mx * my);
        let (tr, disc) = (0.5 * (vx + vy), (0.25 * (vx - vy).powi(2) + c * c).sqrt());
        let aspect = ((tr + disc) / (tr - disc).max(1e-12)).sqrt();
        let hull = crate::geometry::signed_area(&crate::image::patch::convex_hull(pts)).abs();
        Some((n / hull.max(1e-12), aspect))
    }

    /// Whether window pixel `i` is in its cell's core (a marker).
    fn in_core(&self, i: usize) -> bool {
        let l = self.labels[i];
        l != 0
            && self
                .deepest
                .get(&l)
                .is_some_and(|&(d, _)| d > 0.0 && self.dist.data[i] >= CORE * d)
    }

    /// Per cell with a core, its core's mean score.
    fn core_means(&self) -> FxHashMap<u32, f64> {
        let mut sums: FxHashMap<u32, (f64, usize)> = FxHashMap::default();
        for i in (0..self.labels.len()).filter(|&i| self.in_core(i)) {
            let c = sums.entry(self.labels[i]).or_default();
            c.0 += self.score.data[i] as f64;
            c.1 += 1;
        }
        sums.into_iter()
            .map(|(l, (s, k))| (l, s / k as f64))
            .collect()
    }

    /// The width of the thinner of cells `a` and `b`: twice its deepest inside distance.
    fn thinner(&self, a: u32, b: u32) -> f64 {
        let depth = |l: u32| self.deepest.get(&l).map_or(0.0, |d| d.0 as f64);
        2.0 * depth(a).min(depth(b))
    }

    /// Whether cell `l` has a core (some pixel not on its border).
    fn has_core(&self, l: u32) -> bool {
        self.deepest.get(&l).is_some_and(|&(d, _)| d > 0.0)
    }

    /// The outline of `a` and `b` as one cell, the `bridge` pixels between them theirs.
    fn union_across(&mut self, a: u32, b: u32, bridge: &[usize]) -> Option<Vec<Point>> {
        for &p in bridge {
            self.labels[p] = a;
        }
        self.union_ring(a, b)
    }

    /// The outline of cells `a` and `b` together, in frame coordinates (region on the
    /// left), followed from the deepest pixel of their union.
    fn union_ring(&self, a: u32, b: u32) -> Option<Vec<Point>> {
        let merged: Vec<u32> = self
            .labels
            .iter()
            .map(|&l| u32::from(l == a || l == b))
            .collect();
        let inside: Vec<bool> = (0..merged.len())
            .map(|i| merged[i] != 0 && neighbours4(i, self.w, self.h).all(|j| merged[j] != 0))
            .collect();
        let dist = distance_transform(&inside, self.w, self.h);
        let (d, at) =
            dist.data.iter().enumerate().fold(
                (0f32, 0usize),
                |m, (i, &d)| if d > m.0 { (d, i) } else { m },
            );
        if d <= 0.0 {
            return None;
        }
        self.outline(&merged, 1, at)
    }

    /// The marker watershed of the group (see the module doc).
    fn basins(&self) -> Vec<u32> {
        let mut basin = vec![0u32; self.w * self.h];
        let mut heap = std::collections::BinaryHeap::new();
        for (i, &l) in self.labels.iter().enumerate() {
            if self.in_core(i) {
                basin[i] = l;
                heap.push((ordered_bits(self.score.data[i]), i));
            } else if l != 0 && !self.has_core(l) {
                // A cell too thin for a core keeps its ring ([`Cells::ring`]), so it
                // keeps its pixels too: flooded by a neighbour, it would lie under it.
                basin[i] = l;
            }
        }
        while let Some((_, i)) = heap.pop() {
            for j in neighbours4(i, self.w, self.h) {
                if basin[j] == 0 && self.labels[j] != 0 {
                    basin[j] = basin[i];
                    heap.push((ordered_bits(self.score.data[j]), j));
                }
            }
        }
        basin
    }

    /// The ring of basin `l` of `basin` in frame coordinates, region on the left
    /// (positive area, as evolved).
    fn ring(&self, basin: &[u32], l: u32) -> Option<Vec<Point>> {
        let &(d, at) = self.deepest.get(&l)?;
        if d <= 0.0 {
            return None;
        }
        self.outline(basin, l, at)
    }

    /// The outline of label `l` of the window raster `basin`, followed from its pixel
    /// `at`, in frame coordinates, region on the left.
    fn outline(&self, basin: &[u32], l: u32, at: usize) -> Option<Vec<Point>> {
        let shift = Point::new(self.origin.0 as f64, self.origin.1 as f64);
        let mut ring: Vec<Point> = basin_outline(basin, l, at, self.w, self.h)?
            .into_iter()
            .map(|p| p + shift)
            .collect();
        if crate::geometry::signed_area(&ring) < 0.0 {
            ring.reverse();
        }
        Some(ring)
    }
}

/// Pairs of touching cells of `labels` (the model's size) that `keep` accepts, each cell
/// in one pair at most: the longest contacts first. With each pair, the outline of the
/// two cells' union.
pub fn touching_pairs(
    labels: &[u32],
    model: &ImageModel,
    keep: impl Fn(u32, u32) -> bool,
) -> Vec<((u32, u32), Vec<Point>)> {
    let (w, h) = model.size();
    let n = labels.iter().copied().max().unwrap_or(0) as usize;
    if labels.len() != w * h {
        return Vec::new();
    }
    let mut count: std::collections::BTreeMap<(u32, u32), usize> = Default::default();
    for (i, j) in contacts(labels, w, h) {
        let (a, b) = (labels[i], labels[j]);
        *count.entry((a.min(b), a.max(b))).or_default() += 1;
    }
    let mut by_length: Vec<((u32, u32), usize)> = count
        .into_iter()
        .filter(|&((a, b), _)| keep(a, b))
        .collect();
    by_length.sort_by(|x, y| y.1.cmp(&x.1).then(x.0.cmp(&y.0)));
    let mut taken = vec![false; n + 1];
    let mut roots: Vec<u32> = (0..=n as u32).collect();
    let mut pairs = Vec::new();
    for ((a, b), _) in by_length {
        if taken[a as usize] || taken[b as usize] {
            continue;
        }
        taken[a as usize] = true;
        taken[b as usize] = true;
        roots[b as usize] = a;
        pairs.push((a, b));
    }
    let mut rings: FxHashMap<u32, Vec<Point>> =
        joined_rings(labels, &roots, model).into_iter().collect();
    pairs
        .into_iter()
        .filter_map(|(a, b)| rings.remove(&a).map(|r| ((a, b), r)))
        .collect()
}

/// 4-neighbouring pixel pairs `(i, j)` of two different cells (`j` right of or below `i`).
fn contacts(labels: &[u32], w: usize, h: usize) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    for (i, &a) in labels.iter().enumerate() {
        if a == 0 {
            continue;
        }
        let (x, y) = (i % w, i / w);
        if x + 1 < w && labels[i + 1] != 0 && labels[i + 1] != a {
            out.push((i, i + 1));
        }
        if y + 1 < h && labels[i + w] != 0 && labels[i + w] != a {
            out.push((i, i + w));
        }
    }
    out
}

/// `objects` (one frame's cells, by track; `labels` their raster) with those that touch
/// another divided again by the watershed of `model`'s finest region score
/// ([`repartition`]). Whether any changed.
pub fn divide_again(objects: &mut [TrackedObject], labels: &[u32], model: &ImageModel) -> bool {
    let mut new: FxHashMap<u32, Vec<Point>> = repartition(labels, model).into_iter().collect();
    let changed = !new.is_empty();
    for o in objects.iter_mut() {
        if let Some(ring) = new.remove(&o.track) {
            *o = TrackedObject {
                track: o.track,
                ..object(ring)
            };
        }
    }
    changed
}

/// Frame 0's `pieces` (per shape) with the touching ones that are one cell ([`joins`])
/// joined: the group's first piece takes the outline of their union, the others go.
/// Returns the joined outlines. They were judged one cell, and the neck rule must not
/// judge them again: the union's pixel outline keeps a notch at each end of the
/// contact, where the two pieces' fronts met rounded, that the image does not show
/// (`docs/decisions.md`, 2026-12-04: such cells were cut at frame 0 and divided a few
/// frames later in the truth).
pub fn join_pieces(
    pieces: &mut [Vec<TrackedObject>],
    model: &ImageModel,
    rule: Join,
) -> Vec<Vec<Point>> {
    let (w, h) = model.size();
    let labels = labels_of(pieces, w, h);
    let roots = joins(&labels, model, rule);
    let mut rings: FxHashMap<u32, Vec<Point>> =
        joined_rings(&labels, &roots, model).into_iter().collect();
    let mut k = 0u32;
    let mut joined = Vec::new();
    for g in pieces.iter_mut() {
        g.retain_mut(|o| {
            k += 1;
            if roots[k as usize] != k {
                return false;
            }
            if let Some(ring) = rings.remove(&k) {
                joined.push(ring.clone());
                *o = object(ring);
            }
            true
        });
        g.sort_by(|a, b| b.area.total_cmp(&a.area));
    }
    joined
}

/// New rings for the cells of the label raster `labels` (the model's size, 0 outside
/// every cell) that touch another, divided again by the watershed of `model`'s finest
/// region score (see the module doc): `(label, ring)`, in label order. Cells that touch
/// none, and a cell whose basin is too small for a ring, are not listed.
pub fn repartition(labels: &[u32], model: &ImageModel) -> Vec<(u32, Vec<Point>)> {
    let (w, h) = model.size();
    if labels.len() != w * h {
        return Vec::new();
    }
    let mut out: Vec<(u32, Vec<Point>)> = Vec::new();
    for (members, b) in groups(labels, w, h) {
        let cells = Cells::new(labels, model, &members, b);
        let basin = cells.basins();
        out.extend(
            members
                .iter()
                .filter_map(|&l| cells.ring(&basin, l).map(|r| (l, r))),
        );
    }
    out.sort_by_key(|r| r.0);
    out
}

/// Frame 0's touching cells that are one cell cut in two by its seeds: pairs whose
/// contact runs at least [`JOIN_CONTACT`] of the thinner one's width, with the score
/// along it at least [`JOIN_SHARE`] of the weaker core's (a seam between two cells —
/// phase contrast's bright line, fluorescence's dark valley — lowers it) or with a
/// union that is one round convex body ([`JOIN_SOLIDITY`]); or pairs whose union is one
/// straight rod ([`JOIN_ROD_SOLIDITY`]), the only rule under [`Join::Rods`]. Returns,
/// per label (index = label), the label it joins (itself when none), joined
/// transitively.
pub fn joins(labels: &[u32], model: &ImageModel, rule: Join) -> Vec<u32> {
    let (w, h) = model.size();
    let n = labels.iter().copied().max().unwrap_or(0) as usize;
    let mut root: Vec<u32> = (0..=n as u32).collect();
    if labels.len() != w * h {
        return root;
    }
    for (members, b) in groups(labels, w, h) {
        let cells = Cells::new(labels, model, &members, b);
        // Per label, its core's mean score; per pair, the contact's sum and pixels.
        let core = cells.core_means();
        let mut pairs: std::collections::BTreeMap<(u32, u32), (f64, usize)> = Default::default();
        for (i, j) in contacts(&cells.labels, cells.w, cells.h) {
            let (a, b) = (cells.labels[i], cells.labels[j]);
            let e = pairs.entry((a.min(b), a.max(b))).or_default();
            e.0 += 0.5 * (cells.score.data[i] + cells.score.data[j]) as f64;
            e.1 += 1;
        }
        for ((a, b), (sum, count)) in pairs {
            let (Some(ca), Some(cb)) = (core.get(&a), core.get(&b)) else {
                continue;
            };
            let weaker = ca.min(*cb);
            let share = if weaker > 0.0 {
                sum / count as f64 / weaker
            } else {
                0.0
            };
            let contact = count as f64 / cells.thinner(a, b);
            let one = (rule == Join::Any
                && contact >= JOIN_CONTACT
                && (share >= JOIN_SHARE || cells.one_body(a, b)))
                || (contact >= JOIN_ROD_CONTACT && share >= JOIN_ROD_SHARE && cells.one_rod(a, b));
            if one {
                let (ra, rb) = (find(&mut root, a), find(&mut root, b));
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
    if !joined.iter().any(|&j| j) {
        return Vec::new();
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

/// Sisters `a` and `b` of the label raster `labels` (the model's size), born apart the
/// frame before, that are one cell again: they meet, directly or across a gap of at
/// most [`REJOIN_GAP`] pixels (two fronts held apart by the tracking policy leave a
/// pixel or so between their rasters), along at least [`REJOIN_CONTACT`] of the thinner
/// one's width, with object between them (the score where they meet at least
/// [`REJOIN_SHARE`] of the weaker core's). Returns the outline of their union with the
/// gap between.
pub fn rejoined(labels: &[u32], a: u32, b: u32, model: &ImageModel) -> Option<Vec<Point>> {
    let mut cells = pair_window(labels, a, b, model)?;
    let (w, h) = (cells.w, cells.h);
    let core = cells.core_means();
    let weaker = core.get(&a)?.min(*core.get(&b)?);
    let thinner = cells.thinner(a, b);
    // Where they meet: the pixels of each run from one to the other and the gap between.
    let view = model.level(0);
    let (fw, _) = model.size();
    let frame_index = |i: usize| (cells.origin.1 + i / w) * fw + cells.origin.0 + i % w;
    let mut bridge: Vec<usize> = Vec::new();
    let (mut runs, mut sum, mut n) = (0usize, 0.0, 0usize);
    meeting_runs(&cells.labels, w, h, [a, b], |ends, gap| {
        runs += 1;
        for &p in gap.iter().chain(ends.iter()) {
            sum += view.pixel_score(frame_index(p));
            n += 1;
        }
        bridge.extend_from_slice(gap);
    });
    if runs == 0 || weaker <= 0.0 {
        return None;
    }
    let seamless = sum / n as f64 >= REJOIN_SHARE * weaker;
    // Runs are counted along rows and columns both; a contact as long as the thinner
    // width gives about that many of one kind.
    if !(seamless && runs as f64 >= REJOIN_CONTACT * thinner) {
        return None;
    }
    cells.union_across(a, b, &bridge)
}

/// The outline of cells `a` and `b` of the label raster `labels` (the model's size) as
/// one cell, the gaps of at most [`REJOIN_GAP`] pixels where they meet filled; `None`
/// when they do not meet. Whatever the image shows between them: the caller has judged
/// them one cell ([`crate::track::Tracker`]: a rod too young to divide).
pub fn united(labels: &[u32], a: u32, b: u32, model: &ImageModel) -> Option<Vec<Point>> {
    let mut cells = pair_window(labels, a, b, model)?;
    let (w, h) = (cells.w, cells.h);
    let mut bridge: Vec<usize> = Vec::new();
    let mut runs = 0usize;
    meeting_runs(&cells.labels, w, h, [a, b], |_, gap| {
        runs += 1;
        bridge.extend_from_slice(gap);
    });
    if runs == 0 {
        return None;
    }
    cells.union_across(a, b, &bridge)
}

/// The window of `labels` (the model's size) that holds cells `a` and `b`.
fn pair_window(labels: &[u32], a: u32, b: u32, model: &ImageModel) -> Option<Cells> {
    let (fw, fh) = model.size();
    if labels.len() != fw * fh || a == b {
        return None;
    }
    let mut bx = [usize::MAX, usize::MAX, 0, 0];
    for (i, &l) in labels.iter().enumerate() {
        if l == a || l == b {
            let (x, y) = (i % fw, i / fw);
            bx = [bx[0].min(x), bx[1].min(y), bx[2].max(x), bx[3].max(y)];
        }
    }
    if bx[0] == usize::MAX {
        return None;
    }
    Some(Cells::new(labels, model, &[a.min(b), a.max(b)], bx))
}

/// Whether cells `pair` of the label raster `labels` (`w`×`h`) meet: a pixel of one
/// lies within [`REJOIN_GAP`] + 1 pixels of one of the other (in any direction). Sisters
/// that do not were born apart, with background between them; a neck cut leaves a
/// pixel or two.
pub fn meet(labels: &[u32], w: usize, h: usize, [a, b]: [u32; 2]) -> bool {
    let r = REJOIN_GAP as isize + 1;
    labels.iter().enumerate().any(|(i, &l)| {
        l == a && {
            let (x, y) = ((i % w) as isize, (i / w) as isize);
            (-r..=r).any(|dy| {
                (-r..=r).any(|dx| {
                    let (xx, yy) = (x + dx, y + dy);
                    dx * dx + dy * dy <= r * r
                        && (0..w as isize).contains(&xx)
                        && (0..h as isize).contains(&yy)
                        && labels[yy as usize * w + xx as usize] == b
                })
            })
        }
    })
}

/// Calls `visit(ends, gap)` for each run along a row or a column from a pixel of one of
/// `pair` to a pixel of the other across at most [`REJOIN_GAP`] empty pixels: `ends`
/// the two cells' pixels, `gap` the empty ones between.
fn meeting_runs(
    labels: &[u32],
    w: usize,
    h: usize,
    [a, b]: [u32; 2],
    mut visit: impl FnMut([usize; 2], &[usize]),
) {
    let mut gap = Vec::with_capacity(REJOIN_GAP);
    for (i, &l) in labels.iter().enumerate() {
        let other = match l {
            l if l == a => b,
            l if l == b => a,
            _ => continue,
        };
        let (x, y) = (i % w, i / w);
        for (dx, dy) in [(1, 0), (0, 1)] {
            gap.clear();
            for k in 1..=REJOIN_GAP + 1 {
                let (xx, yy) = (x + k * dx, y + k * dy);
                if xx >= w || yy >= h {
                    break;
                }
                let j = yy * w + xx;
                match labels[j] {
                    0 => gap.push(j),
                    m if m == other => {
                        visit([i, j], &gap);
                        break;
                    }
                    _ => break,
                }
            }
        }
    }
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
    fn a_cell_too_thin_for_a_core_keeps_its_pixels() {
        // Column 38 is a cell one pixel wide between two others: it has no core, keeps
        // its ring, and its pixels are not flooded by its neighbours.
        let labels: Vec<u32> = divided(38)
            .iter()
            .enumerate()
            .map(|(i, &l)| if l != 0 && i % 80 == 38 { 3 } else { l })
            .collect();
        let new = repartition(&labels, &block(1.0));
        assert_eq!(new.iter().map(|r| r.0).collect::<Vec<_>>(), [1, 2]);
        let right_of_one = right_end(&new[0].1);
        assert!(right_of_one < 38.0, "{right_of_one}");
        let left_of_two = new[1].1.iter().map(|p| p.x).fold(f64::MAX, f64::min);
        assert!(left_of_two > 38.0, "{left_of_two}");
    }

    #[test]
    fn a_cell_cut_in_two_without_a_seam_is_joined_and_two_with_one_are_not() {
        let labels = divided(40);
        assert_eq!(joins(&labels, &block(1.0), Join::Any), [0, 1, 1]);
        let rings = joined_rings(&labels, &[0, 1, 1], &block(1.0));
        assert_eq!(rings.len(), 1);
        let area = crate::geometry::signed_area(&rings[0].1);
        assert!(area > 700.0 && area <= 800.0, "{area}");
        let labels = divided(34);
        assert_eq!(joins(&labels, &block(0.3), Join::Any), [0, 1, 2]);
    }

    /// Bright disks (centre x, radius) at y = 30 on a dark ground, darker (0.5) along
    /// column `dark`; labels: the disks' pixels, 1 left of column `cut` and 2 from it.
    fn disks(d: &[(f64, f64)], dark: usize, cut: usize) -> (ImageModel, Vec<u32>) {
        let (w, h) = (90, 60);
        let on = |x: usize, y: usize| {
            let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
            d.iter().any(|&(cx, r)| p.dist(Point::new(cx, 30.0)) <= r)
        };
        let data = (0..w * h)
            .map(|i| match (i % w, on(i % w, i / w)) {
                (_, false) => 0.2,
                (x, true) if x == dark => 0.5,
                _ => 1.0,
            })
            .collect();
        let labels = (0..w * h)
            .map(|i| match on(i % w, i / w) {
                false => 0,
                true => 1 + (i % w >= cut) as u32,
            })
            .collect();
        let params = ModelParams::seeds(Polarity::Bright, Modality::Fluorescence);
        (
            ImageModel::prepare(&Field::new(w, h, data), &params, &[]),
            labels,
        )
    }

    #[test]
    fn a_round_body_cut_along_a_darker_band_is_joined_and_two_pressed_disks_are_not() {
        // One nucleus cut where its nucleoli run darker: the band reads as a seam, but
        // the union is round and convex.
        let (model, labels) = disks(&[(40.0, 16.0)], 40, 40);
        assert_eq!(joins(&labels, &model, Join::Any), [0, 1, 1]);
        // New cells on later frames join rods only.
        assert_eq!(joins(&labels, &model, Join::Rods), [0, 1, 2]);
        // Two disks pressed 0.83 radii into each other, the same band along their
        // contact: as convex, but elongated: two cells.
        let (model, labels) = disks(&[(30.0, 12.0), (44.0, 12.0)], 37, 37);
        assert_eq!(joins(&labels, &model, Join::Any), [0, 1, 2]);
    }

    /// A segment's two ends.
    type Segment = ((f64, f64), (f64, f64));

    /// Capsules of radius `r` around segments on a dark ground, bright inside, and
    /// `seam` bright where two capsules meet; labels: each pixel the first capsule it
    /// lies in.
    fn capsules(c: &[Segment], r: f64, seam: f32) -> (ImageModel, Vec<u32>) {
        let (w, h) = (90, 70);
        let dist = |p: Point, ((x0, y0), (x1, y1)): Segment| {
            let (a, b) = (Point::new(x0, y0), Point::new(x1, y1));
            let d = b - a;
            let t = (((p - a).x * d.x + (p - a).y * d.y) / (d.x * d.x + d.y * d.y)).clamp(0.0, 1.0);
            p.dist(a + d * t)
        };
        let at = |i: usize| Point::new((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let labels: Vec<u32> = (0..w * h)
            .map(|i| {
                c.iter()
                    .position(|&s| dist(at(i), s) <= r)
                    .map_or(0, |k| k as u32 + 1)
            })
            .collect();
        let data = (0..w * h)
            .map(
                |i| match c.iter().filter(|&&s| dist(at(i), s) <= r + 1.0).count() {
                    _ if labels[i] == 0 => 0.2,
                    2.. => seam,
                    _ => 1.0,
                },
            )
            .collect();
        let params = ModelParams::seeds(Polarity::Bright, Modality::Fluorescence);
        (
            ImageModel::prepare(&Field::new(w, h, data), &params, &[]),
            labels,
        )
    }

    #[test]
    fn a_straight_rod_cut_by_its_seeds_on_a_short_contact_is_joined_and_two_rods_at_an_angle_are_not(
    ) {
        // One rod whose two seeds' fronts met rounded: the contact runs 0.71 of its
        // width, under JOIN_CONTACT, and the union is one straight rod.
        let rod = [((14.0, 35.0), (38.0, 35.0)), ((52.5, 35.0), (76.0, 35.0))];
        let (model, labels) = capsules(&rod, 8.0, 1.0);
        assert_eq!(joins(&labels, &model, Join::Any), [0, 1, 1]);
        assert_eq!(joins(&labels, &model, Join::Rods), [0, 1, 1]);
        // A seam as dark as the ground between them: two rods end to end.
        let (model, labels) = capsules(&rod, 8.0, 0.2);
        assert_eq!(joins(&labels, &model, Join::Any), [0, 1, 2]);
        // Two rods meeting end to end at a right angle: as short a contact (0.64) and no
        // seam, but their union leaves a notch its hull fills (0.75 of it).
        let bent = [((14.0, 35.0), (38.0, 35.0)), ((53.0, 35.0), (53.0, 60.0))];
        let (model, labels) = capsules(&bent, 8.0, 1.0);
        assert_eq!(joins(&labels, &model, Join::Any), [0, 1, 2]);
    }

    #[test]
    fn join_pieces_returns_the_outlines_it_joined() {
        // Two halves of the block, one shape each (seeds cut it in two).
        let half = |x0: f64, x1: f64| {
            object(vec![
                Point::new(x0, 20.5),
                Point::new(x1, 20.5),
                Point::new(x1, 39.5),
                Point::new(x0, 39.5),
            ])
        };
        let pieces = || vec![vec![half(20.5, 33.9)], vec![half(34.1, 59.5)]];
        let mut p = pieces();
        let joined = join_pieces(&mut p, &block(1.0), Join::Any);
        assert_eq!(joined.len(), 1);
        assert_eq!(p[0][0].ring, joined[0]);
        assert!(p[1].is_empty());
        // With a seam between them they stay two, and nothing is returned.
        let mut p = pieces();
        assert!(join_pieces(&mut p, &block(0.3), Join::Any).is_empty());
        assert_eq!((p[0].len(), p[1].len()), (1, 1));
    }

    #[test]
    fn cells_meet_across_a_gap_of_up_to_three_pixels_in_any_direction() {
        let (w, h) = (20, 20);
        // A pixel of 1 at (5, 5) and of 2 at (5 + dx, 5 + dy).
        let meets = |dx: usize, dy: usize| {
            let mut l = vec![0u32; w * h];
            l[5 * w + 5] = 1;
            l[(5 + dy) * w + 5 + dx] = 2;
            meet(&l, w, h, [1, 2])
        };
        assert!(meets(1, 0));
        assert!(meets(4, 0));
        assert!(!meets(5, 0));
        assert!(meets(2, 2));
        assert!(!meets(3, 3));
        assert!(meets(0, 4));
    }
}
