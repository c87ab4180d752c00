//! The two fronts (seed 000 §3.2): first-order upwind eikonal updates from one min-heap,
//! the growing front conquering object pixels outside R₀, the shrinking one giving up
//! background pixels of R₀, each change of owner only for a simple pixel (§4.1).

use super::{Implicit, DONE, FAR, NONE, REJECTED, TRIAL};
use std::cmp::Reverse;

#[inline]
fn key(t: f64) -> u64 {
    // Non-negative floats order like their bit patterns.
    t.to_bits()
}

impl Implicit {
    /// Known arrival time at `u` for the front conquering pixels with `in_r0 == shrink`.
    #[inline]
    pub(super) fn known(&self, u: usize, shrink: bool) -> f64 {
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
    pub(super) fn update(&mut self, i: usize) {
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

    pub(super) fn grow(&mut self, i: usize) {
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
    pub(super) fn settle(&mut self, i: usize) {
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
    pub(super) fn retry_rejected(&mut self, i: usize) {
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

    pub(super) fn shrink(&mut self, i: usize) {
        let l = self.owner[i];
        if self.connectivity(i, l) != 1 {
            self.reject(i);
            return;
        }
        self.owner[i] = NONE;
        self.settle(i);
    }

    pub(super) fn reject(&mut self, i: usize) {
        self.state[i] = REJECTED;
        self.rejected += 1;
    }
}
