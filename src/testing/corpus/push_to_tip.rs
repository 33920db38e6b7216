//! A box pushed sideways at the top of its back face, on a floor rough enough that it cannot slide:
//! it tips over its front bottom edge once the push's moment about that edge beats the weight's,
//! F·h > m·g·w/2 (w its width along the push, h its height), and stands below. The floor's load
//! moves to the front edge as the push grows; a contact that spreads it over its corner points
//! wrongly, or lets the front edge sink, moves the threshold.

use glam::Vec3;

use super::restitution::scene;
use super::tipping::{BOXES, label, tip_error};
use super::{Family, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::scene::cases::floor;
use crate::testing::hard_case::{Knobs, Timed};

/// Friction of the box and the floor: more than the push over the weight of any member.
const MU: f32 = 1.2;
/// Simulated time the push lasts, s.
const SECONDS: f32 = 2.0;
/// How far a standing box's top may move, m (the error is in metres).
pub const MAX_CREEP_M: f32 = 0.005;
/// The pushes, as fractions of the tipping force.
const BELOW: f32 = 0.98;
const ABOVE: f32 = 1.02;

/// One push: the box's width along the push and height, m, and the push over the tipping force.
#[derive(Clone, Copy, Debug)]
pub struct Push {
    pub width: f32,
    pub height: f32,
    pub fraction: f32,
}

impl Push {
    /// Whether it should tip.
    pub fn tips(&self) -> bool {
        self.fraction > 1.0
    }
}

/// Pushes the box for `SECONDS`; the error, in metres (`tip_error`): for a box that should
/// stand, how far its top moved (or 1 m if it tipped); for one that should tip, 0 if it did, else
/// 1 m.
pub fn outcome(push: Push, knobs: Knobs) -> Outcome {
    let mut ground = floor(10.0);
    ground.desc.friction = MU;
    let half = Vec3::new(0.5 * push.width, 0.5 * push.height, 0.5);
    let shape = Shape::cuboid(half);
    let centre = Vec3::new(0.0, half.y, 0.0);
    let mut desc = BodyDesc::dynamic(shape, Pose::from_position(centre), shape.volume());
    desc.friction = MU;
    let scene = scene(
        format!("push to tip {push:?}"),
        vec![ground, SceneBody::new(desc, PALETTE[1])],
    );
    let g = -scene.settings.gravity.y;
    let force = push.fraction * shape.volume() * g * push.width / (2.0 * push.height);
    let mut run = Timed::new(knobs.world(&scene));
    let id = BodyId(1);
    // The top of the back face, in the box's frame: the push follows the box as it turns.
    let anchor = Vec3::new(-half.x, half.y, 0.0);
    let top = |run: &Timed| {
        run.world
            .body(id)
            .pose()
            .transform_point(Vec3::new(0.0, half.y, 0.0))
    };
    let top_start = top(&run);
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        let at = run.world.body(id).pose().transform_point(anchor);
        run.world.apply_force_at_point(id, Vec3::X * force, at);
        run.step();
    }
    let turned = run
        .world
        .body(id)
        .pose()
        .rotation
        .angle_between(glam::Quat::IDENTITY);
    let moved = (top(&run) - top_start).length();
    Outcome {
        error: tip_error(push.tips(), turned, moved),
        ms_per_step: run.median_ms(),
        detail: format!(
            "pushed with {force:.2} N: turned {turned:.3} rad, top moved {moved:.4} m; should {}",
            if push.tips() { "tip" } else { "stand" }
        ),
    }
}

/// Boxes of aspect h/w 1, 2 and 3, pushed with 0.98 and 1.02 times the force that tips them.
pub fn family() -> Family {
    let pushes = BOXES.into_iter().flat_map(|(width, height)| {
        [BELOW, ABOVE].map(|fraction| Push {
            width,
            height,
            fraction,
        })
    });
    Family::of(
        "push to tip",
        "a box pushed at its top stands while F·h < m·g·w/2 (without creeping), tips beyond",
        Unit::Metres,
        MAX_CREEP_M,
        pushes,
        |push| {
            label(
                push.width,
                push.height,
                &format!("{}×", push.fraction),
                push.tips(),
            )
        },
        outcome,
    )
}
