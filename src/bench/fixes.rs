//! The convergence fixes on top of the soft step, each measured on the hard case it exists for with
//! the fix on and off (part of `nudge bench physics`). The same cases, with limits, are the tests in
//! `tests/physics/convergence_fixes.rs`.
//!
//! With the preload on (the default), two fixes are measured on the soft step without it, because
//! the statics alone hold their cases: the stack stands without the spread row (its boxes'
//! pressure balanced against the moment above them every step), and the pinned box holds without
//! the mass-ratio sweeps. The spread row and the sweeps are not
//! redundant: switched off in `Settings::default()`, each fails other tests of the suite besides its
//! own pin (the spread row: heavy on light, a box
//! landing flat, the light block squeezed against a wall, crowds pushed apart, a box dragged at a
//! wall, the pinned box under the hand; the sweeps: heavy on light up to 10⁴:1, the pinned box under
//! the hand, a body with more contacts than colours). The alternating order is measured at the
//! defaults, on a pile that rocks without it; the alternating sub-steps on the heap with its layers
//! visited bottom-up, no moment changes fed and every ball's rolling rows taking their held mass,
//! as it met the heap (at the defaults the heap now rests within 0.13 mm at 2 iterations either
//! way). Since a new support starts from the statics'
//! moments and a resting point within rounding of touching counts as touching, a pile built
//! resting lands still and stands without several fixes; their rows (the point order, the
//! symmetric relax, the moment changes, the anchors and their cap) are measured on the pile
//! landing as it used to (`kicked`), as their tests are. And since a resting pile carries a blow
//! from above as the ground would (`Settings::piles_carry_blows`), a small ball dropped on one no
//! longer knocks it: the rows whose case is such a knock (the touching spring, the thin soft range,
//! the sleep waiting for springs, the load changes) are measured with the blow passed down the pile
//! as it used to be (`knocked_down`), as their tests are.

use glam::Vec3;
use serde::Serialize;

use crate::bench::rest;
use crate::physics::Settings;
use crate::scene::Scene;
use crate::scene::piles::{self, Pile};
use crate::testing::hard_case::{self, Fixes, Knobs};

/// One fix, on and off.
#[derive(Clone, Debug, Serialize)]
pub struct FixRow {
    /// The fix.
    pub fix: &'static str,
    /// The case and what is measured.
    pub case: &'static str,
    /// The error with the fix on (the defaults), and off, in `unit`.
    pub on: f64,
    pub off: f64,
    pub unit: &'static str,
}

/// The fixes as the defaults have them, with `base` applied (the fixes a row's case is shown
/// without: the preload, for the two whose cases it now covers) and then, for the "off" run, `fix`.
fn knobs(base: fn(&mut Fixes), fix: Option<fn(&mut Fixes)>) -> Knobs {
    let mut knobs = Knobs::default();
    base(&mut knobs.fixes);
    if let Some(fix) = fix {
        fix(&mut knobs.fixes);
    }
    knobs
}

/// A fix's row: `measure` (mm) on its case with the fix on and off, both over `base`.
fn row(
    fix: &'static str,
    case: &'static str,
    measure: impl Fn(Knobs) -> f64,
    base: fn(&mut Fixes),
    switch_off: fn(&mut Fixes),
) -> FixRow {
    FixRow {
        fix,
        case,
        on: measure(knobs(base, None)),
        off: measure(knobs(base, Some(switch_off))),
        unit: "mm",
    }
}

