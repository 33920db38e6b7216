//! A ball dropped with a horizontal speed onto a floor with friction bounces, and friction acts
//! through the impact: the normal impulse is (1 + e)·m·c (c the approach speed), so Coulomb's law
//! bounds the tangential impulse by μ·(1 + e)·m·c. Along +x with spin ω about z the contact point
//! slips at u = v + ω·r; if that bound is at least (2/7)·m·|u| the contact point stops slipping
//! within the impact and the ball leaves rolling,
//!
//!   v⁺ = v − (2/7)·u,   ω⁺ = −v⁺/r,
//!
//! else it slides throughout and leaves with
//!
//!   v⁺ = v − μ·(1 + e)·c·sign u,   ω⁺ = ω − (5/2)·μ·(1 + e)·c·sign u / r.
//!
//! An engine whose friction sees only the plastic part of the impact (the rebound added after it,
//! frictionless) takes away 1/(1 + e) of that: half for an elastic ball.

use glam::Vec3;

use super::restitution::{body, bouncy_floor, scene};
use super::{Family, Outcome, Unit};
use crate::geometry::{Pose, Shape};
use crate::physics::BodyId;
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the ball, m.
const RADIUS: f32 = 0.25;
/// Height of the drop (gap under the ball), m.
const DROP_M: f32 = 1.0;
/// Allowed error of v⁺ and of r·ω⁺, as a fraction of the speed the ball is thrown at.
pub const TOLERANCE: f32 = 0.01;

/// One throw: horizontal speed, spin as r·ω over it, restitution and friction of ball and floor.
#[derive(Clone, Copy, Debug)]
pub struct Throw {
    pub speed: f32,
    pub spin: f32,
    pub e: f32,
    pub mu: f32,
}

impl Throw {
    /// v⁺ and ω⁺ (about z) after the first bounce, for an approach speed `c`.
    pub fn after(&self, c: f32) -> (f32, f32) {
        let (v, w) = (self.speed, self.spin * self.speed / RADIUS);
        let u = v + w * RADIUS;
        let friction = self.mu * (1.0 + self.e) * c;
        if friction >= 2.0 / 7.0 * u.abs() {
            let v_after = v - 2.0 / 7.0 * u;
            (v_after, -v_after / RADIUS)
        } else {
            let sign = u.signum();
            (v - friction * sign, w - 2.5 * friction * sign / RADIUS)
        }
    }

    /// Whether the contact point stops slipping within the impact.
    pub fn grips(&self, c: f32) -> bool {
        self.mu * (1.0 + self.e) * c >= 2.0 / 7.0 * (self.speed * (1.0 + self.spin)).abs()
    }
}

/// Drops the ball from `DROP_M` moving along +x and spinning, and reads its velocity at the apex of
/// its first hop; the error is the larger distance of v and of r·ω from the answer, over the speed
/// thrown.
pub fn outcome(throw: Throw, knobs: Knobs) -> Outcome {
    let shape = Shape::sphere(RADIUS);
    let mut ball = body(
        shape,
        Pose::from_position(Vec3::new(-5.0, RADIUS + DROP_M, 0.0)),
        throw.e,
        4,
    );
    ball.desc.friction = throw.mu;
    ball.desc.linear_velocity = Vec3::X * throw.speed;
    ball.desc.angular_velocity = Vec3::Z * (throw.spin * throw.speed / RADIUS);
    let mut ground = bouncy_floor(throw.e);
    ground.desc.friction = throw.mu;
    let scene = scene(format!("oblique bounce {throw:?}"), vec![ground, ball]);
    let g = -scene.settings.gravity.y;
    let c = (2.0 * g * DROP_M).sqrt();
    let (v_want, w_want) = throw.after(c);
    let mut run = Timed::new(knobs.world(&scene));
    let id = BodyId(1);
    // Fall, bounce, and rise to the apex (the vertical velocity turns from up to down).
    let (mut bounced, mut apex) = (false, None);
    for _ in 0..(3.0 / run.world.settings().dt) as usize {
        run.step();
        let vy = run.world.body(id).linear_velocity().y;
        bounced |= vy > 0.0;
        if bounced && vy <= 0.0 {
            apex = Some(run.world.body(id));
            break;
        }
    }
    let Some(ball) = apex else {
        return Outcome {
            error: f32::NAN,
            ms_per_step: run.median_ms(),
            detail: "never rose to an apex".into(),
        };
    };
    let (v, w) = (ball.linear_velocity(), ball.angular_velocity());
    let v_error = Vec3::new(v.x - v_want, 0.0, v.z).length();
    let w_error = RADIUS * (w - Vec3::Z * w_want).length();
    Outcome {
        error: v_error.max(w_error) / throw.speed,
        ms_per_step: run.median_ms(),
        detail: format!(
            "left at v = {:.4} m/s, r·ω = {:.4} m/s; expected v = {v_want:.4}, r·ω_z = {:.4} ({})",
            v.x,
            RADIUS * w,
            RADIUS * w_want,
            if throw.grips(c) { "grips" } else { "slides" }
        ),
    }
}

/// Elastic and half-elastic balls, thrown at 3 m/s without spin, with topspin or backspin, on floors
/// that let them slide through the impact (μ = 0.05) or grip (μ = 0.5).
pub fn family() -> Family {
    let mut throws = Vec::new();
    for e in [0.5, 1.0] {
        for mu in [0.05, 0.5] {
            for spin in [0.0, -2.0, 1.0] {
                throws.push(Throw {
                    speed: 3.0,
                    spin,
                    e,
                    mu,
                });
            }
        }
    }
    Family::of(
        "oblique bounce",
        "friction through the impact: |Δv| ≤ μ·(1 + e)·c, or the ball leaves rolling (1 %)",
        Unit::Relative,
        TOLERANCE,
        throws,
        |throw| format!("e={} μ={} r·ω/v={}", throw.e, throw.mu, throw.spin),
        outcome,
    )
}
