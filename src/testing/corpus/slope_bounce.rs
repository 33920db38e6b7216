//! A ball dropped straight down onto a frictionless slope of angle θ bounces off along the slope's
//! normal n, not back up: the impact law changes only the normal part of its velocity,
//!
//!   v⁺ = v − (1 + e)·(v·n)·n,   so falling at c it leaves with v⁺ₓ = −(1 + e)·c·sin θ·cos θ
//!
//! sideways, which nothing changes in flight. A contact whose normal is taken from where the ball
//! was a step before it touched, or that bounces along the vertical, gets it wrong.

use glam::{Quat, Vec3};

use super::restitution::{body, scene};
use super::{Family, Outcome, Unit};
use crate::color::FLOOR_COLOR;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the ball, m.
const RADIUS: f32 = 0.25;
/// Height the ball falls before it touches the slope, m.
const DROP_M: f32 = 1.0;
/// Allowed error of the sideways speed after the bounce, as a fraction of the fall speed.
pub const TOLERANCE: f32 = 0.01;

/// One drop: the slope's angle, degrees, and the restitution of ball and slope.
#[derive(Clone, Copy, Debug)]
pub struct SlopeDrop {
    pub angle_deg: f32,
    pub e: f32,
}

/// Drops the ball; the error is the distance of its sideways speed after the first bounce from
/// −(1 + e)·c·sin θ·cos θ, over c.
pub fn outcome(drop: SlopeDrop, knobs: Knobs) -> Outcome {
    let theta = drop.angle_deg.to_radians();
    let tilt = Quat::from_rotation_z(theta);
    let normal = tilt * Vec3::Y;
    let half = Vec3::new(6.0, 0.5, 3.0);
    let mut slope = SceneBody::new(
        BodyDesc::fixed(Shape::cuboid(half), Pose::new(Vec3::ZERO, tilt)),
        FLOOR_COLOR,
    );
    (slope.desc.restitution, slope.desc.friction) = (drop.e, 0.0);
    // Above the slope's centre, where its surface is at the height of the top face's centre.
    let touch_y = half.y / normal.y + RADIUS / normal.y;
    let ball = body(
        Shape::sphere(RADIUS),
        Pose::from_position(Vec3::new(0.0, touch_y + DROP_M, 0.0)),
        drop.e,
        4,
    );
    let scene = scene(format!("slope bounce {drop:?}"), vec![slope, ball]);
    let g = -scene.settings.gravity.y;
    let c = (2.0 * g * DROP_M).sqrt();
    let expected = -(1.0 + drop.e) * c * theta.sin() * theta.cos();
    let mut run = Timed::new(knobs.world(&scene));
    let id = BodyId(1);
    // Until it has bounced (it rises along the slope's normal), then a few steps of flight.
    let mut after = None;
    for _ in 0..(2.0 / run.world.settings().dt) as usize {
        run.step();
        let v = run.world.body(id).linear_velocity();
        if v.dot(normal) > 0.0 {
            after = Some(v);
            break;
        }
    }
    let Some(v) = after else {
        return Outcome {
            error: f32::NAN,
            ms_per_step: run.median_ms(),
            detail: "never bounced".into(),
        };
    };
    Outcome {
        error: ((v.x - expected).abs()).max(v.z.abs()) / c,
        ms_per_step: run.median_ms(),
        detail: format!("left at {v:.4} m/s; expected {expected:.4} m/s along x"),
    }
}

/// Slopes of 10° to 40°, elastic and half-elastic balls.
pub fn family() -> Family {
    let drops = [10.0, 20.0, 30.0, 40.0]
        .into_iter()
        .flat_map(|angle_deg| [1.0, 0.5].map(|e| SlopeDrop { angle_deg, e }));
    Family::of(
        "slope bounce",
        "a ball dropped on a frictionless slope leaves sideways at −(1 + e)·c·sin θ·cos θ (1 %)",
        Unit::Relative,
        TOLERANCE,
        drops,
        |drop| format!("{}° e={}", drop.angle_deg, drop.e),
        outcome,
    )
}
