//! Image loading and exports (DESIGN layer 5).

pub mod atomic;
pub mod classifier;
pub mod export;
pub mod folder;
pub mod load;
pub mod movie;
pub mod roi;
pub mod session;
pub mod tiff_info;

pub use atomic::{write_atomic, OutputError, OutputFiles};
pub use export::{ExportError, Format, Outputs};
pub use load::{decode_image, load_image, load_image_page, ImageInfo, LoadError};
pub use tiff_info::PixelSize;
