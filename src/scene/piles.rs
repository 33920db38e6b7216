//! Piles that must stay where they were built: what a user stacks in the sandbox (with `b`, by hand or
//! from a file) and expects to stand still, awake or asleep.
//!
//! Each pile starts resting, touching where it should touch (side faces flush, no gaps that hide
//! the contacts between neighbours), and is measured by `nudge bench rest`: kept awake, how far its
//! bodies move from where they settled and how fast they still move. The piles are the kinds the
//! sandbox's users build: pyramids (touching and spaced), columns, a crossed "jenga" tower, a brick
//! wall in a running bond, thin plates stacked flat, a big box on small balls, a mixed pile of
//! boxes and balls dropped into a pit, and a box held by friction on a 30° ramp.

use glam::{Quat, Vec3};

use super::builtin::BALL_ROLLING_RESISTANCE;
use super::cases::{self, UNIT_HALF, dynamic, floor};
use super::{Scene, SceneBody, framing};
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, Settings};
use crate::util::SplitMix64;

/// A pile and how long it needs before its rest is judged.
#[derive(Clone, Debug)]
pub struct Pile {
    pub scene: Scene,
    /// Seconds to let it settle (awake) before its positions are taken as where it rests: 0 for a
    /// pile built resting, a few seconds for one dropped into place.
    pub settle_s: f32,
    /// Whether it settles on past `settle_s` until it is still (`nudge bench rest` says how still):
    /// a pile dropped into place has landed only then. Not a pile built resting, which is judged
    /// from where it was built however it moves (a wall that falls in its first seconds and lies
    /// still must not count as resting).
    pub until_still: bool,
}

/// Seconds a pile built resting settles before its rest is judged (every pile of [`all`] but the
/// dropped heap).
pub const BUILT_SETTLE_S: f32 = 1.0;

/// Every pile, in the order `nudge bench rest` reports them.
pub fn all() -> Vec<Pile> {
    let built = |scene| Pile {
        scene,
        settle_s: BUILT_SETTLE_S,
        until_still: false,
    };
    vec![
        built(touching_pyramid(20)),
        built(cases::pyramid(20)),
        built(cases::stack(10, Vec3::ZERO)),
        built(cases::stack(30, Vec3::ZERO)),
        built(cases::stack(50, Vec3::ZERO)),
        built(crossed_tower(20)),
        built(running_bond_wall(12, 8)),
        built(brick_wall(12, 8)),
        built(plates(10)),
        built(box_on_balls()),
        Pile {
            scene: mixed_pile(40),
            settle_s: 5.0,
            until_still: true,
        },
        built(box_on_ramp()),
    ]
}

/// The piles of [`all`] whose name contains `part`, in any case (`nudge bench rest --pile`).
pub fn containing(part: &str) -> Vec<Pile> {
    let part = part.to_lowercase();
    all()
        .into_iter()
        .filter(|p| p.scene.name.to_lowercase().contains(&part))
        .collect()
}

