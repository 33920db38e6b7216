//! Resting contacts never bounce: bodies of restitution 1 set down touching a floor of
//! restitution 1 (and each other) stay where they are. Restitution acts on impacts faster than the
//! threshold, and a body at rest approaches at g·h per sub-step at most.

use glam::Vec3;

use super::restitution::{body, bouncy_floor, scene};
use super::{Family, Outcome, Unit};
use crate::geometry::{Pose, Shape};
use crate::physics::BodyId;
use crate::scene::Scene;
use crate::testing::hard_case::{Knobs, Timed};

/// Simulated time, s.
const SECONDS: f32 = 10.0;
/// Largest rise of any body above where it was set down, m (the error is in metres).
pub const MAX_RISE_M: f32 = 1e-3;

/// What rests on the floor.
#[derive(Clone, Copy, Debug)]
pub enum Pile {
    /// One ball.
    Ball,
    /// A stack of this many unit boxes.
    Stack(usize),
    /// A ball on a unit box.
    BallOnBox,
}

/// `pile` set down touching, everything of restitution 1.
pub fn resting(pile: Pile) -> Scene {
    let mut bodies = vec![bouncy_floor(1.0)];
    let cube = |y: f32, i: usize| {
        body(
            Shape::cuboid(Vec3::splat(0.5)),
            Pose::from_position(Vec3::new(0.0, y, 0.0)),
            1.0,
            i,
        )
    };
    let ball = |y: f32| {
        body(
            Shape::sphere(0.25),
            Pose::from_position(Vec3::new(0.0, y + 0.25, 0.0)),
            1.0,
            3,
        )
    };
    match pile {
        Pile::Ball => bodies.push(ball(0.0)),
        Pile::Stack(n) => bodies.extend((0..n).map(|i| cube(0.5 + i as f32, i))),
        Pile::BallOnBox => {
            bodies.push(cube(0.5, 0));
            bodies.push(ball(1.0));
        }
    }
    scene(format!("resting {pile:?}"), bodies)
}

/// Runs the pile; the error is the largest rise of any body above its start, m.
pub fn outcome(pile: Pile, knobs: Knobs) -> Outcome {
    let scene = resting(pile);
    let mut run = Timed::new(knobs.world(&scene));
    let start: Vec<f32> = (1..scene.bodies.len())
        .map(|i| run.world.body(BodyId(i as u32)).pose().position.y)
        .collect();
    let steps = (SECONDS / run.world.settings().dt).round() as usize;
    let mut rise = 0.0f32;
    for _ in 0..steps {
        run.step();
        for (i, y0) in start.iter().enumerate() {
            let y = run.world.body(BodyId(i as u32 + 1)).pose().position.y;
            rise = rise.max(y - y0);
        }
    }
    Outcome {
        error: rise,
        ms_per_step: run.median_ms(),
        detail: format!("largest rise {rise:.6} m"),
    }
}

/// A ball, stacks of 1, 3 and 10 boxes, and a ball on a box, all of restitution 1, at rest.
pub fn family() -> Family {
    let piles = [
        Pile::Ball,
        Pile::Stack(1),
        Pile::Stack(3),
        Pile::Stack(10),
        Pile::BallOnBox,
    ];
    Family::of(
        "bouncy at rest",
        "nothing rises (m, not relative)",
        Unit::Metres,
        MAX_RISE_M,
        piles,
        |pile| format!("{pile:?}"),
        outcome,
    )
}
