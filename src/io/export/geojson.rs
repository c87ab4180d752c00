//! GeoJSON as QuPath reads it.

use super::{Outputs, PALETTE};
use crate::contours::ContourId;
use crate::evolution::regions;
use serde_json::json;

impl Outputs<'_> {
    /// GeoJSON FeatureCollection of Polygons (outer ring, then holes; closed rings in
    /// pixel coordinates), as QuPath reads them: `objectType`, a `classification` with
    /// name and colour, and the measurements in `properties.measurements` (QuPath
    /// ignores other properties).
    pub fn geojson(&self) -> String {
        let ring = |id: ContourId| {
            let mut pts: Vec<[f64; 2]> = self
                .set
                .ring_points(id)
                .iter()
                .map(|p| [p.x, p.y])
                .collect();
            pts.push(pts[0]);
            pts
        };
        let features: Vec<_> = regions(self.set)
            .iter()
            .map(|r| {
                let coords: Vec<_> = std::iter::once(r.id)
                    .chain(r.holes.iter().copied())
                    .map(ring)
                    .collect();
                json!({
                    "type": "Feature",
                    "geometry": {"type": "Polygon", "coordinates": coords},
                    "properties": {
                        "id": r.id,
                        "name": format!("object {}", r.id),
                        "objectType": "annotation",
                        "classification": {"name": "Object", "color": PALETTE[0]},
                        "measurements": {
                            "Area px^2": r.area,
                            "Perimeter px": r.perimeter,
                            "Circularity": r.circularity,
                            "Centroid X px": r.centroid.x,
                            "Centroid Y px": r.centroid.y,
                            "Holes": r.holes.len(),
                        },
                    },
                })
            })
            .collect();
        serde_json::to_string(&json!({"type": "FeatureCollection", "features": features}))
            .expect("JSON of plain data")
    }
}
