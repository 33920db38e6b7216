//! Coulomb friction at the edge of sticking: a unit box released at rest on a ramp of angle θ whose
//! friction is μ = tan θ ± 0.05. Above tan θ friction holds it (it stays put); below, it slides with
//! a = g·(sin θ − μ·cos θ), here g·0.05·cos θ. Close to the edge is where a friction cone
//! approximated by a pyramid, a limit split per contact point, or a warm start that overshoots shows:
//! the box creeps where it should stick, or sticks where it should slide.

use super::{Family, Member, Outcome, Unit};
use crate::scene::cases;
use crate::testing::hard_case::{Knobs, ramp_at};

/// Slopes tried, degrees (below 45°: a unit cube on a steeper slope tips rather than slides).
pub const ANGLES_DEG: [f32; 8] = [5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0, 40.0];
/// How far μ sits from tan θ, either side.
pub const MARGIN: f32 = 0.05;
/// Simulated time of a run, s.
const SECONDS: f32 = 2.0;
/// Allowed error, relative to the slide at μ = tan θ − [`MARGIN`] (the ramp cases pass at
/// 2 %).
pub const TOLERANCE: f32 = 0.02;

/// Runs the ramp at `angle_deg` with μ = tan θ + `side`·[`MARGIN`]. The error is relative to the
/// sliding twin's slide ½·g·MARGIN·cos θ·t²: how far the box is from the expected slide at the end
/// when it slides, the farthest it got from its start at any step when it sticks.
pub fn outcome(angle_deg: f32, side: f32, knobs: Knobs) -> Outcome {
    let theta = angle_deg.to_radians();
    let mu = theta.tan() + side * MARGIN;
    let out = ramp_at(theta, mu, SECONDS, knobs);
    let g = cases::ramp_at(theta, mu).settings.gravity.length();
    let scale = 0.5 * g * MARGIN * theta.cos() * SECONDS * SECONDS;
    let error = if side > 0.0 {
        out.max_displacement_m / scale
    } else {
        (out.slide_m - out.expected_slide_m).abs() / scale
    };
    Outcome {
        error,
        ms_per_step: out.ms_per_step,
        detail: format!(
            "μ = {mu:.4}: slid {:.5} m (expected {:.5} m), farthest {:.5} m",
            out.slide_m, out.expected_slide_m, out.max_displacement_m
        ),
    }
}

/// Every angle of [`ANGLES_DEG`], μ just above tan θ (sticks) and just below (slides).
pub fn family() -> Family {
    let mut members = Vec::new();
    for angle in ANGLES_DEG {
        for (side, what) in [(1.0, "sticks"), (-1.0, "slides")] {
            members.push(Member {
                label: format!("{angle}° μ=tanθ{:+} {what}", side * MARGIN),
                tolerance: TOLERANCE,
                run: Box::new(move |knobs| outcome(angle, side, knobs)),
            });
        }
    }
    Family {
        name: "ramp friction",
        answer: "μ = tan θ + 0.05 sticks, tan θ − 0.05 slides at g(sin θ − μ cos θ)",
        unit: Unit::Relative,
        members,
    }
}
