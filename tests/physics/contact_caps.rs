//! Memory stays bounded whatever a scene piles up: 2,000 boxes in one place took 5.7 GB (two million
//! four-point manifolds) and 5,000 coincident balls aborted on an 8.5 GB allocation. The contact caps
//! (`physics::contact_cap`) hold the pairs to a bounded count; the step degrades (pairs over the caps
//! are ignored and counted) instead of failing. This file runs alone in its process, so the peak
//! memory it reads is its own.

use glam::Vec3;
use nudge::geometry::{Pose, Shape};
use nudge::physics::broad::contact_cap::{MAX_PAIRS, MAX_PAIRS_PER_BODY};
use nudge::physics::{BodyDesc, Settings, World};

/// `n` bodies of `shape`, all centred at the same point.
fn pile(shape: Shape, n: usize) -> World {
    let mut world = World::new(Settings::default());
    for _ in 0..n {
        world.add_body(BodyDesc::dynamic(
            shape,
            Pose::from_position(Vec3::new(0.0, 1.0, 0.0)),
            1.0,
        ));
    }
    world
}

/// Steps `world` `steps` times; every step must ignore pairs, stay within the caps and stay finite.
fn steps_within_the_caps(world: &mut World, steps: usize) {
    for step in 1..=steps {
        world.step();
        assert!(
            world.pairs_over_cap() > 0,
            "step {step}: nothing was capped"
        );
        assert!(world.contact_count() <= MAX_PAIRS, "step {step}");
        let finite = world.bodies().iter().all(|b| {
            b.pose().is_finite()
                && b.linear_velocity().is_finite()
                && b.angular_velocity().is_finite()
        });
        assert!(finite, "step {step}: non-finite");
    }
}

/// Peak resident memory of this process, bytes (Linux), if it can be read.
fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[test]
fn coincident_piles_run_within_the_caps_and_two_gigabytes() {
    // The two reproducers: 2,000 boxes for 10 steps, 5,000 balls (fewer steps: the same
    // buffers, the allocation that aborted comes in the first).
    steps_within_the_caps(&mut pile(Shape::cuboid(Vec3::splat(0.5)), 2000), 10);
    steps_within_the_caps(&mut pile(Shape::sphere(0.5), 5000), 3);
    if let Some(peak) = peak_memory() {
        assert!(peak < 2 << 30, "peak memory {} MB", peak >> 20);
    }
}

#[test]
fn a_body_may_touch_as_many_bodies_as_the_cap_without_losing_one() {
    // A plank carrying a crowd, every ball on it: as many pairs as the cap allows, none ignored.
    let mut world = World::new(Settings::default());
    world.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(20.0, 0.1, 20.0)),
        Pose::from_position(Vec3::ZERO),
        100.0,
    ));
    let side = (MAX_PAIRS_PER_BODY as f32).sqrt() as usize;
    for i in 0..side * side {
        let (x, z) = ((i % side) as f32 * 1.2 - 5.0, (i / side) as f32 * 1.2 - 5.0);
        world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.5),
            Pose::from_position(Vec3::new(x, 0.6, z)),
            1.0,
        ));
    }
    world.step();
    assert_eq!(world.pairs_over_cap(), 0);
}
