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

use crate::geometry::Point;
use crate::image::{Field, Polarity};
use crate::track::carry::label_raster;
use std::collections::HashSet;

/// Smallest separation (pooled standard deviations) of a new cell from its surroundings.
pub const MIN_SEPARATION: f64 = 1.8;

/// Smallest separation of a carried cell: the bound the gradient blobs stay under.
/// A blob that passed as a new cell (a speck at the frame's edge) grows over the dark
/// corner frame by frame (0.3–1.0 on bacteria 5); a fading cell keeps its track down to
/// here (real cells' least on every movie measured: 1.27, a 37 px sliver).
pub const MIN_CARRIED_SEPARATION: f64 = 1.2;

/// How many pixels out the band around an object starts and ends.
const BAND: [f64; 3] = [2.0, 3.0, 4.0];

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
    let (w, h) = (image.width, image.height);
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0usize, 0usize);
    for p in ring {
        x0 = x0.min(p.x.floor().max(0.0) as usize);
        y0 = y0.min(p.y.floor().max(0.0) as usize);
        x1 = x1.max((p.x.ceil() as usize).min(w));
        y1 = y1.max((p.y.ceil() as usize).min(h));
    }
    let inside = (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .filter(|&(x, y)| raster[y * w + x] == label)
        .map(|(x, y)| image.at(x, y) as f64);
    let n = ring.len();
    let outside = (0..n).flat_map(|k| {
        let t = ring[(k + 1) % n] - ring[(k + n - 1) % n];
        let out = Point::new(t.y, -t.x) * (1.0 / t.norm().max(1e-9));
        BAND.iter().filter_map(move |&d| {
            let p = ring[k] + out * d;
            let (x, y) = (p.x.floor(), p.y.floor());
            let free = x >= 0.0
                && y >= 0.0
                && (x as usize) < w
                && (y as usize) < h
                && raster[y as usize * w + x as usize] == 0;
            free.then(|| image.sample(p))
        })
    });
    let (mi, vi, ni) = moments(inside);
    let (mo, vo, no) = moments(outside);
    if ni < 5 || no < 5 {
        return None;
    }
    let d = match polarity {
        Polarity::Dark => mo - mi,
        Polarity::Bright => mi - mo,
    };
    Some(d / (0.5 * (vi + vo)).sqrt().max(1e-12))
}

/// Which of `objects` (outline, region on the left, and the least separation it needs)
/// stand out from their surroundings. One whose surroundings are all other objects
/// cannot be judged at first; once the faint ones around it are dropped it is judged
/// again on the ground they leave (seeds on a dark corner tile it with blobs that hide
/// each other's surroundings: 57 of bacteria 5's 66 false cells, docs/decisions.md).
/// One that still cannot be judged (inside a colony) is kept.
pub fn standing_out(objects: &[(&[Point], f64)], image: &Field, polarity: Polarity) -> Vec<bool> {
    let labelled: Vec<(u32, &[Point])> = objects
        .iter()
        .enumerate()
        .map(|(k, &(ring, _))| (k as u32 + 1, ring))
        .collect();
    let mut raster = label_raster(&labelled, image.width, image.height);
    let mut verdict: Vec<Option<bool>> = vec![None; objects.len()];
    loop {
        let mut dropped = HashSet::new();
        for (k, &(ring, least)) in objects.iter().enumerate() {
            if verdict[k].is_none() {
                let label = k as u32 + 1;
                if let Some(z) = separation(ring, label, &raster, image, polarity) {
                    verdict[k] = Some(z >= least);
                    if z < least {
                        dropped.insert(label);
                    }
                }
            }
        }
        // Each round judges at least one more object, or it is the last.
        if dropped.is_empty() || verdict.iter().all(Option::is_some) {
            break;
        }
        raster
            .iter_mut()
            .filter(|l| dropped.contains(*l))
            .for_each(|l| *l = 0);
    }
    verdict.into_iter().map(|v| v != Some(false)).collect()
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
            let objects: Vec<(&[Point], f64)> = rings
                .iter()
                .map(|r| (r.as_slice(), MIN_SEPARATION))
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
}
