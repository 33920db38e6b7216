//! Joints against their analytic answers: pendulum periods, a double pendulum's energy, a chain
//! under a heavy load, limits, motors, welds, sliders, ropes and springs; and that a joint sleeps,
//! wakes, restores and replays with its bodies.

use std::f32::consts::PI;

use glam::{Quat, Vec3};
use nudge::geometry::{Pose, Shape};
use nudge::physics::{BodyDesc, BodyId, JointDesc, JointKind, Motor, Settings, Spring, World};
use nudge::scene::cases;
use nudge::testing::corpus;
use nudge::testing::hard_case::{Fixes, Knobs};

use crate::common::joints::{all_finite, widest_joint};

fn world(sleep: bool) -> World {
    World::new(Settings {
        sleep,
        ..Settings::default()
    })
}

fn ball(world: &mut World, position: Vec3, radius: f32, mass: f32) -> BodyId {
    world.add_body(BodyDesc::dynamic(
        Shape::sphere(radius),
        Pose::from_position(position),
        mass,
    ))
}

fn pose(world: &World, id: BodyId) -> Pose {
    *world.body(id).pose()
}

fn joint(
    world: &mut World,
    kind: JointKind,
    a: Option<BodyId>,
    b: BodyId,
    anchor: Vec3,
    axis: Vec3,
) {
    let desc = JointDesc::at(
        kind,
        a.map(|a| (a, pose(world, a))),
        (b, pose(world, b)),
        anchor,
        anchor,
        axis,
        false,
    );
    world.add_joint(desc).unwrap();
}

fn rod(world: &mut World, a: Option<BodyId>, b: BodyId, anchor_a: Vec3, anchor_b: Vec3) {
    let length = anchor_a.distance(anchor_b);
    distance(world, a, b, (anchor_a, anchor_b), (length, length));
}

/// A rope from the world at `anchor` to `b` at `at`, at most `max` long.
fn rope(world: &mut World, b: BodyId, anchor: Vec3, at: Vec3, max: f32) {
    distance(world, None, b, (anchor, at), (0.0, max));
}

/// A distance joint of length `max` between `min` and `max`, no spring.
fn distance(
    world: &mut World,
    a: Option<BodyId>,
    b: BodyId,
    (anchor_a, anchor_b): (Vec3, Vec3),
    (min, max): (f32, f32),
) {
    let desc = JointDesc::at(
        JointKind::Distance {
            length: max,
            min,
            max,
            spring: None,
        },
        a.map(|a| (a, pose(world, a))),
        (b, pose(world, b)),
        anchor_a,
        anchor_b,
        Vec3::Y,
        false,
    );
    world.add_joint(desc).unwrap();
}

/// The period of a pendulum of length `length` released `amplitude` radians from the vertical,
/// measured over its first swings: mean time between successive crossings of the vertical, twice.
fn pendulum_period(amplitude: f32, length: f32) -> f32 {
    let mut w = world(false);
    let pivot = Vec3::new(0.0, 5.0, 0.0);
    let bob = pivot + length * Vec3::new(amplitude.sin(), -amplitude.cos(), 0.0);
    let b = ball(&mut w, bob, 0.02, 1.0);
    rod(&mut w, None, b, pivot, bob);
    let dt = w.settings().dt;
    let mut crossings = Vec::new();
    let mut last = w.body(b).pose().position.x;
    for step in 1..=2000 {
        w.step();
        let x = w.body(b).pose().position.x;
        if last.signum() != x.signum() && x != 0.0 {
            // Linear interpolation of the crossing time within the step.
            let t = (step as f32 - 1.0 + last / (last - x)) * dt;
            crossings.push(t);
        }
        last = x;
    }
    let n = crossings.len();
    assert!(n >= 5, "only {n} crossings");
    2.0 * (crossings[n - 1] - crossings[0]) / (n - 1) as f32
}

/// K(k), the complete elliptic integral of the first kind, by the arithmetic–geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut g) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, g) = (0.5 * (a + g), (a * g).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

#[test]
fn a_small_swing_keeps_the_pendulum_period() {
    let (l, g) = (1.0f32, 9.81f32);
    let period = pendulum_period(5f32.to_radians(), l);
    let expected = 2.0 * PI * (l / g).sqrt();
    let error = (period - expected).abs() / expected;
    println!("5°: {period} s vs {expected} s ({:.3} %)", error * 100.0);
    assert!(error < 0.003, "{period} vs {expected}");
}

#[test]
fn a_ninety_degree_swing_keeps_the_elliptic_period() {
    let (l, g) = (1.0f64, 9.81f64);
    let period = pendulum_period(90f32.to_radians(), l as f32) as f64;
    let expected = 4.0 * (l / g).sqrt() * elliptic_k((45f64).to_radians().sin());
    let error = (period - expected).abs() / expected;
    println!("90°: {period} s vs {expected} s ({:.3} %)", error * 100.0);
    assert!(error < 0.003, "{period} vs {expected}");
}

/// A chain of 20 ball-jointed links, 10 cm each, hung from the world at `top`, holding a load 100
/// times a link; released `angle` radians from the vertical. Returns the world, the load and the
/// chain's length to the load's centre.
fn loaded_chain(angle: f32) -> (World, BodyId, f32, Vec3) {
    let mut w = world(false);
    let links = 20;
    let (link, radius, link_mass) = (0.1f32, 0.04f32, 0.1f32);
    let top = Vec3::new(0.0, 4.0, 0.0);
    let down = Vec3::new(angle.sin(), -angle.cos(), 0.0);
    let mut previous = None;
    for i in 0..links {
        let centre = top + down * (link * (i as f32 + 0.5));
        let id = ball(&mut w, centre, radius, link_mass);
        joint(
            &mut w,
            JointKind::Ball,
            previous,
            id,
            top + down * (link * i as f32),
            Vec3::Y,
        );
        previous = Some(id);
    }
    let end = top + down * (link * links as f32);
    let load = ball(&mut w, end + down * 0.2, 0.2, 100.0 * link_mass);
    joint(&mut w, JointKind::Ball, previous, load, end, Vec3::Y);
    (w, load, link * links as f32 + 0.2, top)
}

