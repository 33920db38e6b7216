//! Driving one point of a body: what a hand needs to move a body by a point it holds.
//!
//! Two drives:
//! - a **speed motor**, computed from the body's state at a step boundary: the force along a direction
//!   that brings the point's speed along it to a target speed, never more than a limit and never
//!   braking (a push that leans in up to a walking pace). The caller applies it with
//!   [`World::apply_force_at_point`] for the next step.
//! - a **point hold** ([`World::hold_point`]): Box2D's mouse joint, a soft constraint pulling the
//!   point toward a target with a natural frequency and damping ratio, its force capped, solved in
//!   every sub-step of the next step while the target moves at a steady speed from where it was at the
//!   step's start to where it is at its end.
//!
//! Both are inputs given between steps, so they are journaled like any other (a recording replays them
//! exactly), and both are capped so the contact solver stays in charge of what the body touches: the
//! hold is applied before the contacts are solved in each sub-step, like a force, so a held body
//! dragged into the floor stops at it, where a constraint as stiff as the contacts would not.
//!
//! Both see the point's effective mass, the mass a force at that point meets once the spin it causes
//! is counted: for a force along unit n at offset r from the centre of mass,
//!
//!   K = (1/m)·𝟙 − \[r\]× · I⁻¹ · \[r\]×       (3×3, world frame; \[r\]× the cross-product matrix)
//!   m_eff(n) = 1 / (nᵀ K n)
//!
//! so an off-centre push spins the body instead of over-driving it (Catto, "Modeling and Solving
//! Constraints", GDC 2009; Box2D v3 `mouse_joint.c`).

use glam::{Mat3, Vec3, Vec3A};

use crate::physics::input::WorldInput;
use crate::physics::solve::softness::Softness;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion, skew};
use crate::physics::{BodyId, World};

/// A soft spring pulling a body's point toward a target (Box2D's mouse joint).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointSpring {
    /// Natural frequency, Hz, > 0: the stiffness is m_eff·(2π·hertz)².
    pub hertz: f32,
    /// Damping ratio, ≥ 0 (1 = critically damped).
    pub damping_ratio: f32,
    /// Largest force the spring exerts, N, ≥ 0.
    pub max_force: f32,
    /// Fastest the spring drives the point toward the target (relative to the target), m/s, > 0
    /// (see [`PointHold`]).
    pub max_speed: f32,
}

impl PointSpring {
    /// Finite, with a frequency and a top speed > 0 and a damping ratio and force ≥ 0.
    pub fn is_valid(&self) -> bool {
        self.hertz.is_finite()
            && self.hertz > 0.0
            && self.damping_ratio.is_finite()
            && self.damping_ratio >= 0.0
            && self.max_force.is_finite()
            && self.max_force >= 0.0
            && self.max_speed.is_finite()
            && self.max_speed > 0.0
    }
}

