//! A movie: the pages of a multi-page TIFF (8 or 16 bit, one page per time point), or the
//! images of a folder in natural name order (`frame_2` before `frame_10`).
//!
//! [`Movie::open`] reads every frame once before anything else happens, so a bad movie
//! (one frame, frames of different sizes, a frame that does not decode) is refused with
//! one error before any output exists; [`Movie::frames`] then reads them again one at a
//! time, so memory holds one frame, never the movie.
//!
//! Each frame is normalised on its own: its 0.1 % and 99.9 % intensity quantiles map to 0
//! and 1 (clamped). A 16-bit movie may use a narrow range (97–276 of 65,535), which read
//! as is would leave every contrast below the engine's noise floor; a few hot pixels must
//! not decide the scale, hence quantiles rather than the extremes; and per frame, because
//! bleaching dims a fluorescence movie over time.

use super::load::{load_image, open_regular, LoadError};
use super::tiff_info::decode_current;
use crate::evolution::Field;
use std::path::{Path, PathBuf};

/// Frames read at most (a malformed chain of TIFF pages must not loop).
const MAX_FRAMES: usize = 100_000;

/// Share of pixels below the value that maps to 0 (and above the one that maps to 1).
const CLIP_SHARE: f64 = 0.001;

/// Why a movie cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum MovieError {
    /// A frame could not be read or decoded.
    #[error("{0}")]
    Load(#[from] LoadError),
    /// Fewer than two frames.
    #[error("{path} holds {frames} frame{}: a movie needs at least two (pages of a TIFF, or images in a folder)", if *.frames == 1 { "" } else { "s" })]
    TooShort {
        /// The movie.
        path: String,
        /// Frames found.
        frames: usize,
    },
    /// One page of several samples per pixel: a colour image, or frames written as one.
    #[error("{path} holds one page of {samples} samples per pixel (a colour image): a movie needs one page per frame (tifffile writes a ({samples}, height, width) array as one colour page unless given photometric='minisblack')")]
    OneColourPage {
        /// The movie.
        path: String,
        /// Samples per pixel of its page.
        samples: usize,
    },
    /// A hyperstack with channels, or slices and frames: its pages are not one plane per
    /// time point.
    #[error("{path} is a hyperstack of {channels} channel(s) × {slices} slice(s) × {frames} frame(s): a movie to track is one grey plane per frame (in Fiji, Image > Color > Split Channels and Image > Stacks > Z Project first)")]
    Hyperstack {
        /// The movie.
        path: String,
        /// Channels.
        channels: usize,
        /// Z slices.
        slices: usize,
        /// Time points.
        frames: usize,
    },
    /// A file of a folder movie holds several pages.
    #[error("{path} holds {pages} pages: a folder movie is one single-page image per frame (open a multi-page TIFF as the movie itself)")]
    PagesInFrame {
        /// The file.
        path: String,
        /// Its pages.
        pages: usize,
    },
    /// A frame whose size differs from the first.
    #[error("{path}: frame {frame}{at} is {width}×{height} but frame 0 is {first_width}×{first_height}; every frame of a movie must have the same size")]
    SizeDiffers {
        /// The movie.
        path: String,
        /// The frame, from 0 as everywhere else (the masks, the tracks, `--overlay-frame`).
        frame: usize,
        /// Where it is read from, for the user to find it: ` (page N)` of a TIFF (pages
        /// count from 1, as Fiji's slices), ` (NAME)` of a folder, or nothing.
        at: String,
        /// Its width.
        width: usize,
        /// Its height.
        height: usize,
        /// The first frame's width.
        first_width: usize,
        /// The first frame's height.
        first_height: usize,
    },
}

/// Where the frames come from.
#[derive(Clone, Debug)]
enum Source {
    /// Pages of one TIFF file.
    Stack(PathBuf),
    /// Image files, in natural name order.
    Files(Vec<PathBuf>),
}

/// A checked movie: at least two frames, all of one size, all decodable.
#[derive(Clone, Debug)]
pub struct Movie {
    source: Source,
    /// The path it was opened from (a TIFF or a folder).
    path: PathBuf,
    name: String,
    frames: usize,
    width: usize,
    height: usize,
}

