//! # topocontour
//!
//! Polygonal active contours in 2D that change topology correctly: contours grow, split,
//! merge and open or close holes, and always stay simple, oriented and non-crossing.
//!
//! The heart is [`ContourSet::move_vertex`], the motion-region topology correction of
//! seed 003 (`shared/seeds/003_…`): one vertex moves at a time, and the rings afterwards
//! bound exactly (R ∪ M⁺) − M⁻.
//!
//! Layers (each uses only those above it):
//! - [`geometry`]: points, exact orientation, segment intersection;
//! - [`contours`]: the ring arena [`ContourSet`] and its broad phase [`contours::VertexBins`];
//! - [`topology`]: motion regions, Directives 1 and 2, topology events;
//! - [`image`]: the field and pyramid, the intensity model, local decision levels,
//!   automatic seeds;
//! - [`learn`]: a pixel classifier (random forest on multiscale features) trained from
//!   a user's strokes, whose probabilities the contours can follow;
//! - [`evolution`]: the engines that move contours under image forces.
//!
//! [`shape`] holds the shapes a user draws to start a run.
//!
//! Cargo features: `gui` (default) builds the desktop app (`app`, eframe/egui), `cli`
//! (default) the headless command line (`cli`, clap); without default features the
//! library builds with neither. `testkit` exposes the test kit (`check`) to tests,
//! benches and fuzz targets.

#![warn(missing_docs)]

#[cfg(feature = "gui")]
pub mod app;
#[cfg(any(test, feature = "testkit"))]
#[doc(hidden)]
pub mod check;
#[cfg(feature = "cli")]
pub mod cli;
pub mod contours;
pub mod evolution;
pub mod geometry;
pub mod image;
pub mod io;
pub mod job;
pub mod learn;
pub mod shape;
pub mod topology;
pub mod track;

pub use contours::{ContourId, ContourSet, RingError, VertexId};
pub use geometry::{Aabb, Point};
pub use topology::{Degeneracy, MotionRegion, MoveError, TopologyEvent};
