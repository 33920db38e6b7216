//! Driving one point of a body: what a hand needs to know to move a body by a point it holds.
//!
//! Two drives, each computed from the body's state at a step boundary:
//! - a **speed motor**: the force along a direction that brings the point's speed along it to a target
//!   speed, never more than a limit and never braking (a push that leans in up to a walking pace);
//! - a **point spring**: Box2D's mouse joint, a soft constraint pulling the point toward a target with
//!   a natural frequency and damping ratio, its force capped.
//!
//! Both return a force for the caller to apply with [`World::apply_force_at_point`] for the next step,
//! so it is journaled like any other input (a recording replays it exactly) and the contact solver stays
//! in charge of what the body touches: a capped force cannot push a body through the floor, where a
//! constraint inside the solver as stiff as the contacts could.
//!
//! Both see the point's effective mass, the mass a force at that point meets once the spin it causes
//! is counted: for a force along unit n at offset r from the centre of mass,
//!
//!   K = (1/m)·𝟙 − [r]× · I⁻¹ · [r]×       (3×3, world frame; [r]× the cross-product matrix)
//!   m_eff(n) = 1 / (nᵀ K n)
//!
//! so an off-centre push spins the body instead of over-driving it (Catto, "Modeling and Solving
//! Constraints", GDC 2009; Box2D v3 `mouse_joint.c`).

use glam::{Mat3, Vec3};

use super::softness::Softness;
use super::solver_body::skew;
use super::{BodyId, World};

/// A soft spring pulling a body's point toward a target (Box2D's mouse joint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointSpring {
    /// Natural frequency, Hz, > 0: the stiffness is m_eff·(2π·hertz)².
    pub hertz: f32,
    /// Damping ratio, ≥ 0 (1 = critically damped).
    pub damping_ratio: f32,
    /// Largest force the spring exerts, N, ≥ 0.
    pub max_force: f32,
    /// Fastest the spring drives the point toward the target, m/s, > 0 (see
    /// [`World::spring_force`]).
    pub max_speed: f32,
}

impl World {
    /// Velocity (m/s, world) of the material point of body `id` that is at `point` (world) now:
    /// v + ω × r.
    pub fn point_velocity(&self, id: BodyId, point: Vec3) -> Vec3 {
        let body = self.body(id);
        body.linear_velocity() + body.angular_velocity().cross(point - body.pose().position)
    }

    /// The matrix K (1/kg) that maps a force (or impulse) at `point` (world) to the change of that
    /// point's acceleration (or velocity): K = (1/m)·𝟙 − [r]×·I⁻¹·[r]×. Zero for static bodies.
    pub fn point_compliance(&self, id: BodyId, point: Vec3) -> Mat3 {
        let body = self.body(id);
        if body.is_static() {
            return Mat3::ZERO;
        }
        let r = skew(point - body.pose().position);
        Mat3::from_diagonal(Vec3::splat(body.inv_mass)) - r * body.inv_inertia_world() * r
    }

    /// The speed motor: the force (N, ≥ 0) along unit `direction` that, applied at `point` for the
    /// next step, brings the point's speed along `direction` to `speed` (m/s), at most `max_force`
    /// (N). Zero if the point already goes that fast (the motor never brakes) or the body is static.
    ///
    ///   F = clamp(m_eff(n) · (speed − n·v_point) / h, 0, max_force)
    ///
    /// It ignores what else acts this step (gravity, friction), so a point held back reaches a little
    /// under `speed`: the next step makes up the difference.
    pub fn motor_force(
        &self,
        id: BodyId,
        point: Vec3,
        direction: Vec3,
        speed: f32,
        max_force: f32,
    ) -> f32 {
        let k = direction.dot(self.point_compliance(id, point) * direction);
        if k.is_nan() || k <= 0.0 {
            return 0.0;
        }
        let shortfall = speed - direction.dot(self.point_velocity(id, point));
        let force = shortfall / (k * self.settings().dt);
        if force.is_finite() {
            force.clamp(0.0, max_force.max(0.0))
        } else {
            0.0
        }
    }

