//! How far the whole field moved between two frames (stage drift, a dish settling, the
//! focus hunting): the carried contours are moved by it before the next frame starts
//! from them.
//!
//! A frame starts from the contours of the frame before, shrunk a little, so a cell that
//! moved under a pixel or two is still under its contour, and the pyramid carries a
//! contour further where it is alone (seed 004 §2.2). When the whole field moves, every
//! contour in a colony lands across its neighbours, and that the pyramid cannot undo:
//! a random walk of 2 px a frame took a synthetic bacteria colony's TRA from 0.99 to
//! 0.80–0.89 (docs/decisions.md, 2026-12-05). The papers track moving surfaces, not a
//! moving camera; a user of a tracking tool expects drift to be followed, as TrackMate
//! and the CTC methods do by registering frames first.
//!
//! The shift is the integer translation that best maps the last frame's cells onto the
//! new frame: the mean squared difference over the cells' pixels (where the texture
//! that tells the shift lies; the background of uneven light does not move with the
//! stage, nor do the optics' bubbles when a colony's pad slides), searched coarse to
//! fine from a quarter of the resolution over ±[`NEAR_SHIFT`] and from an eighth over
//! ±[`MAX_SHIFT`], each refined at half and full resolution; taken only when it beats no
//! shift clearly ([`MIN_GAIN`]), so a field that did not move keeps its contours where
//! they were. Past the frame's edge the new frame counts as background, so a shift
//! that carries cells out of view is no cheap match.

use crate::image::Field;

/// About the largest shift searched, pixels (each way, along each axis): a real colony on a
/// sliding agarose pad moved 103 px in one frame under a still camera.
pub const MAX_SHIFT: i32 = 128;

/// The drift of a stage, searched at a finer resolution than [`MAX_SHIFT`].
pub const NEAR_SHIFT: i32 = 24;

/// A shift is taken only when its mean squared difference is below this share of no
/// shift's: noise alone never favours a neighbouring shift by that much.
pub const MIN_GAIN: f64 = 0.8;

/// A search stands out when its least cost is under this share of its median: the
/// cells found where they went; only when the search over ±[`NEAR_SHIFT`] does not is
/// the wider one made. Over ±[`NEAR_SHIFT`], frames of synthetic movies (still,
/// drifting, dense, fast) and of sim_plus_01 had their least at 0.05–0.15 of the median
/// (medians per movie); a real colony whose pad slid 35–103 px, 0.45–0.95
/// (docs/decisions.md, 2026-12-06).
pub const FLAT: f64 = 0.25;

/// Most pixels sampled (every k-th cell pixel beyond this).
const MAX_SAMPLES: usize = 4_000;

