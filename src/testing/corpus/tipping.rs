//! A box standing on a ramp rough enough that it cannot slide (μ > tan θ): it stands while the
//! vertical through its centre of mass falls inside its downhill edge, tan θ < w/h (w its width along
//! the slope, h its height), and tips over beyond. A contact that acts only at the points it found,
//! or a soft contact that lets the downhill edge sink, moves that threshold: the box tips early, or
//! creeps down the slope while it stands.

use glam::{Quat, Vec3};

use super::restitution::scene;
use super::{Family, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::SceneBody;
use crate::scene::cases::{RAMP_CENTER, RAMP_HALF, ramp_downhill_at, ramp_slab};
use crate::testing::hard_case::{Knobs, Timed};

/// Friction of the box and the ramp: more than tan θ of every member, so nothing slides.
const MU: f32 = 1.2;
/// Simulated time of a run, s.
const SECONDS: f32 = 3.0;
/// How far a box may turn and still be standing, rad; one that tips has turned past 45°.
pub(super) const TIPPED_RAD: f32 = 0.3;
/// The boxes (full width along the slope or push, height), m: aspect h/w 1, 2 and 3.
pub(super) const BOXES: [(f32, f32); 3] = [(1.0, 1.0), (0.5, 1.0), (0.4, 1.2)];
/// How far a standing box may move down the slope, m (the error is in metres).
pub const MAX_CREEP_M: f32 = 0.005;
/// Degrees on either side of the tipping angle the members stand at (rounded to whole degrees).
const MARGIN_DEG: f32 = 1.0;

/// One box on the ramp: full width along the slope and height along the ramp's normal, m, and the
/// ramp's angle, degrees.
#[derive(Clone, Copy, Debug)]
pub struct Tipping {
    pub width: f32,
    pub height: f32,
    pub angle_deg: f32,
}

impl Tipping {
    /// Whether it should tip: tan θ > w/h.
    pub fn tips(&self) -> bool {
        self.angle_deg.to_radians().tan() > self.width / self.height
    }
}

/// Runs the box on the ramp for `SECONDS`. The error, in metres: for a box that should stand, how
/// far it moved down the slope (or 1 m if it tipped); for one that should tip, 0 if it turned past
/// `TIPPED_RAD`, else 1 m.
pub fn outcome(case: Tipping, knobs: Knobs) -> Outcome {
    let theta = case.angle_deg.to_radians();
    let tilt = Quat::from_rotation_z(theta);
    let normal = tilt * Vec3::Y;
    let half = Vec3::new(0.5 * case.width, 0.5 * case.height, 0.5);
    let centre = RAMP_CENTER + normal * (RAMP_HALF.y + half.y);
    let shape = Shape::cuboid(half);
    let mut desc = BodyDesc::dynamic(shape, Pose::new(centre, tilt), shape.volume());
    desc.friction = MU;
    let block = SceneBody::new(desc, PALETTE[1]);
    let scene = scene(
        format!("tipping {case:?}"),
        vec![ramp_slab(theta, MU), block],
    );
    let mut run = Timed::new(knobs.world(&scene));
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        run.step();
    }
    let pose = run.world.body(BodyId(1)).pose();
    let turned = pose.rotation.angle_between(tilt);
    let crept = (pose.position - centre).dot(ramp_downhill_at(theta));
    Outcome {
        error: tip_error(case.tips(), turned, crept),
        ms_per_step: run.median_ms(),
        detail: format!(
            "turned {turned:.3} rad, moved {crept:.4} m down the slope; should {}",
            if case.tips() { "tip" } else { "stand" }
        ),
    }
}

/// The error of a box that should tip (`tips`) or stand, having turned `turned` rad and moved
/// `moved` m, in metres: 0 if it tipped as it should, how far it moved if it stood as it should,
/// else 1 m.
pub(super) fn tip_error(tips: bool, turned: f32, moved: f32) -> f32 {
    match (tips, turned > TIPPED_RAD) {
        (false, false) => moved.abs(),
        (true, true) => 0.0,
        _ => 1.0,
    }
}

/// A member's label: the box, the load (`at`, e.g. "30°"), and what it should do.
pub(super) fn label(width: f32, height: f32, at: &str, tips: bool) -> String {
    let should = if tips { "tips" } else { "stands" };
    format!("{width}×{height} at {at} {should}")
}

/// Boxes of aspect h/w 1, 2 and 3, each about 1° below and 1° above its tipping angle atan(w/h).
pub fn family() -> Family {
    let cases = BOXES.into_iter().flat_map(|(width, height)| {
        let critical = (width / height).atan().to_degrees();
        [-MARGIN_DEG, MARGIN_DEG].map(|off| Tipping {
            width,
            height,
            angle_deg: (critical + off).round(),
        })
    });
    Family::of(
        "tip or stand",
        "stands on a ramp while tan θ < w/h (without creeping), tips beyond",
        Unit::Metres,
        MAX_CREEP_M,
        cases,
        |case| {
            label(
                case.width,
                case.height,
                &format!("{}°", case.angle_deg),
                case.tips(),
            )
        },
        outcome,
    )
}