    /// The point spring: the force (N, world) that, applied at `point` (the body's held point, world)
    /// for the next step, pulls it toward `target` (world) like Box2D's mouse joint, over the step h:
    ///
    ///   d = |target − point|,  n = (target − point) / d
    ///   v_goal = n · min(bias_rate · d,  √(a · d),  max_speed)
    ///   F = −mass_scale · K⁻¹ · (v_point − v_goal) / h,   at most max_force long
    ///
    /// where a = max_force · |K n| is the acceleration the capped force gives the point along n.
    /// with the soft-constraint coefficients of [`Softness`] for the step. Implicit in the spring, so
    /// stable at any frequency; at rest it is a spring of stiffness m_eff·ω² (a held body sags
    /// g·(1 + hω·(2ζ + hω))/ω² under gravity: 1.1 cm at 8 Hz and 60 Hz steps). Box2D's joint is
    /// the first term alone; with the force capped, a target metres away then pulled with a force of
    /// fixed size toward it, a central force, and a body flung past it went into orbit about the
    /// pointer. Bounding the speed it asks for keeps the damping of any sideways motion in the force;
    /// the square root is the speed from which half the capped force stops the point at the target
    /// (v² = 2·(a/2)·d), so a body pulled from afar arrives without sailing past. Zero for static
    /// bodies.
    pub fn spring_force(
        &self,
        id: BodyId,
        point: Vec3,
        target: Vec3,
        spring: &PointSpring,
    ) -> Vec3 {
        let k = self.point_compliance(id, point);
        let h = self.settings().dt;
        if self.body(id).is_static() || k.determinant().abs() <= f32::MIN_POSITIVE {
            return Vec3::ZERO;
        }
        let soft = Softness::new(spring.hertz, spring.damping_ratio, h);
        let v = self.point_velocity(id, point);
        let to_target = target - point;
        let distance = to_target.length();
        let direction = to_target.normalize_or_zero();
        let accel = spring.max_force.max(0.0) * (k * direction).length();
        let speed = (soft.bias_rate * distance)
            .min((accel * distance).sqrt())
            .min(spring.max_speed.max(0.0));
        let goal = direction * speed;
        let force = -soft.mass_scale * (k.inverse() * (v - goal)) / h;
        let max = spring.max_force.max(0.0);
        let force = if force.length() > max {
            force.normalize_or_zero() * max
        } else {
            force
        };
        if force.is_finite() { force } else { Vec3::ZERO }
    }

