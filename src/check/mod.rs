//! Independent checks of the topology core, shared by the property tests, the fuzz
//! target and the `bench` command's self-test.
//!
//! The oracle never calls the core's predicates: it decides "is this point in the region"
//! with a plain floating-point crossing count over the rings, and only at sample points
//! farther than [`NEAR`] from every edge, where rounding cannot change the answer. After a
//! move it checks that every sample in the motion region's box obeys equation 2 of seed
//! 003 — in the region iff M's winding is +1, or it is 0 and the point was in R before —
//! and that a bitmap of the whole domain, updated by the same rule move after move,
//! still matches (so nothing changed outside the motion region either).
//!
//! Files: `rng`, `oracle`, `generators` (ring sets and moves), `fixtures` (the
//! benchmarks'), `drivers` (property-test and fuzz loops), `learn_images` (the pixel
//! classifier's test images and strokes).
//!
//! Set `TOPO_TRACE=1` to print the rings before and after a failing move.

mod drivers;
mod fixtures;
mod generators;
mod learn_images;
mod oracle;
mod rng;

pub use drivers::*;
pub use fixtures::*;
pub use generators::*;
pub use learn_images::*;
pub use oracle::*;
pub use rng::*;
