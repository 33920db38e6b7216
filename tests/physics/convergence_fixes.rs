//! Every convergence fix on top of the soft step, pinned to the hard case it exists for: each test runs
//! that case with the fix on, passing the hard-case test's tolerance, and with the fix off, failing it.
//! A fix whose "off" run starts passing is no longer load-bearing and should be removed (see
//! `contact_solver` for each fix's derivation). Default settings otherwise.
//!
//! What each fix buys, on and off, is measured by `nudge bench physics` (its "fixes" table).

use glam::Vec3;
use nudge::bench::rest::{self, MAX_SPEED_M_S};
use nudge::physics::Settings;
use nudge::scene::piles::Pile;
use nudge::testing::hard_case::{self, Fixes, Knobs};

use crate::rest::kicked;

const TEN_SECONDS: f32 = 10.0;

/// The default knobs with `switch` applied to the fixes.
fn knobs_with(switch: impl Fn(&mut Fixes)) -> Knobs {
    let mut knobs = Knobs::default();
    switch(&mut knobs.fixes);
    knobs
}

#[test]
fn the_spread_row_keeps_a_ten_box_stack_from_walking() {
    /// The ten-box stack test's drift limit, metres.
    const MAX_DRIFT_M: f32 = 0.001;
    let drift = |knobs| hard_case::stack(10, Vec3::ZERO, TEN_SECONDS, knobs).max_drift_m;
    // With the preload (on by default), the warm start already carries the uniform load the spread
    // row exists to find, and the stack stands either way: the spread row's case is shown on the
    // soft step without it.
    let on = drift(knobs_with(|f| f.preload = false));
    let off = drift(knobs_with(|f| {
        f.preload = false;
        f.spread_row = false;
    }));
    assert!(on < MAX_DRIFT_M, "with the spread row: {on} m");
    assert!(
        off > MAX_DRIFT_M,
        "without it the stack should walk: {off} m"
    );
}

#[test]
fn the_preload_keeps_a_thirty_box_column_from_sinking_into_itself() {
    /// The penetration limit for the column of 30, metres.
    const MAX_PENETRATION_M: f32 = 0.005;
    /// Without the preload the lowest spring compresses by load/(m_eff·ω²), about 0.55 mm per box
    /// above it: well over this.
    const SUNK_M: f32 = 0.010;
    let penetration =
        |knobs| hard_case::stack(30, Vec3::ZERO, TEN_SECONDS, knobs).max_penetration_m;
    let on = penetration(Knobs::default());
    let off = penetration(knobs_with(|f| f.preload = false));
    assert!(on < MAX_PENETRATION_M, "with the preload: {on} m");
    assert!(off > SUNK_M, "without it the column should sink: {off} m");
}

/// With the preload, every contact of a column rests at the top of its slop band, and a patch whose
/// friction statics change starts its step with the pressure that balances the moment of what rests
/// on it (see `prepare::preload`): kept awake, the columns that buckled on their contacts' 30 Hz tilt
/// stiffness stand. Without it a column of 30 sways off its base.
#[test]
fn the_preload_keeps_awake_columns_standing() {
    /// The tower family's drift limit, metres, and the penetration limit.
    const MAX_DRIFT_M: f32 = 0.010;
    const MAX_PENETRATION_M: f32 = 0.005;
    let awake = |knobs: Knobs| Knobs {
        sleep: false,
        ..knobs
    };
    for boxes in [10, 20, 30] {
        let out = hard_case::stack(boxes, Vec3::ZERO, TEN_SECONDS, awake(Knobs::default()));
        assert!(
            out.max_drift_m < MAX_DRIFT_M && out.max_penetration_m < MAX_PENETRATION_M,
            "{boxes} boxes with the preload: {out:?}"
        );
    }
    let off = hard_case::stack(
        30,
        Vec3::ZERO,
        TEN_SECONDS,
        awake(knobs_with(|f| f.preload = false)),
    );
    assert!(
        off.max_drift_m > MAX_DRIFT_M,
        "without it the column should sway: {off:?}"
    );
}

/// The preload is for loads at rest: a ball dropped with it on still bounces as restitution says
/// (a contact that carried nothing and may close faster than the threshold within the step is an
/// impact), and a pile falling together carries nothing (only supports that reach a static body
/// are preloaded), so Galileo's cannon still fires.
#[test]
fn the_preload_leaves_impacts_to_restitution() {
    use nudge::testing::corpus;
    let defaults = Knobs::default();
    let names = ["ball drop", "galileo's cannon", "bouncy at rest"];
    let families: Vec<_> = corpus::families()
        .into_iter()
        .filter(|f| names.contains(&f.name))
        .collect();
    assert_eq!(families.len(), names.len(), "a family was renamed");
    for family in families {
        for substeps in [2, 4] {
            let knobs = Knobs {
                substeps,
                ..defaults
            };
            for member in &family.members {
                let out = (member.run)(knobs);
                assert!(
                    out.error <= member.tolerance,
                    "{} {} at {substeps} sub-steps with the preload: {}",
                    family.name,
                    member.label,
                    out.detail
                );
            }
        }
    }
}

