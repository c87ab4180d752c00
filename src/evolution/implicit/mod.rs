//! The implicit engine: topology-preserving fast marching on a cut-edge grid, after
//! seed 000 (Bischoff & Kobbelt), §3.2 (fast marching), §4.1 (cut-edge grids), §4.3
//! (choice of cuts) and §4.4 (cut positioning), in 2D.
//!
//! Every pixel has an owner: an object component (a label) or none. The initial region
//! R₀ (pixel centres inside the drawn shapes) gives one label per 4-connected component.
//! Two fronts march by arrival time (one min-heap, first-order upwind eikonal update):
//! - the *growing* front conquers pixels outside R₀ that the image calls object, with
//!   speed = how clearly object they are (the intensity model's score on a smoothed
//!   copy of the image, at least
//!   [`MIN_SPEED`]); background pixels have speed 0 and are never reached;
//! - the *shrinking* front conquers pixels of R₀ that the image calls background, from
//!   the pixels outside R₀, so a wrap rectangle shrinks onto the objects.
//!
//! Before a pixel changes owner it is tested for simplicity (§4.1) with respect to the
//! label it joins or leaves: labels are 4-connected and their complements 8-connected,
//! and in 2D a pixel is simple iff its 4-connectivity number (Yokoi) is 1. The cases of
//! §4.3, with the paper's choices:
//! - simple: conquered as usual;
//! - it would close a hole or cut a label in two (connectivity number ≠ 1): rejected
//!   (as the paper does), until a neighbour changes owner — then it is tried again, so
//!   tendrils left behind by an earlier rejection are eaten back to where they matter.
//!   A ring grown from one seed keeps a one-pixel slit; a wrap around separate blobs
//!   keeps thin bridges between them;
//! - it touches two labels (two fronts collide): it joins the label whose neighbour
//!   arrived first, and every grid edge to a pixel of another label is *cut*. Cut
//!   positions come from the arrival-time slopes on both sides (§4.4), so contact lines
//!   are sub-pixel: with s the fraction from v₀ to v₁, η(v₀) + s·m₀ = η(v₁) + (1 − s)·m₁,
//!   s = (η(v₁) − η(v₀) + m₁) / (m₀ + m₁).
//!
//! Contours (§4.5) come from marching squares over each label's membership, run per
//! label so labels are never joined: saddles are split (4-connectivity), an edge to
//! another label is crossed at its cut (the two labels' contours stand [`CUT_GAP`] apart
//! there, so rings never touch), an edge to an unowned pixel where the moving front is
//! (by arrival time at the current time τ) or where the image crosses the model's
//! threshold, whichever comes first.
//!
//! Frames: one frame advances τ by one unit, so a front at full speed moves one pixel
//! per frame and the app can step the engine like the explicit ones. The run has
//! converged when no pixel can still be reached.
//!
//! Files: `fast_marching` (the two fronts), `simple_point` (the topology test),
//! `cuts` (contact lines between labels), `marching_squares` (contours), and here
//! the state, its initialisation and [`ImplicitEngine`], the engine a run steps.

mod cuts;
mod fast_marching;
mod marching_squares;
mod simple_point;

use super::engine::{Engine, Frame};
use crate::contours::{BroadPhaseKind, ContourSet};
use crate::geometry::{signed_area2, winding_number, Aabb, Point};
use crate::image::field::Field;
use crate::image::{ImageModel, IntensityModel};
use crate::shape::Shape;
use crate::topology::TopologyEvent;
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::sync::OnceLock;

/// Slowest front speed, pixels per frame, for pixels the image does call object (or
/// background for the shrinking front): keeps faint regions reachable in a bounded time.
pub const MIN_SPEED: f64 = 0.05;
/// Distance between the contours of two labels at their contact line, pixels.
pub const CUT_GAP: f64 = 0.1;

