//! Loads PNG, JPEG and TIFF (8- or 16-bit, gray or colour) into a [`Field`] of luminance
//! in [0, 1], with the `image` crate.
//!
//! Only regular files are read, and the type is checked on the opened file without
//! blocking (a FIFO, a device or a socket named as the image is refused at once, never
//! read); a file larger than the largest image could need is refused before it is read.
//! A header that claims more pixels than the file's bytes can encode is refused before
//! decoding (no codec packs more than about a thousand pixels into a byte).
//! A JPEG that ends before its end-of-image marker is refused: the decoder would fill
//! the missing part silently and the contours would follow the filler.

use crate::evolution::Field;
use std::path::Path;

/// Largest image accepted, in pixels (a 16k × 16k scan).
pub const MAX_PIXELS: u64 = 1 << 28;

/// Why an image cannot be opened.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// Reading failed.
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What failed.
        source: std::io::Error,
    },
    #[error("{path} is not a readable PNG, JPEG or TIFF image: {reason}")]
    /// The bytes are not an image this build decodes.
    Decode {
        /// The file.
        path: String,
        /// What the decoder said.
        reason: String,
    },
    /// The image has no pixels.
    #[error("{path} has no pixels ({width}×{height})")]
    Empty {
        /// The file.
        path: String,
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    #[error("{path} is not a regular file")]
    /// A FIFO, device, socket or folder.
    NotAFile {
        /// The path.
        path: String,
    },
    #[error("{path} is too large ({bytes} bytes; an image of at most {MAX_PIXELS} pixels needs at most {MAX_FILE_BYTES})")]
    /// The file is larger than any image of the allowed size.
    FileTooLarge {
        /// The file.
        path: String,
        /// Its size.
        bytes: u64,
    },
    #[error("{path} is truncated: the JPEG data ends before its end-of-image marker")]
    /// A JPEG without its end.
    Truncated {
        /// The file.
        path: String,
    },
    /// More pixels than allowed.
    #[error("{path} is too large ({width}×{height}; at most {MAX_PIXELS} pixels)")]
    TooLarge {
        /// The file.
        path: String,
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
}

/// Largest file accepted: an uncompressed 16-bit RGBA image of [`MAX_PIXELS`] pixels and
/// room for its headers.
pub const MAX_FILE_BYTES: u64 = MAX_PIXELS * 8 + (1 << 20);

/// Reads an image file as luminance (the first page of a multi-page TIFF).
pub fn load_image(path: &Path) -> Result<Field, LoadError> {
    load_image_page(path, 0).map(|(field, _)| field)
}

/// What a file says about its image besides the pixels.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ImageInfo {
    /// Images in the file (TIFF stacks hold several; 1 otherwise).
    pub pages: usize,
    /// Physical size of a pixel, if the file records one (TIFF).
    pub pixel_size: Option<super::tiff_info::PixelSize>,
}

/// Reads page `page` (0-based) of an image file as luminance, with what the file says
/// about it (pages, pixel size).
pub fn load_image_page(path: &Path, page: usize) -> Result<(Field, ImageInfo), LoadError> {
    let bytes = read_file(path)?;
    let name = path.display().to_string();
    let (pages, pixel_size) = super::tiff_info::tiff_info(&bytes).unwrap_or((1, None));
    let tiff = bytes.starts_with(b"II") || bytes.starts_with(b"MM");
    let field = if page == 0 {
        match decode_image(&bytes, &name) {
            // The image crate reads no floating-point TIFF: such a first page is decoded
            // as the pages after it are.
            Err(e @ LoadError::Decode { .. }) if tiff => {
                super::tiff_info::decode_page(&bytes, &name, 0).map_err(|_| e)?
            }
            other => other?,
        }
    } else if page < pages {
        super::tiff_info::decode_page(&bytes, &name, page)?
    } else {
        return Err(LoadError::Decode {
            path: name,
            reason: format!("there is no page {} (the file holds {pages})", page + 1),
        });
    };
    let mut field = field;
    super::movie::widen_narrow(&mut field);
    Ok((field, ImageInfo { pages, pixel_size }))
}

/// Why a file was not read.
#[derive(Debug)]
pub(crate) enum Unread {
    /// Opening or reading failed.
    Io(std::io::Error),
    /// A FIFO, device, socket or folder.
    NotAFile,
    /// Larger than the limit (its size).
    TooLarge(u64),
}

