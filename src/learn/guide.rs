//! What the contours read from a trained classifier: a probability image in place of
//! the intensity (object bright, decision level ½, no local levels), and the seeds of
//! an instance run.
//!
//! Two images, one per kind of run, because the boundary class must act in two ways:
//! - a run whose topology adapts (a wrap) reads P(object): the boundary between touching
//!   objects counts as background, so the fronts stop on both sides of it and the wrap
//!   splits the colony into one contour per object;
//! - a run that keeps its topology (preserve or implicit mode, seeds) reads
//!   P(object) + P(boundary) where background is far: each seed grows through the
//!   boundary band until it meets its neighbour, where the engine holds the two apart,
//!   so the objects keep their full area; next to background the boundary class (which
//!   the forest also finds on every outer rim) counts only in part, so contours do not
//!   sit loose outside the objects ([`probability_field`]).
//!
//! The seeds ([`seeds`]) are the connected interiors of P(object) > max(P(background),
//! P(boundary)): the boundary band cuts touching objects apart. A wrap around several
//! of them starts from them ([`start_shapes`]), and a taught run has one pyramid level
//! ([`ONE_LEVEL`]).

use super::Probabilities;
use super::{BACKGROUND, BOUNDARY, OBJECT};
use crate::evolution::{EvolveError, Evolver, Mode, Params, Polarity};
use crate::geometry::Point;
use crate::image::{Field, Modality};
use crate::shape::Shape;
use std::sync::Arc;

/// A run guided by a classifier: the probabilities, the image the engine reads and the
/// parameters it reads it with.
#[derive(Clone, Debug)]
pub struct Guide {
    /// Per pixel class probabilities.
    pub probabilities: Probabilities,
    /// The image the engine reads ([`probability_field`]).
    pub field: Field,
    /// `params` with objects bright, the generic image kind and no local levels: the
    /// decision level is probability ½.
    pub params: Params,
    /// Whether the objects are dark or bright in the image itself (the user's
    /// polarity): what the run's edge stage reads ([`crate::image::edges`]).
    pub polarity: Polarity,
}

impl Guide {
    /// The guide of known probabilities.
    pub fn new(probabilities: Probabilities, params: &Params) -> Self {
        // The user's polarity, before the run's own (objects bright) replaces it.
        let polarity = params.polarity;
        let field = probability_field(&probabilities, params.mode != Mode::Adaptive);
        let params = Params {
            polarity: Polarity::Bright,
            modality: Modality::Generic,
            local: false,
            coarsest_side: ONE_LEVEL,
            ..params.clone()
        };
        Guide {
            probabilities,
            field,
            params,
            polarity,
        }
    }

    /// The run this guide drives from `shapes` on `image` (the image the probabilities
    /// are of), in `mode`: it reads [`Guide::field`], cuts its objects at the septa
    /// P(boundary) shows when it finishes ([`Evolver::cut_when_finished`]), then settles
    /// their edges on the image ([`Evolver::edges_when_finished`]). The one way a taught
    /// run is made: a job, the app and its side-by-side run alike.
    pub fn evolver(
        &self,
        image: Arc<Field>,
        shapes: &[Shape],
        mode: Mode,
    ) -> Result<Evolver, EvolveError> {
        let params = Params {
            mode,
            ..self.params.clone()
        };
        let mut ev = Evolver::new(&self.field, shapes, params)?;
        let p = &self.probabilities;
        ev.cut_when_finished(Arc::new(Field::new(p.width, p.height, p.of(BOUNDARY))));
        ev.edges_when_finished(image, self.polarity);
        Ok(ev)
    }
}

/// The coarsest side of a taught run's pyramid: larger than any image, so the run has
/// one level. The probabilities are already smooth, and a coarser copy would average
/// the thin boundary band between touching objects away (docs/decisions.md,
/// 2026-12-02: mean SEG of the instance run 0.688 with the pyramid, 0.732 without).
pub const ONE_LEVEL: usize = 65_536;

/// The image a run reads: P(object) when `keeps_topology` is false, else
/// P(object) + P(boundary) · (1 − the background's share within
/// [`NEAR_BACKGROUND_SIGMA`]).
///
/// Why the weight: the forest learns the boundary strokes as "an edge", and fires on
/// every object's outer rim too, where it borders background. Counted as object there
/// (the former 1 − P(background)), the rim made contours loose and let seeds grow
/// across a narrow gap; deep inside a colony, background is far and the band between
/// touching objects still counts fully, so the seeds grow through it until they meet
/// (docs/decisions.md, 2026-12-02: mean SEG of the instance run 0.7351 → 0.7500 and
/// 0.7823 → 0.8000 on two simulated stroke sets).
pub fn probability_field(p: &Probabilities, keeps_topology: bool) -> Field {
    let data = if keeps_topology {
        let near = near_background(p);
        let (po, pd) = (p.of(OBJECT), p.of(BOUNDARY));
        po.iter()
            .zip(&pd)
            .zip(&near)
            .map(|((o, d), n)| o + d * (1.0 - n.clamp(0.0, 1.0)))
            .collect()
    } else {
        p.of(OBJECT)
    };
    Field::new(p.width, p.height, data)
}

/// The Gaussian σ (pixels) of the background's share around a pixel in
/// [`probability_field`]: about an object's radius, so the rim of an object next to
/// background reads about half background and a band inside a colony about none
/// (mean SEG flat within ±0.003 for σ 8–16, lower at 2–4; docs/decisions.md).
pub const NEAR_BACKGROUND_SIGMA: f64 = 8.0;

