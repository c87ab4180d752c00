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