impl Movie {
    /// Opens a multi-page TIFF or a folder of images and reads every frame once.
    pub fn open(path: &Path) -> Result<Movie, MovieError> {
        let name = path.display().to_string();
        let source = if path.is_dir() {
            Source::Files(image_files(path)?)
        } else {
            Source::Stack(path.to_path_buf())
        };
        let mut movie = Movie {
            source,
            path: path.to_path_buf(),
            name,
            frames: 0,
            width: 0,
            height: 0,
        };
        match &movie.source {
            Source::Stack(p) => {
                if let Some((channels, slices, frames)) = super::tiff_info::stack_dimensions(p) {
                    // A plain ImageJ stack states its pages as slices: only two axes
                    // at once are refused.
                    if channels > 1 || (slices > 1 && frames > 1) {
                        return Err(MovieError::Hyperstack {
                            path: movie.name,
                            channels,
                            slices,
                            frames,
                        });
                    }
                }
            }
            Source::Files(files) => {
                for f in files {
                    let pages = super::tiff_info::pages_of(f);
                    if pages > 1 {
                        return Err(MovieError::PagesInFrame {
                            path: f.display().to_string(),
                            pages,
                        });
                    }
                }
            }
        }
        let mut frames = 0;
        // Every page decoded once here, so a bad one stops the run before any output; not
        // normalised, which only the run needs.
        let mut pages = movie.frames()?;
        pages.normalised = false;
        for (t, frame) in pages.enumerate() {
            let f = frame?;
            if t == 0 {
                (movie.width, movie.height) = (f.width, f.height);
            } else if (f.width, f.height) != (movie.width, movie.height) {
                let at = match &movie.source {
                    Source::Stack(_) => format!(" (page {})", t + 1),
                    Source::Files(files) => files[t]
                        .file_name()
                        .map(|n| format!(" ({})", n.to_string_lossy()))
                        .unwrap_or_default(),
                };
                return Err(MovieError::SizeDiffers {
                    path: movie.name.clone(),
                    frame: t,
                    at,
                    width: f.width,
                    height: f.height,
                    first_width: movie.width,
                    first_height: movie.height,
                });
            }
            frames += 1;
        }
        if let (1, Source::Stack(p)) = (frames, &movie.source) {
            if let Some(samples @ 3..) = super::tiff_info::first_page_samples(p) {
                return Err(MovieError::OneColourPage {
                    path: movie.name,
                    samples,
                });
            }
        }
        if frames < 2 {
            return Err(MovieError::TooShort {
                path: movie.name,
                frames,
            });
        }
        movie.frames = frames;
        Ok(movie)
    }

    /// Number of frames.
    pub fn len(&self) -> usize {
        self.frames
    }

    /// Always false: a movie has at least two frames.
    pub fn is_empty(&self) -> bool {
        self.frames == 0
    }

    /// Width and height of every frame.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// The path it was opened from: the TIFF, or the folder of frames.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The files the movie is read from (outputs must never replace one).
    pub fn files(&self) -> Vec<&Path> {
        match &self.source {
            Source::Stack(p) => vec![p.as_path()],
            Source::Files(v) => v.iter().map(PathBuf::as_path).collect(),
        }
    }

    /// The movie's name as given (for messages).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The frames in order, each normalised ([`normalise`]), read one at a time.
    pub fn frames(&self) -> Result<Frames, MovieError> {
        let reader = match &self.source {
            Source::Stack(path) => {
                let io = |source| LoadError::Io {
                    path: self.name.clone(),
                    source,
                };
                let file = open_regular(path).map_err(io)?;
                if !file.metadata().map_err(io)?.is_file() {
                    return Err(LoadError::NotAFile {
                        path: self.name.clone(),
                    }
                    .into());
                }
                let dec = tiff::decoder::Decoder::new(std::io::BufReader::new(file)).map_err(|e| {
                    match e {
                        // Another kind of file given as the movie (a PNG, a case's JSON).
                        tiff::TiffError::FormatError(
                            tiff::TiffFormatError::TiffSignatureNotFound,
                        ) => decode_error(
                            &self.name,
                            "it does not start as a TIFF does (a movie is a multi-page TIFF or a folder of images)"
                                .into(),
                        ),
                        e => decode_error(&self.name, e.to_string()),
                    }
                })?;
                Reader::Stack(Box::new(dec))
            }
            Source::Files(files) => Reader::Files(files.clone()),
        };
        Ok(Frames {
            reader,
            name: self.name.clone(),
            next: 0,
            normalised: true,
        })
    }
}

fn decode_error(name: &str, reason: String) -> MovieError {
    LoadError::Decode {
        path: name.to_string(),
        reason,
    }
    .into()
}

