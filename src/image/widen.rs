//! The label images a tracked movie reports: each cell's pixels widened by one layer,
//! then up the image's slope to its edge.
//!
//! An evolved outline settles where the region force changes sign: half-way between the
//! level inside and the level of the local statistics outside. Under optics blur that
//! level lies inside the cell's edge — in phase contrast the halo is clipped to the
//! background grey first, so the outline stops short of the steep rise into the halo;
//! a nucleus with a dimmer rim does the same. Tracked masks covered 74–88 % of the true
//! area on synthetic rods with exact truth, and the curated masks of real E. coli movies
//! lie about a pixel further out. The outlines themselves stay where the engine put
//! them: the neck and division rules were fitted on them, and touching cells' outlines
//! must not cross. So only the reported pixels move, in two steps; in both a pixel two
//! cells reach stays unlabelled, and no pixel changes cell.
//!
//! First every unlabelled pixel whose labelled 4-neighbours all belong to one cell joins
//! it ([`widened`]). One layer, for every modality: on 82 synthetic movies, three real or real-shaped
//! bacteria movies, sim_plus_01 and a real HeLa movie it raised TRA and CHOTA or kept
//! them, and raised SEG everywhere but on our own synthetic nuclei (truth ending where
//! the blurred edge is half-way, no dimmer rim: 0.97 → 0.87). A second layer lowered
//! SEG on the real bacteria, and widening only to where the image crosses half-way to
//! the outside level moved too little there (docs/decisions.md, 2026-12-06, seventh
//! session).
//!
//! How far the edge lies beyond that layer depends on the camera: in an 8-bit movie
//! whose cells are clipped to black, the intensity rises slowly from the flat inside,
//! and the steepest rise (the edge a curator traces) lay a pixel beyond the widened
//! masks, which then covered 79 % of the curated cells' area; in a 16-bit movie it lay
//! at them. So the cells then climb the edge ([`to_edges`]): an unlabelled pixel one
//! cell reaches joins it while the image's gradient magnitude (Gaussian derivatives at
//! [`EDGE_SIGMA`]) is larger there than at the cell's pixels beside it, layer by layer
//! (at most [`EDGE_LAYERS`]); past the edge the slope falls, and the climb stops by itself
//! (docs/decisions.md, 2026-12-07, thirteenth session).
//! Still images keep their outlines' pixels: there one layer lowered the Dice of dense
//! fluorescent nuclei.

use super::Field;
use crate::learn::filters::{kernel, separable, Order, Plane};

/// The scale of the gradient the cells climb, in pixels: about the blur of a
/// microscope's edge, over which single pixels' noise averages out (at σ = 1 the noise
/// drew sim_plus_01's nuclei past their edge: SEG 0.953 → 0.943; at 1.5 it stays).
pub const EDGE_SIGMA: f64 = 1.5;

/// At most this many layers climbed: a cell's edge lies a pixel or two out, never
/// farther (the climb stopped by itself within 5 layers on the real movies).
pub const EDGE_LAYERS: usize = 5;

/// `labels` (0 outside every cell, rows of `image`'s width) as a movie reports them:
/// widened by one layer ([`widened`]), then each cell up the slope of `image` to its
/// edge (see the module doc).
pub fn to_edges(labels: &[u32], image: &Field) -> Vec<u32> {
    let w = image.width;
    let mut out = widened(labels, w);
    if out.len() != image.data.len() || !out.iter().any(|&l| l != 0) {
        return out;
    }
    let slope = gradient_magnitude(image, EDGE_SIGMA);
    for _ in 0..EDGE_LAYERS {
        let mut moved = false;
        let next = layer(&out, w, |i, cell| {
            let beside = cell.iter().map(|&j| slope[j]).sum::<f32>() / cell.len() as f32;
            let up = slope[i] > beside;
            moved |= up;
            up
        });
        out = next;
        if !moved {
            break;
        }
    }
    out
}

/// The magnitude of `image`'s gradient by derivatives of the Gaussian at `sigma`.
fn gradient_magnitude(image: &Field, sigma: f64) -> Vec<f32> {
    let plane = Plane {
        width: image.width,
        height: image.height,
        data: image.data.clone(),
    };
    let (d, g) = (kernel(sigma, Order::First), kernel(sigma, Order::Smooth));
    let gx = separable(&plane, &d, &g);
    let gy = separable(&plane, &g, &d);
    gx.data
        .iter()
        .zip(&gy.data)
        .map(|(x, y)| (x * x + y * y).sqrt())
        .collect()
}

