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
    /// Mask PNG, 255 inside.
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

    /// The bytes of this output of `out` (drawn on `image` for the overlay); `path` is
    /// where they go: a label image is TIFF unless `path` ends in something else than
    /// .tif/.tiff (then PNG).
    pub fn render(
        self,
        out: &Outputs,
        image: &dyn Gray,
        path: &Path,
    ) -> Result<Vec<u8>, ExportError> {
        Ok(match self {
            Format::Json => out.json().into_bytes(),
            Format::Mask => out.mask_png(),
            Format::Svg => out.svg().into_bytes(),
            Format::Geojson => out.geojson().into_bytes(),
            Format::Csv => out.csv().into_bytes(),
            Format::Overlay => out.overlay_png(image),
            Format::Roi => crate::io::roi::roi_zip(out.set)?,
            Format::Labels => {
                let tiff = path.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                    e.eq_ignore_ascii_case("tif") || e.eq_ignore_ascii_case("tiff")
                });
                out.labels_image(tiff).ok_or(ExportError::TooManyLabels)?
            }
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
}
