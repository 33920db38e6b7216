//! Rigid bodies: what a scene declares (`BodyDesc`) and what the world keeps (`Body`).

use glam::Vec3;

use crate::geometry::{Pose, Shape};

/// Index of a body in its world, in the order bodies were added (scene-file order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyId(pub u32);

impl BodyId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Everything needed to create a body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyDesc {
    pub shape: Shape,
    pub pose: Pose,
    /// m/s, world frame.
    pub linear_velocity: Vec3,
    /// rad/s, world frame.
    pub angular_velocity: Vec3,
    /// kg; finite and > 0 (a static body keeps it for when it is unfrozen).
    pub mass: f32,
    /// Static bodies never move and cost nothing in the solver.
    pub is_static: bool,
    /// Coulomb friction coefficient, ≥ 0.
    pub friction: f32,
    /// Coefficient of restitution in [0, 1].
    pub restitution: f32,
}

impl BodyDesc {
    /// A dynamic body of the given mass, at rest, with μ = 0.5 and e = 0.
    pub fn dynamic(shape: Shape, pose: Pose, mass: f32) -> Self {
        Self {
            shape,
            pose,
            linear_velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            mass,
            is_static: false,
            friction: 0.5,
            restitution: 0.0,
        }
    }

    /// A static body (its nominal mass is that of density 1).
    pub fn fixed(shape: Shape, pose: Pose) -> Self {
        Self {
            is_static: true,
            ..Self::dynamic(shape, pose, shape.volume())
        }
    }
}

/// A body as the world keeps it.
#[derive(Clone, Debug)]
pub struct Body {
    pub(crate) shape: Shape,
    pub(crate) pose: Pose,
    pub(crate) linear_velocity: Vec3,
    pub(crate) angular_velocity: Vec3,
    pub(crate) mass: f32,
    pub(crate) is_static: bool,
    pub(crate) friction: f32,
    pub(crate) restitution: f32,
    pub(crate) sleeping: bool,
    /// Force and torque accumulated for the next step, cleared by it.
    pub(crate) force: Vec3,
    pub(crate) torque: Vec3,
}

impl Body {
    pub(crate) fn from_desc(desc: &BodyDesc) -> Self {
        Self {
            shape: desc.shape,
            pose: desc.pose,
            linear_velocity: if desc.is_static {
                Vec3::ZERO
            } else {
                desc.linear_velocity
            },
            angular_velocity: if desc.is_static {
                Vec3::ZERO
            } else {
                desc.angular_velocity
            },
            mass: desc.mass,
            is_static: desc.is_static,
            friction: desc.friction,
            restitution: desc.restitution,
            sleeping: false,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
        }
    }

    pub fn shape(&self) -> &Shape {
        &self.shape
    }
    pub fn pose(&self) -> &Pose {
        &self.pose
    }
    pub fn linear_velocity(&self) -> Vec3 {
        self.linear_velocity
    }
    pub fn angular_velocity(&self) -> Vec3 {
        self.angular_velocity
    }
    pub fn mass(&self) -> f32 {
        self.mass
    }
    pub fn is_static(&self) -> bool {
        self.is_static
    }
    pub fn is_sleeping(&self) -> bool {
        self.sleeping
    }
    pub fn friction(&self) -> f32 {
        self.friction
    }
    pub fn restitution(&self) -> f32 {
        self.restitution
    }
}
