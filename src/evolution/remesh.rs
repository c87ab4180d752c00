//! Remeshing (seed 004 §2.3): keep every edge within [d_min, d_max] by splitting long
//! edges at their midpoint and removing a vertex of short ones. Both are topology-safe
//! operations of the core (a removal is a motion and may even change topology, which is
//! reported like any other event).

use crate::contours::ContourSet;
use crate::topology::TopologyEvent;

/// One remeshing pass over all rings.
/// With `preserve_gap`, a vertex is removed only if the chord keeps that gap to all other
/// edges (so remeshing never changes topology either).
pub fn remesh(
    set: &mut ContourSet,
    d_min: f64,
    d_max: f64,
    preserve_gap: Option<f64>,
    events: &mut Vec<TopologyEvent>,
) {
    let order: Vec<u32> = set.vertices().collect();
    for v in order {
        if !set.is_alive(v) {
            continue;
        }
        let n = set.next(v);
        let len = set.position(v).dist(set.position(n));
        if len > d_max {
            set.split_edge(v, (len / d_max).ceil() as usize);
        } else if len < d_min && set.ring_len(set.contour_of(v)) > 3 {
            // Remove the end of the short edge if the edge that replaces it stays short.
            let nn = set.next(n);
            let clear = preserve_gap.is_none_or(|g| set.move_is_clear(n, None, g));
            if clear && set.position(v).dist(set.position(nn)) <= d_max {
                if let Ok(ev) = set.remove_vertex(n) {
                    events.extend(ev);
                }
            }
        }
    }
}
