//! nudge: a 3D rigid-body physics sandbox in the terminal.
//!
//! Layers, each importing only the ones above it in this list (and never one beside it, except where
//! said):
//! - [`color`], [`geometry`], [`util`]: colours and the body palette, shared math, a seeded generator
//!   and a median.
//! - [`physics`]: bodies, contacts, solver (imports geometry only).
//! - [`scene`]: scene files and built-in scenes, and the schema recordings share with scene files;
//!   builds a physics world (imports physics, geometry, color and util).
//! - [`render`]: the software rasterizer; imports only geometry and color, and draws the plain
//!   `Drawable`s the app hands it (it never sees physics or the terminal).
//! - [`term`]: maps pixels to half-block terminal cells; the terminal guard (imports color only).
//! - [`app`], [`sim`], [`recording`], [`replay`], [`bench`](mod@bench), [`cli`]: wire the layers together;
//!   [`testing`] holds what the tests and the benchmarks share.

pub mod app;
pub mod bench;
pub mod cli;
pub mod color;
pub mod geometry;
pub mod physics;
pub mod recording;
pub mod render;
pub mod replay;
pub mod scene;
pub mod sim;
pub mod term;
pub mod testing;
pub mod util;
