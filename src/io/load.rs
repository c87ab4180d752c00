//! Loads PNG, JPEG and TIFF (8- or 16-bit, gray or colour) into a [`Field`] of luminance
//! in [0, 1], with the `image` crate.

use crate::evolution::Field;
use std::path::Path;

/// Largest image accepted, in pixels (a 16k × 16k scan).
pub const MAX_PIXELS: u64 = 1 << 28;

#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("cannot read {path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path} is not a readable PNG, JPEG or TIFF image: {reason}")]
    Decode { path: String, reason: String },
    #[error("{path} has no pixels ({width}×{height})")]
    Empty {
        path: String,
        width: u32,
        height: u32,
    },
    #[error("{path} is too large ({width}×{height}; at most {MAX_PIXELS} pixels)")]
    TooLarge {
        path: String,
        width: u32,
        height: u32,
    },
}

/// Reads an image file as luminance.
pub fn load_image(path: &Path) -> Result<Field, LoadError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        path: name.clone(),
        source,
    })?;
    let decode_err = |e: &dyn std::fmt::Display| LoadError::Decode {
        path: name.clone(),
        reason: e.to_string(),
    };
    let reader = || image::ImageReader::new(std::io::Cursor::new(&bytes)).with_guessed_format();
    // The header first: size limits before any pixel memory is allocated.
    let (width, height) = reader()
        .map_err(|e| decode_err(&e))?
        .into_dimensions()
        .map_err(|e| decode_err(&e))?;
    check_size(&name, width, height)?;
    let mut full = reader().map_err(|e| decode_err(&e))?;
    full.no_limits();
    let img = full.decode().map_err(|e| decode_err(&e))?;
    // 16-bit data keeps its precision through luma16.
    let luma = img.to_luma16();
    let data = luma.as_raw().iter().map(|&v| v as f32 / 65535.0).collect();
    Ok(Field::new(width as usize, height as usize, data))
}

fn check_size(path: &str, width: u32, height: u32) -> Result<(), LoadError> {
    if width == 0 || height == 0 {
        return Err(LoadError::Empty {
            path: path.into(),
            width,
            height,
        });
    }
    if width as u64 * height as u64 > MAX_PIXELS {
        return Err(LoadError::TooLarge {
            path: path.into(),
            width,
            height,
        });
    }
    Ok(())
}