/// The loaded chain's stretch hanging at rest and its speed there, its worst stretch swinging
/// from 30° and its widest joint then, m and m/s, over 10 s each; and the chain's length, m.
fn loaded_chain_outcome(tree: bool) -> ([f32; 4], f32) {
    let (mut w, load, length, top) = loaded_chain(0.0);
    w.settings_mut().joint_tree = tree;
    for _ in 0..600 {
        w.step();
    }
    let hanging = top.distance(w.body(load).pose().position) - length;
    let speed = w.body(load).linear_velocity().length();
    let (mut w, load, length, top) = loaded_chain(30f32.to_radians());
    w.settings_mut().joint_tree = tree;
    let (mut stretch, mut gap) = (0.0f32, 0.0f32);
    for _ in 0..600 {
        w.step();
        stretch = stretch.max(top.distance(w.body(load).pose().position) - length);
        for j in w.joints() {
            let (a, b) = w.joint_anchors(j);
            gap = gap.max(a.distance(b));
        }
    }
    ([hanging, speed, stretch, gap], length)
}

/// Hanging: no stretch and no jitter; swinging from 30°: it never stretches by 1 %, and no joint
/// opens by 0.1 mm. Solved by Gauss–Seidel alone, every row sees a link's mass, each sweep moves
/// the load by a link's share of its error, and the chain hangs stretched by what its soft rows
/// give under the load.
#[test]
fn a_chain_holds_a_load_a_hundred_times_a_link_only_with_the_exact_tree() {
    let ([hanging, speed, stretch, gap], length) = loaded_chain_outcome(true);
    println!(
        "tree: hanging stretch {hanging} m at {speed} m/s; swinging: worst stretch {stretch} m, \
         widest joint {gap} m"
    );
    assert!(
        hanging.abs() < 1e-4 * length,
        "stretch {hanging} m of {length} m"
    );
    assert!(speed < 1e-4, "still moving at {speed} m/s");
    assert!(stretch < 0.01 * length, "stretch {stretch} m of {length} m");
    assert!(gap < 1e-4, "a joint opened {gap} m");

    let ([hanging, speed, stretch, gap], length) = loaded_chain_outcome(false);
    println!(
        "Gauss–Seidel: hanging stretch {hanging} m at {speed} m/s; swinging: worst stretch \
         {stretch} m, widest joint {gap} m"
    );
    // Measured 2026-12-03: 13 % hanging (still swaying at 0.15 m/s), 25 % swinging, a joint
    // open 29 mm.
    assert!(hanging > 0.05 * length, "stretch {hanging} m of {length} m");
    assert!(stretch > 0.1 * length, "stretch {stretch} m of {length} m");
}

#[test]
fn a_double_pendulum_keeps_its_energy() {
    let mut w = World::new(Settings {
        sleep: false,
        ..Settings::default()
    });
    let pivot = Vec3::new(0.0, 5.0, 0.0);
    let (p1, p2) = (pivot + Vec3::X, pivot + 2.0 * Vec3::X);
    let a = ball(&mut w, p1, 0.02, 1.0);
    let b = ball(&mut w, p2, 0.02, 1.0);
    rod(&mut w, None, a, pivot, p1);
    rod(&mut w, Some(a), b, p1, p2);
    let energy = |w: &World| {
        [a, b]
            .iter()
            .map(|&id| {
                let body = w.body(id);
                let m = body.mass();
                0.5 * m * body.linear_velocity().length_squared()
                    + m * 9.81 * body.pose().position.y
            })
            .sum::<f32>()
    };
    let start = energy(&w);
    let mut worst = 0.0f32;
    for _ in 0..1200 {
        w.step();
        worst = worst.max((energy(&w) - start).abs());
    }
    // Relative to the energy that moves: the drop from horizontal to hanging, 3·m·g·L·... = 4 m g.
    let scale = 1.0 * 9.81 * (1.0 + 2.0);
    println!("double pendulum: worst energy error {worst} J of {scale} J");
    assert!(worst < 0.01 * scale, "{worst} J");
}

#[test]
fn a_hinge_limit_holds_an_arm() {
    let mut w = world(false);
    let arm = w.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)),
        Pose::from_position(Vec3::new(0.5, 3.0, 0.0)),
        10.0,
    ));
    let limits = [-30f32.to_radians(), 30f32.to_radians()];
    joint(
        &mut w,
        JointKind::Hinge {
            limits: Some(limits),
            motor: None,
        },
        None,
        arm,
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::Z,
    );
    for _ in 0..600 {
        w.step();
    }
    let q = w.body(arm).pose().rotation;
    let (axis, angle) = q.to_axis_angle();
    let angle = angle * axis.z.signum();
    println!("hinge at {}°", angle.to_degrees());
    assert!(
        (angle - limits[0]).abs() < 0.5f32.to_radians(),
        "{}°",
        angle.to_degrees()
    );
    // The anchor stayed put.
    let tip = w.body(arm).pose().position + q * Vec3::new(-0.5, 0.0, 0.0);
    assert!(tip.distance(Vec3::new(0.0, 3.0, 0.0)) < 1e-3, "{tip}");
}

