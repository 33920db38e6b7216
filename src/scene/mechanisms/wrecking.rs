//! A wrecking ball: a heavy ball on a chain of hinged links, swung into a wall of boxes.

use glam::Vec3;

use super::{joint, part, rubbing_hinge};
use crate::color::PALETTE;
use crate::geometry::{Camera, Pose, Shape};
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::builtin::BALL_ROLLING_RESISTANCE;
use crate::scene::cases;
use crate::scene::framing::DEFAULT_FOV_DEG;

/// Friction torque of each link of [`wrecking_ball`]'s chain, N·m: a real chain's links rub where
/// they turn on each other. Frictionless, a slack chain never stops moving and the scene never
/// sleeps; with this much it comes to rest within seconds of the blow and still swings freely.
pub const CHAIN_LINK_FRICTION: f32 = 0.2;

/// A wrecking ball: a 50 kg ball (100 times a link) on a chain of 20 links hinged about
/// alternate axes (as a chain's links turn on each other), released 50° from the vertical, swings
/// into a wall of 36 boxes (6 wide, 6 high). The chain is hung so the ball rolls along the floor
/// through the bottom of its swing. Body order: floor, wall, links from the top, ball.
pub fn wrecking_ball() -> Scene {
    let mut bodies = vec![cases::floor(20.0)];
    let brick = 0.25;
    for row in 0..6 {
        for col in 0..6 {
            bodies.push(cases::dynamic(
                Shape::cuboid(Vec3::splat(brick)),
                Vec3::new(
                    1.45,
                    brick * (1.0 + 2.0 * row as f32),
                    brick * (2.0 * col as f32 - 5.0),
                ),
                PALETTE[(row + col) % PALETTE.len()],
            ));
        }
    }
    let angle = 50f32.to_radians();
    let down = Vec3::new(-angle.sin(), -angle.cos(), 0.0);
    let (links, link, radius) = (20, 0.3, 0.6);
    // 15 cm more chain than it takes the ball to reach the floor.
    let pivot = Vec3::new(0.0, link * links as f32 + 2.0 * radius - 0.15, 0.0);
    let first = bodies.len();
    for i in 0..links {
        bodies.push(
            part(
                Shape::sphere(0.12),
                Pose::from_position(pivot + down * (link * (i as f32 + 0.5))),
                0.5,
                PALETTE[2],
            )
            .named(format!("link {}", i + 1)),
        );
    }
    let mut ball = part(
        Shape::sphere(radius),
        Pose::from_position(pivot + down * (link * links as f32 + radius)),
        50.0,
        PALETTE[1],
    )
    .named("wrecking ball");
    ball.desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
    bodies.push(ball);
    let joints = (0..=links)
        .map(|i| {
            let b = first + i;
            let anchor = pivot + down * (link * i as f32);
            let axis = if i % 2 == 0 {
                Vec3::Z
            } else {
                down.cross(Vec3::Z)
            };
            let a = (i > 0).then(|| b - 1);
            let hinge = rubbing_hinge(CHAIN_LINK_FRICTION, None);
            joint(&bodies, hinge, a, b, (anchor, anchor), axis)
        })
        .collect();
    Scene {
        name: "wrecking".into(),
        settings: Settings::default(),
        // In front and to the ball's side: the swing and the wall's face in view.
        camera: Camera::perspective(
            Vec3::new(-7.5, 5.0, -8.0),
            Vec3::new(0.0, 3.0, 0.0),
            DEFAULT_FOV_DEG.to_radians(),
        ),
        bodies,
        joints,
    }
}
