//! The convergence fixes on top of the soft step, each measured on the hard case it exists for with
//! the fix on and off (part of `nudge bench physics`). The same cases, with limits, are the tests in
//! `tests/physics_convergence_fixes.rs`; the README's physics notes quote this table.

use glam::Vec3;
use serde::Serialize;

use crate::physics::Settings;
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

/// Measures every fix on and off (about a second of wall time).
pub fn run() -> Vec<FixRow> {
    let with = |switch: fn(&mut Fixes)| {
        let mut knobs = Knobs::default();
        switch(&mut knobs.fixes);
        knobs
    };
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
    let whirl = |knobs: Knobs| {
        let knobs = Knobs {
            substeps: 8,
            sleep: false,
            ..knobs
        };
        mm(hard_case::stack(8, Vec3::ZERO, ten, knobs).max_drift_m)
    };
    let sink = |knobs| mm(hard_case::mass_ratio(ten, knobs).max_penetration_m);
    let slide = |knobs| mm(hard_case::pinned_push_slide(120.0, 120, knobs).0);
    vec![
        FixRow {
            fix: "spread row",
            case: "stack(10), preload off, 10 s: drift",
            on: stack_drift(with(|f| f.preload = false)),
            off: stack_drift(with(|f| {
                f.preload = false;
                f.spread_row = false;
            })),
            unit: "mm",
        },
        FixRow {
            fix: "preload",
            case: "column of 30, 10 s: penetration",
            on: column_sink(Knobs::default()),
            off: column_sink(with(|f| f.preload = false)),
            unit: "mm",
        },
        FixRow {
            fix: "preload",
            case: "column of 30, sleeping off, 10 s: drift",
            on: awake_column_drift(Knobs::default()),
            off: awake_column_drift(with(|f| f.preload = false)),
            unit: "mm",
        },
        FixRow {
            fix: "alternating point order",
            case: "stack(8), 8 sub-steps, sleeping off, 10 s: drift",
            on: whirl(Knobs::default()),
            off: whirl(with(|f| f.alternate_point_order = false)),
            unit: "mm",
        },
        FixRow {
            fix: "shock propagation",
            case: "1000 kg on 1 kg, 10 s: penetration",
            on: sink(Knobs::default()),
            off: sink(with(|f| f.shock_propagation = false)),
            unit: "mm",
        },
        FixRow {
            fix: "mass-ratio sweeps",
            case: "1 kg pinned under 1000 kg, preload off, 120 N for 2 s: slide",
            on: slide(with(|f| f.preload = false)),
            off: slide(with(|f| {
                f.preload = false;
                f.mass_ratio_sweeps = false;
            })),
            unit: "mm",
        },
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
