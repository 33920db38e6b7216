//! Newton's cradle: a row of touching equal balls (e = 1, no friction, no gravity) struck end-on by
//! one more. Momentum and energy both kept leave one answer for equal balls: the striker and the
//! row stop and the far ball leaves at the striker's speed. A solver that treats the row as one
//! body moves it all off together (and loses energy); one that meets the impacts in the order they
//! happen passes the speed along.

use glam::Vec3;

use super::restitution::{body, bouncy_floor, scene};
use super::{Family, Member, Outcome, Unit};
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyId, World};
use crate::scene::Scene;
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the balls, m.
pub const RADIUS: f32 = 0.25;
/// The striker's speed, m/s.
pub const STRIKE_SPEED: f32 = 2.0;
/// Gap between the striker and the row at the start, m.
const STRIKE_GAP: f32 = 0.37;
/// Simulated time of a run, s.
const SECONDS: f32 = 2.0;
/// Allowed error: of the far ball's speed and of every other ball's, over the strike speed, and of
/// the energy, relative (the issue asks for 1.9 m/s, 0.2 m/s and 5 %).
pub const TOLERANCE: f32 = 0.05;

/// `count` balls (≥ 2) along x: the striker (body 0, or 1 over a floor) moving at
/// [`STRIKE_SPEED`] and `count − 1` at rest, touching. `floor`: resting on a frictionless floor
/// under gravity instead of floating.
pub fn cradle(count: usize, floor: bool) -> Scene {
    let mut bodies = Vec::new();
    if floor {
        let mut ground = bouncy_floor(0.0);
        ground.desc.friction = 0.0;
        bodies.push(ground);
    }
    let y = if floor { RADIUS } else { 1.0 };
    for i in 0..count {
        let x = if i == 0 {
            -STRIKE_GAP - 2.0 * RADIUS
        } else {
            2.0 * RADIUS * (i - 1) as f32
        };
        let mut ball = body(
            Shape::sphere(RADIUS),
            Pose::from_position(Vec3::new(x, y, 0.0)),
            1.0,
            i,
        );
        if i == 0 {
            ball.desc.linear_velocity = Vec3::X * STRIKE_SPEED;
        }
        bodies.push(ball);
    }
    let mut scene = scene(format!("cradle({count})"), bodies);
    if !floor {
        scene.settings.gravity = Vec3::ZERO;
    }
    scene
}

/// Kinetic energy of the balls, J.
fn energy(world: &World, balls: &[BodyId]) -> f32 {
    balls
        .iter()
        .map(|&id| world.body(id).kinetic_energy())
        .sum()
}

/// Runs the cradle; the error is the worst of the far ball's speed error and every other ball's
/// speed (over the strike speed) and the energy error (relative).
pub fn outcome(count: usize, floor: bool, knobs: Knobs) -> Outcome {
    let first = usize::from(floor) as u32;
    let balls: Vec<BodyId> = (first..first + count as u32).map(BodyId).collect();
    let mut run = Timed::new(knobs.world(&cradle(count, floor)));
    let before = energy(&run.world, &balls);
    let steps = (SECONDS / run.world.settings().dt).round() as usize;
    for _ in 0..steps {
        run.step();
    }
    let speeds: Vec<f32> = balls
        .iter()
        .map(|&id| run.world.body(id).linear_velocity().x)
        .collect();
    let after = energy(&run.world, &balls);
    let (far, rest) = speeds.split_last().expect("a cradle has balls");
    let far_error = (far - STRIKE_SPEED).abs() / STRIKE_SPEED;
    let rest_error = rest.iter().fold(0.0f32, |a, v| a.max(v.abs())) / STRIKE_SPEED;
    let energy_error = (after - before).abs() / before;
    Outcome {
        error: far_error.max(rest_error).max(energy_error),
        ms_per_step: run.median_ms(),
        detail: format!("speeds {speeds:.3?} m/s, energy {after:.4} J of {before:.4} J"),
    }
}

/// Cradles of 2 to 7 balls, floating and on a frictionless floor.
pub fn family() -> Family {
    let mut members = Vec::new();
    for floor in [false, true] {
        for count in 2..=7 {
            members.push(Member {
                label: format!("{count} balls{}", if floor { " on a floor" } else { "" }),
                tolerance: TOLERANCE,
                run: Box::new(move |knobs| outcome(count, floor, knobs)),
            });
        }
    }
    Family {
        name: "newton's cradle",
        answer: "far ball leaves at the strike speed, the others stop, energy kept",
        unit: Unit::Relative,
        members,
    }
}
