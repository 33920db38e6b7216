//! Geometry: the math every other layer shares, and nothing else.
//!
//! Conventions, stated once for the whole crate:
//! - Right-handed world, **y up**, metres, seconds, kilograms, radians.
//! - Vectors are column vectors (glam); `a_from_b` transforms from frame b to frame a.
//! - Rotations are unit quaternions.
//! - Clip space follows glam's `*_rh` projections: depth in **[0, 1]** (0 at the near plane).
//! - NDC x right, y up; pixel coordinates x right, y down, pixel (i, j) covers [i, i+1) × [j, j+1)
//!   and is sampled at its centre (i + 0.5, j + 0.5).

pub mod aabb;
pub mod camera;
pub mod pose;
pub mod ray;
pub mod shape;
pub mod viewport;

pub use aabb::Aabb;
pub use camera::{Camera, ImageRays, Projection};
pub use pose::Pose;
pub use ray::{Ray, RayHit};
pub use shape::Shape;
pub use viewport::{CellPixels, Viewport};
