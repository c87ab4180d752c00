//! A new cell must stand out from what is around it: a seed on a gentle illumination
//! gradient (the darker corner of an unevenly lit phase-contrast frame) settles into a
//! blob only a shade darker than its surroundings, which no real cell is. The measure is
//! the difference of means between the object and a band just outside it, in units of
//! their pooled standard deviation (a two-sample separation, as Cohen's d): new cells
//! and nuclei, textured or dim, stand at 2.4 or more on every movie measured; the
//! gradient blobs at 1.2 or less (docs/decisions.md). A carried track is judged against
//! the blobs' bound only ([`MIN_CARRIED_SEPARATION`]): a cell fading for a frame keeps its
//! track, and a blob that once passed (a speck at the frame's edge) does not grow over a
//! dark corner for the rest of the movie.
//!
//! In phase contrast a new cell must also be wrapped in its halo: the optics ring every
//! cell with light brighter than the background, while a dark band of uneven light, and
//! the noise blobs seeds settle into on it, have only darker ground around them. The
//! measure ([`halo`]) is the median of the ground a few pixels out against the frame's
//! background (the median of the ground no object covers), in units of the object's
//! own contrast. On a sparse real field the band (257,000 px, the two cells beside it
//! dropped as specks) and every blob on it read −0.45 or less; the outlines kept on
//! cells of two real movies and three synthetic ones −0.21 or more (docs/decisions.md,
//! 2026-12-07, ninth session).

use crate::geometry::Point;
use crate::image::hints::median;
use crate::image::{edges, Field, Polarity};
use crate::track::carry::label_raster;
use std::collections::HashSet;

/// Smallest separation (pooled standard deviations) of a new cell from its surroundings.
pub const MIN_SEPARATION: f64 = 1.8;

/// Smallest separation of a carried cell: the bound the gradient blobs stay under.
/// A blob that passed as a new cell (a speck at the frame's edge) grows over the dark
/// corner frame by frame (0.3–1.0 on bacteria 5); a fading cell keeps its track down to
/// here (real cells' least on every movie measured: 1.27, a 37 px sliver).
pub const MIN_CARRIED_SEPARATION: f64 = 1.2;

/// Least halo ([`halo`]) of a new cell in phase contrast.
pub const MIN_HALO: f64 = -0.3;

/// A carried cell whose area grew more than this many times in one frame is judged as
/// a new one: no cell doubles between two frames, while a blob that passed on a band of
/// uneven light spreads over it (a real sparse field: 574 px to 121,000 px in a frame).
pub const SPREAD: f64 = 2.0;

/// How many pixels out the band around an object starts and ends.
const BAND: [f64; 3] = [2.0, 3.0, 4.0];

/// How many pixels out the ground [`halo`] reads starts and ends: the halo of a real
/// E. coli movie spreads over ten pixels and more beyond the cell's edge.
const HALO_BAND: [f64; 11] = [2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0];

/// What an object must show to stand out ([`standing_out`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Need {
    /// Least separation from the band around it ([`separation`]).
    pub separation: f64,
    /// Least halo ([`halo`]), if one is asked for.
    pub halo: Option<f64>,
}

/// The separation of the object labelled `label` in `raster` (outline `ring`, region on
/// the left) from the band just outside it, not counting pixels of other objects;
/// `None` when either has too few pixels to say.
pub fn separation(
    ring: &[Point],
    label: u32,
    raster: &[u32],
    image: &Field,
    polarity: Polarity,
) -> Option<f64> {
    let (mi, vi, ni) = moments(inside(ring, label, raster, image));
    let (mo, vo, no) = moments(ground(ring, raster, image, &BAND));
    if ni < 5 || no < 5 {
        return None;
    }
    let d = match polarity {
        Polarity::Dark => mo - mi,
        Polarity::Bright => mi - mo,
    };
    Some(d / (0.5 * (vi + vo)).sqrt().max(1e-12))
}

/// The halo of the object labelled `label` in `raster` (outline `ring`): how far the
/// median of the ground 2–12 pixels out, not counting other objects, lies beyond the `background`
/// level on the side away from the object, as a share of the object's own contrast
/// (`background` − its mean for dark objects). A cell in phase contrast, in its bright
/// ring, is above 0; an object on a darker band of the frame well below. `None` when
/// either has too few pixels to say.
pub fn halo(
    ring: &[Point],
    label: u32,
    raster: &[u32],
    image: &Field,
    polarity: Polarity,
    background: f64,
) -> Option<f64> {
    let (mi, _, ni) = moments(inside(ring, label, raster, image));
    let mut around: Vec<f64> = ground(ring, raster, image, &HALO_BAND).collect();
    if ni < 5 || around.len() < 5 {
        return None;
    }
    // The median: a blob beside a cell has that cell's halo on one side only.
    let mo = median(&mut around)?;
    let (beyond, contrast) = match polarity {
        Polarity::Dark => (mo - background, background - mi),
        Polarity::Bright => (background - mo, mi - background),
    };
    Some(beyond / contrast.max(1e-6))
}

