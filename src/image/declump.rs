//! Touching nuclei whose union has no neck in the distance transform: a seed's basin is
//! split at concave points of its outline when the parts are good ellipses.
//!
//! Follows Bai, Sun & Zhou (2009), "Splitting touching cells based on concave points and
//! ellipse fitting" (Pattern Recognition 42(11)): concave points are the deepest pixels
//! of the pieces between a region and its convex hull; a pair of them whose depths are
//! large against the distance between them (salience) marks where two convex objects
//! meet, and the cut along the segment joining them is kept when each part is fitted by
//! an ellipse. The paper leaves the acceptance open; we keep a cut when both parts
//! overlap their moment ellipse by ≥ [`PART_FIT`] (intersection over union) and on
//! average fit no worse than the whole (within [`FIT_SLACK`]) — two nuclei side by side
//! fit two ellipses better than one. The outline is first smoothed (opening then closing
//! by a disk of [`SMOOTH`] object radii) so the specks of a textured nucleus make no
//! concave points.
//!
//! The thresholds sit on a plateau of the public cases, and the fit test is what keeps
//! the ragged, textured nuclei of a dim image whole: without it they are cut at every
//! salience tried (`docs/decisions.md`).

use super::distance::distance_transform;
use super::patch::Patch;

/// Smallest part, in object disks (π r²).
pub const PART_AREA: f64 = 0.3;
/// Radius of the smoothing disk, in object radii.
pub const SMOOTH: f64 = 0.2;
/// Smallest depth of a concave point below the hull, in object radii.
pub const NOTCH: f64 = 0.12;
/// Smallest salience of a cut: the two depths over the cut's length.
pub const SALIENCE: f64 = 0.25;
/// Smallest overlap of each part with its moment ellipse.
pub const PART_FIT: f64 = 0.85;
/// How much worse than the whole the parts may fit on average.
pub const FIT_SLACK: f64 = 0.02;
/// Cuts per basin, nested: a clump of up to 2³ nuclei.
const MAX_DEPTH: usize = 3;

/// Pixels of the digital segment from `p` to `q` (Bresenham).
fn segment(p: (isize, isize), q: (isize, isize)) -> Vec<(isize, isize)> {
    let (dx, dy) = ((q.0 - p.0).abs(), -(q.1 - p.1).abs());
    let (sx, sy) = ((q.0 - p.0).signum(), (q.1 - p.1).signum());
    let (mut x, mut y, mut err) = (p.0, p.1, dx + dy);
    let mut out = vec![(x, y)];
    while (x, y) != q {
        let e2 = 2 * err;
        if e2 >= dy {
            err += dy;
            x += sx;
        }
        if e2 <= dx {
            err += dx;
            y += sy;
        }
        out.push((x, y));
    }
    out
}

/// The parts of `m` after the cuts this module's rules accept (`m` itself if none).
fn split(m: Patch, r: f64, depth: usize) -> Vec<Patch> {
    let a_min = PART_AREA * std::f64::consts::PI * r * r;
    if depth >= MAX_DEPTH || (m.count() as f64) < 2.0 * a_min {
        return vec![m];
    }
    let rho = (SMOOTH * r).round().max(1.0);
    let smooth = m.erode(rho).dilate(rho).dilate(rho).erode(rho).filled();
    let hull = smooth.hull();
    let depth_in_hull = distance_transform(&hull.px, m.w, m.h).data;
    // One concave point per piece of hull outside the smoothed region: its deepest pixel.
    let gap = hull.like(
        hull.px
            .iter()
            .zip(&smooth.px)
            .map(|(&a, &b)| a && !b)
            .collect(),
    );
    let (pieces, sizes) = gap.components();
    let mut deepest = vec![(0.0f32, 0usize); sizes.len()];
    for (i, &l) in pieces.iter().enumerate() {
        if l > 0 && depth_in_hull[i] > deepest[l as usize - 1].0 {
            deepest[l as usize - 1] = (depth_in_hull[i], i);
        }
    }
    let notches: Vec<(f64, usize)> = deepest
        .into_iter()
        .filter(|&(d, _)| d as f64 >= NOTCH * r)
        .map(|(d, i)| (d as f64, i))
        .collect();
    let at = |i: usize| ((i % m.w) as isize, (i / m.w) as isize);
    let mut cuts = Vec::new();
    for (a, &(dp, p)) in notches.iter().enumerate() {
        for &(dq, q) in &notches[a + 1..] {
            let ((px, py), (qx, qy)) = (at(p), at(q));
            let len = (((px - qx).pow(2) + (py - qy).pow(2)) as f64).sqrt();
            let salience = (dp + dq) / len.max(1.0);
            if salience >= SALIENCE {
                cuts.push((salience, p, q));
            }
        }
    }
    cuts.sort_by(|a, b| b.0.total_cmp(&a.0));
    let e0 = m.ellipse_fit();
    for (_, p, q) in cuts {
        // The region less the segment thickened to 3×3, in its two largest pieces.
        let mut cut = m.px.clone();
        for (x, y) in segment(at(p), at(q)) {
            for (ox, oy) in (-1..=1).flat_map(|a| (-1..=1).map(move |b| (a, b))) {
                let (cx, cy) = (x + ox, y + oy);
                if cx >= 0 && cy >= 0 && (cx as usize) < m.w && (cy as usize) < m.h {
                    cut[cy as usize * m.w + cx as usize] = false;
                }
            }
        }
        let (labels, sizes) = m.like(cut).components();
        if sizes.len() < 2 {
            continue;
        }
        let mut order: Vec<usize> = (0..sizes.len()).collect();
        order.sort_by_key(|&k| std::cmp::Reverse(sizes[k]));
        if (sizes[order[1]] as f64) < a_min {
            continue;
        }
        let piece = |k: usize| m.like(labels.iter().map(|&l| l as usize == k + 1).collect());
        let (d1, d2) = (piece(order[0]).distance_to(), piece(order[1]).distance_to());
        // Every pixel of the region goes to the nearer piece.
        let one = m.like((0..m.px.len()).map(|i| m.px[i] && d1[i] <= d2[i]).collect());
        let two = m.like((0..m.px.len()).map(|i| m.px[i] && d1[i] > d2[i]).collect());
        let (e1, e2) = (one.ellipse_fit(), two.ellipse_fit());
        if e1.min(e2) >= PART_FIT && 0.5 * (e1 + e2) >= e0 - FIT_SLACK {
            let mut parts = split(one, r, depth + 1);
            parts.extend(split(two, r, depth + 1));
            return parts;
        }
    }
    vec![m]
}

