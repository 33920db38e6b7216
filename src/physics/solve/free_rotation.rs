//! The torque-free rotation of a body whose principal moments differ, over one sub-step, by the
//! splitting of Dullweber, Leimkuhler & McLachlan ("Symplectic splitting methods for rigid body
//! molecular dynamics", J. Chem. Phys. 107, 1997; also Touma & Wisdom 1994).
//!
//! With L the angular momentum in the body's principal frame, a free body's energy is
//! H = L₁²/2I₁ + L₂²/2I₂ + L₃²/2I₃. Each term alone has an exact flow: H_i spins the body about its
//! principal axis e_i at the constant rate L_i/I_i, and turns L the other way in the body frame,
//! so the world's angular momentum R·L does not change. The step is the symmetric composition
//!
//!   Φ_h = Φ₁(h/2) ∘ Φ₂(h/2) ∘ Φ₃(h) ∘ Φ₂(h/2) ∘ Φ₁(h/2),
//!
//! second order and symplectic: the world's L is kept exactly (to rounding), in length and in
//! direction, and the energy error stays bounded instead of drifting. It replaces an implicit
//! midpoint step on the Euler equations for ω followed by a first-order rotation q += ½·h·ω·q,
//! which turned L by 33 mrad in 10 s on a plank spun fast about its intermediate axis, and 134 mrad
//! at one sub-step.
//!
//! A body's ω after the contacts is taken as its L (in the inertia the solver used), the rotation
//! is advanced by Φ_h, and ω is read back from L in the new attitude: with no contact, the next
//! sub-step starts from the same L.
//!
//! A symmetric top (two equal moments A, the third C about its axis e: a box with two equal
//! sides, most of a ragdoll's limbs) needs no splitting. Its energy is H = |L|²/2A + κ·L_e²/2
//! with κ = 1/C − 1/A, and the two terms commute (|L|² is conserved by any rotation of the
//! body), so their exact flows compose to the exact motion: the body turns about the world's L at
//! |L|/A and about its own axis at κ·L_e,
//!
//!   R(h) = exp(h·L/A) · R(0) · exp(h·κ·L_e·e),
//!
//! two rotations instead of five, exact to rounding at any step
//! (`a_symmetric_top_precesses_exactly_at_any_step`).

use glam::{Quat, Vec3};

/// The rotation `rotation` (body to world, principal axes) and world angular velocity `w` of a
/// body with principal moments `inertia` (kg·m²) after `h` seconds free of torque: the new rotation
/// and the new world angular velocity, with the same world angular momentum. `None` when a moment
/// is not positive and finite (a box with two zero extents has one zero moment) or the result is
/// not finite: the caller turns the body to first order instead.
pub(crate) fn free_rotation(
    rotation: Quat,
    w: Vec3,
    inertia: Vec3,
    h: f32,
) -> Option<(Quat, Vec3)> {
    if !(inertia.min_element() > 0.0 && inertia.is_finite()) {
        return None;
    }
    match symmetry_axis(inertia) {
        Some(axis) => symmetric_top(rotation, w, inertia, axis, h),
        None => splitting(rotation, w, inertia, h),
    }
}

/// Φ_h, the symmetric splitting of the module docs.
fn splitting(rotation: Quat, w: Vec3, inertia: Vec3, h: f32) -> Option<(Quat, Vec3)> {
    let mut q = rotation;
    let mut l = inertia * (rotation.inverse() * w);
    // Unrolled by axis, so that the components are registers: the five flows are a chain, each
    // reading the L the last one turned, and the loop's indexing through memory lengthened it.
    turn::<0>(&mut q, &mut l, inertia, 0.5 * h);
    turn::<1>(&mut q, &mut l, inertia, 0.5 * h);
    turn::<2>(&mut q, &mut l, inertia, h);
    turn::<1>(&mut q, &mut l, inertia, 0.5 * h);
    turn::<0>(&mut q, &mut l, inertia, 0.5 * h);
    let q = q.normalize();
    let w = q * (l / inertia);
    (q.is_finite() && w.is_finite()).then_some((q, w))
}

/// The axis (0, 1 or 2) of a body whose other two moments are equal, bit for bit (a box's two
/// equal sides give equal moments exactly), or `None`. All three equal is the caller's case (its
/// ω is its momentum over one moment and stays).
fn symmetry_axis(inertia: Vec3) -> Option<usize> {
    let [x, y, z] = inertia.to_array();
    if y == z {
        Some(0)
    } else if x == z {
        Some(1)
    } else if x == y {
        Some(2)
    } else {
        None
    }
}

/// The exact torque-free motion of a symmetric top about its axis `axis` (see the module docs).
fn symmetric_top(
    rotation: Quat,
    w: Vec3,
    inertia: Vec3,
    axis: usize,
    h: f32,
) -> Option<(Quat, Vec3)> {
    let body_l = inertia * (rotation.inverse() * w);
    let world_l = rotation * body_l;
    let a = inertia[(axis + 1) % 3];
    let kappa = 1.0 / inertia[axis] - 1.0 / a;
    let mut spin = Vec3::ZERO;
    spin[axis] = h * kappa * body_l[axis];
    let q = (Quat::from_scaled_axis(world_l * (h / a)) * rotation * Quat::from_scaled_axis(spin))
        .normalize();
    let w = q * ((q.inverse() * world_l) / inertia);
    (q.is_finite() && w.is_finite()).then_some((q, w))
}

