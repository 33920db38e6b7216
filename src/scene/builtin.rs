//! The built-in scenes, by name: small hand-made ones here, the large generated ones from [`cases`].

use glam::{Quat, Vec3};

use super::framing::{self, DEFAULT_FOV_DEG, Framed, Framing};
use super::{Scene, SceneBody};
use super::{cases, mechanisms};
use crate::color::Rgb;
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Aabb, Pose, Shape};
use crate::physics::{BodyDesc, Settings};

/// (name, one-line description) of every built-in scene, in the order `nudge scenes` lists them.
pub const BUILTIN_SCENES: &[(&str, &str)] = &[
    (
        "default",
        "two boxes (3 kg, 5 kg) and two balls (1 kg, 2 kg) dropping onto a floor",
    ),
    ("stack", "8 boxes stacked in a column on a floor"),
    ("pyramid", "210 boxes in a 20-box-base pyramid"),
    (
        "ramp",
        "3 boxes slide and 3 balls roll down a 30° ramp to a catch wall",
    ),
    ("dominoes", "a thrown ball knocks over a row of 12 dominoes"),
    (
        "pendulum",
        "a simple and a double pendulum released side by side from 110°",
    ),
    (
        "cradle",
        "Newton's cradle: 5 balls on strings, the first raised 40°",
    ),
    (
        "chain",
        "a chain of 30 links hanging from a hook: grab its end and swing it",
    ),
    (
        "bridge",
        "a rope bridge of 12 hinged planks with 3 boxes dropped onto it",
    ),
    (
        "door",
        "a door on a hinge in its frame: click it to push it open",
    ),
    ("rain", "1,000 boxes and balls raining into a walled pit"),
    (
        "wrecking",
        "a 50 kg ball on a chain of 20 links swings into a wall of 36 boxes",
    ),
    ("ragdoll", "a ragdoll dropped on a flight of stairs"),
];

/// The built-in scene called `name`, or `None`.
pub fn by_name(name: &str) -> Option<Scene> {
    let mut scene = match name {
        "default" => default(),
        "stack" => stack(8),
        "pyramid" => cases::pyramid(20),
        "ramp" => ramp(),
        "dominoes" => dominoes(12),
        "pendulum" => mechanisms::pendulums(),
        "cradle" => mechanisms::cradle(5),
        "chain" => mechanisms::chain(),
        "bridge" => mechanisms::bridge(),
        "door" => mechanisms::door(),
        "rain" => rolling_balls_resist(cases::rain(1000)),
        "wrecking" => mechanisms::wrecking_ball(),
        "ragdoll" => super::ragdoll::on_stairs(),
        _ => return None,
    };
    scene.name = name.to_owned();
    Some(scene)
}

/// A dynamic body of the given mass and colour.
fn body(shape: Shape, pose: Pose, mass_kg: f32, color: Rgb) -> SceneBody {
    SceneBody {
        name: None,
        frozen: false,
        desc: BodyDesc::dynamic(shape, pose, mass_kg),
        color,
    }
}

/// Rolling resistance of the default scene's balls: a ball rolling at 2 m/s stops after about 6 m
/// (a = 5/7 · μr · g), as a wooden ball on a wooden floor more or less does, instead of rolling
/// forever.
pub const BALL_ROLLING_RESISTANCE: f32 = 0.05;

/// A dynamic ball of the given mass and colour that resists rolling.
fn ball(shape: Shape, pose: Pose, mass_kg: f32, color: Rgb) -> SceneBody {
    let mut ball = body(shape, pose, mass_kg, color);
    ball.desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
    ball
}

/// The scene with every dynamic ball resisting rolling (and spinning) as the default scene's do. A
/// ball that rolls forever never sleeps and, in a crowd, keeps waking what it bumps into: `rain` had
/// 40 % of its bodies awake after 30 s. (`cases::rain`, which the benchmarks and `rapier-bench`
/// share, is left as it is.)
fn rolling_balls_resist(mut scene: Scene) -> Scene {
    for body in &mut scene.bodies {
        if !body.desc.is_static && matches!(body.desc.shape, Shape::Sphere { .. }) {
            body.desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
        }
    }
    scene
}

