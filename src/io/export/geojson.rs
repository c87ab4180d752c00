//! GeoJSON as QuPath reads it.

use super::{object_number, Outputs, PALETTE};
use crate::contours::ContourId;
use crate::evolution::regions;
use serde_json::json;

impl Outputs<'_> {
    /// GeoJSON FeatureCollection of Polygons (outer ring, then holes; closed rings in
    /// pixel coordinates), as QuPath reads them: `objectType`, a `classification` with
    /// name and colour, and the measurements in `properties.measurements` (QuPath
    /// ignores other properties). `id` is the object's number
    /// ([`super::object_number`]), `contour` its outer ring's id in the JSON.
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
            .enumerate()
            .map(|(k, r)| {
                let coords: Vec<_> = std::iter::once(r.id)
                    .chain(r.holes.iter().copied())
                    .map(ring)
                    .collect();
                json!({
                    "type": "Feature",
                    "geometry": {"type": "Polygon", "coordinates": coords},
                    "properties": {
                        "id": object_number(k),
                        "name": format!("object {}", object_number(k)),
                        "contour": r.id,
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
