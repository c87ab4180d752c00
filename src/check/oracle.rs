//! The oracle: region membership by a plain crossing count at sample points away from
//! every edge, and a grid of the expected region checked after each move (seed 003,
//! equation 2).

use super::Rng;
use crate::contours::ContourSet;
use crate::geometry::{point_segment_distance, Aabb, Point};
use crate::topology::{MoveError, TopologyEvent};

/// Samples closer than this to an edge are skipped.
pub const NEAR: f64 = 1e-6;

/// Rings as point lists with their bounding boxes.
#[derive(Clone, Debug, PartialEq)]
pub struct Rings {
    pub pts: Vec<Vec<Point>>,
    boxes: Vec<Aabb>,
}

/// Crossing-number membership of `x` in the region bounded by `rings` (plain floats).
pub fn region_has(rings: &Rings, x: Point) -> bool {
    let mut inside = false;
    for (r, b) in rings.pts.iter().zip(&rings.boxes) {
        if x.y < b.min.y || x.y > b.max.y || x.x > b.max.x {
            continue;
        }
        let n = r.len();
        for i in 0..n {
            let (a, b) = (r[i], r[(i + 1) % n]);
            if (a.y > x.y) != (b.y > x.y) {
                let xc = a.x + (x.y - a.y) * (b.x - a.x) / (b.y - a.y);
                if xc > x.x {
                    inside = !inside;
                }
            }
        }
    }
    inside
}

/// Plain winding number of a closed polygon around `x` (floats; `x` far from it).
fn loop_winding(pts: &[Point], x: Point) -> i32 {
    let mut w = 0;
    let n = pts.len();
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        let side = (b.x - a.x) * (x.y - a.y) - (x.x - a.x) * (b.y - a.y);
        if a.y <= x.y && b.y > x.y && side > 0.0 {
            w += 1;
        } else if a.y > x.y && b.y <= x.y && side < 0.0 {
            w -= 1;
        }
    }
    w
}

fn near_any(rings: &Rings, x: Point) -> bool {
    rings
        .pts
        .iter()
        .zip(&rings.boxes)
        .any(|(r, b)| b.expand(NEAR).contains(x) && near_loop(r, x))
}

fn near_loop(pts: &[Point], x: Point) -> bool {
    (0..pts.len()).any(|i| point_segment_distance(x, pts[i], pts[(i + 1) % pts.len()]) < NEAR)
}

/// Whether segment a–b meets box `r` (brute force, for checking the broad phase).
pub fn segment_meets_box(a: Point, b: Point, r: &Aabb) -> bool {
    if r.contains(a) || r.contains(b) {
        return true;
    }
    let c = [
        r.min,
        Point::new(r.max.x, r.min.y),
        r.max,
        Point::new(r.min.x, r.max.y),
    ];
    (0..4).any(|i| {
        crate::geometry::segment_intersection(a, b, c[i], c[(i + 1) % 4])
            != crate::geometry::SegmentIntersection::None
    })
}

/// Every ring's points.
pub fn snapshot(set: &ContourSet) -> Rings {
    rings_of(
        &set.contour_ids()
            .map(|id| set.ring_points(id))
            .collect::<Vec<_>>(),
    )
}

/// Rings from point lists.
pub fn rings_of(pts: &[Vec<Point>]) -> Rings {
    let boxes = pts.iter().map(|p| Aabb::of(p)).collect();
    Rings {
        pts: pts.to_vec(),
        boxes,
    }
}

/// Numbers of outer and hole rings.
pub fn ring_kinds(set: &ContourSet) -> (i64, i64) {
    let holes = set.contour_ids().filter(|&id| set.is_hole(id)).count() as i64;
    (set.contour_count() as i64 - holes, holes)
}

/// Tracks the expected region on a grid across many moves, and checks each move.
pub struct Oracle {
    domain: Aabb,
    n: usize,
    /// Expected membership per grid sample; `None` when it was too close to an edge to say.
    grid: Vec<Option<bool>>,
    moves_since_full: u32,
    pub moves_checked: u64,
    pub samples_checked: u64,
}

impl Oracle {
    pub fn new(set: &ContourSet, domain: Aabb, n: usize) -> Self {
        let mut o = Oracle {
            domain,
            n,
            grid: vec![None; n * n],
            moves_since_full: 0,
            moves_checked: 0,
            samples_checked: 0,
        };
        o.resync(set);
        o
    }

    fn grid_point(&self, i: usize) -> Point {
        let (ix, iy) = (i % self.n, i / self.n);
        // Irrational-ish offsets keep samples off lattice-aligned geometry.
        let fx = (ix as f64 + 0.5 + 0.123_456_7) / self.n as f64;
        let fy = (iy as f64 + 0.5 + 0.234_567_8) / self.n as f64;
        Point::new(
            self.domain.min.x + fx * (self.domain.max.x - self.domain.min.x),
            self.domain.min.y + fy * (self.domain.max.y - self.domain.min.y),
        )
    }