/// The median of `image` where `raster` has no object (`None` where it has no such
/// pixel): the frame's background level.
pub fn background(raster: &[u32], image: &Field) -> Option<f64> {
    let mut free: Vec<f32> = image
        .data
        .iter()
        .zip(raster)
        .filter(|&(_, &l)| l == 0)
        .map(|(&v, _)| v)
        .collect();
    (!free.is_empty()).then(|| edges::median(&mut free))
}

/// The pixels of the object labelled `label` in `raster`, outline `ring`.
fn inside<'a>(
    ring: &[Point],
    label: u32,
    raster: &'a [u32],
    image: &'a Field,
) -> impl Iterator<Item = f64> + 'a {
    let (w, h) = (image.width, image.height);
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0usize, 0usize);
    for p in ring {
        x0 = x0.min(p.x.floor().max(0.0) as usize);
        y0 = y0.min(p.y.floor().max(0.0) as usize);
        x1 = x1.max((p.x.ceil() as usize).min(w));
        y1 = y1.max((p.y.ceil() as usize).min(h));
    }
    (y0..y1)
        .flat_map(move |y| (x0..x1).map(move |x| (x, y)))
        .filter(move |&(x, y)| raster[y * w + x] == label)
        .map(|(x, y)| image.at(x, y) as f64)
}

/// The image sampled along `ring`'s outward normals at each of `distances`, where no
/// object of `raster` is.
fn ground<'a>(
    ring: &'a [Point],
    raster: &'a [u32],
    image: &'a Field,
    distances: &'a [f64],
) -> impl Iterator<Item = f64> + 'a {
    let (w, h) = (image.width, image.height);
    let n = ring.len();
    (0..n).flat_map(move |k| {
        let t = ring[(k + 1) % n] - ring[(k + n - 1) % n];
        let out = Point::new(t.y, -t.x) * (1.0 / t.norm().max(1e-9));
        distances.iter().filter_map(move |&d| {
            let p = ring[k] + out * d;
            let (x, y) = (p.x.floor(), p.y.floor());
            let free = x >= 0.0
                && y >= 0.0
                && (x as usize) < w
                && (y as usize) < h
                && raster[y as usize * w + x as usize] == 0;
            free.then(|| image.sample(p))
        })
    })
}

/// Which of `objects` (outline, region on the left, and what it must show) stand out
/// from their surroundings, judged on the ground no other object covers. One whose
/// surroundings are all other objects cannot be judged at first; once the faint ones
/// around it are dropped it is judged again on the ground they leave (seeds on a dark
/// corner tile it with blobs that hide each other's surroundings: 57 of bacteria 5's 66
/// false cells, docs/decisions.md). One that still cannot be judged (inside a colony)
/// is kept. An object that must show a halo is judged again after every round of drops,
/// even once it stood out: a blob on a band of uneven light stands out against the few
/// free pixels its neighbours leave at first, not once they are gone. The halo's
/// background is the ground no object covers at first.
pub fn standing_out(objects: &[(&[Point], Need)], image: &Field, polarity: Polarity) -> Vec<bool> {
    let labelled: Vec<(u32, &[Point])> = objects
        .iter()
        .enumerate()
        .map(|(k, &(ring, _))| (k as u32 + 1, ring))
        .collect();
    let mut raster = label_raster(&labelled, image.width, image.height);
    let level = objects
        .iter()
        .any(|(_, need)| need.halo.is_some())
        .then(|| background(&raster, image))
        .flatten();
    // Per object: dropped, or judged standing out (and, without a halo to show, final).
    let mut dropped = vec![false; objects.len()];
    let mut standing = vec![false; objects.len()];
    loop {
        let mut more = HashSet::new();
        for (k, &(ring, need)) in objects.iter().enumerate() {
            if dropped[k] || (standing[k] && need.halo.is_none()) {
                continue;
            }
            let label = k as u32 + 1;
            // Either measure alone can say no: blobs tiling a band hide the ground
            // just outside each other, not all of it further out. The halo is read only
            // where the separation did not say no already.
            let separated =
                separation(ring, label, &raster, image, polarity).map(|z| z >= need.separation);
            let halo = match (need.halo, level, separated) {
                (_, _, Some(false)) => None,
                (Some(least), Some(b), _) => {
                    halo(ring, label, &raster, image, polarity, b).map(|z| z >= least)
                }
                _ => Some(true),
            };
            match (separated, halo) {
                (Some(false), _) | (_, Some(false)) => {
                    dropped[k] = true;
                    more.insert(label);
                }
                (Some(true), Some(true)) => standing[k] = true,
                _ => {}
            }
        }
        // Each round drops at least one more object, or it is the last.
        if more.is_empty() {
            break;
        }
        raster
            .iter_mut()
            .filter(|l| more.contains(*l))
            .for_each(|l| *l = 0);
    }
    dropped.into_iter().map(|d| !d).collect()
}

