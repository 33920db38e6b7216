//! Rolling resistance against the analytic answer. A solid ball (I = ⅖mr²) rolling without slipping on
//! a flat floor meets a resisting couple μr·N·r; with friction f at the contact keeping it rolling:
//!
//! ```text
//! m·a = −f,   I·a/r = f·r − μr·m·g·r   ⇒   a = −μr·g / (1 + I/(m·r²)) = −(5/7)·μr·g
//! ```
//!
//! Default `Settings` (dt = 1/60 s, 4 sub-steps), g = 9.81 m/s², friction 0.5.

use glam::Vec3;
use nudge::geometry::{Pose, Shape};
use nudge::physics::{BodyDesc, BodyId, Settings, World};

const G: f32 = 9.81;
const RADIUS: f32 = 0.25;
const SPEED: f32 = 3.0;

/// A static floor (top at y = 0) and a ball on it rolling along +x at `SPEED` without slipping, with
/// rolling resistance `ball_mu` on the ball and `floor_mu` on the floor.
fn rolling_ball(ball_mu: f32, floor_mu: f32, sleep: bool) -> (World, BodyId) {
    let mut world = World::new(Settings {
        sleep,
        ..Settings::default()
    });
    world.add_body(BodyDesc {
        rolling_resistance: floor_mu,
        ..BodyDesc::fixed(
            Shape::cuboid(Vec3::new(200.0, 0.5, 5.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        )
    });
    let ball = world.add_body(BodyDesc {
        linear_velocity: Vec3::new(SPEED, 0.0, 0.0),
        // Rolling: the contact point (−r along y) is at rest, v + ω × (−r ŷ) = 0.
        angular_velocity: Vec3::new(0.0, 0.0, -SPEED / RADIUS),
        rolling_resistance: ball_mu,
        ..BodyDesc::dynamic(
            Shape::sphere(RADIUS),
            Pose::from_position(Vec3::new(0.0, RADIUS, 0.0)),
            1.0,
        )
    });
    (world, ball)
}

fn run(world: &mut World, seconds: f32) {
    for _ in 0..(seconds * 60.0).round() as usize {
        world.step();
    }
}

#[test]
fn a_rolling_ball_slows_at_five_sevenths_of_mu_r_g_and_keeps_rolling() {
    /// Relative tolerance on the speed lost in 2 s (measured 2.2·10⁻⁵; 3 % when written).
    const TOLERANCE: f32 = 1e-4;
    /// Largest slip speed at the contact point, m/s (measured 2.2·10⁻⁵; 0.01 when written).
    const MAX_SLIP_MPS: f32 = 1e-4;
    /// Deepest the ball may sit in the floor, m (measured 4.9 µm, the soft contact under its weight;
    /// 10 mm when written).
    const MAX_SINK_M: f32 = 2e-5;
    for (ball_mu, floor_mu) in [(0.05, 0.0), (0.0, 0.05), (0.02, 0.05)] {
        let mu = f32::max(ball_mu, floor_mu);
        let (mut world, ball) = rolling_ball(ball_mu, floor_mu, false);
        run(&mut world, 2.0);
        let body = world.body(ball);
        let lost = SPEED - body.linear_velocity().x;
        let expected = 5.0 / 7.0 * mu * G * 2.0;
        assert!(
            (lost - expected).abs() < TOLERANCE * expected,
            "μr {ball_mu} on {floor_mu}: lost {lost} m/s, expected {expected}"
        );
        // Still rolling without slipping: the contact point is at rest.
        let slip = body.linear_velocity().x + body.angular_velocity().z * RADIUS;
        assert!(slip.abs() < MAX_SLIP_MPS, "slip {slip} m/s");
        let sink = RADIUS - body.pose().position.y;
        assert!(sink < MAX_SINK_M, "the ball sank {sink} m");
    }
}

#[test]
fn a_ball_with_rolling_resistance_comes_to_rest_and_sleeps() {
    /// Relative tolerance on the distance rolled (measured 5.0·10⁻⁴; 5 % when written).
    const TOLERANCE: f32 = 2e-3;
    let (mut world, ball) = rolling_ball(0.05, 0.0, true);
    // It stops after v / a = 3 / 0.35 ≈ 8.6 s, then falls asleep.
    run(&mut world, 10.0);
    let body = world.body(ball);
    assert!(body.is_sleeping(), "{:?}", body.linear_velocity());
    let travelled = body.pose().position.x;
    let expected = SPEED * SPEED / (2.0 * 5.0 / 7.0 * 0.05 * G);
    assert!(
        (travelled - expected).abs() < TOLERANCE * expected,
        "rolled {travelled} m, expected {expected}"
    );
}

#[test]
fn without_rolling_resistance_a_ball_keeps_rolling() {
    let (mut world, ball) = rolling_ball(0.0, 0.0, true);
    run(&mut world, 5.0);
    let v = world.body(ball).linear_velocity().x;
    // Measured 8.3·10⁻⁶ m/s lost in 5 s (10⁻³ when written).
    assert!((v - SPEED).abs() < 4e-5, "{v}");
}

#[test]
fn rolling_resistance_does_not_stop_a_box_from_tipping_or_resist_a_box_on_a_box() {
    // Boxes do not roll: a box tipped over an edge falls as it would without the coefficient.
    let fall = |mu: f32| {
        let mut world = World::new(Settings::default());
        world.add_body(BodyDesc {
            rolling_resistance: mu,
            ..BodyDesc::fixed(
                Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)),
                Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
            )
        });
        let tilt = glam::Quat::from_rotation_z(0.3);
        let b = world.add_body(BodyDesc {
            rolling_resistance: mu,
            ..BodyDesc::dynamic(
                Shape::cuboid(Vec3::new(0.2, 0.6, 0.2)),
                Pose::new(Vec3::new(0.0, 0.7, 0.0), tilt),
                1.0,
            )
        });
        run(&mut world, 1.0);
        *world.body(b).pose()
    };
    assert_eq!(fall(0.0), fall(0.5));
}

