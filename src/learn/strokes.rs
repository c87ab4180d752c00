//! A user's strokes as a label image: 0 unlabelled, 1 background, 2 object, 3 boundary
//! between touching objects (the values `shared/tools/scribbles.py` writes and ilastik's
//! label export uses), checked against the image they were painted on.

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
#[derive(Clone, Debug, PartialEq)]
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

    /// Reads a stroke PNG (or any gray image the `image` crate decodes; 16-bit values
    /// are taken as they are) and checks it against a `width` × `height` image.
    pub fn read(path: &Path, width: usize, height: usize) -> Result<Self, StrokeError> {
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
        if (w, h) != (width, height) {
            return Err(StrokeError::Size {
                got_w: w,
                got_h: h,
                want_w: width,
                want_h: height,
            });
        }
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
        Strokes::new(w, h, labels)
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
