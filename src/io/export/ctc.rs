//! Tracking outputs: the Cell Tracking Challenge result layout (one 16-bit label TIFF per
//! frame, `maskTTT.tif` with at least three digits, and `res_track.txt`, see
//! [`crate::track::Lineage::ctc_text`]), one CSV row per cell per frame, the JSON of every
//! frame's contours with their tracks and the divisions, and overlays coloured by track
//! with each track's label written beside its cell.

use super::raster::draw_segment;
use super::PALETTE;
use crate::evolution::Field;
use crate::track::{Lineage, TrackedFrame};

/// The mask file name of frame `t` in a movie of `frames` frames: `mask000.tif`, with
/// more digits only when the movie needs them.
pub fn mask_name(t: usize, frames: usize) -> String {
    let digits = frames.saturating_sub(1).to_string().len().max(3);
    format!("mask{t:0digits$}.tif")
}

/// A name the CTC result folder holds: `mask` + at least three digits + `.tif`.
pub fn is_mask_name(name: &str) -> bool {
    name.strip_prefix("mask")
        .and_then(|r| r.strip_suffix(".tif"))
        .is_some_and(|d| d.len() >= 3 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// A name the CTC result folder holds or may clear: a mask or `res_track.txt`.
pub fn is_result_name(name: &str) -> bool {
    name == "res_track.txt" || is_mask_name(name)
}

/// Removes the masks of an earlier result from the CTC folder `dir`: regular files named
/// `mask` + digits + `.tif` other than `written` (this run's, by name). A folder used
/// before would otherwise keep frames past this movie's end (or of another digit count)
/// beside the new ones, and be no valid result. Called once the new result is written.
/// Returns how many it removed (the user is told: they were files in a folder they chose).
pub fn remove_stale_masks(dir: &std::path::Path, written: &[String]) -> std::io::Result<usize> {
    let mut removed = 0;
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if is_mask_name(&name) && !written.contains(&name) && entry.file_type()?.is_file() {
            std::fs::remove_file(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}

/// A label raster as a 16-bit TIFF (`tiff`) or PNG; `None` beyond 65,535 labels.
pub fn label_image(labels: &[u32], width: usize, height: usize, tiff: bool) -> Option<Vec<u8>> {
    let data: Vec<u16> = labels
        .iter()
        .map(|&l| u16::try_from(l).ok())
        .collect::<Option<_>>()?;
    let img =
        image::ImageBuffer::<image::Luma<u16>, _>::from_raw(width as u32, height as u32, data)
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

/// The CSV header of [`csv_rows`].
pub const CSV_HEADER: &str = "track,frame,area_px,centroid_x,centroid_y,parent\n";

/// One row per cell of frame `frame`, from its mask `labels` (`width` wide, track labels,
/// 0 outside), as the label image holds it: track, frame, area (the cell's pixels),
/// centroid (of its pixels' centres), parent track (0: none). From the mask, not the
/// outline, so the CSV and the masks give a cell one size: the masks reach to the cells'
/// edges ([`crate::image::widen::to_edges`]), and a growth rate read from the outline's
/// area was 20–35 % below the mask's on a phase-contrast colony.
pub fn csv_rows(frame: usize, labels: &[u32], width: usize, lineage: &Lineage) -> String {
    let mut sums: std::collections::BTreeMap<u32, (usize, f64, f64)> = Default::default();
    for (i, &l) in labels.iter().enumerate() {
        if l != 0 {
            let e = sums.entry(l).or_default();
            e.0 += 1;
            e.1 += (i % width) as f64 + 0.5;
            e.2 += (i / width) as f64 + 0.5;
        }
    }
    sums.into_iter()
        .map(|(track, (n, x, y))| {
            let parent = lineage.get(track).map_or(0, |t| t.parent);
            let n = n as f64;
            format!(
                "{},{},{:.2},{:.3},{:.3},{}\n",
                track,
                frame,
                n,
                x / n,
                y / n,
                parent
            )
        })
        .collect()
}

/// The JSON of a tracked movie: per frame the cells (track, area, centroid, outline),
/// the divisions, and the tracks.
pub fn json(movie: &str, frames: &[TrackedFrame], lineage: &Lineage) -> String {
    let divisions: Vec<_> = frames.iter().flat_map(|f| f.divisions.iter()).collect();
    let frames: Vec<serde_json::Value> = frames
        .iter()
        .map(|f| {
            serde_json::json!({
                "frame": f.frame,
                "objects": f.objects.iter().map(|o| serde_json::json!({
                    "track": o.track,
                    "area": o.area,
                    "centroid": [o.centroid.x, o.centroid.y],
                    "ring": o.ring.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    let doc = serde_json::json!({
        "movie": movie,
        "frames": frames,
        "divisions": divisions,
        "tracks": lineage.tracks(),
    });
    serde_json::to_string_pretty(&doc).expect("JSON of plain values")
}

/// The colour of track `label`, the same in every frame.
fn colour(label: u32) -> [u8; 3] {
    PALETTE[(label as usize).wrapping_mul(5) % PALETTE.len()]
}

/// An overlay is drawn this many pixels or more on its longer side where a whole factor
/// up to [`OVERLAY_MAX_SCALE`] reaches it: at a movie's own size a label covers a small
/// cell and runs into its neighbours' labels.
pub const OVERLAY_SIDE: usize = 1024;

/// The largest factor a frame is scaled up by for its overlay.
pub const OVERLAY_MAX_SCALE: usize = 4;

/// One tracked frame drawn over its image, scaled up by the whole factor (nearest pixel,
/// at most [`OVERLAY_MAX_SCALE`]) that brings its longer side to [`OVERLAY_SIDE`] or
/// more: each track's outline in its colour, its label on it. RGB bytes and their width
/// and height.
pub fn overlay_rgb(image: &Field, frame: &TrackedFrame) -> (Vec<u8>, usize, usize) {
    let (w, h) = (image.width, image.height);
    let k = OVERLAY_SIDE
        .div_ceil(w.max(h).max(1))
        .clamp(1, OVERLAY_MAX_SCALE);
    let (sw, sh) = (w * k, h * k);
    let mut rgb = vec![0u8; sw * sh * 3];
    for (i, px) in rgb.chunks_exact_mut(3).enumerate() {
        let (x, y) = (i % sw / k, i / sw / k);
        px.fill((image.data[y * w + x].clamp(0.0, 1.0) * 255.0) as u8);
    }
    let scaled = |p: crate::geometry::Point| p * k as f64;
    for o in &frame.objects {
        let c = colour(o.track);
        for i in 0..o.ring.len() {
            let (a, b) = (o.ring[i], o.ring[(i + 1) % o.ring.len()]);
            draw_segment(&mut rgb, sw, sh, scaled(a), scaled(b), c);
        }
        draw_number(&mut rgb, sw, sh, scaled(o.centroid), o.track, c);
    }
    (rgb, sw, sh)
}

/// RGB bytes as PNG.
pub fn png(rgb: &[u8], width: usize, height: usize) -> Vec<u8> {
    let mut out = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut out);
    image::ImageEncoder::write_image(
        enc,
        rgb,
        width as u32,
        height as u32,
        image::ExtendedColorType::Rgb8,
    )
    .expect("PNG encoding into memory");
    out
}

/// 3×5 digit glyphs, one row per 3 bits.
const DIGITS: [[u8; 5]; 10] = [
    [7, 5, 5, 5, 7],
    [2, 6, 2, 2, 7],
    [7, 1, 7, 4, 7],
    [7, 1, 3, 1, 7],
    [5, 5, 7, 1, 1],
    [7, 4, 7, 1, 7],
    [7, 4, 7, 5, 7],
    [7, 1, 1, 2, 2],
    [7, 5, 7, 5, 7],
    [7, 5, 7, 1, 7],
];

/// Writes `n` centred on `at`, glyphs scaled twice, in `c` on a black box.
fn draw_number(rgb: &mut [u8], w: usize, h: usize, at: crate::geometry::Point, n: u32, c: [u8; 3]) {
    let text = n.to_string();
    let (gw, gh, s) = (4usize, 6usize, 2usize);
    let x0 = at.x as isize - (text.len() * gw * s) as isize / 2;
    let y0 = at.y as isize - (gh * s) as isize / 2;
    for (k, ch) in text.bytes().enumerate() {
        let glyph = DIGITS[(ch - b'0') as usize];
        for gy in 0..gh * s {
            for gx in 0..gw * s {
                let (x, y) = (x0 + (k * gw * s + gx) as isize, y0 + gy as isize);
                if x < 0 || y < 0 || x >= w as isize || y >= h as isize {
                    continue;
                }
                let (col, row) = (gx / s, gy / s);
                let on = row < 5 && col < 3 && glyph[row] >> (2 - col) & 1 == 1;
                let i = 3 * (y as usize * w + x as usize);
                rgb[i..i + 3].copy_from_slice(&if on { c } else { [0; 3] });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mask_names_have_at_least_three_digits() {
        assert_eq!(mask_name(7, 65), "mask007.tif");
        assert_eq!(mask_name(7, 2000), "mask0007.tif");
    }
}