const NONE: u32 = u32::MAX;
const FAR: u8 = 0;
const TRIAL: u8 = 1;
const DONE: u8 = 2;
const REJECTED: u8 = 3;
/// Crossings keep this far from pixel centres, so ring vertices stay distinct.
const S_MARGIN: f64 = 0.02;
/// Edge bound of the contour set mirroring the fronts (marching-squares edges are at
/// most √2 pixels).
const IMPLICIT_MAX_EDGE: f64 = 2.0;

/// Fast marching state over the pixel grid.
#[derive(Clone, Debug)]
pub struct Implicit {
    w: usize,
    h: usize,
    /// The image the contour positions are read from, and a smoother copy that decides
    /// speeds (so noise does not stop or leak the fronts).
    image: Vec<f32>,
    /// Speed of the front that may conquer each pixel (0: never), from the smooth copy.
    speed: Vec<f32>,
    model: IntensityModel,
    in_r0: Vec<bool>,
    owner: Vec<u32>,
    /// Arrival time of the front that conquers the pixel (tentative while in the heap).
    t: Vec<f64>,
    state: Vec<u8>,
    heap: BinaryHeap<Reverse<(u64, u32)>>,
    /// Contact point on the edge to the right / below, as a fraction from this pixel.
    cut_x: Vec<f32>,
    cut_y: Vec<f32>,
    tau: f64,
    /// Arrival time of the latest conquest.
    last: f64,
    labels: u32,
    /// Pixels conquered, pixels rejected (they would have changed topology), and edges
    /// cut between labels, so far.
    pub conquered: usize,
    /// Pixels rejected so far (they would have changed topology).
    pub rejected: usize,
    /// Grid edges cut between labels so far.
    pub cuts: usize,
}

impl Implicit {
    /// Rasterises `init` (pixel centres inside any shape) and seeds both fronts.
    /// Speeds come from `image` smoothed twice by [`Field::blur5`].
    pub fn new(image: &Field, model: IntensityModel, init: &[Shape]) -> Self {
        let (w, h) = (image.width, image.height);
        let mut in_r0 = vec![false; w * h];
        for s in init {
            rasterise(s, w, h, &mut in_r0);
        }
        let mut e = Implicit {
            w,
            h,
            image: image.data.clone(),
            speed: Vec::new(),
            model,
            in_r0,
            owner: vec![NONE; w * h],
            t: vec![f64::INFINITY; w * h],
            state: vec![FAR; w * h],
            heap: BinaryHeap::new(),
            cut_x: vec![f32::NAN; w * h],
            cut_y: vec![f32::NAN; w * h],
            tau: 0.0,
            last: 0.0,
            labels: 0,
            conquered: 0,
            rejected: 0,
            cuts: 0,
        };
        e.label_components();
        let smooth = image.blur5().blur5();
        e.speed = (0..w * h)
            .map(|i| {
                let sc = model.score(smooth.data[i] as f64);
                let s = if e.in_r0[i] { -sc } else { sc };
                if s > 0.0 {
                    s.clamp(MIN_SPEED, 1.0) as f32
                } else {
                    0.0
                }
            })
            .collect();
        for i in 0..w * h {
            if e.eligible(i) && e.neighbours(i).any(|u| e.known(u, e.in_r0[i]).is_finite()) {
                e.update(i);
            }
        }
        e
    }

    /// Number of object components (labels).
    pub fn label_count(&self) -> u32 {
        self.labels
    }

    /// Current time τ.
    pub fn time(&self) -> f64 {
        self.tau
    }

    /// Whether no pixel can still be reached.
    pub fn is_done(&self) -> bool {
        self.heap.is_empty()
    }

