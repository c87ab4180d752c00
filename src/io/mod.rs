//! Image loading and exports (DESIGN layer 5).

pub mod atomic;
pub mod classifier;
pub mod export;
pub mod folder;
pub mod load;
pub mod movie;
pub mod roi;
pub mod samples;
pub mod session;
pub mod tiff_info;
pub mod tracking_session;

pub use atomic::{write_atomic, OutputError, OutputFiles};
pub use export::{ExportError, Format, Outputs};
pub use load::{decode_image, load_image, load_image_page, ImageInfo, LoadError};
pub use samples::{field_from_samples, Samples};
pub use tiff_info::PixelSize;
