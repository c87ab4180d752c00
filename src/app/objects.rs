//! The object table's rows: the regions of the frame on screen, measured once per frame
//! shown (the table is drawn every frame).

use super::FrameRecord;
use crate::evolution::measure::{regions_of_rings, Region};

/// Measured regions of the last frame asked for.
#[derive(Default)]
pub struct ObjectTable {
    key: Option<(usize, usize, usize)>,
    rows: std::sync::Arc<Vec<Region>>,
}

impl ObjectTable {
    /// The regions of `rec`, largest first.
    pub fn rows(&mut self, rec: &FrameRecord) -> std::sync::Arc<Vec<Region>> {
        let key = (rec.index, rec.vertices, rec.rings.len());
        if self.key != Some(key) {
            let rings: Vec<(u32, bool, &[crate::geometry::Point])> = rec
                .rings
                .iter()
                .map(|r| (r.id, r.hole, r.points.as_slice()))
                .collect();
            let mut rows = regions_of_rings(&rings);
            rows.sort_by(|a, b| b.area.total_cmp(&a.area));
            self.rows = std::sync::Arc::new(rows);
            self.key = Some(key);
        }
        self.rows.clone()
    }
}