/// The shift `(dx, dy)` such that `after` at `x + (dx, dy)` is `before` at `x` over the
/// pixels of `cells` (a label raster of `before`'s size, 0 outside every cell); `(0, 0)`
/// when the field did not clearly move, the frames differ in size, or there are no cells.
/// Both frames as [`on_quantiles`] puts them: each frame is normalised on its own (its
/// 0.1 % and 99.9 % quantiles), so a bright cell that comes or goes rescales every
/// other, and the squared difference counted that as a move (a still movie of nuclei
/// was shifted by 22 px the frame one bright nucleus faded); their 1 % and 99 %
/// quantiles one cell does not move. The tracker keeps each frame so, for the next.
pub fn field_shift(before: &Field, after: &Field, cells: &[u32]) -> (i32, i32) {
    let (w, h) = (before.width, before.height);
    if after.width != w || after.height != h || cells.len() != w * h {
        return (0, 0);
    }
    let on: Vec<usize> = (0..w * h).filter(|&i| cells[i] != 0).collect();
    if on.is_empty() {
        return (0, 0);
    }
    let step = on.len().div_ceil(MAX_SAMPLES);
    let samples: Vec<(i32, i32)> = on
        .iter()
        .step_by(step)
        .map(|&i| ((i % w) as i32, (i / w) as i32))
        .collect();
    // Past the frame's edge the new frame is taken as its background (its median): a
    // shift that carries cells out of view is judged as one that lands them on nothing.
    let pad = background(after);
    let full = Level::new(before, after, &samples, 1, pad);
    let still = full.cost((0, 0));
    let close = full.best_around((0, 0), 1);
    // A field that did not move: no shift is the best of its neighbours and far better
    // than shifts [`NEAR_SHIFT`] away (the search costs a frame's tracking a tenth).
    if close == (0, 0) {
        let n = NEAR_SHIFT;
        let mut far: Vec<f64> = [
            (n, 0),
            (-n, 0),
            (0, n),
            (0, -n),
            (n, n),
            (-n, -n),
            (n, -n),
            (-n, n),
        ]
        .map(|s| full.cost(s))
        .into();
        let k = far.len() / 2;
        if still <= FLAT * *far.select_nth_unstable_by(k, f64::total_cmp).1 {
            return (0, 0);
        }
    }
    // Coarse to fine, so a move of many pixels is not mistaken for the nearest local
    // minimum of a textured colony: from the quarter resolution over ±[`NEAR_SHIFT`]
    // (a stage's drift), and from the eighth over ±[`MAX_SHIFT`] (a pad that slid, a
    // colony carried off by flow); the lower cost at full resolution wins, and one pixel
    // either way of no shift competes too.
    let b2 = block_mean(before, 2);
    let a2 = block_mean(after, 2);
    let b4 = block_mean(&b2, 2);
    let a4 = block_mean(&a2, 2);
    let half = Level::new(&b2, &a2, &samples, 2, pad);
    let quarter = Level::new(&b4, &a4, &samples, 4, pad);
    let refine = |s: (i32, i32)| refined(&half, &full, s);
    let (near, flat) = quarter.search((0, 0), NEAR_SHIFT / 4);
    let mut candidates = vec![close, refine(near)];
    // Farther only when no shift within reach stands out: the cells landed on nothing.
    if flat {
        let (b8, a8) = (block_mean(&b4, 2), block_mean(&a4, 2));
        let eighth = Level::new(&b8, &a8, &samples, 8, pad);
        let (coarse, _) = eighth.search((0, 0), MAX_SHIFT / 8);
        candidates.push(refine(quarter.best_around((2 * coarse.0, 2 * coarse.1), 1)));
    }
    let best = candidates
        .into_iter()
        .min_by(|&a, &b| full.cost(a).total_cmp(&full.cost(b)))
        .unwrap_or((0, 0));
    if full.cost(best) < MIN_GAIN * still {
        best
    } else {
        (0, 0)
    }
}

/// A field that moved at least this far (pixels, along an axis) also had its cells move
/// against each other: each cell's own shift is then searched ([`cell_shifts`]). A
/// real colony whose pad slid 10–100 px a frame had its cells 3–18 px off one shift for
/// all; a stage's drift of a few pixels moves every cell alike.
///
/// In transmitted light the tracker searches each cell's own shift every frame, moved
/// field or not: rods packed in a growing colony push each other about. In a real dense
/// colony (divbac26, docs/decisions.md 2026-12-07, tenth session) the reference cells
/// moved a median 9.8 px a frame beyond the field's shift (90th percentile 24 px), most
/// of a rod's width: a carried contour landed across its neighbour, leaked into it and
/// split off a piece of it as a false daughter. Nuclei are not searched so: a shift
/// found for a dividing nucleus lands its contour on one daughter, and the division is
/// missed (HeLa division F1 0.62 → 0.59, sim_plus_01 0.98 → 0.96 when searched every
/// frame).
pub const CELL_FROM: i32 = 8;

/// How far each cell's own shift is searched beyond the field's (pixels, each way). On
/// the dense colony above, TRA was 0.636 searching ±6, 0.717 at ±10 and 0.680 at ±14:
/// farther, a rod matches its look-alike neighbour.
pub const CELL_REACH: i32 = 10;

/// How far a cell's neighbourhood ([`NEIGHBOURHOOD`]) is searched beyond the field's
/// shift (pixels, each way). In a sheet of parallel rods one rod's place matches its
/// neighbour's, so a cell alone cannot be searched farther than [`CELL_REACH`]; but the
/// dense colony's rods moved up to 24 px a frame (90th percentile), and there a contour
/// landed on the rod beside its own, the whole sheet's labels moving over by one rod
/// (divbac26 frames 8–9). Several cells together are no periodic pattern, and a
/// colony's cells move with their neighbours (it grows and flows as one), so the
/// neighbourhood's shift is searched this far, and the cell's own near it
/// ([`NEIGHBOURHOOD_FINE`]).
pub const NEIGHBOURHOOD_REACH: i32 = 24;