#[test]
fn a_hinge_motor_reaches_its_speed_under_its_torque_and_stalls_over_it() {
    for (max, reaches) in [(50.0, true), (2.0, false)] {
        let mut w = world(false);
        // A 1 kg arm 1 m long: gravity's torque about the hinge is at most 4.9 N·m.
        let arm = w.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)),
            Pose::from_position(Vec3::new(0.5, 3.0, 0.0)),
            1.0,
        ));
        joint(
            &mut w,
            JointKind::Hinge {
                limits: None,
                motor: Some(Motor { speed: 1.0, max }),
            },
            None,
            arm,
            Vec3::new(0.0, 3.0, 0.0),
            Vec3::Z,
        );
        for _ in 0..30 {
            w.step();
        }
        let spin = w.body(arm).angular_velocity().z;
        println!("motor max {max}: spin {spin}");
        if reaches {
            assert!((spin - 1.0).abs() < 0.01, "{spin}");
        } else {
            assert!(spin < 0.5, "{spin}");
        }
    }
}

#[test]
fn a_weld_holds_a_cantilever() {
    let mut w = world(false);
    let beam = w.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)),
        Pose::from_position(Vec3::new(0.5, 3.0, 0.0)),
        5.0,
    ));
    joint(
        &mut w,
        JointKind::Fixed,
        None,
        beam,
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::Y,
    );
    for _ in 0..300 {
        w.step();
    }
    let p = w.body(beam).pose();
    let tilt = p.rotation.angle_between(Quat::IDENTITY);
    println!(
        "weld: sag {} m, tilt {}°",
        3.0 - p.position.y,
        tilt.to_degrees()
    );
    assert!(p.position.distance(Vec3::new(0.5, 3.0, 0.0)) < 2e-3);
    assert!(tilt < 0.5f32.to_radians());
}

#[test]
fn a_slider_moves_along_its_axis_to_its_limit() {
    let mut w = world(false);
    let block = w.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::splat(0.1)),
        Pose::from_position(Vec3::new(0.0, 3.0, 0.0)),
        1.0,
    ));
    // A rail sloping down along +x at 45°: the block slides 0.5 m to the limit and stops.
    let axis = Vec3::new(1.0, -1.0, 0.0).normalize();
    joint(
        &mut w,
        JointKind::Slider {
            limits: Some([0.0, 0.5]),
            motor: None,
        },
        None,
        block,
        Vec3::new(0.0, 3.0, 0.0),
        axis,
    );
    for _ in 0..300 {
        w.step();
    }
    let p = w.body(block).pose();
    let travel = (p.position - Vec3::new(0.0, 3.0, 0.0)).dot(axis);
    let off_axis = (p.position - Vec3::new(0.0, 3.0, 0.0) - axis * travel).length();
    println!("slider travel {travel} m, off axis {off_axis} m");
    assert!((travel - 0.5).abs() < 2e-3, "{travel}");
    assert!(off_axis < 1e-3, "{off_axis}");
    assert!(p.rotation.angle_between(Quat::IDENTITY) < 1e-3);
}

#[test]
fn a_rope_goes_slack_and_a_spring_oscillates_at_its_frequency() {
    // Rope: a ball dropped from beside the anchor falls freely until the rope is taut.
    let mut w = world(false);
    let b = ball(&mut w, Vec3::new(0.0, 5.0, 0.0), 0.05, 1.0);
    let anchor = Vec3::new(0.0, 5.0, 0.0);
    rope(&mut w, b, anchor, anchor, 1.0);
    for _ in 0..20 {
        w.step();
    }
    let free_fall = 0.5 * 9.81 * (20.0f32 / 60.0).powi(2);
    let fallen = 5.0 - w.body(b).pose().position.y;
    assert!((fallen - free_fall).abs() < 0.01, "{fallen} vs {free_fall}");
    for _ in 0..300 {
        w.step();
    }
    let hang = 5.0 - w.body(b).pose().position.y;
    assert!(hang <= 1.001 && hang > 0.99, "{hang}");

    // Spring: 2 Hz, undamped, sideways (no gravity along it): the period is 0.5 s.
    let mut w = World::new(Settings {
        sleep: false,
        gravity: Vec3::ZERO,
        ..Settings::default()
    });
    let b = ball(&mut w, Vec3::new(1.2, 0.0, 0.0), 0.05, 1.0);
    let spring = JointDesc::at(
        JointKind::Distance {
            length: 1.0,
            min: 0.0,
            max: 10.0,
            spring: Some(Spring {
                hertz: 2.0,
                damping_ratio: 0.0,
            }),
        },
        None,
        (b, pose(&w, b)),
        Vec3::ZERO,
        Vec3::new(1.2, 0.0, 0.0),
        Vec3::Y,
        false,
    );
    w.add_joint(spring).unwrap();
    let mut last = w.body(b).pose().position.x - 1.0;
    let mut crossings = Vec::new();
    for step in 1..=300 {
        w.step();
        let x = w.body(b).pose().position.x - 1.0;
        if last.signum() != x.signum() {
            crossings.push((step as f32 - 1.0 + last / (last - x)) / 60.0);
        }
        last = x;
    }
    let n = crossings.len();
    let period = 2.0 * (crossings[n - 1] - crossings[0]) / (n - 1) as f32;
    println!("spring period {period} s");
    assert!((period - 0.5).abs() < 0.01, "{period}");
}

