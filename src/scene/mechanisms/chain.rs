//! A chain hanging from a hook: thirty links, each hinged to the next about the axis across the
//! one before (as a chain's links turn on each other), its free end just above the floor, to grab
//! and swing.

use std::f32::consts::FRAC_PI_2;

use glam::{Quat, Vec3};

use super::{joint, part, post, rubbing_hinge, scene};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::cases;

/// Links in the chain.
pub const CHAIN_LINKS: usize = 30;
/// From one link's joint to the next, m.
pub const CHAIN_LINK_PITCH: f32 = 0.15;
/// A link's half-size across the chain, m: a flat bar whose ends are its joints, each turned a
/// quarter turn about the chain from the one before, as a chain's links lie.
const LINK_HALF: Vec3 = Vec3::new(0.045, 0.5 * CHAIN_LINK_PITCH, 0.02);
/// Mass of a link, kg.
const LINK_KG: f32 = 0.3;
/// Friction torque of each hinge, N·m: a swung chain comes to rest within seconds of being let go
/// (the wrecking ball's links rub with 0.2 N·m under 0.5 kg links 0.3 m long).
const LINK_FRICTION: f32 = 0.1;
/// Air drag, 1/s: v decays as e^(−c·t). The links' friction damps the chain's bending but not its
/// swing as a whole, a pendulum rubbing at one hook only.
const AIR_DRAG: f32 = 0.3;
/// Clearance of the chain's free end above the floor, m.
const CLEARANCE: f32 = 0.3;

/// [`CHAIN_LINKS`] links hanging in a straight line from a hook (the world) under a beam, the
/// hinges' axes alternating between x and z. Body order: floor, beam, links from the top.
pub fn chain() -> Scene {
    let hook = Vec3::new(0.0, CLEARANCE + CHAIN_LINK_PITCH * CHAIN_LINKS as f32, 0.0);
    let mut bodies = vec![
        cases::floor(3.0),
        post(
            Shape::cuboid(Vec3::new(0.8, 0.1, 0.1)),
            Pose::from_position(hook + Vec3::Y * 0.1),
        ),
    ];
    let first = bodies.len();
    for i in 0..CHAIN_LINKS {
        let centre = hook - Vec3::Y * (CHAIN_LINK_PITCH * (i as f32 + 0.5));
        let turn = Quat::from_rotation_y(if i % 2 == 0 { 0.0 } else { FRAC_PI_2 });
        bodies.push(
            part(
                Shape::cuboid(LINK_HALF),
                Pose::new(centre, turn),
                LINK_KG,
                PALETTE[i % 2 * 4],
            )
            .named(format!("link {}", i + 1)),
        );
    }
    let joints = (0..CHAIN_LINKS)
        .map(|i| {
            let a = (i > 0).then(|| first + i - 1);
            let at = hook - Vec3::Y * (CHAIN_LINK_PITCH * i as f32);
            // Alternating, so the chain bends every way, two links at a time.
            let axis = if i % 2 == 0 { Vec3::Z } else { Vec3::X };
            let hinge = rubbing_hinge(LINK_FRICTION, None);
            joint(&bodies, hinge, a, first + i, (at, at), axis)
        })
        .collect();
    let settings = Settings {
        linear_damping: AIR_DRAG,
        ..Settings::default()
    };
    scene("chain", settings, bodies, joints)
}
