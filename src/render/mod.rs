//! The software rasterizer: draws plain [`Drawable`]s (boxes and spheres with a look) into a [`Frame`]
//! of colours, depths and ids. It knows nothing of the terminal or of physics.
//!
//! Conventions (those of [`crate::geometry`]):
//! - World space is right-handed, **y up**, metres. View space looks down −z (glam `look_to_rh`).
//! - Clip space is glam's `perspective_rh` / `orthographic_rh`: depth `z/w` in **[0, 1]**, 0 at the near
//!   plane, 1 at the far plane; the depth buffer stores it and a smaller value is nearer.
//! - NDC x right, y up. Pixels x right, **y down**, row-major; pixel `(x, y)` covers
//!   `[x, x+1) × [y, y+1)` and is sampled at its centre `(x + ½, y + ½)`, through
//!   [`crate::geometry::Viewport::pixel_from_ndc`], the same map picking inverts.
//! - Front faces wind counter-clockwise seen from outside (and so in NDC); back faces are culled.
//!
//! The pipeline, one file per stage, driven by [`renderer`]: [`mesh`] (unit meshes) → `vertex`
//! (unit → world → clip) → [`clip`] (near/far/guard band, Sutherland–Hodgman) → divide and viewport
//! (`view`) → [`raster`] (fixed-point edge functions, top-left rule) → `fragment` (depth test,
//! perspective-correct attributes, [`shade`] and [`texture`], writes into the [`frame`]) → image
//! passes ([`shadow`], [`post`]). Balls skip the first four stages: `sphere` intersects each pixel's
//! ray with them, as picking does, and hands the hit to the fragment stage. [`line`](mod@line) draws wireframe edges; [`overlay`] draws debug marks
//! over the finished frame.

pub mod clip;
pub mod drawable;
mod fragment;
pub mod frame;
pub mod line;
pub mod mesh;
pub mod mode;
pub mod options;
pub mod overlay;
pub mod post;
pub mod raster;
pub mod renderer;
pub mod shade;
pub mod shadow;
mod sphere;
pub mod tether;
pub mod texture;
mod vertex;
mod view;

pub use drawable::{Drawable, Material};
pub use frame::Frame;
pub use mesh::{Mesh, MeshSet};
pub use mode::RenderMode;
pub use options::RenderOptions;
pub use overlay::{Overlay, draw_overlay};
pub use renderer::{RenderTimings, Renderer};
pub use shade::Lights;