/// A cell's neighbourhood: the cells whose boxes' centres lie within this many times its
/// box's diagonal of its own.
pub const NEIGHBOURHOOD: f64 = 1.5;

/// How far a cell's own shift is searched around its neighbourhood's (pixels, each way).
pub const NEIGHBOURHOOD_FINE: i32 = 2;

/// Per cell of `labels` (a label raster of `before`), the shift beyond the field's `s`
/// that best maps its pixels and a 2 px band around them onto `after` (the mean squared
/// difference, the band being where a rod's end and sides show; past the edge against
/// the frame's background, so a leaving cell is not pulled back in). Two places are
/// weighed, and the one that matches the cell better is taken: its best within
/// [`CELL_REACH`] of the field's shift (a cell that moved on its own: in a sliding
/// colony the neighbourhood's shift missed single rods' by up to 10 px), and its best
/// within [`NEIGHBOURHOOD_FINE`] of its neighbourhood's shift (see
/// [`NEIGHBOURHOOD_REACH`]). A cell is left out unless its best beats no shift of its
/// own by [`MIN_GAIN`].
///
/// Two cells never lie on one place, so the cells are placed one by one, the best
/// matched first (least cost), and a cell whose place lands more than
/// [`PLACED_OVERLAP`] of it on cells placed before takes its best free one: a rod whose
/// own place changed (it divided, or turned) matches its look-alike neighbour's body
/// better, and its contour, started over the neighbour's, was dropped by the evolver
/// and the neighbour's track ended (on a real dense colony, 99 of the 102 tracks whose
/// contour vanished in a frame's evolution; docs/decisions.md, 2026-12-08).
pub fn cell_shifts(
    before: &Field,
    after: &Field,
    labels: &[u32],
    s: (i32, i32),
) -> std::collections::HashMap<u32, (i32, i32)> {
    let (w, h) = (before.width as i32, before.height as i32);
    let mut out = std::collections::HashMap::new();
    if after.width != before.width
        || after.height != before.height
        || labels.len() != (w * h) as usize
    {
        return out;
    }
    // Each cell's box, and its pixels (where it lands when placed).
    let mut boxes: std::collections::BTreeMap<u32, [i32; 4]> = std::collections::BTreeMap::new();
    let mut pixels: std::collections::HashMap<u32, Vec<(i32, i32)>> =
        std::collections::HashMap::new();
    for (i, &l) in labels.iter().enumerate() {
        if l != 0 {
            let (x, y) = (i as i32 % w, i as i32 / w);
            pixels.entry(l).or_default().push((x, y));
            let b = boxes.entry(l).or_insert([x, y, x, y]);
            *b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        }
    }
    let pad = background(after);
    let shifts = by_distance(CELL_REACH);
    let samples: std::collections::BTreeMap<u32, Vec<(i32, i32)>> = boxes
        .iter()
        .map(|(&l, &b)| (l, cell_samples(labels, w, h, l, b)))
        .collect();
    let (b2, a2) = (block_mean(before, 2), block_mean(after, 2));
    let (b4, a4) = (block_mean(&b2, 2), block_mean(&a2, 2));
    let centre = |b: &[i32; 4]| (0.5 * (b[0] + b[2]) as f64, 0.5 * (b[1] + b[3]) as f64);
    // Per cell: the cost of no shift of its own, and every place weighed, with its cost.
    let mut weighed: Vec<(u32, f64, Vec<Place>)> = Vec::with_capacity(boxes.len());
    for (&l, b) in &boxes {
        let own = &samples[&l];
        let step = own.len().div_ceil(MAX_CELL_SAMPLES).max(1);
        let own: Vec<(i32, i32)> = own.iter().copied().step_by(step).collect();
        let level = Level::new(before, after, &own, 1, pad);
        let none = level.cost(s);
        // Nearest shifts first, so of equal costs the shortest move wins (the sort
        // below is stable): a rod matches its look-alike neighbour as well as its own
        // new place.
        let mut places: Vec<Place> = shifts
            .iter()
            .map(|&(dx, dy)| {
                let at = (s.0 + dx, s.1 + dy);
                (level.cost(at), at)
            })
            .collect();
        // The neighbourhood's shift, coarse to fine as the field's.
        let (cx, cy) = centre(b);
        let reach = NEIGHBOURHOOD * ((b[2] - b[0]) as f64).hypot((b[3] - b[1]) as f64);
        let mut near: Vec<(i32, i32)> = Vec::new();
        for (k, bk) in &boxes {
            let (x, y) = centre(bk);
            if (x - cx).hypot(y - cy) <= reach.max(1.0) {
                near.extend_from_slice(&samples[k]);
            }
        }
        let step = near.len().div_ceil(NEIGHBOURHOOD_SAMPLES).max(1);
        let near: Vec<(i32, i32)> = near.into_iter().step_by(step).collect();
        let (quarter, half) = (
            Level::new(&b4, &a4, &near, 4, pad),
            Level::new(&b2, &a2, &near, 2, pad),
        );
        let full = Level::new(before, after, &near, 1, pad);
        let (c4, _) = quarter.search((s.0 / 4, s.1 / 4), NEIGHBOURHOOD_REACH / 4);
        let moved = refined(&half, &full, c4);
        let moved = if full.cost(moved) < full.cost(s) {
            moved
        } else {
            s
        };
        let along = level.best_around(moved, NEIGHBOURHOOD_FINE);
        // On a tie the cell moves with its neighbours: a colony flows as one.
        places.insert(0, (level.cost(along), along));
        places.sort_by(|x, y| x.0.total_cmp(&y.0));
        weighed.push((l, none, places));
    }
    // The best matched (least cost) are placed first; a cell whose place another took
    // goes to its best free one.
    let least = |(_, none, places): &(u32, f64, Vec<Place>)| places.first().map_or(*none, |p| p.0);
    weighed.sort_by(|x, y| least(x).total_cmp(&least(y)));
    let mut taken = vec![0u32; labels.len()];
    for (l, none, places) in weighed {
        let px = &pixels[&l];
        let step = px.len().div_ceil(MAX_CELL_SAMPLES).max(1);
        let free = |at: (i32, i32)| {
            let (mut on, mut n) = (0usize, 0usize);
            for &(x, y) in px.iter().step_by(step) {
                let (u, v) = (x + at.0, y + at.1);
                n += 1;
                if u >= 0 && v >= 0 && u < w && v < h && taken[(v * w + u) as usize] != 0 {
                    on += 1;
                }
            }
            on as f64 <= PLACED_OVERLAP * n as f64
        };
        // Its best place when that beats no shift clearly and is free; else no shift
        // when that is free and no free place beats it clearly; else its best free
        // place; with none free, where it would go alone.
        let trusted = |c: f64| c < MIN_GAIN * none;
        let best = places.first().copied().filter(|p| trusted(p.0));
        let at = match (best, free(s)) {
            (Some((_, at)), _) if free(at) => at,
            (None, true) => s,
            (_, stays) => match places.iter().find(|p| free(p.1)) {
                Some(&(c, at)) if trusted(c) || !stays => at,
                _ if stays => s,
                _ => best.map_or(s, |p| p.1),
            },
        };
        for &(x, y) in px {
            let (u, v) = (x + at.0, y + at.1);
            if u >= 0 && v >= 0 && u < w && v < h {
                taken[(v * w + u) as usize] = l;
            }
        }
        let e = (at.0 - s.0, at.1 - s.1);
        if e != (0, 0) {
            out.insert(l, e);
        }
    }
    out
}