/// A body's point held on a [`PointSpring`] to a moving target for one step ([`World::hold_point`]).
///
/// In each sub-step of length h (at time t from the step's start, of length dt), with the held point
/// x = c + R·anchor at offset r = R·anchor from the centre c, the target T = from + (to − from)·t/dt
/// moving at u = (to − from)/dt (taken as 0 if faster than `max_speed`), the point's velocity v + ω × r, and the soft-constraint coefficients
/// of `Softness` for (hertz, ζ, h):
///
///   d = |T − x|,  n = (T − x)/d
///   w = u + n · min(bias_rate · d,  √(a · d)),  at most max_speed long   (the velocity asked for)
///   λ = −mass_scale · K⁻¹ · ((v + ω × r) − w),   |λ| ≤ max_force · h, holding up first
///   v += λ/m,  ω += I⁻¹ (r × λ),  then  ω ← ω · e^(−h/τ)      (τ = `spin_time`)
///
/// With u = 0 and w = n·bias_rate·d this is Box2D's mouse joint (one soft-constraint solve per sub-step;
/// with a single solve, warm starting adds nothing), implicit in the spring so stable at any
/// frequency; at rest it is a spring of stiffness m_eff·ω², so a held body sags g/ω² under gravity
/// (each sub-step's −g·h is taken back when (1 − mass_scale)·g·h = mass_scale·bias_rate·sag): 3.9 mm
/// at 8 Hz, where a force from the same spring applied once per 60 Hz step, gravity integrated with
/// it, sagged g·(1 + hω·(2ζ + hω))/ω² = 1.1 cm. Three things differ from Box2D's joint:
/// - The damping acts on the point's velocity relative to the target's, so a point dragged at a steady
///   speed keeps up with it instead of trailing by 2ζ·v/ω, and a release leaves it the drag's speed.
/// - The velocity asked for is bounded. With the force capped, a target metres away pulls with a
///   force of fixed size toward it, a central force, and a body flung past it went into orbit about
///   the pointer; bounding the speed asked for keeps the damping of any sideways motion in the
///   impulse. A target moving faster than `max_speed` (a pointer that jumped: it left the terminal
///   and came back) is taken as being moved, not as moving: u = 0, and the approach brings the
///   point to it without sailing past.
/// - The cap serves the body's weight first: the impulse λ_g = −m·g·h that cancels the sub-step's
///   gravity, then the rest of λ − λ_g within what is left (|λ| ≤ max_force·h still). A body chasing a
///   pointer metres away spent the whole cap on the chase and fell a metre or more on the way.
///   √(a·d) is the speed from which half the capped force stops the point at the target
///   (v² = 2·(a/2)·d), a = (max_force − m·|g|)·|K n| what the cap left after the body's weight gives
///   the point along n.
/// - A little spin damping (time constant τ) is the hand's grip: a body held off its centre swings
///   about the held point, where the spring cannot damp it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointHold {
    pub body: BodyId,
    /// The held point in the body's frame, m.
    pub anchor: Vec3,
    /// Where the target is at the start of the step and at its end, world, m.
    pub from: Vec3,
    pub to: Vec3,
    pub spring: PointSpring,
    /// Time constant of the spin damping, s; 0 for none.
    pub spin_time: f32,
}

impl PointHold {
    /// Finite, with a valid spring and a spin time ≥ 0.
    pub fn is_valid(&self) -> bool {
        self.anchor.is_finite()
            && self.from.is_finite()
            && self.to.is_finite()
            && self.spring.is_valid()
            && self.spin_time.is_finite()
            && self.spin_time >= 0.0
    }

    /// One sub-step of the hold on its body's solver copy: `centre` is its centre of mass now, `t`
    /// the time since the step's start, `h` the sub-step, `dt` the step and `gravity` the world's
    /// (see the type's docs). Returns the impulse applied at the held point, N·s.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve_substep(
        &self,
        body: &mut SolverBody,
        motion: &SolverMotion,
        centre: Vec3,
        gravity: Vec3,
        t: f32,
        h: f32,
        dt: f32,
    ) -> Vec3 {
        if self.spin_time > 0.0 {
            body.w *= (-h / self.spin_time).exp();
        }
        let inv_inertia = Mat3::from(motion.inv_inertia);
        let r = motion.rotation * self.anchor;
        let skew_r = skew(r);
        let k = Mat3::from_diagonal(Vec3::splat(motion.inv_mass)) - skew_r * inv_inertia * skew_r;
        if k.determinant().abs() <= f32::MIN_POSITIVE {
            return Vec3::ZERO;
        }
        let soft = Softness::new(self.spring.hertz, self.spring.damping_ratio, h);
        let target = self.from.lerp(self.to, t / dt);
        let moved = (self.to - self.from) / dt;
        let target_velocity = if moved.length() <= self.spring.max_speed {
            moved
        } else {
            Vec3::ZERO
        };
        let to_target = target - (centre + r);
        let distance = to_target.length();
        let direction = to_target.normalize_or_zero();
        // The cap holds the body up first (its weight comes out of the cap before the rest of the
        // pull), so what is left of it is what brakes the approach.
        let max = self.spring.max_force * h;
        let support = (-gravity * h / motion.inv_mass).clamp_length_max(max);
        let accel = (max - support.length()) / h * (k * direction).length();
        let approach = direction * (soft.bias_rate * distance).min((accel * distance).sqrt());
        let goal = (target_velocity + approach).clamp_length_max(self.spring.max_speed);
        let v = Vec3::from(body.v) + Vec3::from(body.w).cross(r);
        let impulse = -soft.mass_scale * (k.inverse() * (v - goal));
        let impulse = support + (impulse - support).clamp_length_max(max - support.length());
        if !impulse.is_finite() {
            return Vec3::ZERO;
        }
        body.v += motion.inv_mass * Vec3A::from(impulse);
        body.w += motion.inv_inertia * Vec3A::from(r.cross(impulse));
        impulse
    }
}