#[test]
fn jointed_bodies_do_not_collide_unless_asked() {
    for collide in [false, true] {
        let mut w = world(false);
        let a = ball(&mut w, Vec3::new(0.0, 3.0, 0.0), 0.5, 1.0);
        let b = ball(&mut w, Vec3::new(0.6, 3.0, 0.0), 0.5, 1.0);
        w.set_gravity(Vec3::ZERO);
        let desc = JointDesc::at(
            JointKind::Ball,
            Some((a, pose(&w, a))),
            (b, pose(&w, b)),
            Vec3::new(0.3, 3.0, 0.0),
            Vec3::new(0.3, 3.0, 0.0),
            Vec3::Y,
            collide,
        );
        w.add_joint(desc).unwrap();
        w.step();
        assert_eq!(
            w.contact_count(),
            usize::from(collide),
            "collide = {collide}"
        );
    }
}

#[test]
fn a_pendulum_sleeps_with_its_island_and_wakes_with_it() {
    let mut w = world(true);
    w.add_body(BodyDesc::fixed(
        Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)),
        Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
    ));
    // Two balls on a rod, at rest on the floor: they sleep together.
    let a = ball(&mut w, Vec3::new(0.0, 0.2, 0.0), 0.2, 1.0);
    let b = ball(&mut w, Vec3::new(1.0, 0.2, 0.0), 0.2, 1.0);
    rod(
        &mut w,
        Some(a),
        b,
        Vec3::new(0.0, 0.2, 0.0),
        Vec3::new(1.0, 0.2, 0.0),
    );
    for _ in 0..120 {
        w.step();
    }
    assert_eq!(w.awake_count(), 0);
    // A push on one along the rod wakes the other and moves it.
    w.apply_impulse_at_point(a, Vec3::new(-1.0, 0.0, 0.0), Vec3::new(0.0, 0.2, 0.0));
    w.step();
    assert_eq!(w.awake_count(), 2);
    assert!(w.body(b).linear_velocity().length() > 0.1);
}

#[test]
fn a_jointed_world_restores_bit_for_bit() {
    let mut w = world(false);
    let pivot = Vec3::new(0.0, 5.0, 0.0);
    let a = ball(&mut w, pivot + Vec3::X, 0.05, 1.0);
    let b = ball(&mut w, pivot + 2.0 * Vec3::X, 0.05, 1.0);
    joint(&mut w, JointKind::Ball, None, a, pivot, Vec3::Y);
    joint(
        &mut w,
        JointKind::Ball,
        Some(a),
        b,
        pivot + Vec3::X * 1.5,
        Vec3::Y,
    );
    for _ in 0..30 {
        w.step();
    }
    let snapshot = w.snapshot();
    for _ in 0..60 {
        w.step();
    }
    let end = w.snapshot();
    w.restore(&snapshot);
    for _ in 0..60 {
        w.step();
    }
    assert_eq!(w.snapshot().first_difference(&end), None);
    // Into a fresh world too: a step starts from the tree's factorisation and rows of the last
    // one when its poses and masses are the same to the bit, and must step as one that computes
    // them afresh.
    let mut fresh = world(false);
    fresh.restore(&snapshot);
    for _ in 0..60 {
        fresh.step();
    }
    assert_eq!(fresh.snapshot().first_difference(&end), None);
}

#[test]
fn bad_joints_are_refused() {
    let mut w = world(false);
    let a = ball(&mut w, Vec3::ZERO, 0.1, 1.0);
    let desc = |kind| {
        JointDesc::at(
            kind,
            Some((a, Pose::IDENTITY)),
            (a, Pose::IDENTITY),
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::Y,
            false,
        )
    };
    assert!(w.add_joint(desc(JointKind::Ball)).is_err());
    let mut other = desc(JointKind::Ball);
    other.a = None;
    other.b = BodyId(7);
    assert!(w.add_joint(other).is_err());
    let mut bad_limits = desc(JointKind::Hinge {
        limits: Some([1.0, -1.0]),
        motor: None,
    });
    bad_limits.a = None;
    assert!(w.add_joint(bad_limits).is_err());
    let mut negative = desc(JointKind::Distance {
        length: -1.0,
        min: 0.0,
        max: 1.0,
        spring: None,
    });
    negative.a = None;
    assert!(w.add_joint(negative).is_err());
    // Friction: never negative, and only where a joint has a free axis to resist.
    let mut ball_joint = desc(JointKind::Ball);
    ball_joint.a = None;
    assert!(w.add_joint(ball_joint.with_friction(-1.0)).is_err());
    let mut weld = desc(JointKind::Fixed);
    weld.a = None;
    assert!(w.add_joint(weld.with_friction(1.0)).is_err());
    assert!(w.add_joint(ball_joint.with_friction(1.0)).is_ok());
}

#[test]
fn a_journal_with_joints_replays_bit_for_bit() {
    let mut w = world(true);
    w.start_journal();
    let pivot = Vec3::new(0.0, 3.0, 0.0);
    let a = ball(&mut w, pivot + Vec3::X, 0.1, 1.0);
    joint(&mut w, JointKind::Ball, None, a, pivot, Vec3::Y);
    for _ in 0..20 {
        w.step();
    }
    // A second link added mid-swing, with a hinge.
    let b = ball(&mut w, pivot + Vec3::X * 1.5, 0.1, 0.5);
    joint(
        &mut w,
        JointKind::Hinge {
            limits: Some([-0.5, 0.5]),
            motor: Some(Motor {
                speed: 1.0,
                max: 0.5,
            }),
        },
        Some(a),
        b,
        pivot + Vec3::X * 1.25,
        Vec3::Z,
    );
    for _ in 0..100 {
        w.step();
    }
    let journal = w.take_journal();
    let mut replay = world(true);
    let mut k = 0;
    for step in 0..120u64 {
        while k < journal.len() && journal[k].0 == step {
            replay.apply_input(&journal[k].1, &[]).unwrap();
            k += 1;
        }
        replay.step();
    }
    assert_eq!(replay.snapshot().first_difference(&w.snapshot()), None);
}