/// A place weighed for a cell: its cost, and the shift.
type Place = (f64, (i32, i32));

/// The most of a cell's pixels that may land on cells already placed ([`cell_shifts`]):
/// two cells never lie on one place, so a shift that lands a cell on another's is
/// wrong for one of them. Neighbours pressed together and deforming overlap a little at
/// any rigid shift.
pub const PLACED_OVERLAP: f64 = 0.25;

/// A shift `s` found at a quarter of the resolution, refined at `half` and then `full`
/// resolution (one pixel either way at each).
fn refined(half: &Level, full: &Level, s: (i32, i32)) -> (i32, i32) {
    let s = half.best_around((2 * s.0, 2 * s.1), 1);
    full.best_around((2 * s.0, 2 * s.1), 1)
}

/// Cell `l`'s pixels of `labels` (`w`×`h`) in its box `b`, and the free ones within 2 px
/// of them.
fn cell_samples(labels: &[u32], w: i32, h: i32, l: u32, b: [i32; 4]) -> Vec<(i32, i32)> {
    const BAND: i32 = 2;
    let mut samples: Vec<(i32, i32)> = Vec::new();
    for y in (b[1] - BAND).max(0)..=(b[3] + BAND).min(h - 1) {
        for x in (b[0] - BAND).max(0)..=(b[2] + BAND).min(w - 1) {
            let at = labels[(y * w + x) as usize];
            let near = at == l
                || (at == 0
                    && (-BAND..=BAND).any(|dy| {
                        (-BAND..=BAND).any(|dx| {
                            let (u, v) = (x + dx, y + dy);
                            u >= 0 && v >= 0 && u < w && v < h && labels[(v * w + u) as usize] == l
                        })
                    }));
            if near {
                samples.push((x, y));
            }
        }
    }
    samples
}

