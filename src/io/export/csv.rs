//! Measurements as CSV, one row per region, with the pixel size and calibrated
//! measurements when known.

use super::{csv_quoted, fmt, Outputs};
use crate::evolution::regions;

impl Outputs<'_> {
    /// Measurements, one row per region.
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,pixel_size,unit,area_calibrated,perimeter_calibrated\n",
        );
        let image = csv_quoted(self.image);
        // Calibrated columns stay empty without a pixel size.
        let (size, unit) = match &self.pixel {
            Some(p) => (format!("{}", p.size), csv_quoted(&p.unit)),
            None => (String::new(), String::new()),
        };
        for r in regions(self.set) {
            let (area, perimeter) = match &self.pixel {
                Some(p) => (
                    format!("{:e}", r.area * p.size * p.size),
                    format!("{:e}", r.perimeter * p.size),
                ),
                None => (String::new(), String::new()),
            };
            s.push_str(&format!(
                "{image},{},{},{},{},{},{},{},{size},{unit},{area},{perimeter}\n",
                r.id,
                fmt(r.area),
                fmt(r.perimeter),
                fmt(r.circularity),
                fmt(r.centroid.x),
                fmt(r.centroid.y),
                r.holes.len()
            ));
        }
        s
    }
}
