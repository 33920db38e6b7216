//! A ragdoll: eleven bodies and ten joints shaped like a person of 67 kg, and the scenes built of
//! it: the built-in `ragdoll` (one dropped on stairs) and the pile of ragdolls the joint
//! benchmarks time (`nudge bench mechanisms`, `rapier-bench --versus`).
//!
//! # The body
//! Standing at attention, facing +z, feet at y = 0 (right-handed, y up, metres, kg):
//!
//! ```text
//!            head (sphere)             neck: ball
//!        ┌────── chest ──────┐         shoulders: balls
//!   upper arm            upper arm     spine (chest on pelvis): hinge about x, −0.4…0.8 rad
//!   lower arm  pelvis    lower arm     elbows: hinges about x, −2.6…0 rad (forearms swing forward)
//!        upper leg   upper leg         hips: balls
//!        lower leg   lower leg         knees: hinges about x, 0…2.4 rad (shins swing back)
//! ```
//!
//! A hinge's angle is the child's turn about +x from the standing pose: positive swings a hanging
//! part's lower end back (−z), so elbows bend at negative angles and knees at positive ones. The
//! ball joints turn any way: the engine's ball joint has no limits. Every joint has a little
//! friction ([`JOINT_FRICTION_PER_KG`]). Jointed neighbours do not collide; every other pair of
//! parts does.
//!
//! # Postures
//! A [`Posture`] is each joint's turn of the child relative to its parent (a hinge's about its axis,
//! within its limits). The joints are always made in the standing pose, so a posture bends the
//! ragdoll without moving where its joints' zero angles are: parts are placed from the pelvis out,
//! each turned about its joint's anchor.

use glam::{Quat, Vec3};

use super::builtin::BALL_ROLLING_RESISTANCE;
use super::framing::DEFAULT_FOV_DEG;
use super::{Scene, SceneBody, cases};
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Camera, Pose, Shape};
use crate::physics::narrow::collide::collide;
use crate::physics::{BodyDesc, BodyId, JointDesc, JointKind, Settings};
use crate::util::SplitMix64;

/// Bodies in one ragdoll.
pub const PARTS: usize = 11;
/// Joints in one ragdoll (each part but the pelvis hangs from one).
pub const JOINTS: usize = PARTS - 1;

/// How a part hangs from its parent.
#[derive(Clone, Copy, Debug)]
enum Hang {
    /// A ball joint.
    Ball,
    /// A hinge about +x with limits (rad).
    Hinge([f32; 2]),
}

/// One part of the standing ragdoll.
#[derive(Clone, Copy, Debug)]
struct Part {
    shape: Shape,
    /// Centre in the standing pose, m.
    centre: Vec3,
    mass_kg: f32,
    /// The part it hangs from (an index into [`BODY`], always earlier), with the joint's anchor in
    /// the standing pose and its kind; `None` for the pelvis.
    parent: Option<(usize, Vec3, Hang)>,
}

/// Each joint's friction, N·m per kg of the part it holds: a part hanging 15 cm below its joint
/// rests anywhere within about 2° of straight down (its weight's torque there), so the ragdoll still
/// falls limp. Without it a limb that came to rest on an edge, or on a nearly upright hinge, swung
/// about its joint for good: 5 of 40 piles of four ragdolls never slept, and the built-in scene
/// lands a forearm on a stair edge where it swung for a minute
/// (`tests/physics/ragdoll.rs`, `loose_limbs_stop_swinging_only_with_joint_friction`).
pub const JOINT_FRICTION_PER_KG: f32 = 0.05;

const SPINE: Hang = Hang::Hinge([-0.4, 0.8]);
const ELBOW: Hang = Hang::Hinge([-2.6, 0.0]);
const KNEE: Hang = Hang::Hinge([0.0, 2.4]);

const fn cuboid(x: f32, y: f32, z: f32) -> Shape {
    Shape::Cuboid {
        half_extents: Vec3::new(x, y, z),
    }
}

