//! Fast bodies: what keeps a small body from passing through a floor, and a body from reporting
//! more than the speed caps.
//!
//! A pair gets (speculative) contact points while its surfaces are within its margin,
//! `(|v_rel| + spin)·dt + speculative_distance`, the velocities taken at the start of the step. Gravity
//! adds up to `|g|·dt²` of travel towards a floor during the step that the start velocity does not
//! show: 2.7 mm at 1 g and 60 Hz, well inside the 2 cm speculative distance, but 28 cm at 100 g,
//! through which a 1 cm ball at 30 m/s fell straight through a 10 cm floor. [`gravity_reach`] is
//! the part the speculative distance does not cover; it is added to the margin of every pair of a
//! moving body and a static or sleeping one (two moving bodies fall together), and to the moving
//! bodies' boxes in the broad phase. At ordinary gravity it is zero: nothing changes.
//!
//! The speed caps (`Settings::max_linear_speed`, `max_angular_speed`) bound every velocity the
//! step reports, restitution's bounce included ([`cap_speeds`]); scene files may not start a body
//! above them.

use glam::Vec3;

/// Extra margin, m, for a moving body against a static or sleeping one: gravity's travel in a step
/// beyond half the speculative distance (which absorbs the rest), 0 at ordinary gravity.
pub fn gravity_reach(gravity: Vec3, dt: f32, speculative_distance: f32) -> f32 {
    (gravity.length() * dt * dt - 0.5 * speculative_distance).max(0.0)
}

/// `v` and `w` held to the caps (lengths `max_v`, `max_w`); non-finite vectors become zero.
pub fn cap_speeds(v: Vec3, w: Vec3, max_v: f32, max_w: f32) -> (Vec3, Vec3) {
    (cap(v, max_v), cap(w, max_w))
}

fn cap(v: Vec3, max: f32) -> Vec3 {
    if !v.is_finite() {
        return Vec3::ZERO;
    }
    let length = v.length();
    if length <= max {
        v
    } else {
        // Two ulps short, so that rounding cannot leave the result a hair over the cap.
        v * (max / length * (1.0 - 2.0 * f32::EPSILON))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordinary_gravity_needs_no_extra_reach() {
        assert_eq!(
            gravity_reach(Vec3::new(0.0, -9.81, 0.0), 1.0 / 60.0, 0.02),
            0.0
        );
        let strong = gravity_reach(Vec3::new(0.0, -1000.0, 0.0), 1.0 / 60.0, 0.02);
        assert!((strong - (1000.0 / 3600.0 - 0.01)).abs() < 1e-6, "{strong}");
    }

    #[test]
    fn speeds_over_the_caps_are_scaled_to_them() {
        let (v, w) = cap_speeds(Vec3::new(300.0, 400.0, 0.0), Vec3::Z, 400.0, 200.0);
        assert!(v.length() <= 400.0 && v.length() > 399.99, "{}", v.length());
        assert_eq!(w, Vec3::Z);
        assert_eq!(cap_speeds(Vec3::NAN, Vec3::ZERO, 1.0, 1.0).0, Vec3::ZERO);
    }
}
