//! A user's strokes as a label image: 0 unlabelled, 1 background, 2 object, 3 boundary
//! between touching objects (the values `shared/tools/scribbles.py` writes and ilastik's
//! label export uses), checked against the image they were painted on.
//!
//! A session stores its strokes inline as runs ([`Strokes`]' serde form: width,
//! height and a string of `gap length label` triples over the pixels row by row). Why
//! runs in the session rather than a PNG beside it: strokes cover about 1 % of the
//! pixels in a few dozen strokes, so the runs are a few kilobytes of text; one file
//! stays one atomic write, moves as a whole, and cannot lose its strokes to a missing
//! or swapped side file.

use std::path::Path;

/// Stroke label of background.
pub const BACKGROUND: u8 = 1;
/// Stroke label of object interior.
pub const OBJECT: u8 = 2;
/// Stroke label of the boundary between touching objects.
pub const BOUNDARY: u8 = 3;

/// Why strokes cannot be used.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum StrokeError {
    /// The file could not be read or decoded.
    #[error("cannot read the strokes {path}: {reason}")]
    Read {
        /// The file.
        path: String,
        /// What failed.
        reason: String,
    },
    /// Not the image's size.
    #[error("the strokes are {got_w}×{got_h} but the image is {want_w}×{want_h}")]
    Size {
        /// The strokes' width.
        got_w: usize,
        /// The strokes' height.
        got_h: usize,
        /// The image's width.
        want_w: usize,
        /// The image's height.
        want_h: usize,
    },
    /// A value other than 0–3.
    #[error("the strokes hold the value {value} at ({x}, {y}); labels are 0 none, 1 background, 2 object, 3 boundary")]
    Value {
        /// The value.
        value: u8,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
    },
    /// No object pixel.
    #[error("the strokes mark no object pixel (label 2)")]
    NoObject,
    /// Only one class.
    #[error("the strokes mark only one class; paint background (1) or boundary (3) too")]
    OneClass,
}

/// A stroke label image.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "StrokeRuns", try_from = "StrokeRuns")]
pub struct Strokes {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Labels row by row.
    pub labels: Vec<u8>,
}

impl Strokes {
    /// Checked strokes: values 0–3, an object class and at least one other.
    pub fn new(width: usize, height: usize, labels: Vec<u8>) -> Result<Self, StrokeError> {
        assert_eq!(labels.len(), width * height, "stroke image size");
        if let Some(i) = labels.iter().position(|&v| v > BOUNDARY) {
            return Err(StrokeError::Value {
                value: labels[i],
                x: i % width,
                y: i / width,
            });
        }
        let mut seen = [false; 4];
        for &v in &labels {
            seen[v as usize] = true;
        }
        if !seen[OBJECT as usize] {
            return Err(StrokeError::NoObject);
        }
        if !seen[BACKGROUND as usize] && !seen[BOUNDARY as usize] {
            return Err(StrokeError::OneClass);
        }
        Ok(Strokes {
            width,
            height,
            labels,
        })
    }

    /// Reads a stroke PNG and checks it against a `width` × `height` image.
    pub fn read(path: &Path, width: usize, height: usize) -> Result<Self, StrokeError> {
        let (w, h, labels) = decode(path)?;
        Strokes::for_image(w, h, labels, width, height)
    }

    /// [`Strokes::new`] for a `width` × `height` image: the size is checked first
    /// (strokes of another image are that, whatever they hold), then the labels.
    pub fn for_image(
        w: usize,
        h: usize,
        labels: Vec<u8>,
        width: usize,
        height: usize,
    ) -> Result<Self, StrokeError> {
        Strokes {
            width: w,
            height: h,
            labels: Vec::new(),
        }
        .check_size(width, height)?;
        Strokes::new(w, h, labels)
    }

    /// Reads a stroke PNG of any size; [`Strokes::check_size`] checks it against an image.
    pub fn read_any(path: &Path) -> Result<Self, StrokeError> {
        let (w, h, labels) = decode(path)?;
        Strokes::new(w, h, labels)
    }

