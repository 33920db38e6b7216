//! Far from the origin: a box, and a column of five, resting on a floor kilometres from the origin
//! stand as they do at the origin. f32 positions there have a coarse grain (0.98 mm at 10 km), so a
//! solver that forms contact points or relative positions in world coordinates (rather than relative
//! to the bodies) jitters, drifts or sinks by that grain.

use glam::Vec3;

use super::{Family, Member, Outcome, Unit};
use crate::testing::hard_case::{Knobs, stack};

/// Distances from the origin tried, m (along the diagonal of x and z; the grain at 100 km is
/// 7.8 mm).
pub const DISTANCES_M: [f32; 3] = [1_000.0, 10_000.0, 100_000.0];
/// Columns tried, boxes.
pub const COUNTS: [usize; 2] = [1, 5];
/// Simulated time, s.
const SECONDS: f32 = 10.0;
/// Largest error allowed, m: the drift, or the difference from the origin's penetration (one
/// millimetre, about the f32 grain at 10 km).
pub const MAX_ERROR_M: f32 = 1e-3;

/// Runs the column at `distance` and at the origin; the error is the worst of the far column's
/// horizontal drift and how much its deepest overlap differs from the near one's, m.
pub fn outcome(count: usize, distance: f32, knobs: Knobs) -> Outcome {
    let base = Vec3::new(distance, 0.0, distance) / 2f32.sqrt();
    let near = stack(count, Vec3::ZERO, SECONDS, knobs);
    let far = stack(count, base, SECONDS, knobs);
    let sink = (far.max_penetration_m - near.max_penetration_m).abs();
    Outcome {
        error: far.max_drift_m.max(sink),
        ms_per_step: far.ms_per_step,
        detail: format!(
            "drift {:.2e} m (at the origin {:.2e}), penetration {:.3e} m (at the origin {:.3e})",
            far.max_drift_m, near.max_drift_m, far.max_penetration_m, near.max_penetration_m
        ),
    }
}

/// Each column of [`COUNTS`] at each distance of [`DISTANCES_M`].
pub fn family() -> Family {
    let mut members = Vec::new();
    for distance in DISTANCES_M {
        for count in COUNTS {
            members.push(Member {
                label: format!("{count} at {} km", distance / 1000.0),
                tolerance: MAX_ERROR_M,
                run: Box::new(move |knobs| outcome(count, distance, knobs)),
            });
        }
    }
    Family {
        name: "far from the origin",
        answer: "stands as at the origin: drift, penetration difference (m, not relative)",
        unit: Unit::Metres,
        members,
    }
}
