//! Piles kept awake stay where they settled: the awake twins of the sleeping tower tests. Each
//! threshold is a few times what the engine measures (`nudge bench rest` prints the figures for
//! every pile at 2, 4 and 8 sub-steps; not every pile there holds yet, and these pin the ones that
//! do, so that the next change to the solver cannot lose them unnoticed).

use glam::Vec3;
use nudge::bench::rest::{self, AwakeRun, MAX_DRIFT_M, MAX_SPEED_M_S};
use nudge::scene::cases;
use nudge::scene::piles::{self, Pile};
use nudge::testing::hard_case::{Fixes, Knobs};

fn built(scene: nudge::scene::Scene) -> Pile {
    Pile {
        scene,
        settle_s: 1.0,
        until_still: false,
    }
}

/// `pile` with every biased pass bottom-up (`Settings::alternate_layer_order` off, as below 4
/// sub-steps) and no moment changes fed (`Settings::feed_moment_changes`): the pile as the fixes
/// pinned on it met it. Passes going up and down in turn, and the moment changes, now hold these
/// piles without those fixes too (`alternating_layers_keep_an_awake_heap_still`), so each fix is
/// shown where it is what holds them.
fn bottom_up(mut pile: Pile) -> Pile {
    pile.scene.settings.alternate_layer_order = false;
    pile.scene.settings.feed_moment_changes = false;
    pile
}

/// `pile` landing as piles did before a new support's first warm start carried its patch's moment
/// (`Settings::balance_new_supports`) and a resting point within rounding of touching counted as
/// touching (`Settings::touching_tolerance`): its first step kicks it, and its points flicker
/// between rows. Built resting and landing still, the piles below now stand without the fixes
/// they pin as well; each of those fixes is shown on the pile as it met it.
pub(crate) fn kicked(mut pile: Pile) -> Pile {
    pile.scene.settings.balance_new_supports = false;
    pile.scene.settings.touching_tolerance = 0.0;
    pile
}

/// `pile` knocked as piles were before they carried a blow from above as the ground would
/// (`Settings::piles_carry_blows`): a small ball dropped on it is passed down it a layer a pass,
/// and a heap dropped into its pit lands as it did then. The fixes below that exist for such a
/// knock, or were pinned on the heap as it landed then, are shown on the pile as they met it.
fn knocked_down(mut pile: Pile) -> Pile {
    pile.scene.settings.piles_carry_blows = false;
    pile
}

/// `pile` with its balls' rolling rows as they were before a contact took the mass it has with its
/// friction held only where it is its bodies' only one (`Settings::rolling_held_mass_alone`): the
/// heap's balls, most of them resting between boxes, land and rest a little differently with it.
/// The fixes pinned on the heap as it rested then are shown on it as they met it.
fn rolling_as_before(mut pile: Pile) -> Pile {
    pile.scene.settings.rolling_held_mass_alone = false;
    pile
}

/// How far each of `nudge bench rest`'s copies of `pile` (`rest::perturbed`) ends from where it
/// slept, woken by the 20 g ball at `substeps` (`rest::woken`), m.
fn woken_copies(pile: &Pile, substeps: u32) -> Vec<f32> {
    (0..rest::COPIES)
        .map(|k| rest::woken(&rest::perturbed(pile, k), substeps).0)
        .collect()
}

/// Watches `pile` awake for a minute at `substeps` and checks it moved at most `drift_m` from where
/// it settled and moved no faster than `speed_m_s` over the last second.
fn stands(pile: &Pile, substeps: u32, drift_m: f32, speed_m_s: f32) -> AwakeRun {
    let run = rest::watch_awake(pile, substeps, 60.0);
    assert!(
        run.drift_m <= drift_m && run.speed_m_s <= speed_m_s,
        "{} at {substeps} sub-steps: {run:?}",
        pile.scene.name
    );
    run
}

/// A box that friction holds on a 30° ramp stays put, awake, at every sub-step count: friction
/// that holds must hold exactly, not creep down the slope.
#[test]
fn a_box_held_by_friction_on_a_ramp_stays_put_for_a_minute_awake() {
    let pile = built(piles::box_on_ramp());
    for substeps in rest::SUBSTEPS {
        stands(&pile, substeps, MAX_DRIFT_M, MAX_SPEED_M_S);
    }
}

/// Columns of ten, thirty and fifty boxes kept awake a minute stand still at 2, 4 and 8 sub-steps
/// (at most 0.15 mm, measured 2026-11-28). A column leaned over while its patches' pressure was
/// balanced against the moment above only on the steps its friction's demand changed (a column of
/// thirty 235 mm at 4 sub-steps); balanced on every step, it stands (`prepare::preload`).
#[test]
fn columns_of_ten_to_fifty_kept_awake_stand_still_for_a_minute() {
    for count in [10, 30, 50] {
        let column = built(cases::stack(count, Vec3::ZERO));
        for substeps in rest::SUBSTEPS {
            stands(&column, substeps, 0.0005, MAX_SPEED_M_S);
        }
    }
}

/// The same columns asleep, woken by a 20 g ball dropped on top (`bench::rest::woken`), settle
/// back where they slept. Inside the slop band a contact's row neither leaked nor pushed, so the
/// knock left each contact a little deeper in it and the column shorter for good (1.2 and 1.3 mm
/// for thirty and fifty boxes at 4 sub-steps, 0.46 and 0.72 mm at 8); determinate supports are
/// springs centred where they touch (`wide_contacts::velocity`, `Settings::touching_spring`), and
/// the island sleeps only once those springs rest (`sleep`, "Pressed springs"). Measured
/// 2026-11-29, as built: 0.030, 0.17 and 0.27 mm for ten, thirty and fifty boxes at 2 sub-steps;
/// 0.007, 0.094 and 0.12 mm at 4; 0.006, 0.046 and 0.085 mm at 8. Thresholds about three times
/// those: 1 mm (the issue's) at 2 sub-steps, 0.3 mm at 4 and 8. Knocked as they were then
/// (`knocked_down`): carrying the blow, they barely move
/// (`resting_piles_woken_by_a_small_ball_carry_its_blow_at_every_sub_step_count`).
#[test]
fn columns_woken_by_a_small_ball_settle_back_where_they_slept() {
    for count in [10, 30, 50] {
        let column = knocked_down(built(cases::stack(count, Vec3::ZERO)));
        for substeps in rest::SUBSTEPS {
            let limit = if substeps == 2 { MAX_DRIFT_M } else { 0.0003 };
            let (drift, slept) = rest::woken(&column, substeps);
            assert!(
                slept && drift < limit,
                "stack({count}) woken at {substeps} sub-steps: {drift} m"
            );
        }
    }
}

