//! A taught run's last stage: each object's edge where its own image puts it.
//!
//! The classifier decides which pixels are objects, but a user's strokes leave the edge
//! itself unlabelled: object strokes run along the cells' middles and background strokes
//! keep a few pixels off them (the simulated user of `scribbles.py` paints ≥ 1 px inside
//! and ≥ 3 px outside, as a person does), so the forest's ½ level falls wherever its
//! features happen to interpolate across that gap — inside a phase-contrast rod's dark
//! rim, outside a dim nucleus. An annotator traces the edge where the intensity is
//! half-way between the object and what is around it. So once the run on the
//! probabilities has settled, it runs on again on a field that is the probabilities
//! everywhere except in a band of [`BAND`] pixels about each object's outline, where it
//! reads the image: half-way between that object's inside and its free surroundings is
//! the decision level (a per-object local threshold, as CellProfiler's per-object
//! thresholding does, here as a field the contours settle on with sub-pixel accuracy).
//!
//! The background between two objects closer than two bands is left as the classifier
//! put it: it is theirs to keep apart (read from the image, a dark contact would join
//! them in a run whose topology adapts). An object is left to the classifier when its
//! surroundings are mostly other objects (under [`MIN_FREE`] of the ring around it is
//! background: inside a dense colony there is no "outside" to measure) or when its
//! inside is not on its polarity's side of them.
//!
//! Chosen on the six public real cases with two simulated stroke sets and checked on two
//! more (docs/decisions.md, 2026-12-05: mean SEG 0.7679 → 0.7844 over the four).

use super::distance::distance_transform;
use super::{Field, Polarity};
use crate::contours::measure::regions;
use crate::contours::ContourSet;
use crate::geometry::{fill_even_odd, Point};

/// Widest band (pixels) each side of an outline where the image sets the edge; half the
/// object's inscribed radius when that is less (a thin rod's band must not reach its
/// middle).
pub const BAND: f64 = 3.0;

/// Least share of the ring 2–5 px outside an object that must be background (no other
/// object) for its edge to be read from the image.
pub const MIN_FREE: f64 = 0.3;

/// Inner (exclusive) and outer (inclusive) distances, pixels, of the ring outside an
/// object whose intensity is its surroundings'.
const OUTSIDE: (f32, f32) = (2.0, 5.0);

/// Fewest pixels the inside band and the free surroundings each need.
const MIN_PIXELS: usize = 5;

/// Margin (pixels) around an object's box in which it is measured: past [`OUTSIDE`] and
/// [`BAND`].
const MARGIN: usize = 8;

/// `field` (what a taught run reads: objects at `object`, background at `background`,
/// decided half-way) with each object of `set` given its edge from `image`: within
/// [`BAND`] of its outline, the field ramps from `background` to `object` as the
/// intensity (smoothed at σ 1) goes from the object's surroundings to its inside,
/// crossing the decision level half-way between them. Pixels of other objects are left
/// as they are. Returns the field and how many objects were given their edge.
pub fn edge_field(
    field: &Field,
    image: &Field,
    set: &ContourSet,
    polarity: Polarity,
    object: f64,
    background: f64,
) -> (Field, usize) {
    let (w, h) = (field.width, field.height);
    let smooth = image.blur5();
    // Each region's rings, outer first, read once.
    let rings: Vec<Vec<Vec<Point>>> = regions(set)
        .iter()
        .map(|r| {
            std::iter::once(r.id)
                .chain(r.holes.iter().copied())
                .map(|id| set.ring_points(id))
                .collect()
        })
        .collect();
    let mut labels = vec![0u32; w * h];
    for (k, r) in rings.iter().enumerate() {
        fill_even_odd(r, w, h, |i| labels[i] = k as u32 + 1);
    }
    let level = 0.5 * (object + background);
    let half = 0.5 * (object - background);
    let sign = match polarity {
        Polarity::Bright => 1.0,
        Polarity::Dark => -1.0,
    };
    let mut out = field.data.clone();
    let mut done = 0;
    for (k, r) in rings.iter().enumerate() {
        let own = k as u32 + 1;
        let bb = r[0].iter().fold(
            (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
            |(x0, y0, x1, y1), p| (x0.min(p.x), y0.min(p.y), x1.max(p.x), y1.max(p.y)),
        );
        let x0 = (bb.0.floor().max(0.0) as usize).saturating_sub(MARGIN);
        let y0 = (bb.1.floor().max(0.0) as usize).saturating_sub(MARGIN);
        let x1 = ((bb.2.ceil().max(0.0) as usize) + MARGIN).min(w);
        let y1 = ((bb.3.ceil().max(0.0) as usize) + MARGIN).min(h);
        if x1 <= x0 || y1 <= y0 {
            continue;
        }
        let (bw, bh) = (x1 - x0, y1 - y0);
        let at = |i: usize| (y0 + i / bw) * w + x0 + i % bw;
        let mine: Vec<bool> = (0..bw * bh).map(|i| labels[at(i)] == own).collect();
        let inside = distance_transform(&mine, bw, bh);
        let not_mine: Vec<bool> = mine.iter().map(|&m| !m).collect();
        let outside = distance_transform(&not_mine, bw, bh);
        // Distance to the other objects: the gap between two of them is theirs to keep
        // (read from the image, a dark contact would join them in a run that merges).
        let not_other: Vec<bool> = (0..bw * bh)
            .map(|i| mine[i] || labels[at(i)] == 0)
            .collect();
        let apart = distance_transform(&not_other, bw, bh);
        let deepest = inside.data.iter().fold(0f32, |a, &b| a.max(b));
        let band = BAND.min((0.5 * deepest as f64).max(1.0)) as f32;
        let (mut inner, mut free, mut ring) = (Vec::new(), Vec::new(), 0usize);
        for i in 0..bw * bh {
            let (din, dout) = (inside.data[i], outside.data[i]);
            if mine[i] && din > 1.0 && din <= band.max(2.0) {
                inner.push(smooth.data[at(i)]);
            } else if !mine[i] && dout > OUTSIDE.0 && dout <= OUTSIDE.1 {
                ring += 1;
                if labels[at(i)] == 0 {
                    free.push(smooth.data[at(i)]);
                }
            }
        }
        if inner.len() < MIN_PIXELS
            || free.len() < MIN_PIXELS
            || (free.len() as f64) < MIN_FREE * ring as f64
        {
            continue;
        }
        let (mi, mo) = (median(&mut inner), median(&mut free));
        let spread = sign * (mi - mo);
        if spread <= 0.0 {
            continue;
        }
        let mid = 0.5 * (mi + mo);
        for i in 0..bw * bh {
            let near = if mine[i] {
                inside.data[i] <= band
            } else {
                outside.data[i] <= band && labels[at(i)] == 0 && apart.data[i] > band
            };
            if near {
                let t =
                    (sign * (smooth.data[at(i)] as f64 - mid) / (0.5 * spread)).clamp(-1.0, 1.0);
                out[at(i)] = (level + t * half) as f32;
            }
        }
        done += 1;
    }
    (Field::new(w, h, out), done)
}

/// The median of `v` (not empty), which it reorders.
pub(crate) fn median(v: &mut [f32]) -> f64 {
    let m = v.len() / 2;
    v.select_nth_unstable_by(m, f32::total_cmp);
    v[m] as f64
}
