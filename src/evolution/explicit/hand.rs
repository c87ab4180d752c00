//! Hand edits through the topology core: a dragged vertex pulls a tongue of its contour,
//! every step an ordinary motion region, so a drag that makes two contours touch merges
//! them, one that pinches splits, one that closes a gap makes a hole — exactly.

use super::{spacing, Explicit, Motion};
use crate::contours::{ContourId, ContourSet};
use crate::geometry::Point;
use crate::topology::{MoveError, TopologyEvent};

/// Vertices on each side that follow a hand-dragged vertex (with weights falling to 0).
const HAND_FOLLOW: usize = 3;

impl<M: Motion> Explicit<M> {
    /// Drags vertex `v` towards `to` (clamped to the image) at pyramid level `level`, in
    /// steps of a quarter of the edge bound with the moving vertex's edges split ahead of
    /// it and its three neighbours on each side following with weights ¾, ½, ¼ (a tongue,
    /// not a spike); a degenerate step is retried at half and a quarter length. Returns
    /// the events and the vertex that leads at the end: when the lead vanishes without a
    /// topology event (a remesh joined it to a neighbour), the vertex of its contour
    /// nearest to where it was; after a merge or split the drag has done its work
    /// (`None`).
    pub(super) fn drag(
        &mut self,
        v: u32,
        to: Point,
        level: usize,
    ) -> (Vec<TopologyEvent>, Option<u32>) {
        let mut events = Vec::new();
        if !self.set.is_alive(v) {
            return (events, None);
        }
        let mut v = v;
        let to = self.bounds.clamp(to);
        let (scale, d_min, d_max) = spacing(level);
        let step = 0.25 * self.set.max_edge();
        let from = self.set.position(v);
        let n = (from.dist(to) / step).ceil().max(1.0) as usize;
        for k in 1..=n {
            if !self.set.is_alive(v) {
                break;
            }
            let (contour, was) = (self.set.contour_of(v), self.set.position(v));
            let before = events.len();
            let target = from.lerp(to, k as f64 / n as f64);
            if !self.drag_step(v, target, step, scale, &mut events) {
                break;
            }
            if !self.set.is_alive(v) && events.len() == before {
                let Some(u) = successor(&self.set, was, contour) else {
                    break;
                };
                v = u;
            }
        }
        let at = self
            .set
            .is_alive(v)
            .then(|| (self.set.position(v), self.set.contour_of(v)));
        let before = events.len();
        super::remesh(&mut self.set, d_min, d_max, M::gap(scale), &mut events);
        let lead = match at {
            Some(_) if self.set.is_alive(v) => Some(v),
            Some((p, c)) if events.len() == before => successor(&self.set, p, c),
            _ => None,
        };
        (events, lead)
    }

    /// One step of a drag: `v` towards `target`, its neighbours following. Returns
    /// whether the lead moved.
    fn drag_step(
        &mut self,
        v: u32,
        target: Point,
        step: f64,
        scale: f64,
        events: &mut Vec<TopologyEvent>,
    ) -> bool {
        let bound = self.set.max_edge();
        // Split the moving vertex's edges that this step could stretch past the bound.
        for a in [self.set.prev(v), v] {
            let b = self.set.next(a);
            if self.set.position(a).dist(self.set.position(b)) > bound - step {
                let _ = self.set.insert_vertex(a, 0.5);
            }
        }
        let d = target - self.set.position(v);
        // The vertex leads; its neighbours follow with falling weights, so the drag pulls
        // a tongue, not a one-vertex spike whose two edges are nearly parallel (such a
        // spike meets other contours only in degenerate crossings).
        let (mut p, mut q) = (v, v);
        let mut chain = vec![(v, 1.0)];
        for i in 1..=HAND_FOLLOW {
            p = self.set.prev(p);
            q = self.set.next(q);
            if p == q || p == v {
                break;
            }
            let w = 1.0 - i as f64 / (HAND_FOLLOW + 1) as f64;
            chain.extend([(p, w), (q, w)]);
        }
        let mut lead_moved = true;
        for (u, w) in chain {
            if !self.set.is_alive(u) {
                continue;
            }
            let goal = self.bounds.clamp(self.set.position(u) + d * w);
            let done = self.shortened(u, goal, scale, events);
            if u == v {
                lead_moved = done;
            }
        }
        lead_moved
    }
}

impl<M: Motion> Explicit<M> {
    /// Moves `v` towards `goal` (inside the image) through the core, shortened to a half
    /// and a quarter when the move is degenerate; returns whether it moved.
    fn shortened(
        &mut self,
        v: u32,
        goal: Point,
        scale: f64,
        events: &mut Vec<TopologyEvent>,
    ) -> bool {
        let at = self.set.position(v);
        for f in [1.0, 0.5, 0.25] {
            match M::attempt(&mut self.set, v, at.lerp(goal, f), scale) {
                Ok(ev) => {
                    events.extend(ev);
                    return true;
                }
                Err(MoveError::Degenerate(_)) => continue,
                Err(_) => return false,
            }
        }
        false
    }
}

/// The vertex of `contour` nearest to where a dragged vertex was, within two edge bounds:
/// it leads the drag on when the dragged one was joined to a neighbour.
fn successor(set: &ContourSet, was: Point, contour: ContourId) -> Option<u32> {
    set.nearest_vertex(was, 2.0 * set.max_edge())
        .filter(|&u| set.contour_of(u) == contour)
}