/// Put to sleep on its speed alone, half a second after the knock, a column keeps the dent its
/// touching springs were still pushing out (at their rate, about 9/s, times their depth: a
/// millimetre a second at 0.1 mm, far under the sleep speed): thirty and fifty boxes at 2
/// sub-steps slept 1.44 mm short (measured 2026-11-29; 0.17 and 0.27 mm waiting for the springs,
/// above). At 4 sub-steps, where fifty boxes slept 0.79 mm short while reused manifolds kept
/// stale separations, they now sleep 0.16 mm from where they stood either way (2026-11-30). On
/// its speed alone: a column whose springs push it back speeds up as they do, and waiting while
/// bodies speed up (`sleep`, "Speeding up") keeps it awake too (thirty boxes then slept 0.21 mm
/// short, 2026-12-01), so that rule is off here as well.
#[test]
fn a_column_woken_by_a_ball_sleeps_where_it_stood_only_once_its_springs_rest() {
    for (count, substeps) in [(30, 2), (50, 2)] {
        let mut column = knocked_down(built(cases::stack(count, Vec3::ZERO)));
        column.scene.settings.sleep_waits_for_springs = false;
        column.scene.settings.sleep_waits_while_speeding_up = false;
        let (drift, slept) = rest::woken(&column, substeps);
        assert!(
            slept && drift > 0.0006,
            "stack({count}) woken at {substeps} sub-steps, asleep on its speed alone: {drift} m"
        );
    }
}

/// Piles whose loads statics cannot split (neighbours flush side by side, bricks over joints)
/// kept awake a minute at 2, 4 and 8 sub-steps. They keep the solver's own warm start once they
/// have one (`prepare::preload`, "Determinate loads"; reset to the lever rule's every step, a
/// touching 20-row pyramid drifted 71 mm in a minute at 4 sub-steps and a running-bond wall fell),
/// start from the statics' moments (`prepare::preload`, "New supports") and rest touching within
/// rounding (`Settings::touching_tolerance`). Measured as built, 2026-12-01: every one within
/// 1.4 µm of where it settled and under 0.7 µm/s (the spaced pyramid at 2 sub-steps the most),
/// most within 0.2 µm; before the last two, at 2 sub-steps the touching pyramid's top swayed
/// 1.1 mm and both walls fell, and at 4 the walls rested 0.4 mm off. Thresholds about five times
/// those.
#[test]
fn pyramids_and_walls_kept_awake_do_not_creep_or_fall() {
    let piles = [
        built(piles::touching_pyramid(20)),
        built(cases::pyramid(20)),
        built(piles::running_bond_wall(12, 8)),
        built(piles::brick_wall(12, 8)),
    ];
    for pile in &piles {
        for substeps in rest::SUBSTEPS {
            let drift = if substeps == 2 { 0.000007 } else { 0.000002 };
            stands(pile, substeps, drift, 0.000004);
        }
    }
}

/// A wall of real bricks built resting and kept awake at 2 sub-steps. Its end bricks carry the
/// course above on half their length; a new support's first warm start shared evenly over its
/// points (the load, not its moment) turned the bottom course's end brick 7 mrad in the first
/// step, and the wall, rocking from there, fell within two seconds (1.1 m in a minute). Started
/// from the statics' moments (`Settings::balance_new_supports`, `prepare::preload`, "New
/// supports") it does not move when its first step begins: 0.4 µm in a minute, 0.2 µm/s
/// (measured 2026-12-01). Shown with the biased pass visiting one way, as it did then: visiting a
/// preloaded face both ways at 2 sub-steps (`Settings::symmetric_biased_pass`), the wall stands
/// kicked too.
#[test]
fn a_wall_built_at_two_sub_steps_stands_only_with_balanced_new_supports() {
    let wall = built(piles::brick_wall(12, 8));
    stands(&wall, 2, 0.000002, 0.000001);
    let mut even = wall.clone();
    even.scene.settings.balance_new_supports = false;
    even.scene.settings.symmetric_biased_pass = false;
    let run = rest::watch_awake(&even, 2, 10.0);
    assert!(run.drift_m > 0.1, "shared evenly: {run:?}");
}

/// The touching pyramid built resting and kept awake at 4 sub-steps. Landing still (above), its
/// points rest at zero separation, where the rounding of its poses flipped them between a
/// speculative row (rigid, its gap a bias) and the slop band's (soft) from step to step: the
/// flicker rocked the pyramid out of its plane, still for half a minute and then swinging, 1.0 mm
/// from where it stood after a minute at 3 mm/s. Counting a point within half a micrometre of
/// touching as touching (`Settings::touching_tolerance`) it stands within 0.2 µm, 0.4 µm/s
/// (measured 2026-12-01).
#[test]
fn a_touching_pyramid_built_and_kept_awake_stands_only_with_a_touching_tolerance() {
    let pyramid = built(piles::touching_pyramid(20));
    stands(&pyramid, 4, 0.000001, 0.000002);
    let mut flicker = pyramid.clone();
    flicker.scene.settings.touching_tolerance = 0.0;
    let run = rest::watch_awake(&flicker, 4, 60.0);
    assert!(run.speed_m_s > MAX_SPEED_M_S, "no tolerance: {run:?}");
}

