//! A simple pendulum beside a double pendulum, released from the same angle: one swings to and fro
//! as a clock's does, the other tumbles chaotically.

use glam::{Quat, Vec3};

use super::{joint, part, post, rubbing_hinge, scene};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::cases;

/// Length of each arm, pivot to bob, m.
const ARM: f32 = 1.2;
/// Radius of a bob, m.
const BOB: f32 = 0.15;
/// Mass of a bob, kg.
const BOB_KG: f32 = 1.0;
/// Release angle from the vertical, degrees.
const RELEASE_DEG: f32 = 110.0;
/// Height of the pivots above the floor, m: the double pendulum hangs 2·ARM + BOB below them.
const PIVOT_HEIGHT: f32 = 2.9;
/// Friction torque of each pivot, N·m: the swings die down over some twenty seconds.
const PIVOT_FRICTION: f32 = 0.6;
/// Air drag, 1/s: v decays as e^(−c·t).
const AIR_DRAG: f32 = 0.2;
/// The two pendulums' pivots, x, m.
const PIVOT_X: [f32; 2] = [-1.6, 1.4];

/// A simple pendulum (at −x, the right of the picture: the camera looks along +z) and a double
/// pendulum (at +x), each arm `ARM` long with a 1 kg bob
/// at its end, hinged about z to a beam behind them (the beam stands back so a bob swinging over
/// its pivot passes in front of it), both released `RELEASE_DEG` from the vertical. Body order:
/// floor, beam, its two posts, the simple pendulum's bob, the double pendulum's upper and lower bob.
pub fn pendulums() -> Scene {
    let beam_z = BOB + 0.15;
    let mut bodies = vec![
        cases::floor(5.0),
        post(
            Shape::cuboid(Vec3::new(2.9, 0.08, 0.1)),
            Pose::from_position(Vec3::new(-0.1, PIVOT_HEIGHT, beam_z)),
        ),
    ];
    for x in [-2.9, 2.7] {
        let h = 0.5 * PIVOT_HEIGHT;
        bodies.push(post(
            Shape::cuboid(Vec3::new(0.08, h, 0.08)),
            Pose::from_position(Vec3::new(x, h, beam_z)),
        ));
    }
    let theta = RELEASE_DEG.to_radians();
    let arm = Quat::from_rotation_z(-theta) * Vec3::new(0.0, -ARM, 0.0);
    let bob = |centre: Vec3, color| {
        part(
            Shape::sphere(BOB),
            Pose::from_position(centre),
            BOB_KG,
            color,
        )
    };
    let hinge = rubbing_hinge(PIVOT_FRICTION, None);
    let mut joints = Vec::new();

    let pivot = Vec3::new(PIVOT_X[0], PIVOT_HEIGHT, 0.0);
    bodies.push(bob(pivot + arm, PALETTE[1]).named("bob"));
    let simple = bodies.len() - 1;
    joints.push(joint(&bodies, hinge, None, simple, (pivot, pivot), Vec3::Z));

    let pivot = Vec3::new(PIVOT_X[1], PIVOT_HEIGHT, 0.0);
    bodies.push(bob(pivot + arm, PALETTE[2]).named("upper bob"));
    bodies.push(bob(pivot + 2.0 * arm, PALETTE[4]).named("lower bob"));
    let upper = bodies.len() - 2;
    joints.push(joint(&bodies, hinge, None, upper, (pivot, pivot), Vec3::Z));
    let elbow = pivot + arm;
    joints.push(joint(
        &bodies,
        hinge,
        Some(upper),
        upper + 1,
        (elbow, elbow),
        Vec3::Z,
    ));
    let settings = Settings {
        linear_damping: AIR_DRAG,
        ..Settings::default()
    };
    scene("pendulum", settings, bodies, joints)
}
