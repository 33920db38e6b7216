//! The engine: collision, contacts, friction, stacks and piles at rest, hard cases, the corpus, determinism and snapshots.
//!
//! One test crate per area (each integration-test file used to link the whole library on its own).

#[path = "../common/mod.rs"]
mod common;

mod broad_phase;
mod collide_box_box;
mod collide_fuzz;
mod collide_spheres;
mod contact_caps;
mod convergence_fixes;
mod corpus;
mod cradle;
mod determinism;
mod fast_bodies;
mod friction;
mod hard_cases;
mod hostile_scenes;
mod joints;
mod mechanisms;
mod overlap;
mod patch_friction;
mod point_drive;
mod ragdoll;
mod rest;
mod rolling;
mod towers;
mod world_snapshot;
