//! Rolling resistance of one-point contacts, four at a time.
//!
//! A ball rolling on a floor is slowed by the deformation at its contact: the normal force acts a little
//! ahead of the contact point, a couple up to `μr · N · r` against the rolling (the usual coefficient
//! of rolling resistance, μr = F/N). As a constraint on the relative angular velocity ω = ω_B − ω_A
//! across the normal, along the friction tangents t₁, t₂:
//!
//! ```text
//! Jⱼ = (0, −tⱼ, 0, tⱼ)                         (angular only)
//! mⱼ = 1 / tⱼ·(I_A⁻¹ + I_B⁻¹)tⱼ                 (effective mass, kg·m²)
//! Lⱼ ← Lⱼ − mⱼ (tⱼ · ω),   |L| ≤ c · Σλn        (clamped as a pair, like friction; c = μr · r)
//! ω_A −= I_A⁻¹ tⱼ ΔLⱼ,   ω_B += I_B⁻¹ tⱼ ΔLⱼ
//! ```
//!
//! The spin about the normal is the twist row's (a one-point contact has none), so only the two
//! tangential components are resisted. Only one-point groups carry these rows: balls touch everything
//! at one point, and a box's face or edge contact resists rolling by its geometry already. A group
//! whose lanes all have c = 0 skips them (`GroupRef::rolling`), so scenes without rolling resistance
//! pay nothing.
//!
//! The accumulated impulse is kept across steps as a world vector (`CachedImpulses::rolling`), like
//! friction's, so it survives a change of tangent basis.

use glam::{Vec3A, Vec4};

use super::{LANES, LaneSource};
use crate::physics::contact::Contact;
use crate::physics::lanes::{Mat3x4, Vec3x4, inverse_or_zero};
use crate::physics::solver_body::SolverMotion;

/// The rolling rows of a one-point lane group (zero in lanes without rolling resistance).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RollingLanes {
    /// c = μr · r: the largest rolling couple per unit normal impulse, m.
    pub limit: Vec4,
    /// Accumulated angular impulse on B along each tangent, N·m·s.
    pub impulse: [Vec4; 2],
    /// Effective mass per tangent, kg·m².
    pub mass: [Vec4; 2],
    /// I_A⁻¹ tⱼ and I_B⁻¹ tⱼ, 1/(kg·m²).
    pub it_a: [Vec3x4; 2],
    pub it_b: [Vec3x4; 2],
}

/// Prepares the rolling rows of a one-point group whose friction tangents are `tangents`, from the
/// same `sources` the group was prepared from. Returns whether any lane resists rolling.
pub(super) fn prepare_rolling(
    r: &mut RollingLanes,
    tangents: &[Vec3x4; 2],
    sources: &[LaneSource],
    contacts: &[Contact],
    motions: &[SolverMotion],
) -> bool {
    let mut limit = [0.0; LANES];
    for (k, source) in sources.iter().enumerate() {
        limit[k] = contacts[source.contact as usize].rolling_resistance;
    }
    if limit.iter().all(|&c| c <= 0.0) {
        // Nothing to resist: the group is flagged so, and `r` (possibly another group's rows of an
        // earlier step) is never read.
        return false;
    }
    let mut cached = [Vec3A::ZERO; LANES];
    let mut inertia_a = [glam::Mat3A::ZERO; LANES];
    let mut inertia_b = [glam::Mat3A::ZERO; LANES];
    for (k, source) in sources.iter().enumerate() {
        cached[k] = contacts[source.contact as usize].impulses.rolling.into();
        inertia_a[k] = motions[source.a as usize].inv_inertia;
        inertia_b[k] = motions[source.b as usize].inv_inertia;
    }
    r.limit = Vec4::from_array(limit);
    let (inertia_a, inertia_b) = (Mat3x4::from_lanes(inertia_a), Mat3x4::from_lanes(inertia_b));
    let cached = Vec3x4::from_lanes(cached);
    let resists = r.limit.cmpgt(Vec4::ZERO);
    for (j, &t) in tangents.iter().enumerate() {
        r.it_a[j] = inertia_a * t;
        r.it_b[j] = inertia_b * t;
        let k = t.dot(r.it_a[j]) + t.dot(r.it_b[j]);
        r.mass[j] = Vec4::select(resists, inverse_or_zero(k), Vec4::ZERO);
        r.impulse[j] = Vec4::select(resists, cached.dot(t), Vec4::ZERO);
    }
    true
}

/// Writes the rolling impulses of group `r` (tangents `tangents`, contacts `contact` per lane,
/// `u32::MAX` in padding) back to the contacts, as world vectors.
pub(super) fn store_rolling(
    r: &RollingLanes,
    tangents: &[Vec3x4; 2],
    contact: &[u32; LANES],
    contacts: &mut [Contact],
) {
    for (k, &c) in contact.iter().enumerate() {
        if c != u32::MAX {
            let (l1, l2) = (r.impulse[0][k], r.impulse[1][k]);
            contacts[c as usize].impulses.rolling =
                (l1 * tangents[0].lane(k) + l2 * tangents[1].lane(k)).into();
        }
    }
}
