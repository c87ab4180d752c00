//! `ContourSet`: closed polygonal rings over a vertex arena (DESIGN layer 2).
//!
//! Connectivity is kept apart from coordinates: each vertex has `prev`/`next` links, so
//! splicing two rings at a crossing (seed 003, §2.3) is O(1). Each vertex carries the id
//! of the ring it belongs to; after a split only one of the two rings is relabelled, the
//! "pseudo-local" tracking of seed 003, §2.4.
//!
//! Conventions (stated once, here):
//! - the region lies on the left of every ring, in the algebraic sense of
//!   [`crate::geometry::orient`] on image coordinates (x right, y down): outer rings have
//!   positive signed area, hole rings negative;
//! - rings are simple, have at least 3 vertices, and no two edges anywhere cross or touch;
//! - no edge is longer than [`ContourSet::reach`], which is what makes the broad-phase
//!   search local (seed 003, §3: "constraining the maximum edge length").

mod access;
pub mod broad_phase;
mod invariants;
pub mod measure;
pub mod staggered_hash;
pub mod vertex_bins;

use crate::geometry::{edges_clash, signed_area2, Aabb, Point};

pub use access::RingWalk;
pub use broad_phase::{Broad, BroadPhase, BroadPhaseKind, Countable};
pub use staggered_hash::StaggeredHash;
pub use vertex_bins::VertexBins;

pub(crate) const NIL: u32 = u32::MAX;

/// Handle of a vertex in a [`ContourSet`].
pub type VertexId = u32;

/// Id of a ring. Ids are never reused within one set.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
#[serde(transparent)]
pub struct ContourId(pub u32);

impl std::fmt::Display for ContourId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// Why a ring could not be added.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum RingError {
    /// Fewer than three vertices.
    #[error("a ring needs at least 3 vertices, got {0}")]
    TooFewVertices(usize),
    /// A coordinate is not finite.
    #[error("ring has a non-finite coordinate")]
    NotFinite,
    #[error("ring edge of length {len} exceeds the edge bound {bound}")]
    /// An edge longer than the bound.
    EdgeTooLong {
        /// The edge's length.
        len: f64,
        /// The bound.
        bound: f64,
    },
    /// The ring has no area.
    #[error("ring has zero area")]
    ZeroArea,
    /// The ring crosses or touches itself or another ring.
    #[error("ring crosses or touches itself or another ring")]
    Intersects,
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Ring {
    /// Any live vertex of the ring.
    pub anchor: u32,
    pub len: u32,
    /// Twice the signed area, kept up to date incrementally.
    pub area2: f64,
}

/// A set of disjoint, simple, oriented polygonal rings bounding a region.
#[derive(Clone, Debug)]
pub struct ContourSet {
    pub(crate) pos: Vec<Point>,
    pub(crate) next: Vec<u32>,
    pub(crate) prev: Vec<u32>,
    /// Ring id of each vertex; `NIL` for a free slot.
    pub(crate) label: Vec<u32>,
    pub(crate) free: Vec<u32>,
    pub(crate) rings: Vec<Option<Ring>>,
    pub(crate) live_rings: usize,
    pub(crate) bins: Broad,
    pub(crate) max_edge: f64,
    /// Longest edge the bins must account for: `max_edge`, or more if an edge longer than
    /// it ever had to stay (never in practice; kept so correctness never depends on it).
    pub(crate) reach: f64,
    pub(crate) domain: Aabb,
    /// Per-vertex stamps for walks that must not visit twice.
    pub(crate) mark: Vec<u32>,
    pub(crate) stamp: u32,
    pub(crate) scratch: Vec<u32>,
}

impl ContourSet {
    /// An empty set whose rings are expected to live in `domain` (the image rectangle)
    /// with edges no longer than `max_edge` pixels.
    ///
    /// # Panics
    /// If `max_edge` is not a positive finite number (a programming error: callers
    /// validate user parameters first).
    pub fn new(domain: Aabb, max_edge: f64) -> Self {
        Self::with_broad_phase(domain, max_edge, BroadPhaseKind::Bins)
    }