/// Every shift of at most `reach` along each axis, nearest to none first (ties in
/// row order).
fn by_distance(reach: i32) -> Vec<(i32, i32)> {
    let mut v: Vec<(i32, i32)> = (-reach..=reach)
        .flat_map(|dy| (-reach..=reach).map(move |dx| (dx, dy)))
        .collect();
    v.sort_by_key(|&(dx, dy)| (dx * dx + dy * dy, dy, dx));
    v
}

/// The frame's background: its median (read from every [`QUANTILE_STRIDE`]-th pixel).
fn background(f: &Field) -> f32 {
    let mut v: Vec<f32> = f.data.iter().step_by(QUANTILE_STRIDE).copied().collect();
    if v.is_empty() {
        return 0.0;
    }
    let k = v.len() / 2;
    *v.select_nth_unstable_by(k, f32::total_cmp).1
}

/// Most pixels sampled per cell ([`cell_shifts`]).
const MAX_CELL_SAMPLES: usize = 600;

/// Most pixels sampled per neighbourhood ([`cell_shifts`]).
const NEIGHBOURHOOD_SAMPLES: usize = 2_400;

/// Quantiles [`ON_QUANTILES`] of a frame put at 0 and 1 (read from every
/// [`QUANTILE_STRIDE`]-th pixel).
pub fn on_quantiles(f: &Field) -> Field {
    let mut v: Vec<f32> = f.data.iter().step_by(QUANTILE_STRIDE).copied().collect();
    if v.is_empty() {
        return f.clone();
    }
    let at = |v: &mut Vec<f32>, q: f64| {
        let k = ((v.len() - 1) as f64 * q).round() as usize;
        *v.select_nth_unstable_by(k, |a, b| a.total_cmp(b)).1
    };
    let (lo, hi) = (at(&mut v, ON_QUANTILES.0), at(&mut v, ON_QUANTILES.1));
    let span = (hi - lo).max(1e-6);
    Field::new(
        f.width,
        f.height,
        f.data.iter().map(|&x| (x - lo) / span).collect(),
    )
}

/// The quantiles both frames are put on before they are compared ([`field_shift`]).
pub const ON_QUANTILES: (f64, f64) = (0.01, 0.99);

/// Every this many pixels are read for [`ON_QUANTILES`].
pub const QUANTILE_STRIDE: usize = 7;

/// `f` at 1/`k` of its resolution: the mean of each k×k block (a partial block at the
/// right and bottom edges averages what it has). Cheaper than the pyramid's blurred
/// reduction, and the same for both frames, which is all the search needs.
fn block_mean(f: &Field, k: usize) -> Field {
    let (w, h) = (f.width, f.height);
    let (wk, hk) = (w.div_ceil(k), h.div_ceil(k));
    let mut sum = vec![0f32; wk * hk];
    let mut count = vec![0u16; wk * hk];
    for y in 0..h {
        let row = (y / k) * wk;
        for x in 0..w {
            sum[row + x / k] += f.data[y * w + x];
            count[row + x / k] += 1;
        }
    }
    let data = sum.iter().zip(&count).map(|(s, &n)| s / n as f32).collect();
    Field::new(wk, hk, data)
}

/// One resolution of the search: the two frames at `scale` (1, 2, 4, 8) and the samples
/// at that resolution.
struct Level<'a> {
    before: &'a Field,
    after: &'a Field,
    samples: Vec<(i32, i32)>,
    /// The new frame's value past its edge.
    pad: f32,
}

impl<'a> Level<'a> {
    fn new(
        before: &'a Field,
        after: &'a Field,
        samples: &[(i32, i32)],
        scale: i32,
        pad: f32,
    ) -> Self {
        let mut s: Vec<(i32, i32)> = samples
            .iter()
            .map(|&(x, y)| (x / scale, y / scale))
            .collect();
        // Row by row, as the samples were taken, so full resolution sums in the same order.
        s.sort_unstable_by_key(|&(x, y)| (y, x));
        s.dedup();
        Level {
            before,
            after,
            samples: s,
            pad,
        }
    }

