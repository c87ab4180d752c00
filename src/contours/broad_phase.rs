//! The broad phase of the crossing search (seed 003, §3; seed 001, §2): which vertices
//! may lie in a box. Two implementations sit behind one trait, chosen per contour set:
//! dense vertex bins ([`VertexBins`], the default: a flat array over the image) and
//! staggered spatial hashing ([`StaggeredHash`]: no domain, memory in proportion to the
//! vertices). Both give the same answers as brute force (tests/broad_phase.rs).

use super::staggered_hash::StaggeredHash;
use super::vertex_bins::VertexBins;
use crate::geometry::{Aabb, Point};

/// A broad phase over vertex positions: which vertices may lie in a box.
pub trait BroadPhase {
    /// Registers vertex `v` at `p`.
    fn insert(&mut self, v: u32, p: Point);
    /// Forgets vertex `v`.
    fn remove(&mut self, v: u32);
    /// Vertex `v` moved to `p`.
    fn update(&mut self, v: u32, p: Point);
    /// Clears `out` and fills it with a superset of the vertices whose position lies in `b`.
    fn query(&self, b: &Aabb, out: &mut Vec<u32>);
    /// Whether `v` is registered at a place where a query for `p` would find it.
    fn finds(&self, v: u32, p: Point) -> bool;
    /// Clears `out` and fills it with the start vertex of every edge with an endpoint in
    /// `b`, each once: the vertices lying in `b` (tested exactly, so the broad phase's
    /// granularity does not matter) and the predecessors of those that lie outside it.
    #[inline]
    fn query_edges(&self, b: &Aabb, prev: &[u32], pos: &[Point], out: &mut Vec<u32>) {
        self.query(b, out);
        out.retain(|&v| b.contains(pos[v as usize]));
        push_outside_prevs(b, prev, pos, out);
    }
    /// Number of registered vertices.
    fn len(&self) -> usize;
    /// Whether no vertex is stored.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Appends the predecessor of each vertex in `out` (all lying in `b`) that lies outside
/// `b`: with them, `out` starts every edge with an endpoint in `b`, each once.
#[inline]
pub(crate) fn push_outside_prevs(b: &Aabb, prev: &[u32], pos: &[Point], out: &mut Vec<u32>) {
    for i in 0..out.len() {
        let a = prev[out[i] as usize];
        if !b.contains(pos[a as usize]) {
            out.push(a);
        }
    }
}

/// A broad phase whose parts can be counted: the quiet-move certificate of
/// `ContourSet::move_vertex`. A region is a part that holds every vertex lying in some box
/// (a rectangle of bins, or a rectangle of boxes of one hash system); if a walk
/// along the rings meets as many vertices registered in the region as it holds, nothing
/// else lies in the box.
pub trait Countable: BroadPhase {
    /// A region of the structure a quiet move's count reads.
    type Region: Copy;
    /// The part of the broad phase a query for `b` would read, with the number of
    /// vertices registered in it; `None` when that part is too large to count cheaply.
    fn region(&self, b: &Aabb) -> Option<(Self::Region, u32)>;
    /// Whether vertex `v` is registered in region `r`.
    fn in_region(&self, v: u32, r: &Self::Region) -> bool;
    /// The vertices registered in `r`, counted one by one where [`Countable::region`]'s
    /// count may include others (hash collisions).
    fn exact_count(&self, r: &Self::Region) -> u32;
}

/// Which broad phase a contour set uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum BroadPhaseKind {
    /// Dense vertex bins over the image (seed 003).
    #[default]
    Bins,
    /// Four staggered hash grids (seed 001).
    Hash,
}

impl BroadPhaseKind {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            BroadPhaseKind::Bins => "bins",
            BroadPhaseKind::Hash => "hash",
        }
    }
}

/// The broad phase of a contour set: an enum rather than a trait object, so the hot path
/// dispatches by one predictable branch.
#[derive(Clone, Debug)]
pub enum Broad {
    /// Uniform vertex bins (seed 003).
    Bins(VertexBins),
    /// The staggered spatial hash (seed 001).
    Hash(StaggeredHash),
}

impl Broad {
    /// A broad phase of `kind` over `domain` for edges up to `reach`.
    pub fn new(kind: BroadPhaseKind, domain: Aabb, reach: f64) -> Self {
        match kind {
            BroadPhaseKind::Bins => Broad::Bins(VertexBins::new(domain, reach)),
            BroadPhaseKind::Hash => Broad::Hash(StaggeredHash::new(reach)),
        }
    }

    /// Which kind this is.
    pub fn kind(&self) -> BroadPhaseKind {
        match self {
            Broad::Bins(_) => BroadPhaseKind::Bins,
            Broad::Hash(_) => BroadPhaseKind::Hash,
        }
    }
}

macro_rules! dispatch {
    ($self:ident, $b:ident => $e:expr) => {
        match $self {
            Broad::Bins($b) => $e,
            Broad::Hash($b) => $e,
        }
    };
}

impl BroadPhase for Broad {
    #[inline]
    fn insert(&mut self, v: u32, p: Point) {
        dispatch!(self, b => b.insert(v, p))
    }
    #[inline]
    fn remove(&mut self, v: u32) {
        dispatch!(self, b => b.remove(v))
    }
    #[inline]
    fn update(&mut self, v: u32, p: Point) {
        dispatch!(self, b => b.update(v, p))
    }
    #[inline]
    fn query(&self, bx: &Aabb, out: &mut Vec<u32>) {
        dispatch!(self, b => b.query(bx, out))
    }
    #[inline]
    fn query_edges(&self, bx: &Aabb, prev: &[u32], pos: &[Point], out: &mut Vec<u32>) {
        dispatch!(self, b => b.query_edges(bx, prev, pos, out))
    }
    #[inline]
    fn finds(&self, v: u32, p: Point) -> bool {
        dispatch!(self, b => b.finds(v, p))
    }
    #[inline]
    fn len(&self) -> usize {
        dispatch!(self, b => b.len())
    }
}