    /// Like [`ContourSet::new`], with the broad phase of `kind`.
    pub fn with_broad_phase(domain: Aabb, max_edge: f64, kind: BroadPhaseKind) -> Self {
        assert!(
            max_edge.is_finite() && max_edge > 0.0,
            "edge bound must be positive, got {max_edge}"
        );
        ContourSet {
            pos: Vec::new(),
            next: Vec::new(),
            prev: Vec::new(),
            label: Vec::new(),
            free: Vec::new(),
            rings: Vec::new(),
            live_rings: 0,
            bins: Broad::new(kind, domain, max_edge),
            max_edge,
            reach: max_edge,
            domain,
            mark: Vec::new(),
            stamp: 0,
            scratch: Vec::new(),
        }
    }

    /// The edge-length bound every edge respects.
    pub fn max_edge(&self) -> f64 {
        self.max_edge
    }

    /// Which broad phase the set uses.
    pub fn broad_phase(&self) -> BroadPhaseKind {
        self.bins.kind()
    }

    /// The domain the bins cover.
    pub fn domain(&self) -> Aabb {
        self.domain
    }

    /// The distance the broad phase searches around a motion (≥ `max_edge`).
    pub fn reach(&self) -> f64 {
        self.reach
    }

    /// Rebuilds the bins for a new edge bound (a pyramid level change). Existing edges
    /// longer than the new bound stay, and the search reach grows to cover them, until
    /// remeshing splits them.
    pub fn set_max_edge(&mut self, max_edge: f64) {
        assert!(
            max_edge.is_finite() && max_edge > 0.0,
            "edge bound must be positive, got {max_edge}"
        );
        self.max_edge = max_edge;
        let longest = self
            .vertices()
            .map(|v| self.pos[v as usize].dist(self.pos[self.next[v as usize] as usize]))
            .fold(0.0, f64::max);
        self.reach = max_edge.max(longest);
        self.bins = Broad::new(self.bins.kind(), self.domain, self.reach);
        for v in 0..self.pos.len() as u32 {
            if self.label[v as usize] != NIL {
                self.bins.insert(v, self.pos[v as usize]);
            }
        }
    }

    /// Adds a ring through `points` in order, keeping their orientation: counter-clockwise
    /// in the algebraic sense (positive area) for an outer ring, the other way for a hole.
    pub fn add_ring(&mut self, points: &[Point]) -> Result<ContourId, RingError> {
        let n = points.len();
        if n < 3 {
            return Err(RingError::TooFewVertices(n));
        }
        if points.iter().any(|p| !p.is_finite()) {
            return Err(RingError::NotFinite);
        }
        for i in 0..n {
            let len = points[i].dist(points[(i + 1) % n]);
            if len > self.max_edge {
                return Err(RingError::EdgeTooLong {
                    len,
                    bound: self.max_edge,
                });
            }
        }
        let area2 = signed_area2(points);
        if area2 == 0.0 {
            return Err(RingError::ZeroArea);
        }
        let id = self.rings.len() as u32;
        let first = self.alloc(points[0], id);
        let mut last = first;
        for &p in &points[1..] {
            let v = self.alloc(p, id);
            self.next[last as usize] = v;
            self.prev[v as usize] = last;
            last = v;
        }
        self.next[last as usize] = first;
        self.prev[first as usize] = last;
        if self.new_ring_intersects(first) {
            // Undo: the slots go back to the free list, the id is not used.
            let ring: Vec<VertexId> = self.walk(first).collect();
            for w in ring {
                self.release(w);
            }
            return Err(RingError::Intersects);
        }
        self.rings.push(Some(Ring {
            anchor: first,
            len: n as u32,
            area2,
        }));
        self.live_rings += 1;
        Ok(ContourId(id))
    }

