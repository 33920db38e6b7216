//! Rigid-body dynamics for boxes and spheres: bodies, contacts, the solver, islands and sleeping.
//!
//! Uses `geometry` only. Units: metres, kilograms, seconds, radians; y up. The step is described in
//! [`world`]; the contact solver and its derivation in `contact_solver`.

pub mod body;
pub mod broad_phase;
mod coincident;
pub mod collide;
mod constraint_order;
mod contact;
pub mod contact_cap;
mod contact_solver;
pub mod contact_view;
pub mod fast_bodies;
mod finite;
mod free_rotation;
pub mod input;
mod island;
mod lanes;
pub mod limits;
pub mod manifold;
mod measures;
pub mod point_drive;
pub mod profile;
mod push_out;
pub mod settings;
pub mod snapshot;
mod softness;
mod solver_body;
mod wide_contacts;
pub mod world;

pub use body::{Body, BodyDesc, BodyId};
pub use contact_view::{ContactPointView, ContactView, NO_ISLAND};
pub use input::WorldInput;
pub use manifold::{ContactPoint, Manifold, Patch};
pub use point_drive::{PointHold, PointSpring};
pub use profile::{Stage, StepProfile};
pub use settings::Settings;
pub use snapshot::WorldSnapshot;
pub use world::World;