/// P(background) smoothed with a Gaussian of σ [`NEAR_BACKGROUND_SIGMA`] (borders
/// reflect).
fn near_background(p: &Probabilities) -> Vec<f32> {
    use super::filters::{kernel, separable, Order, Plane};
    let k = kernel(NEAR_BACKGROUND_SIGMA, Order::Smooth);
    let pb = Plane {
        width: p.width,
        height: p.height,
        data: p.of(BACKGROUND),
    };
    separable(&pb, &k, &k).data
}

/// Fewest pixels an object's interior needs to become a seed (scikit-image's
/// trainable segmentation as `shared/tools/peer.py` runs it drops objects under 10 px).
pub const MIN_SEED_PIXELS: usize = 10;

/// One seed per connected interior (4-connected pixels where the object class wins) of
/// at least [`MIN_SEED_PIXELS`]: its outline, or a disk where the outline is too small.
pub fn seeds(p: &Probabilities) -> Vec<Shape> {
    interiors(p).into_iter().map(|(s, _)| s).collect()
}

/// [`seeds`], each with its most interior pixel's centre (a point inside it and in no
/// other seed).
pub fn interiors(p: &Probabilities) -> Vec<(Shape, Point)> {
    let (w, h) = (p.width, p.height);
    let (po, pb, pd) = (p.of(OBJECT), p.of(BACKGROUND), p.of(BOUNDARY));
    let core: Vec<bool> = (0..w * h).map(|i| po[i] > pb[i] && po[i] > pd[i]).collect();
    let mut label = vec![0u32; w * h];
    let mut parts: Vec<(usize, usize)> = Vec::new(); // (first pixel, size)
    let mut stack = Vec::new();
    for start in 0..w * h {
        if !core[start] || label[start] != 0 {
            continue;
        }
        let l = parts.len() as u32 + 1;
        label[start] = l;
        stack.push(start);
        let mut size = 0;
        while let Some(i) = stack.pop() {
            size += 1;
            for j in crate::image::field::neighbours4(i, w, h) {
                if core[j] && label[j] == 0 {
                    label[j] = l;
                    stack.push(j);
                }
            }
        }
        parts.push((start, size));
    }
    let dist = crate::image::distance::distance_transform(&core, w, h);
    // Per part, its most interior pixel: the outline is traced from there.
    let mut deepest = vec![usize::MAX; parts.len()];
    for (i, &l) in label.iter().enumerate() {
        if l > 0 {
            let d = &mut deepest[l as usize - 1];
            if *d == usize::MAX || dist.data[i] > dist.data[*d] {
                *d = i;
            }
        }
    }
    parts
        .iter()
        .zip(&deepest)
        .enumerate()
        .filter(|(_, (&(_, size), _))| size >= MIN_SEED_PIXELS)
        .map(|(k, (_, &at))| {
            let center = Point::new((at % w) as f64 + 0.5, (at / w) as f64 + 0.5);
            let shape = crate::image::outline::basin_outline(&label, k as u32 + 1, at, w, h)
                .map(Shape::Polygon)
                .unwrap_or(Shape::Disk {
                    center,
                    radius: (0.5 * dist.data[at] as f64).max(1.0),
                });
            (shape, center)
        })
        .collect()
}

/// The shapes a taught run whose topology adapts starts from: each of the user's
/// rectangles and disks that holds two or more of the classifier's objects (their
/// [`interiors`]' points) gives way to those objects' interiors, the others stay.
///
/// Why: a wrap means "everything in here", and with a classifier the objects in there
/// are known. A front shrinking from the rectangle stops on the outside of a colony and
/// cannot follow the thin boundary band between touching cells inwards (it would have
/// to push a finger down each band against its own smoothing), so the boundary strokes
/// would be lost; started from the interiors, the fronts grow out to the objects'
/// edges and meet only where the classifier joins two objects. A click inside one
/// object holds at most one interior and stays. Polygons stay too: the seeds a session
/// records are polygons, so a replay starts from exactly the shapes it saved.
///
/// Returns the shapes and, per interior, whether it is among them.
pub fn start_shapes(user: &[Shape], interiors: &[(Shape, Point)]) -> (Vec<Shape>, Vec<bool>) {
    let mut taken = vec![false; interiors.len()];
    let mut out = Vec::new();
    for shape in user {
        let held: Vec<usize> = match shape {
            Shape::Polygon(_) => Vec::new(),
            _ => {
                let ring = shape.ring(1.0);
                (0..interiors.len())
                    .filter(|&k| !taken[k])
                    .filter(|&k| crate::geometry::winding_number(&ring, interiors[k].1) != 0)
                    .collect()
            }
        };
        if held.len() >= 2 {
            for k in held {
                taken[k] = true;
                out.push(interiors[k].0.clone());
            }
        } else {
            out.push(shape.clone());
        }
    }
    (out, taken)
}

/// Whether a taught run's wraps and rectangles give way to the classifier's objects
/// ([`start_shapes`]): in the engines that let one front become many objects. Preserve
/// and implicit keep the user's shapes as the objects, one each.
pub fn gives_way(mode: Mode) -> bool {
    matches!(mode, Mode::Adaptive | Mode::Track)
}

/// The shapes a run guided by `guide` starts from, the user's shapes given: what a
/// taught [`crate::job::Job`] starts from before it adds found seeds (the app's runs).
pub fn taught_shapes(user: &[Shape], guide: &Guide) -> Vec<Shape> {
    if gives_way(guide.params.mode) {
        start_shapes(user, &interiors(&guide.probabilities)).0
    } else {
        user.to_vec()
    }
}