/// The parts, parents first. A 1 cm gap between the arms and the chest keeps them from touching
/// while standing; the joints' anchors sit on the faces the parts share.
const BODY: [Part; PARTS] = {
    let v = Vec3::new;
    [
        // 0 pelvis
        Part {
            shape: cuboid(0.15, 0.10, 0.09),
            centre: v(0.0, 1.00, 0.0),
            mass_kg: 10.0,
            parent: None,
        },
        // 1 chest, on the pelvis
        Part {
            shape: cuboid(0.17, 0.16, 0.10),
            centre: v(0.0, 1.26, 0.0),
            mass_kg: 20.0,
            parent: Some((0, v(0.0, 1.10, 0.0), SPINE)),
        },
        // 2 head, on the chest
        Part {
            shape: Shape::Sphere { radius: 0.11 },
            centre: v(0.0, 1.55, 0.0),
            mass_kg: 5.0,
            parent: Some((1, v(0.0, 1.42, 0.0), Hang::Ball)),
        },
        // 3, 4 upper arms, from the chest's top corners
        Part {
            shape: cuboid(0.05, 0.14, 0.05),
            centre: v(0.23, 1.26, 0.0),
            mass_kg: 2.5,
            parent: Some((1, v(0.23, 1.40, 0.0), Hang::Ball)),
        },
        Part {
            shape: cuboid(0.05, 0.14, 0.05),
            centre: v(-0.23, 1.26, 0.0),
            mass_kg: 2.5,
            parent: Some((1, v(-0.23, 1.40, 0.0), Hang::Ball)),
        },
        // 5, 6 lower arms
        Part {
            shape: cuboid(0.045, 0.13, 0.045),
            centre: v(0.23, 0.99, 0.0),
            mass_kg: 1.5,
            parent: Some((3, v(0.23, 1.12, 0.0), ELBOW)),
        },
        Part {
            shape: cuboid(0.045, 0.13, 0.045),
            centre: v(-0.23, 0.99, 0.0),
            mass_kg: 1.5,
            parent: Some((4, v(-0.23, 1.12, 0.0), ELBOW)),
        },
        // 7, 8 upper legs, from the pelvis
        Part {
            shape: cuboid(0.07, 0.20, 0.07),
            centre: v(0.09, 0.70, 0.0),
            mass_kg: 8.0,
            parent: Some((0, v(0.09, 0.90, 0.0), Hang::Ball)),
        },
        Part {
            shape: cuboid(0.07, 0.20, 0.07),
            centre: v(-0.09, 0.70, 0.0),
            mass_kg: 8.0,
            parent: Some((0, v(-0.09, 0.90, 0.0), Hang::Ball)),
        },
        // 9, 10 lower legs
        Part {
            shape: cuboid(0.06, 0.20, 0.06),
            centre: v(0.09, 0.30, 0.0),
            mass_kg: 4.0,
            parent: Some((7, v(0.09, 0.50, 0.0), KNEE)),
        },
        Part {
            shape: cuboid(0.06, 0.20, 0.06),
            centre: v(-0.09, 0.30, 0.0),
            mass_kg: 4.0,
            parent: Some((8, v(-0.09, 0.50, 0.0), KNEE)),
        },
    ]
};

/// Each joint's turn of its child relative to its parent, in the parent's frame: joint k moves
/// part k + 1. [`STANDING`] is no turn at all.
pub type Posture = [Quat; JOINTS];

/// The standing pose.
pub const STANDING: Posture = [Quat::IDENTITY; JOINTS];

/// A random posture: each hinge at an angle uniform within its limits, each ball joint turned
/// about a random axis by up to `ball_max` radians; drawn again while two parts that no joint
/// joins overlap (a limb through the chest): the push-out would then tear at the joints.
pub fn random_posture(rng: &mut SplitMix64, ball_max: f32) -> Posture {
    loop {
        let posture: Posture = std::array::from_fn(|k| match BODY[k + 1].parent {
            Some((_, _, Hang::Hinge([lo, hi]))) => Quat::from_rotation_x(rng.range(lo, hi)),
            _ => Quat::from_axis_angle(rng.direction(), rng.range(0.0, ball_max)),
        });
        if !tangled(&poses(Pose::IDENTITY, &posture)) {
            return posture;
        }
    }
}

/// Whether two parts no joint joins overlap (or touch) in these poses.
fn tangled(poses: &[Pose; PARTS]) -> bool {
    let joined = |i: usize, j: usize| {
        BODY[j].parent.is_some_and(|(p, _, _)| p == i)
            || BODY[i].parent.is_some_and(|(p, _, _)| p == j)
    };
    (0..PARTS).any(|i| {
        (i + 1..PARTS).any(|j| {
            !joined(i, j)
                && collide(&BODY[i].shape, &poses[i], &BODY[j].shape, &poses[j], 0.0).len > 0
        })
    })
}

