//! Image-driven evolution (DESIGN layer 4): the image field and pyramid, forces,
//! initialisations, remeshing, the frame-by-frame `Evolver` and measurements.

pub mod evolver;
pub mod field;
pub mod forces;
pub mod implicit;
pub mod init;
pub mod local;
pub mod measure;
pub mod remesh;
pub mod seeds;

pub use evolver::{EvolveError, Evolver, Frame, FrameEvent, Mode, Params};
pub use field::{Field, Pyramid};
pub use forces::{ForceWeights, IntensityModel, Polarity};
pub use init::Shape;
pub use local::Modality;
pub use measure::{regions, Region};
pub use seeds::find_seeds;