    fn label_components(&mut self) {
        let mut stack = Vec::new();
        for i in 0..self.w * self.h {
            if !self.in_r0[i] || self.owner[i] != NONE {
                continue;
            }
            let l = self.labels;
            self.labels += 1;
            self.owner[i] = l;
            stack.push(i);
            while let Some(j) = stack.pop() {
                for u in self.neighbours(j) {
                    if self.in_r0[u] && self.owner[u] == NONE {
                        self.owner[u] = l;
                        stack.push(u);
                    }
                }
            }
        }
    }

    /// 4-neighbours inside the image (a fixed array and its length: no allocation).
    #[inline]
    fn neighbours4(&self, i: usize) -> ([usize; 4], usize) {
        let (x, y, w, h) = (i % self.w, i / self.w, self.w, self.h);
        let mut out = [0; 4];
        let mut n = 0;
        for (ok, j) in [
            (x + 1 < w, i + 1),
            (x > 0, i.wrapping_sub(1)),
            (y + 1 < h, i + w),
            (y > 0, i.wrapping_sub(w)),
        ] {
            if ok {
                out[n] = j;
                n += 1;
            }
        }
        (out, n)
    }

    /// 4-neighbours inside the image.
    #[inline]
    fn neighbours(&self, i: usize) -> impl Iterator<Item = usize> {
        let (a, n) = self.neighbours4(i);
        a.into_iter().take(n)
    }

    /// Speed of the front that may conquer pixel `i` (0: never).
    #[inline]
    fn speed(&self, i: usize) -> f64 {
        self.speed[i] as f64
    }

    /// Whether a front may still conquer `i`.
    #[inline]
    fn eligible(&self, i: usize) -> bool {
        let want_owner = self.in_r0[i]; // shrink takes owned R₀ pixels, grow takes unowned others
        (self.owner[i] != NONE) == want_owner
            && self.state[i] != DONE
            && self.state[i] != REJECTED
            && self.speed(i) > 0.0
    }

    /// Whether pixel (x, y) belongs to some label.
    pub fn owned(&self, x: usize, y: usize) -> bool {
        self.owner[y * self.w + x] != NONE
    }
}

/// The implicit engine as an [`Engine`]: the fronts, and the contours extracted from
/// them. The contour set is built only when asked for (a run that marches to its end
/// builds it once); each frame's figures come from the rings directly.
#[derive(Clone)]
pub struct ImplicitEngine {
    state: Implicit,
    domain: Aabb,
    broad_phase: BroadPhaseKind,
    rings: Vec<Vec<Point>>,
    set: OnceLock<ContourSet>,
}

impl ImplicitEngine {
    /// The engine marching from the shapes `init` under the global model of `image` (on
    /// its full-resolution level), its contours in `domain`.
    pub fn new(
        image: &ImageModel,
        init: &[Shape],
        domain: Aabb,
        broad_phase: BroadPhaseKind,
    ) -> Self {
        let state = Implicit::new(image.fine(), image.global(), init);
        let rings = state.rings();
        ImplicitEngine {
            state,
            domain,
            broad_phase,
            rings,
            set: OnceLock::new(),
        }
    }

    /// The fast marching state.
    pub fn state(&self) -> &Implicit {
        &self.state
    }

    /// Marches the fronts to time `until` and extracts the rings.
    fn march(&mut self, index: usize, until: f64) -> Frame {
        debug_assert!(until.is_finite());
        let before = self.state.conquered;
        self.state.advance(until);
        let moved = self.state.conquered - before;
        self.rings = self.state.rings();
        self.set = OnceLock::new();
        let vertices: usize = self.rings.iter().map(Vec::len).sum();
        let active = moved as f64 / vertices.max(1) as f64;
        Frame {
            // A frame is one time unit: after a long advance, count the units it took.
            index: (index + 1).max(self.state.time().ceil() as usize),
            level: 0,
            events: Vec::new(),
            area: self.rings.iter().map(|r| 0.5 * signed_area2(r)).sum(),
            vertices,
            contours: self.rings.len(),
            mean_speed: active,
            energy: 0.0,
            active_share: active,
            converged: self.state.is_done(),
            motions: Vec::new(),
        }
    }