/// The parts' poses for a ragdoll placed by `root` and bent into `posture`, from the pelvis out:
/// a part keeps its standing offset from its joint's anchor, turned by its parent's rotation and
/// then its own joint's turn.
fn poses(root: Pose, posture: &Posture) -> [Pose; PARTS] {
    let mut poses = [Pose::IDENTITY; PARTS];
    for (i, part) in BODY.iter().enumerate() {
        poses[i] = match part.parent {
            None => Pose::new(root.position + root.rotation * part.centre, root.rotation),
            Some((p, anchor, _)) => {
                let parent = poses[p];
                let rotation = (parent.rotation * posture[i - 1]).normalize();
                let anchor_now = parent.position + parent.rotation * (anchor - BODY[p].centre);
                Pose::new(anchor_now + rotation * (part.centre - anchor), rotation)
            }
        };
    }
    poses
}

/// Appends a ragdoll to `bodies` and its joints to `joints`: placed by `root` (the standing
/// ragdoll's feet-centre frame: where it is and how it is turned) and bent into `posture`. Its
/// bodies are `bodies[first..first + PARTS]` in `BODY`'s order, `first` being `bodies.len()`
/// before the call.
pub fn add(
    bodies: &mut Vec<SceneBody>,
    joints: &mut Vec<JointDesc>,
    root: Pose,
    posture: &Posture,
) {
    let first = bodies.len();
    let poses = poses(root, posture);
    for (i, part) in BODY.iter().enumerate() {
        let mut desc = BodyDesc::dynamic(part.shape, poses[i], part.mass_kg);
        if matches!(part.shape, Shape::Sphere { .. }) {
            // A head does not roll on for ever.
            desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
        }
        let color = match i {
            0 | 1 => PALETTE[0],
            2 => PALETTE[1],
            3..=6 => PALETTE[2],
            _ => PALETTE[3],
        };
        bodies.push(SceneBody::new(desc, color));
    }
    // The joints are made standing (at `root`, unbent), so that their zero angles are the standing
    // pose's whatever the posture.
    let standing = |i: usize| {
        Pose::new(
            root.position + root.rotation * BODY[i].centre,
            root.rotation,
        )
    };
    for (i, part) in BODY.iter().enumerate() {
        let Some((p, anchor, hang)) = part.parent else {
            continue;
        };
        let kind = match hang {
            Hang::Ball => JointKind::Ball,
            Hang::Hinge(limits) => JointKind::Hinge {
                limits: Some(limits),
                motor: None,
            },
        };
        let id = |k: usize| BodyId((first + k) as u32);
        let anchor = root.position + root.rotation * anchor;
        joints.push(
            JointDesc::at(
                kind,
                Some((id(p), standing(p))),
                (id(i), standing(i)),
                anchor,
                anchor,
                root.rotation * Vec3::X,
                false,
            )
            .with_friction(JOINT_FRICTION_PER_KG * part.mass_kg),
        );
    }
}

/// The built-in scene `ragdoll`: a ragdoll lying face down, arms and legs a little bent, dropped
/// at 1.5 m/s onto the landing at the top of a flight of five stairs (static boxes, 25 cm high,
/// 45 cm deep) that descends along +x to the floor, its legs out over the first step; it tumbles
/// down and comes to rest. Body order: floor, stairs from the top, the ragdoll.
pub fn on_stairs() -> Scene {
    let mut bodies = vec![cases::floor(8.0)];
    let (steps, rise, run) = (5, 0.25, 0.45);
    for k in 0..steps {
        // Step k (0 the top) spans x from k·run to (k + 1)·run, standing on the floor; the top one
        // reaches back to x = −1.2 to make a landing.
        let height = rise * (steps - k) as f32;
        let back = if k == 0 { -1.2 } else { run * k as f32 };
        let front = run * (k + 1) as f32;
        bodies.push(SceneBody {
            name: None,
            frozen: false,
            desc: BodyDesc::fixed(
                cuboid(0.5 * (front - back), 0.5 * height, 1.0),
                Pose::from_position(Vec3::new(0.5 * (front + back), 0.5 * height, 0.0)),
            ),
            color: FLOOR_COLOR,
        });
    }
    // Lying face down along x, head toward −x (standing up turned to −x, then the face, +z, turned
    // down about x), pelvis over the landing, legs out over the first step.
    let half_pi = std::f32::consts::FRAC_PI_2;
    let lying = Quat::from_rotation_x(half_pi) * Quat::from_rotation_z(half_pi);
    let top = rise * steps as f32;
    let root = Pose::new(Vec3::new(1.4, top + 0.6, 0.1), lying);
    let mut posture = STANDING;
    posture[4] = Quat::from_rotation_x(-0.7); // the +x elbow
    posture[5] = Quat::from_rotation_x(-1.2); // the −x elbow
    posture[8] = Quat::from_rotation_x(0.5); // the +x knee
    posture[6] = Quat::from_rotation_z(0.3); // the +x hip, out to the side
    let mut joints = Vec::new();
    add(&mut bodies, &mut joints, root, &posture);
    // Pushed off the landing, down the stairs.
    for part in &mut bodies[1 + steps..] {
        part.desc.linear_velocity = Vec3::new(1.5, 0.0, 0.0);
    }
    Scene {
        name: "ragdoll".into(),
        settings: Settings::default(),
        // In front of the stairs (−z, as every built-in scene's camera), a little to their foot's side.
        camera: Camera::perspective(
            Vec3::new(1.6, 2.0, -2.8),
            Vec3::new(0.8, 0.7, 0.0),
            DEFAULT_FOV_DEG.to_radians(),
        ),
        bodies,
        joints,
    }
}

