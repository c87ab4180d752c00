//! Which kinds of topology event a move may cause: a policy per kind, checked by the
//! core itself, so every engine and hand edit that moves through it obeys it exactly.
//!
//! The adaptive engine allows every event (seed 003 as written); preserve allows none.
//! Tracking cells through a movie needs a third rule: **objects never merge, holes are not
//! made, but an object may split** — a dividing cell pinches in two and the split event
//! names both pieces (seed 003, §2.4's pseudo-local tracking), while two touching cells
//! stay two. [`TopologyPolicy::TRACKING`] is that rule.
//!
//! How a move is held: the motion region, crossings and Directive 2 rings are planned as
//! for any move (nothing changes yet). A move that crosses no ring and deletes none is
//! carried out at once (it cannot change topology). Any other move is carried out on the
//! set, and if one of its events is one the policy holds back, the set is put back as it
//! was (a copy taken before) and the move is refused with [`MoveError::Held`]. Guessing
//! the events from the crossings alone is not safe: the property test found a move that
//! crosses another object where the region grows and yet reports only a split. Such
//! moves are rare in an evolution (a division, a contour pinching in on itself, two
//! objects pressing on each other, which [`crate::evolution::Mode::Track`] also keeps
//! apart by repulsion), so the copy costs little. So the rings after a held move are exactly the rings before,
//! and an allowed move is exactly the adaptive move.

use super::{MoveError, TopologyEvent};
use crate::contours::{ContourSet, VertexId};
use crate::geometry::Point;

/// The kinds of topology event a move may cause. A ring shrinking to nothing and a hole
/// filling or opening are always allowed (the region only loses what the motion removes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TopologyPolicy {
    /// Two components may join.
    pub merge: bool,
    /// One component may split in two.
    pub split: bool,
    /// A new hole may open.
    pub hole_made: bool,
}

impl TopologyPolicy {
    /// Every change allowed: the adaptive engine (seed 003).
    pub const ADAPTIVE: TopologyPolicy = TopologyPolicy {
        merge: true,
        split: true,
        hole_made: true,
    };
    /// One object per seed that may divide: no merge, no new hole, splits carried out
    /// and reported.
    pub const TRACKING: TopologyPolicy = TopologyPolicy {
        merge: false,
        split: true,
        hole_made: false,
    };

    /// Whether the policy lets `event` happen.
    pub fn allows(&self, event: &TopologyEvent) -> bool {
        match event {
            TopologyEvent::Merge { .. } => self.merge,
            TopologyEvent::Split { .. } => self.split,
            TopologyEvent::HoleMade { .. } => self.hole_made,
            TopologyEvent::HoleGone { .. } | TopologyEvent::Vanished { .. } => true,
        }
    }
}

impl ContourSet {
    /// [`ContourSet::move_vertex`] under `policy`: the same move and events when the
    /// policy allows them all, otherwise [`MoveError::Held`] and nothing changed.
    pub fn move_vertex_under(
        &mut self,
        v: VertexId,
        to: Point,
        policy: TopologyPolicy,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        if policy == TopologyPolicy::ADAPTIVE {
            return self.move_vertex(v, to);
        }
        if self.settled_without_correction(v, to)? {
            return Ok(Vec::new());
        }
        self.replace_under(v, Some(to), policy)
    }

    /// [`ContourSet::remove_vertex`] under `policy`.
    pub fn remove_vertex_under(
        &mut self,
        v: VertexId,
        policy: TopologyPolicy,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        if policy == TopologyPolicy::ADAPTIVE {
            return self.remove_vertex(v);
        }
        self.check_removal(v)?;
        self.replace_under(v, None, policy)
    }

    fn replace_under(
        &mut self,
        v: u32,
        to: Option<Point>,
        policy: TopologyPolicy,
    ) -> Result<Vec<TopologyEvent>, MoveError> {
        let mut plan = self.plan_move(v, to)?;
        let quiet =
            plan.crossings.is_empty() && plan.inside.is_empty() && plan.moving_inside.is_none();
        if quiet {
            let moved = self.commit_move(&plan, v, to);
            return Ok(self.settle_move(&mut plan, moved));
        }
        let before = self.clone();
        let moved = self.commit_move(&plan, v, to);
        let events = self.settle_move(&mut plan, moved);
        if let Some(e) = events.iter().find(|e| !policy.allows(e)) {
            let kind = e.kind();
            *self = before;
            return Err(MoveError::Held(kind));
        }
        Ok(events)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Aabb;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> Vec<Point> {
        vec![
            Point::new(x0, y0),
            Point::new(x1, y0),
            Point::new(x1, y1),
            Point::new(x0, y1),
        ]
    }

    fn set_of(rings: &[Vec<Point>]) -> ContourSet {
        let dom = Aabb {
            min: Point::new(0.0, 0.0),
            max: Point::new(100.0, 100.0),
        };
        let mut s = ContourSet::new(dom, 50.0);
        for r in rings {
            s.add_ring(r).unwrap();
        }
        s
    }

    fn at(s: &ContourSet, p: Point) -> u32 {
        s.vertices().find(|&v| s.position(v) == p).unwrap()
    }

    #[test]
    fn a_merge_is_held_and_changes_nothing() {
        let mut s = set_of(&[rect(0.0, 0.0, 10.0, 10.0), rect(20.0, 0.0, 30.0, 10.0)]);
        let v = at(&s, Point::new(10.0, 0.0));
        let before: Vec<_> = s.contour_ids().map(|id| s.ring_points(id)).collect();
        let r = s.move_vertex_under(v, Point::new(25.0, 5.0), TopologyPolicy::TRACKING);
        assert_eq!(r, Err(MoveError::Held("merge")));
        let after: Vec<_> = s.contour_ids().map(|id| s.ring_points(id)).collect();
        assert_eq!(before, after);
        s.sanity_check().unwrap();
        // The adaptive policy merges.
        let ev = s
            .move_vertex_under(v, Point::new(25.0, 5.0), TopologyPolicy::ADAPTIVE)
            .unwrap();
        assert!(matches!(ev[..], [TopologyEvent::Merge { .. }]), "{ev:?}");
    }

    #[test]
    fn a_pinch_splits_under_tracking() {
        // A U-shape whose arm tip is pushed through the other arm: the ring is cut in two.
        let u = vec![
            Point::new(0.0, 0.0),
            Point::new(30.0, 0.0),
            Point::new(30.0, 10.0),
            Point::new(20.0, 10.0),
            Point::new(15.0, 10.0),
            Point::new(10.0, 10.0),
            Point::new(0.0, 10.0),
        ];
        let mut s = set_of(&[u]);
        let v = at(&s, Point::new(15.0, 10.0));
        let ev = s
            .move_vertex_under(v, Point::new(15.0, -5.0), TopologyPolicy::TRACKING)
            .unwrap();
        assert!(matches!(ev[..], [TopologyEvent::Split { .. }]), "{ev:?}");
        assert_eq!(s.contour_count(), 2);
        s.sanity_check().unwrap();
    }
}