    /// Whether the ring just linked at `first` (already in the broad phase) crosses or
    /// touches itself or another ring: each edge against the edges the broad phase offers
    /// near it, so the check is O(n) rather than O(n²).
    fn new_ring_intersects(&self, first: u32) -> bool {
        let mut cand = Vec::new();
        for a in self.walk(first) {
            let b = self.next[a as usize];
            let (a0, a1) = (self.pos[a as usize], self.pos[b as usize]);
            if a0 == a1 {
                return true;
            }
            self.edges_near(&Aabb::of(&[a0, a1]), &mut cand);
            for &c in &cand {
                if c == a {
                    continue;
                }
                let cn = self.next[c as usize];
                let (c0, c1) = (self.pos[c as usize], self.pos[cn as usize]);
                // Neighbouring edges share one vertex and must not fold onto each other.
                if edges_clash([(a, a0), (b, a1)], [(c, c0), (cn, c1)]) {
                    return true;
                }
            }
        }
        // A ring with no crossing may still enclose or sit inside another one: that is
        // fine as long as orientations nest, which `sanity_check` verifies; callers that
        // build nested rings state holes explicitly.
        false
    }

    pub(crate) fn alloc(&mut self, p: Point, label: u32) -> u32 {
        let v = if let Some(v) = self.free.pop() {
            self.pos[v as usize] = p;
            self.label[v as usize] = label;
            v
        } else {
            self.pos.push(p);
            self.next.push(NIL);
            self.prev.push(NIL);
            self.label.push(label);
            self.mark.push(0);
            (self.pos.len() - 1) as u32
        };
        self.bins.insert(v, p);
        v
    }

    /// Frees a vertex slot (links are the caller's business).
    pub(crate) fn release(&mut self, v: u32) {
        self.bins.remove(v);
        self.label[v as usize] = NIL;
        self.free.push(v);
    }

    #[inline]
    pub(crate) fn ring(&self, id: u32) -> &Ring {
        self.rings[id as usize].as_ref().expect("live ring")
    }
    #[inline]
    pub(crate) fn ring_mut(&mut self, id: u32) -> &mut Ring {
        self.rings[id as usize].as_mut().expect("live ring")
    }

    pub(crate) fn next_stamp(&mut self) -> u32 {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.mark.iter_mut().for_each(|m| *m = 0);
            self.stamp = 1;
        }
        self.stamp
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    fn set() -> ContourSet {
        ContourSet::new(
            Aabb {
                min: p(0.0, 0.0),
                max: p(100.0, 100.0),
            },
            20.0,
        )
    }

    #[test]
    fn add_ring_refuses_crossings_and_touches_without_using_an_id() {
        let mut s = set();
        // A figure eight crosses itself.
        let eight = [p(10., 10.), p(22., 22.), p(22., 10.), p(10., 18.)];
        assert_eq!(s.add_ring(&eight), Err(RingError::Intersects));
        // A spike folding back onto its own edge.
        let fold = [p(10., 10.), p(20., 10.), p(15., 10.), p(15., 15.)];
        assert_eq!(s.add_ring(&fold), Err(RingError::Intersects));
        let a = s.add_ring(&[p(10., 10.), p(20., 10.), p(20., 20.), p(10., 20.)]);
        assert_eq!(a, Ok(ContourId(0)));
        // Crossing the first ring, and touching it at a vertex.
        let cross = [p(15., 15.), p(30., 15.), p(30., 30.), p(15., 30.)];
        assert_eq!(s.add_ring(&cross), Err(RingError::Intersects));
        let touch = [p(20., 20.), p(30., 20.), p(30., 30.), p(20., 30.)];
        assert_eq!(s.add_ring(&touch), Err(RingError::Intersects));
        // Refusals left nothing behind: the next ring gets id 1 and the set is sound.
        let b = s.add_ring(&[p(40., 40.), p(50., 40.), p(50., 50.), p(40., 50.)]);
        assert_eq!(b, Ok(ContourId(1)));
        assert_eq!(s.vertex_count(), 8);
        s.sanity_check().unwrap();
    }
}
