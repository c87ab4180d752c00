//! Exports of a segmentation, as bytes in memory ([`super::atomic`] writes them): one
//! file per format — `json.rs` (the CLI contract), `raster.rs` (mask, label image,
//! overlay), `svg.rs`, `geojson.rs` (QuPath), `csv.rs` — over one bundle, [`Outputs`]; [`Format`] names them.

mod csv;
pub mod ctc;
mod format;
mod geojson;
mod json;
mod raster;
mod svg;

pub use format::{is_tiff, ExportError, Format};

use crate::contours::ContourSet;
use crate::evolution::{Evolver, FrameEvent};
use crate::io::PixelSize;

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

    /// The same outputs with a known pixel size (or none; or none when it is too large or
    /// small to calibrate this image's area).
    pub fn with_pixel_size(mut self, pixel: Option<PixelSize>) -> Self {
        // A size whose square is not a positive finite number (a TIFF resolution of
        // 1e-320, say) calibrates nothing: no `inf` or 0 in the CSV.
        self.pixel = pixel.filter(|p| {
            let area = p.size * p.size * (self.width * self.height) as f64;
            area.is_finite() && p.size * p.size > 0.0
        });
        self
    }
}

pub(crate) fn fmt(v: f64) -> String {
    // Three decimals: sub-pixel, and stable across platforms.
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// The number every export gives the `k`-th region of [`crate::evolution::regions`]
/// (0-based): 1, 2, 3, … It is the value of the region's pixels in the label image, the
/// `id` of its CSV row and GeoJSON feature and the name of its ROI, so a table measured
/// on the labels (Fiji, QuPath) joins the CSV by id. The JSON lists rings by contour id
/// (holes too, and ids are not consecutive after merges): the CSV's `contour` column
/// and GeoJSON's `contour` property give that id.
pub fn object_number(k: usize) -> u32 {
    k as u32 + 1
}

/// `text` (a name, a unit: anything from a user or a file) as one CSV field: in double
/// quotes, inner quotes doubled, and a leading `=`, `+`, `-`, `@`, tab or carriage return
/// behind a `'`, so a spreadsheet shows it as text instead of running it as a formula
/// (OWASP, "CSV Injection").
pub fn csv_quoted(text: &str) -> String {
    let formula = text.starts_with(['=', '+', '-', '@', '\t', '\r']);
    let guard = if formula { "'" } else { "" };
    format!("\"{guard}{}\"", text.replace('"', "\"\""))
}

/// Distinct colours for neighbouring labels (Okabe–Ito, readable by colour-blind users).
pub(crate) const PALETTE: [[u8; 3]; 7] = [
    [230, 159, 0],
    [86, 180, 233],
    [0, 158, 115],
    [240, 228, 66],
    [0, 114, 178],
    [213, 94, 0],
    [204, 121, 167],
];
