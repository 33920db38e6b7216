//! Scenes built by code, shared by the built-in scenes, the hard-case tests and `nudge bench`.

use glam::{Quat, Vec3};

use super::{Scene, SceneBody, framing};
use crate::color::{FLOOR_COLOR, PALETTE, Rgb};
use crate::geometry::{Camera, Pose, Shape};
use crate::physics::{BodyDesc, Settings};
use crate::util::SplitMix64;

/// A static slab whose top face is at y = 0.
pub fn floor(half_width: f32) -> SceneBody {
    SceneBody {
        name: None,
        frozen: false,
        desc: BodyDesc::fixed(
            Shape::cuboid(Vec3::new(half_width, 0.5, half_width)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ),
        color: FLOOR_COLOR,
    }
}

/// A dynamic unit-density body of the given shape at `position`.
pub fn dynamic(shape: Shape, position: Vec3, color: Rgb) -> SceneBody {
    SceneBody {
        name: None,
        frozen: false,
        desc: BodyDesc::dynamic(shape, Pose::from_position(position), shape.volume()),
        color,
    }
}

/// A 2D pyramid of unit boxes (half-extent 0.5) standing on the floor: `base` boxes in the bottom row,
/// one fewer in each row above (base 20 → 210 boxes). Boxes in a row are 5 cm apart.
pub fn pyramid(base: usize) -> Scene {
    let mut bodies = vec![floor(40.0)];
    let spacing = 1.05;
    for row in 0..base {
        let count = base - row;
        let y = 0.5 + row as f32;
        let x0 = -0.5 * spacing * (count as f32 - 1.0);
        for i in 0..count {
            let x = x0 + spacing * i as f32;
            let color = PALETTE[(row + i) % PALETTE.len()];
            bodies.push(dynamic(
                Shape::cuboid(Vec3::splat(0.5)),
                Vec3::new(x, y, 0.0),
                color,
            ));
        }
    }
    let height = base as f32;
    Scene {
        name: format!("pyramid({base})"),
        settings: Settings::default(),
        // Close enough that the pyramid fills most of the view height (70° fov: visible height ≈ 1.4 × distance).
        camera: Camera::perspective(
            Vec3::new(0.0, 0.6 * height, -height - 1.0),
            Vec3::new(0.0, 0.45 * height, 0.0),
            70f32.to_radians(),
        ),
        bodies,
        joints: Vec::new(),
    }
}

/// Half-width of [`rain`]'s pit, m.
const RAIN_PIT_HALF: f32 = 19.5;

/// `count` boxes and spheres (half-size 0.4) in a jittered grid above a 39 m × 39 m pit with 4 m walls,
/// ready to rain down. Deterministic for a given count. From 1,445 bodies the grid has more than one
/// layer, and the bodies land on one another: rain(4000) piles three deep, with 5.4 times
/// rain(1000)'s contacts, many between moving bodies.
pub fn rain(count: usize) -> Scene {
    rain_in_pit(count, RAIN_PIT_HALF)
}

/// [`rain`] in a pit whose area grows with `count` (a side of 39 m·√(count / 1000)), so the bodies
/// fall in one layer as rain(1000)'s do and land as far apart: each finds the same number of
/// neighbours, and the contacts grow with the bodies (4.3 times rain(1000)'s at 4,000, where
/// [`rain`]'s grow 5.4 times). What it costs against rain(1000) is how the engine scales, without
/// the pile's own growth.
pub fn spread_rain(count: usize) -> Scene {
    let side = (count as f32 / 1000.0).sqrt().max(1.0);
    let mut scene = rain_in_pit(count, RAIN_PIT_HALF * side);
    scene.name = format!("spread rain({count})");
    scene
}

fn rain_in_pit(count: usize, pit_half: f32) -> Scene {
    let wall_half_height = 2.0;
    let wall_half_thickness = 0.5;
    let mut bodies = vec![floor(pit_half + 2.0 * wall_half_thickness)];
    for (axis, side) in [(0, -1.0), (0, 1.0), (2, -1.0), (2, 1.0)] {
        let mut half = Vec3::new(wall_half_thickness, wall_half_height, pit_half);
        let mut center = Vec3::new(
            side * (pit_half + wall_half_thickness),
            wall_half_height,
            0.0,
        );
        if axis == 2 {
            half = Vec3::new(pit_half, wall_half_height, wall_half_thickness);
            center = Vec3::new(
                0.0,
                wall_half_height,
                side * (pit_half + wall_half_thickness),
            );
        }
        bodies.push(SceneBody {
            name: None,
            frozen: false,
            desc: BodyDesc::fixed(Shape::cuboid(half), Pose::from_position(center)),
            color: FLOOR_COLOR,
        });
    }

    let spacing = 1.0;
    let per_row = ((2.0 * pit_half - 1.0) / spacing) as usize; // 38
    let per_layer = per_row * per_row;
    let mut rng = SplitMix64(0x6e75_6467_6521);
    for i in 0..count {
        let layer = i / per_layer;
        let in_layer = i % per_layer;
        let (row, col) = (in_layer / per_row, in_layer % per_row);
        let jitter = Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed()) * 0.08;
        let position = Vec3::new(
            -pit_half + 1.0 + col as f32 * spacing,
            2.0 + layer as f32 * spacing * 1.2,
            -pit_half + 1.0 + row as f32 * spacing,
        ) + jitter;
        let shape = if i % 2 == 0 {
            Shape::cuboid(Vec3::splat(0.4))
        } else {
            Shape::sphere(0.4)
        };
        let axis = Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed())
            .try_normalize()
            .unwrap_or(Vec3::Y);
        let rotation = Quat::from_axis_angle(axis, rng.next_signed() * std::f32::consts::PI);
        let mut body = dynamic(shape, position, PALETTE[i % PALETTE.len()]);
        body.desc.pose.rotation = rotation;
        bodies.push(body);
    }
    Scene {
        name: format!("rain({count})"),
        settings: Settings::default(),
        camera: framing::auto_camera(&bodies, framing::DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// Half-extent of the unit boxes the hard cases use, metres.
pub const UNIT_HALF: f32 = 0.5;

/// A unit box (1 m cube).
pub fn unit_box() -> Shape {
    Shape::cuboid(Vec3::splat(UNIT_HALF))
}

/// A static slab `half_width` wide each way whose top face is at y = 0, centred under `center_xz`
/// (its y is ignored).
pub fn floor_at(center_xz: Vec3, half_width: f32) -> SceneBody {
    let mut floor = floor(half_width);
    floor.desc.pose.position = Vec3::new(center_xz.x, -0.5, center_xz.z);
    floor
}

/// A scene whose camera frames its bodies automatically ([`framing::auto_camera`]).
fn scene(name: String, settings: Settings, bodies: Vec<SceneBody>) -> Scene {
    Scene {
        name,
        settings,
        camera: framing::auto_camera(&bodies, framing::DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// A vertical stack of `count` unit boxes, exactly touching, on a floor, centred over `base` (x, z;
/// its y is ignored). Body 0 is the floor, box i (from the bottom, 0-based) is body i + 1 with its centre at
/// y = 0.5 + i.
pub fn stack(count: usize, base: Vec3) -> Scene {
    let mut bodies = vec![floor_at(base, 10.0)];
    for i in 0..count {
        let position = Vec3::new(base.x, UNIT_HALF + i as f32, base.z);
        bodies.push(dynamic(unit_box(), position, PALETTE[i % PALETTE.len()]));
    }
    scene(format!("stack({count})"), Settings::default(), bodies)
}

/// Half-thickness (across its rocking) and half-length of the block of [`tipped_block`], m.
pub const TIPPED_BLOCK_HALF_WIDTH: f32 = 0.1;
pub const TIPPED_BLOCK_HALF_LENGTH: f32 = 0.4;
/// Friction of the block of [`tipped_block`] and its floor: enough that its edge does not slip.
pub const TIPPED_BLOCK_FRICTION: f32 = 1.0;

/// The critical angle of a block `aspect` times as high as it is thick: atan(b/h), rad. Tipped
/// further onto an edge it falls over; less, it rocks back.
pub fn critical_angle(aspect: f32) -> f32 {
    (1.0 / aspect).atan()
}

/// A block `aspect` times as high as it is thick (0.2 m thick, 0.8 m long), standing on a rough floor
/// tipped onto its bottom edge at +z by `tip` of its [`critical_angle`], at rest (body 1, leaning
/// towards +z, turned about x).
pub fn tipped_block(aspect: f32, tip: f32) -> Scene {
    let half = Vec3::new(
        TIPPED_BLOCK_HALF_LENGTH,
        aspect * TIPPED_BLOCK_HALF_WIDTH,
        TIPPED_BLOCK_HALF_WIDTH,
    );
    let turn = Quat::from_rotation_x(tip * critical_angle(aspect));
    let edge = Vec3::new(0.0, 0.0, TIPPED_BLOCK_HALF_WIDTH);
    let centre = edge + turn * (Vec3::new(0.0, half.y, 0.0) - edge);
    let shape = Shape::cuboid(half);
    let mut block = BodyDesc::dynamic(shape, Pose::new(centre, turn), shape.volume());
    block.friction = TIPPED_BLOCK_FRICTION;
    let mut ground = floor(10.0);
    ground.desc.friction = TIPPED_BLOCK_FRICTION;
    let bodies = vec![ground, SceneBody::new(block, PALETTE[2])];
    scene(
        format!("block h/b={aspect} tipped {tip} of its critical angle"),
        Settings::default(),
        bodies,
    )
}

/// Mass of the light bottom box of [`mass_ratio`], kg.
pub const MASS_RATIO_LIGHT_KG: f32 = 1.0;
/// Mass of the heavy top box of [`mass_ratio`], kg.
pub const MASS_RATIO_HEAVY_KG: f32 = 1000.0;

/// A 1000 kg unit box resting on a 1 kg unit box on the floor. Bodies: floor, light box (centre y = 0.5),
/// heavy box (centre y = 1.5).
pub fn mass_ratio() -> Scene {
    heavy_on_light(MASS_RATIO_HEAVY_KG)
}

/// A unit box of `heavy_kg` resting on a [`MASS_RATIO_LIGHT_KG`] unit box on the floor, named
/// "mass ratio R:1". Bodies: floor, light box (centre y = 0.5), heavy box (centre y = 1.5).
pub fn heavy_on_light(heavy_kg: f32) -> Scene {
    let mut light = dynamic(unit_box(), Vec3::new(0.0, UNIT_HALF, 0.0), PALETTE[2]);
    light.desc.mass = MASS_RATIO_LIGHT_KG;
    let mut heavy = dynamic(unit_box(), Vec3::new(0.0, 3.0 * UNIT_HALF, 0.0), PALETTE[1]);
    heavy.desc.mass = heavy_kg;
    scene(
        format!("mass ratio {}:1", heavy_kg / MASS_RATIO_LIGHT_KG),
        Settings::default(),
        vec![floor(10.0), light, heavy],
    )
}

/// Gap between the floor and the bottom of the ball of [`bounce`] at release, metres.
pub const BOUNCE_GAP: f32 = 5.0;
/// Restitution of both the ball and the floor of [`bounce`].
pub const BOUNCE_RESTITUTION: f32 = 0.5;

/// A ball of radius 0.5 released at rest with its bottom [`BOUNCE_GAP`] above a floor; both have restitution
/// [`BOUNCE_RESTITUTION`]. Bodies: floor, ball. The first rebound should reach e²·gap (1.25 m).
pub fn bounce() -> Scene {
    let mut ground = floor(10.0);
    ground.desc.restitution = BOUNCE_RESTITUTION;
    let mut ball = dynamic(
        Shape::sphere(UNIT_HALF),
        Vec3::new(0.0, BOUNCE_GAP + UNIT_HALF, 0.0),
        PALETTE[3],
    );
    ball.desc.restitution = BOUNCE_RESTITUTION;
    scene("bounce".into(), Settings::default(), vec![ground, ball])
}

/// Slope of the ramp of [`ramp`], radians (30°).
pub const RAMP_ANGLE: f32 = std::f32::consts::FRAC_PI_6;

/// Unit vector straight down the slope of [`ramp`].
pub fn ramp_downhill() -> Vec3 {
    ramp_downhill_at(RAMP_ANGLE)
}

/// Unit vector straight down the slope of [`ramp_at`]`(angle, _)`.
pub fn ramp_downhill_at(angle: f32) -> Vec3 {
    Quat::from_rotation_z(angle) * Vec3::NEG_X
}

/// Centre of the slab of [`ramp_slab`].
pub const RAMP_CENTER: Vec3 = Vec3::new(0.0, 4.0, 0.0);
/// Half-extents of the slab of [`ramp_slab`], m: 16 m long down the slope.
pub const RAMP_HALF: Vec3 = Vec3::new(8.0, UNIT_HALF, 3.0);

/// A static slab centred on [`RAMP_CENTER`] tilted by `angle` about z (it descends towards −x), of
/// friction `friction`. Its top face passes through `RAMP_CENTER + n · RAMP_HALF.y`, n its normal.
pub fn ramp_slab(angle: f32, friction: f32) -> SceneBody {
    let rotation = Quat::from_rotation_z(angle);
    let mut ramp = SceneBody::new(
        BodyDesc::fixed(Shape::cuboid(RAMP_HALF), Pose::new(RAMP_CENTER, rotation)),
        FLOOR_COLOR,
    );
    ramp.desc.friction = friction;
    ramp
}

/// A static ramp tilted by [`RAMP_ANGLE`] about z (it descends towards −x) with a unit box resting on its top
/// face, released at rest; the ramp and the box both have friction `friction`. Bodies: ramp, box.
/// The box is exactly touching the ramp (separation 0).
pub fn ramp(friction: f32) -> Scene {
    ramp_at(RAMP_ANGLE, friction)
}

/// [`ramp`] tilted by `angle` instead of [`RAMP_ANGLE`].
pub fn ramp_at(angle: f32, friction: f32) -> Scene {
    let rotation = Quat::from_rotation_z(angle);
    let normal = rotation * Vec3::Y;
    let mut block = dynamic(
        unit_box(),
        RAMP_CENTER + normal * (RAMP_HALF.y + UNIT_HALF),
        PALETTE[0],
    );
    block.desc.pose.rotation = rotation;
    block.desc.friction = friction;
    let name = if angle == RAMP_ANGLE {
        format!("ramp(mu={friction})")
    } else {
        format!("ramp(angle={angle}, mu={friction})")
    };
    scene(
        name,
        Settings::default(),
        vec![ramp_slab(angle, friction), block],
    )
}

/// Initial speed of the ball of [`rolling_ball`], m/s along +x.
pub const ROLL_SPEED: f32 = 5.0;
/// Friction of the ball and the floor of [`rolling_ball`].
pub const ROLL_FRICTION: f32 = 0.5;

/// A ball of radius 0.5 resting on a floor, sliding at [`ROLL_SPEED`] along +x with no spin; ball and floor
/// have friction [`ROLL_FRICTION`]. Bodies: floor, ball. It should end up rolling at 5/7 of the speed.
pub fn rolling_ball() -> Scene {
    let mut ground = floor(40.0);
    ground.desc.friction = ROLL_FRICTION;
    let mut ball = dynamic(
        Shape::sphere(UNIT_HALF),
        Vec3::new(-10.0, UNIT_HALF, 0.0),
        PALETTE[4],
    );
    ball.desc.friction = ROLL_FRICTION;
    ball.desc.linear_velocity = Vec3::new(ROLL_SPEED, 0.0, 0.0);
    scene(
        "rolling ball".into(),
        Settings::default(),
        vec![ground, ball],
    )
}

/// Initial velocity of the ball of [`projectile`], m/s.
pub const PROJECTILE_VELOCITY: Vec3 = Vec3::new(3.0, 5.0, 0.0);

/// A lone ball of radius 0.5 at the origin thrown with [`PROJECTILE_VELOCITY`], nothing to hit. Bodies: ball.
pub fn projectile() -> Scene {
    let mut ball = dynamic(Shape::sphere(UNIT_HALF), Vec3::ZERO, PALETTE[5]);
    ball.desc.linear_velocity = PROJECTILE_VELOCITY;
    scene("projectile".into(), Settings::default(), vec![ball])
}

/// Four unit boxes on a floor, spawned with their centres 0.4 m apart (0.6 m deep overlaps), turned about
/// y by different angles. Bodies: floor, four boxes.
pub fn deep_overlap() -> Scene {
    let mut bodies = vec![floor(10.0)];
    let offsets = [(-0.2, -0.2), (0.2, -0.2), (-0.2, 0.2), (0.2, 0.2)];
    for (i, (x, z)) in offsets.into_iter().enumerate() {
        let mut block = dynamic(unit_box(), Vec3::new(x, UNIT_HALF, z), PALETTE[i]);
        block.desc.pose.rotation = Quat::from_rotation_y(0.3 * i as f32);
        bodies.push(block);
    }
    scene("deep overlap".into(), Settings::default(), bodies)
}

/// Half-extents of the box of [`intermediate_axis`]: its intermediate principal axis is local y.
pub const SPIN_HALF_EXTENTS: Vec3 = Vec3::new(0.1, 0.4, 1.0);
/// Initial angular velocity of [`intermediate_axis`], rad/s: 5 about the intermediate axis plus a
/// perturbation of 1e-3 about the other two.
pub const SPIN_ANGULAR_VELOCITY: Vec3 = Vec3::new(1e-3, 5.0, 1e-3);

/// A free box (half-extents [`SPIN_HALF_EXTENTS`]) in zero gravity spinning about its intermediate axis
/// (the Dzhanibekov effect: the spin is unstable and the box flips periodically). Bodies: box.
pub fn intermediate_axis() -> Scene {
    free_spin(SPIN_HALF_EXTENTS, SPIN_ANGULAR_VELOCITY)
}

/// A free box of half-extents `half` in zero gravity spinning at `angular_velocity` (rad/s, world
/// frame = its own at the start). Bodies: box.
pub fn free_spin(half: Vec3, angular_velocity: Vec3) -> Scene {
    let mut block = dynamic(Shape::cuboid(half), Vec3::new(0.0, 2.0, 0.0), PALETTE[1]);
    block.desc.angular_velocity = angular_velocity;
    let name = if (half, angular_velocity) == (SPIN_HALF_EXTENTS, SPIN_ANGULAR_VELOCITY) {
        "intermediate axis".to_string()
    } else {
        format!("free spin {half} {angular_velocity}")
    };
    scene(
        name,
        Settings {
            gravity: Vec3::ZERO,
            ..Settings::default()
        },
        vec![block],
    )
}

/// Speed of the ball of [`bullet`], m/s along +x.
pub const BULLET_SPEED: f32 = 200.0;
/// Radius of the ball of [`bullet`], metres.
pub const BULLET_RADIUS: f32 = 0.1;
/// Thickness of the wall of [`bullet`] (centred on x = 0), metres.
pub const BULLET_WALL_THICKNESS: f32 = 0.1;

/// A 0.1 m ball flying at [`BULLET_SPEED`] towards a static wall [`BULLET_WALL_THICKNESS`] thick whose
/// mid-plane is x = 0. Bodies: wall, ball (starting at x = −4). At 1/60 s the ball moves 3.3 m per step,
/// so only continuous collision stops it.
pub fn bullet() -> Scene {
    let wall = SceneBody {
        name: None,
        frozen: false,
        desc: BodyDesc::fixed(
            Shape::cuboid(Vec3::new(0.5 * BULLET_WALL_THICKNESS, 3.0, 3.0)),
            Pose::IDENTITY,
        ),
        color: FLOOR_COLOR,
    };
    let mut ball = dynamic(
        Shape::sphere(BULLET_RADIUS),
        Vec3::new(-4.0, 0.0, 0.0),
        PALETTE[1],
    );
    ball.desc.linear_velocity = Vec3::new(BULLET_SPEED, 0.0, 0.0);
    scene("bullet".into(), Settings::default(), vec![wall, ball])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_with_base_20_has_210_boxes_and_a_floor() {
        assert_eq!(pyramid(20).bodies.len(), 211);
    }

    #[test]
    fn stack_boxes_touch_each_other_and_the_floor() {
        let scene = stack(10, Vec3::new(5000.0, 0.0, 5000.0));
        assert_eq!(scene.bodies.len(), 11);
        let floor_top = scene.bodies[0].desc.pose.position.y + 0.5;
        assert_eq!(floor_top, 0.0);
        for (i, body) in scene.bodies[1..].iter().enumerate() {
            assert_eq!(body.desc.pose.position.y, 0.5 + i as f32);
        }
    }

    #[test]
    fn ramp_box_sits_on_the_ramp_face() {
        let scene = ramp(0.3);
        let (ramp, block) = (&scene.bodies[0].desc.pose, &scene.bodies[1].desc.pose);
        let normal = ramp.rotation * Vec3::Y;
        let height = (block.position - ramp.position).dot(normal);
        assert!(
            (height - 1.0).abs() < 1e-5,
            "box centre {height} m above ramp centre"
        );
        assert!((normal.y - RAMP_ANGLE.cos()).abs() < 1e-6);
    }

    #[test]
    fn intermediate_axis_box_spins_about_its_middle_principal_axis() {
        let scene = intermediate_axis();
        let desc = &scene.bodies[0].desc;
        let inertia = desc.shape.principal_inertia(desc.mass);
        assert!(inertia.z < inertia.y && inertia.y < inertia.x);
        assert_eq!(scene.settings.gravity, Vec3::ZERO);
    }

    #[test]
    fn rain_holds_exactly_the_bodies_asked_for_plus_pit() {
        assert_eq!(rain(1000).bodies.len(), 1005);
        assert_eq!(rain(1000), rain(1000));
    }

    #[test]
    fn a_spread_rain_falls_in_one_layer_as_rain_1000_does() {
        let lowest_and_highest = |scene: &Scene| {
            let heights = scene.bodies[5..].iter().map(|b| b.desc.pose.position.y);
            heights.fold((f32::MAX, f32::MIN), |(lo, hi), y| (lo.min(y), hi.max(y)))
        };
        // One layer: the 2 m row, jittered by at most 8 cm.
        let one_layer = |(lo, hi): (f32, f32)| lo >= 1.92 && hi <= 2.08;
        assert!(one_layer(lowest_and_highest(&rain(1000))));
        assert!(one_layer(lowest_and_highest(&spread_rain(4000))));
        assert!(!one_layer(lowest_and_highest(&rain(4000))));
        assert_eq!(spread_rain(4000).bodies.len(), 4005);
        let mut same = spread_rain(1000);
        same.name = rain(1000).name;
        assert_eq!(same, rain(1000));
    }
}
