//! Coincident bodies: N unit boxes spawned at one point half a metre above a floor must come apart
//! gently, however many there are. A push-out speed limit that holds per contact lets N bodies fly
//! apart at about N times it; one that holds per body keeps the crowd at its limit. The answer is
//! the three limits: no body ever faster than 5 m/s (by its velocity or by how far it moved
//! in a step), none ending more than 10 m from the spawn point, and no overlap left over 1 cm after
//! 5 s.

use glam::{Quat, Vec3};

use super::restitution::scene;
use super::{Family, Member, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::BodyDesc;
use crate::scene::SceneBody;
use crate::scene::cases::{floor, unit_box};
use crate::testing::hard_case::{Knobs, Timed};
use crate::testing::penetration::max_penetration;

/// Bodies in the crowds.
pub const COUNTS: [usize; 7] = [2, 3, 5, 10, 20, 35, 50];
/// Where every body is spawned: half a metre above resting on the floor.
const SPAWN: Vec3 = Vec3::new(0.0, 1.0, 0.0);
/// Simulated time the crowd gets to come apart, s.
const SETTLE_S: f32 = 5.0;
/// No body may move faster, m/s.
pub const MAX_SPEED_MPS: f32 = 5.0;
/// No body may end farther from the spawn point, m.
pub const MAX_DISTANCE_M: f32 = 10.0;
/// Deepest overlap left after `SETTLE_S`, m.
pub const MAX_OVERLAP_M: f32 = 0.01;

/// Runs `count` coincident unit boxes (each turned about y by `turn` radians more than the one
/// before); the error is the largest fraction of its limit any of the three measures reached (1 is
/// at a limit; NaN counts as infinite).
pub fn outcome(count: usize, turn: f32, knobs: Knobs) -> Outcome {
    let mut bodies = vec![floor(40.0)];
    for i in 0..count {
        let pose = Pose::new(SPAWN, Quat::from_rotation_y(turn * i as f32));
        bodies.push(SceneBody::new(
            BodyDesc::dynamic(unit_box(), pose, Shape::volume(&unit_box())),
            PALETTE[i % PALETTE.len()],
        ));
    }
    let mut run = Timed::new(knobs.world(&scene(format!("{count} coincident"), bodies)));
    let dt = run.world.settings().dt;
    let nan_is_inf = |x: f32| if x.is_nan() { f32::INFINITY } else { x };
    let mut previous: Vec<Vec3> = run
        .world
        .bodies()
        .iter()
        .map(|b| b.pose().position)
        .collect();
    let mut speed = 0.0f32;
    for _ in 0..(SETTLE_S / dt).round() as usize {
        run.step();
        for (body, before) in run.world.bodies().iter().zip(&mut previous) {
            let now = body.pose().position;
            let by_velocity = body.linear_velocity().length();
            speed = speed.max(nan_is_inf(by_velocity.max((now - *before).length() / dt)));
            *before = now;
        }
    }
    let distance = run.world.bodies()[1..]
        .iter()
        .map(|b| nan_is_inf((b.pose().position - SPAWN).length()))
        .fold(0.0, f32::max);
    let overlap = nan_is_inf(max_penetration(&run.world, true).0);
    let error = (speed / MAX_SPEED_MPS)
        .max(distance / MAX_DISTANCE_M)
        .max(overlap / MAX_OVERLAP_M);
    Outcome {
        error,
        ms_per_step: run.median_ms(),
        detail: format!(
            "fastest {speed:.3} m/s, farthest {distance:.3} m, overlap {overlap:.5} m at the end"
        ),
    }
}

/// Turn about y between one box of a turned crowd and the next, radians.
pub const TURN: f32 = 0.37;
/// Turned crowds tried, boxes.
pub const TURNED_COUNTS: [usize; 3] = [5, 20, 50];

/// Crowds of [`COUNTS`] boxes all aligned (the case), and of [`TURNED_COUNTS`] each turned
/// [`TURN`] about y from the one before (faces that disagree: pairs meet edge to face).
pub fn family() -> Family {
    let aligned = COUNTS.into_iter().map(|count| (count, 0.0));
    let turned = TURNED_COUNTS.into_iter().map(|count| (count, TURN));
    let members = aligned
        .chain(turned)
        .map(|(count, turn)| Member {
            label: format!("{count} {}boxes", if turn == 0.0 { "" } else { "turned " }),
            tolerance: 1.0,
            run: Box::new(move |knobs| outcome(count, turn, knobs)),
        })
        .collect();
    Family {
        name: "overlap",
        answer: "≤ 5 m/s, ≤ 10 m away, overlap < 1 cm after 5 s (error: fraction of the limit)",
        unit: Unit::Relative,
        members,
    }
}