    /// Mean squared difference of the samples moved by `s`, those moved past the edge
    /// against the pad.
    fn cost(&self, s: (i32, i32)) -> f64 {
        let (w, h) = (self.before.width as i32, self.before.height as i32);
        let mut sum = 0.0f64;
        for &(x, y) in &self.samples {
            let (u, v) = (x + s.0, y + s.1);
            let moved = if u < 0 || v < 0 || u >= w || v >= h {
                self.pad
            } else {
                self.after.data[(v * w + u) as usize]
            };
            let d = moved - self.before.data[(y * w + x) as usize];
            sum += (d * d) as f64;
        }
        sum / self.samples.len().max(1) as f64
    }

    /// The shift of least cost within `reach` of `centre` (the centre on a tie).
    fn best_around(&self, centre: (i32, i32), reach: i32) -> (i32, i32) {
        self.search(centre, reach).0
    }

    /// The shift of least cost within `reach` of `centre` (the centre on a tie), and
    /// whether the search found nothing that stands out: its least cost above
    /// [`FLAT`] of the median.
    fn search(&self, centre: (i32, i32), reach: i32) -> ((i32, i32), bool) {
        let mut costs = Vec::with_capacity(((2 * reach + 1) * (2 * reach + 1)) as usize);
        let mut best = (self.cost(centre), centre);
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let s = (centre.0 + dx, centre.1 + dy);
                let c = self.cost(s);
                costs.push(c);
                if c < best.0 {
                    best = (c, s);
                }
            }
        }
        let k = costs.len() / 2;
        let median = *costs.select_nth_unstable_by(k, f64::total_cmp).1;
        (best.1, best.0 > FLAT * median)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blurred-looking blobs `(x, y, r)` on a `w`×`h` frame, and their labels (1, 2, …).
    fn blobs(w: usize, h: usize, centres: &[(i32, i32, i32)]) -> (Field, Vec<u32>) {
        let mut data = vec![0.2f32; w * h];
        let mut labels = vec![0u32; w * h];
        for (k, &(cx, cy, r)) in centres.iter().enumerate() {
            for y in 0..h as i32 {
                for x in 0..w as i32 {
                    let d2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) as f32;
                    data[(y * w as i32 + x) as usize] += 0.7 * (-d2 / (r * r) as f32).exp();
                    if d2 <= (r * r) as f32 {
                        labels[(y * w as i32 + x) as usize] = k as u32 + 1;
                    }
                }
            }
        }
        (Field::new(w, h, data), labels)
    }

    /// A frame of four blobs moved by `offset`, with the labels of the blobs unmoved.
    fn scene(offset: (i32, i32)) -> (Field, Vec<u32>) {
        let centres = [(30, 30, 8), (70, 40, 10), (50, 70, 7), (90, 75, 9)];
        let moved = centres.map(|(x, y, r)| (x + offset.0, y + offset.1, r));
        (blobs(120, 100, &moved).0, blobs(120, 100, &centres).1)
    }

    #[test]
    fn a_moved_field_gives_its_shift_and_a_still_one_none() {
        let (before, cells) = scene((0, 0));
        let before = on_quantiles(&before);
        for s in [(0, 0), (1, 0), (-2, 3), (9, -7), (-17, 14)] {
            let (after, _) = scene(s);
            assert_eq!(field_shift(&before, &on_quantiles(&after), &cells), s);
        }
        // No cells: nothing to tell the shift by.
        let after = on_quantiles(&scene((5, 5)).0);
        assert_eq!(field_shift(&before, &after, &vec![0; cells.len()]), (0, 0));
    }

    #[test]
    fn a_frame_brightened_as_a_whole_is_not_a_move() {
        // Per-frame normalisation rescales a frame whose brightest cell faded.
        let (before, cells) = scene((0, 0));
        for s in [(0, 0), (3, -2), (-11, 8)] {
            let (mut after, _) = scene(s);
            after.data.iter_mut().for_each(|v| *v = 2.2 * *v - 0.3);
            let moved = field_shift(&on_quantiles(&before), &on_quantiles(&after), &cells);
            assert_eq!(moved, s);
        }
    }

    #[test]
    fn a_cell_that_moved_beyond_the_field_gets_its_own_shift() {
        let at = [(30, 30, 8), (60, 40, 10), (45, 75, 7)];
        let (before, cells) = blobs(160, 120, &at);
        let before = on_quantiles(&before);
        // The field moved (40, 10); the second cell 4 px further right and 3 up.
        let moved: Vec<(i32, i32, i32)> = at
            .iter()
            .enumerate()
            .map(|(k, &(x, y, r))| {
                if k == 1 {
                    (x + 44, y + 7, r)
                } else {
                    (x + 40, y + 10, r)
                }
            })
            .collect();
        let after = on_quantiles(&blobs(160, 120, &moved).0);
        let own = cell_shifts(&before, &after, &cells, (40, 10));
        assert_eq!(own.get(&2), Some(&(4, -3)));
        assert_eq!(own.get(&1), None);
        assert_eq!(own.get(&3), None);
    }

    /// Vertical rods `(x, top, bottom)` 7 px wide on a `w`×`h` frame, and their labels.
    fn rods(w: usize, h: usize, at: &[(i32, i32, i32)]) -> (Field, Vec<u32>) {
        let mut data = vec![0.9f32; w * h];
        let mut labels = vec![0u32; w * h];
        for (k, &(cx, top, bottom)) in at.iter().enumerate() {
            for y in top..=bottom {
                for x in cx - 3..=cx + 3 {
                    if (0..w as i32).contains(&x) && (0..h as i32).contains(&y) {
                        data[y as usize * w + x as usize] = 0.1;
                        labels[y as usize * w + x as usize] = k as u32 + 1;
                    }
                }
            }
        }
        (Field::new(w, h, data), labels)
    }

    #[test]
    fn a_sheet_of_rods_that_moved_past_a_rods_reach_is_followed_by_its_neighbourhood() {
        // Five parallel rods 12 px apart (no two of one length) move 14 px right together,
        // beyond CELL_REACH: alone, each matches the place its left neighbour moved to,
        // 2 px to its right. A larger sheet beside them stays, so the field did not move.
        let sheet = [
            (20, 10, 50),
            (32, 14, 58),
            (44, 8, 46),
            (56, 18, 60),
            (68, 12, 49),
        ];
        let still: Vec<(i32, i32, i32)> = (0..8)
            .map(|k| (120 + 12 * k, 20 + 3 * (k % 3), 70))
            .collect();
        let before_at: Vec<(i32, i32, i32)> =
            sheet.iter().copied().chain(still.iter().copied()).collect();
        let after_at: Vec<(i32, i32, i32)> = sheet
            .iter()
            .map(|&(x, t, b)| (x + 14, t, b))
            .chain(still.iter().copied())
            .collect();
        let (before, labels) = rods(240, 90, &before_at);
        let (after, _) = rods(240, 90, &after_at);
        let own = cell_shifts(&before, &after, &labels, (0, 0));
        for k in 1..=sheet.len() as u32 {
            assert_eq!(own.get(&k), Some(&(14, 0)), "rod {k}");
        }
        for k in sheet.len() as u32 + 1..=before_at.len() as u32 {
            assert_eq!(own.get(&k), None, "still rod {k}");
        }
    }

    #[test]
    fn a_cell_whose_look_alike_neighbour_stayed_is_not_moved_onto_it() {
        // Two rods side by side; the right one is gone from the new frame (it left the
        // focus), the left one stayed. The right rod alone matches best on its
        // neighbour's place (10 px left), but that place is the left rod's own.
        let (before, labels) = rods(80, 70, &[(20, 10, 50), (30, 14, 42)]);
        let (after, _) = rods(80, 70, &[(20, 10, 50)]);
        let alone = Level::new(
            &before,
            &after,
            &cell_samples(&labels, 80, 70, 2, [27, 14, 33, 42]),
            1,
            0.9,
        );
        let best = alone.search((0, 0), CELL_REACH).0;
        assert_eq!(best.0, -10, "the right rod alone matches the left one");
        assert!(alone.cost(best) < MIN_GAIN * alone.cost((0, 0)));
        let own = cell_shifts(&before, &after, &labels, (0, 0));
        assert_eq!(own.get(&1), None);
        assert!(own.get(&2).is_none_or(|e| e.0 > -4), "{:?}", own.get(&2));
    }
}