impl World {
    /// Velocity (m/s, world) of the material point of body `id` that is at `point` (world) now:
    /// v + ω × r.
    pub fn point_velocity(&self, id: BodyId, point: Vec3) -> Vec3 {
        let body = self.body(id);
        body.linear_velocity() + body.angular_velocity().cross(point - body.pose().position)
    }

    /// The matrix K (1/kg) that maps a force (or impulse) at `point` (world) to the change of that
    /// point's acceleration (or velocity): K = (1/m)·𝟙 − \[r\]×·I⁻¹·\[r\]×. Zero for static bodies.
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

    /// Holds `hold.anchor` of `hold.body` on its spring to a target moving from `hold.from` to
    /// `hold.to` during the next step only, solved in every sub-step (see [`PointHold`]); wakes the
    /// body. Ignored for static bodies and invalid holds.
    pub fn hold_point(&mut self, hold: PointHold) {
        let Some(body) = self.bodies.get(hold.body.index()) else {
            return;
        };
        if body.is_static || !hold.is_valid() {
            return;
        }
        self.log(WorldInput::Hold(hold));
        self.wake_island(hold.body.0);
        self.holds.push(hold);
    }

    /// The mean force (N, world) the holds exerted on body `id` at their held points over the last
    /// step: what a hand's spring pulled with.
    pub fn hold_force(&self, id: BodyId) -> Vec3 {
        self.scratch
            .holds
            .impulses
            .iter()
            .filter(|(body, _)| *body == id)
            .map(|(_, impulse)| *impulse)
            .sum::<Vec3>()
            / self.settings.dt
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

    fn hold(id: BodyId, target: Vec3, max_force: f32, spin_time: f32) -> PointHold {
        PointHold {
            body: id,
            anchor: Vec3::ZERO,
            from: target,
            to: target,
            spring: PointSpring {
                hertz: 8.0,
                damping_ratio: 0.7,
                max_force,
                max_speed: 10.0,
            },
            spin_time,
        }
    }

    #[test]
    fn a_hold_is_capped_and_pulls_toward_its_target() {
        let (mut world, id) = floating_box();
        let centre = world.body(id).pose().position;
        world.hold_point(hold(id, centre + Vec3::new(0.0, 0.0, 100.0), 50.0, 0.0));
        world.step();
        // At most the capped force for a step: Δv ≤ F·dt/m, all of it toward the target.
        let v = world.body(id).linear_velocity();
        let most = 50.0 * world.settings().dt / 3.0;
        assert!(v.z > 0.999 * most && v.length() <= most * 1.0001, "{v}");
        assert!((world.hold_force(id).length() - 50.0).abs() < 0.01);
        // The hold lasts one step.
        world.step();
        assert!((world.body(id).linear_velocity() - v).length() < 1e-6);
        assert_eq!(world.hold_force(id), Vec3::ZERO);
    }

    #[test]
    fn a_hold_on_a_static_body_or_an_invalid_hold_is_ignored() {
        let (mut world, id) = floating_box();
        world.start_journal();
        let mut bad = hold(id, Vec3::ZERO, 50.0, 0.0);
        bad.spring.hertz = f32::NAN;
        world.hold_point(bad);
        world.set_static(id, true);
        world.hold_point(hold(id, Vec3::ZERO, 50.0, 0.0));
        let journal = world.take_journal();
        assert!(
            !journal
                .iter()
                .any(|(_, i)| matches!(i, WorldInput::Hold(_))),
            "{journal:?}"
        );
        world.step();
        assert_eq!(world.body(id).linear_velocity(), Vec3::ZERO);
    }

    #[test]
    fn spin_damping_takes_its_fraction_of_the_spin_each_step() {
        let mut world = World::new(Settings {
            gravity: Vec3::ZERO,
            ..Settings::default()
        });
        // A cube: no gyroscopic term, so only the damping changes ω.
        let id = world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::splat(0.5)),
            Pose::from_position(Vec3::ZERO),
            3.0,
        ));
        world.apply_impulse_at_point(id, Vec3::X, Vec3::Z);
        let before = world.body(id).angular_velocity();
        assert!(before.length() > 0.1);
        world.hold_point(hold(id, Vec3::ZERO, 50.0, 0.25));
        world.step();
        let after = world.body(id).angular_velocity();
        let expected = before * (-world.settings().dt / 0.25).exp();
        assert!(
            (after - expected).length() < 1e-5 * before.length(),
            "{after} vs {expected}"
        );
    }
}
