//! Built-in scenes of bodies held by joints: pendulums, Newton's cradle, a hanging chain, a rope
//! bridge and a door. Each is built so that it shows one mechanism at work and, like every built-in
//! scene, comes to rest within seconds: where nothing else would stop it, its joints rub (a hinge
//! motor held at zero speed with a small torque is friction) or the air drags it.

mod bridge;
mod chain;
mod cradle;
mod door;
mod pendulum;
mod wrecking;

pub use bridge::{BRIDGE_PLANKS, bridge};
pub use chain::{CHAIN_LINK_PITCH, CHAIN_LINKS, chain};
pub use cradle::{CRADLE_DROP, CRADLE_RAISE_DEG, CRADLE_RESTITUTION, cradle};
pub use door::{DOOR_LIMIT_DEG, door};
pub use pendulum::pendulums;
pub use wrecking::{CHAIN_LINK_FRICTION, wrecking_ball};

use glam::Vec3;

use super::framing::{self, DEFAULT_FOV_DEG, Framed, Framing};
use super::{Scene, SceneBody};
use crate::color::{FLOOR_COLOR, Rgb};
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId, JointDesc, JointKind, Motor, Settings};

/// A dynamic body of the given mass and colour.
fn part(shape: Shape, pose: Pose, mass_kg: f32, color: Rgb) -> SceneBody {
    SceneBody::new(BodyDesc::dynamic(shape, pose, mass_kg), color)
}

/// A static body (floor colour): a post, a beam, a frame.
fn post(shape: Shape, pose: Pose) -> SceneBody {
    SceneBody::new(BodyDesc::fixed(shape, pose), FLOOR_COLOR)
}

/// A hinge that rubs: a motor held at zero speed with at most `friction` N·m, as a real pivot's
/// friction holds back a swing (none at all: it would swing for ever and never sleep).
fn rubbing_hinge(friction: f32, limits: Option<[f32; 2]>) -> JointKind {
    JointKind::Hinge {
        limits,
        motor: Some(Motor {
            speed: 0.0,
            max: friction,
        }),
    }
}

/// A joint from world coordinates in the bodies' poses as `bodies` has them now; `a` is `None` for
/// the world.
fn joint(
    bodies: &[SceneBody],
    kind: JointKind,
    a: Option<usize>,
    b: usize,
    anchors: (Vec3, Vec3),
    axis: Vec3,
) -> JointDesc {
    let end = |i: usize| (BodyId(i as u32), bodies[i].desc.pose);
    JointDesc::at(kind, a.map(end), end(b), anchors.0, anchors.1, axis, false)
}

/// A scene of `bodies` (the floor first) and `joints` whose camera frames every body a joint holds
/// where it hangs (the others where they would land) and the whole of every static body but the
/// floor: the beam a pendulum hangs from, the posts a bridge is slung between are part of the
/// mechanism, not ground the picture may cut off.
fn scene(name: &str, settings: Settings, bodies: Vec<SceneBody>, joints: Vec<JointDesc>) -> Scene {
    let mut held = vec![false; bodies.len()];
    for j in &joints {
        for id in j.a.into_iter().chain([j.b]) {
            held[id.index()] = true;
        }
    }
    let mut framing = Framing::of_held(&bodies, &held);
    framing.bodies.extend(
        bodies[1..]
            .iter()
            .filter(|b| b.desc.is_static)
            .map(|b| Framed {
                shape: b.desc.shape,
                pose: b.desc.pose,
            }),
    );
    Scene {
        name: name.into(),
        settings,
        camera: framing::framing_camera(&framing, DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints,
    }
}
