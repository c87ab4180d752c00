//! [`Format`]: the one list of what a segmentation can be written as, with each format's
//! file extension, the file name it gets from an image's stem, and its bytes. The CLI
//! (`--json …`, `batch --formats`) and the app's Export menu both name outputs through
//! it, so a format has one default name everywhere.

use super::Outputs;
use crate::image::Gray;
use std::path::Path;

/// An output format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Format {
    /// Contours and events (the CLI contract).
    Json,
    /// Mask, 255 inside (PNG, or TIFF for a .tif name).
    Mask,
    /// SVG of the regions.
    Svg,
    /// GeoJSON polygons as QuPath reads them.
    Geojson,
    /// Measurements, one row per region.
    Csv,
    /// 16-bit label image (TIFF, or PNG for a .png name).
    Labels,
    /// The image with the contours drawn (PNG).
    Overlay,
    /// ImageJ ROI set (zip).
    Roi,
}

/// Why an output cannot be rendered.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ExportError {
    /// A 16-bit label image holds at most 65,535 objects.
    #[error("more than 65,535 objects for a 16-bit label image")]
    TooManyLabels,
    /// An ImageJ ROI holds coordinates below 32,767 px.
    #[error(
        "an object reaches {0} px; ImageJ ROI coordinates stop at 32,767 (export GeoJSON instead)"
    )]
    RoiTooFar(u64),
    /// The file name's extension names an image format this output is not written in.
    #[error("{format} is written as {allowed}, not .{ext}")]
    Extension {
        /// What the output is ("a mask").
        format: &'static str,
        /// The formats it is written in ("PNG or TIFF").
        allowed: &'static str,
        /// The extension given.
        ext: String,
    },
}

/// Whether `path` ends in .tif or .tiff (a mask or label image is then TIFF, else PNG).
pub fn is_tiff(path: &Path) -> bool {
    extension(path).is_some_and(|e| e == "tif" || e == "tiff")
}

fn extension(path: &Path) -> Option<String> {
    Some(path.extension()?.to_str()?.to_ascii_lowercase())
}

impl Format {
    /// Every format, in the order the CLI lists its flags.
    pub const ALL: [Format; 8] = [
        Format::Json,
        Format::Mask,
        Format::Svg,
        Format::Geojson,
        Format::Csv,
        Format::Overlay,
        Format::Labels,
        Format::Roi,
    ];

    /// The format's name on the command line (`--formats json,labels`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Json => "json",
            Format::Mask => "mask",
            Format::Svg => "svg",
            Format::Geojson => "geojson",
            Format::Csv => "csv",
            Format::Labels => "labels",
            Format::Overlay => "overlay",
            Format::Roi => "roi",
        }
    }

    /// The file extension (without the dot) of this format's default file name.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Json => "json",
            Format::Mask | Format::Overlay => "png",
            Format::Svg => "svg",
            Format::Geojson => "geojson",
            Format::Csv => "csv",
            Format::Labels => "tif",
            Format::Roi => "zip",
        }
    }

    /// The default output file name for an image with file stem `stem`
    /// (`cells` → `cells.mask.png`, `cells.roi.zip`, …): what batch writes and what the
    /// app proposes.
    pub fn file_name(self, stem: &str) -> String {
        match self {
            Format::Mask => format!("{stem}.mask.png"),
            Format::Labels => format!("{stem}.labels.tif"),
            Format::Overlay => format!("{stem}.overlay.png"),
            Format::Roi => format!("{stem}.roi.zip"),
            _ => format!("{stem}.{}", self.extension()),
        }
    }

    /// Refuses a file name whose extension names an image format this output is not
    /// written in (`--mask cells.jpg` would hold PNG bytes); checked before any work.
    pub fn check_name(self, path: &Path) -> Result<(), ExportError> {
        let (format, allowed, ok): (_, _, &[&str]) = match self {
            Format::Mask => ("a mask", "PNG or TIFF", &["png", "tif", "tiff"]),
            Format::Labels => ("a label image", "PNG or TIFF", &["png", "tif", "tiff"]),
            Format::Overlay => ("an overlay", "PNG", &["png"]),
            _ => return Ok(()),
        };
        match extension(path) {
            Some(ext)
                if image::ImageFormat::from_extension(&ext).is_some() && !ok.contains(&&*ext) =>
            {
                Err(ExportError::Extension {
                    format,
                    allowed,
                    ext,
                })
            }
            _ => Ok(()),
        }
    }

    /// The bytes of this output of `out` (drawn on `image` for the overlay); `path` is
    /// where they go: a mask or label image is TIFF when `path` ends in .tif/.tiff,
    /// else PNG.
    pub fn render(
        self,
        out: &Outputs,
        image: &dyn Gray,
        path: &Path,
    ) -> Result<Vec<u8>, ExportError> {
        self.check_name(path)?;
        Ok(match self {
            Format::Json => out.json().into_bytes(),
            Format::Mask => out.mask_image(is_tiff(path)),
            Format::Svg => out.svg().into_bytes(),
            Format::Geojson => out.geojson().into_bytes(),
            Format::Csv => out.csv().into_bytes(),
            Format::Overlay => out.overlay_png(image),
            Format::Roi => crate::io::roi::roi_zip(out.set)?,
            Format::Labels => out
                .labels_image(is_tiff(path))
                .ok_or(ExportError::TooManyLabels)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_names_end_in_their_extension() {
        for f in Format::ALL {
            let name = f.file_name("cells");
            assert!(name.starts_with("cells."), "{name}");
            assert!(name.ends_with(&format!(".{}", f.extension())), "{name}");
        }
        assert_eq!(Format::Roi.file_name("a"), "a.roi.zip");
    }

    #[test]
    fn an_image_output_named_in_another_image_format_is_refused() {
        let name = |f: Format, n: &str| f.check_name(Path::new(n)).map_err(|e| e.to_string());
        assert_eq!(
            name(Format::Labels, "a.JPG"),
            Err("a label image is written as PNG or TIFF, not .jpg".into())
        );
        assert!(name(Format::Mask, "a.jpeg").is_err());
        assert!(name(Format::Overlay, "a.tif").is_err());
        assert!(
            name(Format::Mask, "a.pgm").is_err(),
            "any image format the name says"
        );
        for ok in ["a.png", "a.TIFF", "a", "a.mask", "a.out"] {
            assert!(name(Format::Mask, ok).is_ok(), "{ok}");
        }
        assert!(name(Format::Json, "a.png").is_ok(), "not an image output");
    }
}