/// The touching pyramid on the soft step alone, every convergence fix off (`Fixes::NONE`: no
/// statics, spread rows, anchors, symmetric or alternating passes, touching tolerance), kept
/// awake: it stirs, 1.37 mm from where it settled after a minute and moving at up to 8.4 mm/s
/// over its last second (measured 2026-12-03), where the defaults hold it within a micrometre
/// (`a_touching_pyramid_built_and_kept_awake_stands_only_with_a_touching_tolerance`). What the
/// fixes cost beside Rapier is `rapier-bench --versus`'s "soft step alone" row.
#[test]
fn a_touching_pyramid_kept_awake_stands_only_with_the_convergence_fixes() {
    let mut pyramid = built(piles::touching_pyramid(20));
    let knobs = Knobs {
        fixes: Fixes::NONE,
        ..Knobs::default()
    };
    pyramid.scene.settings = knobs.settings(&pyramid.scene.settings);
    let run = rest::watch_awake(&pyramid, 4, 60.0);
    println!("soft step alone: {run:?}");
    assert!(
        run.speed_m_s > 2.0 * MAX_SPEED_M_S,
        "soft step alone: {run:?}"
    );
}

/// A running-bond wall built to scale (`piles::brick_wall`: real bricks, 12 courses, 78 cm high and
/// 10 cm thick) kept awake. Its supports are indeterminate (bricks over joints, flush neighbours),
/// so their pressure is the solver's own, and without the statics' moment changes
/// (`Settings::feed_moment_changes`) the news of a lean reaches its lower courses one pass at a
/// time: it leans out of its plane and falls within seconds at the default 4 sub-steps (every one
/// of eight copies, 2026-11-30). Fed, it stands: 0.16 mm at 4 sub-steps and 0.07 mm at 8 (0.05 to
/// 0.23 mm and 0.05 to 0.07 over the eight copies).
#[test]
fn a_wall_of_real_bricks_kept_awake_stands_only_with_moment_changes_fed() {
    let wall = kicked(built(piles::brick_wall(12, 8)));
    stands(&wall, 4, 0.0008, MAX_SPEED_M_S);
    stands(&wall, 8, 0.0003, MAX_SPEED_M_S);
    let mut unfed = wall.clone();
    unfed.scene.settings.feed_moment_changes = false;
    let run = rest::watch_awake(&unfed, 4, 10.0);
    assert!(run.drift_m > 0.01, "without: {run:?}");
}

/// The same wall asleep, woken by a 20 g ball dropped on its top (`bench::rest::woken`). The ball
/// comes to rest on the top course on one point, off level. While no support under a body resting
/// off level was fed, that ball took the whole wall under it off the moment changes, and the woken
/// wall leaned as an unfed one does: 2.4 mm from where it slept at 4 sub-steps, 11 mm in the worst
/// of `nudge bench rest`'s eight copies. Fed on every level face, with the moment of the loads
/// alone (`prepare::preload`, "Moment changes"), it rests 0.23 mm from where it slept (0.18 to
/// 0.42 mm over the copies, 2026-11-30), knocked as it was then (`knocked_down`).
#[test]
fn a_sleeping_wall_of_real_bricks_woken_by_a_small_ball_stands() {
    let wall = knocked_down(built(piles::brick_wall(12, 8)));
    let (drift, slept) = rest::woken(&wall, 4);
    assert!(slept, "the wall never slept");
    assert!(drift < 0.0008, "woken at 4 sub-steps it moved {drift} m");
}

/// The touching pyramid kept awake at the default 4 sub-steps, with the relax pass visiting each
/// manifold's points once (`Settings::symmetric_relax` off): its top two thirds rock out of its
/// plane on the middle rows' contacts with a period of about 3 s and do not settle, 1.7 mm from
/// where it stood after a minute and 1.6 mm/s at its fastest in the last second (measured
/// 2026-11-29). Visited forward and back, 0.07 mm and 0.11 mm/s.
#[test]
fn the_symmetric_relax_keeps_an_awake_touching_pyramid_from_rocking() {
    let mut pyramid = kicked(bottom_up(built(piles::touching_pyramid(20))));
    stands(&pyramid, 4, 0.0003, 0.0005);
    pyramid.scene.settings.symmetric_relax = false;
    let run = rest::watch_awake(&pyramid, 4, 60.0);
    assert!(
        run.drift_m > MAX_DRIFT_M && run.speed_m_s > MAX_SPEED_M_S,
        "visited once: {run:?}"
    );
}

/// A crossed ("jenga") tower of twenty layers kept awake: friction couples its layers (each block
/// crosses two below near their ends), and a rigid friction row warm-started from last step let
/// its sway grow: the tower fell within seconds, at 4 and 8 sub-steps alike, and since its blocks'
/// contacts stopped flickering (`box_box`, "Near-face edge axes") it still creeps 12 mm in a
/// minute at 4. Held at anchors it stands: measured 2026-11-28, 0.014 mm at 4 sub-steps and 0.005
/// mm at 8 over a minute.
#[test]
fn an_awake_crossed_tower_holds_still_only_with_friction_anchors() {
    let tower = bottom_up(built(piles::crossed_tower(20)));
    stands(&tower, 4, 0.00007, MAX_SPEED_M_S);
    stands(&tower, 8, 0.00003, MAX_SPEED_M_S);
    let mut unanchored = tower.clone();
    unanchored.scene.settings.friction_anchors = false;
    let run = rest::watch_awake(&unanchored, 4, 60.0);
    assert!(run.drift_m > 0.005, "without anchors: {run:?}");
}

/// The same tower kept awake at 2 sub-steps. Its anchors between blocks at the contacts' 30 Hz, a
/// quarter of the sub-step rate, made its sway grow (doubling about every 0.5 s from 3 s on, 87 mm
/// at 10 s) until it fell; at an eighth of that rate (`Settings::anchor_frequency_cap`) it stands
/// within 0.015 mm over a minute (measured 2026-11-30; `contact_solver`, "How fast an anchor may
/// be").
#[test]
fn an_awake_crossed_tower_stands_at_two_sub_steps_only_with_slower_anchors() {
    let tower = kicked(built(piles::crossed_tower(20)));
    stands(&tower, 2, 0.00007, MAX_SPEED_M_S);
    let mut stiff = tower.clone();
    stiff.scene.settings.anchor_frequency_cap = false;
    let run = rest::watch_awake(&stiff, 2, 10.0);
    assert!(run.drift_m > 0.01, "anchors at the contacts' rate: {run:?}");
}

