//! Soft constraint coefficients (Box2D v3 "soft step"; Catto, "Solver2D", 2024, and GDC 2011 "Soft
//! Constraints").
//!
//! A constraint C with effective mass m is made a damped spring of natural frequency ω = 2π·hertz and
//! damping ratio ζ by solving, with implicit Euler over a sub-step h, the velocity update
//!
//!   Δλ = −m · mass_scale · (Jv + bias_rate · C) − impulse_scale · λ_accumulated
//!
//! with a1 = 2ζ + hω, a2 = hω·a1, a3 = 1 / (1 + a2):
//!   bias_rate = ω / a1,   mass_scale = a2 · a3,   impulse_scale = a3.
//! At rest this is a spring of stiffness k = m·ω² (so the stiffness scales with the effective mass, which
//! is why a heavy body on a light one sinks — see `contact_solver`). The coefficients are independent of
//! the mass, so one `Softness` serves every contact of a kind.

/// The highest frequency a soft row may have, as a fraction of the sub-step rate: Box2D v3 caps its
/// contacts at a quarter for stability, and so does every spring here (contacts, joints, springs
/// on a distance joint).
pub const MAX_STEP_FRACTION: f32 = 0.25;

/// `hertz`, capped at [`MAX_STEP_FRACTION`] of the rate of sub-steps `h` long.
pub fn capped_hertz(hertz: f32, h: f32) -> f32 {
    hertz.min(MAX_STEP_FRACTION / h)
}

/// Coefficients of a soft constraint for one sub-step length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Softness {
    /// Fraction of the position error turned into velocity, 1/s.
    pub bias_rate: f32,
    /// Scale on the effective mass, in [0, 1].
    pub mass_scale: f32,
    /// Scale on the accumulated impulse subtracted each solve, in [0, 1].
    pub impulse_scale: f32,
}

impl Softness {
    /// A rigid constraint: no bias, full mass, no impulse leak.
    pub const RIGID: Softness = Softness {
        bias_rate: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// Coefficients for frequency `hertz` (Hz), damping ratio `zeta` and sub-step `h` (s).
    /// A non-positive frequency gives [`Softness::RIGID`].
    pub fn new(hertz: f32, zeta: f32, h: f32) -> Self {
        if !(hertz > 0.0 && h > 0.0) {
            return Self::RIGID;
        }
        let omega = 2.0 * std::f32::consts::PI * hertz;
        let a1 = 2.0 * zeta.max(0.0) + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

/// The two springs of a contact: its normal rows' and its friction anchors' (`contact_solver`,
/// "Friction anchors"), which between two dynamic bodies may be slower.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactSoftness {
    pub normal: Softness,
    pub anchor: Softness,
}

impl ContactSoftness {
    /// Both springs alike.
    pub const fn uniform(softness: Softness) -> Self {
        Self {
            normal: softness,
            anchor: softness,
        }
    }

    /// The coefficients' bits, normal first (groups share a softness only if it is the same bit
    /// for bit).
    pub fn bits(&self) -> [u32; 6] {
        let (n, a) = (self.normal, self.anchor);
        [
            n.bias_rate,
            n.mass_scale,
            n.impulse_scale,
            a.bias_rate,
            a.mass_scale,
            a.impulse_scale,
        ]
        .map(f32::to_bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steady_state_of_a_soft_contact_is_a_spring_of_stiffness_m_omega_squared() {
        // At rest Δλ = 0 and Jv = 0, so λ = −m · (mass_scale / impulse_scale) · bias_rate · C = −m h ω² C.
        let (hertz, zeta, h) = (30.0, 10.0, 1.0 / 240.0);
        let s = Softness::new(hertz, zeta, h);
        let omega = 2.0 * std::f32::consts::PI * hertz;
        let k_over_m_h = s.mass_scale / s.impulse_scale * s.bias_rate;
        assert!((k_over_m_h - h * omega * omega).abs() / (h * omega * omega) < 1e-5);
    }

    #[test]
    fn zero_frequency_is_rigid() {
        assert_eq!(Softness::new(0.0, 1.0, 0.01), Softness::RIGID);
    }
}
