//! The initial rings of a run: the user's shapes clipped to the image, their union the
//! region.

use super::params::{EvolveError, Params};
use crate::contours::ContourSet;
use crate::geometry::Aabb;
use crate::shape::Shape;

/// The initial rings: each shape clipped to the image with vertices 1.5 grid spacings
/// apart; the region is the union of the shapes.
pub(crate) fn initial_set(
    init: &[Shape],
    domain: Aabb,
    spacing: f64,
    params: &Params,
) -> Result<ContourSet, EvolveError> {
    let mut set = ContourSet::with_broad_phase(
        domain,
        spacing * 2.0 * std::f64::consts::SQRT_2,
        params.broad_phase,
    );
    for shape in init {
        // Overlapping shapes: a smaller copy still seeds the region; growth joins them.
        for f in [1.0, 0.5, 0.25] {
            let ring = shape.scaled(f).ring_within(spacing * 1.5, &domain);
            if ring.len() >= 3 && set.add_ring(&ring).is_ok() {
                break;
            }
        }
    }
    // A ring inside another shape's ring (a seed inside the wrap rectangle) bounds nothing
    // new, and an outer ring nested in an outer ring would break the orientation invariant.
    let nested: Vec<_> = set
        .parents()
        .into_iter()
        .filter(|(_, parent)| parent.is_some())
        .map(|(id, _)| id)
        .collect();
    for id in nested {
        set.remove_ring(id);
    }
    if set.contour_count() == 0 {
        return Err(EvolveError::EmptyInit);
    }
    Ok(set)
}