/// A chain of 20 hinges about alternate axes (as a chain's links turn) holding a 50 kg ball,
/// released 50° from the vertical onto a floor it rolls along: it swings on without a joint
/// opening by 1 cm (the bound for a ragdoll; measured 6.9 mm, as the ball lands) or
/// anything flying off (1.5 m/s at most over the last 10 s). The hinges' warm start once applied
/// their whole stored torque, its part along the (since turned) free axis too: energy every
/// sub-step, and this chain whipped itself apart after 10 s at 300 m/s.
#[test]
fn a_hinged_chain_under_a_heavy_ball_swings_without_coming_apart() {
    let mut w = world(false);
    w.add_body(BodyDesc::fixed(
        Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)),
        Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
    ));
    let angle = 50f32.to_radians();
    let down = Vec3::new(-angle.sin(), -angle.cos(), 0.0);
    let (links, link, radius) = (20, 0.3f32, 0.6f32);
    let pivot = Vec3::new(0.0, link * links as f32 + 2.0 * radius - 0.15, 0.0);
    let mut previous = None;
    for i in 0..=links {
        let (r, mass, reach) = if i == links {
            (radius, 50.0, link * i as f32 + radius)
        } else {
            (0.12, 0.5, link * (i as f32 + 0.5))
        };
        let id = ball(&mut w, pivot + down * reach, r, mass);
        let axis = if i % 2 == 0 {
            Vec3::Z
        } else {
            down.cross(Vec3::Z)
        };
        let hinge = JointKind::Hinge {
            limits: None,
            motor: None,
        };
        joint(
            &mut w,
            hinge,
            previous,
            id,
            pivot + down * (link * i as f32),
            axis,
        );
        previous = Some(id);
    }
    let (mut widest, mut fastest) = (0.0f32, 0.0f32);
    for step in 0..1800 {
        w.step();
        for j in w.joints() {
            let (a, b) = w.joint_anchors(j);
            widest = widest.max(a.distance(b));
        }
        if step >= 1200 {
            for body in w.bodies() {
                fastest = fastest.max(body.linear_velocity().length());
            }
        }
    }
    println!("hinged chain: widest joint {widest} m, fastest over the last 10 s {fastest} m/s");
    assert!(widest < 0.01, "a joint opened {widest} m");
    assert!(fastest < 5.0, "whipping at {fastest} m/s");
}

/// A joint's load is its impulses over the sub-step they act in: a 1 kg ball hung from a ball joint
/// feels its weight up, and one on a rod from a pivot above is pulled by a tension of its weight.
#[test]
fn a_joint_reports_the_weight_it_holds() {
    for rod_joint in [false, true] {
        let mut w = world(false);
        let pivot = Vec3::new(0.0, 3.0, 0.0);
        let b = ball(&mut w, pivot - Vec3::Y, 0.1, 1.0);
        if rod_joint {
            rod(&mut w, None, b, pivot, pivot - Vec3::Y);
        } else {
            joint(&mut w, JointKind::Ball, None, b, pivot, Vec3::Y);
        }
        for _ in 0..60 {
            w.step();
        }
        let load = w.joint_load(&w.joints()[0]);
        let weight = 9.81;
        if rod_joint {
            assert!((load.axial + weight).abs() < 1e-3 * weight, "{load:?}");
        } else {
            assert!(
                (load.force - Vec3::Y * weight).length() < 1e-3 * weight,
                "{load:?}"
            );
        }
    }
}

/// Freezing a jointed body's last free end leaves the joint nothing to carry: its load reads zero
/// (it read the hanging weight for as long as the end stayed frozen), and let go the bob hangs and
/// swings from the joint again.
#[test]
fn a_joint_frozen_at_both_ends_carries_nothing_and_takes_its_load_again_when_let_go() {
    let mut w = world(false);
    let pivot = Vec3::new(0.0, 3.0, 0.0);
    let bob_at = pivot + Vec3::new(0.5, -0.5, 0.0);
    let bob = ball(&mut w, bob_at, 0.1, 2.0);
    joint(&mut w, JointKind::Ball, None, bob, pivot, Vec3::Y);
    for _ in 0..30 {
        w.step();
    }
    assert!(w.joint_load(&w.joints()[0]).force.length() > 1.0);
    w.set_static(bob, true);
    w.step();
    assert_eq!(w.joint_load(&w.joints()[0]).force, Vec3::ZERO);
    w.set_static(bob, false);
    let held = w.body(bob).pose().position;
    for _ in 0..60 {
        w.step();
    }
    let (a, b) = w.joint_anchors(&w.joints()[0]);
    assert!(a.distance(b) < 1e-4, "the joint opened {} m", a.distance(b));
    assert!(
        w.body(bob).pose().position.distance(held) > 0.05,
        "the bob did not swing"
    );
    assert!(w.joint_load(&w.joints()[0]).force.length() > 1.0);
}

