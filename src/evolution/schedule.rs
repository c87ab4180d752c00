//! The coarse-to-fine schedule and the convergence test (seed 004 §2.5).
//!
//! Evolution runs over the pyramid from the coarsest level down. A level ends when the
//! share of active vertices stays below `converged_share` with the area steady for three
//! frames — or, when noise keeps vertices chattering while the area stays put, after
//! [`STALL_FRAMES`] (on a coarse level the finer one will settle them), or at
//! [`LEVEL_FRAMES_CAP`]. Only a run that reached a level-0 equilibrium is converged; one
//! cut by the cap on level 0 with areas still drifting is only stopped.
//!
//! Steadiness is judged per contour, not in total: on a large image with many settled
//! cells, one region still shrinking is a tiny share of the total area, yet it is not
//! done. Drift is a net change beyond the tolerance that is also most of the path the area
//! took: contours chattering in noise go up and down and count as steady.

use crate::contours::ContourSet;

/// Frames one pyramid level may take before the next finer level takes over.
pub const LEVEL_FRAMES_CAP: usize = 600;
/// Frames after which a level whose area is steady ends even if vertices still chatter.
pub const STALL_FRAMES: usize = 40;
/// Frames of per-contour areas the steadiness test reads.
const WINDOW: usize = 11;

/// Where a run is in the schedule.
#[derive(Clone, Debug)]
pub struct Schedule {
    /// The pyramid level frames run on now.
    pub level: usize,
    calm: usize,
    level_frames: usize,
    /// Per-contour areas (sorted by id) after each of the last frames of this level.
    areas: Vec<Vec<(u32, f64)>>,
    /// Reached an equilibrium on the finest level.
    pub converged: bool,
    /// Cut by the frame cap of the finest level without converging.
    pub stopped: bool,
}

impl Schedule {
    /// A schedule starting on `level` (the coarsest).
    pub fn new(level: usize) -> Self {
        Schedule {
            level,
            calm: 0,
            level_frames: 0,
            areas: Vec::new(),
            converged: false,
            stopped: false,
        }
    }

    /// The run goes on from where it is (forces changed): nothing is settled any more.
    pub fn resume(&mut self) {
        self.calm = 0;
        self.level_frames = 0;
        self.areas.clear();
        self.converged = false;
        self.stopped = false;
    }

    /// Ends the run here, converged or stopped as `converged` says (a stage of fixed
    /// length after the run had settled: [`crate::evolution::Evolver::edges_when_finished`]).
    pub fn end(&mut self, converged: bool) {
        self.converged = converged;
        self.stopped = !converged;
    }

    /// Judges the frame that just left `set` with `share` of its vertices active; returns
    /// the finer level to move to, if this level is done.
    pub fn judge(&mut self, set: &ContourSet, share: f64, converged_share: f64) -> Option<usize> {
        self.level_frames += 1;
        let mut now: Vec<(u32, f64)> = set
            .contour_ids()
            .map(|id| (id.0, set.signed_area(id)))
            .collect();
        now.sort_unstable_by_key(|&(id, _)| id);
        if self.areas.len() == WINDOW {
            self.areas.remove(0);
        }
        self.areas.push(now);
        let scale = super::Pyramid::scale(self.level);
        let settling = share < converged_share && self.steady(0.002, scale);
        self.calm = if settling { self.calm + 1 } else { 0 };
        let stall_tol = if self.level > 0 { 0.01 } else { 0.003 };
        let stalled = self.level_frames >= STALL_FRAMES && self.steady(stall_tol, scale);
        let capped = self.level_frames >= LEVEL_FRAMES_CAP;
        let empty = set.vertex_count() == 0;
        if !(self.calm >= 3 || stalled || capped || empty) {
            return None;
        }
        if empty || (self.level == 0 && !capped) {
            self.converged = true;
        } else if self.level == 0 {
            // The cap ends the run; it converged only if the areas stopped drifting.
            self.converged = self.steady(0.003, scale);
            self.stopped = !self.converged;
        } else {
            self.level -= 1;
            self.calm = 0;
            self.level_frames = 0;
            self.areas.clear();
            return Some(self.level);
        }
        None
    }

    /// No contour's area drifted by more than `tol` (relative, plus one grid cell) over
    /// the last ten frames, or it went up and down more than it went anywhere.
    fn steady(&self, tol: f64, scale: f64) -> bool {
        let n = self.areas.len();
        if n < WINDOW {
            return false;
        }
        let at = |k: usize, id: u32| {
            let f = &self.areas[k];
            f.binary_search_by_key(&id, |&(i, _)| i)
                .ok()
                .map(|j| f[j].1)
        };
        self.areas[n - 1].iter().all(|&(id, a)| {
            let Some(then) = at(n - WINDOW, id) else {
                return false; // too young to judge
            };
            let net = (a - then).abs();
            if net <= tol * a.abs() + scale * scale {
                return true;
            }
            let mut path = 0.0;
            let mut prev = then;
            for k in n - 10..n {
                let Some(x) = at(k, id) else { return false };
                path += (x - prev).abs();
                prev = x;
            }
            net < 0.5 * path
        })
    }
}