impl<M: Motion> Explicit<M> {
    /// A brush stroke: the disc of `radius` around the brush moves from `from` to `to`,
    /// in steps of a quarter of the edge bound, and at each step every contour vertex
    /// inside the disc is pushed out to its rim, straight away from the centre, through
    /// the topology core. Brushing from inside a region pushes its boundary out (it grows
    /// and may merge with another); from outside pushes it in (it shrinks, may split or
    /// open a hole). Returns the events.
    ///
    /// Where the brush lands, its disc grows from nothing to `radius` in the same steps:
    /// every push is then at most a step long, an ordinary small motion region. Pushing
    /// vertices a whole radius at once made long edges whose new vertices lay inside the
    /// disc and were pushed again, a cascade that grew faster than any power of the
    /// radius (40 px: 8 s, 60 px: over a minute). The stroke is clipped to the image
    /// grown by the radius, beyond which it touches nothing.
    pub(super) fn brush_stroke(
        &mut self,
        from: Point,
        to: Point,
        radius: f64,
        level: usize,
    ) -> Vec<TopologyEvent> {
        let mut events = Vec::new();
        let reach = self.bounds.expand(radius);
        let Some((from, to)) = clip_segment(from, to, &reach) else {
            return events;
        };
        let step = 0.25 * self.set.max_edge();
        let grow = (radius / step).ceil().max(1.0) as usize;
        for k in 1..=grow {
            let r = radius * k as f64 / grow as f64;
            self.brush_disc(from, from, r, level, &mut events);
        }
        let n = (from.dist(to) / step).ceil() as usize;
        for k in 1..=n {
            let was = from.lerp(to, (k - 1) as f64 / n as f64);
            let c = from.lerp(to, k as f64 / n as f64);
            self.brush_disc(was, c, radius, level, &mut events);
        }
        events
    }

    /// One placement of the brush, its centre moved from `was` to `c`: the vertices
    /// inside the disc pushed to its rim along the ray from `was`, then the rings remeshed
    /// so the next placement finds vertices all along the rim.
    ///
    /// Along the ray from the last centre, not from this one: a vertex the moving disc
    /// meets was outside the last disc, so it goes on ahead of the brush. Pushed straight
    /// away from this centre, a vertex that came to lie near it (a remeshed edge's new
    /// midpoint across the tip of a narrow cut) could go either way, and a cut by a brush
    /// narrower than about the edge bound (2 px) turned inside out behind it and healed.
    /// An edge the disc cuts with both ends outside first gets a vertex where it comes
    /// nearest the centre, so a narrow disc cannot slip between two vertices.
    fn brush_disc(
        &mut self,
        was: Point,
        c: Point,
        radius: f64,
        level: usize,
        events: &mut Vec<TopologyEvent>,
    ) {
        let (scale, d_min, d_max) = spacing(level);
        let mut near = Vec::new();
        self.set.vertices_near(
            &crate::geometry::Aabb { min: c, max: c }.expand(radius + self.set.max_edge()),
            &mut near,
        );
        for &a in &near {
            if !self.set.is_alive(a) {
                continue;
            }
            let (pa, pb) = (self.set.position(a), self.set.position(self.set.next(a)));
            let d = pb - pa;
            if pa.dist(c) < radius || pb.dist(c) < radius || d.norm2() == 0.0 {
                continue;
            }
            let t = ((c - pa).dot(d) / d.norm2()).clamp(0.0, 1.0);
            if t > 0.0 && t < 1.0 && pa.lerp(pb, t).dist(c) < radius {
                // Refused only where the edge is degenerate; the push then does without.
                let _ = self.set.insert_vertex(a, t);
            }
        }
        near.clear();
        self.set.vertices_near(
            &crate::geometry::Aabb { min: c, max: c }.expand(radius),
            &mut near,
        );
        for &v in &near {
            if !self.set.is_alive(v) {
                continue;
            }
            let x = self.set.position(v);
            let d = x.dist(c);
            if d >= radius || d == 0.0 {
                continue;
            }
            let goal = self
                .bounds
                .clamp(rim_along(was, x, c, radius).unwrap_or(c + (x - c) * (radius / d)));
            self.shortened(v, goal, scale, events);
        }
        super::remesh(&mut self.set, d_min, d_max, M::gap(scale), events);
    }
}

/// Where the ray from `o` through `x` leaves the disc of `radius` about `c` (`x` inside
/// it), if `x` is not `o`.
fn rim_along(o: Point, x: Point, c: Point, radius: f64) -> Option<Point> {
    let len = x.dist(o);
    if len < 1e-9 {
        return None;
    }
    let u = (x - o) * (1.0 / len);
    // |o + u s − c|² = r², the larger root.
    let w = c - o;
    let b = u.dot(w);
    let disc = b * b - w.norm2() + radius * radius;
    (disc >= 0.0).then(|| o + u * (b + disc.sqrt()))
}

/// The part of segment `a`–`b` inside `bounds` (Liang–Barsky), if any.
fn clip_segment(a: Point, b: Point, bounds: &crate::geometry::Aabb) -> Option<(Point, Point)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x - bounds.min.x),
        (d.x, bounds.max.x - a.x),
        (-d.y, a.y - bounds.min.y),
        (d.y, bounds.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then(|| (a.lerp(b, t0), a.lerp(b, t1)))
}
