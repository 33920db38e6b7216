//! Rolling resistance: a ball of radius r meets a couple up to μr·N·r against rolling. With friction
//! keeping it rolling (I = ⅖·m·r²),
//!
//!   m·a = m·g·sin θ − f,   I·a/r = f·r − μr·m·g·cos θ·r   ⇒   a = (5/7)·g·(sin θ − μr·cos θ),
//!
//! so on a floor a ball rolling at v stops after v²/(2·(5/7)·μr·g), and on a slope it stays put while
//! μr ≥ tan θ (the couple is clamped like static friction) and rolls down with that acceleration
//! below. A couple that acts on the linear motion, or is clamped without the 5/7, misses both.

use glam::{Quat, Vec3};

use super::restitution::scene;
use super::{Family, Member, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::cases::{RAMP_CENTER, RAMP_HALF, floor, ramp_downhill_at, ramp_slab};
use crate::scene::{Scene, SceneBody};
use crate::testing::hard_case::{Knobs, Timed};

/// Friction of the balls and what they roll on (enough to keep them rolling).
const FRICTION: f32 = 0.5;
/// Time the ball is watched after it should have stopped on the floor, s.
const AFTER_S: f32 = 1.0;
/// Time on the slope, s.
const SLOPE_S: f32 = 2.0;
/// How far μr sits from tan θ on the slope, either side.
pub const MARGIN: f32 = 0.02;
/// Allowed relative error (of the stopping distance; of the slope's roll, against the rolling
/// twin's distance).
pub const TOLERANCE: f32 = 0.01;

/// A ball of `radius` and rolling resistance `mu_r` at `position`, moving at `velocity` and rolling
/// on a surface of normal `normal` (ω = n × v / r).
fn ball(radius: f32, mu_r: f32, position: Vec3, velocity: Vec3, normal: Vec3) -> SceneBody {
    let shape = Shape::sphere(radius);
    let mut desc = BodyDesc::dynamic(shape, Pose::from_position(position), shape.volume());
    desc.friction = FRICTION;
    desc.rolling_resistance = mu_r;
    desc.linear_velocity = velocity;
    desc.angular_velocity = normal.cross(velocity) / radius;
    SceneBody::new(desc, PALETTE[5])
}

/// A ball rolling along +x at `speed` on a floor.
fn floor_scene(radius: f32, mu_r: f32, speed: f32) -> Scene {
    let mut ground = floor(40.0);
    ground.desc.friction = FRICTION;
    ground.desc.rolling_resistance = mu_r;
    let start = Vec3::new(-30.0, radius, 0.0);
    let rolling = ball(radius, mu_r, start, Vec3::X * speed, Vec3::Y);
    scene(
        format!("rolling r={radius} μr={mu_r}"),
        vec![ground, rolling],
    )
}

/// Runs the ball on the floor past its stopping time; the error is where it ends against
/// v²/(2·(5/7)·μr·g), relative.
pub fn floor_outcome(radius: f32, mu_r: f32, speed: f32, knobs: Knobs) -> Outcome {
    let scene = floor_scene(radius, mu_r, speed);
    let deceleration = 5.0 / 7.0 * mu_r * -scene.settings.gravity.y;
    let expected = speed * speed / (2.0 * deceleration);
    let mut run = Timed::new(knobs.world(&scene));
    let start = run.world.body(BodyId(1)).pose().position;
    let seconds = speed / deceleration + AFTER_S;
    for _ in 0..(seconds / run.world.settings().dt).ceil() as usize {
        run.step();
    }
    let moved = run.world.body(BodyId(1)).pose().position - start;
    Outcome {
        error: (moved.x - expected).abs().max(moved.z.abs()) / expected,
        ms_per_step: run.median_ms(),
        detail: format!("ended {moved:.4} m away, expected {expected:.4} m along x"),
    }
}

/// Runs a ball of radius 0.5 released at rest on a slope of `angle_deg` with μr = tan θ +
/// `side`·[`MARGIN`]; the error is against the rolling twin's distance (5/7)·g·MARGIN·cos θ·t²/2:
/// how far it is from the expected roll when it rolls, the farthest it got when it holds.
pub fn slope_outcome(angle_deg: f32, side: f32, knobs: Knobs) -> Outcome {
    const RADIUS: f32 = 0.5;
    let theta = angle_deg.to_radians();
    let mu_r = theta.tan() + side * MARGIN;
    let normal = Quat::from_rotation_z(theta) * Vec3::Y;
    let centre = RAMP_CENTER + normal * (RAMP_HALF.y + RADIUS);
    let mut slab = ramp_slab(theta, FRICTION);
    slab.desc.rolling_resistance = mu_r;
    let scene = scene(
        format!("rolling on a slope {angle_deg}° μr={mu_r}"),
        vec![slab, ball(RADIUS, mu_r, centre, Vec3::ZERO, normal)],
    );
    let g = scene.settings.gravity.length();
    let mut run = Timed::new(knobs.world(&scene));
    let mut farthest = 0.0f32;
    for _ in 0..(SLOPE_S / run.world.settings().dt).round() as usize {
        run.step();
        farthest = farthest.max((run.world.body(BodyId(1)).pose().position - centre).length());
    }
    let t = run.time();
    let accel = 5.0 / 7.0 * g * (theta.sin() - mu_r * theta.cos());
    let expected = (0.5 * accel * t * t).max(0.0);
    let scale = 0.5 * 5.0 / 7.0 * g * MARGIN * theta.cos() * t * t;
    let went = (run.world.body(BodyId(1)).pose().position - centre).dot(ramp_downhill_at(theta));
    let error = if side > 0.0 {
        farthest / scale
    } else {
        (went - expected).abs() / scale
    };
    Outcome {
        error,
        ms_per_step: run.median_ms(),
        detail: format!(
            "μr = {mu_r:.4}: went {went:.5} m (expected {expected:.5} m), farthest {farthest:.5} m"
        ),
    }
}

/// Balls of radius 0.25–1 m rolling to a stop on a floor, and balls on 5° and 10° slopes with μr
/// just above tan θ (they hold) and just below (they roll).
pub fn family() -> Family {
    let mut members: Vec<Member> = [
        (0.25, 0.05, 3.0),
        (0.5, 0.02, 2.0),
        (1.0, 0.1, 5.0),
        (0.25, 0.2, 4.0),
    ]
    .into_iter()
    .map(|(radius, mu_r, speed): (f32, f32, f32)| Member {
        label: format!("floor r={radius} μr={mu_r} v={speed}"),
        tolerance: TOLERANCE,
        run: Box::new(move |knobs| floor_outcome(radius, mu_r, speed, knobs)),
    })
    .collect();
    for angle in [5.0f32, 10.0] {
        for (side, what) in [(1.0f32, "holds"), (-1.0, "rolls")] {
            members.push(Member {
                label: format!("{angle}° μr=tanθ{:+} {what}", side * MARGIN),
                tolerance: TOLERANCE,
                run: Box::new(move |knobs| slope_outcome(angle, side, knobs)),
            });
        }
    }
    Family {
        name: "rolling resistance",
        answer: "a = (5/7)·g·(sin θ − μr·cos θ): stops after v²/(2·(5/7)·μr·g); holds if μr ≥ tan θ",
        unit: Unit::Relative,
        members,
    }
}
