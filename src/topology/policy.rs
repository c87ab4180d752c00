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
//! carried out at once (it cannot change topology). Where merges are held, a move whose
//! new edges cross another object's outline is refused at once: it would join the two,
//! or (the property test found one) cut through the other so that only a split is
//! reported — the other cell torn by its neighbour, not dividing. Two touching cells
//! press on each other in most tracked frames, thousands of such moves a frame; carried
//! out and put back, they made a 512² frame of a 60-cell colony 1.5–3 times slower
//! (docs/decisions.md, 2026-12-06). Any other move is carried out on the
//! set, and if one of its events is one the policy holds back, the set is put back as it
//! was and the move is refused with [`MoveError::Held`]. Putting back is local
//! (`Undo`): a move changes only the rings it crosses, its own and those inside its
//! motion region, so only those are recorded before it (vertex ids, links, positions,
//! ring entries) with the free list, and restored after; a copy of the whole set cost
//! 15 % of a tracked frame, where two objects press on each other in most frames. So the
//! rings after a held move are exactly the rings before (the same vertex and ring ids),
//! and an allowed move is exactly the adaptive move.

use super::plan::MovePlan;
use super::{MoveError, TopologyEvent};
use crate::contours::{BroadPhase, ContourSet, Ring, VertexId, NIL};
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
        if !policy.merge && self.crosses_another_object(&plan) {
            return Err(MoveError::Held("merge"));
        }
        let quiet =
            plan.crossings.is_empty() && plan.inside.is_empty() && plan.moving_inside.is_none();
        if quiet {
            let moved = self.commit_move(&plan, v, to);
            return Ok(self.settle_move(&mut plan, moved));
        }
        let undo = Undo::record(self, &plan);
        let moved = self.commit_move(&plan, v, to);
        let events = self.settle_move(&mut plan, moved);
        if let Some(e) = events.iter().find(|e| !policy.allows(e)) {
            let kind = e.kind();
            undo.restore(self);
            return Err(MoveError::Held(kind));
        }
        Ok(events)
    }

    /// Whether a planned move's new edges cross the outline of another object: an outer
    /// ring other than the moving one, itself outer. Such a move joins the two regions
    /// (a merge), or cuts through the other object; neither is one object dividing.
    fn crosses_another_object(&self, plan: &MovePlan) -> bool {
        let outer = |l: u32| {
            let r = self.ring(l);
            self.loop_is_outer(r.anchor, r.area2)
        };
        plan.crossings.iter().any(|c| {
            let l = self.label[c.edge as usize];
            l != plan.label && outer(l)
        }) && outer(plan.label)
    }
}

/// A ring a move touches, as it was: its id, its entry and its vertices (id, position) in
/// ring order from the anchor.
type TouchedRing = (u32, Ring, Vec<(u32, Point)>);

/// What a planned move may change, as it was: the rings it touches (its own, those it
/// crosses, those inside its motion region) vertex by vertex, and the set's allocation
/// state. A move allocates and frees vertex slots and ring ids but changes no vertex of
/// another ring, so these suffice to put the set back.
struct Undo {
    rings: Vec<TouchedRing>,
    free: Vec<u32>,
    slots: usize,
    ring_slots: usize,
    live_rings: usize,
    reach: f64,
}

impl Undo {
    fn record(set: &ContourSet, plan: &MovePlan) -> Undo {
        let mut ids = vec![plan.label];
        let more = plan.old.iter().map(|r| r.id);
        for id in more.chain(plan.inside.iter().map(|&(l, _)| l)) {
            if !ids.contains(&id) {
                ids.push(id);
            }
        }
        let rings = ids
            .into_iter()
            .map(|id| {
                let r = *set.ring(id);
                let pts = set
                    .walk(r.anchor)
                    .map(|w| (w, set.pos[w as usize]))
                    .collect();
                (id, r, pts)
            })
            .collect();
        Undo {
            rings,
            free: set.free.clone(),
            slots: set.pos.len(),
            ring_slots: set.rings.len(),
            live_rings: set.live_rings,
            reach: set.reach,
        }
    }

    /// Puts `set` back as it was when recorded. Vertices the move made are freed (and
    /// forgotten by the broad phase), the recorded ones take their slots, links and
    /// positions again; the broad phase is told only what changed.
    fn restore(self, set: &mut ContourSet) {
        let stamp = set.next_stamp();
        for (_, _, pts) in &self.rings {
            for &(w, _) in pts {
                set.mark[w as usize] = stamp;
            }
        }
        // The rings the move left where the touched rings were: touched ids still live,
        // and the ids it made.
        let now: Vec<u32> = self
            .rings
            .iter()
            .map(|&(id, _, _)| id)
            .chain(self.ring_slots as u32..set.rings.len() as u32)
            .filter_map(|id| set.rings.get(id as usize).copied().flatten())
            .flat_map(|r| set.walk(r.anchor).collect::<Vec<_>>())
            .collect();
        for w in now {
            if set.mark[w as usize] != stamp {
                set.bins.remove(w);
                set.label[w as usize] = NIL;
            }
        }
        for (id, _, pts) in &self.rings {
            let n = pts.len();
            for (i, &(w, p)) in pts.iter().enumerate() {
                let wi = w as usize;
                if set.label[wi] == NIL {
                    set.bins.insert(w, p);
                } else if set.pos[wi] != p {
                    set.bins.update(w, p);
                }
                set.pos[wi] = p;
                set.label[wi] = *id;
                set.next[wi] = pts[(i + 1) % n].0;
                set.prev[wi] = pts[(i + n - 1) % n].0;
            }
        }
        set.pos.truncate(self.slots);
        set.next.truncate(self.slots);
        set.prev.truncate(self.slots);
        set.label.truncate(self.slots);
        set.mark.truncate(self.slots);
        set.rings.truncate(self.ring_slots);
        for (id, ring, _) in self.rings {
            set.rings[id as usize] = Some(ring);
        }
        set.free = self.free;
        set.live_rings = self.live_rings;
        set.reach = self.reach;
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
