//! Torque-free rotation: a box spinning in zero gravity keeps its kinetic energy ½·ω·I·ω and its
//! angular momentum L = I·ω, in length and direction, whichever axis it spins about (about the
//! intermediate axis the spin is unstable and the box flips, with L still fixed). An integrator that
//! drops the gyroscopic term ω × I·ω keeps ω instead of L and turns L with the box; an explicit one
//! gains energy.

use glam::Vec3;

use super::{Family, Member, Outcome, Unit};
use crate::testing::hard_case::{Knobs, free_spin};

/// Simulated time, s.
const SECONDS: f32 = 10.0;
/// Allowed drift of the energy and of |L| (relative) and turn of L (radians): the 1 % an earlier
/// issue set for the energy and |L| of the intermediate-axis case.
pub const TOLERANCE: f32 = 0.01;

/// Runs the box; the error is the worst of the energy's and |L|'s relative drift and L's turn.
pub fn outcome(half: Vec3, omega: Vec3, knobs: Knobs) -> Outcome {
    let out = free_spin(half, omega, SECONDS, knobs);
    Outcome {
        error: out
            .max_energy_drift
            .max(out.max_momentum_drift)
            .max(out.max_momentum_turn_rad),
        ms_per_step: out.ms_per_step,
        detail: format!(
            "energy drift {:.2e}, |L| drift {:.2e}, L turned {:.2e} rad, {} flips",
            out.max_energy_drift, out.max_momentum_drift, out.max_momentum_turn_rad, out.flips
        ),
    }
}

/// A 0.2 × 0.8 × 2 m box about each principal axis (its major axis is x, its minor z), slow and
/// fast about the intermediate one, and a box tumbling about no principal axis.
pub fn family() -> Family {
    let plank = Vec3::new(0.1, 0.4, 1.0);
    let runs = [
        ("major axis", plank, Vec3::new(5.0, 1e-3, 1e-3)),
        ("minor axis", plank, Vec3::new(1e-3, 1e-3, 5.0)),
        ("intermediate axis", plank, Vec3::new(1e-3, 5.0, 1e-3)),
        ("intermediate axis fast", plank, Vec3::new(1e-3, 20.0, 1e-3)),
        (
            "tumbling",
            Vec3::new(0.2, 0.5, 0.8),
            Vec3::new(1.0, 2.0, 3.0),
        ),
    ];
    Family {
        name: "free spin",
        answer: "energy and angular momentum kept (drift, relative; turn of L, rad)",
        unit: Unit::Relative,
        members: runs
            .into_iter()
            .map(|(label, half, omega)| Member {
                label: label.into(),
                tolerance: TOLERANCE,
                run: Box::new(move |knobs| outcome(half, omega, knobs)),
            })
            .collect(),
    }
}
