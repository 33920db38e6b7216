//! Rigid-body dynamics for boxes and spheres: bodies, contacts, the solver, islands and sleeping.
//!
//! Uses `geometry` only. Units: metres, kilograms, seconds, radians; y up.

pub mod body;
pub mod broad_phase;
pub mod collide;
pub mod manifold;
pub mod settings;
pub mod world;

pub use body::{Body, BodyDesc, BodyId};
pub use manifold::{ContactPoint, Manifold};
pub use settings::Settings;
pub use world::World;