/// A ball hung by two ropes, beside a pendulum, in two worlds: one where the pendulum's bob is
/// frozen halfway (its joint, added between the ropes, then joins no dynamic body and leaves the
/// solve, and the ropes are the only joints left), one with no pendulum. The ropes' ball steps the
/// same in both, to the bit: what the solve keeps about the pendulum's tree (one nothing else
/// touched, whose joints are not warm-started) must not outlive the tree (it once did, and the
/// second rope lost its warm start, which the first reads).
#[test]
fn freezing_a_pendulum_leaves_the_ropes_beside_it_as_they_were() {
    let at = Vec3::new(5.0, 5.0, 0.0);
    let hang = |w: &mut World, c: BodyId, anchor: Vec3| rope(w, c, anchor, at, anchor.distance(at));
    let (left, right) = (Vec3::new(4.4, 5.8, 0.0), Vec3::new(5.6, 5.8, 0.0));
    let mut with = world(false);
    let in_with = ball(&mut with, at, 0.05, 1.0);
    hang(&mut with, in_with, left);
    let pivot = Vec3::new(0.0, 5.0, 0.0);
    let bob = ball(&mut with, pivot + Vec3::new(0.7, -0.7, 0.0), 0.05, 1.0);
    joint(&mut with, JointKind::Ball, None, bob, pivot, Vec3::Y);
    hang(&mut with, in_with, right);
    let mut alone = world(false);
    let in_alone = ball(&mut alone, at, 0.05, 1.0);
    hang(&mut alone, in_alone, left);
    hang(&mut alone, in_alone, right);
    for step in 0..120 {
        if step == 30 {
            with.set_static(bob, true);
        }
        with.step();
        alone.step();
        assert_eq!(pose(&with, in_with), pose(&alone, in_alone), "step {step}");
    }
}

/// A 10 kg box welded above a 1 kg foot on the floor: the foot's support carries eleven times the
/// foot's weight, which statics of contacts cannot know (`prepare::preload`, "Not preloaded").
/// Skipped by the statics, it sleeps after 0.52 s, the top 1.7 mm lower (the soft row's give);
/// preloaded with the foot's own weight it never slept, the top moving at 0.2 m/s and the foot
/// jumping 4 mm off the floor (measured 2026-12-02).
#[test]
fn a_box_welded_above_a_light_foot_rests_on_it_and_sleeps_only_when_statics_skip_it() {
    let weld = |skip: bool| {
        let mut w = World::new(Settings {
            statics_skip_jointed: skip,
            ..Settings::default()
        });
        w.add_body(cases::floor(5.0).desc);
        let cube = Shape::cuboid(Vec3::splat(0.25));
        let foot = w.add_body(BodyDesc::dynamic(
            cube,
            Pose::from_position(Vec3::new(0.0, 0.25, 0.0)),
            1.0,
        ));
        let built = Vec3::new(0.0, 1.0, 0.0);
        let top = w.add_body(BodyDesc::dynamic(cube, Pose::from_position(built), 10.0));
        joint(
            &mut w,
            JointKind::Fixed,
            Some(foot),
            top,
            Vec3::new(0.0, 0.625, 0.0),
            Vec3::Y,
        );
        let mut slept_at = None;
        for step in 1..=300 {
            w.step();
            if slept_at.is_none() && w.awake_count() == 0 {
                slept_at = Some(step);
            }
        }
        (slept_at, w.body(top).pose().position.distance(built))
    };
    let (slept_at, moved) = weld(true);
    assert!(slept_at.is_some_and(|s| s <= 120), "slept at {slept_at:?}");
    assert!(moved < 5e-3, "the top moved {moved} m");
    let (slept_at, moved) = weld(false);
    assert!(
        slept_at.is_none(),
        "preloaded, slept at {slept_at:?}, {moved} m off"
    );
}

/// A 1 kg arm 1 m long (0.1 m thick) hinged at one end, as `kind` (a ball joint or a hinge about
/// z) from the world, with `friction`; the arm lies along +x from the joint at `angle` below the
/// horizontal.
fn arm_with_friction(kind: JointKind, friction: f32, angle: f32) -> (World, BodyId) {
    let mut w = world(false);
    let pivot = Vec3::new(0.0, 3.0, 0.0);
    let turn = Quat::from_rotation_z(-angle);
    let arm = w.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(0.5, 0.05, 0.05)),
        Pose::new(pivot + turn * Vec3::new(0.5, 0.0, 0.0), turn),
        1.0,
    ));
    let desc = JointDesc::at(
        kind,
        None,
        (arm, pose(&w, arm)),
        pivot,
        pivot,
        Vec3::Z,
        false,
    )
    .with_friction(friction);
    w.add_joint(desc).unwrap();
    (w, arm)
}

fn free_hinge() -> JointKind {
    JointKind::Hinge {
        limits: None,
        motor: None,
    }
}