    /// Whether the strokes are `width` × `height` (the image they are used on).
    pub fn check_size(&self, width: usize, height: usize) -> Result<(), StrokeError> {
        if (self.width, self.height) != (width, height) {
            return Err(StrokeError::Size {
                got_w: self.width,
                got_h: self.height,
                want_w: width,
                want_h: height,
            });
        }
        Ok(())
    }

    /// The labels present, in order (1, 2, 3 at most).
    pub fn classes(&self) -> Vec<u8> {
        let mut seen = [false; 4];
        for &v in &self.labels {
            seen[v as usize] = true;
        }
        (1..=BOUNDARY).filter(|&l| seen[l as usize]).collect()
    }
}

/// Width, height and values of a stroke image file (PNG or any gray image the `image`
/// crate decodes; 16-bit values are taken as they are).
fn decode(path: &Path) -> Result<(usize, usize, Vec<u8>), StrokeError> {
    let read = |reason: String| StrokeError::Read {
        path: path.display().to_string(),
        reason,
    };
    let img = image::ImageReader::open(path)
        .map_err(|e| read(e.to_string()))?
        .with_guessed_format()
        .map_err(|e| read(e.to_string()))?
        .decode()
        .map_err(|e| read(e.to_string()))?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    // The values as stored (a conversion would scale 8-bit labels to 16 bits); above
    // 255 is no label: saturate so the value check names it.
    let labels = match img {
        image::DynamicImage::ImageLuma8(b) => b.into_raw(),
        image::DynamicImage::ImageLuma16(b) => {
            b.into_raw().into_iter().map(|v| v.min(255) as u8).collect()
        }
        image::DynamicImage::ImageLumaA8(b) => b.into_raw().chunks(2).map(|p| p[0]).collect(),
        other => other.into_luma8().into_raw(),
    };
    Ok((w, h, labels))
}

/// The serde form of [`Strokes`]: runs of labelled pixels.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct StrokeRuns {
    width: usize,
    height: usize,
    /// `gap length label` triples, space-separated: `gap` unlabelled pixels, then
    /// `length` pixels of `label`, over the pixels row by row.
    runs: String,
}

impl From<Strokes> for StrokeRuns {
    fn from(s: Strokes) -> Self {
        let mut runs = String::new();
        let (mut gap, mut i) = (0usize, 0usize);
        while i < s.labels.len() {
            let l = s.labels[i];
            if l == 0 {
                gap += 1;
                i += 1;
                continue;
            }
            let len = s.labels[i..].iter().take_while(|&&v| v == l).count();
            if !runs.is_empty() {
                runs.push(' ');
            }
            runs.push_str(&format!("{gap} {len} {l}"));
            (gap, i) = (0, i + len);
        }
        StrokeRuns {
            width: s.width,
            height: s.height,
            runs,
        }
    }
}

impl TryFrom<StrokeRuns> for Strokes {
    type Error = String;
    fn try_from(r: StrokeRuns) -> Result<Self, String> {
        let n = r
            .width
            .checked_mul(r.height)
            .filter(|&n| n <= 1 << 31)
            .ok_or_else(|| format!("strokes of {}×{} pixels", r.width, r.height))?;
        let numbers: Vec<usize> = r
            .runs
            .split_ascii_whitespace()
            .map(|t| {
                t.parse()
                    .map_err(|_| format!("stroke runs: {t:?} is no count"))
            })
            .collect::<Result<_, _>>()?;
        if !numbers.len().is_multiple_of(3) {
            return Err("stroke runs come in threes (gap, length, label)".into());
        }
        let mut labels = vec![0u8; n];
        let mut at = 0usize;
        for t in numbers.chunks_exact(3) {
            let (gap, len, label) = (t[0], t[1], t[2]);
            let end = at.saturating_add(gap).saturating_add(len);
            if end > n || len == 0 || !(1..=BOUNDARY as usize).contains(&label) {
                return Err(format!(
                    "stroke run {gap} {len} {label} does not fit {}×{} pixels of labels 1–3",
                    r.width, r.height
                ));
            }
            labels[at + gap..end].fill(label as u8);
            at = end;
        }
        Strokes::new(r.width, r.height, labels).map_err(|e| e.to_string())
    }
}