/// Measures every fix on and off (about three seconds of wall time, most of it the piles watched
/// for a minute).
pub fn run() -> Vec<FixRow> {
    let mm = |m: f32| f64::from(m) * 1e3;
    let ten = 10.0;
    let stack_drift = |knobs| mm(hard_case::stack(10, Vec3::ZERO, ten, knobs).max_drift_m);
    let column_sink = |knobs| mm(hard_case::stack(30, Vec3::ZERO, ten, knobs).max_penetration_m);
    let awake_column_drift = |knobs: Knobs| {
        let knobs = Knobs {
            sleep: false,
            ..knobs
        };
        mm(hard_case::stack(30, Vec3::ZERO, ten, knobs).max_drift_m)
    };
    // A pile whose scene carries the knobs' settings (the rest bench builds its own world from the
    // scene's, at the sub-steps and sleeping each of its runs asks for).
    let pile = |scene: Scene, settle_s: f32, knobs: &Knobs| {
        let settings = knobs.settings(&scene.settings);
        Pile {
            scene: Scene { settings, ..scene },
            settle_s,
            until_still: false,
        }
    };
    // The copy of the spaced pyramid that rocks in one order (see the order's test).
    let rocking_at_eight = |knobs: Knobs| {
        let built = pile(crate::scene::cases::pyramid(20), 1.0, &knobs);
        mm(rest::watch_awake(&rest::perturbed(&built, 1), 8, 60.0).drift_m)
    };
    let sink = |knobs| mm(hard_case::mass_ratio(ten, knobs).max_penetration_m);
    let awake_drift = |scene: Scene, settle_s: f32, seconds: f32, knobs: Knobs| {
        let pile = pile(scene, settle_s, &knobs);
        mm(rest::watch_awake(&pile, knobs.substeps, seconds).drift_m)
    };
    // Without anchors the tower stands its first ten seconds and creeps after.
    let tower_drift = |knobs| awake_drift(piles::crossed_tower(20), 0.0, 60.0, knobs);
    let rocking = |knobs| awake_drift(piles::touching_pyramid(20), 1.0, ten, knobs);
    let tower_drift_at_two = |knobs: Knobs| {
        let pile = pile(piles::crossed_tower(20), 1.0, &knobs);
        mm(rest::watch_awake(&pile, 2, ten).drift_m)
    };
    let heap_drift = |knobs| awake_drift(piles::mixed_pile(40), 5.0, 60.0, knobs);
    let brick_wall_drift = |knobs| awake_drift(piles::brick_wall(12, 8), 1.0, 60.0, knobs);
    let heap_at_two_iterations = |knobs| {
        heap_drift(Knobs {
            iterations: 2,
            ..knobs
        })
    };
    let slide = |knobs| mm(hard_case::pinned_push_slide(120.0, 120, knobs).0);
    // A pile asleep, hit by the 20 g ball dropped from `drop_m` above it at `substeps`.
    let knocked = |scene: Scene, substeps: u32, drop_m: f32, knobs: Knobs| {
        let pile = pile(scene, 1.0, &knobs);
        mm(rest::woken_by_drop(&pile, substeps, drop_m).0)
    };
    let drop = rest::BALL_DROP_M;
    let knocked_plates = |knobs: Knobs| knocked(piles::plates(10), knobs.substeps, drop, knobs);
    let plates_hit_hard = |knobs: Knobs| knocked(piles::plates(10), knobs.substeps, 5.0, knobs);
    let woken_column = |knobs| knocked(crate::scene::cases::stack(50, Vec3::ZERO), 2, drop, knobs);
    let woken_tower = |knobs: Knobs| knocked(piles::crossed_tower(20), knobs.substeps, drop, knobs);
    let woken_wall =
        |knobs: Knobs| knocked(piles::running_bond_wall(12, 8), knobs.substeps, drop, knobs);
    let woken_wall_at_two = |knobs: Knobs| knocked(piles::running_bond_wall(12, 8), 2, drop, knobs);
    let wall_at_two = |knobs: Knobs| {
        let pile = pile(piles::brick_wall(12, 8), 1.0, &knobs);
        mm(rest::watch_awake(&pile, 2, 60.0).drift_m)
    };
    let touching_drift = |knobs| awake_drift(piles::touching_pyramid(20), 1.0, 60.0, knobs);
    let leaning_block = |knobs| mm(hard_case::let_go_leaning(12.0, 0.9, 40.0, knobs).0);
    let ragdolls_creep = |knobs| mm(hard_case::ragdoll_pile_creep(0, knobs));
    let woken_heap = |knobs: Knobs| {
        let pile = pile(piles::mixed_pile(40), 5.0, &knobs);
        mm(rest::woken(&pile, 8).0)
    };
    // The corpus's chain of 20 light links under 100 times a link, at 2 sub-steps.
    let loaded_chain_at_two = |knobs: Knobs| {
        let knobs = Knobs {
            substeps: 2,
            ..knobs
        };
        let chain = crate::testing::corpus::joints::chain_outcome(
            (20, 100.0, crate::testing::corpus::joints::LINK_RADIUS),
            knobs,
        );
        mm(chain.error * crate::testing::corpus::joints::chain_length(20))
    };
    // The corpus's chain of 20 links of 1 cm balls under 100 times a link, at the default sub-steps.
    let small_chain = |knobs: Knobs| {
        let chain = crate::testing::corpus::joints::chain_outcome((20, 100.0, 0.01), knobs);
        mm(chain.error * crate::testing::corpus::joints::chain_length(20))
    };
    // The corpus's heaviest arm on its hinge limit at 1 sub-step, in degrees.
    let limit_at_one = |knobs: Knobs| {
        let knobs = Knobs {
            substeps: 1,
            iterations: 1,
            sleep: false,
            ..knobs
        };
        let arm = crate::testing::corpus::joints::limit_outcome((10.0, 1.0, 30.0), knobs);
        f64::from(arm.error * crate::testing::corpus::joints::LIMIT_GIVE).to_degrees()
    };
    let defaults: fn(&mut Fixes) = |_| {};
    // Piles landing as they did before new supports were balanced and resting points had a
    // touching tolerance: built resting and landing still, they now stand without the fixes shown
    // on them (see `tests/physics/rest.rs`, `kicked`).
    let kicked: fn(&mut Fixes) = |f| {
        f.balance_new_supports = false;
        f.touching_tolerance = false;
    };
    let no_preload: fn(&mut Fixes) = |f| f.preload = false;
    // A ball's blow passed down the pile a layer a pass, as before piles carried blows: the knock
    // these fixes exist for (see the module docs).
    let knocked_down: fn(&mut Fixes) = |f| f.piles_carry_blows = false;
    // The heap as the alternating sub-steps met it, before the layers' alternation, the moment
    // changes and the wedged balls' own rolling mass, which now hold it either way (see the module
    // docs).
    let bottom_up: fn(&mut Fixes) = |f| {
        f.alternate_layer_order = false;
        f.feed_moment_changes = false;
        f.rolling_held_mass_alone = false;
    };
    vec![
        row(
            "spread row",
            "stack(10), preload off, 10 s: drift",
            stack_drift,
            no_preload,
            |f| f.spread_row = false,
        ),
        row(
            "preload",
            "column of 30, 10 s: penetration",
            column_sink,
            defaults,
            no_preload,
        ),
        row(
            "preload",
            "column of 30, sleeping off, 10 s: drift",
            awake_column_drift,
            defaults,
            no_preload,
        ),
        row(
            "alternating point order",
            "pyramid(20) copy 1, 8 sub-steps, sleeping off, 60 s: drift",
            rocking_at_eight,
            kicked,
            |f| f.alternate_point_order = false,
        ),
        row(
            "alternating sub-steps",
            "mixed pile(40), 2 iterations, layers bottom-up, sleeping off, 60 s: drift",
            heap_at_two_iterations,
            bottom_up,
            |f| f.alternate_sub_steps = false,
        ),
        row(
            "alternating layer order",
            "mixed pile(40), sleeping off, 60 s: drift",
            heap_drift,
            defaults,
            |f| f.alternate_layer_order = false,
        ),
        row(
            "symmetric relax",
            "touching pyramid(20), sleeping off, 10 s: drift",
            rocking,
            kicked,
            |f| f.symmetric_relax = false,
        ),
        row(
            "touching spring",
            "plates(10) asleep, woken by a 20 g ball: drift 10 s after",
            knocked_plates,
            knocked_down,
            |f| f.touching_spring = false,
        ),
        row(
            "thin soft range",
            "plates(10) asleep, a 20 g ball dropped 5 m on them: drift 10 s after",
            plates_hit_hard,
            knocked_down,
            |f| f.thin_soft_range = false,
        ),
        row(
            "sleep waits for springs",
            "column of 50 asleep at 2 sub-steps, woken by a 20 g ball: drift 10 s after",
            woken_column,
            |f| {
                f.sleep_waits_while_speeding_up = false;
                f.piles_carry_blows = false;
            },
            |f| f.sleep_waits_for_springs = false,
        ),
        row(
            "load changes fed",
            "crossed tower(20) asleep, woken by a 20 g ball: drift 10 s after",
            woken_tower,
            knocked_down,
            |f| f.feed_load_changes = false,
        ),
        row(
            "piles carry blows",
            "running bond wall(12) asleep, woken by a 20 g ball: drift 10 s after",
            woken_wall,
            defaults,
            |f| f.piles_carry_blows = false,
        ),
        row(
            "moment changes fed",
            "brick wall(12) of real bricks, sleeping off, 60 s: drift",
            brick_wall_drift,
            kicked,
            |f| f.feed_moment_changes = false,
        ),
        row(
            "balanced new supports",
            "brick wall(12) of real bricks, 2 sub-steps, sleeping off, 60 s: drift",
            wall_at_two,
            defaults,
            |f| f.balance_new_supports = false,
        ),
        row(
            "touching tolerance",
            "touching pyramid(20), sleeping off, 60 s: drift",
            touching_drift,
            defaults,
            |f| f.touching_tolerance = false,
        ),
        row(
            "sleep waits while speeding up",
            "block 2.4 m high let go at 0.9 of its critical angle, 40 s: top off upright",
            leaning_block,
            defaults,
            |f| f.sleep_waits_while_speeding_up = false,
        ),
        row(
            "statics skip jointed bodies",
            "pile of 4 ragdolls, 60 s: how far a part moved in the last 30 s",
            ragdolls_creep,
            defaults,
            |f| f.statics_skip_jointed = false,
        ),
        row(
            "joints' geometric stiffness",
            "chain of 20 light links under 100× a link, 2 sub-steps, 10 s: stretch",
            loaded_chain_at_two,
            defaults,
            |f| f.joint_geometric_stiffness = false,
        ),
        row(
            "joints' pull from their load",
            "chain of 20 links of 1 cm balls under 100× a link, 10 s: stretch",
            small_chain,
            defaults,
            |f| f.joint_pull_from_load = false,
        ),
        FixRow {
            unit: "°",
            ..row(
                "joints' scalar rows last",
                "10 kg arm on 1 m falling onto a 30° hinge limit, 1 sub-step, 5 s: past it",
                limit_at_one,
                defaults,
                |f| f.joint_scalar_rows_last = false,
            )
        },
        row(
            "symmetric biased pass",
            "running bond wall(12) asleep, 2 sub-steps, woken by a 20 g ball: drift 10 s after",
            woken_wall_at_two,
            defaults,
            |f| f.symmetric_biased_pass = false,
        ),
        row(
            "wedged balls roll with their own mass",
            "mixed pile(40) asleep, 8 sub-steps, woken by a 20 g ball: drift 10 s after",
            woken_heap,
            defaults,
            |f| f.rolling_held_mass_alone = false,
        ),
        row(
            "friction anchors",
            "crossed tower(20), sleeping off, 60 s: drift",
            tower_drift,
            kicked,
            |f| f.friction_anchors = false,
        ),
        row(
            "anchor frequency cap",
            "crossed tower(20), 2 sub-steps, sleeping off, 10 s: drift",
            tower_drift_at_two,
            kicked,
            |f| f.anchor_frequency_cap = false,
        ),
        row(
            "shock propagation",
            "1000 kg on 1 kg, 10 s: penetration",
            sink,
            defaults,
            |f| f.shock_propagation = false,
        ),
        row(
            "mass-ratio sweeps",
            "1 kg pinned under 1000 kg, preload off, 120 N for 2 s: slide",
            slide,
            no_preload,
            |f| f.mass_ratio_sweeps = false,
        ),
        FixRow {
            fix: "mass-ratio sweeps (heavy load)",
            case: "3 kg plank under 100 balls, second second: ball off its rest",
            on: mm(hard_case::plank_ball_error(
                Settings::default().mass_ratio_iterations,
            )),
            off: mm(hard_case::plank_ball_error(0)),
            unit: "mm",
        },
    ]
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(
    fix_rows: &[FixRow],
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "physics: each convergence fix on its hard case, on (the defaults) and off"
    )?;
    let mut table = Table::new(&["fix", "case", "on", "off"]);
    for r in fix_rows {
        table.push(vec![
            r.fix.to_string(),
            r.case.to_string(),
            format!("{:.3} {}", r.on, r.unit),
            format!("{:.3} {}", r.off, r.unit),
        ]);
    }
    table.write(out)
}
