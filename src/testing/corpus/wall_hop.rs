//! A ball rolling along a floor into a wall hops. Rolling at v (ω = v/r), the point that meets the
//! wall slides down it at v, so the wall's friction through the impact pushes the ball up: at most
//! μ·(1 + e)·m·v, the bound of the impact's normal impulse, and no more than stops the slip, (2/7)·m·v
//! (the point then rolls up the wall). The ball leaves with
//!
//!   v_y = min(μ·(1 + e), 2/7)·v   and rises   h = v_y² / (2·g).
//!
//! An engine whose friction sees only the plastic part of the impact gives μ·v (half for e = 1);
//! one without friction in impacts, no hop at all.
//!
//! The hop is read as its apex between the steps' samples (`apex`), not as the highest sample: the
//! slippery elastic wall's hop (e = 1, μ = 0.05, 8.2 mm) peaks between two steps, and its highest
//! sample was 3.3 % low at every sub-step count, which read as an error of the engine's (it was
//! the bench's; the ball leaves the wall at μ·(1 + e)·v to 0.05 %).

use glam::Vec3;

use super::apex::apexes;
use super::restitution::{AIRBORNE_M, scene};
use super::{Family, Outcome, Unit};
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId};
use crate::scene::cases::floor;
use crate::scene::{Scene, SceneBody};
use crate::testing::hard_case::{Knobs, Timed};

/// Radius of the ball, m.
const RADIUS: f32 = 0.25;
/// Rolling speed towards the wall, m/s.
const SPEED: f32 = 4.0;
/// Simulated time: the impact after 0.5 s, the hop well within the rest, s.
const SECONDS: f32 = 1.5;
/// Allowed error of the hop's height, relative.
pub const TOLERANCE: f32 = 0.02;

/// One hop: restitution and friction of the ball and the wall.
#[derive(Clone, Copy, Debug)]
pub struct Hop {
    pub e: f32,
    pub mu: f32,
}

impl Hop {
    /// The upward speed the ball leaves the wall with, m/s.
    pub fn lift(&self) -> f32 {
        (self.mu * (1.0 + self.e)).min(2.0 / 7.0) * SPEED
    }
}

/// Rolls the ball into the wall; the error is the top of its first hop (its bottom above the floor,
/// the vertex of the step samples around it: see `apex`) against v_y²/(2·g), relative.
pub fn outcome(hop: Hop, knobs: Knobs) -> Outcome {
    let scene = scene_of(hop);
    let g = -scene.settings.gravity.y;
    let expected = hop.lift() * hop.lift() / (2.0 * g);
    let mut run = Timed::new(knobs.world(&scene));
    let mut heights = Vec::new();
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        run.step();
        heights.push(run.world.body(BodyId(2)).pose().position.y - RADIUS);
    }
    // The hop's top falls between two steps' samples: read where the parabola through them peaks.
    let top = apexes(&heights, 0.0, AIRBORNE_M)
        .first()
        .copied()
        .unwrap_or(0.0);
    let error = if heights.iter().any(|y| y.is_nan()) {
        f32::NAN
    } else {
        (top - expected).abs() / expected
    };
    Outcome {
        error,
        ms_per_step: run.median_ms(),
        detail: format!("hopped {top:.5} m, expected {expected:.5} m"),
    }
}

/// The floor, the wall (body 1) and the ball (body 2) rolling at it, for `hop`.
pub fn scene_of(hop: Hop) -> Scene {
    let mut ground = floor(10.0);
    // Floor friction is the ball's rolling: high enough to keep it rolling, not part of the hop.
    ground.desc.friction = 1.0;
    let mut wall = SceneBody::new(
        BodyDesc::fixed(
            Shape::cuboid(Vec3::new(0.5, 2.0, 3.0)),
            Pose::from_position(Vec3::new(2.5, 2.0, 0.0)),
        ),
        FLOOR_COLOR,
    );
    (wall.desc.restitution, wall.desc.friction) = (hop.e, hop.mu);
    let shape = Shape::sphere(RADIUS);
    let start = Vec3::new(2.0 - RADIUS - 0.5 * SPEED, RADIUS, 0.0);
    let mut desc = BodyDesc::dynamic(shape, Pose::from_position(start), shape.volume());
    desc.linear_velocity = Vec3::X * SPEED;
    desc.angular_velocity = Vec3::Z * (-SPEED / RADIUS);
    (desc.restitution, desc.friction) = (hop.e, hop.mu);
    let ball = SceneBody::new(desc, PALETTE[4]);
    scene(format!("wall hop {hop:?}"), vec![ground, wall, ball])
}

/// Walls of friction 0.05–0.5 and restitution 0.5 and 1: the point slides through the impact, or
/// stops sliding within it.
pub fn family() -> Family {
    let hops = [
        Hop { e: 1.0, mu: 0.05 },
        Hop { e: 0.5, mu: 0.05 },
        Hop { e: 1.0, mu: 0.1 },
        Hop { e: 0.5, mu: 0.5 },
        Hop { e: 1.0, mu: 0.5 },
    ];
    Family::of(
        "wall hop",
        "a ball rolling into a wall hops v_y²/(2g), v_y = min(μ(1 + e), 2/7)·v (2 %)",
        Unit::Relative,
        TOLERANCE,
        hops,
        |hop| format!("e={} μ={}", hop.e, hop.mu),
        outcome,
    )
}
