//! A ball launched along a floor with spin: it skids until friction has made it roll, then rolls on.
//! Along +x with spin ω about z, the contact point (r below the centre) moves at u = v + ω·r. Sliding
//! friction F = −μ·m·g·sign u there slows the centre and, through its torque r·F about z against the
//! inertia (2/5)·m·r², turns the ball:
//!
//!   dv/dt = −μ·g·sign u,   dω/dt = −(5/2)·(μ·g/r)·sign u   ⇒   du/dt = −(7/2)·μ·g·sign u,
//!
//! so the slip is gone after t* = 2·|u₀|/(7·μ·g), and the ball rolls on at
//!
//!   v* = v₀ − (2/7)·u₀ = (5·v₀ − 2·ω₀·r)/7
//!
//! whatever μ is (angular momentum about the contact point is kept). A ball thrown without spin rolls
//! at 5/7 of its speed; with backspin ω₀·r = 2.5·v₀ it stops dead (the stop shot); with more it comes
//! back (the draw shot); already rolling, nothing changes. An engine whose friction row sees only the
//! centre's velocity, or that lets the row's impulse overshoot the slip, rolls at the wrong speed or
//! never stops skidding.

use glam::Vec3;

use super::restitution::scene;
use super::{Family, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::scene::cases::floor;
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the ball, m.
pub const RADIUS: f32 = 0.25;
/// Allowed error of the final speed and of the final spin (as r·ω), as a fraction of v₀.
pub const TOLERANCE: f32 = 0.01;
/// Time the ball is watched after it should roll, s: rolling must be kept, not only reached.
const AFTER_S: f32 = 1.0;

/// One launch: speed along +x, spin about z as r·ω₀ over v₀ (−1: rolling; 0: none; > 0: backspin),
/// and the friction of ball and floor.
#[derive(Clone, Copy, Debug)]
pub struct Skid {
    pub speed: f32,
    pub spin: f32,
    pub mu: f32,
}

impl Skid {
    /// The rolling speed the ball ends at, m/s.
    pub fn rolling_speed(&self) -> f32 {
        (5.0 * self.speed - 2.0 * self.spin * self.speed) / 7.0
    }

    /// The contact point's initial slip speed u₀ = v₀ + r·ω₀, m/s.
    fn slip(&self) -> f32 {
        self.speed * (1.0 + self.spin)
    }

    /// When the slip is gone, s, under gravity `g`.
    pub fn skid_time(&self, g: f32) -> f32 {
        2.0 * self.slip().abs() / (7.0 * self.mu * g)
    }

    /// The speed of the centre `t` seconds into the skid (t ≤ the skid time), m/s.
    pub fn skidding_speed(&self, t: f32, g: f32) -> f32 {
        self.speed - self.mu * g * self.slip().signum() * t
    }
}

/// Runs the launch until `AFTER_S` past the skid time; the error, over v₀, is the largest of the
/// distances of the final speed and of the final r·ω from the rolling answer, and of the speed halfway
/// through the skid from v₀ − μ·g·t (the rolling speed does not depend on μ; the skid's deceleration
/// does). The speed is compared rather than the distance gone: semi-implicit Euler, which every engine
/// of this kind steps with, lags the distance by ½·μ·g·h·t (2 % of a 0.2 s skid at the default
/// sub-step) but gives the speed exactly.
pub fn outcome(skid: Skid, knobs: Knobs) -> Outcome {
    let mut ground = floor(40.0);
    ground.desc.friction = skid.mu;
    let shape = Shape::sphere(RADIUS);
    let pose = Pose::from_position(Vec3::new(-15.0, RADIUS, 0.0));
    let mut desc = BodyDesc::dynamic(shape, pose, shape.volume());
    desc.friction = skid.mu;
    desc.linear_velocity = Vec3::X * skid.speed;
    desc.angular_velocity = Vec3::Z * (skid.spin * skid.speed / RADIUS);
    let ball = SceneBody::new(desc, PALETTE[4]);
    let scene = scene(format!("skid {skid:?}"), vec![ground, ball]);
    let g = -scene.settings.gravity.y;
    let mut run = Timed::new(knobs.world(&scene));
    let dt = run.world.settings().dt;
    let skid_time = skid.skid_time(g);
    // Halfway (to the step) through the skid; a ball already rolling has none.
    for _ in 0..(0.5 * skid_time / dt).floor() as usize {
        run.step();
    }
    let (t_mid, v_mid) = (run.time(), run.world.body(BodyId(1)).linear_velocity());
    let mid_error = (v_mid - Vec3::X * skid.skidding_speed(t_mid, g)).length();
    for _ in 0..((skid_time + AFTER_S) / dt).ceil() as usize - run.step_count() {
        run.step();
    }
    let ball = run.world.body(BodyId(1));
    let (v, w) = (ball.linear_velocity(), ball.angular_velocity());
    let expected = skid.rolling_speed();
    // Rolling along +x at v* turns the ball at ω_z = −v*/r; off-axis motion or spin counts too.
    let speed_error = (v - Vec3::X * expected).length();
    let spin_error = (RADIUS * w - Vec3::Z * -expected).length();
    Outcome {
        error: speed_error.max(spin_error).max(mid_error) / skid.speed,
        ms_per_step: run.median_ms(),
        detail: format!(
            "{v_mid:.4} m/s after {t_mid:.3} s (expected {:.4} along x); ends at v = {v:.4} m/s, \
             r·ω = {:.4} m/s (expected v = {expected:.4} along x, rolling)",
            skid.skidding_speed(t_mid, g),
            RADIUS * w
        ),
    }
}

/// Thrown without spin, with topspin, already rolling, and with the backspin of the stop and draw
/// shots, at frictions 0.1–0.5 and speeds 1–6 m/s.
pub fn family() -> Family {
    let skids = [
        Skid {
            speed: 3.0,
            spin: 0.0,
            mu: 0.5,
        },
        Skid {
            speed: 3.0,
            spin: 0.0,
            mu: 0.1,
        },
        Skid {
            speed: 6.0,
            spin: 0.0,
            mu: 0.2,
        },
        Skid {
            speed: 3.0,
            spin: -2.0,
            mu: 0.3,
        },
        Skid {
            speed: 6.0,
            spin: -1.0,
            mu: 0.2,
        },
        Skid {
            speed: 3.0,
            spin: 2.5,
            mu: 0.3,
        },
        Skid {
            speed: 1.0,
            spin: 2.5,
            mu: 0.5,
        },
        Skid {
            speed: 3.0,
            spin: 4.0,
            mu: 0.3,
        },
    ];
    Family::of(
        "skid to roll",
        "rolls on at (5·v₀ − 2·r·ω₀)/7 after 2·|v₀ + r·ω₀|/(7·μ·g)",
        Unit::Relative,
        TOLERANCE,
        skids,
        |skid| format!("v={} r·ω/v={} μ={}", skid.speed, skid.spin, skid.mu),
        outcome,
    )
}
