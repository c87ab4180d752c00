//! Image loading and exports (DESIGN layer 5).

pub mod export;
pub mod load;

pub use export::{write_atomic, Outputs};
pub use load::{load_image, LoadError};
