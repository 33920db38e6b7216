//! A door in its frame, hinged on a vertical axis at one edge, that opens one way up to a stop.

use glam::Vec3;

use super::{joint, part, post, rubbing_hinge, scene};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::cases;

/// How far the door opens, degrees (away from the camera).
pub const DOOR_LIMIT_DEG: f32 = 100.0;
/// The door's half-size: width, height, thickness, m.
const HALF: Vec3 = Vec3::new(0.45, 1.0, 0.03);
/// Mass of the door, kg.
const DOOR_KG: f32 = 20.0;
/// Friction torque of the hinge, N·m: the door stops where a push leaves it (a click's swings it
/// to its stop) instead of swinging on for ever.
const HINGE_FRICTION: f32 = 3.0;
/// Gap under the door, m.
const GAP: f32 = 0.02;

/// A door (0.9 m × 2 m × 6 cm, 20 kg) closed in a frame of two posts and a lintel, hinged about a
/// vertical axis along its −x edge; it opens away from the camera, the hinge's limits (0 and
/// [`DOOR_LIMIT_DEG`]) keeping it from opening towards it and stopping it wide open. Body order:
/// floor, the hinge side's post, the other post, lintel, door.
pub fn door() -> Scene {
    let (w, h, t) = (HALF.x, HALF.y, HALF.z);
    let post_half = Vec3::new(0.08, h + 0.5 * GAP + 0.08, 0.08);
    let post_at = |x: f32| Pose::from_position(Vec3::new(x, post_half.y, 0.0));
    let mut bodies = vec![
        cases::floor(3.0),
        // The hinge side's post stands clear of the door's corner as it turns (2·t across).
        post(
            Shape::cuboid(post_half),
            post_at(-w - 0.08 - 2.0 * t - 0.02),
        ),
        post(Shape::cuboid(post_half), post_at(w + 0.09)),
        post(
            Shape::cuboid(Vec3::new(w + 0.2, 0.08, 0.08)),
            Pose::from_position(Vec3::new(-0.03, 2.0 * post_half.y + 0.08, 0.0)),
        ),
    ];
    bodies.push(
        part(
            Shape::cuboid(HALF),
            Pose::from_position(Vec3::new(0.0, GAP + h, 0.0)),
            DOOR_KG,
            PALETTE[0],
        )
        .named("door"),
    );
    let door = bodies.len() - 1;
    // The hinge's line: the door's left edge on its back face. A positive angle about −y swings
    // the free (+x) edge towards +z, away from the camera.
    let at = Vec3::new(-w, GAP + h, t);
    let limits = Some([0.0, DOOR_LIMIT_DEG.to_radians()]);
    let hinge = rubbing_hinge(HINGE_FRICTION, limits);
    let joints = vec![joint(&bodies, hinge, None, door, (at, at), -Vec3::Y)];
    scene("door", Settings::default(), bodies, joints)
}
