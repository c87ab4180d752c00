//! The image a seeded taught run reads ([`probability_field`]): the boundary class on
//! an object's outer rim, next to background, does not count as object (the forest
//! fires on every edge, and counting the rim made contours loose), while the band
//! between touching objects deep inside a colony still does (seeds grow through it).

use topocontour::learn::guide::probability_field;
use topocontour::learn::{Probabilities, BACKGROUND, BOUNDARY, OBJECT};

const W: usize = 96;
const H: usize = 96;

/// Probabilities of three classes with `class(x, y)` certain at each pixel.
fn certain(class: impl Fn(usize, usize) -> u8) -> Probabilities {
    let labels = vec![BACKGROUND, OBJECT, BOUNDARY];
    let mut data = Vec::with_capacity(W * H * 3);
    for y in 0..H {
        for x in 0..W {
            let c = class(x, y);
            data.extend(labels.iter().map(|&l| if l == c { 1.0 } else { 0.0 }));
        }
    }
    Probabilities {
        width: W,
        height: H,
        labels,
        data,
    }
}

#[test]
fn a_boundary_rim_next_to_background_is_not_object() {
    // A disk of object (radius 9) ringed by boundary out to radius 12, on background.
    let p = certain(|x, y| {
        let r = ((x as f64 - 48.0).powi(2) + (y as f64 - 48.0).powi(2)).sqrt();
        if r < 9.0 {
            OBJECT
        } else if r < 12.0 {
            BOUNDARY
        } else {
            BACKGROUND
        }
    });
    let f = probability_field(&p, true);
    // On the ring's outer half, next to background: below the decision level ½.
    for (x, y) in [(59, 48), (48, 59), (37, 48), (48, 37)] {
        assert!(f.at(x, y) < 0.5, "rim at ({x},{y}) reads {}", f.at(x, y));
    }
    // The object itself stays object.
    assert!(f.at(48, 48) > 0.9);
    // Background stays background.
    assert!(f.at(5, 5) < 0.05);
}

#[test]
fn a_boundary_band_inside_a_colony_is_grown_through() {
    // A 64 × 64 colony of two objects split by a 3 px boundary band, on background.
    let p = certain(|x, y| {
        if !(16..80).contains(&x) || !(16..80).contains(&y) {
            BACKGROUND
        } else if (47..50).contains(&x) {
            BOUNDARY
        } else {
            OBJECT
        }
    });
    let f = probability_field(&p, true);
    // The middle of the band, far from background: above ½, so the seeds on both
    // sides grow until they meet.
    for y in [32, 40, 48, 56, 64] {
        assert!(f.at(48, y) > 0.5, "band at y {y} reads {}", f.at(48, y));
    }
    // A run whose topology adapts reads P(object): the band stays background.
    let adaptive = probability_field(&p, false);
    assert!(adaptive.at(48, 48) < 0.05);
}
