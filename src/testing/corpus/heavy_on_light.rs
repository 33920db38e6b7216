//! Heavy on light: a unit box R times heavier than the unit box it rests on (on a floor). At rest the
//! top box stays where it was set down; a solver whose sweeps pass the heavy load down slowly lets
//! the light box be crushed into the floor, and the heavy box sinks.

use super::{Family, Member, Outcome, Unit};
use crate::scene::cases::MASS_RATIO_LIGHT_KG;
use crate::testing::hard_case::heavy_on_light;

/// Mass ratios tried, heavy over light.
pub const RATIOS: [f32; 7] = [10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10000.0];
/// Simulated time, s.
const SECONDS: f32 = 10.0;
/// Largest height error of the top box, m (the 0.1 mm).
pub const MAX_HEIGHT_ERROR_M: f32 = 1e-4;

/// Every ratio of [`RATIOS`]; the error is the top box's largest |y − y₀| at any step, m.
pub fn family() -> Family {
    Family {
        name: "heavy on light",
        answer: "the top box stays at its height (m, not relative)",
        unit: Unit::Metres,
        members: RATIOS
            .into_iter()
            .map(|ratio| Member {
                label: format!("{ratio}:1"),
                tolerance: MAX_HEIGHT_ERROR_M,
                run: Box::new(move |knobs| {
                    let out = heavy_on_light(ratio * MASS_RATIO_LIGHT_KG, SECONDS, knobs);
                    Outcome {
                        error: out.max_height_error_m,
                        ms_per_step: out.ms_per_step,
                        detail: format!(
                            "height error {:.3e} m, penetration {:.3e} m",
                            out.max_height_error_m, out.max_penetration_m
                        ),
                    }
                }),
            })
            .collect(),
    }
}