    fn build(&self) -> ContourSet {
        let mut set =
            ContourSet::with_broad_phase(self.domain, IMPLICIT_MAX_EDGE, self.broad_phase);
        for ring in &self.rings {
            // Rings from marching squares are disjoint by construction; a refusal here
            // would be a bug, never silently different output in release.
            let added = set.add_ring(ring);
            debug_assert!(added.is_ok(), "implicit ring refused: {added:?}");
        }
        set
    }
}

impl Engine for ImplicitEngine {
    /// The fronts march one time unit.
    fn step(&mut self, index: usize, _: usize) -> Frame {
        let until = self.state.time() + 1.0;
        self.march(index, until)
    }
    /// No intermediate contours are needed: march to the end, extract once.
    fn finish(&mut self, index: usize, frames_left: usize) -> Option<Frame> {
        let until = self.state.time() + frames_left as f64;
        Some(self.march(index, until))
    }
    fn refine(&mut self, _: usize) -> Vec<TopologyEvent> {
        Vec::new()
    }
    fn contours(&self) -> &ContourSet {
        self.set.get_or_init(|| self.build())
    }
    fn contours_mut(&mut self) -> &mut ContourSet {
        if self.set.get().is_none() {
            let set = self.build();
            self.set = OnceLock::from(set);
        }
        self.set.get_mut().expect("built above")
    }
    fn settled(&self) -> Option<bool> {
        Some(self.state.is_done())
    }
    /// Cut grid edges plus rejected pixels.
    fn held_contacts(&self, _: usize) -> usize {
        self.state.cuts + self.state.rejected
    }
    fn set_forces(&mut self, _: super::forces::ForceWeights, _: f64) {}
    fn nucleate(&mut self, _: usize) -> Vec<TopologyEvent> {
        Vec::new()
    }
    /// Contours extracted from the grid do not move by hand.
    fn hand_drag(&mut self, _: u32, _: Point, _: usize) -> (Vec<TopologyEvent>, Option<u32>) {
        (Vec::new(), None)
    }
    /// Contours extracted from the grid do not move by hand.
    fn brush(&mut self, _: Point, _: Point, _: f64, _: usize) -> Vec<TopologyEvent> {
        Vec::new()
    }
}

/// Marks the pixels whose centres lie inside `shape`.
fn rasterise(shape: &Shape, w: usize, h: usize, out: &mut [bool]) {
    let ring = shape.ring(1.0);
    let b = crate::geometry::Aabb::of(&ring);
    let x0 = (b.min.x - 0.5).ceil().max(0.0) as usize;
    let y0 = (b.min.y - 0.5).ceil().max(0.0) as usize;
    let x1 = ((b.max.x - 0.5).floor().max(-1.0) + 1.0).min(w as f64) as usize;
    let y1 = ((b.max.y - 0.5).floor().max(-1.0) + 1.0).min(h as f64) as usize;
    for y in y0..y1 {
        for x in x0..x1 {
            let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
            let inside = match shape {
                Shape::Disk { center, radius } => p.dist(*center) < *radius,
                Shape::Rect { min, max } => {
                    p.x > min.x && p.x < max.x && p.y > min.y && p.y < max.y
                }
                Shape::Polygon(_) => winding_number(&ring, p) != 0,
            };
            if inside {
                out[y * w + x] = true;
            }
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// A 0.5-grey engine whose label 0 owns the pixels `owned`.
    pub(crate) fn engine(w: usize, h: usize, owned: &[(usize, usize)]) -> Implicit {
        let image = Field::new(w, h, vec![0.5; w * h]);
        let mut e = Implicit::new(
            &image,
            IntensityModel {
                object: 0.0,
                background: 1.0,
            },
            &[],
        );
        for &(x, y) in owned {
            e.owner[y * w + x] = 0;
        }
        e
    }
}
