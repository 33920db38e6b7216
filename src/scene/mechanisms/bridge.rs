//! A rope bridge: planks hinged end to end across a gap between two towers, sagging under their
//! own weight, and boxes dropped onto it.

use glam::{Quat, Vec3};

use super::{joint, part, post, rubbing_hinge, scene};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::cases;

/// Planks in the bridge.
pub const BRIDGE_PLANKS: usize = 12;
/// A plank's length along the bridge, hinge to hinge, m.
const PLANK: f32 = 0.45;
/// A plank's thickness and width, m.
const PLANK_THICKNESS: f32 = 0.06;
const PLANK_WIDTH: f32 = 1.2;
/// Mass of a plank, kg.
const PLANK_KG: f32 = 2.0;
/// Gap between the towers' anchors, m: the planks' length 5.4 m hangs across 5 m.
const SPAN: f32 = 5.0;
/// Height of the anchors, m.
const ANCHOR_HEIGHT: f32 = 2.0;
/// Friction torque of each hinge, N·m: the bridge stops swaying soon after the boxes land.
const HINGE_FRICTION: f32 = 0.3;

/// The points `count` segments of length `pitch` pass through when they hang as a circular arc from
/// (−span/2, 0) to (span/2, 0) sagging downwards, in x and y: ends included. The arc's radius R
/// solves count·2·asin(pitch / 2R) = 2·asin(span / 2R) by bisection (count·pitch > span).
fn arc(count: usize, pitch: f32, span: f32) -> Vec<Vec3> {
    let half_angle = |r: f32| count as f32 * (pitch / (2.0 * r)).asin();
    // The chord the segments span on a circle of radius r.
    let chord = |r: f32| 2.0 * r * half_angle(r).min(std::f32::consts::PI).sin();
    let (mut lo, mut hi) = (0.5 * span, 1e4 * span);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        // A larger radius is a flatter arc, spanning more.
        if chord(mid) < span {
            lo = mid
        } else {
            hi = mid
        }
    }
    let r = 0.5 * (lo + hi);
    let step = 2.0 * (pitch / (2.0 * r)).asin();
    let start = -half_angle(r);
    let centre_y = (r * r - 0.25 * span * span).sqrt();
    (0..=count)
        .map(|i| {
            let a = start + step * i as f32;
            Vec3::new(r * a.sin(), centre_y - r * a.cos(), 0.0)
        })
        .collect()
}

/// [`BRIDGE_PLANKS`] planks hung end to end between two towers, each hinged about z (across the
/// bridge) to the next and the end ones to the towers, sagging in an arc; three boxes over the
/// middle, dropped onto it. Body order: floor, the towers, the planks from the left, the boxes.
pub fn bridge() -> Scene {
    let mut bodies = vec![cases::floor(5.0)];
    let tower = Vec3::new(0.3, 0.5 * ANCHOR_HEIGHT, 0.7);
    for x in [-1.0, 1.0] {
        bodies.push(post(
            Shape::cuboid(tower),
            Pose::from_position(Vec3::new(x * (0.5 * SPAN + tower.x), tower.y, 0.0)),
        ));
    }
    let lift = Vec3::Y * ANCHOR_HEIGHT;
    let hinges: Vec<Vec3> = arc(BRIDGE_PLANKS, PLANK, SPAN)
        .into_iter()
        .map(|p| p + lift)
        .collect();
    let first = bodies.len();
    for (i, ends) in hinges.windows(2).enumerate() {
        let along = ends[1] - ends[0];
        let tilt = Quat::from_rotation_z(along.y.atan2(along.x));
        bodies.push(
            part(
                Shape::cuboid(Vec3::new(
                    0.5 * PLANK,
                    0.5 * PLANK_THICKNESS,
                    0.5 * PLANK_WIDTH,
                )),
                Pose::new(0.5 * (ends[0] + ends[1]), tilt),
                PLANK_KG,
                PALETTE[i % 2],
            )
            .named(format!("plank {}", i + 1)),
        );
    }
    let hinge = rubbing_hinge(HINGE_FRICTION, None);
    // The end planks hang from the towers themselves, not from the world: joined, they do not
    // collide, and a plank's end turning about the hinge at a tower's top corner does not dig into
    // it (hung from the world, it sat 6 mm into the tower and its hinge stood 7 mm open, the
    // contact and the hinge fighting for good).
    let (left_tower, right_tower) = (1, 2);
    let joints = hinges
        .iter()
        .enumerate()
        .map(|(i, &at)| {
            let a = if i == 0 { left_tower } else { first + i - 1 };
            if i == BRIDGE_PLANKS {
                joint(&bodies, hinge, Some(right_tower), a, (at, at), Vec3::Z)
            } else {
                joint(&bodies, hinge, Some(a), first + i, (at, at), Vec3::Z)
            }
        })
        .collect();
    for (i, x) in [-1.2f32, 0.1, 1.0].into_iter().enumerate() {
        let size = 0.2 + 0.05 * i as f32;
        bodies.push(
            part(
                Shape::cuboid(Vec3::splat(size)),
                Pose::new(
                    Vec3::new(
                        x,
                        ANCHOR_HEIGHT + 1.0 + 0.4 * i as f32,
                        0.2 * i as f32 - 0.2,
                    ),
                    Quat::from_rotation_y(0.3 * i as f32),
                ),
                4.0,
                PALETTE[2 + i],
            )
            .named(format!("crate {}", i + 1)),
        );
    }
    scene("bridge", Settings::default(), bodies, joints)
}
