//! The corpus of `nudge::testing::corpus` at the default knobs: every member of every family within
//! its tolerance. One test per family; a failure lists every member that missed, with what it
//! measured.

use glam::Vec3;
use nudge::geometry::Shape;
use nudge::physics::BodyId;
use nudge::testing::corpus::collisions::Collision;
use nudge::testing::corpus::{self, Family};
use nudge::testing::hard_case::Knobs;

/// Runs every member of `family` at the defaults and panics listing those over their tolerance.
fn holds(family: Family) {
    let mut failures = Vec::new();
    for member in &family.members {
        let out = (member.run)(Knobs::default());
        eprintln!(
            "{}: {} error {:.5} (tolerance {}) {}",
            family.name, member.label, out.error, member.tolerance, out.detail
        );
        if !corpus::within(out.error, member.tolerance) {
            failures.push(format!(
                "{}: error {} > {}: {}",
                member.label, out.error, member.tolerance, out.detail
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} ({}):\n{}",
        family.name,
        family.answer,
        failures.join("\n")
    );
}

/// The family of `corpus::families()` named `name`.
fn family(name: &str) -> Family {
    corpus::families()
        .into_iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no family named {name}"))
}

#[test]
fn balls_dropped_on_a_floor_rebound_to_e_squared_n_times_the_drop() {
    holds(family("ball drop"));
}

#[test]
fn a_ball_dropped_on_a_box_on_the_floor_rebounds_as_from_the_floor() {
    holds(family("ball on box"));
}

#[test]
fn a_ball_dropped_on_a_stack_of_three_boxes_rebounds_as_from_the_floor() {
    holds(family("ball on a stack"));
}

#[test]
fn a_cube_landing_on_a_corner_keeps_the_energy_the_impact_law_leaves() {
    holds(family("cube on a corner"));
}

#[test]
fn a_box_landing_flat_rebounds_without_tipping() {
    holds(family("box drop flat"));
}

#[test]
fn bouncy_bodies_at_rest_never_bounce() {
    holds(family("bouncy at rest"));
}

#[test]
fn newtons_cradles_of_two_to_seven_balls_pass_the_strike_to_the_far_ball() {
    holds(family("newton's cradle"));
}

#[test]
fn two_equal_elastic_balls_meeting_head_on_exchange_their_velocities_exactly() {
    /// Largest velocity error after, m/s (f32 rounding of a few impulses).
    const MAX_ERROR_MPS: f32 = 1e-4;
    let collision = Collision {
        shapes: [Shape::sphere(0.25); 2],
        densities: [1.0; 2],
        positions: [Vec3::new(-0.4, 1.0, 0.0), Vec3::new(0.4, 1.0, 0.0)],
        velocities: [Vec3::new(3.0, 0.0, 0.0), Vec3::new(-1.0, 0.0, 0.0)],
        e: 1.0,
        normal: Vec3::X,
    };
    let mut world = Knobs::default().world(&collision.scene("head-on".into()));
    for _ in 0..60 {
        world.step();
    }
    let after = [0, 1].map(|i| world.body(BodyId(i)).linear_velocity());
    for (got, want) in after
        .iter()
        .zip([collision.velocities[1], collision.velocities[0]])
    {
        assert!((*got - want).length() < MAX_ERROR_MPS, "{after:?}");
    }
}

#[test]
fn balls_meeting_head_on_leave_as_the_impact_law_says() {
    holds(family("balls head-on"));
}

#[test]
fn a_ball_hitting_a_moving_box_leaves_as_the_impact_law_says() {
    holds(family("ball hits moving box"));
}