/// The spaced pyramid kept awake at 4 sub-steps of 2 iterations. More sweeps a sub-step made the
/// anchors between its boxes, at the contacts' 30 Hz, as unstable as the tower's at 2 sub-steps:
/// three copies of eight rock at 1.4 to 3.2 mm/s after a minute, this one 1.4 mm/s. With the cap
/// divided by the square root of the iterations (21 Hz) it rests within 0.05 mm, 0.08 mm/s
/// (measured 2026-11-30; `contact_solver`, "How fast an anchor may be").
#[test]
fn an_awake_pyramid_at_two_iterations_rests_only_with_slower_anchors() {
    let mut pyramid = kicked(bottom_up(built(cases::pyramid(20))));
    pyramid.scene.settings.iterations = 2;
    stands(&pyramid, 4, 0.0002, 0.0003);
    pyramid.scene.settings.anchor_frequency_cap = false;
    let run = rest::watch_awake(&pyramid, 4, 60.0);
    assert!(
        run.speed_m_s > MAX_SPEED_M_S,
        "anchors at the contacts' rate: {run:?}"
    );
}

/// The heap of boxes and balls kept awake at 4 sub-steps of 2 and of 4 iterations. A sub-step's
/// passes alternate directions, and with an even number of iterations the relax pass makes their
/// count odd: started alike, every sub-step visited the points backward once more than forward,
/// and that handedness kept the heap stirring at 2 iterations (1.6 mm/s at its fastest in the
/// last second) and leaned it 0.18 mm at 4. Starting sub-steps in turn backward and forward
/// (`Settings::alternate_sub_steps`), it rests within 0.05 mm at 0.002 mm/s, and within a
/// micrometre at 4 (measured 2026-11-30; `wide_contacts::PointOrder::before_substep`). Since a
/// side contact leaves a load open only when pressed (`prepare::preload`, "Determinate loads")
/// the heap no longer leaned at 4 iterations without the alternation (2.5 µm; with it 0.1 µm).
/// Since a point keeps its id when the reference face passes to the other box (`box_box`,
/// "Feature ids") and a load outside the middle of its patch is carried by three of its points
/// (`wide_contacts::build::spread_pressure`), the heap lands a little differently: at 4
/// iterations it leans 0.037 mm without the alternation and 0.006 mm with it, and at 2 it stirs
/// at 1.3 mm/s without it and rests within a micrometre with it (measured 2026-12-01). Shown with
/// the balls' rolling rows as they were then (`rolling_as_before`): with wedged balls rolling with
/// their own mass, the heap rests at 2 iterations without the alternation too (0.002 mm/s).
#[test]
fn even_iterations_stir_an_awake_heap_unless_sub_steps_alternate() {
    let heap = rolling_as_before(knocked_down(bottom_up(Pile {
        scene: piles::mixed_pile(40),
        settle_s: 5.0,
        until_still: false,
    })));
    let at = |iterations: u32, alternate: bool| {
        let mut pile = heap.clone();
        pile.scene.settings.iterations = iterations;
        pile.scene.settings.alternate_sub_steps = alternate;
        pile
    };
    stands(&at(2, true), 4, 0.0002, 0.00001);
    stands(&at(4, true), 4, 0.00002, 0.00001);
    let stirred = rest::watch_awake(&at(2, false), 4, 60.0);
    assert!(
        stirred.speed_m_s > MAX_SPEED_M_S,
        "2 iterations: {stirred:?}"
    );
}

/// The heap of boxes and balls kept awake at the default 4 sub-steps. With every biased pass
/// bottom-up, Gauss–Seidel left its residual at the top of the heap sub-step after sub-step, and
/// the heap crept 9.9 mm in a minute (1.6 mm/s at its fastest in the last second); with the
/// passes going up and down in turn (`Settings::alternate_layer_order`) it rests within 0.006 mm
/// at 0.002 mm/s (measured 2026-11-30, with no moment changes fed, as the order met it; fed, 0.06
/// mm; `wide_contacts::LayerOrder`). Since a side contact leaves a load open only when pressed
/// (`prepare::preload`, "Determinate loads") one box, alone on the floor with neighbours a
/// fraction of a millimetre away, rests on a determinate support; its touching spring leaves it a
/// speed of about a micrometre a second, which moves its position by one rounding step (60 nm)
/// every step for 25 s: 0.084 mm, then it stops (2.2 mm bottom-up; measured 2026-11-30). Landed
/// as it lands since a load outside the middle of its patch is carried by three of its points
/// (`wide_contacts::build::spread_pressure`), it rests within a micrometre at 0.002 mm/s, and
/// bottom-up it still moves at 1.8 mm/s at the minute's end, 0.72 mm off (measured 2026-12-01).
/// Shown with the balls' rolling rows as they were then (`rolling_as_before`): with wedged balls
/// rolling with their own mass it rests within 0.01 mm, but a box whose points drift apart across
/// the touching tolerance (`wide_contacts::velocity`) jumps to 0.047 mm/s for a step in the
/// minute's last second (measured 2026-12-02).
#[test]
fn alternating_layers_keep_an_awake_heap_still() {
    let mut heap = rolling_as_before(Pile {
        scene: piles::mixed_pile(40),
        settle_s: 5.0,
        until_still: false,
    });
    heap.scene.settings.feed_moment_changes = false;
    stands(&heap, 4, 0.00025, 0.00001);
    heap.scene.settings.alternate_layer_order = false;
    let run = rest::watch_awake(&heap, 4, 60.0);
    assert!(
        run.drift_m > MAX_DRIFT_M || run.speed_m_s > MAX_SPEED_M_S,
        "bottom-up alone: {run:?}"
    );
}

/// A unit box resting on another 0.4 m off its centre along both axes, kept awake: its load is
/// outside the middle of the patch, where the least spread of its pressure that carries its moment
/// pulls the far corner. Clamped to zero there, the warm start carried less than the moment and the
/// box rocked for good (7.2 mm/s at 2 sub-steps, 3.1 at 4, 0.9 at 8); carried by the other three
/// points (`wide_contacts::build::spread_pressure`), it rests within a micrometre at 0.1 µm/s
/// (measured 2026-12-01).
#[test]
fn a_box_across_the_corner_of_another_rests_still() {
    let mut scene = cases::stack(2, Vec3::ZERO);
    let top = scene.bodies.len() - 1;
    scene.bodies[top].desc.pose.position += Vec3::new(0.4, 0.0, 0.4);
    let pile = built(scene);
    for substeps in rest::SUBSTEPS {
        stands(&pile, substeps, 0.000001, 0.000001);
    }
}

