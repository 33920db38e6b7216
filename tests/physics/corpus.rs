//! The corpus of `nudge::testing::corpus` at the default knobs: every member of every family within
//! its tolerance. One test per family; a failure lists every member that missed, with what it
//! measured.

use glam::Vec3;
use nudge::geometry::Shape;
use nudge::physics::BodyId;
use nudge::testing::corpus::collisions::Collision;
use nudge::testing::corpus::{self, Family};
use nudge::testing::hard_case::Knobs;

/// Runs every member of `family` at the defaults and panics listing those over their tolerance: the
/// member's own (the limit, which `nudge bench physics` judges by) or `regression`, whichever
/// is smaller. `regression` sits at about 3–5× the family's worst error measured at the defaults
/// (2026-11-25, noted at each call), so a regression fails long before it reaches the limit.
fn holds(family: Family, regression: f32) {
    let mut failures = Vec::new();
    for member in &family.members {
        let out = (member.run)(Knobs::default());
        let tolerance = member.tolerance.min(regression);
        eprintln!(
            "{}: {} error {:.2e} (tolerance {tolerance}) {}",
            family.name, member.label, out.error, out.detail
        );
        if !corpus::within(out.error, tolerance) {
            failures.push(format!(
                "{}: error {} > {tolerance}: {}",
                member.label, out.error, out.detail
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
    // Worst measured 4.2·10⁻⁵; issue limit 1 %.
    holds(family("ball drop"), 2e-4);
}

#[test]
fn a_ball_dropped_on_a_box_on_the_floor_rebounds_as_from_the_floor() {
    // Worst measured 2.7·10⁻⁴ (4.0·10⁻⁴ before the rebound had friction); issue limit 1 %.
    holds(family("ball on box"), 2e-3);
}

#[test]
fn a_ball_dropped_on_a_stack_of_three_boxes_rebounds_as_from_the_floor() {
    // Worst measured 2.2·10⁻³; issue limit 1 %.
    holds(family("ball on a stack"), 8e-3);
}

#[test]
fn a_cube_landing_on_a_corner_keeps_the_energy_the_impact_law_leaves() {
    // Worst measured 4.2·10⁻⁵; issue limit 1 %.
    holds(family("cube on a corner"), 2e-4);
}

#[test]
fn a_box_landing_flat_rebounds_without_tipping() {
    // Worst measured 6.5·10⁻⁴; issue limit 1 %.
    holds(family("box drop flat"), 3e-3);
}

#[test]
fn bouncy_bodies_at_rest_never_bounce() {
    // Measured no rise at all; issue limit 1 mm.
    holds(family("bouncy at rest"), 1e-5);
}

#[test]
fn newtons_cradles_of_two_to_seven_balls_pass_the_strike_to_the_far_ball() {
    // Measured exact to f32 (1.3·10⁻³ before the rebound had friction and the events' impulses
    // were applied directly); issue limit 5 %.
    holds(family("newton's cradle"), 5e-3);
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
    // Worst measured 6·10⁻⁸, f32 rounding: a few of its steps allowed; issue limit 1 %.
    holds(family("balls head-on"), 1e-6);
}

#[test]
fn a_ball_hitting_a_moving_box_leaves_as_the_impact_law_says() {
    // Worst measured 2·10⁻⁷; issue limit 1 %.
    holds(family("ball hits moving box"), 1e-6);
}

#[test]
fn on_a_ramp_friction_just_above_tan_theta_holds_and_just_below_slides_as_coulomb_says() {
    // Worst measured 8.7·10⁻³ (40°, sliding; the rest 2.1·10⁻³, the symplectic step's h/t); the
    // members' 2 % (the ramp hard case's) is tighter than 3× that.
    holds(family("ramp friction"), 0.03);
}

#[test]
fn boxes_of_any_aspect_ratio_spin_down_in_the_time_the_contact_patch_gives() {
    // Worst measured 2.0·10⁻⁵; issue limit 1 %.
    holds(family("spin-down"), 1e-4);
}

#[test]
fn sliding_boxes_stop_after_v_squared_over_two_mu_g_and_stay() {
    // Worst measured 4.1·10⁻³; the 1 % is tighter than 3× that.
    holds(family("slide to stop"), 0.015);
}

#[test]
fn columns_of_ten_to_fifty_boxes_do_not_drift() {
    // Worst measured 0.58 mm (50 boxes); issue limit 1 cm.
    holds(family("tower drift"), 0.002);
}

#[test]
fn columns_of_ten_to_fifty_boxes_sink_no_deeper_than_the_contact_spring_allows() {
    // Measured 5.3 to 32.0 mm (0.53 to 0.64 mm per box): each member's own allowance,
    // `tower::PENETRATION_SLOP_M` + `tower::PENETRATION_PER_BOX_M` per box, is what holds (far
    // tighter than 3× the worst); the issue asks 5 mm at 30 boxes, which it does not reach yet.
    holds(family("tower penetration"), 0.1);
}

#[test]
fn coincident_boxes_come_apart_gently_however_many_there_are() {
    // Worst measured 0.89 of the limits (4.46 m/s by displacement, 50 boxes); the limits
    // (1) are tighter than 3× that. Every member holds since bodies holding each other's centre
    // come apart across gravity (`physics::coincident`): the crowd of 35 built a tower and reached
    // 5.8 m/s, the turned crowds 8.6–9.7 m/s.
    holds(family("overlap"), 3.0);
}

#[test]
fn a_box_up_to_ten_thousand_times_heavier_rests_on_a_light_one_at_its_height() {
    // Worst measured 1.8·10⁻⁵ m (10⁴:1; 7.4·10⁻⁵ while face manifolds around a mass ratio were
    // reused, `narrow::PairStep::reusable`), so 6·10⁻⁵ is the pin; the issue asks for 0.1 mm.
    holds(family("heavy on light"), 6e-5);
}

#[test]
fn a_ball_on_a_ramp_rolls_at_five_sevenths_g_sin_theta_or_slips_as_coulomb_says() {
    // Worst measured 2.8·10⁻³ (every member: the symplectic step's h/t); limit 1 %.
    holds(family("ball on a ramp"), 0.01);
}

#[test]
fn balls_with_rolling_resistance_stop_hold_and_roll_at_five_sevenths_of_the_net_pull() {
    // Worst measured 2.4·10⁻³ (2026-11-27, 10° slope, μr = tan θ − 0.02, rolling: the symplectic
    // step's own bias once the rolling pair is solved with friction held; 1.7 % before).
    holds(family("rolling resistance"), 0.01);
}

#[test]
fn a_free_box_keeps_its_energy_and_angular_momentum_about_any_axis() {
    // Worst measured 7.2·10⁻⁴ (2026-11-27, the energy at 20 rad/s about the intermediate axis;
    // L keeps its direction to rounding since the free rotation splits the energy by axes).
    holds(family("free spin"), 0.003);
}

#[test]
fn a_column_a_hundred_kilometres_from_the_origin_stands_as_one_at_the_origin() {
    // Worst measured 6·10⁻⁷ m (the 5-box column's penetration differs by f32 rounding; no drift);
    // limit 1 mm, the f32 grain at 10 km (7.8 mm at 100 km, where nothing moves sideways).
    holds(family("far from the origin"), 3e-6);
}

#[test]
fn balls_striking_off_centre_leave_as_the_impact_law_along_the_normal_of_impact_says() {
    // Worst measured 4.0·10⁻³ (0.1 m off-centre, e = 1; 0.25 and 0.4 m: 1.7·10⁻⁷) since the
    // speculative contact is taken at the time of impact (12.5 % before); the 1 % is
    // tighter than 3× that.
    holds(family("balls off-centre"), 0.015);
}

#[test]
fn a_ball_launched_with_any_spin_skids_then_rolls_at_five_v_minus_two_r_omega_over_seven() {
    // Worst measured 1.7·10⁻⁵ of v₀ (2026-11-27); limit 1 %.
    holds(family("skid to roll"), 1e-4);
}

#[test]
fn a_box_on_a_rough_ramp_stands_below_its_tipping_angle_and_tips_above() {
    // Worst measured 0.09 mm of creep for the standing boxes (2026-11-27); limit 5 mm.
    holds(family("tip or stand"), 5e-4);
}

#[test]
fn a_zero_g_melee_of_boxes_and_balls_keeps_its_momentum() {
    // Worst measured 2.0·10⁻⁷ of Σ m·|v| (2026-11-27); limit 10⁻⁵. Its sister family, "melee L and
    // energy", fails at the defaults and has no test yet (see `testing::corpus::melee`).
    holds(family("melee momentum"), 1e-5);
}

#[test]
fn a_ball_bouncing_obliquely_feels_friction_through_the_whole_impact() {
    // Worst measured 2.3·10⁻⁴ of the throw's speed (2026-11-27); limit 1 %. Before friction acted
    // on the rebound, sliding bounces kept 1/(1 + e) of it: 9.3 % off at e = 0.5, 18.5 % at e = 1.
    holds(family("oblique bounce"), 1e-3);
}

#[test]
fn a_ball_rolling_into_a_wall_hops_as_the_walls_friction_through_the_impact_lifts_it() {
    // Worst measured 7·10⁻⁵ of the hop's height (e = 0.5, μ = 0.5, 2026-12-02); limit 2 %. Read
    // as its highest step sample, the slippery elastic wall's hop was 3.3 % low (see
    // `testing::corpus::wall_hop`).
    holds(family("wall hop"), 3e-4);
}

#[test]
fn a_light_block_squeezed_between_a_wall_and_a_heavy_one_leaves_as_the_collisions_in_order_say() {
    // Worst measured 2.2·10⁻³ of the heavy block's speed (1:16, 2026-11-27); limit 1 %. Before the
    // events' impulses were applied directly, 1:16 was 4 % off and 1:100 ended nearly at rest.
    holds(family("wall squeeze"), 8e-3);
}

#[test]
fn a_box_pushed_at_its_top_stands_below_the_tipping_force_and_tips_above() {
    // Worst measured 0.08 mm for the standing boxes at 0.98 of the tipping force (2026-11-27);
    // limit 5 mm.
    holds(family("push to tip"), 5e-4);
}

#[test]
fn a_slender_block_tipped_onto_its_edge_reaches_upright_when_the_rigid_block_would() {
    // Worst measured 3.8·10⁻³ (h/b = 6 tipped to half its critical angle, 2026-12-01); limit 1 %.
    // Its sister family, "rocking: rebound", fails at the defaults and has no test yet (see
    // `testing::corpus::rocking`).
    holds(family("rocking: 1st impact"), 1.5e-2);
}

#[test]
fn galileos_cannon_sends_the_light_box_up_as_the_impacts_in_order_say() {
    // Worst measured 1.6·10⁻³ (M/m = 10, H = 0.5 m, 2026-11-27); limit 1 %.
    holds(family("galileo's cannon"), 6e-3);
}

#[test]
fn a_ball_dropped_on_a_frictionless_slope_leaves_along_its_normal() {
    // Worst measured 6.2·10⁻⁴ of the fall speed (40°, e = 1, 2026-11-27); limit 1 %.
    holds(family("slope bounce"), 3e-3);
}

#[test]
fn pendulums_keep_the_elliptic_period_on_hinges_and_rods() {
    // Worst measured 3.3·10⁻⁴ (a rod, 5°, 0.5 m; hinges within 7·10⁻⁵, 2026-11-28); limit 0.3 %.
    holds(family("pendulum period"), 1.5e-3);
}

#[test]
fn double_pendulums_keep_their_energy() {
    // Worst measured 0.59 % of the energy the fall releases (4 kg over 1 kg, hinged, 2026-11-28):
    // 3× that is past the 1 %, which holds.
    holds(family("double pendulum"), 0.01);
}

#[test]
fn chains_holding_a_hundred_times_a_link_do_not_stretch() {
    // Worst measured 1.9·10⁻⁵ of the length (10 links under 100×, 2026-11-28); limit 1 %.
    holds(family("loaded chain"), 1e-4);
}

#[test]
fn a_hinge_limit_stops_a_falling_arm() {
    // Worst measured 0.022° past the limit (error 0.043; 10 kg at 1 m, 2026-11-28); limit 0.5°.
    holds(family("hinge limit"), 0.2);
}
