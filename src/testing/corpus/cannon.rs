//! Galileo's cannon: a light box resting on a heavy one, the pair dropped together on a floor, all
//! elastic. The heavy box meets the floor first and turns; then it meets the light one, still
//! falling, at twice the fall speed v = √(2·g·H). In that order the light box leaves at
//!
//!   v' = (3·M − m)/(M + m)·v,
//!
//! rising (v'/v)² times the drop: 7 times for M = 10·m, H for equal boxes (the heavy one stops
//! dead). With both impacts taken at once, or the pair's contact counted as a support, it rises only
//! H, as one body.

use glam::Vec3;

use super::restitution::{body, bouncy_floor, scene};
use super::{Family, Outcome, Unit};
use crate::geometry::{Pose, Shape};
use crate::physics::BodyId;
use crate::testing::hard_case::{Knobs, Timed};

/// Half-extent of both boxes, m.
const HALF: f32 = 0.25;
/// Allowed error of the light box's rise, relative.
pub const TOLERANCE: f32 = 0.01;

/// One drop: the heavy box's mass over the light one's, and the height the pair falls, m.
#[derive(Clone, Copy, Debug)]
pub struct Cannon {
    pub ratio: f32,
    pub drop_m: f32,
}

impl Cannon {
    /// How high the light box rises above where it rests on the heavy one, m.
    pub fn rise(&self) -> f32 {
        let factor = (3.0 * self.ratio - 1.0) / (self.ratio + 1.0);
        factor * factor * self.drop_m
    }
}

/// Drops the pair; the error is the light box's highest rise above its resting height, against
/// [`Cannon::rise`], relative.
pub fn outcome(cannon: Cannon, knobs: Knobs) -> Outcome {
    let cube = Shape::cuboid(Vec3::splat(HALF));
    let bottom_y = HALF + cannon.drop_m;
    let mut heavy = body(cube, Pose::from_position(Vec3::Y * bottom_y), 1.0, 2);
    heavy.desc.mass *= cannon.ratio;
    let light = body(
        cube,
        Pose::from_position(Vec3::Y * (bottom_y + 2.0 * HALF)),
        1.0,
        3,
    );
    let scene = scene(
        format!("cannon {cannon:?}"),
        vec![bouncy_floor(1.0), heavy, light],
    );
    let g = -scene.settings.gravity.y;
    let expected = cannon.rise();
    let resting = 3.0 * HALF;
    let fall_s = (2.0 * cannon.drop_m / g).sqrt();
    let rise_s = (2.0 * expected / g).sqrt();
    let mut run = Timed::new(knobs.world(&scene));
    let mut highest = f32::NEG_INFINITY;
    for _ in 0..((fall_s + rise_s + 0.2) / run.world.settings().dt).round() as usize {
        run.step();
        let y = run.world.body(BodyId(2)).pose().position.y;
        highest = if y.is_nan() { f32::NAN } else { highest.max(y) };
    }
    let rose = highest - resting;
    Outcome {
        error: (rose - expected).abs() / expected,
        ms_per_step: run.median_ms(),
        detail: format!("the light box rose {rose:.4} m, expected {expected:.4} m"),
    }
}

/// Mass ratios 1, 3 and 10, dropped 0.5 and 2 m.
pub fn family() -> Family {
    let cannons = [1.0, 3.0, 10.0]
        .into_iter()
        .flat_map(|ratio| [0.5, 2.0].map(|drop_m| Cannon { ratio, drop_m }));
    Family::of(
        "galileo's cannon",
        "a light box dropped on a heavy one rises ((3M − m)/(M + m))²·H (1 %)",
        Unit::Relative,
        TOLERANCE,
        cannons,
        |cannon| format!("M/m={} H={}m", cannon.ratio, cannon.drop_m),
        outcome,
    )
}
