//! Image analysis (the layer between topology and evolution): what the image says,
//! before any contour moves.
//!
//! The field and its Gaussian pyramid ([`field`]), box and blur filters ([`filters`]),
//! the two-class intensity model and polarity ([`intensity`]), the kind of image and
//! its phase-contrast halo ([`modality`], [`halo`]), the pixel noise and the object
//! scale ([`noise`], [`scale`]), the local decision levels ([`local`]), the medians
//! under the user's shapes ([`hints`]); and the automatic seeds built from them: the
//! distance transform ([`distance`]), persistent maxima ([`maxima`]), the seeds' basins
//! ([`seeds`], [`outline`]) and their cuts at notches ([`declump`]); what a run keeps
//! of the image for its outputs ([`stored`]); the label images a tracked movie reports,
//! widened to the cells' edges ([`widen`]).
//!
//! [`model::ImageModel`] gathers what an engine reads, prepared once
//! ([`ImageModel::prepare`]): the evolver and the automatic seeds both start from it.
//!
//! Nothing here knows contours or engines: the evolution reads the image through this
//! layer only.

pub mod declump;
pub mod distance;
pub mod edges;
pub mod field;
pub mod filters;
pub mod halo;
pub mod hints;
pub mod intensity;
pub mod local;
pub mod maxima;
pub mod modality;
pub mod model;
pub mod noise;
pub mod outline;
pub(crate) mod patch;
pub mod scale;
pub mod seeds;
pub mod stored;
pub mod widen;

pub use field::{Field, Pyramid};
pub use intensity::{IntensityModel, Polarity};
pub use local::Decision;
pub use modality::Modality;
pub use model::{ImageModel, LevelView, ModelKind, ModelParams, Probe};
pub use seeds::find_seeds;
pub use stored::{Gray, Stored};