    /// Re-reads unknown grid entries from the set (after rings were added, say).
    pub fn resync(&mut self, set: &ContourSet) {
        let rings = snapshot(set);
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            self.grid[i] = (!near_any(&rings, x)).then(|| region_has(&rings, x));
        }
    }

    /// Compares the whole grid with `rings`: nothing may have changed outside the motion
    /// regions. Entries unknown so far are learned where they are clear of every edge.
    pub fn compare_grid(&mut self, rings: &Rings) -> Result<(), String> {
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            if near_any(rings, x) {
                self.grid[i] = None;
                continue;
            }
            let now = region_has(rings, x);
            match self.grid[i] {
                Some(expect) if expect != now => {
                    return Err(format!(
                        "grid sample {x:?} is {now} but every motion since says {expect}"
                    ));
                }
                Some(_) => self.samples_checked += 1,
                None => self.grid[i] = Some(now),
            }
        }
        Ok(())
    }

    /// Checks one move of a vertex with neighbours `p`, `n` from `o` to `q` (`None`:
    /// removal), given the rings `before` it and its result.
    #[allow(clippy::too_many_arguments)]
    pub fn check_move(
        &mut self,
        set: &ContourSet,
        before: &Rings,
        kinds_before: (i64, i64),
        (p, o, n, q): (Point, Point, Point, Option<Point>),
        result: &Result<Vec<TopologyEvent>, MoveError>,
        rng: &mut Rng,
    ) -> Result<(), String> {
        if let Err(e) = set.sanity_check() {
            if std::env::var("TOPO_TRACE").is_ok() {
                eprintln!("move p {p:?} o {o:?} n {n:?} q {q:?} result {result:?}");
                for (i, r) in before.pts.iter().enumerate() {
                    eprintln!("before {i}: {r:?}");
                }
                for id in set.contour_ids() {
                    eprintln!(
                        "after {id} hole {} {:?}",
                        set.is_hole(id),
                        set.ring_points(id)
                    );
                }
            }
            return Err(e);
        }
        self.moves_checked += 1;
        let after = snapshot(set);
        let mloop: Vec<Point> = match q {
            Some(q) => vec![p, q, n, o],
            None => vec![p, n, o],
        };
        let events = match result {
            Err(_) => {
                if after != *before {
                    return Err("a refused move changed the rings".into());
                }
                return Ok(());
            }
            Ok(ev) => ev,
        };
        // Event bookkeeping matches the change in outer and hole counts.
        let (mut d_outer, mut d_holes) = (0i64, 0i64);
        for e in events {
            match e {
                TopologyEvent::Split { .. } => d_outer += 1,
                TopologyEvent::Merge { .. } | TopologyEvent::Vanished { .. } => d_outer -= 1,
                TopologyEvent::HoleMade { .. } => d_holes += 1,
                TopologyEvent::HoleGone { .. } => d_holes -= 1,
            }
        }
        let kinds_after = ring_kinds(set);
        if (
            kinds_after.0 - kinds_before.0,
            kinds_after.1 - kinds_before.1,
        ) != (d_outer, d_holes)
        {
            return Err(format!(
                "events {events:?} do not explain rings {kinds_before:?} -> {kinds_after:?}"
            ));
        }
        // Random samples in M's box: equation 2.
        let b = Aabb::of(&mloop);
        for _ in 0..24 {
            let x = Point::new(rng.range(b.min.x, b.max.x), rng.range(b.min.y, b.max.y));
            if near_loop(&mloop, x) || near_any(before, x) || near_any(&after, x) {
                continue;
            }
            self.samples_checked += 1;
            let w = loop_winding(&mloop, x);
            let expect = match w {
                1 => true,
                -1 => false,
                _ => region_has(before, x),
            };
            if region_has(&after, x) != expect {
                return Err(format!(
                    "sample {x:?}: winding {w}, expected in-region {expect}"
                ));
            }
        }
        // The grid: entries inside M's box follow the same rule.
        for i in 0..self.grid.len() {
            let x = self.grid_point(i);
            if b.contains(x) {
                self.grid[i] = match (near_loop(&mloop, x), loop_winding(&mloop, x)) {
                    (true, _) => None,
                    (false, 1) => Some(true),
                    (false, -1) => Some(false),
                    (false, _) => self.grid[i],
                };
            }
        }
        self.moves_since_full += 1;
        if self.moves_since_full >= 200 {
            self.moves_since_full = 0;
            self.compare_grid(&after)?;
        }
        Ok(())
    }
}
