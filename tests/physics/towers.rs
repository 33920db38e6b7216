//! Tall structures stand: columns of 10 to 50 unit boxes for 10 s at the default settings, let sleep
//! and kept awake. Their lowest contacts carry the most (without the preload the soft contact's spring compresses in
//! proportion to the load it carries, 0.55 mm per box above), so they are where a change to
//! loaded or deep contacts shows first (a 2 cm soft range made the columns of 40 and 50 fall).

use glam::Vec3;
use nudge::testing::hard_case::{self, Knobs};

#[test]
fn columns_of_ten_to_fifty_boxes_stand_for_ten_seconds_asleep_or_awake() {
    /// Largest horizontal drift of any box, metres (measured at most 2.2 µm kept awake, fifty
    /// boxes, 0.2 µm thirty, 0.02 µm let sleep, 2026-11-30; 0.58 mm before the preload). Fifty
    /// drifted 0.2 µm (0.5 µm in a minute) while reused manifolds kept the points they were
    /// computed with; followed to where their boxes are (`Contact::follow`), 2.2 µm, and no more
    /// in a minute.
    const MAX_DRIFT_M: f32 = 0.000_007;
    /// Widest gap between neighbours, metres: a column coming apart (measured none).
    const MAX_HOVER_M: f32 = 0.000_01;
    /// Deepest overlap past nothing, metres: the preloaded springs rest at the slop (measured
    /// none; 5.3 to 32.0 mm at 10 to 50 boxes without the preload).
    const MAX_PENETRATION_M: f32 = 0.000_01;
    for sleep in [true, false] {
        for count in [10, 20, 30, 40, 50] {
            let knobs = Knobs {
                sleep,
                ..Knobs::default()
            };
            let out = hard_case::stack(count, Vec3::ZERO, 10.0, knobs);
            let what = format!("{count} boxes, sleep {sleep}: {out:?}");
            assert!(out.max_drift_m < MAX_DRIFT_M, "{what}");
            assert!(out.max_hover_m < MAX_HOVER_M, "{what}");
            assert!(out.max_penetration_m < MAX_PENETRATION_M, "{what}");
        }
    }
}
