//! Bodies that start out overlapping separate gently, however many there are: the push-out speed
//! limit holds per body (`physics::push_out`), and bodies with one common centre, or each inside
//! the other, spread over the floor like a pile rather than up into a tower (`physics::coincident`). Default settings; overlaps measured from the poses
//! (`testing::penetration`), speeds from the bodies' velocities and from how far they moved per step.

use glam::{Quat, Vec3};
use nudge::geometry::{Pose, Shape};
use nudge::physics::{BodyDesc, Settings, World};
use nudge::testing::penetration::max_penetration;

/// No body may ever move faster, m/s (by its velocity, or by how far it moved in a step). The issue's
/// limits, all within 2× of what is measured, stay: here at most 4.5 m/s by displacement (the
/// position pass's push plus gravity; 4.55 m/s, 100 boxes) and 3.0 m/s by velocity.
const MAX_SPEED_MPS: f32 = 5.0;
/// No body may end farther from where it was spawned, m (measured at most 5.1 m, 50 boxes;
/// 8.4 m, 100 boxes and balls, whose balls roll on).
const MAX_DISTANCE_M: f32 = 10.0;
/// Deepest overlap between any two bodies, the floor included, after `SETTLE_S`, m (measured at most
/// 5.7 mm, 50 boxes; 7.9 mm, 100 boxes).
const MAX_OVERLAP_M: f32 = 0.01;
/// Simulated time the crowd gets to come apart, s.
const SETTLE_S: f32 = 5.0;

/// Where every body is spawned: half a metre above resting on the floor (y = 0).
const SPAWN: Vec3 = Vec3::new(0.0, 1.0, 0.0);

/// How the i-th body of a crowd is turned.
type Turn = dyn Fn(usize) -> Quat;

#[derive(Debug)]
struct Outcome {
    /// Fastest any body moved at any step, by velocity and by displacement over the step, m/s.
    max_velocity_mps: f32,
    max_step_speed_mps: f32,
    /// Farthest any body ended from `SPAWN`, m.
    max_distance_m: f32,
    /// Deepest overlap at the end, m.
    final_overlap_m: f32,
    /// Fastest any body moves at the end, m/s.
    final_speed_mps: f32,
    /// Highest any body's centre is at the end, m.
    final_height_m: f32,
}

/// `shapes` all spawned at `SPAWN` (turned by `turn(i)`), above a static floor under gravity or
/// floating without it, run for `SETTLE_S`.
fn crowd(shapes: &[Shape], turn: impl Fn(usize) -> Quat, gravity: bool) -> Outcome {
    let mut world = World::new(Settings {
        gravity: if gravity {
            Settings::default().gravity
        } else {
            Vec3::ZERO
        },
        ..Settings::default()
    });
    if gravity {
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(40.0, 0.5, 40.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ));
    }
    let first = world.len();
    for (i, &shape) in shapes.iter().enumerate() {
        world.add_body(BodyDesc::dynamic(shape, Pose::new(SPAWN, turn(i)), 1.0));
    }
    let dt = world.settings().dt;
    let mut previous: Vec<Vec3> = world.bodies().iter().map(|b| b.pose().position).collect();
    let (mut max_velocity_mps, mut max_step_speed_mps) = (0.0f32, 0.0f32);
    // NaN must fail: fold it in as infinity.
    let nan_is_inf = |x: f32| if x.is_nan() { f32::INFINITY } else { x };
    for _ in 0..(SETTLE_S / dt).round() as usize {
        world.step();
        for (body, before) in world.bodies().iter().zip(&mut previous) {
            let now = body.pose().position;
            max_velocity_mps = max_velocity_mps.max(nan_is_inf(body.linear_velocity().length()));
            max_step_speed_mps = max_step_speed_mps.max(nan_is_inf((now - *before).length() / dt));
            *before = now;
        }
    }
    let dynamic = &world.bodies()[first..];
    Outcome {
        max_velocity_mps,
        max_step_speed_mps,
        max_distance_m: dynamic
            .iter()
            .map(|b| nan_is_inf((b.pose().position - SPAWN).length()))
            .fold(0.0, f32::max),
        final_overlap_m: max_penetration(&world, true).0,
        final_speed_mps: dynamic
            .iter()
            .map(|b| nan_is_inf(b.linear_velocity().length()))
            .fold(0.0, f32::max),
        final_height_m: dynamic
            .iter()
            .map(|b| nan_is_inf(b.pose().position.y))
            .fold(f32::NEG_INFINITY, f32::max),
    }
}

