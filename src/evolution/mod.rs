//! Image-driven evolution: forces, the engines behind one trait, the schedule and the
//! frame-by-frame `Evolver`. What the image says comes from [`crate::image`].
//!
//! The names that moved to [`crate::image`], [`crate::shape`] and
//! [`crate::contours::measure`] are re-exported here, so `evolution::Field`,
//! `evolution::Shape`, `evolution::regions` and the rest keep working.

pub mod edit;
pub mod engine;
pub mod evolver;
pub mod explicit;
pub mod forces;
pub mod implicit;
mod initial;
pub mod params;
pub mod remesh;
pub mod schedule;

pub use crate::contours::measure;
pub use crate::contours::measure::{regions, Region};
pub use crate::image::{find_seeds, Field, IntensityModel, Modality, Polarity, Pyramid};
pub use crate::shape::Shape;
pub use edit::{Edit, FrameEvent};
pub use engine::{Engine, Frame};
pub use evolver::Evolver;
pub use forces::ForceWeights;
pub use params::{EvolveError, Mode, Params};
