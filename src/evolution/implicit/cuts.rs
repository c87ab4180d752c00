//! Cut edges (seed 000 §4.3–4.4): where two labels' fronts meet, the grid edge between
//! them is cut at a sub-pixel position from the arrival-time slopes on both sides; the
//! contour of a label crosses an edge at its cut, at the moving front, or where the
//! image crosses the model's threshold.

use super::{Implicit, CUT_GAP, NONE, S_MARGIN, TRIAL};

impl Implicit {
    /// Arrival-time slope at `v` looking away from `w` (its own front's time per pixel).
    pub(super) fn slope(&self, v: usize, away: isize) -> f64 {
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
    pub(super) fn place_cut(&mut self, x: usize, u: usize) {
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
    pub(super) fn crossing(&self, a: usize, b: Option<usize>, b_dir: isize) -> f64 {
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
}