/// Copy 0 of the heap of boxes and balls (`rest::perturbed`) kept awake at 2 sub-steps. In one of
/// its columns (three boxes, a fourth leaning on the middle one) the faces of the bottom two boxes
/// were within the separating-axis bias of each other: the narrow phase clipped against one box's
/// face, and for one step in every six or eight against the other's. Each switch renamed the four
/// points of the contact, their loads were shared out equally, and the column rocked at 14 mm/s
/// for the whole minute (0.49 mm off). Named by the boxes' own features (`box_box`, "Feature ids")
/// the points keep their loads through a switch, and the heap rests within 0.07 mm at 0.01 mm/s;
/// since a load outside the middle of its patch is carried by three of its points
/// (`wide_contacts::build::spread_pressure`), within 0.10 mm at 0.002 mm/s (measured 2026-12-01).
#[test]
fn a_reference_face_that_changes_box_keeps_its_points_loads() {
    let heap = Pile {
        scene: piles::mixed_pile(40),
        settle_s: 5.0,
        until_still: false,
    };
    stands(&rest::perturbed(&heap, 0), 2, 0.00025, 0.00005);
}

/// The heap of boxes and balls asleep at the default 4 sub-steps, woken by a 20 g ball dropped on
/// its top (`bench::rest::woken`). While a ball apart from the column the ball lands on still
/// counted as its side contact, three copies of `nudge bench rest`'s eight stayed 1.5 to 1.9 mm
/// off; since a side contact leaves a load open only when pressed (`prepare::preload`,
/// "Determinate loads") they come back within 0.004 mm (measured 2026-11-30). The heap lands a
/// little differently since a point keeps its id when the reference face passes to the other box
/// (`box_box`, "Feature ids") and a load outside the middle of its patch is carried by three of its
/// points (`wide_contacts::build::spread_pressure`): without determinate loads seven copies of the
/// eight never sleep again (0.35 to 4.4 mm off); with them every copy sleeps and comes back within
/// a micrometre, but for copy 2, 0.69 mm off (measured 2026-12-01), which holds it to the bench's
/// 1 mm. Knocked as it was then (`knocked_down`): carrying blows, copy 2 lands a little
/// differently asleep, its top box tilted 10°, and the ball knocks it 2.1 mm off
/// (`prepare::preload::blows`). Shown with the balls' rolling rows as they were then
/// (`rolling_as_before`): with wedged balls rolling with their own mass, copy 2 without
/// determinate loads lands otherwise and sleeps 1.1 mm off.
#[test]
fn a_column_beside_a_ball_it_does_not_touch_comes_back_from_a_knock() {
    let heap = rolling_as_before(knocked_down(Pile {
        scene: piles::mixed_pile(40),
        settle_s: 5.0,
        until_still: false,
    }));
    let mut loose = heap.clone();
    loose.scene.settings.determinate_preload = false;
    for k in 0..rest::COPIES {
        let (drift, slept) = rest::woken(&rest::perturbed(&heap, k), 4);
        assert!(slept, "copy {k} never slept");
        assert!(drift < MAX_DRIFT_M, "copy {k} moved {drift} m");
        if k > 0 {
            let (drift, slept) = rest::woken(&rest::perturbed(&loose, k), 4);
            assert!(
                !slept,
                "copy {k} slept without determinate loads, {drift} m off"
            );
        }
    }
}

/// The same tower asleep, woken by a 20 g ball dropped on its top (`bench::rest::woken`). Its long
/// blocks, tilted a fraction of a degree, made edge–edge contacts of nearly parallel edges that
/// flickered between one point and four (`box_box`, "Near-face edge axes"), and the tower fell
/// through itself: 10 m of drift at 4 sub-steps. Then the ball's knock set it bouncing, and it
/// rested 7.8 mm from where it slept at 4 sub-steps until the symmetric relax (`contact_solver`),
/// and 1.6 mm (0.9 to 1.8 mm over `nudge bench rest`'s eight copies) while the ball's weight
/// reached its lower layers one sweep at a time, the tower sagging into its springs meanwhile.
/// With the change in the load fed to every support under it at once (`Settings::
/// feed_load_changes`, `prepare::preload`, "Load changes") it rests 0.88 mm from where it slept
/// at 4 sub-steps (0.70 to 0.88 mm over the copies) and 0.37 mm at 8 (measured 2026-11-30). At 2
/// it rests 1.7 to 7 mm from where it slept. All knocked as it was then (`knocked_down`): carrying
/// the blow, it moves a fraction of a micrometre at every count.
#[test]
fn a_sleeping_crossed_tower_woken_by_a_small_ball_stands() {
    let tower = knocked_down(built(piles::crossed_tower(20)));
    for (substeps, most) in [(4, MAX_DRIFT_M), (8, 0.0008)] {
        let (drift, slept) = rest::woken(&tower, substeps);
        assert!(slept, "at {substeps} sub-steps the tower never slept");
        assert!(drift < most, "at {substeps} sub-steps it moved {drift} m");
    }
    let mut unfed = tower.clone();
    unfed.scene.settings.feed_load_changes = false;
    let (drift, _) = rest::woken(&unfed, 4);
    assert!(drift > 0.0012, "without the load fed: {drift} m");
}

/// How a load change is fed (`prepare::preload`, "Load changes"). Only towards the statics' new
/// load and by at most its change: fed the change whole, the 8 kg box on four balls, whose
/// supports the knock had already loaded, rolled 44 mm off them woken at 8 sub-steps in the copy
/// below (0.17 mm as it is). Not across a change of rule: ten 2 cm plates woken at 2 sub-steps,
/// whose supports flicker between determinate and not, were fed the difference between the two
/// rules' loads and sank 5 cm through each other (0.01 mm as they are). Measured 2026-11-30.
#[test]
fn load_changes_are_fed_towards_the_statics_and_not_across_a_change_of_rule() {
    let balls = rest::perturbed(&built(piles::box_on_balls()), 1);
    let (drift, slept) = rest::woken(&balls, 8);
    assert!(
        slept && drift < 0.001,
        "box on balls woken at 8 sub-steps: {drift} m"
    );
    let (drift, slept) = rest::woken(&built(piles::plates(10)), 2);
    assert!(
        slept && drift < 0.0001,
        "plates woken at 2 sub-steps: {drift} m"
    );
}

