//! The Euclidean distance transform, by Felzenszwalb and Huttenlocher's lower envelope
//! of parabolas ("Distance Transforms of Sampled Functions", 2012, §2), one axis at a
//! time.

use super::field::Field;

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
}
