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

use super::field::Field;
use super::forces::IntensityModel;
use super::init::Shape;
use crate::geometry::{orient, winding_number, Point};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};

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
    pub rejected: usize,
    pub cuts: usize,
}

#[inline]
fn key(t: f64) -> u64 {
    // Non-negative floats order like their bit patterns.
    t.to_bits()
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

    /// Known arrival time at `u` for the front conquering pixels with `in_r0 == shrink`.
    #[inline]
    fn known(&self, u: usize, shrink: bool) -> f64 {
        if shrink {
            if !self.in_r0[u] && self.owner[u] == NONE {
                0.0 // background from the start: a source
            } else if self.in_r0[u] && self.state[u] == DONE {
                self.t[u]
            } else {
                f64::INFINITY
            }
        } else if self.in_r0[u] && self.owner[u] != NONE {
            0.0 // the initial region: a source
        } else if !self.in_r0[u] && self.state[u] == DONE {
            self.t[u]
        } else {
            f64::INFINITY
        }
    }

    /// First-order upwind eikonal update of pixel `i`; queues it if its time fell.
    fn update(&mut self, i: usize) {
        let shrink = self.in_r0[i];
        let (x, y) = (i % self.w, i / self.w);
        let get = |ok: bool, j: usize| {
            if ok {
                self.known(j, shrink)
            } else {
                f64::INFINITY
            }
        };
        let a = get(x > 0, i.wrapping_sub(1)).min(get(x + 1 < self.w, i + 1));
        let b = get(y > 0, i.wrapping_sub(self.w)).min(get(y + 1 < self.h, i + self.w));
        let f = 1.0 / self.speed(i);
        let t = if (a - b).abs() >= f || !a.is_finite() || !b.is_finite() {
            a.min(b) + f
        } else {
            0.5 * (a + b + (2.0 * f * f - (a - b) * (a - b)).sqrt())
        };
        if t < self.t[i] {
            self.t[i] = t;
            self.state[i] = TRIAL;
            self.heap.push(Reverse((key(t), i as u32)));
        }
    }

    /// Conquers every pixel whose arrival time is at most `until`, then sets τ to it.
    pub fn advance(&mut self, until: f64) {
        while let Some(&Reverse((k, i))) = self.heap.peek() {
            let t = f64::from_bits(k);
            if t > until {
                break;
            }
            self.heap.pop();
            let i = i as usize;
            if self.state[i] != TRIAL || self.t[i] != t || !self.eligible(i) {
                continue; // stale entry
            }
            if self.in_r0[i] {
                self.shrink(i);
            } else {
                self.grow(i);
            }
        }
        // Once nothing is left to reach, time stops at the last conquest.
        self.tau = if self.heap.is_empty() {
            self.tau.max(self.last)
        } else {
            until
        };
    }

    fn grow(&mut self, i: usize) {
        // The label whose neighbour arrived first (§4.3, case nint ≥ 2).
        let mut best = (f64::INFINITY, NONE);
        for u in self.neighbours(i) {
            let l = self.owner[u];
            let t = self.known(u, false);
            if l != NONE && t < best.0 {
                best = (t, l);
            }
        }
        let a = best.1;
        if a == NONE || self.connectivity(i, a) != 1 {
            self.reject(i);
            return;
        }
        self.owner[i] = a;
        self.settle(i);
        let (nbrs, k) = self.neighbours4(i);
        for &u in &nbrs[..k] {
            if self.owner[u] != NONE && self.owner[u] != a {
                self.place_cut(i, u);
            }
        }
    }

    /// Pixel `i` has changed owner at its arrival time: its front moves on to the
    /// neighbours on the same side of R₀, and rejected pixels around it are retried.
    fn settle(&mut self, i: usize) {
        self.state[i] = DONE;
        self.conquered += 1;
        self.last = self.t[i];
        let (nbrs, k) = self.neighbours4(i);
        for &u in &nbrs[..k] {
            if self.in_r0[u] == self.in_r0[i] && self.eligible(u) {
                self.update(u);
            }
        }
        self.retry_rejected(i);
    }

    /// Gives the rejected pixels around a conquest another chance: what was not simple
    /// may be now (a two-pixel-wide tendril thinned to one pixel ends in a simple tip),
    /// so only the bridges that hold topology stay. Each pixel changes owner at most
    /// once, so this terminates.
    fn retry_rejected(&mut self, i: usize) {
        let (x, y) = ((i % self.w) as isize, (i / self.w) as isize);
        for dy in -1..=1 {
            for dx in -1..=1 {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx as usize >= self.w || ny as usize >= self.h {
                    continue;
                }
                let u = ny as usize * self.w + nx as usize;
                if self.state[u] == REJECTED {
                    self.state[u] = FAR;
                    self.t[u] = f64::INFINITY;
                    self.rejected -= 1;
                    if self.eligible(u) {
                        self.update(u);
                    }
                }
            }
        }
    }

    fn shrink(&mut self, i: usize) {
        let l = self.owner[i];
        if self.connectivity(i, l) != 1 {
            self.reject(i);
            return;
        }
        self.owner[i] = NONE;
        self.settle(i);
    }

    fn reject(&mut self, i: usize) {
        self.state[i] = REJECTED;
        self.rejected += 1;
    }

    /// Yokoi 4-connectivity number of pixel `i` with respect to label `l` (pixel `i`
    /// itself not counted): 1 iff adding or removing `i` keeps the label's topology.
    fn connectivity(&self, i: usize, l: u32) -> u32 {
        let (x, y) = ((i % self.w) as isize, (i / self.w) as isize);
        // E, NE, N, NW, W, SW, S, SE (y grows downwards; the cyclic order is what counts).
        const D: [(isize, isize); 8] = [
            (1, 0),
            (1, -1),
            (0, -1),
            (-1, -1),
            (-1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ];
        let mut b = [0u32; 8];
        for (k, (dx, dy)) in D.iter().enumerate() {
            let (nx, ny) = (x + dx, y + dy);
            if nx >= 0 && ny >= 0 && (nx as usize) < self.w && (ny as usize) < self.h {
                b[k] = (self.owner[ny as usize * self.w + nx as usize] == l) as u32;
            }
        }
        [0, 2, 4, 6]
            .iter()
            .map(|&k| b[k] - b[k] * b[(k + 1) % 8] * b[(k + 2) % 8])
            .sum()
    }

    /// Arrival-time slope at `v` looking away from `w` (its own front's time per pixel).
    fn slope(&self, v: usize, away: isize) -> f64 {
        let l = self.owner[v];
        let tv = self.known(v, false);
        let j = v as isize + away;
        let inside = j >= 0 && (j as usize) < self.w * self.h && {
            let (vx, jx) = (v % self.w, j as usize % self.w);
            vx.abs_diff(jx) <= 1
        };
        if inside {
            let j = j as usize;
            let tj = self.known(j, false);
            if self.owner[j] == l && tj.is_finite() && tv > tj {
                return tv - tj;
            }
        }
        let s = self.speed(v);
        if s > 0.0 {
            1.0 / s
        } else {
            1.0
        }
    }

    /// Places the cut on the edge between `x` (just conquered) and `u` (another label).
    fn place_cut(&mut self, x: usize, u: usize) {
        let d = u as isize - x as isize;
        let (m0, m1) = (self.slope(x, -d), self.slope(u, d));
        let (e0, e1) = (self.known(x, false), self.known(u, false));
        let s = ((e1 - e0 + m1) / (m0 + m1)).clamp(0.05, 0.95);
        self.cuts += 1;
        match d {
            1 => self.cut_x[x] = s as f32,
            -1 => self.cut_x[u] = (1.0 - s) as f32,
            _ if d > 0 => self.cut_y[x] = s as f32,
            _ => self.cut_y[u] = (1.0 - s) as f32,
        }
    }

    /// Where the contour of `a`'s label crosses the edge from pixel `a` to its neighbour
    /// `b` (`None` outside the image), as a fraction of the way from `a`.
    fn crossing(&self, a: usize, b: Option<usize>, b_dir: isize) -> f64 {
        let Some(b) = b else { return 0.5 };
        let (la, lb) = (self.owner[a], self.owner[b]);
        let s = if lb != NONE {
            // Another label: the cut, or the midpoint.
            let stored = match b_dir {
                1 => Some(self.cut_x[a] as f64),
                -1 => Some(1.0 - self.cut_x[b] as f64),
                d if d > 0 => Some(self.cut_y[a] as f64),
                _ => Some(1.0 - self.cut_y[b] as f64),
            }
            .filter(|s| s.is_finite())
            .unwrap_or(0.5);
            debug_assert_ne!(la, lb);
            stored - 0.5 * CUT_GAP
        } else {
            let theta = self.model.threshold();
            let (ia, ib) = (self.image[a] as f64 - theta, self.image[b] as f64 - theta);
            let s_i = if ia * ib < 0.0 { ia / (ia - ib) } else { 0.5 };
            if !self.in_r0[b] && self.state[b] == TRIAL {
                // The growing front is between a and b.
                let ta = self.known(a, false);
                let f = ((self.tau - ta) / (self.t[b] - ta)).clamp(0.0, 1.0);
                f.min(s_i)
            } else if self.in_r0[a] && self.state[a] == TRIAL {
                // The shrinking front is between b and a.
                let tb = self.known(b, true);
                let f = ((self.tau - tb) / (self.t[a] - tb)).clamp(0.0, 1.0);
                (1.0 - f).max(s_i)
            } else {
                s_i
            }
        };
        s.clamp(S_MARGIN, 1.0 - S_MARGIN)
    }

    /// The contours: for each label, its boundary rings (region on the left: outer rings
    /// counter-clockwise in the algebraic sense, holes the other way).
    pub fn rings(&self) -> Vec<Vec<Point>> {
        let (w, h) = (self.w as isize, self.h as isize);
        let owner = |x: isize, y: isize| -> u32 {
            if x < 0 || y < 0 || x >= w || y >= h {
                NONE
            } else {
                self.owner[(y * w + x) as usize]
            }
        };
        // A crossing is named by its grid edge: (x, y, 0) to (x + 1, y), (x, y, 1) to
        // (x, y + 1), over pixels padded by one all round; per label.
        let pw = (w + 2) as u64;
        let edge_id =
            |x: isize, y: isize, dir: u64| (((y + 1) as u64 * pw + (x + 1) as u64) << 1) | dir;
        let mut next: HashMap<(u32, u64), u64> = HashMap::new();
        let mut point: HashMap<(u32, u64), Point> = HashMap::new();
        let centre = |x: isize, y: isize| Point::new(x as f64 + 0.5, y as f64 + 0.5);
        let crossing_point = |point: &mut HashMap<(u32, u64), Point>,
                              l: u32,
                              (x0, y0): (isize, isize),
                              (x1, y1): (isize, isize)|
         -> (u64, Point) {
            // Edge between pixels (x0, y0) and (x1, y1); one of them belongs to l.
            let (ex, ey, dir) = if y0 == y1 {
                (x0.min(x1), y0, 0)
            } else {
                (x0, y0.min(y1), 1)
            };
            let id = edge_id(ex, ey, dir);
            let p = *point.entry((l, id)).or_insert_with(|| {
                let (ax, ay, bx, by) = if owner(x0, y0) == l {
                    (x0, y0, x1, y1)
                } else {
                    (x1, y1, x0, y0)
                };
                let inside = |x: isize, y: isize| x >= 0 && y >= 0 && x < w && y < h;
                let a = (ay * w + ax) as usize;
                let b = inside(bx, by).then(|| (by * w + bx) as usize);
                let dir = if ay == by { bx - ax } else { (by - ay) * w };
                let s = if inside(ax, ay) {
                    self.crossing(a, b, dir)
                } else {
                    0.5
                };
                centre(ax, ay).lerp(centre(bx, by), s)
            });
            (id, p)
        };
        for cy in -1..h {
            for cx in -1..w {
                // Cell corners: c0 (cx, cy), c1 (cx+1, cy), c2 (cx+1, cy+1), c3 (cx, cy+1).
                let c = [(cx, cy), (cx + 1, cy), (cx + 1, cy + 1), (cx, cy + 1)];
                let o = c.map(|(x, y)| owner(x, y));
                if o[0] == o[1] && o[1] == o[2] && o[2] == o[3] {
                    continue;
                }
                for k in 0..4 {
                    let l = o[k];
                    if l == NONE || o[..k].contains(&l) {
                        continue;
                    }
                    let m = o.map(|x| x == l);
                    // Crossed sides: side j joins corners j and j + 1.
                    let mut pairs = [(0usize, 0usize); 2];
                    let np = if m[0] && m[2] && !m[1] && !m[3] {
                        pairs = [(3, 0), (1, 2)]; // saddle: cut off corner 0, then corner 2
                        2
                    } else if m[1] && m[3] && !m[0] && !m[2] {
                        pairs = [(0, 1), (2, 3)];
                        2
                    } else {
                        // Exactly two sides are crossed: the first and the last.
                        let crossed = |j: usize| m[j] != m[(j + 1) % 4];
                        let first = (0..4).find(|&j| crossed(j)).expect("two crossed sides");
                        let last = (0..4).rfind(|&j| crossed(j)).expect("two crossed sides");
                        pairs[0] = (first, last);
                        1
                    };
                    for &(s0, s1) in &pairs[..np] {
                        let (e0, p0) = crossing_point(&mut point, l, c[s0], c[(s0 + 1) % 4]);
                        let (e1, p1) = crossing_point(&mut point, l, c[s1], c[(s1 + 1) % 4]);
                        // A member corner the segment bounds (for a saddle, the one it
                        // cuts off; otherwise all members lie on one side).
                        let member = (0..4)
                            .find(|&j| {
                                m[j] && (j == s0 || j == (s0 + 1) % 4)
                                    && (j == s1 || j == (s1 + 1) % 4)
                            })
                            .or_else(|| (0..4).find(|&j| m[j]))
                            .expect("a label corner");
                        let mc = centre(c[member].0, c[member].1);
                        if orient(p0, p1, mc) > 0.0 {
                            next.insert((l, e0), e1);
                        } else {
                            next.insert((l, e1), e0);
                        }
                    }
                }
            }
        }
        // Chain the segments into rings.
        let mut rings = Vec::new();
        let mut keys: Vec<(u32, u64)> = next.keys().copied().collect();
        keys.sort_unstable();
        let mut used: std::collections::HashSet<(u32, u64)> = std::collections::HashSet::new();
        for start in keys {
            if used.contains(&start) {
                continue;
            }
            let (l, mut e) = start;
            let mut ring = Vec::new();
            loop {
                used.insert((l, e));
                ring.push(point[&(l, e)]);
                match next.get(&(l, e)) {
                    Some(&n) => e = n,
                    None => {
                        debug_assert!(false, "marching squares left a crossing open");
                        break;
                    }
                }
                if e == start.1 {
                    break;
                }
            }
            if ring.len() >= 3 {
                rings.push(ring);
            }
        }
        rings
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

impl Implicit {
    /// Whether pixel (x, y) belongs to some label.
    pub fn owned(&self, x: usize, y: usize) -> bool {
        self.owner[y * self.w + x] != NONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn engine(w: usize, h: usize, owned: &[(usize, usize)]) -> Implicit {
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

    #[test]
    fn connectivity_number_decides_simple_pixels() {
        // Centre pixel (2, 2) of a 5×5 grid; label 0 around it as given.
        let c = 2 * 5 + 2;
        // One neighbour: simple (growth).
        assert_eq!(engine(5, 5, &[(3, 2)]).connectivity(c, 0), 1);
        // Opposite neighbours: joining them would close a loop.
        assert_eq!(engine(5, 5, &[(3, 2), (1, 2)]).connectivity(c, 0), 2);
        // An L-shaped corner (E, NE, N): simple.
        assert_eq!(
            engine(5, 5, &[(3, 2), (3, 1), (2, 1)]).connectivity(c, 0),
            1
        );
        // Surrounded: filling a one-pixel hole is not simple.
        let all: Vec<_> = (1..4)
            .flat_map(|y| (1..4).map(move |x| (x, y)))
            .filter(|&p| p != (2, 2))
            .collect();
        assert_eq!(engine(5, 5, &all).connectivity(c, 0), 0);
        // Only diagonals: 4-connectivity does not see them, nothing to join.
        assert_eq!(engine(5, 5, &[(3, 3), (1, 1)]).connectivity(c, 0), 0);
    }

    #[test]
    fn rings_bound_exactly_the_owned_pixels() {
        // A plus, a diagonal pair (two 4-components of one label would not arise, but
        // the extraction must still separate them) and a pixel on the border.
        let e = engine(
            7,
            6,
            &[
                (2, 1),
                (1, 2),
                (2, 2),
                (3, 2),
                (2, 3),
                (5, 4),
                (6, 5),
                (0, 0),
            ],
        );
        let rings = e.rings();
        assert_eq!(rings.len(), 4);
        for y in 0..6 {
            for x in 0..7 {
                let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let w: i32 = rings.iter().map(|r| winding_number(r, p)).sum();
                assert_eq!(w != 0, e.owned(x, y), "pixel {x},{y}");
            }
        }
        for r in &rings {
            assert!(
                crate::geometry::signed_area(r) > 0.0,
                "outer rings run counter-clockwise"
            );
        }
    }
}
