//! Penetration depth between two bodies' shapes, measured from their poses alone, so tests and benchmarks
//! judge the engine with geometry the engine did not compute.
//!
//! Depth is the minimum translation that separates the two solids, metres, 0 when they do not overlap.
//! - sphere–sphere: r_a + r_b − |c_b − c_a|;
//! - sphere–box: from the closest point on the box to the centre (Ericson 5.1.3), or, for a centre inside
//!   the box, r + the distance to the nearest face;
//! - box–box: separating-axis test over the 15 candidate axes (3 + 3 face normals, 9 edge×edge; Ericson
//!   4.4.1): for convex polyhedra the smallest overlap over these axes is the penetration depth.

use glam::{Mat3, Vec3};

use crate::geometry::{Pose, Shape};
use crate::physics::World;

/// Overlap of two solids, metres; 0 when they are apart or just touching.
pub fn penetration_depth(shape_a: &Shape, pose_a: &Pose, shape_b: &Shape, pose_b: &Pose) -> f32 {
    let depth = match (*shape_a, *shape_b) {
        (Shape::Sphere { radius: ra }, Shape::Sphere { radius: rb }) => {
            ra + rb - (pose_b.position - pose_a.position).length()
        }
        (Shape::Sphere { radius }, Shape::Cuboid { half_extents }) => {
            sphere_box_depth(pose_a.position, radius, half_extents, pose_b)
        }
        (Shape::Cuboid { half_extents }, Shape::Sphere { radius }) => {
            sphere_box_depth(pose_b.position, radius, half_extents, pose_a)
        }
        (Shape::Cuboid { half_extents: ha }, Shape::Cuboid { half_extents: hb }) => {
            box_box_depth(ha, pose_a, hb, pose_b)
        }
    };
    depth.max(0.0)
}

fn sphere_box_depth(center_world: Vec3, radius: f32, half_extents: Vec3, box_pose: &Pose) -> f32 {
    let c_local = box_pose.inverse_transform_point(center_world);
    let inside = c_local.abs().cmple(half_extents).all();
    if inside {
        radius + (half_extents - c_local.abs()).min_element()
    } else {
        let closest = c_local.clamp(-half_extents, half_extents);
        radius - (c_local - closest).length()
    }
}

fn box_box_depth(ha: Vec3, pose_a: &Pose, hb: Vec3, pose_b: &Pose) -> f32 {
    let axes_a = Mat3::from_quat(pose_a.rotation);
    let axes_b = Mat3::from_quat(pose_b.rotation);
    let a = [axes_a.x_axis, axes_a.y_axis, axes_a.z_axis];
    let b = [axes_b.x_axis, axes_b.y_axis, axes_b.z_axis];
    let d = pose_b.position - pose_a.position;
    let overlap = |axis: Vec3| -> f32 {
        let ra =
            ha.x * a[0].dot(axis).abs() + ha.y * a[1].dot(axis).abs() + ha.z * a[2].dot(axis).abs();
        let rb =
            hb.x * b[0].dot(axis).abs() + hb.y * b[1].dot(axis).abs() + hb.z * b[2].dot(axis).abs();
        ra + rb - d.dot(axis).abs()
    };
    let mut depth = f32::INFINITY;
    for axis in a.iter().chain(b.iter()) {
        depth = depth.min(overlap(*axis));
    }
    for ea in a {
        for eb in b {
            // Parallel edges give no axis of their own (a face normal already covers them).
            if let Some(axis) = ea
                .cross(eb)
                .try_normalize()
                .filter(|_| ea.cross(eb).length() > 1e-4)
            {
                depth = depth.min(overlap(axis));
            }
        }
    }
    depth
}

/// The deepest overlap between any two bodies of `world`, metres, and the pair (indices, ascending).
/// Pairs of two static bodies are skipped, and pairs with a static body too unless `include_static`.
/// O(n²) with a bounding-box filter: meant for test scenes of a few hundred bodies.
pub fn max_penetration(world: &World, include_static: bool) -> (f32, Option<(usize, usize)>) {
    let bodies = world.bodies();
    let boxes: Vec<_> = bodies.iter().map(|b| b.shape().aabb(b.pose())).collect();
    let mut deepest = (0.0, None);
    for i in 0..bodies.len() {
        for j in i + 1..bodies.len() {
            let (a, b) = (&bodies[i], &bodies[j]);
            let statics = a.is_static() as u8 + b.is_static() as u8;
            if statics == 2 || (statics == 1 && !include_static) || !boxes[i].overlaps(&boxes[j]) {
                continue;
            }
            let depth = penetration_depth(a.shape(), a.pose(), b.shape(), b.pose());
            if depth > deepest.0 {
                deepest = (depth, Some((i, j)));
            }
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    fn unit() -> Shape {
        Shape::cuboid(Vec3::splat(0.5))
    }

    #[test]
    fn stacked_boxes_overlapping_by_a_centimetre_have_that_depth() {
        let a = Pose::from_position(Vec3::ZERO);
        let b = Pose::from_position(Vec3::new(0.003, 0.99, -0.002));
        let depth = penetration_depth(&unit(), &a, &unit(), &b);
        assert!((depth - 0.01).abs() < 1e-5, "{depth}");
    }

    #[test]
    fn boxes_apart_or_touching_have_zero_depth() {
        let a = Pose::from_position(Vec3::ZERO);
        for x in [1.0, 1.5] {
            let b = Pose::from_position(Vec3::new(x, 0.2, 0.0));
            assert_eq!(penetration_depth(&unit(), &a, &unit(), &b), 0.0);
        }
    }

    #[test]
    fn edge_on_edge_boxes_are_separated_by_a_cross_product_axis() {
        // Two cubes turned 45° about different axes, edge to edge: their face normals all overlap but the
        // cross axis of the two edges separates them.
        let a = Pose::new(
            Vec3::ZERO,
            Quat::from_rotation_z(std::f32::consts::FRAC_PI_4),
        );
        let b = Pose::new(
            Vec3::new(0.0, 2.0 * 0.5 * std::f32::consts::SQRT_2 + 0.01, 0.0),
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_4),
        );
        assert_eq!(penetration_depth(&unit(), &a, &unit(), &b), 0.0);
    }

    #[test]
    fn ball_on_a_turned_box_face_measures_along_the_face_normal() {
        let pose_box = Pose::new(Vec3::ZERO, Quat::from_rotation_z(0.5));
        let normal = pose_box.rotation * Vec3::Y;
        let ball = Pose::from_position(normal * (0.5 + 0.3 - 0.02));
        let depth = penetration_depth(&Shape::sphere(0.3), &ball, &unit(), &pose_box);
        assert!((depth - 0.02).abs() < 1e-5, "{depth}");
    }

    #[test]
    fn ball_centre_inside_a_box_counts_the_way_out_through_the_nearest_face() {
        let ball = Pose::from_position(Vec3::new(0.4, 0.0, 0.0));
        let depth = penetration_depth(&unit(), &Pose::IDENTITY, &Shape::sphere(0.2), &ball);
        assert!((depth - 0.3).abs() < 1e-6, "{depth}");
    }

    #[test]
    fn overlapping_balls_measure_the_sum_of_radii_minus_the_distance() {
        let a = Pose::from_position(Vec3::ZERO);
        let b = Pose::from_position(Vec3::new(0.0, 0.0, 0.7));
        let depth = penetration_depth(&Shape::sphere(0.5), &a, &Shape::sphere(0.3), &b);
        assert!((depth - 0.1).abs() < 1e-6, "{depth}");
    }
}
