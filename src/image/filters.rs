//! Box filters: the mean and the extremes over a (2r+1)² box, in O(1) per pixel whatever
//! r (running sums; van Herk and Gil-Werman), on whole rows at once so they vectorise.

use super::field::Field;

/// Mean over the (2r+1)² box around each pixel, the box cut to the image (the mean of
/// its part inside). Separable running sums: a column window slides down the image as
/// whole rows (added entering, subtracted leaving: vectorised), then a row window along
/// each row. The column sums are f32, one add and one subtract per row (their drift
/// over a few thousand rows stays far below an 8-bit grey step); the row's prefix sums
/// are f64, so their differences keep f32 precision.
pub fn box_mean(f: &Field, r: usize) -> Field {
    let (w, h) = (f.width, f.height);
    let row = |y: usize| &f.data[y * w..(y + 1) * w];
    let mut out = vec![0f32; w * h];
    // Column sums over rows [y − r, y + r] ∩ image, as a running window of whole rows.
    let mut acc = vec![0f32; w];
    for y in 0..r.min(h) {
        acc.iter_mut().zip(row(y)).for_each(|(a, &v)| *a += v);
    }
    let mut line = vec![0f64; w + 1];
    for y in 0..h {
        if y + r < h {
            acc.iter_mut().zip(row(y + r)).for_each(|(a, &v)| *a += v);
        }
        if y > r {
            acc.iter_mut()
                .zip(row(y - r - 1))
                .for_each(|(a, &v)| *a -= v);
        }
        let rows = ((y + r + 1).min(h) - y.saturating_sub(r)) as f32;
        // Prefix sums along the row, in f64: their differences keep f32 precision.
        let mut run = 0f64;
        for (x, &a) in acc.iter().enumerate() {
            run += a as f64;
            line[x + 1] = run;
        }
        let dst = &mut out[y * w..(y + 1) * w];
        let cut = |x: usize| {
            let (x0, x1) = (x.saturating_sub(r), (x + r + 1).min(w));
            ((line[x1] - line[x0]) / (rows as f64 * (x1 - x0) as f64)) as f32
        };
        // Where the window lies whole in the row, one reciprocal serves all.
        let lo = r.min(w);
        let hi = w.saturating_sub(r).max(lo);
        let inv = 1.0 / (rows as f64 * (2 * r + 1) as f64);
        for (x, d) in dst.iter_mut().enumerate().take(lo) {
            *d = cut(x);
        }
        if lo < hi {
            for ((d, &a), &b) in dst[lo..hi]
                .iter_mut()
                .zip(&line[lo + r + 1..hi + r + 1])
                .zip(&line[lo - r..hi - r])
            {
                *d = ((a - b) * inv) as f32;
            }
        }
        for (x, d) in dst.iter_mut().enumerate().skip(hi) {
            *d = cut(x);
        }
    }
    Field::new(w, h, out)
}

/// The maximum (`max` true) or minimum over the (2r+1)² box around each pixel, the box
/// cut to the image. Separable, each pass by van Herk and Gil-Werman: in blocks of 2r + 1
/// a running extreme from the block's start and one from its end, so every window is one
/// comparison of two of them (O(1) per pixel, whatever r). Each pass runs on a strip of
/// 64 columns at once (element-wise; the horizontal one on a transposed strip of
/// rows), so it reads memory in order and vectorises, and its buffers stay a sliver of
/// the image: the result is written over the input ([`box_extreme_in`]), so a large
/// image costs no more than its own field.
pub fn box_extreme(f: &Field, r: usize, max: bool) -> Field {
    box_extreme_in(f.clone(), r, max)
}

/// [`box_extreme`] of a field the caller no longer needs, written over it.
pub fn box_extreme_in(mut f: Field, r: usize, max: bool) -> Field {
    // Monomorphised per extreme, so the comparisons inline and vectorise.
    if max {
        box_extreme_with(&mut f, r, f32::max, f32::NEG_INFINITY);
    } else {
        box_extreme_with(&mut f, r, f32::min, f32::INFINITY);
    }
    f
}

/// Rows or columns extremised together: wide enough to vectorise, narrow enough that a
/// pass's buffers are a sliver of the image.
const STRIP: usize = 64;

fn box_extreme_with(f: &mut Field, r: usize, pick: impl Fn(f32, f32) -> f32 + Copy, identity: f32) {
    let (w, h) = (f.width, f.height);
    let (mut strip, mut out, mut ahead, mut behind) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    // Horizontal: a strip of rows transposed, so its columns are items of `s` values.
    for y0 in (0..h).step_by(STRIP) {
        let s = STRIP.min(h - y0);
        strip.clear();
        strip.resize(w * s, 0.0);
        for y in 0..s {
            let row = &f.data[(y0 + y) * w..(y0 + y + 1) * w];
            for (x, &v) in row.iter().enumerate() {
                strip[x * s + y] = v;
            }
        }
        extreme_1d(
            &strip,
            s,
            r,
            pick,
            identity,
            &mut out,
            &mut ahead,
            &mut behind,
        );
        for y in 0..s {
            let row = &mut f.data[(y0 + y) * w..(y0 + y + 1) * w];
            for (x, v) in row.iter_mut().enumerate() {
                *v = out[x * s + y];
            }
        }
    }
    // Vertical: a strip of columns, its rows the items.
    for x0 in (0..w).step_by(STRIP) {
        let s = STRIP.min(w - x0);
        strip.clear();
        for y in 0..h {
            strip.extend_from_slice(&f.data[y * w + x0..y * w + x0 + s]);
        }
        extreme_1d(
            &strip,
            s,
            r,
            pick,
            identity,
            &mut out,
            &mut ahead,
            &mut behind,
        );
        for y in 0..h {
            f.data[y * w + x0..y * w + x0 + s].copy_from_slice(&out[y * s..(y + 1) * s]);
        }
    }
}

