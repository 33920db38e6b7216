//! Rolling and spinning resistance of one-point contacts, four at a time.
//!
//! A ball rolling on a floor is slowed by the deformation at its contact: the normal force acts a little
//! ahead of the contact point, a couple up to `μr · N · r` against the rolling (the usual coefficient
//! of rolling resistance, μr = F/N). The same small deformed patch resists spinning about the normal
//! (a point contact has no twist friction, so a ball knocked into a spin in place, as a glancing box
//! leaves it, spun forever and kept its island awake: the built-in `rain` never came to rest); its
//! couple is bounded by the same `c · N`. As a constraint on the relative angular velocity
//! ω = ω_B − ω_A along the friction tangents t₁, t₂ and the normal n (a₁ = t₁, a₂ = t₂, a₃ = n):
//!
//! ```text
//! Jⱼ = (0, −aⱼ, 0, aⱼ)                         (angular only)
//! mⱼ = 1 / aⱼ·(I_A⁻¹ + I_B⁻¹)aⱼ                 (effective mass, kg·m²)
//! Lⱼ ← Lⱼ − mⱼ (aⱼ · ω),   |(L₁, L₂)| ≤ c · Σλn (clamped as a pair, like friction; c = μr · r)
//!                          |L₃| ≤ c · Σλn       (the spin, on its own)
//! ω_A −= I_A⁻¹ aⱼ ΔLⱼ,   ω_B += I_B⁻¹ aⱼ ΔLⱼ
//! ```
//!
//! The spin row is not the twist row of multi-point manifolds (whose radius comes from the patch
//! the points span): it exists only where rolling resistance does. Only one-point groups carry these rows: balls touch everything
//! at one point, and a box's face or edge contact resists rolling by its geometry already. A group
//! whose lanes all have c = 0 skips them (`GroupRef::rolling`), so scenes without rolling resistance
//! pay nothing.
//!
//! The accumulated impulse is kept across steps as a world vector (`CachedImpulses::rolling`), like
//! friction's, so it survives a change of tangent basis.
//!
//! The rolling pair and the friction pair are strongly coupled: friction at the contact point spins
//! the ball (its angular part r × t lies along the other tangent), and the rolling couple makes it
//! slip. Solved one after the other, each with its own mass, a sub-step's two passes (solve and
//! relax) left a ball just set rolling slipping forward: a ball released on a 10° slope with μr
//! 0.02 under tan θ kept the extra speed of its first sub-step and ran 1.7 % ahead (6.8 % at one
//! sub-step). While friction holds (its pair inside its circle), the rolling pair is solved with
//! the mass it has with friction held, the Schur complement of the block [[K_ff, K_fr], [K_rf, K_rr]]:
//!
//! ```text
//! S = K_rr − K_rf · K_ff⁻¹ · K_fr        (2×2; K_ff taken diagonal, as the friction pair is solved)
//! (ΔL₁, ΔL₂) = −S⁻¹ · (t₁·ω, t₂·ω)       then clamped to the circle as before
//! ```
//!
//! For a ball on a floor S⁻¹ = I + m·r², its inertia about the contact point: the couple it takes to
//! change a rolling ball's spin, slip included. The friction pass after it removes the slip, and
//! the pair is solved within one solve and relax. When friction slides, the rolling pair keeps its
//! own masses.
//!
//! That held mass is the ball's only while it can pivot about this contact. Wedged between two (a
//! ball on the floor under a plank's end), its translation is held by the other contact too, and
//! the held mass, 3.5 times a solid ball's own (I + m·r² over I), over-relaxed the rolling rows:
//! the ball buzzed at 0.1 m/s and 3 rad/s for good once the plank weighed five times the ball (ten
//! without the mass-ratio sweeps), and 4 to 6 of 12 random heaps of boxes and balls of mixed sizes
//! never slept. So a contact takes the held mass only where it is each of its dynamic bodies' only
//! one (`Settings::rolling_held_mass_alone`; `LaneSource::rolling_held`): the wedged ball sleeps in
//! half a second at every mass up to 140 times its own, all of 40 random heaps sleep, and every
//! figure of `nudge bench corpus` is kept (the slope's 1.7 % is a lone contact's). The rest
//! bench's heap, whose balls rest between boxes, holds in more copies (`tests/physics/rolling.rs`,
//! `a_ball_wedged_under_a_plank_sleeps_only_when_a_lone_contact_takes_the_held_mass`).

use glam::{Vec3A, Vec4};

use crate::physics::narrow::contact::Contact;
use crate::physics::solve::lanes::{Mat3x4, Vec3x4, inverse_or_zero};
use crate::physics::solve::solver_body::SolverMotion;
use crate::physics::solve::wide_contacts::{LANES, LaneSource, StruckPile};

