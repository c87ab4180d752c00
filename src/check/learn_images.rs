//! Test images for the pixel classifier: a phase-contrast-like colony of touching rods
//! whose contacts carry no intensity step (only a faint ridge), with its instance
//! labels, and the strokes a simulated user paints on such labels.

use super::Rng;

/// A `w` × `h` colony: rows of rods `len` × `width` px laid end to end and side by side
/// with no gap, dark (0.3) on grey (0.6), a bright halo round the colony, a faint ridge
/// (0.36) on every contact between rods, and noise of σ 0.02. Returns the image and
/// the instance labels (0 background, rods 1..).
pub fn touching_rods(w: usize, h: usize, len: usize, width: usize) -> (Vec<f32>, Vec<u32>) {
    let mut rng = Rng(7);
    let mut labels = vec![0u32; w * h];
    let (x0, y0) = (w / 6, h / 6);
    let (x1, y1) = (w - w / 6, h - h / 6);
    let mut next = 1;
    let mut y = y0;
    let mut row = 0;
    while y + width <= y1 {
        // Alternate rows start half a rod later, like a growing colony.
        let mut x = x0 + (row % 2) * len / 2;
        while x + len <= x1 {
            for yy in y..y + width {
                for xx in x..x + len {
                    labels[yy * w + xx] = next;
                }
            }
            next += 1;
            x += len;
        }
        y += width;
        row += 1;
    }
    let inside = |x: isize, y: isize| {
        x >= 0
            && y >= 0
            && (x as usize) < w
            && (y as usize) < h
            && labels[y as usize * w + x as usize] > 0
    };
    let mut image = vec![0.6f32; w * h];
    for y in 0..h as isize {
        for x in 0..w as isize {
            let i = y as usize * w + x as usize;
            let l = labels[i];
            let v = if l > 0 {
                let contact = [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|&(dx, dy)| {
                    let (nx, ny) = (x + dx, y + dy);
                    inside(nx, ny) && labels[ny as usize * w + nx as usize] != l
                });
                if contact {
                    0.36
                } else {
                    0.3
                }
            } else {
                // The halo: brighter within 3 px of the colony.
                let near = (-3..=3).any(|dy| (-3..=3).any(|dx| inside(x + dx, y + dy)));
                if near {
                    0.8
                } else {
                    0.6
                }
            };
            image[i] = v + 0.02 * (rng.unit() as f32 - 0.5) * 3.46;
        }
    }
    (image, labels)
}

/// Strokes on instance labels (0 none, 1 background, 2 object, 3 boundary), as a user
/// paints them: an object stroke along the middle row of up to `objects` objects, three
/// background strokes away from every object, and, with `boundary`, the contact pixels
/// (a 3 × 3 neighbourhood holding two labels) of every other contact.
pub fn strokes_for(labels: &[u32], w: usize, h: usize, objects: usize, boundary: bool) -> Vec<u8> {
    let mut s = vec![0u8; w * h];
    let n = labels.iter().copied().max().unwrap_or(0) as usize;
    for l in 1..=n.min(objects) {
        // Every object an even share apart: l · n / objects.
        let id = (l * n / objects.min(n)).max(1) as u32;
        let px: Vec<usize> = (0..w * h).filter(|&i| labels[i] == id).collect();
        let Some(&first) = px.first() else { continue };
        let (ymin, ymax) = (first / w, px[px.len() - 1] / w);
        let mid = (ymin + ymax) / 2;
        for &i in &px {
            let (x, y) = (i % w, i / w);
            let interior = (x > 0 && labels[i - 1] == id) && (x + 1 < w && labels[i + 1] == id);
            if y == mid && interior {
                s[i] = 2;
            }
        }
    }
    let far = |x: usize, y: usize| {
        (y.saturating_sub(6)..(y + 7).min(h))
            .all(|yy| (x.saturating_sub(6)..(x + 7).min(w)).all(|xx| labels[yy * w + xx] == 0))
    };
    for k in 0..3 {
        let y = (2 + k * 3) * h / 12;
        let x0 = w / 12;
        for x in x0..(x0 + w / 4).min(w) {
            for yy in [y, y + 1] {
                if yy < h && far(x, yy) {
                    s[yy * w + x] = 1;
                }
            }
        }
    }
    if boundary {
        let mut count = 0usize;
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                let i = y * w + x;
                let here = labels[i];
                let two = (y - 1..=y + 1).any(|yy| {
                    (x - 1..=x + 1).any(|xx| {
                        let o = labels[yy * w + xx];
                        o != here && o > 0 && here > 0
                    })
                });
                if two {
                    // Every other contact pixel's run of 8: about half the contacts.
                    if (count / 8).is_multiple_of(2) {
                        s[i] = 3;
                    }
                    count += 1;
                }
            }
        }
    }
    s
}