fn assert_gentle(what: &str, out: &Outcome) {
    assert!(out.max_velocity_mps < MAX_SPEED_MPS, "{what}: {out:?}");
    assert!(out.max_step_speed_mps < MAX_SPEED_MPS, "{what}: {out:?}");
    assert!(out.max_distance_m < MAX_DISTANCE_M, "{what}: {out:?}");
    assert!(out.final_overlap_m < MAX_OVERLAP_M, "{what}: {out:?}");
}

#[test]
fn coincident_unit_boxes_above_a_floor_separate_gently_however_many_there_are() {
    for n in [2, 5, 20, 50] {
        let out = crowd(
            &vec![Shape::cuboid(Vec3::splat(0.5)); n],
            |_| Quat::IDENTITY,
            true,
        );
        assert_gentle(&format!("{n} boxes"), &out);
    }
}

/// Without gravity nothing but the push-out moves the bodies, so what they keep once apart is what
/// the push-out left as velocity: position-space push-out leaves none (the soft contact's own push,
/// a few tenths of a metre per second at most, is mostly taken back by the relax pass). Boxes turned
/// every which way (their faces do not agree, so pairs meet edge to edge and face to face) and
/// concentric balls.
#[test]
fn coincident_bodies_in_zero_gravity_come_apart_and_keep_almost_no_speed() {
    /// Fastest any body may still move after `SETTLE_S`, m/s (measured at most 0.47 m/s, 50 turned
    /// boxes).
    const MAX_FINAL_SPEED_MPS: f32 = 1.0;
    let turned =
        |i: usize| Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 0.37 * i as f32);
    for n in [2, 5, 20, 50] {
        for (what, shape) in [
            ("turned boxes", Shape::cuboid(Vec3::new(0.5, 0.3, 0.7))),
            ("balls", Shape::sphere(0.5)),
        ] {
            let out = crowd(&vec![shape; n], turned, false);
            let what = format!("{n} {what}");
            assert_gentle(&what, &out);
            assert!(out.final_speed_mps < MAX_FINAL_SPEED_MPS, "{what}: {out:?}");
        }
    }
}

/// Crowds of every size spread over the floor instead of building a tower: a body holding another's
/// centre is pushed apart from it across gravity (`physics::coincident`), not along whichever axis
/// their small offset happens to favour. 35 aligned boxes, millimetres apart after the first steps,
/// once sorted themselves into a column 3.4 box heights tall whose top box fell off at 5.8 m/s; 10
/// boxes each turned 0.37 rad about the vertical from the one before reached 8.6 m/s. Unit boxes
/// aligned and turned so, balls of the same size, and boxes and balls in turn (turned). Measured over
/// all 32 crowds: at most 2.96 m/s by velocity and 4.55 m/s by displacement (100 aligned boxes), at
/// most 8.4 m from the spawn (100 boxes and balls: balls roll on), overlap at most 7.9 mm after 5 s
/// (100 boxes); every crowd one layer high but for a ball on top (100 boxes and balls).
#[test]
fn crowds_of_any_size_above_a_floor_spread_out_instead_of_up() {
    /// Highest any body's centre may end, m: at most one body's height above the floor layer
    /// (measured at most 0.57 m, 100 turned boxes, where a box ends tilted on a neighbour; 1.19 m, 100
    /// boxes and balls, where a ball ends in a hollow on top).
    const MAX_HEIGHT_M: f32 = 1.5;
    let turned = |i: usize| Quat::from_rotation_y(0.37 * i as f32);
    let cube = Shape::cuboid(Vec3::splat(0.5));
    let ball = Shape::sphere(0.5);
    for n in [2, 3, 5, 10, 20, 35, 50, 100] {
        let mixed: Vec<Shape> = (0..n)
            .map(|i| if i % 2 == 0 { cube } else { ball })
            .collect();
        let cases: [(&str, Vec<Shape>, &Turn); 4] = [
            ("aligned boxes", vec![cube; n], &|_| Quat::IDENTITY),
            ("turned boxes", vec![cube; n], &turned),
            ("balls", vec![ball; n], &|_| Quat::IDENTITY),
            ("boxes and balls", mixed, &turned),
        ];
        for (what, shapes, turn) in cases {
            let out = crowd(&shapes, turn, true);
            assert_gentle(&format!("{n} {what}"), &out);
            assert!(out.final_height_m < MAX_HEIGHT_M, "{n} {what}: {out:?}");
        }
    }
}
