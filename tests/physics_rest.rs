//! Piles kept awake stay where they settled: the awake twins of the sleeping tower tests. Each
//! threshold is a few times what the engine measures (`nudge bench rest` prints the figures for
//! every pile; most piles there do not hold yet, and these pin the ones that do so that the next
//! change to the solver cannot lose them unnoticed).

use glam::Vec3;
use nudge::bench::rest::{self, MAX_DRIFT_M, MAX_SPEED_M_S};
use nudge::scene::cases;
use nudge::scene::piles::{self, Pile};

fn built(scene: nudge::scene::Scene) -> Pile {
    Pile {
        scene,
        settle_s: 1.0,
    }
}

/// A box that friction holds on a 30° ramp stays put, awake, at every sub-step count: friction
/// that holds must hold exactly, not creep down the slope.
#[test]
fn a_box_held_by_friction_on_a_ramp_stays_put_for_a_minute_awake() {
    let pile = built(piles::box_on_ramp());
    for substeps in rest::SUBSTEPS {
        let run = rest::watch_awake(&pile, substeps, 60.0);
        assert!(
            run.drift_m <= MAX_DRIFT_M && run.speed_m_s <= MAX_SPEED_M_S,
            "{substeps} sub-steps: {run:?}"
        );
    }
}

/// A column of ten boxes kept awake a minute: about 0.6 mm at 4 sub-steps and 0.23 mm at 8
/// (measured 2026-11-27), each under 0.2 mm/s.
#[test]
fn a_column_of_ten_kept_awake_stands_within_two_millimetres_for_a_minute() {
    let pile = built(cases::stack(10, Vec3::ZERO));
    for (substeps, drift_m) in [(4, 0.002), (8, 0.001)] {
        let run = rest::watch_awake(&pile, substeps, 60.0);
        assert!(
            run.drift_m <= drift_m && run.speed_m_s <= MAX_SPEED_M_S,
            "{substeps} sub-steps: {run:?}"
        );
    }
}

/// At 8 sub-steps a column of thirty (about 0.24 mm) and a running-bond brick wall (about 0.07 mm)
/// stand still awake for a minute.
#[test]
fn at_eight_sub_steps_a_column_of_thirty_and_a_brick_wall_stand_still_awake() {
    for (pile, drift_m) in [
        (built(cases::stack(30, Vec3::ZERO)), 0.001),
        (built(piles::running_bond_wall(12, 8)), 0.0003),
    ] {
        let run = rest::watch_awake(&pile, 8, 60.0);
        assert!(
            run.drift_m <= drift_m && run.speed_m_s <= MAX_SPEED_M_S,
            "{}: {run:?}",
            pile.scene.name
        );
    }
}
