//! Narrow phase: contact manifolds between pairs of shapes.
//!
//! [`collide`] is the one entry point; it dispatches on the shape pair and handles argument order
//! (sphere–box is box–sphere with the normal flipped). One file per shape pair, as in parry.
//!
//! Conventions every routine here follows (see [`Manifold`]):
//! - The normal is unit length, world space, and points from A to B.
//! - Each point is the midpoint between the two surfaces, world space; `separation` is the signed
//!   distance between the surfaces along the normal (negative = penetrating).
//! - Points are reported while `separation <= margin` (speculative contacts: the solver passes a margin of
//!   about relative speed × dt plus slop so fast bodies are caught before they tunnel). When the shapes are
//!   farther apart than `margin` the manifold is empty (`len == 0`).
//! - Every point has a feature `id` that names the pair of features (faces, edges, vertices, clip planes)
//!   that produced it; it stays the same while the same features touch, so the solver can warm-start.
//!   Ids are unique within one manifold. Their encodings are documented per shape pair.
//! - Work happens in the frame of body A (or of a box), so bodies far from the origin keep their precision.
//! - Non-finite poses or sizes give an empty manifold, never NaN.

mod at_impact;
mod box_box;
mod box_sphere;
mod patch;
mod sphere_sphere;

pub use at_impact::{Motion, at_impact};
pub use box_box::box_box;
pub use box_sphere::box_sphere;
pub use patch::patch as patch_of;
pub use sphere_sphere::sphere_sphere;

use glam::Vec3;

use crate::geometry::{Pose, Shape};
use crate::physics::Manifold;

/// Contact manifold between `shape_a` at `pose_a` and `shape_b` at `pose_b`.
///
/// `margin` (metres, ≥ 0) is how far apart surfaces may be and still be reported as speculative contacts;
/// a negative or non-finite margin is treated as 0. The normal points from A to B. Returns an empty
/// manifold when the shapes are separated by more than `margin`, or when a pose or size is not finite.
pub fn collide(
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
    margin: f32,
) -> Manifold {
    let margin = if margin.is_finite() {
        margin.max(0.0)
    } else {
        0.0
    };
    if !(pose_a.is_finite() && pose_b.is_finite() && sizes_ok(shape_a) && sizes_ok(shape_b)) {
        return Manifold::default();
    }
    match (*shape_a, *shape_b) {
        (Shape::Sphere { radius: r_a }, Shape::Sphere { radius: r_b }) => {
            sphere_sphere(r_a, pose_a.position, r_b, pose_b.position, margin)
        }
        (Shape::Cuboid { half_extents }, Shape::Sphere { radius }) => {
            box_sphere(half_extents, pose_a, radius, pose_b.position, margin)
        }
        (Shape::Sphere { radius }, Shape::Cuboid { half_extents }) => {
            let mut manifold = box_sphere(half_extents, pose_b, radius, pose_a.position, margin);
            manifold.normal = -manifold.normal;
            manifold
        }
        (Shape::Cuboid { half_extents: h_a }, Shape::Cuboid { half_extents: h_b }) => {
            box_box(h_a, pose_a, h_b, pose_b, margin)
        }
    }
}

/// Sizes that the routines can work with: finite and ≥ 0 (a zero size is a degenerate but usable shape).
fn sizes_ok(shape: &Shape) -> bool {
    match *shape {
        Shape::Cuboid { half_extents } => {
            half_extents.is_finite() && half_extents.cmpge(Vec3::ZERO).all()
        }
        Shape::Sphere { radius } => radius.is_finite() && radius >= 0.0,
    }
}

/// `v` normalised, or `fallback` when `v` is zero or not finite. Scales by the largest component first,
/// so tiny (1e-30) and huge (1e30) vectors normalise without underflow or overflow.
#[inline]
pub(crate) fn unit_or(v: Vec3, fallback: Vec3) -> Vec3 {
    let scale = v.abs().max_element();
    if !(scale > 0.0 && scale.is_finite()) {
        return fallback;
    }
    let w = v / scale;
    w / w.length()
}

/// +1 for x ≥ 0 (including +0 and −0), −1 otherwise: a sign with no zero case, so ties pick a side.
#[inline]
pub(crate) fn sign_nonzero(x: f32) -> f32 {
    if x < 0.0 { -1.0 } else { 1.0 }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn sphere_box_order_flips_the_normal_but_not_the_points() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let ball = Shape::sphere(0.25);
        let pose_box = Pose::IDENTITY;
        let pose_ball = Pose::from_position(Vec3::new(0.0, 0.7, 0.0));
        let ab = collide(&cube, &pose_box, &ball, &pose_ball, 0.0);
        let ba = collide(&ball, &pose_ball, &cube, &pose_box, 0.0);
        assert_eq!(ab.len, 1);
        assert_eq!(ba.len, 1);
        assert!((ab.normal + ba.normal).length() < 1e-6);
        assert_eq!(ab.points[0], ba.points[0]);
    }

    #[test]
    fn a_nan_pose_gives_an_empty_manifold() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let bad = Pose::new(Vec3::new(f32::NAN, 0.0, 0.0), Quat::IDENTITY);
        assert!(collide(&cube, &Pose::IDENTITY, &cube, &bad, 0.1).is_empty());
    }

    #[test]
    fn unit_or_normalises_tiny_and_huge_vectors() {
        for v in [Vec3::new(1e-30, 2e-30, 0.0), Vec3::new(3e30, -4e30, 0.0)] {
            let u = unit_or(v, Vec3::Y);
            assert!((u.length() - 1.0).abs() < 1e-6);
        }
        assert_eq!(unit_or(Vec3::ZERO, Vec3::Y), Vec3::Y);
    }
}