/// Mean, variance and count of `v`.
fn moments(v: impl Iterator<Item = f64>) -> (f64, f64, usize) {
    let (mut s, mut s2, mut n) = (0.0, 0.0, 0usize);
    for x in v {
        s += x;
        s2 += x * x;
        n += 1;
    }
    if n == 0 {
        return (0.0, 0.0, 0);
    }
    let m = s / n as f64;
    (m, (s2 / n as f64 - m * m).max(0.0), n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::signed_area;

    /// A square from (x0, y0) of side `s`, a point every pixel, region on the left.
    fn square(x0: f64, y0: f64, s: f64) -> Vec<Point> {
        let n = s.round() as usize;
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let mut ring: Vec<Point> = (0..4)
            .flat_map(|c| {
                let (a, b) = (corners[c], corners[(c + 1) % 4]);
                (0..n).map(move |k| {
                    let t = k as f64 / n as f64;
                    Point::new(
                        x0 + s * (a.0 + (b.0 - a.0) * t),
                        y0 + s * (a.1 + (b.1 - a.1) * t),
                    )
                })
            })
            .collect();
        if signed_area(&ring) < 0.0 {
            ring.reverse();
        }
        ring
    }

    /// A 3 × 3 tiling of squares of side 10 from (15, 15) on a 64² image of a fine
    /// texture about 0.5, the middle square's pixels at `middle` instead.
    fn tiled(middle: f32) -> (Vec<Vec<Point>>, Field) {
        let rings: Vec<Vec<Point>> = (0..9)
            .map(|k| {
                square(
                    15.0 + 10.0 * (k % 3) as f64,
                    15.0 + 10.0 * (k / 3) as f64,
                    10.0,
                )
            })
            .collect();
        let data = (0..64 * 64)
            .map(|i| {
                let (x, y) = (i % 64, i / 64);
                let tex = if (x + y) % 2 == 0 { 0.02 } else { -0.02 };
                let inner = (25..35).contains(&x) && (25..35).contains(&y);
                if inner {
                    middle + tex
                } else {
                    0.5 + tex
                }
            })
            .collect();
        (rings, Field::new(64, 64, data))
    }

    #[test]
    fn blobs_tiling_flat_ground_are_all_dropped_and_a_cell_among_them_is_kept() {
        let judge = |middle: f32| {
            let (rings, image) = tiled(middle);
            let objects: Vec<(&[Point], Need)> = rings
                .iter()
                .map(|r| {
                    let need = Need {
                        separation: MIN_SEPARATION,
                        halo: None,
                    };
                    (r.as_slice(), need)
                })
                .collect();
            let raster = label_raster(
                &rings
                    .iter()
                    .enumerate()
                    .map(|(k, r)| (k as u32 + 1, r.as_slice()))
                    .collect::<Vec<_>>(),
                64,
                64,
            );
            // The middle one's surroundings are all its neighbours: it cannot be judged
            // on its own.
            assert!(separation(&rings[4], 5, &raster, &image, Polarity::Bright).is_none());
            standing_out(&objects, &image, Polarity::Bright)
        };
        assert_eq!(judge(0.5), vec![false; 9]);
        let mut cell = vec![false; 9];
        cell[4] = true;
        assert_eq!(judge(0.9), cell);
    }

    /// A 64² phase-contrast image: grey ground (0.6), a dark square (0.05) from (24, 24)
    /// of side 16, and around it a ring 14 px wide at `ring`.
    fn square_in(ring: f32) -> (Vec<Point>, Field) {
        let data = (0..64 * 64)
            .map(|i| {
                let (x, y) = ((i % 64) as f32, (i / 64) as f32);
                let d = (24.0 - x).max(x - 39.0).max(24.0 - y).max(y - 39.0);
                if d <= 0.0 {
                    0.05
                } else if d <= 14.0 {
                    ring
                } else {
                    0.6
                }
            })
            .collect();
        (square(24.0, 24.0, 16.0), Field::new(64, 64, data))
    }

    #[test]
    fn a_cell_in_its_halo_has_one_and_a_blob_on_a_darker_band_has_none() {
        let judge = |ring: f32| {
            let (square, image) = square_in(ring);
            let raster = label_raster(&[(1, square.as_slice())], 64, 64);
            let level = background(&raster, &image).unwrap();
            assert!((level - 0.6).abs() < 1e-6, "{level}");
            halo(&square, 1, &raster, &image, Polarity::Dark, level).unwrap()
        };
        // Halo 0.95: 0.35 beyond the ground, 0.55 the square's contrast.
        let (lit, band) = (judge(0.95), judge(0.3));
        assert!((lit - 0.35 / 0.55).abs() < 0.02, "{lit}");
        // On a band at 0.3: its ground 0.3 short of the background.
        assert!((band + 0.3 / 0.55).abs() < 0.02, "{band}");
        assert!(band < MIN_HALO && lit > MIN_HALO);
    }
}
