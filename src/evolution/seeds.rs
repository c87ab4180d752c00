//! Automatic seeds: one seed disk per object, placed as ordinary shapes (a user can then
//! move, delete or add some).
//!
//! The objects are the pixels on the object side of the local decision level of
//! [`super::local`] (phase contrast with its halo clipped). Touching objects join in that
//! mask, but each keeps a maximum of the distance to the background at its centre, and
//! the neck between two of them is narrower. The seeds are the maxima of the (lightly
//! smoothed) Euclidean distance transform that persist: pixels are added in decreasing
//! distance, a union-find joins them into components, and when two components meet at
//! level v the one with the lower peak p ends there; its peak is a seed if p − v ≥
//! [`PERSISTENCE`] pixels (the 0-dimensional persistence of the maximum), else it was a
//! bump on a ridge. Every component's highest peak is a seed. This is the marker step of
//! a distance-transform watershed, the classical way to split touching nuclei; we chose
//! it over multi-scale Laplacian-of-Gaussian blobs because it needs no list of scales
//! and follows the mask the evolution will see. Long rods (bacteria) have a flat ridge
//! and get one seed; two rods touching end to end get one at their junction when the
//! neck is as wide as the rods. A seed's radius is half the distance at its peak, so the
//! disk lies inside its object. In phase contrast the mask keeps only pixels ¾ of a
//! local contrast past the level ([`CORE_PHASE`]): touching cells are separated there
//! by grey gaps that read as object at the level itself.

use super::field::{Field, Pyramid};
use super::forces::{IntensityModel, Polarity};
use super::init::Shape;
use super::local::{self, Modality};
use crate::geometry::Point;

/// Smallest height (pixels of distance) of a maximum above the neck that joins it to a
/// higher one, for both to be seeds.
pub const PERSISTENCE: f32 = 1.0;

/// Smallest distance to the background at a seed (pixels): thinner specks are noise.
pub const MIN_PEAK: f32 = 1.5;

/// In phase contrast, how far past the level (in local half contrasts) a pixel must be
/// to count for the seeds.
pub const CORE_PHASE: f64 = 0.75;

/// One seed disk per object found in `image`.
pub fn find_seeds(image: &Field, polarity: Polarity, modality: Modality) -> Vec<Shape> {
    let image = local::for_modality(image, polarity, modality, None);
    let fine = Pyramid::new(&image, usize::MAX, 1).levels.remove(0).image;
    let model = IntensityModel::learn(&fine, polarity, None, None);
    let r = local::object_scale(&fine, &model).round() as usize;
    let level = local::decision_field(&fine, r, &model, local::floor(&fine, &model, modality));
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
    persistent_maxima(&height, fine.width, fine.height, PERSISTENCE)
        .into_iter()
        .filter(|&i| dist.data[i] >= MIN_PEAK)
        .map(|i| Shape::Disk {
            center: Point::new((i % fine.width) as f64 + 0.5, (i / fine.width) as f64 + 0.5),
            radius: (0.5 * dist.data[i] as f64).max(1.0),
        })
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
        let (x, y) = ((p as usize % w) as i64, (p as usize / w) as i64);
        for (dx, dy) in [
            (-1, -1),
            (0, -1),
            (1, -1),
            (-1, 0),
            (1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ] {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let q = (ny as usize * w + nx as usize) as u32;
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
}
