//! Newton's cradle on strings (the built-in `cradle` scene's, with perfectly elastic balls and no
//! air): the ball at the far end of the row leaves at the speed the raised ball strikes with.
//! Sequential-impulse solvers are known to smear the blow across the touching balls (the row moves
//! off together); the impacts pass (`solve/wide_contacts/impacts.rs`) meets the impacts in the
//! order they happen, and the strings, pulling across the row's line, must not undo it.

use nudge::physics::{BodyId, World};
use nudge::scene::mechanisms::{CRADLE_DROP, CRADLE_RAISE_DEG, CRADLE_RESTITUTION, cradle};

/// The cradle of `count` balls, with restitution 1 and no drag if `elastic`; the balls' ids, the
/// raised one first.
fn cradle_world(count: usize, elastic: bool) -> (World, Vec<BodyId>) {
    let mut scene = cradle(count);
    let first = scene.bodies.len() - count;
    if elastic {
        scene.settings.linear_damping = 0.0;
        for ball in &mut scene.bodies[first..] {
            ball.desc.restitution = 1.0;
        }
    }
    let balls = (first..first + count).map(|i| BodyId(i as u32)).collect();
    (scene.build_world(), balls)
}

/// (the raised ball's fastest speed before the row moves, the far ball's fastest after, every
/// other ball's fastest after), m/s, over the first swing.
fn first_strike(count: usize, elastic: bool) -> (f32, f32, f32) {
    let (mut world, balls) = cradle_world(count, elastic);
    let speed = |w: &World, id: BodyId| w.body(id).linear_velocity().length();
    let (mut strike, mut far, mut others) = (0.0f32, 0.0f32, 0.0f32);
    let mut struck = false;
    // Half a period: the raised ball falls and strikes, the far one rises and turns back.
    for _ in 0..90 {
        world.step();
        let far_speed = speed(&world, balls[count - 1]);
        struck |= far_speed > 0.1;
        if !struck {
            strike = strike.max(speed(&world, balls[0]));
        } else {
            far = far.max(far_speed);
            for &id in &balls[..count - 1] {
                others = others.max(speed(&world, id));
            }
        }
    }
    (strike, far, others)
}

/// Measured, with 3 balls and with 5: the raised ball strikes at 2.7064 m/s (its fastest in the
/// step before the row moves; 2.7100 falling 40° on its 1.6 m strings); the far ball leaves at
/// 2.7121 m/s (+0.21 %) and 2.7125 m/s (+0.23 %), and no other ball moves faster than 0.015 m/s
/// after the blow. The issue asked for 2 %; the bounds are 1 % and 0.05 m/s.
#[test]
fn the_far_ball_of_a_cradle_on_strings_leaves_at_the_strike_speed() {
    let drop = CRADLE_DROP * (1.0 - CRADLE_RAISE_DEG.to_radians().cos());
    let free_fall = (2.0 * 9.81 * drop).sqrt();
    for count in [3, 5] {
        let (strike, far, others) = first_strike(count, true);
        assert!(
            (strike - free_fall).abs() < 0.005 * free_fall,
            "{count} balls: strike {strike} m/s, {free_fall} in free fall"
        );
        assert!(
            (far - strike).abs() < 0.01 * strike,
            "{count} balls: the far one left at {far} m/s, struck at {strike}"
        );
        assert!(
            others < 0.05,
            "{count} balls: another moved at {others} m/s"
        );
    }
}

/// The built-in scene's steel balls (e = 0.95): met in order, each impact passes on (1 + e)/2 of
/// the speed it meets, so the far one of 5 leaves at 0.975⁴ = 90.37 % of the strike. Measured:
/// 90.27 % (2.3323 m/s of 2.5837; the air's drag takes a little over the step of the blow).
#[test]
fn the_built_in_cradle_passes_the_blow_on_as_its_restitution_says() {
    let (strike, far, _) = first_strike(5, false);
    let expected = (0.5 * (1.0 + CRADLE_RESTITUTION)).powi(4);
    assert!(
        (far / strike - expected).abs() < 0.005,
        "the far ball left at {far} m/s of {strike}, {expected} of it expected"
    );
}

/// A cradle whose swings have drifted out of step (the air's drag, 0.15/s, slows the balls unevenly)
/// meets blows from both sides at once; with e = 1 and the restitution threshold at 0.3 m/s it
/// must still never gain energy. A point parting at the start of a step was read as struck at its
/// parting speed (the approach at impact, √(c₀² + 2·closing·gap), squared its sign away) and
/// pushed off again: the balls' energy rose 5.35 J in one step and from 30.0 J to 39.5 J (gravity's
/// included) in 8 s. With the friction anchors off as well: the balls' joints went unseen there,
/// and their contacts were visited top-down in turn like a pile's (`wide_contacts::LayerOrder`),
/// 0.027 J gained in a step. Measured 2026-11-30: at most 0.0036 J in a step over 30 s, either way.
#[test]
fn a_cradle_out_of_step_gains_no_energy_from_its_impacts() {
    for friction_anchors in [true, false] {
        let mut scene = cradle(5);
        scene.settings.restitution_threshold = 0.3;
        scene.settings.friction_anchors = friction_anchors;
        let first = scene.bodies.len() - 5;
        for ball in &mut scene.bodies[first..] {
            ball.desc.restitution = 1.0;
        }
        let mut world = scene.build_world();
        let energy = |w: &World| -> f32 {
            (first..first + 5)
                .map(|i| {
                    let b = w.body(BodyId(i as u32));
                    b.kinetic_energy() + b.mass() * 9.81 * b.pose().position.y
                })
                .sum()
        };
        let mut last = energy(&world);
        let mut most_gained = 0.0f32;
        for _ in 0..60 * 30 {
            world.step();
            let now = energy(&world);
            most_gained = most_gained.max(now - last);
            last = now;
        }
        assert!(
            most_gained < 0.01,
            "anchors {friction_anchors}: {most_gained} J gained in a step"
        );
    }
}