/// An 8 kg box on four 4 g balls (a mass ratio the shock pass owns) kept awake stays put at every
/// sub-step count, and asleep, woken by a small ball, settles back. Around a mass ratio the
/// supports were not preloaded and the shock pass pushed the box at each ball in turn as if that
/// one alone held it: the box rocked and walked two balls out, 0.3 m in a minute and still moving
/// at 0.65 m/s (`prepare::preload`, "Mass ratios"). The supports of a body on several are now
/// preloaded with the lever rule's split and the shock pass skips them. Measured 2026-11-29 over
/// four copies (`bench::rest::perturbed`): awake, at most 0.2 µm at 4 and 8 sub-steps and 5 to
/// 77 µm at 2 (the copy as built measured 0.8 µm there before the symmetric top's exact rotation
/// and 75 µm after, like the other three: this test pinned that one copy at 5 µm), under 4 µm/s;
/// woken, 0.82, 0.26 and 0.17 mm at 2, 4 and 8 sub-steps. Without the preload the box still rocks
/// off its balls.
#[test]
fn a_box_on_four_small_balls_kept_awake_stays_put_only_with_its_supports_preloaded() {
    let pile = built(piles::box_on_balls());
    for k in 0..4 {
        let copy = rest::perturbed(&pile, k);
        for (substeps, drift) in [(2, 0.00025), (4, 0.000005), (8, 0.000005)] {
            stands(&copy, substeps, drift, 0.00002);
        }
    }
    for substeps in [4, 8] {
        let (drift, slept) = rest::woken(&pile, substeps);
        assert!(slept && drift < 0.001, "woken at {substeps}: {drift} m");
    }
    let mut unloaded = pile.clone();
    unloaded.scene.settings.preload = false;
    let run = rest::watch_awake(&unloaded, 4, 60.0);
    assert!(run.drift_m > 0.05, "without the preload: {run:?}");
}

/// Ten 2 cm plates stacked flat stay stacked at every sub-step count: they squeezed out sideways
/// by 18 cm in a minute at 4 sub-steps when their warm starts were reset to the lever rule's, and
/// each plate also took a share of its load on the plate two below, which it does not touch (a
/// contact only supports where it touches). Now nothing measurable moves.
#[test]
fn thin_plates_stacked_flat_stay_stacked_awake() {
    let plates = built(piles::plates(10));
    for substeps in rest::SUBSTEPS {
        stands(&plates, substeps, 0.0001, MAX_SPEED_M_S);
    }
}

/// The plates asleep, woken by a 20 g ball (as heavy as a plate): the knock squeezes the stack by
/// 20 mm, 2 to 5 mm in every other contact. Its supports are determinate, and a determinate
/// support is a spring centred where it touches (`Settings::touching_spring`), so the stack comes
/// back to where it slept: measured 2026-11-29, 0.0005 mm at 4 sub-steps and 0.0004 mm at 8.
/// Without it the knocked contacts stay where the knock left them inside the slop band: 7.2 and
/// 5.5 mm. (Pushed back inside the band alone, by a law that vanished at both its edges, the
/// plates tilted and came to rest with one edge of a patch at the band's edge: 2.4 and 1.6 mm.)
#[test]
fn thin_plates_woken_by_a_small_ball_settle_back_only_on_touching_springs() {
    let plates = knocked_down(built(piles::plates(10)));
    let mut without = plates.clone();
    without.scene.settings.touching_spring = false;
    for substeps in [4, 8] {
        let (drift, slept) = rest::woken(&plates, substeps);
        assert!(slept && drift < 0.000_005, "woken at {substeps}: {drift} m");
        let (drift, _) = rest::woken(&without, substeps);
        assert!(
            drift > 0.002,
            "woken at {substeps} without touching springs: {drift} m"
        );
    }
}

/// The plates asleep, hit hard: the 20 g ball dropped from 5 m at the default 4 sub-steps, or from
/// 0.5 m at 2. With a soft range of 5 cm two 2 cm plates were driven past the depth at which their
/// centres cross, where the separating axis flips and pushes them on through, and one plate was
/// squeezed 0.36 m out of the stack. A contact's soft range is at most a quarter of that depth
/// (`Settings::thin_soft_range`, `push_out::soft_depth`): the deep rows and the position pass stop
/// the plates first, and the stack settles back. Measured 2026-11-29: 0.041 and 0.009 mm; without,
/// 362 and 354 mm.
#[test]
fn thin_plates_hit_hard_stay_stacked_only_with_a_soft_range_short_of_their_thickness() {
    let plates = knocked_down(built(piles::plates(10)));
    let mut without = plates.clone();
    without.scene.settings.thin_soft_range = false;
    for (substeps, drop_m) in [(4, 5.0), (2, rest::BALL_DROP_M)] {
        let (drift, slept) = rest::woken_by_drop(&plates, substeps, drop_m);
        assert!(
            slept && drift < 0.000_2,
            "dropped {drop_m} m at {substeps}: {drift} m"
        );
        let (drift, _) = rest::woken_by_drop(&without, substeps, drop_m);
        assert!(
            drift > 0.1,
            "dropped {drop_m} m at {substeps} with a 5 cm soft range: {drift} m"
        );
    }
}

/// The touching pyramid with every support's warm start reset to the lever rule's share
/// (`Settings::determinate_preload` off) creeps: the case the rule exists for.
#[test]
fn reset_to_the_lever_rule_every_step_the_touching_pyramid_creeps() {
    let mut pyramid = built(piles::touching_pyramid(20));
    pyramid.scene.settings.determinate_preload = false;
    let run = rest::watch_awake(&pyramid, 4, 60.0);
    assert!(run.drift_m > 0.01, "{run:?}");
}