/// The running extreme over windows of 2r + 1 items of `src`, an item being `width`
/// consecutive values (extremised element-wise), items cut at both ends; into `out`.
#[allow(clippy::too_many_arguments)]
fn extreme_1d(
    src: &[f32],
    width: usize,
    r: usize,
    pick: impl Fn(f32, f32) -> f32 + Copy,
    identity: f32,
    out: &mut Vec<f32>,
    ahead: &mut Vec<f32>,
    behind: &mut Vec<f32>,
) {
    let n = src.len() / width;
    let k = 2 * r + 1;
    // Padded with r identity items on each side, rounded up to whole blocks.
    let padded = (n + 2 * r).div_ceil(k) * k;
    let item = |i: usize| -> Option<&[f32]> {
        (i >= r && i - r < n).then(|| &src[(i - r) * width..(i - r + 1) * width])
    };
    // Each item's values as whole slices (split, zipped): bounds checked once an item, so
    // the element-wise picks vectorise.
    let merge = |into: &mut [f32], from: &[f32]| {
        for (c, &q) in into.iter_mut().zip(from) {
            *c = pick(*c, q);
        }
    };
    ahead.clear();
    ahead.reserve(padded * width);
    for i in 0..padded {
        let cur = ahead.len();
        match item(i) {
            Some(v) => ahead.extend_from_slice(v),
            None => ahead.resize(cur + width, identity),
        }
        if i % k != 0 {
            let (before, now) = ahead.split_at_mut(cur);
            merge(now, &before[cur - width..]);
        }
    }
    behind.clear();
    behind.resize(padded * width, identity);
    for i in (0..padded).rev() {
        let cur = i * width;
        if let Some(v) = item(i) {
            behind[cur..cur + width].copy_from_slice(v);
        }
        if (i + 1) % k != 0 && i + 1 < padded {
            let (now, after) = behind.split_at_mut(cur + width);
            merge(&mut now[cur..], &after[..width]);
        }
    }
    // Window of output item o is padded items [o, o + 2r]: behind[o] covers to its
    // block's end, ahead[o + 2r] from that block's start (the two overlap or meet).
    out.clear();
    out.reserve(n * width);
    for o in 0..n {
        let (b, a) = (o * width, (o + 2 * r) * width);
        out.extend(
            behind[b..b + width]
                .iter()
                .zip(&ahead[a..a + width])
                .map(|(&x, &y)| pick(x, y)),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_extreme_over_many_strips_equals_the_brute_force_extreme() {
        // Wider and taller than a strip, with a partial last strip both ways.
        let (w, h) = (2 * STRIP + 11, STRIP + 7);
        let f = Field::new(
            w,
            h,
            (0..w * h).map(|i| ((i * 7919) % 101) as f32).collect(),
        );
        for (r, max) in [(1, true), (3, false), (9, true)] {
            let m = box_extreme(&f, r, max);
            for y in (0..h).step_by(5) {
                for x in (0..w).step_by(3) {
                    let mut e = if max { f32::MIN } else { f32::MAX };
                    for yy in y.saturating_sub(r)..(y + r + 1).min(h) {
                        for xx in x.saturating_sub(r)..(x + r + 1).min(w) {
                            let v = f.at(xx, yy);
                            e = if max { e.max(v) } else { e.min(v) };
                        }
                    }
                    assert_eq!(m.at(x, y), e, "r {r} max {max} at {x},{y}");
                }
            }
        }
    }

    #[test]
    fn box_extreme_equals_the_brute_force_extreme() {
        let f = Field::new(7, 5, (0..35).map(|i| ((i * 17) % 11) as f32).collect());
        for r in 0..4 {
            for max in [false, true] {
                let m = box_extreme(&f, r, max);
                for y in 0..5usize {
                    for x in 0..7usize {
                        let mut e = if max { f32::MIN } else { f32::MAX };
                        for yy in y.saturating_sub(r)..(y + r + 1).min(5) {
                            for xx in x.saturating_sub(r)..(x + r + 1).min(7) {
                                let v = f.at(xx, yy);
                                e = if max { e.max(v) } else { e.min(v) };
                            }
                        }
                        assert_eq!(m.at(x, y), e, "r {r} max {max} at {x},{y}");
                    }
                }
            }
        }
    }
}
