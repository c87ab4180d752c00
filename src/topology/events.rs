//! Topology events and pseudo-local relabelling (seed 003, §2.4).
//!
//! After a move has spliced rings, each surviving loop that took part is walked once; the
//! ring ids its vertices carried tell what happened. Ids follow the user's eye: the
//! largest piece of a split keeps the old id (preferring a piece of the same kind, outer
//! or hole), a merge keeps the id of the largest ring merged, and only the vertices of the
//! other pieces are relabelled.

use crate::contours::ContourId;

/// A change of the region's topology caused by one move.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum TopologyEvent {
    /// Outer ring `new` split off ring `from` (one more component).
    Split {
        /// The ring that split.
        from: ContourId,
        /// The new ring.
        new: ContourId,
    },
    /// Component bounded by `absorbed` joined the one bounded by `into`.
    Merge {
        /// The component that remains.
        into: ContourId,
        /// The one that joined it.
        absorbed: ContourId,
    },
    /// Hole ring `hole` appeared, split off ring `from` (one more hole).
    HoleMade {
        /// The ring the hole split off.
        from: ContourId,
        /// The hole.
        hole: ContourId,
    },
    /// Hole ring `hole` is gone: filled, or opened into `into`.
    HoleGone {
        /// The hole.
        hole: ContourId,
        /// The ring it opened into (none: filled).
        into: Option<ContourId>,
    },
    /// Outer ring `contour` shrank to nothing.
    Vanished {
        /// The ring.
        contour: ContourId,
    },
}

impl TopologyEvent {
    /// The event in words, naming the objects (contours) by id, as the app's log shows
    /// it: "object 3 split into 3 and 7".
    pub fn describe(&self) -> String {
        match *self {
            TopologyEvent::Split { from, new } => {
                format!("object {from} split into {from} and {new}")
            }
            TopologyEvent::Merge { into, absorbed } => {
                format!("object {absorbed} merged into {into}")
            }
            TopologyEvent::HoleMade { from, hole } => format!("object {from} made hole {hole}"),
            TopologyEvent::HoleGone { hole, into: None } => format!("hole {hole} filled"),
            TopologyEvent::HoleGone {
                hole,
                into: Some(i),
            } => format!("hole {hole} opened into {i}"),
            TopologyEvent::Vanished { contour } => format!("object {contour} vanished"),
        }
    }

    /// Short name as used in JSON and the app's log: split, merge, hole_made, hole_gone,
    /// vanished.
    pub fn kind(&self) -> &'static str {
        match self {
            TopologyEvent::Split { .. } => "split",
            TopologyEvent::Merge { .. } => "merge",
            TopologyEvent::HoleMade { .. } => "hole_made",
            TopologyEvent::HoleGone { .. } => "hole_gone",
            TopologyEvent::Vanished { .. } => "vanished",
        }
    }

    /// The ring ids involved, the surviving or older one first.
    pub fn contours(&self) -> Vec<ContourId> {
        match *self {
            TopologyEvent::Split { from, new } => vec![from, new],
            TopologyEvent::Merge { into, absorbed } => vec![into, absorbed],
            TopologyEvent::HoleMade { from, hole } => vec![from, hole],
            TopologyEvent::HoleGone { hole, into } => into.map_or(vec![hole], |i| vec![i, hole]),
            TopologyEvent::Vanished { contour } => vec![contour],
        }
    }
}

/// A ring that took part in a splice, as it was before the move.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OldRing {
    pub id: u32,
    pub len: u32,
    pub outer: bool,
}

/// A loop that survived a splice.
#[derive(Clone, Debug)]
pub(crate) struct NewLoop {
    pub anchor: u32,
    pub len: u32,
    pub area2: f64,
    pub outer: bool,
    /// Distinct old ring ids among its vertices.
    pub labels: Vec<u32>,
    /// Id given to it.
    pub id: u32,
}

/// Gives every surviving loop an id and says what happened. `fresh` hands out new ids.
///
/// A loop keeps an old id only if it is of the same kind (outer or hole) as that ring was,
/// so outer and hole counts change exactly as the events say: each fresh outer loop is a
/// `Split`, each fresh hole a `HoleMade`, each old id no loop kept a `Merge` (outer) or
/// `HoleGone` (hole).
pub(crate) fn assign_ids(
    loops: &mut [NewLoop],
    old: &[OldRing],
    mut fresh: impl FnMut() -> u32,
    events: &mut Vec<TopologyEvent>,
) {
    let old_of = |id: u32| old.iter().find(|r| r.id == id).copied();
    let mut order: Vec<usize> = (0..loops.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(loops[i].len));
    let mut taken: Vec<u32> = Vec::new();
    for &i in &order {
        let outer = loops[i].outer;
        let choice = loops[i]
            .labels
            .iter()
            .copied()
            .filter(|l| !taken.contains(l))
            .filter_map(|l| old_of(l).filter(|r| r.outer == outer))
            .max_by_key(|r| r.len)
            .map(|r| r.id);
        let id = match choice {
            Some(l) => l,
            None => {
                let id = fresh();
                let from = ContourId(loops[i].labels[0]);
                let new = ContourId(id);
                events.push(if outer {
                    TopologyEvent::Split { from, new }
                } else {
                    TopologyEvent::HoleMade { from, hole: new }
                });
                id
            }
        };
        taken.push(id);
        loops[i].id = id;
    }
    for r in old.iter().filter(|r| !taken.contains(&r.id)) {
        // The largest loop holding a piece of it is where it went.
        let into = order
            .iter()
            .map(|&i| &loops[i])
            .find(|lp| lp.labels.contains(&r.id))
            .map(|lp| ContourId(lp.id));
        let gone = ContourId(r.id);
        events.push(match (r.outer, into) {
            (true, Some(into)) => TopologyEvent::Merge {
                into,
                absorbed: gone,
            },
            (true, None) => TopologyEvent::Vanished { contour: gone },
            (false, into) => TopologyEvent::HoleGone { hole: gone, into },
        });
    }
}