/// The bench's running-bond wall asleep, woken by the 20 g ball (heavier than one of its 16 g
/// bricks) dropped on its top. Passed down a course a pass, the blow sank the struck brick and the
/// two under it 3.4 to 3.6 mm in the step it landed and set them turning, and the wall settled
/// 6 to 12 mm from where it slept at 4 sub-steps (`nudge bench rest`'s eight copies; 5.9 mm as
/// built). The wall carries the blow as it carries its weight (`Settings::piles_carry_blows`,
/// `prepare::preload::blows`): measured 2026-12-01 as built, 0.16 mm at 4 sub-steps and 0.17 mm at
/// 8 (the ball stops on the wall, and the wall, kept awake by the ball rolling on it, sways a
/// little until it sleeps). Thresholds three times those; without, above half the 4-sub-step
/// figure.
#[test]
fn a_sleeping_running_bond_wall_woken_by_a_ball_stands_only_when_piles_carry_blows() {
    let wall = built(piles::running_bond_wall(12, 8));
    for substeps in [4, 8] {
        let (drift, slept) = rest::woken(&wall, substeps);
        assert!(slept && drift < 0.0005, "woken at {substeps}: {drift} m");
    }
    let mut without = wall.clone();
    without.scene.settings.piles_carry_blows = false;
    let (drift, _) = rest::woken(&without, 4);
    assert!(drift > 0.003, "without blows carried: {drift} m");
}

/// Every pile built resting, asleep and woken by the 20 g ball at 2, 4 and 8 sub-steps, with the
/// blow carried (`Settings::piles_carry_blows`): the ball stops on the pile, which then carries its
/// weight. Measured 2026-12-01, as built, the most over the three counts: pyramids 2.2 µm, columns
/// of 10, 30 and 50 boxes 16, 121 and 123 µm (the ball's weight on the top box at 2 and 4
/// sub-steps), the crossed tower 0.2 µm, the wall of real bricks 2.5 µm, the plates 0.7 µm. Each
/// limit about four times its pile's, and a few micrometres where the pile measured none.
#[test]
fn resting_piles_woken_by_a_small_ball_carry_its_blow_at_every_sub_step_count() {
    let piles = [
        (cases::pyramid(20), 0.00001),
        (piles::touching_pyramid(20), 0.00001),
        (cases::stack(10, Vec3::ZERO), 0.00007),
        (cases::stack(30, Vec3::ZERO), 0.0005),
        (cases::stack(50, Vec3::ZERO), 0.0005),
        (piles::crossed_tower(20), 0.000002),
        (piles::brick_wall(12, 8), 0.00001),
        (piles::plates(10), 0.000003),
    ];
    for (scene, most) in piles {
        let pile = built(scene);
        for substeps in rest::SUBSTEPS {
            let (drift, slept) = rest::woken(&pile, substeps);
            assert!(
                slept && drift < most,
                "{} woken at {substeps} sub-steps: {drift} m",
                pile.scene.name
            );
        }
    }
}

/// Where a blow is not over the supports of every body it passes through, the pile does not carry
/// it: a 50 g ball dropped on the end of a 1 kg plank balanced on a narrow block rocks the plank, as
/// it would rock a real one, and so does the ball dropped on a 50 g box standing on that end (the
/// box is over its own support, the plank is not); together too light to tip the plank by their
/// weight, carried as by the ground they would have left it still. The same ball dropped over the
/// block stops on the plank, which does not move (`prepare::preload::blows`). Measured 2026-12-01:
/// the plank turns 49 mrad at most under the ball on its end, 78 mrad under the ball on the box
/// (not at all with the box alone), and not at all under the ball over the block.
#[test]
fn a_blow_beside_the_supports_rocks_a_balanced_plank_and_one_over_them_does_not() {
    use nudge::geometry::{Pose, Shape};
    use nudge::physics::{BodyDesc, Settings, World};
    let most_tilt_after_ball_at = |x: f32, box_under_ball: bool| {
        let mut world = World::new(Settings {
            sleep: false,
            ..Settings::default()
        });
        world.add_body(cases::floor(5.0).desc);
        world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(0.1, 0.25, 0.2)),
            Pose::from_position(Vec3::new(0.0, 0.25, 0.0)),
            2.0,
        ));
        let plank = world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(1.0, 0.05, 0.2)),
            Pose::from_position(Vec3::new(0.0, 0.55, 0.0)),
            1.0,
        ));
        if box_under_ball {
            world.add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::splat(0.1)),
                Pose::from_position(Vec3::new(x, 0.7, 0.0)),
                0.05,
            ));
        }
        for _ in 0..60 {
            world.step();
        }
        world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.05),
            Pose::from_position(Vec3::new(x, 1.4, 0.0)),
            0.05,
        ));
        (0..120)
            .map(|_| {
                world.step();
                let turn = world.body(plank).pose().rotation;
                turn.angle_between(glam::Quat::IDENTITY)
            })
            .fold(0.0, f32::max)
    };
    let over = most_tilt_after_ball_at(0.08, false);
    let beside = most_tilt_after_ball_at(0.9, false);
    let on_a_box_beside = most_tilt_after_ball_at(0.85, true);
    assert!(over < 1e-4, "ball over the block: plank turned {over} rad");
    assert!(
        beside > 0.01,
        "ball on the plank's end: plank turned {beside} rad"
    );
    assert!(
        on_a_box_beside > 0.01,
        "ball on a box on the plank's end: plank turned {on_a_box_beside} rad"
    );
}

/// The heap of boxes and balls asleep at 8 sub-steps, woken by a 20 g ball (`bench::rest::woken`),
/// in `nudge bench rest`'s eight copies. Most of its balls rest between boxes, and where a ball has
/// two contacts the mass its rolling rows have with friction held (its inertia about one contact)
/// is not its mass: it over-relaxed them, and 2 of the 8 copies came back 1.1 and 1.3 mm off. Held
/// only on a contact that is each of its bodies' only one (`Settings::rolling_held_mass_alone`,
/// `wide_contacts::rolling`), every copy comes back within 0.19 mm (measured 2026-12-02).
#[test]
fn a_woken_heap_comes_back_only_when_wedged_balls_roll_with_their_own_mass() {
    let heap = Pile {
        scene: piles::mixed_pile(40),
        settle_s: 5.0,
        until_still: false,
    };
    let with = woken_copies(&heap, 8);
    let without = woken_copies(&rolling_as_before(heap), 8);
    println!("with: {with:?}\nwithout: {without:?}");
    assert!(with.iter().all(|&d| d < 0.0008), "{with:?}");
    let off = without.iter().filter(|&&d| d > MAX_DRIFT_M).count();
    assert!(
        off >= 2,
        "without, {off} copies more than 1 mm off: {without:?}"
    );
}