/// Held level, the arm's weight turns it with 4.905 N·m about the joint. Friction of 6 N·m holds
/// it there; friction of 3 N·m lets it go with the rest: α = (4.905 − 3) N·m / I, with
/// I = m (L² + t²)/12 + m (L/2)² = 0.3342 kg·m² about the joint, and it gains 0.285 rad/s from
/// 0.05 s to 0.1 s (0.05 % off). Let go at rest, the friction rows see no turn in the first
/// sub-step until the tree has made one, so the friction takes hold a sub-step late: the held arm
/// sags 0.04° and the other turns 4 % faster at 0.1 s than if it had held from the start. Both
/// for a hinge and for a ball joint, whose friction block holds all three turns.
#[test]
fn joint_friction_holds_an_arm_under_its_torque_and_slows_it_over_it() {
    let weight_torque = 9.81 * 0.5;
    let inertia = (1.0 + 0.01) / 12.0 + 0.25;
    for kind in [free_hinge(), JointKind::Ball] {
        let (mut w, arm) = arm_with_friction(kind, 6.0, 0.0);
        for _ in 0..120 {
            w.step();
        }
        let tilt = (w.body(arm).pose().rotation * Vec3::X).y.asin().abs();
        println!("{kind:?}, 6 N·m: sagged {:.4}°", tilt.to_degrees());
        assert!(
            tilt < 0.2f32.to_radians(),
            "{kind:?}: sagged {}°",
            tilt.to_degrees()
        );

        let (mut w, arm) = arm_with_friction(kind, 3.0, 0.0);
        let mut spins = Vec::new();
        for _ in 0..6 {
            w.step();
            spins.push(-w.body(arm).angular_velocity().z);
        }
        // From 0.05 s to 0.1 s: the friction has taken hold (see the test's doc).
        let gained = spins[5] - spins[2];
        let expected = (weight_torque - 3.0) / inertia * 0.05;
        let error = (gained - expected).abs() / expected;
        println!(
            "{kind:?}, 3 N·m: {gained} rad/s gained from 0.05 to 0.1 s, expected {expected} \
             ({:.2} %); {} rad/s at 0.1 s",
            error * 100.0,
            spins[5]
        );
        assert!(
            error < 0.01,
            "{kind:?}: {gained} rad/s, expected {expected}"
        );
    }
}

/// A pendulum with dry friction in its hinge loses a fixed angle a swing, not a fixed share: from
/// one turning point θ₁ to the next θ₂ (on the other side) its weight's work m g d (cos θ₂ − cos θ₁)
/// is the friction's τ (θ₁ + θ₂), and it stops for good once its weight's torque at a turning
/// point is under τ. The arm of `arm_with_friction`, hanging (d = 0.5 m) from a hinge with 0.1 N·m
/// of friction, let go 20° out: each half swing is checked against that energy balance.
#[test]
fn a_pendulum_with_joint_friction_loses_a_fixed_angle_a_swing_and_stops() {
    let (m_g_d, friction) = (9.81 * 0.5, 0.1f32);
    let (mut w, arm) = arm_with_friction(free_hinge(), friction, 70f32.to_radians());
    // Angle from hanging straight down, positive towards +x.
    let angle = |w: &World| {
        let down = w.body(arm).pose().rotation * Vec3::X;
        down.x.atan2(-down.y)
    };
    let mut turning = vec![angle(&w)];
    let mut last_spin = 0.0f32;
    for _ in 0..60 * 20 {
        w.step();
        let spin = w.body(arm).angular_velocity().z;
        if spin * last_spin < 0.0 {
            turning.push(angle(&w));
        }
        if spin != 0.0 {
            last_spin = spin;
        }
    }
    // The next turning point's size from the energy balance, by bisection.
    let next = |a: f32| {
        let left = |b: f32| m_g_d * (b.cos() - a.cos()) - friction * (a + b);
        let (mut lo, mut hi) = (0.0f32, a);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if left(mid) > 0.0 { lo = mid } else { hi = mid }
        }
        lo
    };
    println!(
        "turning points (°): {:?}",
        turning.iter().map(|a| a.to_degrees()).collect::<Vec<_>>()
    );
    assert!(turning.len() >= 8, "only {} turning points", turning.len());
    let stop = (friction / m_g_d).asin();
    for pair in turning.windows(2) {
        let (a, b) = (pair[0].abs(), pair[1].abs());
        if m_g_d * (1.0 - a.cos()) <= friction * a {
            // It cannot reach the bottom: it stops on this side, as it did.
            break;
        }
        let expected = next(a);
        println!(
            "{:.3}° → {:.3}°, expected {:.3}°",
            a.to_degrees(),
            b.to_degrees(),
            expected.to_degrees()
        );
        assert!(
            (b - expected).abs() < 0.1f32.to_radians(),
            "{a} → {b}, expected {expected}"
        );
    }
    let end = angle(&w).abs();
    assert!(
        end <= stop * 1.05,
        "stopped at {}°, friction holds within {}°",
        end.to_degrees(),
        stop.to_degrees()
    );
}

/// How far past its limit the corpus's hinged arm (`mass` kg at `length` m, limits ±`limit`°) ever
/// swings over 5 s at one sub-step, with the corpus's knobs and in its unit (1 = 0.5°), with a
/// tree's scalar rows solved after its rows or before them.
fn limit_give_at_one_sub_step(arm: (f32, f32, f32), last: bool) -> f32 {
    let mut knobs = Knobs {
        substeps: 1,
        iterations: 1,
        sleep: false,
        ..Knobs::default()
    };
    knobs.fixes.joint_scalar_rows_last = last;
    corpus::joints::limit_outcome(arm, knobs).error
}

/// The tree closes its joints' whole error within a sub-step, so whatever it solves after a limit
/// undoes it: with the scalar rows before the tree, at one sub-step a 10 kg arm on 1 m fell 78° past
/// its 30° limit (error 156), one on 0.5 m 68° past its 60° (error 136), and the 1 kg arm 3.8°.
/// With them after it, every arm stays within 0.11° (error 0.22, 2026-12-02; see "Order" in
/// `physics::joint`).
#[test]
fn a_hinge_limit_holds_a_loaded_arm_at_one_sub_step_only_with_scalar_rows_last() {
    for arm in [(1.0, 0.5, 30.0), (10.0, 1.0, 30.0), (10.0, 0.5, 60.0)] {
        let last = limit_give_at_one_sub_step(arm, true);
        let first = limit_give_at_one_sub_step(arm, false);
        println!("arm {arm:?}: past its limit by {last} last, {first} first (1 = 0.5°)");
        assert!(last < 1.0, "{arm:?}: {last}");
        if arm.0 == 10.0 {
            assert!(
                first > 20.0,
                "{arm:?} held with the scalar rows first: {first}"
            );
        }
    }
}

