//! A rigid transform: where a body is and how it is turned.

use glam::{Mat3, Quat, Vec3};

/// `world_from_body`: maps body-local points to world points as `rotation * p + position`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Position of the body's centre of mass in the world, metres.
    pub position: Vec3,
    /// Orientation; unit length.
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    pub const IDENTITY: Pose = Pose {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    pub fn new(position: Vec3, rotation: Quat) -> Self {
        Self { position, rotation }
    }

    pub fn from_position(position: Vec3) -> Self {
        Self::new(position, Quat::IDENTITY)
    }

    /// Body-local point → world point.
    #[inline]
    pub fn transform_point(&self, p_local: Vec3) -> Vec3 {
        self.rotation * p_local + self.position
    }

    /// Body-local direction → world direction.
    #[inline]
    pub fn transform_vector(&self, v_local: Vec3) -> Vec3 {
        self.rotation * v_local
    }

    /// World point → body-local point.
    #[inline]
    pub fn inverse_transform_point(&self, p_world: Vec3) -> Vec3 {
        self.rotation.inverse() * (p_world - self.position)
    }

    /// World direction → body-local direction.
    #[inline]
    pub fn inverse_transform_vector(&self, v_world: Vec3) -> Vec3 {
        self.rotation.inverse() * v_world
    }

    /// The rotation as a matrix whose columns are the body's axes in world space.
    #[inline]
    pub fn rotation_matrix(&self) -> Mat3 {
        Mat3::from_quat(self.rotation)
    }

    pub fn is_finite(&self) -> bool {
        self.position.is_finite() && self.rotation.is_finite()
    }
}