    /// A torque (N·m, world) that, applied for the next step, takes the fraction 1 − e^(−h/τ) of the
    /// body's spin away: rotational damping with time constant `time_constant` (s). A held body
    /// swings about the held point, where the spring cannot damp it. Zero for static bodies.
    pub fn spin_damping_torque(&self, id: BodyId, time_constant: f32) -> Vec3 {
        let body = self.body(id);
        let h = self.settings().dt;
        if body.is_static() || time_constant.is_nan() || time_constant <= 0.0 {
            return Vec3::ZERO;
        }
        let fraction = 1.0 - (-h / time_constant).exp();
        let inertia_world = body.inv_inertia_world().inverse();
        let torque = -(inertia_world * body.angular_velocity()) * fraction / h;
        if torque.is_finite() {
            torque
        } else {
            Vec3::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Pose, Shape};
    use crate::physics::{BodyDesc, Settings};

    fn floating_box() -> (World, BodyId) {
        let mut world = World::new(Settings {
            gravity: Vec3::ZERO,
            ..Settings::default()
        });
        let id = world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(0.5, 0.25, 1.0)),
            Pose::from_position(Vec3::new(1.0, 2.0, 3.0)),
            3.0,
        ));
        (world, id)
    }

    #[test]
    fn compliance_at_the_centre_is_one_over_the_mass_and_grows_off_centre() {
        let (world, id) = floating_box();
        let centre = world.body(id).pose().position;
        let k = world.point_compliance(id, centre);
        assert!((k - Mat3::from_diagonal(Vec3::splat(1.0 / 3.0))).abs_diff_eq(Mat3::ZERO, 1e-6));
        // A sideways force at the end of the box also turns it: the point gives way more easily.
        let end = centre + Vec3::new(0.0, 0.0, 1.0);
        let k_end = world.point_compliance(id, end);
        assert!(Vec3::X.dot(k_end * Vec3::X) > 1.0 / 3.0 + 0.1);
        // Along the arm it does not turn it.
        assert!((Vec3::Z.dot(k_end * Vec3::Z) - 1.0 / 3.0).abs() < 1e-6);
    }

    #[test]
    fn an_impulse_at_a_point_changes_its_velocity_by_compliance_times_impulse() {
        let (mut world, id) = floating_box();
        let point = world.body(id).pose().position + Vec3::new(0.4, 0.2, -0.7);
        let impulse = Vec3::new(1.0, -2.0, 0.5);
        let expected = world.point_compliance(id, point) * impulse;
        world.apply_impulse_at_point(id, impulse, point);
        let got = world.point_velocity(id, point);
        assert!((got - expected).length() < 1e-5, "{got} vs {expected}");
    }

    #[test]
    fn the_motor_drives_a_free_point_to_its_speed_in_one_step_when_the_force_allows() {
        let (mut world, id) = floating_box();
        let point = world.body(id).pose().position + Vec3::new(0.3, 0.0, -1.0);
        let force = world.motor_force(id, point, Vec3::X, 2.5, 1e6);
        world.apply_force_at_point(id, Vec3::X * force, point);
        world.step();
        // The point moved and turned with the body: its material velocity is what the motor aimed at.
        let pose = *world.body(id).pose();
        let held = pose.position + pose.rotation * Vec3::new(0.3, 0.0, -1.0);
        let v = world.point_velocity(id, held);
        assert!(v.x > 2.3 && v.x < 2.7, "{v}");
    }

    #[test]
    fn the_motor_never_brakes_and_respects_its_limit() {
        let (mut world, id) = floating_box();
        let centre = world.body(id).pose().position;
        world.apply_impulse_at_point(id, Vec3::X * 30.0, centre); // 10 m/s
        assert_eq!(world.motor_force(id, centre, Vec3::X, 2.5, 100.0), 0.0);
        assert_eq!(world.motor_force(id, centre, -Vec3::X, 2.5, 100.0), 100.0);
    }

    #[test]
    fn the_spring_is_capped_and_pulls_toward_its_target() {
        let (world, id) = floating_box();
        let centre = world.body(id).pose().position;
        let spring = PointSpring {
            hertz: 8.0,
            damping_ratio: 0.7,
            max_force: 50.0,
            max_speed: 10.0,
        };
        let far = world.spring_force(id, centre, centre + Vec3::new(0.0, 0.0, 100.0), &spring);
        assert!((far.length() - 50.0).abs() < 1e-3 && far.z > 49.9, "{far}");
        let near = world.spring_force(id, centre, centre + Vec3::new(0.01, 0.0, 0.0), &spring);
        assert!(near.x > 0.0 && near.length() < 50.0, "{near}");
    }

    #[test]
    fn spin_damping_takes_its_fraction_of_the_spin_each_step() {
        let (mut world, id) = floating_box();
        let centre = world.body(id).pose().position;
        world.apply_impulse_at_point(id, Vec3::X, centre + Vec3::Z);
        let before = world.body(id).angular_momentum().length();
        assert!(before > 0.1);
        let torque = world.spin_damping_torque(id, 0.25);
        // A torque as a couple: the force at a unit arm perpendicular to it, and its opposite at the centre.
        let arm = torque.normalize().any_orthonormal_vector();
        let force = torque.cross(arm);
        world.apply_force_at_point(id, force, centre + arm);
        world.apply_force_at_point(id, -force, centre);
        world.step();
        // Free of other torques, angular momentum is what the damping changes (ω turns with the box).
        let after = world.body(id).angular_momentum().length();
        let expected = before * (-world.settings().dt / 0.25).exp();
        assert!(
            (after - expected).abs() < 1e-3 * before,
            "{before} → {after}, expected {expected}"
        );
    }
}