/// `nudge bench rest` judges the heap, dropped into its pit, from where it has come to rest
/// (`Pile::until_still`): in its copy 6 at 2 sub-steps a ball still rolled at 12 mm/s when the
/// heap's 5 s of settling were up, and stopped 4.2 mm on, 2 s later; taken as where the heap
/// rested, that counted as a slump. From where it stops, the heap stays within 0.1 mm for the
/// minute (measured 2026-12-02). With the biased pass visiting one way at 2 sub-steps, as then:
/// visiting preloaded faces both ways (`Settings::symmetric_biased_pass`) this copy lands still.
#[test]
fn a_dropped_heap_is_judged_from_where_it_came_to_rest() {
    let mut heap = rest::perturbed(&piles::all()[10], 6);
    heap.scene.settings.symmetric_biased_pass = false;
    assert_eq!(heap.scene.name, "mixed pile(40)");
    assert!(heap.until_still);
    stands(&heap, 2, 0.0004, MAX_SPEED_M_S);
    heap.until_still = false;
    let run = rest::watch_awake(&heap, 2, 60.0);
    assert!(run.drift_m > MAX_DRIFT_M, "judged at 5 s: {run:?}");
}

/// The bench's running-bond wall asleep at 2 sub-steps, woken by the 20 g ball, in `nudge bench
/// rest`'s eight copies. Below 4 sub-steps the biased passes cannot alternate over the layers, and
/// visiting every face's points backward the biased pass left its residual on one side of every
/// face: the knocked wall crept, six copies of eight ending 1.1 to 113 mm from where they slept
/// (median 18 mm). Visiting a preloaded face's points both ways, as the relax pass does
/// (`Settings::symmetric_biased_pass`, `contact_solver`, "The symmetric biased pass"), every copy
/// comes back within 0.58 mm (measured 2026-12-02).
#[test]
fn a_wall_woken_at_two_sub_steps_stands_only_with_a_symmetric_biased_pass() {
    let wall = built(piles::running_bond_wall(12, 8));
    let with = woken_copies(&wall, 2);
    let mut one_way = wall.clone();
    one_way.scene.settings.symmetric_biased_pass = false;
    let without = woken_copies(&one_way, 2);
    println!("with: {with:?}\nwithout: {without:?}");
    assert!(with.iter().all(|&d| d < MAX_DRIFT_M), "{with:?}");
    let off = without.iter().filter(|&&d| d > MAX_DRIFT_M).count();
    assert!(
        off >= 4,
        "one way, {off} copies more than 1 mm off: {without:?}"
    );
}

/// Two touching pyramids of six rows, 5 m apart, built resting and kept awake at 4 sub-steps. Still,
/// their statics are kept, not found again every step (`Settings::statics_reuse`,
/// `prepare::preload::reuse`): found on 2 of 600 steps after the first second, on every step with
/// reuse off, and they stand as still either way (9.4 nm off where they stood after a minute,
/// both; measured 2026-12-02). A push on one pyramid's top box has that pyramid's statics found
/// on the step it lands, and the other's kept; restored from a snapshot, the pile steps to the
/// same bits; new settings have every island's found again.
#[test]
fn a_still_pile_keeps_its_statics_and_stands_as_when_they_are_found_every_step() {
    let mut scene = piles::touching_pyramid(6);
    let boxes: Vec<_> = scene
        .bodies
        .iter()
        .filter(|body| !body.desc.is_static)
        .cloned()
        .collect();
    let per_pyramid = boxes.len();
    for mut body in boxes {
        body.desc.pose.position.z += 5.0;
        scene.bodies.push(body);
    }
    scene.settings.sleep = false;
    let positions = |world: &nudge::physics::World| -> Vec<Vec3> {
        world.bodies().iter().map(|b| b.pose().position).collect()
    };
    for reuse in [true, false] {
        let mut scene = scene.clone();
        scene.settings.statics_reuse = reuse;
        let mut world = scene.build_world();
        for _ in 0..60 {
            world.step();
        }
        let rest = positions(&world);
        let mut found_on = 0;
        for _ in 0..600 {
            world.step();
            found_on += usize::from(world.statics_found() > 0);
        }
        let drift = positions(&world)
            .iter()
            .zip(&rest)
            .map(|(p, q)| p.distance(*q))
            .fold(0.0, f32::max);
        let what = format!("reuse {reuse}: found on {found_on} of 600 steps, drift {drift} m");
        assert!(drift < 4e-8, "{what}");
        if !reuse {
            assert_eq!(found_on, 600, "{what}");
            continue;
        }
        assert!(found_on <= 10, "{what}");
        // What was kept is world state: restored into a fresh world, the still pyramids step to
        // the same bits.
        let snapshot = world.snapshot();
        for _ in 0..60 {
            world.step();
        }
        let end = world.snapshot();
        let mut restored = scene.build_world();
        restored.restore(&snapshot);
        for _ in 0..60 {
            restored.step();
        }
        assert_eq!(restored.snapshot().first_difference(&end), None);
        // Found under other settings, what was kept is forgotten.
        world.settings_mut().restitution_threshold *= 1.01;
        world.step();
        assert_eq!(world.statics_found(), world.contact_count());
        let kept_again = (0..10).any(|_| {
            world.step();
            world.statics_found() == 0
        });
        assert!(kept_again, "kept again within 10 steps");
        // The first pyramid's top box (the floor is body 0).
        let top = nudge::physics::BodyId(per_pyramid as u32);
        let at = world.body(top).pose().position;
        world.apply_impulse_at_point(top, Vec3::new(0.01, 0.0, 0.0), at);
        world.step();
        let (found, all) = (world.statics_found(), world.contact_count());
        assert_eq!(2 * found, all, "found {found} of {all} contacts' statics");
    }
}
