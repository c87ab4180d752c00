//! Tracking on from a frame already tracked: the app's hand corrections of frame t
//! (a wrong split undone, a merge forced) make a new frame t, and the frames after it
//! are tracked again from its contours, as [`Tracker::step`] would have from its own.

use super::carry::label_raster;
use super::{Lineage, TrackSettings, TrackedFrame, Tracker};
use crate::geometry::Point;

impl Tracker {
    /// A tracker whose next frame is `last.frame + 1`, started from `last`'s cells, with
    /// the tracks so far `lineage`, on `width`×`height` frames.
    pub fn resume(
        settings: TrackSettings,
        lineage: Lineage,
        last: &TrackedFrame,
        width: usize,
        height: usize,
    ) -> Self {
        let mut t = Tracker::new(settings, Vec::new());
        t.lineage = lineage;
        t.live = last
            .objects
            .iter()
            .map(|o| (o.track, o.ring.clone()))
            .collect();
        let rings: Vec<(u32, &[Point])> = last
            .objects
            .iter()
            .map(|o| (o.track, o.ring.as_slice()))
            .collect();
        t.labels = label_raster(&rings, width, height);
        t.frame = last.frame + 1;
        t
    }
}
