//! Image-driven evolution (DESIGN layer 4): the image field and pyramid, forces,
//! initialisations, the engines behind one trait, the schedule, the frame-by-frame
//! `Evolver` and measurements.

pub mod declump;
pub mod engine;
pub mod evolver;
pub mod explicit;
pub mod field;
pub mod forces;
pub mod implicit;
pub mod init;
pub mod local;
pub mod measure;
pub mod params;
pub mod remesh;
pub mod schedule;
pub mod seeds;

pub use engine::{Engine, Frame};
pub use evolver::{Edit, Evolver, FrameEvent};
pub use field::{Field, Pyramid};
pub use forces::{ForceWeights, IntensityModel, Polarity};
pub use init::Shape;
pub use local::Modality;
pub use measure::{regions, Region};
pub use params::{EvolveError, Mode, Params};
pub use seeds::find_seeds;