/// The rolling and spinning rows of a one-point lane group (zero in lanes without rolling
/// resistance), along the two tangents and the normal.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RollingLanes {
    /// c = μr · r: the largest rolling (or spinning) couple per unit normal impulse, m.
    pub limit: Vec4,
    /// Accumulated angular impulse on B along each axis, N·m·s.
    pub impulse: [Vec4; 3],
    /// Effective mass per axis, kg·m².
    pub mass: [Vec4; 3],
    /// I_A⁻¹ aⱼ and I_B⁻¹ aⱼ, 1/(kg·m²).
    pub it_a: [Vec3x4; 3],
    pub it_b: [Vec3x4; 3],
    /// S⁻¹, the rolling pair's mass with friction held (symmetric: S⁻¹₁₁, S⁻¹₁₂, S⁻¹₂₂), kg·m²; the
    /// per-axis masses where S is singular.
    pub held_mass: [Vec4; 3],
}

/// The friction pair of a group as the rolling rows couple to it: I_A⁻¹(r_A × tⱼ), I_B⁻¹(r_B × tⱼ)
/// and the pair's per-axis effective masses.
pub(super) struct FrictionCoupling<'a> {
    pub irt_a: &'a [Vec3x4; 2],
    pub irt_b: &'a [Vec3x4; 2],
    pub mass: &'a [Vec4; 2],
}

/// Prepares the rolling rows of a one-point group whose friction tangents and normal are `axes`,
/// from the same `sources` the group was prepared from. Returns whether any lane resists rolling.
pub(super) fn prepare_rolling(
    r: &mut RollingLanes,
    axes: &[Vec3x4; 3],
    friction: FrictionCoupling,
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
    let mut held = [false; LANES];
    let mut inertia_a = [glam::Mat3A::ZERO; LANES];
    let mut inertia_b = [glam::Mat3A::ZERO; LANES];
    for (k, source) in sources.iter().enumerate() {
        cached[k] = contacts[source.contact as usize].impulses.rolling.into();
        held[k] = source.rolling_held;
        // A struck pile is immovable to the landing's rows, these too (`preload::blows`).
        let inertia = |body: u32, pile: StruckPile| {
            if source.struck_pile == pile {
                glam::Mat3A::ZERO
            } else {
                motions[body as usize].inv_inertia
            }
        };
        inertia_a[k] = inertia(source.a, StruckPile::A);
        inertia_b[k] = inertia(source.b, StruckPile::B);
    }
    r.limit = Vec4::from_array(limit);
    let (inertia_a, inertia_b) = (Mat3x4::from_lanes(inertia_a), Mat3x4::from_lanes(inertia_b));
    let cached = Vec3x4::from_lanes(cached);
    let resists = r.limit.cmpgt(Vec4::ZERO);
    for (j, &t) in axes.iter().enumerate() {
        r.it_a[j] = inertia_a * t;
        r.it_b[j] = inertia_b * t;
        let k = t.dot(r.it_a[j]) + t.dot(r.it_b[j]);
        r.mass[j] = Vec4::select(resists, inverse_or_zero(k), Vec4::ZERO);
        r.impulse[j] = Vec4::select(resists, cached.dot(t), Vec4::ZERO);
    }
    // S = K_rr − K_rf·K_ff⁻¹·K_fr over the tangent pair: K_rr(j,l) = tⱼ·(I_A⁻¹ + I_B⁻¹)t_l,
    // K_rf(j,k) = tⱼ·(I_A⁻¹(r_A × t_k) + I_B⁻¹(r_B × t_k)), K_ff⁻¹ = diag(friction masses).
    let coupling =
        |j: usize, k: usize| axes[j].dot(friction.irt_a[k]) + axes[j].dot(friction.irt_b[k]);
    let schur = |j: usize, l: usize| {
        let k_rr = axes[j].dot(r.it_a[l]) + axes[j].dot(r.it_b[l]);
        (0..2).fold(k_rr, |s, k| {
            s - coupling(j, k) * friction.mass[k] * coupling(l, k)
        })
    };
    let (s11, s12, s22) = (schur(0, 0), schur(0, 1), schur(1, 1));
    let det = s11 * s22 - s12 * s12;
    // Singular (nothing to turn, or friction and rolling one row): the own masses.
    let solvable =
        det.cmpgt(Vec4::splat(f32::MIN_POSITIVE)) & resists & glam::BVec4A::from_array(held);
    let inv_det = inverse_or_zero(det);
    r.held_mass = [
        Vec4::select(solvable, s22 * inv_det, r.mass[0]),
        Vec4::select(solvable, -s12 * inv_det, Vec4::ZERO),
        Vec4::select(solvable, s11 * inv_det, r.mass[1]),
    ];
    true
}

/// Writes the rolling impulses of group `r` (axes `axes`, contacts `contact` per lane, `u32::MAX`
/// in padding) back to the contacts, as world vectors.
pub(super) fn store_rolling(
    r: &RollingLanes,
    axes: &[Vec3x4; 3],
    contact: &[u32; LANES],
    contacts: &mut [Contact],
) {
    for (k, &c) in contact.iter().enumerate() {
        if c != u32::MAX {
            let (l1, l2, l3) = (r.impulse[0][k], r.impulse[1][k], r.impulse[2][k]);
            contacts[c as usize].impulses.rolling =
                (l1 * axes[0].lane(k) + l2 * axes[1].lane(k) + l3 * axes[2].lane(k)).into();
        }
    }
}