/// The bytes of a regular file of at most `limit` bytes: opened without blocking (a FIFO
/// is refused, never waited on), its type checked on the opened file, its size before
/// reading, and never more than `limit` bytes read (a file growing meanwhile).
pub(crate) fn read_regular(path: &Path, limit: u64) -> Result<Vec<u8>, Unread> {
    let file = open_regular(path).map_err(Unread::Io)?;
    let meta = file.metadata().map_err(Unread::Io)?;
    if !meta.is_file() {
        return Err(Unread::NotAFile);
    }
    if meta.len() > limit {
        return Err(Unread::TooLarge(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::io::Read::read_to_end(&mut std::io::Read::take(file, limit + 1), &mut bytes)
        .map_err(Unread::Io)?;
    if bytes.len() as u64 > limit {
        return Err(Unread::TooLarge(bytes.len() as u64));
    }
    Ok(bytes)
}

/// The bytes of a regular file no larger than [`MAX_FILE_BYTES`].
fn read_file(path: &Path) -> Result<Vec<u8>, LoadError> {
    let path_name = path.display().to_string();
    read_regular(path, MAX_FILE_BYTES).map_err(|e| match e {
        Unread::Io(source) => LoadError::Io {
            path: path_name,
            source,
        },
        Unread::NotAFile => LoadError::NotAFile { path: path_name },
        Unread::TooLarge(bytes) => LoadError::FileTooLarge {
            path: path_name,
            bytes,
        },
    })
}

/// Opens without blocking: on a FIFO a plain open waits for a writer.
pub(crate) fn open_regular(path: &Path) -> std::io::Result<std::fs::File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::custom_flags(&mut options, libc::O_NONBLOCK);
    options.open(path)
}

/// Decodes image file bytes as luminance; `name` is the file's name in messages.
pub fn decode_image(bytes: &[u8], name: &str) -> Result<Field, LoadError> {
    let decode_err = |e: &dyn std::fmt::Display| LoadError::Decode {
        path: name.to_string(),
        reason: e.to_string(),
    };
    let reader = || image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format();
    // The header first: size limits before any pixel memory is allocated.
    let header = reader().map_err(|e| decode_err(&e))?;
    let format = header.format();
    let (width, height) = header.into_dimensions().map_err(|e| decode_err(&e))?;
    check_size(name, width, height)?;
    // No codec we read packs more than about a thousand pixels into a byte (deflate's
    // limit is 1032:1): a header claiming far more is a lie or a bomb, refused before
    // the decoder allocates for it.
    if width as u64 * height as u64 > 4096 * bytes.len() as u64 + (1 << 16) {
        return Err(decode_err(&format!(
            "the header claims {width}×{height} pixels, more than {} bytes can hold",
            bytes.len()
        )));
    }
    if format == Some(image::ImageFormat::Jpeg) && !jpeg_is_complete(bytes) {
        return Err(LoadError::Truncated { path: name.into() });
    }
    let mut full = reader().map_err(|e| decode_err(&e))?;
    full.no_limits();
    let img = full.decode().map_err(|e| decode_err(&e))?;
    // 16-bit data keeps its precision through luma16.
    let luma = img.to_luma16();
    let data = luma.as_raw().iter().map(|&v| v as f32 / 65535.0).collect();
    Ok(Field::new(width as usize, height as usize, data))
}

/// Whether a JPEG has an end-of-image marker after its first scan. Marker segments are
/// walked up to the first start-of-scan (a thumbnail in an APP segment has an EOI of its
/// own); in the entropy-coded data that follows, 0xFF is always stuffed or a marker.
fn jpeg_is_complete(b: &[u8]) -> bool {
    let mut i = 2; // after SOI
    while i + 4 <= b.len() {
        if b[i] != 0xFF {
            return false;
        }
        let marker = b[i + 1];
        if marker == 0xFF {
            i += 1; // fill byte
            continue;
        }
        let len = u16::from_be_bytes([b[i + 2], b[i + 3]]) as usize;
        if marker == 0xDA {
            return b[i + 2 + len.min(b.len() - i - 2)..]
                .windows(2)
                .any(|w| w == [0xFF, 0xD9]);
        }
        i += 2 + len;
    }
    false
}

pub(crate) fn check_size(path: &str, width: u32, height: u32) -> Result<(), LoadError> {
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
