//! A light block between a wall and a heavy block sliding at it, elastic and frictionless, in zero
//! gravity (Galperin's billiard: with masses m and M = 100ⁿ·m the blocks collide ⌊π·10ⁿ⌋ times, the
//! digits of π; 31 times for 1:100). The light block is squeezed: it bounces between the wall and the heavy block ever
//! faster, many times within one step, until the heavy block turns and both leave. Whatever the
//! count, the speeds they leave with follow from the collisions in order, each an exchange by the
//! impact law, replayed here exactly (in f64); energy and the order of events are all there is.
//! Chains of impacts within a step, and a light body between heavy ones, are where an engine's
//! restitution (or its iteration count) gives way.

use glam::{Quat, Vec3};

use super::restitution::{body, scene};
use super::{Family, Outcome, Unit};
use crate::color::FLOOR_COLOR;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::testing::hard_case::{Knobs, Timed};

/// Speed of the heavy block towards the wall, m/s: fast enough that every collision of every member
/// is faster than the default restitution threshold (the slowest, 1:100, closes at 1.7 m/s), slow
/// enough that the light block stays under the speed cap (at most √(M/m)·10 = 100 m/s).
const SPEED: f32 = 10.0;
/// Simulated time of a run, s: long enough for both to leave.
const SECONDS: f32 = 6.0;
/// Allowed error of each block's final velocity, as a fraction of `SPEED`.
pub const TOLERANCE: f32 = 0.01;

/// The velocities (light, heavy) along x the blocks leave with, and how many collisions there were,
/// for masses `m` and `heavy`: the heavy block starting at −`SPEED` (towards the wall at the
/// light block's −x side), the light one at rest.
pub fn expected(m: f64, heavy: f64) -> (f64, f64, u32) {
    let (mut v, mut w) = (0.0f64, -f64::from(SPEED));
    let mut collisions = 0;
    loop {
        if w < v {
            // The heavy block catches the light one: an elastic exchange.
            let sum = m + heavy;
            (v, w) = (
                ((m - heavy) * v + 2.0 * heavy * w) / sum,
                ((heavy - m) * w + 2.0 * m * v) / sum,
            );
        } else if v < 0.0 {
            v = -v;
        } else {
            return (v, w, collisions);
        }
        collisions += 1;
    }
}

/// Runs it for a heavy block `ratio` times the light one; the error is the larger distance of the
/// two blocks' final velocities from [`expected`], over `SPEED`.
pub fn outcome(ratio: f32, knobs: Knobs) -> Outcome {
    let unit = Shape::cuboid(Vec3::splat(0.5));
    let wall = SceneBody::new(
        BodyDesc::fixed(
            Shape::cuboid(Vec3::new(0.5, 3.0, 3.0)),
            Pose::from_position(Vec3::new(-0.5, 0.0, 0.0)),
        ),
        FLOOR_COLOR,
    );
    let light = body(
        unit,
        Pose::new(Vec3::new(1.5, 0.0, 0.0), Quat::IDENTITY),
        1.0,
        1,
    );
    let mut heavy = body(unit, Pose::from_position(Vec3::new(3.5, 0.0, 0.0)), 1.0, 2);
    heavy.desc.mass *= ratio;
    heavy.desc.linear_velocity = Vec3::X * -SPEED;
    let mut wall = wall;
    (wall.desc.restitution, wall.desc.friction) = (1.0, 0.0);
    let mut scene = scene(format!("wall squeeze 1:{ratio}"), vec![wall, light, heavy]);
    scene.settings.gravity = Vec3::ZERO;
    let (m, big) = (scene.bodies[1].desc.mass, scene.bodies[2].desc.mass);
    let (v_want, w_want, collisions) = expected(f64::from(m), f64::from(big));
    let mut run = Timed::new(knobs.world(&scene));
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        run.step();
    }
    let (v, w) = (
        run.world.body(BodyId(1)).linear_velocity(),
        run.world.body(BodyId(2)).linear_velocity(),
    );
    let error = (v - Vec3::X * v_want as f32)
        .length()
        .max((w - Vec3::X * w_want as f32).length())
        / SPEED;
    Outcome {
        error,
        ms_per_step: run.median_ms(),
        detail: format!(
            "light leaves at {v:.4}, heavy at {w:.4} m/s; expected {v_want:.4} and {w_want:.4} \
             along x after {collisions} collisions"
        ),
    }
}

/// Mass ratios 1, 4, 16 and 100 (3, 6, 12 and 31 collisions). (1:10 000, 314 collisions, would need
/// the heavy block slower than the restitution threshold allows, or the light one faster than the
/// speed cap.)
pub fn family() -> Family {
    Family::of(
        "wall squeeze",
        "a light block between a wall and a heavy one: the speeds the collisions in order leave (1 %)",
        Unit::Relative,
        TOLERANCE,
        [1.0, 4.0, 16.0, 100.0],
        |ratio| format!("1:{ratio}"),
        outcome,
    )
}
