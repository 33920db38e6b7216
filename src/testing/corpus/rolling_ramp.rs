//! A ball released on a ramp of angle θ. Friction acts at the contact; with μ large enough the ball
//! rolls without slipping and, its inertia 2/5·m·r² taking a share of gravity's work,
//!
//!   m·a = m·g·sin θ − f,   (2/5)·m·r²·a/r = f·r   ⇒   a = (5/7)·g·sin θ,   f = (2/7)·m·g·sin θ,
//!
//! which friction can supply while (2/7)·tan θ ≤ μ. Below that it slips: a = g·(sin θ − μ·cos θ).
//! A solver that lets friction act on the linear motion only (or resolves the rolling constraint
//! loosely) gives g·sin θ; one that locks the contact point regardless of μ rolls where it should
//! slip.

use glam::{Quat, Vec3};

use super::restitution::scene;
use super::{Family, Member, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::scene::cases::{RAMP_CENTER, RAMP_HALF, ramp_downhill_at, ramp_slab};
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the ball, m.
pub const RADIUS: f32 = 0.5;
/// Simulated time of a run, s.
const SECONDS: f32 = 1.5;
/// Where on the ramp the ball starts, m up the slope from its centre.
const START_UPHILL_M: f32 = 5.0;
/// Allowed relative error of the distance rolled.
pub const TOLERANCE: f32 = 0.01;

/// The acceleration down a slope of `theta` for friction `mu` under gravity `g`, m/s²: rolling
/// while μ ≥ (2/7)·tan θ, slipping below.
pub fn expected_acceleration(theta: f32, mu: f32, g: f32) -> f32 {
    if mu >= 2.0 / 7.0 * theta.tan() {
        5.0 / 7.0 * g * theta.sin()
    } else {
        g * (theta.sin() - mu * theta.cos())
    }
}

/// Runs the ball on the ramp at `angle_deg` of friction `mu` for `SECONDS`; the error is the
/// distance it went down the slope against ½·a·t², relative.
pub fn outcome(angle_deg: f32, mu: f32, knobs: Knobs) -> Outcome {
    let theta = angle_deg.to_radians();
    let down = ramp_downhill_at(theta);
    let normal = Quat::from_rotation_z(theta) * Vec3::Y;
    let centre = RAMP_CENTER - down * START_UPHILL_M + normal * (RAMP_HALF.y + RADIUS);
    let shape = Shape::sphere(RADIUS);
    let mut desc = BodyDesc::dynamic(shape, Pose::from_position(centre), shape.volume());
    desc.friction = mu;
    let ball = SceneBody::new(desc, PALETTE[4]);
    let scene = scene(
        format!("ball on a ramp {angle_deg}° μ={mu}"),
        vec![ramp_slab(theta, mu), ball],
    );
    let g = scene.settings.gravity.length();
    let mut run = Timed::new(knobs.world(&scene));
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        run.step();
    }
    let t = run.time();
    let expected = 0.5 * expected_acceleration(theta, mu, g) * t * t;
    let went = (run.world.body(BodyId(1)).pose().position - centre).dot(down);
    Outcome {
        error: (went - expected).abs() / expected,
        ms_per_step: run.median_ms(),
        detail: format!("went {went:.4} m down the slope, expected {expected:.4} m"),
    }
}

/// Rolling at 10°–40° (μ = 0.5), and slipping at 30° and 40° (μ below (2/7)·tan θ).
pub fn family() -> Family {
    let runs = [
        (10.0, 0.5),
        (20.0, 0.5),
        (30.0, 0.5),
        (40.0, 0.5),
        (30.0, 0.1),
        (40.0, 0.15),
    ];
    Family {
        name: "ball on a ramp",
        answer: "rolls at (5/7)·g·sin θ, or slips at g(sin θ − μ cos θ) below μ = (2/7)·tan θ",
        unit: Unit::Relative,
        members: runs
            .into_iter()
            .map(|(angle, mu): (f32, f32)| {
                let rolls = mu >= 2.0 / 7.0 * f32::tan(angle.to_radians());
                Member {
                    label: format!("{angle}° μ={mu} {}", if rolls { "rolls" } else { "slips" }),
                    tolerance: TOLERANCE,
                    run: Box::new(move |knobs| outcome(angle, mu, knobs)),
                }
            })
            .collect(),
    }
}
