//! Automatic seeds: one seed per object, placed as ordinary shapes (a user can then move,
//! delete or add some).
//!
//! The objects are the pixels on the object side of the local decision level of
//! [`super::local`] (phase contrast with its halo clipped). Touching objects join in that
//! mask, but each keeps a maximum of the distance to the background at its centre, and
//! the neck between two of them is narrower. The seeds are the maxima of the (lightly
//! smoothed) Euclidean distance transform that persist: pixels are added in decreasing
//! distance, a union-find joins them into components, and when two components meet at
//! level v the one with the lower peak p ends there; its peak is a seed if p − v ≥
//! [`PERSISTENCE`] object radii (the 0-dimensional persistence of the maximum), else it was a
//! bump on a ridge. Every component's highest peak is a seed. This is the marker step of
//! a distance-transform watershed, the classical way to split touching nuclei; we chose
//! it over multi-scale Laplacian-of-Gaussian blobs because it needs no list of scales
//! and follows the mask the evolution will see. Long rods (bacteria) have a flat ridge
//! and get one seed; two rods touching end to end get one at their junction when the
//! neck is as wide as the rods.
//!
//! Each seed's shape is its basin of that watershed (pixels flooded from the peaks in
//! decreasing distance), less the pixels touching another basin, outlined and simplified
//! (Douglas–Peucker, 0.75 px): touching objects start already divided at their neck, so
//! where the line between them falls is not decided by which front gets there first
//! (on the phase-contrast bacteria of `ecoli_phase_early` that moved SEG from 0.65 to
//! 0.76 in the instance run). Seeds thinner than [`BASIN_PEAK`] (specks of a textured
//! nucleus) and basins of fewer than nine pixels get a disk of half the peak's distance
//! instead: as basins, the specks of textured dim nuclei stayed fragments held apart
//! (mahotas_nuclear: 126 objects with basins for every seed, 113 from a 3 px peak, 90
//! from 4 px, 94 with disks only; dsb2018 SEG 0.694 / 0.681 / 0.694 / 0.687).
//!
//! Nuclei side by side along their short axes make a union whose distance transform
//! peaks once, at the contact: no persistence splits them. Their basins are then cut at
//! the notches of their outline when the parts are good ellipses ([`super::declump`]).
//! A basin's outline drops pixels that meet the rest only at a corner, so the ring never
//! passes a corner twice: such a ring touches itself, the contour set refuses it, and
//! the seed was lost (one nucleus on dsb2018_nuclei, three on mahotas_nuclear).
//!
//! In phase contrast the mask keeps only pixels ¾ of a local contrast past the level
//! ([`CORE_PHASE`]): touching cells are separated there by grey gaps that read as
//! object at the level itself.

use super::declump;
use super::field::{neighbours4, neighbours8, Field, Pyramid};
use super::forces::{IntensityModel, Polarity};
use super::init::Shape;
use super::local::{self, Modality};
use crate::geometry::Point;

/// Smallest height of a maximum above the neck that joins it to a higher one, for both
/// to be seeds, in object radii (the necks between touching nuclei deepen with their
/// size). On the public fluorescence case (r = 11 px) 1/16 r = 0.7 px: instance SEG
/// 0.755 at 1 px → 0.769; 1/12 and 1/20 of r measured 0.760 and 0.768.
pub const PERSISTENCE: f32 = 1.0 / 16.0;

/// Smallest distance to the background at a seed (pixels): thinner specks are noise.
pub const MIN_PEAK: f32 = 1.5;

/// Smallest distance to the background at a seed (pixels) for its basin to be its shape:
/// thinner seeds (specks of a textured nucleus) stay small disks, which the evolution
/// joins or lets vanish, instead of fragments held apart.
pub const BASIN_PEAK: f32 = 4.0;

/// In phase contrast, how far past the level (in local half contrasts) a pixel must be
/// to count for the seeds.
pub const CORE_PHASE: f64 = 0.75;

