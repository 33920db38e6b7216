//! Newton's cradle: balls in a row, each hung from a beam by two strings in a V, so it swings only
//! in the plane of the row; the first ball raised and let go.

use glam::{Quat, Vec3};

use super::{joint, part, post, scene};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{JointKind, Settings};
use crate::scene::Scene;
use crate::scene::cases;

/// Radius of the balls, m.
const RADIUS: f32 = 0.2;
/// How far the first ball is raised from the vertical at the start, degrees: it strikes the row at
/// √(2·g·ℓ·(1 − cos θ)) ≈ 2.7 m/s.
pub const CRADLE_RAISE_DEG: f32 = 40.0;
/// Mass of a ball, kg (a steel ball of 20 cm radius would weigh 260 kg; the cradle's behaviour does
/// not depend on it).
const MASS_KG: f32 = 1.0;
/// Drop from the beam's strings to the balls' centres, m: the pendulum's length.
pub const CRADLE_DROP: f32 = 1.6;
/// Half the spread of each ball's two strings along the beam's width, m.
const SPREAD: f32 = 0.5;
/// Height of the balls' centres above the floor, m.
const BALL_HEIGHT: f32 = 0.6;
/// Coefficient of restitution of the balls (steel on steel is about 0.95): each blow passes on
/// (1 + e)/2 of its speed, so the clacks die down over a few swings and the balls then swing
/// together until the air stops them.
pub const CRADLE_RESTITUTION: f32 = 0.95;
/// Air drag, 1/s: v decays as e^(−c·t). Without it the balls, once their impacts have turned
/// plastic (slower than the 1 m/s restitution threshold), swing together for ever on their
/// frictionless strings.
const AIR_DRAG: f32 = 0.15;

/// A cradle of `count` balls touching in a row along x, each hung by two strings (ropes: slack when
/// pushed, never longer than at the start) from a beam above to its centre, the first raised
/// [`CRADLE_RAISE_DEG`] about its strings' line. Body order: floor, beam, its two posts, the balls
/// from the raised one.
pub fn cradle(count: usize) -> Scene {
    let r = RADIUS;
    let top = BALL_HEIGHT + CRADLE_DROP;
    let half_row = r * count as f32;
    // The posts stand clear of the end balls' swings (each out to CRADLE_DROP·sin θ and a bit more).
    let reach = half_row + CRADLE_DROP * CRADLE_RAISE_DEG.to_radians().sin() + r + 0.3;
    let mut bodies = vec![
        cases::floor(4.0),
        // The beam, its underside where the strings hang from.
        post(
            Shape::cuboid(Vec3::new(reach + 0.1, 0.05, SPREAD + 0.1)),
            Pose::from_position(Vec3::new(0.0, top + 0.05, 0.0)),
        ),
    ];
    for x in [-1.0, 1.0] {
        let h = 0.5 * (top + 0.1);
        bodies.push(post(
            Shape::cuboid(Vec3::new(0.05, h, 0.05)),
            Pose::from_position(Vec3::new(x * reach, h, 0.0)),
        ));
    }
    let first = bodies.len();
    let theta = CRADLE_RAISE_DEG.to_radians();
    let mut joints = Vec::new();
    for i in 0..count {
        let x = -half_row + r * (2 * i + 1) as f32;
        let hang = if i == 0 {
            // Turned about the strings' line (along z through the beam's point above it).
            Quat::from_rotation_z(-theta) * Vec3::new(0.0, -CRADLE_DROP, 0.0)
        } else {
            Vec3::new(0.0, -CRADLE_DROP, 0.0)
        };
        let centre = Vec3::new(x, top, 0.0) + hang;
        let mut ball = part(
            Shape::sphere(r),
            Pose::from_position(centre),
            MASS_KG,
            PALETTE[2],
        )
        .named(format!("ball {}", i + 1));
        ball.desc.restitution = CRADLE_RESTITUTION;
        ball.desc.friction = 0.0;
        bodies.push(ball);
        let b = first + i;
        for z in [-SPREAD, SPREAD] {
            let at_beam = Vec3::new(x, top, z);
            let length = at_beam.distance(centre);
            let rope = JointKind::Distance {
                length,
                min: 0.0,
                max: length,
                spring: None,
            };
            joints.push(joint(&bodies, rope, None, b, (at_beam, centre), Vec3::Y));
        }
    }
    let settings = Settings {
        linear_damping: AIR_DRAG,
        ..Settings::default()
    };
    scene("cradle", settings, bodies, joints)
}
