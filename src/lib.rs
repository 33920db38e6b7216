//! nudge: a 3D rigid-body physics sandbox in the terminal.
//!
//! Layers, each importing only the ones above it in this list:
//! - [`color`], [`geometry`]: shared math and colour types.
//! - [`physics`]: bodies, contacts, solver (uses geometry).
//! - [`scene`]: scene files and built-in scenes; builds a physics world.
//! - [`render`]: the software rasterizer (uses geometry; reads bodies through plain `Drawable`s).
//! - [`term`]: maps pixels to half-block terminal cells; the terminal guard.
//! - [`app`], [`sim`], [`recording`], [`replay`], [`bench`](mod@bench), [`cli`]: wire the layers together.

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