/// `labels` (0 outside every cell, rows of `width`) with each cell widened by one layer
/// of the unlabelled pixels next to it (see the module doc).
pub fn widened(labels: &[u32], width: usize) -> Vec<u32> {
    layer(labels, width, |_, _| true)
}

/// `labels` (rows of `width`) with each unlabelled pixel `i` whose labelled 4-neighbours
/// `cell` all belong to one cell given to it when `take(i, cell)`.
fn layer(labels: &[u32], width: usize, mut take: impl FnMut(usize, &[usize]) -> bool) -> Vec<u32> {
    let w = width;
    let h = labels.len().checked_div(w).unwrap_or(0);
    let mut out = labels.to_vec();
    for i in (0..w * h).filter(|&i| labels[i] == 0) {
        let (x, y) = (i % w, i / w);
        let near = [
            (x > 0).then(|| i - 1),
            (x + 1 < w).then(|| i + 1),
            (y > 0).then(|| i - w),
            (y + 1 < h).then(|| i + w),
        ];
        let mut cell = [0usize; 4];
        let mut n = 0;
        let mut one = None;
        let mut sole = true;
        for j in near.into_iter().flatten().filter(|&j| labels[j] != 0) {
            sole &= one.is_none_or(|l| l == labels[j]);
            one = Some(labels[j]);
            cell[n] = j;
            n += 1;
        }
        if let (Some(l), true) = (one, sole) {
            if take(i, &cell[..n]) {
                out[i] = l;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_cell_takes_the_free_pixels_next_to_it_and_none_another_reaches() {
        // Two cells a pixel apart on one row, one alone below.
        #[rustfmt::skip]
        let labels = vec![
            0, 0, 0, 0, 0, 0, 0,
            0, 1, 1, 0, 2, 2, 0,
            0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 0, 0, 0, 0,
            0, 0, 0, 3, 0, 0, 0,
        ];
        #[rustfmt::skip]
        let expected = vec![
            0, 1, 1, 0, 2, 2, 0,
            1, 1, 1, 0, 2, 2, 2,
            0, 1, 1, 0, 2, 2, 0,
            0, 0, 0, 3, 0, 0, 0,
            0, 0, 3, 3, 3, 0, 0,
        ];
        assert_eq!(widened(&labels, 7), expected);
        // No cell, nothing to widen; an empty raster stays empty.
        assert_eq!(widened(&[0; 6], 3), vec![0; 6]);
        assert!(widened(&[], 0).is_empty());
    }

    /// A dark band on a bright ground whose intensity rises from the flat inside (|x − 20|
    /// ≤ 5) to the ground with its steepest rise at |x − 20| = 8, as an edge blurred at
    /// σ 1.5 (a logistic step of about that width).
    fn band() -> Field {
        let (w, h) = (40, 12);
        let step = |d: f64| 1.0 / (1.0 + (-(d - 8.0) / 0.9).exp());
        let data = (0..w * h)
            .map(|i| {
                let d = ((i % w) as f64 - 20.0).abs();
                if d <= 5.0 {
                    0.0
                } else {
                    step(d) as f32
                }
            })
            .collect();
        Field::new(w, h, data)
    }

    #[test]
    fn a_cell_climbs_to_the_steepest_rise_of_its_edge_and_stops_there() {
        let image = band();
        let w = image.width;
        let inside: Vec<u32> = (0..image.data.len())
            .map(|i| u32::from(((i % w) as i64 - 20).abs() <= 5))
            .collect();
        let out = to_edges(&inside, &image);
        for (i, &l) in out.iter().enumerate() {
            let d = ((i % w) as i64 - 20).abs();
            assert_eq!(l, u32::from(d <= 8), "pixel {i} at {d} from the middle");
        }
        // On a flat image nothing climbs: the one layer only.
        let flat = Field::new(w, image.height, vec![0.5; image.data.len()]);
        assert_eq!(to_edges(&inside, &flat), widened(&inside, w));
    }

    #[test]
    fn two_cells_climbing_toward_each_other_leave_the_pixels_both_reach() {
        // The left half of the band is one cell, the right half another: a pixel of the
        // middle column both reach stays free, and neither takes the other's pixels.
        let image = band();
        let w = image.width;
        let cells: Vec<u32> = (0..image.data.len())
            .map(|i| match i % w {
                15..=19 => 1,
                21..=25 => 2,
                _ => 0,
            })
            .collect();
        let out = to_edges(&cells, &image);
        for (i, &l) in out.iter().enumerate() {
            match i % w {
                20 => assert_eq!(l, 0),
                12..=19 => assert_eq!(l, 1),
                21..=28 => assert_eq!(l, 2),
                _ => assert_eq!(l, 0),
            }
        }
    }
}