/// The image files of a folder, in natural name order (as `batch` lists them).
fn image_files(dir: &Path) -> Result<Vec<PathBuf>, MovieError> {
    super::folder::list_images(dir).map_err(|source| {
        LoadError::Io {
            path: dir.display().to_string(),
            source,
        }
        .into()
    })
}

enum Reader {
    Stack(Box<tiff::decoder::Decoder<std::io::BufReader<std::fs::File>>>),
    Files(Vec<PathBuf>),
}

/// The frames of a [`Movie`], read one at a time.
pub struct Frames {
    reader: Reader,
    name: String,
    next: usize,
    /// Each frame normalised as it is read (false: as decoded, for [`Movie::open`]'s check).
    normalised: bool,
}

impl Iterator for Frames {
    type Item = Result<Field, MovieError>;

    fn next(&mut self) -> Option<Self::Item> {
        let t = self.next;
        if t >= MAX_FRAMES {
            return None;
        }
        let frame = match &mut self.reader {
            Reader::Stack(dec) => {
                if t > 0 {
                    if !dec.more_images() {
                        return None;
                    }
                    if let Err(e) = dec.next_image() {
                        self.next = MAX_FRAMES;
                        return Some(Err(decode_error(
                            &self.name,
                            format!("frame {t} (page {}): {e}", t + 1),
                        )));
                    }
                }
                decode_current(dec, &self.name, t).map_err(MovieError::from)
            }
            Reader::Files(files) => load_image(files.get(t)?).map_err(MovieError::from),
        };
        self.next = if frame.is_ok() { t + 1 } else { MAX_FRAMES };
        Some(frame.map(|mut f| {
            if self.normalised {
                normalise(&mut f);
            }
            f
        }))
    }
}

/// Maps the 0.1 % and 99.9 % quantiles of `f` to 0 and 1, clamping beyond; a flat frame
/// stays as it is.
pub fn normalise(f: &mut Field) {
    if let Some((lo, hi)) = quantile_range(f) {
        stretch(f, lo, hi);
    }
}

/// A still image whose darkest and brightest pixels lie closer than this (intensities in
/// [0, 1]) is stretched to fill [0, 1]: fewer grey levels than a full 8-bit image has in
/// eight, as a 12-bit camera's image in a 16-bit file, or a 16-bit one using 97–276. The
/// intensity model's least contrast is absolute ([`crate::image::intensity::MIN_CONTRAST`]),
/// and such an image read as it is was one object covering everything, or none. Images
/// of a wider range keep their values: a run on them is what it was.
pub const NARROW_RANGE: f32 = 1.0 / 8.0;

/// `f` stretched from its darkest to its brightest pixel when they lie closer than
/// [`NARROW_RANGE`]. By the extremes, not by quantiles as a movie's frames: a few small
/// bright objects on a dim ground (under 0.1 % of the pixels) must stay brighter than
/// the ground, not be clamped into it.
pub fn widen_narrow(f: &mut Field) {
    let (lo, hi) = f
        .data
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if hi > lo && hi - lo < NARROW_RANGE {
        stretch(f, lo, hi);
    }
}

/// The 0.1 % and 99.9 % quantiles of `f`, if they differ.
fn quantile_range(f: &Field) -> Option<(f32, f32)> {
    let n = f.data.len();
    if n == 0 {
        return None;
    }
    let mut v = f.data.clone();
    let k = ((n as f64 * CLIP_SHARE) as usize).min(n - 1);
    let lo = *v.select_nth_unstable_by(k, f32::total_cmp).1;
    let hi = *v.select_nth_unstable_by(n - 1 - k, f32::total_cmp).1;
    (hi > lo).then_some((lo, hi))
}

fn stretch(f: &mut Field, lo: f32, hi: f32) {
    let scale = 1.0 / (hi - lo);
    for x in &mut f.data {
        *x = ((*x - lo) * scale).clamp(0.0, 1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_narrow_sixteen_bit_range_fills_zero_to_one() {
        let data: Vec<f32> = (0..10_000)
            .map(|i| (97 + i % 180) as f32 / 65535.0)
            .collect();
        let mut f = Field::new(100, 100, data);
        normalise(&mut f);
        let (lo, hi) = f
            .data
            .iter()
            .fold((1.0f32, 0.0f32), |(a, b), &x| (a.min(x), b.max(x)));
        assert_eq!((lo, hi), (0.0, 1.0));
    }
}
