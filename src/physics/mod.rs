//! Rigid-body dynamics for boxes and spheres: bodies, contacts, the solver, islands and sleeping.
//!
//! Uses `geometry` only. Units: metres, kilograms, seconds, radians; y up. The step is described in
//! [`world`]; the contact solver and its derivation in `contact_solver`.

// The step's stages, in the order `World::step` runs them.
pub mod broad;
pub mod joint;
pub mod narrow;
pub mod prepare;
pub mod sleep;
pub mod solve;

// The world, its bodies and settings, and what the app reads of it.
pub mod body;
pub mod contact_view;
pub mod fast_bodies;
mod finite;
pub mod input;
pub mod limits;
mod measures;
pub mod profile;
mod scratch;
pub mod settings;
pub mod snapshot;
mod union_find;
pub mod world;

pub use body::{Body, BodyDesc, BodyId};
pub use contact_view::{ContactPointView, ContactView, NO_ISLAND};
pub use input::WorldInput;
pub use joint::{Joint, JointDesc, JointError, JointId, JointKind, JointLoad, Motor, Spring};
pub use narrow::manifold::{ContactPoint, Manifold, Patch};
pub use profile::{Stage, StepProfile};
pub use settings::Settings;
pub use snapshot::WorldSnapshot;
pub use solve::point_drive::{PointHold, PointSpring};
pub use world::World;
