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
//! where the line between them falls is not decided by which front gets there first.
//! Seeds thinner than [`BASIN_PEAK`] (specks of a textured nucleus) and basins of fewer
//! than nine pixels get a disk of half the peak's distance instead: as basins, the specks
//! of textured dim nuclei stayed fragments held apart (`docs/decisions.md`).
//!
//! Nuclei side by side along their short axes make a union whose distance transform
//! peaks once, at the contact: no persistence splits them. Their basins are then cut at
//! the notches of their outline when the parts are good ellipses ([`super::declump`]).
//! A basin's outline drops pixels that meet the rest only at a corner, so the ring never
//! passes a corner twice: such a ring touches itself, the contour set refuses it, and
//! the seed was lost.
//!
//! In phase contrast the mask keeps only pixels ¾ of a local contrast past the level
//! ([`CORE_PHASE`]): touching cells are separated there by grey gaps that read as
//! object at the level itself.

use super::declump;
use super::distance::distance_transform;
use super::field::{neighbours4, Field};
use super::intensity::Polarity;
use super::maxima::persistent_maxima;
use super::modality::Modality;
use super::model::{ImageModel, ModelParams};
use super::outline::basin_outline;
use crate::geometry::Point;
use crate::shape::Shape;

/// Smallest height of a maximum above the neck that joins it to a higher one, for both
/// to be seeds, in object radii (the necks between touching nuclei deepen with their
/// size; `docs/decisions.md`).
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
/// The image is prepared as for an evolution without shapes ([`ImageModel::prepare`]
/// with [`ModelParams::seeds`]), so the seeds see the mask the evolution will see.
pub fn find_seeds(image: &Field, polarity: Polarity, modality: Modality) -> Vec<Shape> {
    let params = ModelParams::seeds(polarity, modality);
    seeds_of(&ImageModel::prepare(image, &params, &[]))
}

/// One seed per object of the prepared `image`, from its full-resolution level and
/// local decision level (none without local levels).
fn seeds_of(image: &ImageModel) -> Vec<Shape> {
    let (Some(radius), Some(level)) = (image.radius(), image.decision(0)) else {
        return Vec::new();
    };
    let (fine, model, modality) = (image.fine(), image.global(), image.params().modality);
    let r = radius.round() as usize;
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