/// A static body (floor colour).
fn fixed(shape: Shape, pose: Pose) -> SceneBody {
    SceneBody {
        name: None,
        frozen: false,
        desc: BodyDesc::fixed(shape, pose),
        color: FLOOR_COLOR,
    }
}

/// Half-size of the default scene's floor, x by z, m.
const FLOOR_HALF: glam::Vec2 = glam::Vec2::new(4.0, 2.5);

/// Height of the rim around the default floor, m: above the balls' contact with a step they could
/// climb (a ball of radius r rolls over a step of height h < r when fast enough, and the larger
/// ball's r is 0.65 m, so the rim is most of it).
const RIM_HEIGHT: f32 = 0.4;

/// Thickness of the rim's walls, m.
const RIM_THICKNESS: f32 = 0.2;

/// Four low walls standing on the edges of a floor of half-size `half` (x by z, top at y = 0), like
/// a tray's rim. The hand sends a body off at 2–3 m/s, and a ball at 2.5 m/s rolls about 9 m
/// before its rolling resistance stops it: without a rim a newcomer's first click on a ball rolled
/// it off the 8 × 5 m floor ("sphere #4 fell off the world"). Boxes slide to a stop well within it.
fn rim(half: glam::Vec2) -> [SceneBody; 4] {
    let (t, h) = (0.5 * RIM_THICKNESS, 0.5 * RIM_HEIGHT);
    let wall = |half_extents: Vec3, x: f32, z: f32| {
        fixed(
            Shape::cuboid(half_extents),
            Pose::from_position(Vec3::new(x, h, z)),
        )
    };
    [
        wall(Vec3::new(half.x, h, t), 0.0, half.y - t),
        wall(Vec3::new(half.x, h, t), 0.0, -half.y + t),
        wall(Vec3::new(t, h, half.y - 2.0 * t), half.x - t, 0.0),
        wall(Vec3::new(t, h, half.y - 2.0 * t), -half.x + t, 0.0),
    ]
}

