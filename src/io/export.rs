//! Exports of a segmentation: JSON (the CLI contract), mask PNG, SVG, GeoJSON, CSV, as
//! bytes in memory; [`super::atomic`] writes them.

use crate::contours::{ContourId, ContourSet};
use crate::evolution::{regions, Evolver, FrameEvent};
use crate::geometry::Point;
use crate::io::PixelSize;
use serde_json::json;

/// The finished segmentation, ready to export.
pub struct Outputs<'a> {
    /// The contours.
    pub set: &'a ContourSet,
    /// Image width, pixels.
    pub width: usize,
    /// Image height, pixels.
    pub height: usize,
    /// Frames run.
    pub frames: usize,
    /// Whether the run converged.
    pub converged: bool,
    /// The topology events with their frames.
    pub events: &'a [FrameEvent],
    /// The image's file name (recorded in the JSON and the CSV).
    pub image: &'a str,
    /// The parameters of the run (recorded in the JSON; `mode` names the engine).
    pub params: &'a crate::evolution::Params,
    /// Places where a topology-keeping engine held fronts apart (0 when adaptive).
    pub held: usize,
    /// The physical size of a pixel, if known: the CSV adds calibrated measurements.
    pub pixel: Option<PixelSize>,
}

impl<'a> Outputs<'a> {
    /// The run of `ev` on the image `name` (a file name), with the contours `set` (the
    /// evolver's, or a filtered copy): the one place both the CLI and the app build it.
    pub fn of(ev: &'a Evolver, set: &'a ContourSet, name: &'a str) -> Self {
        let (width, height) = ev.size();
        Outputs {
            set,
            width,
            height,
            frames: ev.frames(),
            converged: ev.is_converged(),
            events: ev.events(),
            image: name,
            params: ev.params(),
            held: ev.held_contacts(),
            pixel: None,
        }
    }

    /// The same outputs with a known pixel size (or none).
    pub fn with_pixel_size(mut self, pixel: Option<PixelSize>) -> Self {
        self.pixel = pixel;
        self
    }
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
            "contours": contours, "events": events, "mode": self.params.mode.name(), "held": self.held,
            "image": self.image, "params": self.params,
        });
        serde_json::to_string(&doc).expect("JSON of plain data")
    }

    /// Inside (255) where a pixel's centre lies in the region, by scanline over all rings
    /// (even-odd, which equals the region for non-crossing rings).
    pub fn mask(&self) -> Vec<u8> {
        let rings: Vec<Vec<Point>> = self
            .set
            .contour_ids()
            .map(|id| self.set.ring_points(id))
            .collect();
        let mut mask = vec![0u8; self.width * self.height];
        fill_even_odd(&rings, self.width, self.height, |i| mask[i] = 255);
        mask
    }

    /// One label per region (outer ring less its holes), 1, 2, … in the order of
    /// [`regions`]; 0 outside.
    pub fn labels(&self) -> Vec<u32> {
        let mut labels = vec![0u32; self.width * self.height];
        for (k, r) in regions(self.set).iter().enumerate() {
            let rings: Vec<Vec<Point>> = std::iter::once(r.id)
                .chain(r.holes.iter().copied())
                .map(|id| self.set.ring_points(id))
                .collect();
            fill_even_odd(&rings, self.width, self.height, |i| {
                labels[i] = k as u32 + 1
            });
        }
        labels
    }

    /// The label image as a 16-bit PNG, or a 16-bit TIFF when `tiff` is true, as Fiji
    /// and QuPath read label images. `None` when there are more regions than 16 bits
    /// can label.
    pub fn labels_image(&self, tiff: bool) -> Option<Vec<u8>> {
        let labels = self.labels();
        let data: Vec<u16> = labels
            .iter()
            .map(|&l| u16::try_from(l).ok())
            .collect::<Option<_>>()?;
        let img = image::ImageBuffer::<image::Luma<u16>, _>::from_raw(
            self.width as u32,
            self.height as u32,
            data,
        )
        .expect("one label per pixel");
        let format = if tiff {
            image::ImageFormat::Tiff
        } else {
            image::ImageFormat::Png
        };
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, format)
            .expect("encoding into memory");
        Some(out.into_inner())
    }

    /// The image in gray with each region tinted in its own colour and every ring (holes
    /// too) drawn on top, as PNG bytes.
    pub fn overlay_png(&self, image: &crate::evolution::Field) -> Vec<u8> {
        let (w, h) = (self.width, self.height);
        let labels = self.labels();
        let colour = |k: u32| PALETTE[(k as usize - 1) % PALETTE.len()];
        let mut rgb = vec![0u8; w * h * 3];
        for i in 0..w * h {
            let g = image.data[i].clamp(0.0, 1.0) * 255.0;
            let px = if labels[i] == 0 {
                [g; 3]
            } else {
                let c = colour(labels[i]);
                std::array::from_fn(|k| 0.7 * g + 0.3 * c[k] as f32)
            };
            for k in 0..3 {
                rgb[3 * i + k] = px[k] as u8;
            }
        }
        for (k, r) in regions(self.set).iter().enumerate() {
            let c = colour(k as u32 + 1);
            for id in std::iter::once(r.id).chain(r.holes.iter().copied()) {
                let pts = self.set.ring_points(id);
                for i in 0..pts.len() {
                    draw_segment(&mut rgb, w, h, pts[i], pts[(i + 1) % pts.len()], c);
                }
            }
        }
        let mut out = Vec::new();
        let enc = image::codecs::png::PngEncoder::new(&mut out);
        image::ImageEncoder::write_image(
            enc,
            &rgb,
            w as u32,
            h as u32,
            image::ExtendedColorType::Rgb8,
        )
        .expect("PNG encoding into memory");
        out
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

/// `text` as one CSV field: in double quotes, inner quotes doubled.
pub fn csv_quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// Distinct colours for neighbouring labels (Okabe–Ito, readable by colour-blind users).
const PALETTE: [[u8; 3]; 7] = [
    [230, 159, 0],
    [86, 180, 233],
    [0, 158, 115],
    [240, 228, 66],
    [0, 114, 178],
    [213, 94, 0],
    [204, 121, 167],
];

/// Calls `set` for every pixel whose centre lies inside `rings` by the even-odd rule,
/// scanline by scanline; edges are bucketed by the rows they span, so the cost is linear
/// in the output size.
fn fill_even_odd(rings: &[Vec<Point>], w: usize, h: usize, mut set: impl FnMut(usize)) {
    let mut rows: Vec<Vec<(Point, Point)>> = vec![Vec::new(); h];
    for r in rings {
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
    let mut xs: Vec<f64> = Vec::new();
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
            for x in x0..x1 {
                set(y * w + x);
            }
        }
    }
}

/// A one-pixel line from `a` to `b` (pixel coordinates), sampled every half pixel.
fn draw_segment(rgb: &mut [u8], w: usize, h: usize, a: Point, b: Point, c: [u8; 3]) {
    let n = (a.dist(b) * 2.0).ceil().max(1.0) as usize;
    for i in 0..=n {
        let p = a.lerp(b, i as f64 / n as f64);
        let (x, y) = (p.x.floor(), p.y.floor());
        if x >= 0.0 && y >= 0.0 && (x as usize) < w && (y as usize) < h {
            let k = 3 * (y as usize * w + x as usize);
            rgb[k..k + 3].copy_from_slice(&c);
        }
    }
}