/// A ball on a floor spinning about the vertical at `spin` rad/s, with rolling resistance `mu`.
fn spinning_ball(mu: f32, spin: f32) -> (World, BodyId) {
    let (mut world, _) = rolling_ball(0.0, 0.0, false);
    let ball = world.add_body(BodyDesc {
        angular_velocity: Vec3::new(0.0, spin, 0.0),
        rolling_resistance: mu,
        ..BodyDesc::dynamic(
            Shape::sphere(RADIUS),
            Pose::from_position(Vec3::new(50.0, RADIUS, 0.0)),
            1.0,
        )
    });
    (world, ball)
}

/// The deformed patch that resists rolling resists spinning in place by the same couple μr·N·r:
/// I·α = μr·m·g·r with I = ⅖mr², so α = (5/2)·μr·g/r. A point contact has no twist friction, and
/// balls knocked into a spin in the built-in `rain` spun for ever and kept it awake.
#[test]
fn a_ball_spinning_in_place_slows_at_five_halves_of_mu_r_g_over_r_and_stops() {
    /// Relative tolerance on the spin lost in 0.5 s.
    const TOLERANCE: f32 = 0.03;
    let (mu, spin) = (0.05, 5.0);
    let alpha = 2.5 * mu * G / RADIUS; // 4.9 rad/s², stops after about 1 s
    let (mut world, ball) = spinning_ball(mu, spin);
    run(&mut world, 0.5);
    let lost = spin - world.body(ball).angular_velocity().y;
    let expected = alpha * 0.5;
    assert!(
        (lost - expected).abs() < TOLERANCE * expected,
        "lost {lost} rad/s in 0.5 s, expected {expected}"
    );
    run(&mut world, 1.5);
    let w = world.body(ball).angular_velocity().length();
    assert!(w < 1e-3, "still spinning at {w} rad/s");
    let drift = world.body(ball).pose().position - Vec3::new(50.0, RADIUS, 0.0);
    assert!(drift.length() < 1e-3, "wandered {drift}");
    // Without rolling resistance nothing resists the spin (a point contact has no twist friction).
    let (mut free, ball) = spinning_ball(0.0, spin);
    run(&mut free, 2.0);
    assert!((free.body(ball).angular_velocity().y - spin).abs() < 1e-3);
}

/// A ball of 5 cm radius (0.52 kg, rolling resistance 0.05) on a floor under the end of a plank 1 m
/// long whose other end rests on the floor, the plank `ratio` times the ball's mass; sleeping on.
/// Returns when it first slept, in steps, within a minute.
fn wedged_ball_sleeps_at(ratio: f32, held_mass_alone: bool) -> Option<usize> {
    let mut world = World::new(Settings {
        rolling_held_mass_alone: held_mass_alone,
        ..Settings::default()
    });
    world.add_body(nudge::scene::cases::floor(5.0).desc);
    let r = 0.05;
    let ball_mass = 1000.0 * 4.0 / 3.0 * std::f32::consts::PI * r * r * r;
    world.add_body(BodyDesc {
        rolling_resistance: 0.05,
        ..BodyDesc::dynamic(
            Shape::sphere(r),
            Pose::from_position(Vec3::new(0.45, r, 0.0)),
            ball_mass,
        )
    });
    let half = Vec3::new(0.5, 0.05, 0.2);
    let tilt = glam::Quat::from_rotation_z((2.0 * r / 0.95).atan());
    let centre = tilt * Vec3::new(0.0, half.y, 0.0) + Vec3::new(0.0, r + 0.001, 0.0);
    world.add_body(BodyDesc::dynamic(
        Shape::cuboid(half),
        Pose::new(centre, tilt),
        ratio * ball_mass,
    ));
    (1..=3600).find(|_| {
        world.step();
        world.awake_count() == 0
    })
}

/// The rolling rows take the mass they have with the contact's friction held only on a contact
/// that is each of its bodies' only one (`wide_contacts::rolling`): a ball wedged between the floor
/// and a plank 5, 20 or 140 times its mass sleeps within half a second; taking the held mass on
/// both its contacts, it buzzes at 0.1 m/s and never sleeps under a plank 5 or 20 times its mass.
#[test]
fn a_ball_wedged_under_a_plank_sleeps_only_when_a_lone_contact_takes_the_held_mass() {
    for ratio in [5.0, 20.0, 140.0] {
        let slept = wedged_ball_sleeps_at(ratio, true);
        println!("plank {ratio}x the ball: asleep at step {slept:?}");
        assert!(slept.is_some_and(|step| step <= 120), "{ratio}x: {slept:?}");
    }
    for ratio in [5.0, 20.0] {
        let slept = wedged_ball_sleeps_at(ratio, false);
        println!("plank {ratio}x, held mass everywhere: asleep at step {slept:?}");
        assert_eq!(slept, None, "{ratio}x");
    }
}