/// `count` ragdolls in random postures (seeded by `seed`), lying in layers of two crosswise to the
/// layer below, 0.6 m apart from 0.6 m up, dropped into a pile on a floor: the joint benchmark's
/// ragdoll scene. Sleeping is off, as the benchmarks run.
pub fn pile(count: usize, seed: u64) -> Scene {
    let mut rng = SplitMix64(seed);
    let mut bodies = vec![cases::floor(10.0)];
    let mut joints = Vec::new();
    for k in 0..count {
        let (layer, side) = (k / 2, k % 2);
        let across = Quat::from_rotation_y(if layer % 2 == 0 {
            0.0
        } else {
            std::f32::consts::FRAC_PI_2
        });
        // On its back, head toward −z before the layer's turn; the two of a layer side by side.
        let lying = across * Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
        let offset = across * Vec3::new(if side == 0 { -0.35 } else { 0.35 }, 0.0, -0.8);
        let root = Pose::new(
            offset + Vec3::new(0.0, 0.6 + 0.6 * layer as f32, 0.0),
            lying,
        );
        add(
            &mut bodies,
            &mut joints,
            root,
            &random_posture(&mut rng, 0.6),
        );
    }
    Scene {
        name: format!("ragdoll pile({count})"),
        settings: Settings {
            sleep: false,
            ..Settings::default()
        },
        camera: Camera::perspective(
            Vec3::new(3.0, 3.0, -5.0),
            Vec3::new(0.0, 1.0, 0.0),
            DEFAULT_FOV_DEG.to_radians(),
        ),
        bodies,
        joints,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn widest_joint(scene: &Scene) -> f32 {
        let world = scene.build_world();
        world
            .joints()
            .iter()
            .map(|j| {
                let (a, b) = world.joint_anchors(j);
                a.distance(b)
            })
            .fold(0.0, f32::max)
    }

    #[test]
    fn a_bent_ragdoll_is_built_with_its_joints_closed() {
        let mut rng = SplitMix64(7);
        let mut bodies = Vec::new();
        let mut joints = Vec::new();
        let root = Pose::new(Vec3::new(1.0, 2.0, 3.0), rng.rotation());
        add(
            &mut bodies,
            &mut joints,
            root,
            &random_posture(&mut rng, 1.0),
        );
        assert_eq!((bodies.len(), joints.len()), (PARTS, JOINTS));
        let scene = Scene {
            name: String::new(),
            settings: Settings::default(),
            camera: Camera::perspective(Vec3::Z, Vec3::ZERO, 1.0),
            bodies,
            joints,
        };
        assert!(widest_joint(&scene) < 1e-5, "{}", widest_joint(&scene));
    }

    #[test]
    fn a_posture_sets_the_hinge_angle_it_names() {
        // The +x knee bent 1 rad: its shin's rotation is the thigh's turned 1 rad about x.
        let mut posture = STANDING;
        posture[8] = Quat::from_rotation_x(1.0);
        let (mut bodies, mut joints) = (Vec::new(), Vec::new());
        add(&mut bodies, &mut joints, Pose::IDENTITY, &posture);
        let (thigh, shin) = (bodies[7].desc.pose, bodies[9].desc.pose);
        let turn = thigh.rotation.inverse() * shin.rotation;
        assert!(turn.angle_between(Quat::from_rotation_x(1.0)) < 1e-5);
        // The shin swings back (−z) and its knee stays at the thigh's lower face.
        assert!(shin.position.z < -0.1);
        assert!(matches!(
            joints[8].kind,
            JointKind::Hinge {
                limits: Some([0.0, _]),
                ..
            }
        ));
    }
}