/// The corpus's loaded chain (balls of `radius` 0.1 m apart, 0.1 kg each, holding a ball 100 times
/// a link, released 30° out): how far it stretches over 10 s, relative to its length, at
/// `substeps` with `fixes` (the defaults' less what it switches off).
fn loaded_chain_stretch(
    (links, radius): (usize, f32),
    substeps: u32,
    fixes: impl Fn(&mut Fixes),
) -> f32 {
    let mut knobs = Knobs {
        substeps,
        ..Knobs::default()
    };
    fixes(&mut knobs.fixes);
    corpus::joints::chain_outcome((links, 100.0, radius), knobs).error
}

/// A light link between two heavy pulls turns stiffly about its centre, and the sub-steps amplify
/// that turn once it is faster than they are (see "Geometric stiffness" in `physics::joint`):
/// without the joints' geometric stiffness, 20 links under 100 times a link stretch 361 % of the
/// chain at 2 sub-steps and 3,215 % at 1 (the joints open), and 40 links 3.2 % at the default 4.
/// With it they hold within 0.004 %, 0.018 % and 0.00001 % (2026-12-02).
#[test]
fn a_light_chain_under_a_heavy_load_holds_at_low_sub_steps_only_with_geometric_stiffness() {
    for (links, substeps, limit) in [(20, 2, 2e-4), (20, 1, 8e-4), (40, 4, 1e-5)] {
        let chain = (links, corpus::joints::LINK_RADIUS);
        let on = loaded_chain_stretch(chain, substeps, |_| {});
        let off = loaded_chain_stretch(chain, substeps, |f| f.joint_geometric_stiffness = false);
        println!("{links} links at {substeps} sub-steps: stretched {on} on, {off} off");
        assert!(on < limit, "{links} links at {substeps}: {on}");
        assert!(
            off > 0.02,
            "{links} links at {substeps} held without it: {off}"
        );
    }
}

/// The widest joint of the corpus's chain of 20 balls of `radius` holding a ball as heavy as a
/// link, at `substeps` with `fixes`, when after 2 s its load is pulled down with 100 times a link's
/// weight, over the 8 s after (NaN once it is not finite).
fn yanked_chain_widest_joint(radius: f32, substeps: u32, fixes: impl Fn(&mut Fixes)) -> f32 {
    let mut knobs = Knobs {
        substeps,
        ..Knobs::default()
    };
    fixes(&mut knobs.fixes);
    let chain = corpus::joints::chain_scene((20, 1.0, radius));
    let mut world = knobs.world(&chain);
    let load = BodyId(20);
    let mut widest = 0.0f32;
    for step in 0..600 {
        if step >= 120 {
            let at = world.body(load).pose().position;
            world.apply_force_at_point(load, Vec3::new(0.0, -100.0 * 0.1 * 9.81, 0.0), at);
        }
        world.step();
        if step >= 120 {
            widest = if all_finite(&world) {
                widest.max(widest_joint(&world))
            } else {
                f32::NAN
            };
        }
    }
    widest
}

/// A light link between two pulls must turn as heavily as their geometric stiffness from the step
/// the pulls come (see "Geometric stiffness" in `physics::joint`). Floored by the pull its joints
/// carried the step before alone, a new chain of 20 balls holding 100 times a link had no floor in
/// its first step, spun up its links and flew apart: 2 cm balls at 2 sub-steps (stretched 158 %),
/// 1 cm balls at 2 and at the default 4 (132 % and 251 %); and a chain of 4 cm balls whose light
/// end was suddenly pulled with 100 times a link's weight opened a joint 36 cm at 2 sub-steps
/// (2 cm balls: 71 cm, and 25 cm at 4). With the pull at least its articulation's load
/// (`Settings::joint_pull_from_load`) each chain holds within 0.02 %, and the pulled ones open a
/// joint 1.2 mm at most (2026-12-02).
#[test]
fn light_links_stiffen_with_their_load_from_its_first_step_only_when_floors_take_it() {
    for (radius, substeps) in [
        (0.02, 1),
        (0.02, 2),
        (0.02, 4),
        (0.01, 1),
        (0.01, 2),
        (0.01, 4),
    ] {
        let chain = (20, radius);
        let on = loaded_chain_stretch(chain, substeps, |_| {});
        let off = loaded_chain_stretch(chain, substeps, |f| f.joint_pull_from_load = false);
        println!("{radius} m links at {substeps} sub-steps: stretched {on} on, {off} off");
        assert!(on < 1e-3, "{radius} m links at {substeps}: {on}");
        if (radius, substeps) != (0.02, 4) && substeps > 1 {
            // Flown apart: stretched past half its length, or to no number at all.
            assert!(
                off.is_nan() || off > 0.5,
                "{radius} m links at {substeps} held without it: {off}"
            );
        }
    }
    for (radius, substeps) in [(0.04, 2), (0.02, 2), (0.02, 4)] {
        let on = yanked_chain_widest_joint(radius, substeps, |_| {});
        let off = yanked_chain_widest_joint(radius, substeps, |f| f.joint_pull_from_load = false);
        println!(
            "{radius} m links at {substeps} sub-steps, yanked: widest joint {on} m on, {off} m off"
        );
        assert!(on < 5e-3, "{radius} m links at {substeps}, yanked: {on} m");
        assert!(
            off.is_nan() || off > 0.02,
            "{radius} m links at {substeps}, yanked, held without it: {off} m"
        );
    }
}
