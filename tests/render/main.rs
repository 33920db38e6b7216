//! The software rasterizer and picking: what is drawn, the rays cast through it, the built-in scenes' pictures.
//!
//! One test crate per area (each integration-test file used to link the whole library on its own).

#[path = "../common/mod.rs"]
mod common;

mod builtin_scenes;
mod looks;
mod picking;
mod raster;
mod raycast;