/// The reference engine's scene, re-proportioned for a terminal: an 8 m × 5 m floor slab (top at
/// y = 0) inside a low rim, a 1 m cube of 3 kg and a flat 5 kg box, a 1 kg ball (r 0.4 m) and a 2 kg
/// ball (r 0.65 m) that resist rolling, all a little above the floor so they drop and settle. The
/// automatic camera frames them where they settle ([`framing`]): they fall into the picture from
/// above and come to rest filling its width.
pub fn default() -> Scene {
    let mut bodies = vec![
        fixed(
            Shape::cuboid(Vec3::new(FLOOR_HALF.x, 0.5, FLOOR_HALF.y)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ),
        body(
            Shape::cuboid(Vec3::splat(0.5)),
            Pose::new(
                Vec3::new(-2.2, 1.5, 0.3),
                Quat::from_rotation_y(20f32.to_radians()),
            ),
            3.0,
            PALETTE[0],
        ),
        body(
            Shape::cuboid(Vec3::new(0.7, 0.45, 0.6)),
            Pose::new(
                Vec3::new(1.9, 2.2, -0.2),
                Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0).normalize(), 35f32.to_radians()),
            ),
            5.0,
            PALETTE[2],
        ),
        ball(
            Shape::sphere(0.4),
            Pose::from_position(Vec3::new(-0.6, 2.4, -0.6)),
            1.0,
            PALETTE[1],
        ),
        ball(
            Shape::sphere(0.65),
            Pose::from_position(Vec3::new(0.5, 3.1, 0.6)),
            2.0,
            PALETTE[3],
        ),
    ];
    bodies.extend(rim(FLOOR_HALF));
    Scene {
        name: "default".into(),
        settings: Settings::default(),
        camera: framing::auto_camera(&bodies, DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// `count` unit boxes (half-extent 0.5 m) in a vertical column on a floor, each resting exactly on the
/// one below (bottom face of box i at y = i metres).
pub fn stack(count: usize) -> Scene {
    let mut bodies = vec![cases::floor(6.0)];
    for i in 0..count {
        bodies.push(cases::dynamic(
            Shape::cuboid(Vec3::splat(0.5)),
            Vec3::new(0.0, 0.5 + i as f32, 0.0),
            PALETTE[i % PALETTE.len()],
        ));
    }
    Scene {
        name: format!("stack({count})"),
        settings: Settings::default(),
        camera: framing::auto_camera(&bodies, DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// Ramp incline, degrees.
const RAMP_ANGLE_DEG: f32 = 30.0;
/// Where the ramp scene's catch wall faces the slope, x in metres (the slope's foot is at x ≈ −0.6).
const RAMP_CATCH_WALL_X: f32 = -7.0;

/// A static 8 m ramp inclined at 30° (rising toward +x, its low edge resting on the floor) with three
/// boxes (μ = 0.3 < tan 30° ≈ 0.58, so they slide) in one lane and three balls (they roll) in the other,
/// each 2 cm above the slope, and a low wall across the floor that catches the balls. Body order:
/// floor, ramp, boxes, balls, wall.
pub fn ramp() -> Scene {
    let angle = RAMP_ANGLE_DEG.to_radians();
    // Rotating about +z by +30° turns local +x up the slope (toward +x, +y) and local +y into the
    // surface normal (−sin 30°, cos 30°, 0).
    let rotation = Quat::from_rotation_z(angle);
    let half = Vec3::new(4.0, 0.25, 1.6);
    // The lowest corner, local (−hx, −hy), sits on the floor: y = h − hx sin θ − hy cos θ = 0.
    let center = Vec3::new(3.0, half.x * angle.sin() + half.y * angle.cos(), 0.0);
    let ramp_pose = Pose::new(center, rotation);
    let mut bodies = vec![
        fixed(
            Shape::cuboid(Vec3::new(8.5, 0.5, 5.0)),
            Pose::from_position(Vec3::new(-0.5, -0.5, 0.0)),
        ),
        fixed(Shape::cuboid(half), ramp_pose),
    ];
    let on_slope = |u: f32, size: f32, lane_z: f32| {
        ramp_pose.transform_point(Vec3::new(u, half.y + size + 0.02, 0.0)) + Vec3::Z * lane_z
    };
    let size = 0.3;
    for (i, u) in [3.0, 1.5, 0.0].into_iter().enumerate() {
        let mut b = cases::dynamic(
            Shape::cuboid(Vec3::splat(size)),
            on_slope(u, size, -0.8),
            PALETTE[i],
        );
        b.desc.pose.rotation = rotation;
        b.desc.friction = 0.3;
        bodies.push(b);
    }
    for (i, u) in [3.0, 1.5, 0.0].into_iter().enumerate() {
        let mut ball = cases::dynamic(Shape::sphere(size), on_slope(u, size, 0.8), PALETTE[3 + i]);
        ball.desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
        bodies.push(ball);
    }
    // A ball leaves the slope at about 7 m/s and would roll some 80 m before its rolling
    // resistance stopped it: a low wall across the floor catches it (the boxes stop by friction
    // short of it).
    bodies.push(fixed(
        Shape::cuboid(Vec3::new(0.25, 0.5, 5.0)),
        Pose::from_position(Vec3::new(RAMP_CATCH_WALL_X - 0.25, 0.5, 0.0)),
    ));
    // The slope the bodies go down and the wall across their lanes where they end up are framed as
    // bodies too, not as ground the picture may cut off at its sides.
    let mut framing = Framing::of(&bodies);
    framing.bodies.push(Framed {
        shape: Shape::cuboid(half),
        pose: ramp_pose,
    });
    framing.bodies.push(Framed::aabb(&Aabb::new(
        Vec3::new(RAMP_CATCH_WALL_X - 0.5, 0.0, -half.z),
        Vec3::new(RAMP_CATCH_WALL_X, 1.0, half.z),
    )));
    Scene {
        name: "ramp".into(),
        settings: Settings::default(),
        camera: framing::framing_camera(&framing, DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// `count` dominoes (0.2 m × 1 m × 0.6 m, 0.6 m apart, so each reaches the next as it tips) standing in a
/// row along −x, and a 0.5 kg ball (r 0.3 m) thrown at the first one at 5 m/s, slightly upward, so it
/// strikes above the domino's centre of mass. Body order: floor, dominoes, ball.
pub fn dominoes(count: usize) -> Scene {
    let spacing = 0.6;
    let mut bodies = vec![cases::floor(10.0)];
    for i in 0..count {
        bodies.push(cases::dynamic(
            Shape::cuboid(Vec3::new(0.1, 0.5, 0.3)),
            Vec3::new(-spacing * i as f32, 0.5, 0.0),
            PALETTE[i % 2 * 2],
        ));
    }
    let mut ball = ball(
        Shape::sphere(0.3),
        Pose::from_position(Vec3::new(1.6, 0.8, 0.0)),
        0.5,
        PALETTE[1],
    );
    ball.desc.linear_velocity = Vec3::new(-5.0, 1.5, 0.0);
    bodies.push(ball);
    // The row falls toward −x: the floor where the last domino lands is framed as a body too.
    let last = -spacing * count.saturating_sub(1) as f32;
    let mut framing = Framing::of(&bodies);
    framing.bodies.push(Framed::aabb(&Aabb::new(
        Vec3::new(last - 1.1, 0.0, -0.3),
        Vec3::new(last, 0.0, 0.3),
    )));
    Scene {
        name: format!("dominoes({count})"),
        settings: Settings::default(),
        camera: framing::framing_camera(&framing, DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every corner of every body's bounds, in the NDC of `camera` for a 120×80-pixel image (a 120×40
    /// terminal of 1:2 cells).
    fn ndc_corners(scene: &Scene) -> Vec<Vec3> {
        let clip_from_world = scene.camera.clip_from_world(1.5);
        let mut out = Vec::new();
        for body in &scene.bodies {
            let b = body.desc.shape.aabb(&body.desc.pose);
            for i in 0..8 {
                let corner = Vec3::select(
                    glam::BVec3::new(i & 1 == 0, i & 2 == 0, i & 4 == 0),
                    b.min,
                    b.max,
                );
                let clip = clip_from_world * corner.extend(1.0);
                out.push(clip.truncate() / clip.w);
            }
        }
        out
    }

    #[test]
    fn every_listed_scene_is_built_and_every_built_scene_is_listed() {
        for (name, description) in BUILTIN_SCENES {
            let scene = by_name(name).unwrap_or_else(|| panic!("{name} is listed but not built"));
            assert_eq!(scene.name, *name);
            assert!(!description.is_empty() && !description.contains('\n'));
        }
        assert!(by_name("nonsense").is_none());
    }

    #[test]
    fn the_default_scene_has_the_reference_masses() {
        let scene = default();
        let masses: Vec<f32> = scene.bodies[1..5].iter().map(|b| b.desc.mass).collect();
        assert_eq!(masses, [3.0, 5.0, 1.0, 2.0]);
        assert!(scene.bodies[0].desc.is_static);
        assert!(
            scene.bodies[5..].iter().all(|b| b.desc.is_static),
            "the rim"
        );
        assert!(matches!(scene.bodies[1].desc.shape, Shape::Cuboid { .. }));
        assert!(matches!(scene.bodies[3].desc.shape, Shape::Sphere { .. }));
    }

    /// The camera frames the bodies where they come to rest (`framing::settle`): there they fill
    /// most of a 120×40 terminal's width or height without leaving it.
    #[test]
    fn the_default_scene_at_rest_fills_a_120_by_40_terminal_without_leaving_it() {
        let scene = default();
        assert!(scene.camera.position.z < 0.0 && scene.camera.position.y > scene.camera.target.y);
        // The boxes' corners, and the balls' extremes across and up the picture.
        let basis = scene.camera.basis();
        let framing = Framing::of(&scene.bodies);
        let points = framing.bodies.iter().flat_map(|f| match f.shape {
            Shape::Cuboid { half_extents: h } => framing::corners(&Aabb::new(-h, h))
                .map(|p| f.pose.transform_point(p))
                .to_vec(),
            Shape::Sphere { radius } => [basis.right, -basis.right, basis.up, -basis.up]
                .map(|d| f.pose.position + radius * d)
                .to_vec(),
        });
        let clip_from_world = scene.camera.clip_from_world(1.5);
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for p in points {
            let clip = clip_from_world * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            lo = lo.min(ndc);
            hi = hi.max(ndc);
        }
        assert!(lo.z > 0.0 && hi.z < 1.0, "depth {lo} {hi}");
        assert!(
            lo.x >= -1.0 && hi.x <= 1.0 && lo.y >= -1.0 && hi.y <= 1.0,
            "{lo} {hi}"
        );
        // At least 80% of the width and 35% of the height (the floor in front takes the rest).
        assert!(hi.x - lo.x >= 1.6 && hi.y - lo.y >= 0.7, "{lo} {hi}");
    }

    #[test]
    fn ramp_bodies_start_just_above_the_slope_and_the_ramp_rests_on_the_floor() {
        let scene = ramp();
        let ramp = &scene.bodies[1].desc;
        let bounds = ramp.shape.aabb(&ramp.pose);
        assert!(bounds.min.y.abs() < 1e-5, "{}", bounds.min.y);
        let normal = ramp.pose.transform_vector(Vec3::Y);
        let Shape::Cuboid { half_extents } = ramp.shape else {
            panic!("ramp is a box");
        };
        for body in &scene.bodies[2..8] {
            // Height of the body's centre above the slope's top plane, minus its half-size along the normal.
            let height =
                (body.desc.pose.position - ramp.pose.position).dot(normal) - half_extents.y;
            let clearance = height - 0.3;
            assert!((clearance - 0.02).abs() < 1e-4, "{clearance}");
        }
    }

    #[test]
    fn ramp_boxes_are_slippery_enough_to_slide() {
        let scene = ramp();
        for body in &scene.bodies[2..5] {
            assert!(body.desc.friction < RAMP_ANGLE_DEG.to_radians().tan());
        }
    }

    /// `dominoes` was framed from far off, the row a short stroke across the middle of the view.
    #[test]
    fn the_dominoes_row_fills_the_view() {
        let scene = dominoes(12);
        let row = Scene {
            bodies: scene.bodies[1..=12].to_vec(),
            ..scene.clone()
        };
        let corners = ndc_corners(&row);
        let (lo, hi) = corners.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), c| (lo.min(*c), hi.max(*c)),
        );
        assert!(
            lo.x >= -1.0 && hi.x <= 1.0 && lo.y >= -1.0 && hi.y <= 1.0,
            "{lo} {hi}"
        );
        // At least 60 % of the width (it was 27 %).
        assert!(
            hi.x - lo.x > 1.2,
            "the row spans {} of the width",
            (hi.x - lo.x) / 2.0
        );
    }

    #[test]
    fn dominoes_are_close_enough_to_topple_into_each_other() {
        let scene = dominoes(12);
        let Shape::Cuboid { half_extents } = scene.bodies[1].desc.shape else {
            panic!("dominoes are boxes");
        };
        let gap = scene.bodies[1].desc.pose.position.x - scene.bodies[2].desc.pose.position.x;
        assert!(gap < 2.0 * half_extents.y);
        assert!(gap > 2.0 * half_extents.x);
    }
}