fn scene(name: String, bodies: Vec<SceneBody>) -> Scene {
    Scene {
        name,
        settings: Settings::default(),
        camera: framing::auto_camera(&bodies, framing::DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

fn cuboid(half: Vec3, position: Vec3, colour_index: usize) -> SceneBody {
    dynamic(
        Shape::cuboid(half),
        position,
        PALETTE[colour_index % PALETTE.len()],
    )
}

/// [`cases::pyramid`] with each box's side faces flush against its neighbours' (no 5 cm gaps): every
/// row is a run of touching boxes, as a user builds one.
pub fn touching_pyramid(base: usize) -> Scene {
    let mut bodies = vec![floor(40.0)];
    for row in 0..base {
        let count = base - row;
        let x0 = -0.5 * (count as f32 - 1.0);
        for i in 0..count {
            let position = Vec3::new(x0 + i as f32, UNIT_HALF + row as f32, 0.0);
            bodies.push(cuboid(Vec3::splat(UNIT_HALF), position, row + i));
        }
    }
    scene(format!("touching pyramid({base})"), bodies)
}

/// Half-extents of a block of [`crossed_tower`]: 3 m long, 0.5 m wide, 0.3 m high.
pub const TOWER_BLOCK_HALF: Vec3 = Vec3::new(1.5, 0.15, 0.25);

/// `layers` layers of two long blocks each, every layer turned 90° from the one below (the jenga
/// pattern), the two blocks of a layer 2 m apart so each crosses the layer below near its ends.
pub fn crossed_tower(layers: usize) -> Scene {
    let mut bodies = vec![floor(20.0)];
    let h = TOWER_BLOCK_HALF;
    for layer in 0..layers {
        let y = h.y * (1.0 + 2.0 * layer as f32);
        for side in [-1.0, 1.0] {
            let (half, position) = if layer % 2 == 0 {
                (h, Vec3::new(0.0, y, side))
            } else {
                (Vec3::new(h.z, h.y, h.x), Vec3::new(side, y, 0.0))
            };
            bodies.push(cuboid(half, position, layer));
        }
    }
    scene(format!("crossed tower({layers})"), bodies)
}

/// Half-extents of a brick of [`running_bond_wall`]: 0.4 × 0.2 × 0.2 m.
pub const BRICK_HALF: Vec3 = Vec3::new(0.2, 0.1, 0.1);

/// Half-extents of a real brick (215 × 102.5 × 65 mm, laid on its bed face) for [`brick_wall`].
pub const REAL_BRICK_HALF: Vec3 = Vec3::new(0.1075, 0.0325, 0.05125);

/// Density of a clay brick, kg/m³ (2.3 kg for one of [`REAL_BRICK_HALF`]).
pub const REAL_BRICK_DENSITY: f32 = 1600.0;

/// [`running_bond_wall`] built to scale: real bricks ([`REAL_BRICK_HALF`], [`REAL_BRICK_DENSITY`]),
/// a wall 78 cm high and 10 cm thick at 12 courses, more slender than one of [`BRICK_HALF`] bricks
/// (2.4 m and 20 cm), and heavy enough that the 20 g ball `nudge bench rest` drops on it only
/// wakes it.
pub fn brick_wall(courses: usize, bricks: usize) -> Scene {
    let mut scene = running_bond_wall_of(courses, bricks, REAL_BRICK_HALF);
    for body in scene.bodies.iter_mut().filter(|b| !b.desc.is_static) {
        body.desc.mass *= REAL_BRICK_DENSITY;
    }
    scene.name = format!("brick wall({courses}), 215 × 102.5 × 65 mm");
    scene
}

/// A wall `courses` bricks high laid in a running bond: `bricks` bricks end to end in the even
/// courses, and in the odd ones `bricks − 1` shifted by half a brick, each over a joint below.
pub fn running_bond_wall(courses: usize, bricks: usize) -> Scene {
    running_bond_wall_of(courses, bricks, BRICK_HALF)
}

/// [`running_bond_wall`] of bricks with half-extents `h`.
pub fn running_bond_wall_of(courses: usize, bricks: usize, h: Vec3) -> Scene {
    let mut bodies = vec![floor(20.0)];
    for course in 0..courses {
        let y = h.y * (1.0 + 2.0 * course as f32);
        let (count, offset) = if course % 2 == 0 {
            (bricks, 0.0)
        } else {
            (bricks - 1, h.x)
        };
        let x0 = -h.x * (bricks as f32 - 1.0) + offset;
        for i in 0..count {
            let position = Vec3::new(x0 + 2.0 * h.x * i as f32, y, 0.0);
            bodies.push(cuboid(h, position, course + i));
        }
    }
    scene(format!("running bond wall({courses})"), bodies)
}

/// Half-extents of a plate of [`plates`]: 1 m square, 2 cm thick.
pub const PLATE_HALF: Vec3 = Vec3::new(0.5, 0.01, 0.5);

/// `count` thin plates stacked flat, each resting on the one below.
pub fn plates(count: usize) -> Scene {
    let mut bodies = vec![floor(10.0)];
    for i in 0..count {
        let position = Vec3::new(0.0, PLATE_HALF.y * (1.0 + 2.0 * i as f32), 0.0);
        bodies.push(cuboid(PLATE_HALF, position, i));
    }
    scene(format!("plates({count})"), bodies)
}

/// Radius of the balls of [`box_on_balls`], m.
pub const SMALL_BALL_RADIUS: f32 = 0.1;

/// A 4 m × 0.5 m × 4 m box resting on four 0.1 m balls near its corners, on a level floor: the
/// balls can roll, so only friction that is exactly balanced keeps the box where it is.
pub fn box_on_balls() -> Scene {
    let r = SMALL_BALL_RADIUS;
    let mut bodies = vec![floor(20.0)];
    for (i, (x, z)) in [(-1.5, -1.5), (1.5, -1.5), (-1.5, 1.5), (1.5, 1.5)]
        .into_iter()
        .enumerate()
    {
        bodies.push(dynamic(
            Shape::sphere(r),
            Vec3::new(x, r, z),
            PALETTE[i % PALETTE.len()],
        ));
    }
    let half = Vec3::new(2.0, 0.25, 2.0);
    bodies.push(cuboid(half, Vec3::new(0.0, 2.0 * r + half.y, 0.0), 4));
    scene("box on balls".to_string(), bodies)
}

/// `count` boxes and balls (half-size 0.25 m) dropped in a jittered grid into a 4 m square pit with
/// walls: a heap that comes to rest where it lands. Deterministic for a given count. The balls
/// resist rolling as the sandbox's do ([`BALL_ROLLING_RESISTANCE`]): without it a ball set rolling
/// as the heap lands has no rest to come to, and rolled on at 1 cm/s for the whole minute.
///
/// Its bodies weigh what their volume does (125 g a box, 65 g a ball), so the 20 g ball `nudge
/// bench rest` drops on it is a sixth of the box it strikes, not a tap: struck at 3.1 m/s, that box
/// leaves at 75–136 mm/s and slides 1.1–1.2 mm before friction stops it, and its column is
/// pressed into its supports' slop band (2.3 mm at 2 sub-steps), where a heap's indeterminate
/// supports do not push it back (`solve::wide_contacts::velocity`, "No push inside the band"). The
/// heap's woken rows that miss 1 mm are these. Woken with no ball, every copy moves under 0.07 mm
/// at 2 and 4 sub-steps (measured 2026-12-02). The 18 mm copy at 4 sub-steps is the dropped ball
/// rolling off its box's tilted top 8.5 s after the drop and striking a ball on the floor.
pub fn mixed_pile(count: usize) -> Scene {
    let pit_half = 2.0;
    let mut bodies = vec![floor(10.0)];
    for (half, center) in [
        (
            Vec3::new(0.1, 1.0, pit_half),
            Vec3::new(-pit_half - 0.1, 1.0, 0.0),
        ),
        (
            Vec3::new(0.1, 1.0, pit_half),
            Vec3::new(pit_half + 0.1, 1.0, 0.0),
        ),
        (
            Vec3::new(pit_half, 1.0, 0.1),
            Vec3::new(0.0, 1.0, -pit_half - 0.1),
        ),
        (
            Vec3::new(pit_half, 1.0, 0.1),
            Vec3::new(0.0, 1.0, pit_half + 0.1),
        ),
    ] {
        bodies.push(SceneBody::new(
            BodyDesc::fixed(Shape::cuboid(half), Pose::from_position(center)),
            FLOOR_COLOR,
        ));
    }
    let mut rng = SplitMix64(0x7069_6c65);
    let (per_row, spacing) = (4, 0.9);
    for i in 0..count {
        let layer = i / (per_row * per_row);
        let (row, col) = ((i / per_row) % per_row, i % per_row);
        let jitter = Vec3::new(rng.next_signed(), 0.0, rng.next_signed()) * 0.05;
        let position = Vec3::new(
            spacing * (col as f32 - 1.5),
            0.5 + spacing * layer as f32,
            spacing * (row as f32 - 1.5),
        ) + jitter;
        let shape = if i % 2 == 0 {
            Shape::cuboid(Vec3::splat(0.25))
        } else {
            Shape::sphere(0.25)
        };
        let mut body = dynamic(shape, position, PALETTE[i % PALETTE.len()]);
        if i % 2 == 1 {
            body.desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
        }
        let axis = Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed())
            .try_normalize()
            .unwrap_or(Vec3::Y);
        body.desc.pose.rotation = Quat::from_axis_angle(axis, rng.next_signed());
        bodies.push(body);
    }
    scene(format!("mixed pile({count})"), bodies)
}

/// Friction of [`box_on_ramp`]'s box and ramp: 0.8, over tan 30° ≈ 0.58, so the box holds.
pub const RAMP_HOLD_FRICTION: f32 = 0.8;

/// A unit box resting on a 30° ramp whose friction holds it ([`cases::ramp`] at μ = 0.8).
pub fn box_on_ramp() -> Scene {
    let mut scene = cases::ramp(RAMP_HOLD_FRICTION);
    scene.name = "box on a 30° ramp".to_string();
    scene
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::World;

    /// Every pile starts with its bodies touching, not overlapping: the deepest overlap the first
    /// step finds is within the slop (the dropped mixed pile starts apart).
    #[test]
    fn every_pile_is_built_touching_and_not_overlapping() {
        for pile in all() {
            let mut world: World = pile.scene.build_world();
            world.step();
            assert!(
                world.max_penetration() <= world.settings().linear_slop,
                "{}: {} m",
                pile.scene.name,
                world.max_penetration()
            );
        }
    }

    #[test]
    fn the_touching_pyramid_has_210_boxes_flush_side_by_side() {
        let scene = touching_pyramid(20);
        assert_eq!(scene.bodies.len(), 211);
        let x = |i: usize| scene.bodies[i].desc.pose.position.x;
        assert_eq!(x(2) - x(1), 2.0 * UNIT_HALF);
        assert_eq!(cases::unit_box(), scene.bodies[1].desc.shape);
    }
}
