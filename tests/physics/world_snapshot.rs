//! World snapshots: a restored world is bit-identical to the world at that step (warm-start
//! impulses, sleep timers and island links included) and steps on exactly as the original did.

use glam::Vec3;
use nudge::physics::{BodyId, Settings, World};
use nudge::scene::builtin;

fn run(world: &mut World, steps: usize) -> Vec<nudge::physics::WorldSnapshot> {
    (0..steps)
        .map(|_| {
            world.step();
            world.snapshot()
        })
        .collect()
}

fn assert_same(
    got: &[nudge::physics::WorldSnapshot],
    expected: &[nudge::physics::WorldSnapshot],
    what: &str,
) {
    assert_eq!(got.len(), expected.len());
    for (step, (g, e)) in got.iter().zip(expected).enumerate() {
        if let Some(diff) = g.first_difference(e) {
            panic!("{what}: differs {step} steps after the restore: {diff}");
        }
    }
}

#[test]
fn a_restored_world_steps_bit_for_bit_as_the_original_through_falls_contacts_and_sleep() {
    // The pyramid settles and sleeps within the window; rain is mid-fall; the default scene's balls roll.
    for (name, before, after) in [("pyramid", 40, 400), ("rain", 90, 60), ("default", 30, 300)] {
        let mut world = builtin::by_name(name).unwrap().build_world();
        for _ in 0..before {
            world.step();
        }
        // A push pending for the next step, so forces are part of the copy too.
        let at = world.body(BodyId(3)).pose().position;
        world.apply_force_at_point(BodyId(3), Vec3::new(5.0, 0.0, 0.0), at);
        let snapshot = world.snapshot();
        assert_eq!(snapshot.step(), before as u64);
        let expected = run(&mut world, after);
        // Into the same world (its scratch from the future) and into a fresh one.
        world.restore(&snapshot);
        assert_eq!(world.step_count(), before as u64);
        assert!(world.snapshot().first_difference(&snapshot).is_none());
        assert_same(
            &run(&mut world, after),
            &expected,
            &format!("{name}, restored in place"),
        );
        let mut fresh = World::new(Settings::default());
        fresh.restore(&snapshot);
        assert_same(
            &run(&mut fresh, after),
            &expected,
            &format!("{name}, restored fresh"),
        );
    }
}

#[test]
fn a_snapshot_holds_warm_start_impulses_and_sleep_timers() {
    let mut world = builtin::by_name("stack").unwrap().build_world();
    for _ in 0..20 {
        world.step();
    }
    let snapshot = world.snapshot();
    let text = format!("{snapshot:?}");
    assert!(
        text.contains("sleep_time: 0.33"),
        "sleep timers are kept: the stack has rested 20 steps"
    );
    assert!(text.contains("normal: ["), "warm-start impulses are kept");
    for _ in 0..100 {
        world.step();
    }
    assert!(world.snapshot().first_difference(&snapshot).is_some());
    world.restore(&snapshot);
    assert_eq!(world.snapshot().first_difference(&snapshot), None);
}

/// A hold's pull is part of the state: the preload takes a body held again to pull as it did over
/// the last step, so a world restored mid-hold must remember that pull (it once started from none,
/// and the held box's floor took its whole weight for a step).
#[test]
fn a_world_restored_while_a_hand_holds_a_box_steps_on_as_the_original() {
    use nudge::physics::{PointHold, PointSpring};
    let mut world = builtin::by_name("stack").unwrap().build_world();
    for _ in 0..30 {
        world.step();
    }
    let held = BodyId(2);
    let spring = PointSpring {
        hertz: 8.0,
        damping_ratio: 0.7,
        max_force: 200.0,
        max_speed: 15.0,
    };
    let hold = |world: &mut World, step: usize| {
        let at = world.body(held).pose().position;
        let target = Vec3::new(0.002 * step as f32, 0.3, 0.0);
        world.hold_point(PointHold {
            body: held,
            anchor: Vec3::new(0.0, 0.5, 0.0),
            from: at + target,
            to: at + target,
            spring,
            spin_time: 0.0,
        });
    };
    for step in 0..20 {
        hold(&mut world, step);
        world.step();
    }
    let snapshot = world.snapshot();
    let go_on = |world: &mut World| -> Vec<nudge::physics::WorldSnapshot> {
        (20..80)
            .map(|step| {
                hold(world, step);
                world.step();
                world.snapshot()
            })
            .collect()
    };
    let expected = go_on(&mut world);
    let mut fresh = World::new(Settings::default());
    fresh.restore(&snapshot);
    assert_same(&go_on(&mut fresh), &expected, "held, restored fresh");
}