/// The flow of H_AXIS alone over `t` seconds: the body turns about its principal axis `AXIS` at
/// the rate L_AXIS/I_AXIS, and L turns the other way about it in the body frame.
#[inline(always)]
fn turn<const AXIS: usize>(q: &mut Quat, l: &mut Vec3, inertia: Vec3, t: f32) {
    let angle = l[AXIS] / inertia[AXIS] * t;
    let (sin, cos) = (0.5 * angle).sin_cos();
    let mut xyz = Vec3::ZERO;
    xyz[AXIS] = sin;
    *q *= Quat::from_xyzw(xyz.x, xyz.y, xyz.z, cos);
    // L turns by −angle about the axis, in the plane of the two other components: the rotation's
    // matrix from the half angle's sine and cosine, not a general quaternion's.
    let (c, s) = (1.0 - 2.0 * sin * sin, 2.0 * sin * cos);
    let (i, j) = ((AXIS + 1) % 3, (AXIS + 2) % 3);
    (l[i], l[j]) = (c * l[i] + s * l[j], c * l[j] - s * l[i]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// World angular momentum and kinetic energy of the body in `rotation` spinning at `w`.
    fn momentum_and_energy(rotation: Quat, w: Vec3, inertia: Vec3) -> (Vec3, f32) {
        let body_w = rotation.inverse() * w;
        let l = rotation * (inertia * body_w);
        (l, 0.5 * body_w.dot(inertia * body_w))
    }

    #[test]
    fn a_spin_about_a_principal_axis_turns_the_body_at_that_rate_and_keeps_w() {
        let inertia = Vec3::new(1.0, 2.0, 3.0);
        let (q, w) = free_rotation(Quat::IDENTITY, Vec3::new(0.0, 3.0, 0.0), inertia, 0.1).unwrap();
        assert!((w - Vec3::new(0.0, 3.0, 0.0)).length() < 1e-6);
        assert!(q.angle_between(Quat::from_rotation_y(0.3)) < 1e-6);
    }

    /// The Dzhanibekov plank spun fast about its intermediate axis, 10 s at one sub-step of 60 Hz
    /// (a third of a radian a step): it flips over and over, L stays put and the energy stays
    /// within a percent.
    #[test]
    fn a_fast_intermediate_axis_spin_flips_with_its_momentum_fixed() {
        let half = Vec3::new(0.1, 0.4, 1.0);
        let mass = 1.0;
        let sq = half * half;
        let inertia = mass / 3.0 * Vec3::new(sq.y + sq.z, sq.x + sq.z, sq.x + sq.y);
        let (mut q, mut w) = (Quat::IDENTITY, Vec3::new(1e-3, 20.0, 1e-3));
        let (l0, e0) = momentum_and_energy(q, w, inertia);
        let mut flips = 0;
        let mut up = true;
        let (mut worst, mut worst_energy) = (0.0f32, 0.0f32);
        for _ in 0..600 {
            (q, w) = free_rotation(q, w, inertia, 1.0 / 60.0).unwrap();
            let (l, e) = momentum_and_energy(q, w, inertia);
            let turned = l.cross(l0).length().atan2(l.dot(l0));
            worst = worst
                .max(turned)
                .max((l.length() / l0.length() - 1.0).abs());
            worst_energy = worst_energy.max((e / e0 - 1.0).abs());
            let now_up = (q * Vec3::Y).dot(l0) > 0.0;
            flips += usize::from(now_up != up);
            up = now_up;
        }
        // Measured 6.8e-5 (f32 rounding over 3000 turns), 0.51 % and 9 flips.
        assert!(worst < 2e-4, "L drifted or turned by {worst}");
        assert!(worst_energy < 0.01, "the energy drifted by {worst_energy}");
        assert!(flips >= 4, "the plank flipped {flips} times");
    }

    /// A symmetric top spun off its axis: in one step of any length its axis precesses about L at
    /// |L|/A, to rounding (1e-7), where the splitting is second order: it strays 4e-6 at 0.01 s,
    /// 4e-3 at 0.1 s and 0.19 at 0.5 s (measured 2026-11-29). L and the energy are kept.
    #[test]
    fn a_symmetric_top_precesses_exactly_at_any_step() {
        let inertia = Vec3::new(0.5, 0.2, 0.5);
        let q0 = Quat::from_rotation_z(0.3);
        let w0 = Vec3::new(1.0, 4.0, -0.5);
        let (l0, e0) = momentum_and_energy(q0, w0, inertia);
        for h in [0.01, 0.1, 0.5] {
            let exact_axis = Quat::from_scaled_axis(l0 * (h / inertia.x)) * (q0 * Vec3::Y);
            let (q, w) = free_rotation(q0, w0, inertia, h).unwrap();
            let strayed = (q * Vec3::Y).distance(exact_axis);
            assert!(strayed < 1e-6, "at {h} s the axis strayed {strayed}");
            let (l, e) = momentum_and_energy(q, w, inertia);
            assert!(l.distance(l0) < 1e-6 * l0.length(), "L moved: {l0} → {l}");
            assert!((e / e0 - 1.0).abs() < 1e-6, "energy {e0} → {e}");
        }
    }

    #[test]
    fn a_zero_or_unbounded_moment_or_spin_is_left_to_the_caller() {
        let q = Quat::IDENTITY;
        assert!(free_rotation(q, Vec3::ONE, Vec3::new(0.0, 1.0, 1.0), 0.1).is_none());
        assert!(free_rotation(q, Vec3::ONE, Vec3::new(f32::INFINITY, 1.0, 1.0), 0.1).is_none());
        assert!(free_rotation(q, Vec3::splat(f32::NAN), Vec3::new(1.0, 2.0, 3.0), 0.1).is_none());
    }
}