/// The spaced 20-row pyramid kept awake a minute at 8 sub-steps, in the copy of `nudge bench rest`
/// whose boxes are moved sideways by up to 2 µm (`bench::rest::perturbed`, copy 1): solved in one
/// point order every sub-step, it rocks and is still moving at 1.9 mm/s in its last second (0.5 mm
/// from where it settled); alternating, it stands within 0.02 mm and under 0.001 mm/s (measured
/// 2026-11-30). Before manifolds were followed to where their bodies are (`narrow::contact`,
/// `Contact::follow`) the order's case was a stack of eight on the bare soft step, which whirled
/// 21 mm in 10 s in one order; with current geometry it stands either way (0.12 mm). Measured with
/// every biased pass bottom-up (`Settings::alternate_layer_order` off) and no moment changes fed
/// (`Settings::feed_moment_changes`): passes going up and down in turn hold this copy in one point
/// order too (0.006 mm), and so do the moment changes (0.003 mm, 2026-11-30).
#[test]
fn alternating_the_point_order_keeps_an_awake_pyramid_at_eight_sub_steps_from_rocking() {
    let mut pyramid = nudge::scene::cases::pyramid(20);
    pyramid.settings.alternate_layer_order = false;
    pyramid.settings.feed_moment_changes = false;
    // Landing as it did: built resting and landing still, it now stands in one point order too.
    let pile = rest::perturbed(
        &kicked(Pile {
            scene: pyramid,
            settle_s: 1.0,
            until_still: false,
        }),
        1,
    );
    let on = rest::watch_awake(&pile, 8, 60.0);
    assert!(
        on.drift_m < 0.0001 && on.speed_m_s < MAX_SPEED_M_S,
        "alternating: {on:?}"
    );
    let mut one_order = pile.clone();
    one_order.scene.settings.alternate_point_order = false;
    let off = rest::watch_awake(&one_order, 8, 60.0);
    assert!(off.speed_m_s > MAX_SPEED_M_S, "in one order: {off:?}");
}

#[test]
fn shock_propagation_holds_a_thousand_kilograms_on_one() {
    /// The 1000:1 test's penetration limit, metres.
    const MAX_PENETRATION_M: f32 = 0.0001;
    let penetration = |knobs| hard_case::mass_ratio(TEN_SECONDS, knobs).max_penetration_m;
    let on = penetration(Knobs::default());
    let off = penetration(knobs_with(|f| f.shock_propagation = false));
    assert!(on < MAX_PENETRATION_M, "with the shock pass: {on} m");
    assert!(
        off > MAX_PENETRATION_M,
        "without it the heavy box should sink: {off} m"
    );
}

/// The sweeps' case is shown without the preload: with it, the friction statics alone hold the
/// pinned box (its floor and the heavy box's contact start each step with the friction the push
/// asks of them, within their limits), so the sweeps are no longer what holds it.
#[test]
fn the_mass_ratio_sweeps_hold_a_light_box_pinned_under_a_heavy_one() {
    /// The pinned-box test's slide limit, metres, under its strong hand (120 N for 2 s).
    const MAX_SLIDE_M: f32 = 0.003;
    let slide = |knobs| hard_case::pinned_push_slide(120.0, 120, knobs).0;
    let on = slide(knobs_with(|f| f.preload = false));
    let off = slide(knobs_with(|f| {
        f.preload = false;
        f.mass_ratio_sweeps = false;
    }));
    assert!(on < MAX_SLIDE_M, "with the sweeps: {on} m");
    assert!(
        off > MAX_SLIDE_M,
        "without them the light box should slide out: {off} m"
    );
    let preload_alone = slide(knobs_with(|f| f.mass_ratio_sweeps = false));
    assert!(
        preload_alone < MAX_SLIDE_M,
        "with the preload and no sweeps: {preload_alone} m"
    );
}

/// A light plank under a crowd has no mass ratio at any contact, only in load: the heavy-load
/// marking gives its contacts the sweeps.
#[test]
fn the_mass_ratio_sweeps_reach_a_light_plank_under_a_heavy_load() {
    /// How far a ball may sit from resting on the plank over the second second, metres (measured
    /// 1.08 mm with the sweeps, 27.1 mm without, 2026-11-29; 0.85 and 20.1 mm before the plank, a
    /// symmetric top, turned by its exact flow).
    const MAX_BALL_ERROR_M: f32 = 0.003;
    let on = hard_case::plank_ball_error(Settings::default().mass_ratio_iterations);
    let off = hard_case::plank_ball_error(0);
    assert!(on < MAX_BALL_ERROR_M, "with the sweeps: {on} m");
    assert!(
        off > MAX_BALL_ERROR_M,
        "without them the balls should jiggle: {off} m"
    );
}

/// The preload's own hard case, with it on: a light ball bouncing on a stack. Its contact is a mass
/// ratio's, which takes no preload but must still hand the ball's weight down; when it did not, the
/// stack sank 0.6 mm under each impact and the ball rebounded 2–4 % high off it.
#[test]
fn with_the_preload_a_ball_bounces_on_a_stack_as_from_the_floor() {
    let family = nudge::testing::corpus::families()
        .into_iter()
        .find(|f| f.name == "ball on a stack")
        .expect("the corpus has the ball on a stack");
    let knobs = Knobs::default();
    for member in &family.members {
        let out = (member.run)(knobs);
        assert!(
            nudge::testing::corpus::within(out.error, member.tolerance),
            "{}: error {} > {}: {}",
            member.label,
            out.error,
            member.tolerance,
            out.detail
        );
    }
}