/// Splits the basins (labels 1..=`peaks.len()` of a `w`×`h` image) of the seeds that
/// `eligible` names, for objects of radius `r`: a part keeps its basin's label or gets
/// the next free one, and its peak (the pixel of largest `dist`) is set or appended.
pub fn split_basins(
    labels: &mut [u32],
    peaks: &mut Vec<usize>,
    dist: &[f32],
    (w, h): (usize, usize),
    r: f64,
    eligible: impl Fn(usize) -> bool,
) {
    let n = peaks.len();
    let mut boxes = vec![(usize::MAX, usize::MAX, 0usize, 0usize); n];
    for (i, &l) in labels.iter().enumerate() {
        if l > 0 {
            let b = &mut boxes[l as usize - 1];
            let (x, y) = (i % w, i / w);
            *b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
        }
    }
    // A margin wide enough for the smoothing disk: the box's edge stays background.
    let pad = (SMOOTH * r).round().max(1.0) as usize + 3;
    for k in 0..n {
        let (x0, y0, x1, y1) = boxes[k];
        if x0 == usize::MAX || !eligible(peaks[k]) {
            continue;
        }
        let (pw, ph) = (x1 - x0 + 1 + 2 * pad, y1 - y0 + 1 + 2 * pad);
        let to_image = |j: usize| -> Option<usize> {
            let (x, y) = (
                (j % pw + x0).checked_sub(pad)?,
                (j / pw + y0).checked_sub(pad)?,
            );
            (x < w && y < h).then(|| y * w + x)
        };
        let l = k as u32 + 1;
        let px = (0..pw * ph)
            .map(|j| to_image(j).is_some_and(|i| labels[i] == l))
            .collect();
        let origin = (x0 as isize - pad as isize, y0 as isize - pad as isize);
        let patch = Patch {
            w: pw,
            h: ph,
            px,
            origin,
            image: (w, h),
        };
        let parts = split(patch, r, 0);
        if parts.len() < 2 {
            continue;
        }
        for (p, part) in parts.iter().enumerate() {
            let label = if p == 0 { l } else { peaks.len() as u32 + 1 };
            let mut peak = (f32::MIN, 0);
            for j in (0..part.px.len()).filter(|&j| part.px[j]) {
                let i = to_image(j).expect("parts lie on their basin");
                labels[i] = label;
                if dist[i] > peak.0 {
                    peak = (dist[i], i);
                }
            }
            if p == 0 {
                peaks[k] = peak.1;
            } else {
                peaks.push(peak.1);
            }
        }
    }
}
#[cfg(test)]
mod tests {
    use super::super::patch::tests::{ellipse, patch};
    use super::*;

    #[test]
    fn two_touching_disks_split_in_two_and_one_ellipse_stays_whole() {
        let (w, h) = (70, 44);
        let (l, r) = (
            ellipse(w, h, (24.0, 22.0), 11.0, 11.0),
            ellipse(w, h, (44.0, 22.0), 11.0, 11.0),
        );
        let pair = patch(w, h, l.iter().zip(&r).map(|(&a, &b)| a || b).collect());
        let parts = split(pair.clone(), 11.0, 0);
        assert_eq!(parts.len(), 2);
        for part in &parts {
            let agree =
                |truth: &Vec<bool>| part.px.iter().zip(truth).filter(|(a, b)| a == b).count();
            assert!(agree(&l).max(agree(&r)) as f64 > 0.97 * (w * h) as f64);
        }
        let whole = patch(w, h, ellipse(w, h, (34.0, 22.0), 21.0, 11.0));
        assert_eq!(split(whole, 11.0, 0).len(), 1);
    }
}
