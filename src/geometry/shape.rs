//! Collision and render shapes: solid boxes and solid spheres, centred on the body's centre of mass.

use glam::{Mat3, Quat, Vec3};

use super::{Aabb, Pose};

/// A convex solid in its body-local frame, centred at the origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A box; every half-extent is finite and > 0, metres.
    Cuboid { half_extents: Vec3 },
    /// A ball; radius finite and > 0, metres.
    Sphere { radius: f32 },
}

impl Shape {
    pub fn cuboid(half_extents: Vec3) -> Self {
        Shape::Cuboid { half_extents }
    }

    pub fn sphere(radius: f32) -> Self {
        Shape::Sphere { radius }
    }

    /// Volume in m³.
    pub fn volume(&self) -> f32 {
        match *self {
            Shape::Cuboid { half_extents: h } => 8.0 * h.x * h.y * h.z,
            Shape::Sphere { radius: r } => 4.0 / 3.0 * std::f32::consts::PI * r * r * r,
        }
    }

    /// Principal moments of inertia of the solid with this mass, body frame, kg·m².
    ///
    /// Solid box: I_x = m (h_y² + h_z²) / 3 with half-extents h (= m (b² + c²) / 12 for full sizes);
    /// solid sphere: I = 2/5 m r².
    pub fn principal_inertia(&self, mass: f32) -> Vec3 {
        match *self {
            Shape::Cuboid { half_extents: h } => {
                let s = h * h;
                mass / 3.0 * Vec3::new(s.y + s.z, s.x + s.z, s.x + s.y)
            }
            Shape::Sphere { radius: r } => Vec3::splat(0.4 * mass * r * r),
        }
    }

    /// Half the shape's thinnest width, m: a box's smallest half-extent, a ball's radius.
    pub fn half_thickness(&self) -> f32 {
        match *self {
            Shape::Cuboid { half_extents } => half_extents.min_element(),
            Shape::Sphere { radius } => radius,
        }
    }

    /// Radius of the smallest origin-centred sphere that holds the shape.
    pub fn bounding_radius(&self) -> f32 {
        match *self {
            Shape::Cuboid { half_extents } => half_extents.length(),
            Shape::Sphere { radius } => radius,
        }
    }

    /// How far the shape, turned by `rotation`, reaches from its centre along the unit direction
    /// `dir`: half its width across the planes normal to `dir`, metres. A box reaches h · |Rᵀ dir|
    /// (its support function; Ericson 5.2.3), a ball its radius.
    pub fn reach(&self, rotation: Quat, dir: Vec3) -> f32 {
        match *self {
            Shape::Cuboid { half_extents } => half_extents.dot((rotation.inverse() * dir).abs()),
            Shape::Sphere { radius } => radius,
        }
    }

    /// Tight world-space bounds of the shape at `pose`.
    pub fn aabb(&self, pose: &Pose) -> Aabb {
        match *self {
            Shape::Cuboid { half_extents } => {
                // |R| h gives the extents of a rotated box (Ericson 4.2.6).
                let r = Mat3::from_quat(pose.rotation);
                let abs = Mat3::from_cols(r.x_axis.abs(), r.y_axis.abs(), r.z_axis.abs());
                Aabb::from_center_half_extents(pose.position, abs * half_extents)
            }
            Shape::Sphere { radius } => {
                Aabb::from_center_half_extents(pose.position, Vec3::splat(radius))
            }
        }
    }

    /// True when every size is finite and strictly positive.
    pub fn is_valid(&self) -> bool {
        match *self {
            Shape::Cuboid { half_extents } => {
                half_extents.is_finite() && half_extents.cmpgt(Vec3::ZERO).all()
            }
            Shape::Sphere { radius } => radius.is_finite() && radius > 0.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_cube_inertia_is_m_over_6() {
        let i = Shape::cuboid(Vec3::splat(0.5)).principal_inertia(6.0);
        assert!((i - Vec3::ONE).abs().max_element() < 1e-6);
    }

    #[test]
    fn rotated_box_aabb_grows() {
        let shape = Shape::cuboid(Vec3::splat(0.5));
        let pose = Pose::new(
            Vec3::ZERO,
            Quat::from_rotation_y(std::f32::consts::FRAC_PI_4),
        );
        let aabb = shape.aabb(&pose);
        let expected = 0.5 * std::f32::consts::SQRT_2;
        assert!((aabb.max.x - expected).abs() < 1e-6);
        assert!((aabb.max.y - 0.5).abs() < 1e-6);
    }

    #[test]
    fn reach_is_the_half_width_along_a_direction() {
        let shape = Shape::cuboid(Vec3::new(0.5, 1.0, 2.0));
        assert!((shape.reach(Quat::IDENTITY, Vec3::Y) - 1.0).abs() < 1e-6);
        // Along the world axes it is the bounding box's half-extent, whatever the rotation.
        let rotation = Quat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 0.7);
        let aabb = shape.aabb(&Pose::new(Vec3::new(3.0, -2.0, 1.0), rotation));
        for (axis, half) in [(Vec3::X, 0), (Vec3::Y, 1), (Vec3::Z, 2)] {
            let expected = aabb.half_extents()[half];
            assert!((shape.reach(rotation, axis) - expected).abs() < 1e-5);
            assert!((shape.reach(rotation, -axis) - expected).abs() < 1e-5);
        }
        assert_eq!(Shape::sphere(0.3).reach(rotation, Vec3::X), 0.3);
    }
}
