//! Rigid bodies: what a scene declares (`BodyDesc`) and what the world keeps (`Body`).

use glam::{Mat3, Mat3A, Quat, Vec3};

use crate::physics::solve::solver_body::normalized_or;

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
    /// Coefficient of rolling resistance, ≥ 0: a ball of radius r pressed on a surface with normal
    /// force N is resisted by a torque up to this × N × r against rolling, and the same against
    /// spinning about the normal (0: it rolls and spins forever on a flat floor).
    pub rolling_resistance: f32,
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
            rolling_resistance: 0.0,
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

/// Marks "no body" in the intrusive sleep lists.
pub(crate) const NO_BODY: u32 = u32::MAX;

/// A body as the world keeps it (the cold, per-body state; the solver copies the hot part into
/// `SolverBody`s each step).
#[derive(Clone, Debug)]
pub struct Body {
    pub(crate) shape: Shape,
    /// Centre of mass and orientation; the rotation is renormalised every sub-step.
    pub(crate) pose: Pose,
    /// m/s, world frame; zero for static bodies.
    pub(crate) linear_velocity: Vec3,
    /// rad/s, world frame; zero for static bodies.
    pub(crate) angular_velocity: Vec3,
    /// kg, finite and > 0 (kept while static, for when the body is unfrozen).
    pub(crate) mass: f32,
    /// 1 / mass, 1/kg.
    pub(crate) inv_mass: f32,
    /// Principal moments of inertia, body frame, kg·m².
    pub(crate) inertia_local: Vec3,
    /// Their reciprocals, 1/(kg·m²).
    pub(crate) inv_inertia_local: Vec3,
    pub(crate) is_static: bool,
    pub(crate) friction: f32,
    pub(crate) restitution: f32,
    pub(crate) rolling_resistance: f32,
    pub(crate) sleeping: bool,
    /// How long the body has been slower than the sleep thresholds, s.
    pub(crate) sleep_time: f32,
    /// The slowest it moved since that rest began, m/s: a body speeding up from it is not resting
    /// (see `sleep`, "Speeding up").
    pub(crate) rest_speed: f32,
    /// Next body of the same sleeping island (a circular list), or `NO_BODY` when awake.
    pub(crate) sleep_next: u32,
    /// Force and torque accumulated for the next step, cleared by it. N and N·m, world frame.
    pub(crate) force: Vec3,
    pub(crate) torque: Vec3,
}

impl Body {
    pub(crate) fn from_desc(desc: &BodyDesc) -> Self {
        let mass = if desc.mass.is_finite() && desc.mass > 0.0 {
            desc.mass
        } else {
            desc.shape.volume().max(f32::MIN_POSITIVE)
        };
        let inertia_local = desc.shape.principal_inertia(mass);
        let mut pose = desc.pose;
        // Renormalise only a rotation that is not unit already, so a valid pose is kept bit for bit.
        if (pose.rotation.length_squared() - 1.0).abs() > 1e-6 {
            pose.rotation = normalized_or(pose.rotation, Quat::IDENTITY);
        }
        let keep = |v: Vec3| {
            if desc.is_static || !v.is_finite() {
                Vec3::ZERO
            } else {
                v
            }
        };
        Self {
            shape: desc.shape,
            pose,
            linear_velocity: keep(desc.linear_velocity),
            angular_velocity: keep(desc.angular_velocity),
            mass,
            inv_mass: 1.0 / mass,
            inertia_local,
            inv_inertia_local: inertia_local.recip(),
            is_static: desc.is_static,
            friction: desc.friction.max(0.0),
            restitution: desc.restitution.clamp(0.0, 1.0),
            rolling_resistance: if desc.rolling_resistance.is_finite() {
                desc.rolling_resistance.max(0.0)
            } else {
                0.0
            },
            sleeping: false,
            sleep_time: 0.0,
            rest_speed: 0.0,
            sleep_next: NO_BODY,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
        }
    }

    /// True when the solver moves this body this step.
    #[inline]
    pub(crate) fn is_awake_dynamic(&self) -> bool {
        !self.is_static && !self.sleeping
    }

    /// World-space inverse inertia R · diag(1/I) · Rᵀ, 1/(kg·m²).
    pub(crate) fn inv_inertia_world(&self) -> Mat3 {
        let r = Mat3::from_quat(self.pose.rotation);
        r * Mat3::from_diagonal(self.inv_inertia_local) * r.transpose()
    }

    /// The same as [`Body::inv_inertia_world`] in SIMD form ([`inv_inertia_world`]).
    #[inline]
    pub(crate) fn inv_inertia_world_simd(&self) -> Mat3A {
        inv_inertia_world(self.pose.rotation, self.inv_inertia_local)
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

    pub fn rolling_resistance(&self) -> f32 {
        self.rolling_resistance
    }
    /// Principal moments of inertia, body frame, kg·m².
    pub fn inertia_local(&self) -> Vec3 {
        self.inertia_local
    }
    /// Angular momentum about the centre of mass, world frame, kg·m²/s.
    pub fn angular_momentum(&self) -> Vec3 {
        let q = self.pose.rotation;
        q * (self.inertia_local * (q.inverse() * self.angular_velocity))
    }
    /// Kinetic energy ½mv² + ½ωᵀIω, J.
    pub fn kinetic_energy(&self) -> f32 {
        let w_local = self.pose.rotation.inverse() * self.angular_velocity;
        0.5 * self.mass * self.linear_velocity.length_squared()
            + 0.5 * w_local.dot(self.inertia_local * w_local)
    }
}

/// The world inverse inertia R·diag(d)·Rᵀ of a body turned by `rotation` with principal inverse
/// moments `d`: R's columns scaled by the diagonal, then times Rᵀ (what [`Body::inv_inertia_world`]
/// computes, in SIMD form).
#[inline]
pub(crate) fn inv_inertia_world(rotation: Quat, d: Vec3) -> Mat3A {
    let r = Mat3A::from_quat(rotation);
    let scaled = Mat3A::from_cols(r.x_axis * d.x, r.y_axis * d.y, r.z_axis * d.z);
    scaled * r.transpose()
}