/// One seed per object found in `image`: its watershed basin (or a disk, for a tiny one).
pub fn find_seeds(image: &Field, polarity: Polarity, modality: Modality) -> Vec<Shape> {
    let image = local::for_modality(image, polarity, modality, None);
    let fine = Pyramid::new(&image, usize::MAX, 1).levels.remove(0).image;
    let model = IntensityModel::learn(&fine, polarity, None, None);
    let r = local::object_scale(&fine, &model).round() as usize;
    let rule = local::LevelRule::new(&fine, &model, modality);
    let level = local::decision_field(&fine, r, &model, &rule);
    let bright = model.object >= model.background;
    let sign = if bright { 1.0 } else { -1.0 };
    // Phase contrast: only the cells' cores, well past the level, so the blurred gaps
    // between touching cells (grey, halfway to the halo) separate them.
    let core = if modality == Modality::PhaseContrast {
        CORE_PHASE
    } else {
        0.0
    };
    let mask: Vec<bool> = fine
        .data
        .iter()
        .zip(&level.level.data)
        .zip(&level.half.data)
        .map(|((&v, &t), &h)| sign * (v - t) as f64 > core * h as f64)
        .collect();
    let dist = distance_transform(&mask, fine.width, fine.height);
    let smooth = dist.blur(&[0.25, 0.5, 0.25]).blur(&[0.25, 0.5, 0.25]);
    let height: Vec<f32> = smooth
        .data
        .iter()
        .zip(&mask)
        .map(|(&d, &m)| if m { d } else { 0.0 })
        .collect();
    let (w, h) = (fine.width, fine.height);
    let mut peaks: Vec<usize> = persistent_maxima(&height, w, h, PERSISTENCE * r as f32)
        .into_iter()
        .filter(|&i| dist.data[i] >= MIN_PEAK)
        .collect();
    // Each seed's basin of the distance watershed, one pixel in from its neighbours, as
    // the seed's shape: touching objects start already divided where their neck is, so
    // which front reaches a contact first no longer decides where the line between them
    // falls. A basin too small for a ring keeps the disk.
    let mut labels = basins(&height, &peaks, w, h);
    declump::split_basins(&mut labels, &mut peaks, &dist.data, (w, h), r as f64, |i| {
        dist.data[i] >= BASIN_PEAK
    });
    peaks
        .iter()
        .enumerate()
        .map(|(k, &i)| {
            let centre = Point::new((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
            let disk = Shape::Disk {
                center: centre,
                radius: (0.5 * dist.data[i] as f64).max(1.0),
            };
            if dist.data[i] < BASIN_PEAK {
                return disk;
            }
            match basin_outline(&labels, k as u32 + 1, i, w, h) {
                Some(ring) => Shape::Polygon(ring),
                None => disk,
            }
        })
        .collect()
}

/// Labels 1..=n of the watershed basins of `height` (> 0 on the mask) flooded from the
/// `peaks`, highest first, over 4-neighbours; 0 off the mask or unreached.
fn basins(height: &[f32], peaks: &[usize], w: usize, h: usize) -> Vec<u32> {
    use std::collections::BinaryHeap;
    let mut label = vec![0u32; w * h];
    let mut heap = BinaryHeap::new();
    for (k, &i) in peaks.iter().enumerate() {
        label[i] = k as u32 + 1;
        heap.push((height[i].to_bits(), i));
    }
    // Heights are non-negative: their bits order like the values.
    while let Some((_, i)) = heap.pop() {
        for j in neighbours4(i, w, h) {
            if label[j] == 0 && height[j] > 0.0 {
                label[j] = label[i];
                heap.push((height[j].to_bits(), j));
            }
        }
    }
    label
}

/// The outline (pixel corners, region on one side) of the 4-connected part of basin `l`
/// that holds pixel `at`, after removing its pixels that touch another basin, so
/// neighbouring outlines keep a gap. `None` if fewer than 9 pixels remain.
fn basin_outline(labels: &[u32], l: u32, at: usize, w: usize, h: usize) -> Option<Vec<Point>> {
    let get = |x: isize, y: isize| -> u32 {
        if x < 0 || y < 0 || x >= w as isize || y >= h as isize {
            0
        } else {
            labels[y as usize * w + x as usize]
        }
    };
    let keep = |x: isize, y: isize| {
        get(x, y) == l
            && [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (1, -1),
                (-1, 1),
                (-1, -1),
            ]
            .iter()
            .all(|&(dx, dy)| matches!(get(x + dx, y + dy), 0) || get(x + dx, y + dy) == l)
    };
    // The 4-connected part holding the peak, and its top-left pixel.
    let (ax, ay) = ((at % w) as isize, (at / w) as isize);
    if !keep(ax, ay) {
        return None;
    }
    let part = |kept: &dyn Fn(isize, isize) -> bool| {
        let mut inside = std::collections::HashSet::new();
        let mut stack = vec![(ax, ay)];
        inside.insert((ax, ay));
        while let Some((x, y)) = stack.pop() {
            for (nx, ny) in [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)] {
                if !inside.contains(&(nx, ny)) && kept(nx, ny) {
                    inside.insert((nx, ny));
                    stack.push((nx, ny));
                }
            }
        }
        inside
    };
    let mut inside = part(&keep);
    // Two pixels meeting only at a corner would make the outline pass that corner twice
    // (a ring touching itself, which the contour set refuses): drop one of each such
    // pair until none is left, then keep the peak's part.
    loop {
        let pinched: Vec<(isize, isize)> = inside
            .iter()
            .copied()
            .filter(|&(x, y)| {
                [(1, 1), (1, -1)].iter().any(|&(dx, dy)| {
                    inside.contains(&(x + dx, y + dy))
                        && !inside.contains(&(x + dx, y))
                        && !inside.contains(&(x, y + dy))
                })
            })
            .filter(|&p| p != (ax, ay))
            .collect();
        if pinched.is_empty() {
            break;
        }
        let kept: std::collections::HashSet<_> = inside
            .iter()
            .copied()
            .filter(|p| !pinched.contains(p))
            .collect();
        inside = part(&|x, y| kept.contains(&(x, y)));
    }
    if inside.len() < 9 {
        return None;
    }
    let &(sx, sy) = inside.iter().min_by_key(|&&(x, y)| (y, x))?;
    let is_in = |x: isize, y: isize| inside.contains(&(x, y));
    // Crack following with the region on the right: at corner (vx, vy) heading d, the
    // pixels ahead on the left and right decide: right one out → turn right, left one
    // in → turn left, else straight. Directions E, S, W, N (y down), clockwise.
    const D: [(isize, isize); 4] = [(1, 0), (0, 1), (-1, 0), (0, -1)];
    let ahead = |vx: isize, vy: isize, d: usize| match d {
        0 => ((vx, vy - 1), (vx, vy)),
        1 => ((vx, vy), (vx - 1, vy)),
        2 => ((vx - 1, vy), (vx - 1, vy - 1)),
        _ => ((vx - 1, vy - 1), (vx, vy - 1)),
    };
    // The top-left corner of the top-left pixel is a corner where the walk turns from
    // north to east: it starts and ends there.
    let (mut vx, mut vy, mut d) = (sx, sy, 0usize);
    let mut ring = vec![Point::new(sx as f64, sy as f64)];
    for _ in 0..8 * inside.len() + 8 {
        let ((lx, ly), (rx, ry)) = ahead(vx, vy, d);
        let nd = if !is_in(rx, ry) {
            (d + 1) % 4
        } else if is_in(lx, ly) {
            (d + 3) % 4
        } else {
            d
        };
        if nd != d {
            if (vx, vy) == (sx, sy) && nd == 0 {
                // Simplifying a narrow part can make it cross itself: keep the staircase.
                let simple = simplify(&ring, 0.75);
                let ring = if is_simple(&simple) { simple } else { ring };
                return (ring.len() >= 4).then_some(ring);
            }
            ring.push(Point::new(vx as f64, vy as f64));
            d = nd;
            continue;
        }
        vx += D[d].0;
        vy += D[d].1;
    }
    None
}

/// Whether the closed ring's edges meet only where neighbours share a corner.
fn is_simple(ring: &[Point]) -> bool {
    use crate::geometry::{segment_intersection, SegmentIntersection};
    let n = ring.len();
    let edge = |i: usize| (ring[i], ring[(i + 1) % n]);
    (0..n).all(|i| {
        (i + 1..n).all(|j| {
            let ((a0, a1), (b0, b1)) = (edge(i), edge(j));
            match segment_intersection(a0, a1, b0, b1) {
                SegmentIntersection::None => true,
                SegmentIntersection::Overlap => false,
                _ => j == i + 1 || (i == 0 && j == n - 1),
            }
        })
    })
}

/// Douglas–Peucker on a closed ring: corners within `tol` of the chord between kept
/// ones are dropped (a staircase outline becomes its diagonals).
fn simplify(ring: &[Point], tol: f64) -> Vec<Point> {
    let n = ring.len();
    if n < 5 {
        return ring.to_vec();
    }
    // Split at the corner farthest from the first, then simplify both chains.
    let far = (1..n)
        .max_by(|&a, &b| ring[0].dist(ring[a]).total_cmp(&ring[0].dist(ring[b])))
        .unwrap_or(n / 2);
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[far] = true;
    let mut stack = vec![(0, far), (far, n)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (ring[a], ring[b % n]);
        let worst = (a + 1..b)
            .map(|i| (i, crate::geometry::point_segment_distance(ring[i], p, q)))
            .max_by(|x, y| x.1.total_cmp(&y.1));
        if let Some((i, d)) = worst {
            if d > tol {
                keep[i] = true;
                stack.extend([(a, i), (i, b)]);
            }
        }
    }
    ring.iter()
        .zip(&keep)
        .filter(|(_, &k)| k)
        .map(|(&p, _)| p)
        .collect()
}

/// Euclidean distance from each pixel of `mask` to the nearest pixel outside it (0
/// outside; the image border counts as inside, so objects cut by it keep their centre),
/// by Felzenszwalb and Huttenlocher's lower envelope of parabolas, one axis at a time.
pub fn distance_transform(mask: &[bool], w: usize, h: usize) -> Field {
    const FAR: f32 = 1e12;
    let mut sq: Vec<f32> = mask.iter().map(|&m| if m { FAR } else { 0.0 }).collect();
    let mut line = Vec::new();
    let mut out = Vec::new();
    for x in 0..w {
        line.clear();
        line.extend((0..h).map(|y| sq[y * w + x]));
        envelope(&line, &mut out);
        for y in 0..h {
            sq[y * w + x] = out[y];
        }
    }
    for y in 0..h {
        line.clear();
        line.extend_from_slice(&sq[y * w..(y + 1) * w]);
        envelope(&line, &mut out);
        sq[y * w..(y + 1) * w].copy_from_slice(&out);
    }
    // A mask with no background anywhere: distances to nothing, clamp to the image size.
    let cap = (w.max(h) as f32).powi(2);
    Field::new(w, h, sq.into_iter().map(|d| d.min(cap).sqrt()).collect())
}

/// The 1-D squared distance transform of `f` (the lower envelope of the parabolas
/// (q − i)² + f(i)).
fn envelope(f: &[f32], out: &mut Vec<f32>) {
    let n = f.len();
    out.clear();
    out.resize(n, 0.0);
    let mut v = vec![0usize; n];
    let mut z = vec![0f32; n + 1];
    let mut k = 0;
    z[0] = f32::NEG_INFINITY;
    z[1] = f32::INFINITY;
    let meet = |q: usize, p: usize| {
        let (q2, p2) = ((q * q) as f32, (p * p) as f32);
        ((f[q] + q2) - (f[p] + p2)) / (2.0 * (q as f32 - p as f32))
    };
    for q in 1..n {
        let mut s = meet(q, v[k]);
        while s <= z[k] {
            k -= 1;
            s = meet(q, v[k]);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f32::INFINITY;
    }
    k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f32 {
            k += 1;
        }
        let d = q as f32 - v[k] as f32;
        *o = d * d + f[v[k]];
    }
}

/// Pixels (indices) of the maxima of `height` over its positive pixels whose persistence
/// is at least `min_persistence`, 8-connected; each component's highest maximum always.
pub fn persistent_maxima(height: &[f32], w: usize, h: usize, min_persistence: f32) -> Vec<usize> {
    const NONE: u32 = u32::MAX;
    let mut order: Vec<u32> = (0..height.len() as u32)
        .filter(|&i| height[i as usize] > 0.0)
        .collect();
    order.sort_unstable_by(|&a, &b| {
        height[b as usize]
            .total_cmp(&height[a as usize])
            .then(a.cmp(&b))
    });
    let mut parent = vec![NONE; height.len()];
    let mut peak = vec![NONE; height.len()];
    fn find(parent: &mut [u32], mut x: u32) -> u32 {
        while parent[x as usize] != x {
            let up = parent[parent[x as usize] as usize];
            parent[x as usize] = up;
            x = up;
        }
        x
    }
    let mut seeds = Vec::new();
    for &p in &order {
        parent[p as usize] = p;
        peak[p as usize] = p;
        for q in neighbours8(p as usize, w, h) {
            let q = q as u32;
            if parent[q as usize] == NONE {
                continue;
            }
            let (mut a, mut b) = (find(&mut parent, p), find(&mut parent, q));
            if a == b {
                continue;
            }
            let (ha, hb) = (
                height[peak[a as usize] as usize],
                height[peak[b as usize] as usize],
            );
            if ha < hb {
                std::mem::swap(&mut a, &mut b);
            }
            // b's maximum ends here, at the level of the pixel that joins them.
            let pb = peak[b as usize];
            if height[pb as usize] - height[p as usize] >= min_persistence {
                seeds.push(pb as usize);
            }
            parent[b as usize] = a;
        }
    }
    for &p in &order {
        if find(&mut parent, p) == p {
            seeds.push(peak[p as usize] as usize);
        }
    }
    seeds.sort_unstable();
    seeds
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_transform_equals_brute_force() {
        let (w, h) = (13, 9);
        let mask: Vec<bool> = (0..w * h).map(|i| (i * 7919) % 5 != 0).collect();
        let d = distance_transform(&mask, w, h);
        for i in 0..w * h {
            let (x, y) = ((i % w) as f64, (i / w) as f64);
            let mut best = f64::INFINITY;
            for j in (0..w * h).filter(|&j| !mask[j]) {
                let (u, v) = ((j % w) as f64, (j / w) as f64);
                best = best.min((x - u).hypot(y - v));
            }
            assert!(
                (d.data[i] as f64 - best).abs() < 1e-4,
                "{i}: {} vs {best}",
                d.data[i]
            );
        }
    }

    #[test]
    fn two_peaks_persist_and_a_bump_does_not() {
        // Heights along a line: peaks 5 and 4 joined at 2 (persistence 2), then a bump of
        // 0.5 on the slope.
        let hgt = [1.0, 3.0, 5.0, 3.0, 2.0, 3.0, 4.0, 3.0, 2.5, 3.0, 1.0];
        let s = persistent_maxima(&hgt, hgt.len(), 1, 1.0);
        assert_eq!(s, vec![2, 6]);
    }

    #[test]
    fn a_basin_pinched_at_a_corner_still_outlines_a_simple_ring() {
        // Two blocks meeting only at a corner and joined round the side: the raw outline
        // passes the shared corner twice.
        let rows = [
            "............",
            ".####.......",
            ".####.......",
            ".####.......",
            ".####.......",
            ".##..####...",
            ".##..####...",
            ".##..####...",
            ".########...",
            ".########...",
            "............",
        ];
        let (w, h) = (rows[0].len(), rows.len());
        let labels: Vec<u32> = rows
            .iter()
            .flat_map(|r| r.bytes().map(|b| u32::from(b == b'#')))
            .collect();
        let ring = basin_outline(&labels, 1, 2 * w + 2, w, h).expect("a ring");
        assert!(is_simple(&ring));
        let area = crate::geometry::signed_area(&ring).abs();
        assert!((30.0..=50.0).contains(&area), "{area}");
    }

    #[test]
    fn rings_that_touch_or_cross_themselves_are_not_simple() {
        let p = |x, y| Point::new(x, y);
        assert!(is_simple(&[
            p(0.0, 0.0),
            p(2.0, 0.0),
            p(2.0, 2.0),
            p(0.0, 2.0)
        ]));
        let bowtie = [p(0.0, 0.0), p(2.0, 2.0), p(2.0, 0.0), p(0.0, 2.0)];
        assert!(!is_simple(&bowtie));
        // Two squares sharing the corner (1, 1), walked as one ring.
        let pinched = [
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(2.0, 1.0),
            p(2.0, 2.0),
            p(1.0, 2.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
        ];
        assert!(!is_simple(&pinched));
    }
}
