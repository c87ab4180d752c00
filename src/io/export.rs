//! Exports of a segmentation: JSON (the CLI contract), mask PNG, SVG, GeoJSON, CSV, as
//! bytes in memory; [`super::atomic`] writes them.

use crate::contours::{ContourId, ContourSet};
use crate::evolution::{regions, FrameEvent};
use crate::geometry::Point;
use serde_json::json;

/// The finished segmentation, ready to export.
pub struct Outputs<'a> {
    pub set: &'a ContourSet,
    pub width: usize,
    pub height: usize,
    pub frames: usize,
    pub converged: bool,
    pub events: &'a [FrameEvent],
    /// Engine name (`adaptive`, `preserve`, `implicit`).
    pub mode: &'a str,
    /// Places where a topology-keeping engine held fronts apart (0 when adaptive).
    pub held: usize,
}

fn fmt(v: f64) -> String {
    // Three decimals: sub-pixel, and stable across platforms.
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

impl Outputs<'_> {
    /// The JSON document of the CLI contract.
    pub fn json(&self) -> String {
        let parents = self.set.parents();
        let contours: Vec<_> = parents
            .iter()
            .map(|&(id, parent)| {
                let pts: Vec<[f64; 2]> = self.set.ring_points(id).iter().map(|p| [p.x, p.y]).collect();
                json!({"id": id, "hole": self.set.is_hole(id), "parent": parent, "area": self.set.signed_area(id).abs(), "points": pts})
            })
            .collect();
        let events: Vec<_> = self.events.iter().map(|e| json!({"frame": e.frame, "kind": e.event.kind(), "contours": e.event.contours()})).collect();
        let doc = json!({
            "width": self.width, "height": self.height, "frames": self.frames, "converged": self.converged,
            "contours": contours, "events": events, "mode": self.mode, "held": self.held,
        });
        serde_json::to_string(&doc).expect("JSON of plain data")
    }

    /// Inside (255) where a pixel's centre lies in the region, by scanline over all rings
    /// (even-odd, which equals the region for non-crossing rings).
    pub fn mask(&self) -> Vec<u8> {
        let (w, h) = (self.width, self.height);
        let mut mask = vec![0u8; w * h];
        let rings: Vec<Vec<Point>> = self
            .set
            .contour_ids()
            .map(|id| self.set.ring_points(id))
            .collect();
        let mut xs: Vec<f64> = Vec::new();
        // Edges bucketed by the rows they span keep this linear in the output size.
        let mut rows: Vec<Vec<(Point, Point)>> = vec![Vec::new(); h];
        for r in &rings {
            for i in 0..r.len() {
                let (a, b) = (r[i], r[(i + 1) % r.len()]);
                let (y0, y1) = (a.y.min(b.y), a.y.max(b.y));
                let lo = (y0 - 0.5).ceil().max(0.0) as usize;
                let hi = ((y1 - 0.5).floor()).min(h as f64 - 1.0);
                if hi < 0.0 {
                    continue;
                }
                for row in rows.iter_mut().take(hi as usize + 1).skip(lo) {
                    row.push((a, b));
                }
            }
        }
        for (y, row) in rows.iter().enumerate() {
            let yc = y as f64 + 0.5;
            xs.clear();
            for &(a, b) in row {
                if (a.y > yc) != (b.y > yc) {
                    xs.push(a.x + (yc - a.y) * (b.x - a.x) / (b.y - a.y));
                }
            }
            xs.sort_by(f64::total_cmp);
            for pair in xs.chunks_exact(2) {
                // Pixels whose centre x + 0.5 lies in [x0, x1).
                let x0 = (pair[0] - 0.5).ceil().max(0.0) as usize;
                let x1 = ((pair[1] - 0.5).ceil().max(0.0) as usize).min(w);
                if x0 < x1 {
                    mask[y * w + x0..y * w + x1].fill(255);
                }
            }
        }
        mask
    }

    /// Mask as PNG bytes.
    pub fn mask_png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let enc = image::codecs::png::PngEncoder::new(&mut out);
        image::ImageEncoder::write_image(
            enc,
            &self.mask(),
            self.width as u32,
            self.height as u32,
            image::ExtendedColorType::L8,
        )
        .expect("PNG encoding into memory");
        out
    }

    fn path_d(&self, rings: &[ContourId]) -> String {
        let mut d = String::new();
        for &r in rings {
            for (i, p) in self.set.ring_points(r).iter().enumerate() {
                d.push_str(if i == 0 { "M" } else { "L" });
                d.push_str(&fmt(p.x));
                d.push(' ');
                d.push_str(&fmt(p.y));
            }
            d.push('Z');
        }
        d
    }

    /// SVG: one path per outer ring with its holes, even-odd fill, the image as viewBox.
    pub fn svg(&self) -> String {
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n",
            w = self.width,
            h = self.height
        );
        for r in regions(self.set) {
            let rings: Vec<ContourId> = std::iter::once(r.id)
                .chain(r.holes.iter().copied())
                .collect();
            s.push_str(&format!(
                "  <path id=\"contour-{}\" fill=\"#e8a33d\" fill-opacity=\"0.5\" fill-rule=\"evenodd\" d=\"{}\"/>\n",
                r.id,
                self.path_d(&rings)
            ));
        }
        s.push_str("</svg>\n");
        s
    }

    /// GeoJSON FeatureCollection of Polygons (outer ring, then holes; closed rings in
    /// pixel coordinates), as QuPath and napari read them.
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
                let coords: Vec<_> = std::iter::once(r.id).chain(r.holes.iter().copied()).map(ring).collect();
                json!({
                    "type": "Feature",
                    "geometry": {"type": "Polygon", "coordinates": coords},
                    "properties": {"id": r.id, "objectType": "annotation", "area": r.area, "perimeter": r.perimeter},
                })
            })
            .collect();
        serde_json::to_string(&json!({"type": "FeatureCollection", "features": features}))
            .expect("JSON of plain data")
    }

    /// Measurements, one row per region.
    pub fn csv(&self) -> String {
        let mut s = String::from("id,area,perimeter,circularity,centroid_x,centroid_y,holes\n");
        for r in regions(self.set) {
            s.push_str(&format!(
                "{},{},{},{},{},{},{}\n",
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
