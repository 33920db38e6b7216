//! The solver's copy of an awake dynamic body: the hot state the contact solver reads and writes, and
//! the integration of velocities and positions over one sub-step.
//!
//! Hot and cold data are split as in Box2D v3: `SolverBody` holds only what the contact kernels touch
//! (velocities and position/rotation deltas since the start of the step; the constraints carry their
//! own mass terms), `SolverMotion` the mass properties and what the integrator alone needs. Index 0 of both arrays is a shared static
//! dummy with zero inverse mass and inertia: contacts against static (or sleeping) bodies point there, so
//! applying an impulse to it adds exactly zero and the kernels need no branch. Static bodies therefore cost
//! nothing in the solver.

use glam::{Mat3, Mat3A, Quat, Vec3, Vec3A};

use crate::physics::solve::free_rotation::free_rotation;

/// Hot per-body solver state (64 bytes, SIMD vectors). Invariant: the dummy at index 0 stays all zero.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SolverBody {
    /// Linear velocity, m/s, world.
    pub v: Vec3A,
    /// Angular velocity, rad/s, world.
    pub w: Vec3A,
    /// Translation since the start of the step, m.
    pub dp: Vec3A,
    /// Rotation since the start of the step as a rotation vector (Σ ω·h), rad. Only used to update
    /// contact separations to first order, like Box2D v3's anchor-based separation.
    pub dtheta: Vec3A,
}

impl SolverBody {
    pub const DUMMY: SolverBody = SolverBody {
        v: Vec3A::ZERO,
        w: Vec3A::ZERO,
        dp: Vec3A::ZERO,
        dtheta: Vec3A::ZERO,
    };
}

/// Cold per-body data: mass properties (read when constraints are prepared) and what the integrator
/// alone needs.
///
/// Laid out by hand in two cache lines (`repr(C)`, 64-byte aligned): the first holds everything the
/// integrators read every sub-step (rotation, accelerations, and the gyroscopic data), the second what
/// constraint preparation reads (mass, inertia). Each sub-step's integration thus touches one line
/// per body, and preparation the other.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct SolverMotion {
    /// Orientation, unit quaternion, renormalised every sub-step.
    pub rotation: Quat,
    /// Linear acceleration from gravity and applied force, m/s².
    pub linear_accel: Vec3A,
    /// Angular acceleration from applied torque, I⁻¹τ with the body's own world inertia at the
    /// step's start (not its joints' floor), rad/s².
    pub angular_accel: Vec3A,
    /// Principal moments of inertia, body frame, kg·m².
    pub inertia_local: Vec3,
    /// False when the three moments are equal (spheres, cubes): ω × Iω = 0, nothing to integrate.
    pub gyroscopic: bool,
    /// World inverse inertia at the start of the step, 1/(kg·m²); zero for the dummy.
    pub inv_inertia: Mat3A,
    /// Index of the body in the world.
    pub body: u32,
    /// 1/kg; 0 for the dummy.
    pub inv_mass: f32,
    /// The least each principal moment of inertia may be in the step's rows, kg·m²: the geometric
    /// stiffness of the joints pulling on it (`Settings::joint_geometric_stiffness`; in
    /// `inv_inertia` already, not in `inertia_local`, which the integration keeps as it is).
    pub inertia_floor: f32,
}

impl SolverMotion {
    pub const DUMMY: SolverMotion = SolverMotion {
        rotation: Quat::IDENTITY,
        linear_accel: Vec3A::ZERO,
        angular_accel: Vec3A::ZERO,
        inertia_local: Vec3::ONE,
        gyroscopic: false,
        inv_inertia: Mat3A::ZERO,
        body: u32::MAX,
        inv_mass: 0.0,
        inertia_floor: 0.0,
    };
}

/// Velocity-integration parameters for one sub-step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct VelocityStep {
    /// Sub-step, s.
    pub h: f32,
    /// 1 / (1 + h·c_linear): implicit linear damping factor, 1 when damping is off.
    pub linear_damping: f32,
    /// Same for angular damping.
    pub angular_damping: f32,
    /// Speed caps, m/s and rad/s.
    pub max_linear_speed: f32,
    pub max_angular_speed: f32,
}

/// Symplectic Euler, velocity half: v += h·a; ω += h·I⁻¹τ (the gyroscopic part of a free rotation is
/// the position half's, see [`free_rotation`]).
///
/// Lane-wise SIMD (`Vec3A`): each lane computes exactly the scalar expression
/// `(v + h·a)·damping`, so results are the same bit for bit as with `Vec3`. A vector is clamped
/// when `|v|² > max²` or it has a NaN component; both are `!(|v|² ≤ max²)`, since |v|² is NaN
/// exactly when a component is (squares are ≥ 0 or +∞). A NaN cap clamps only NaN vectors, which
/// `!(|v|² ≤ ∞)` also says, so the cap's square is taken as ∞ then.
#[inline(never)]
pub(crate) fn integrate_velocities(
    bodies: &mut [SolverBody],
    motions: &[SolverMotion],
    step: &VelocityStep,
) {
    let h = step.h;
    let square_cap = |max: f32| {
        let max2 = max * max;
        if max2.is_nan() { f32::INFINITY } else { max2 }
    };
    let max_v2 = square_cap(step.max_linear_speed);
    let max_w2 = square_cap(step.max_angular_speed);
    // Index 0 is the dummy; slicing both to one length lets the loop run on a plain counter.
    let n = bodies.len().min(motions.len());
    let (bodies, motions) = (&mut bodies[1.min(n)..n], &motions[1.min(n)..n]);
    for (sb, m) in bodies.iter_mut().zip(motions) {
        let v = (sb.v + h * m.linear_accel) * step.linear_damping;
        let w = (sb.w + h * m.angular_accel) * step.angular_damping;
        let v_over = over_cap(v.length_squared(), max_v2);
        let w_over = over_cap(w.length_squared(), max_w2);
        if v_over | w_over {
            (sb.v, sb.w) = clamp_speeds(v, w, v_over, w_over, step);
        } else {
            sb.v = v;
            sb.w = w;
        }
    }
}

/// `!(len2 ≤ max2)`: true when `len2` is above the cap or NaN (one comparison for both).
#[inline(always)]
#[allow(clippy::neg_cmp_op_on_partial_ord)] // the negation is the point: NaN counts as over
fn over_cap(len2: f32, max2: f32) -> bool {
    !(len2 <= max2)
}

/// The cold path of [`integrate_velocities`]: `v` and `w` with whichever is over its cap clamped.
#[cold]
#[inline(never)]
fn clamp_speeds(
    v: Vec3A,
    w: Vec3A,
    v_over: bool,
    w_over: bool,
    step: &VelocityStep,
) -> (Vec3A, Vec3A) {
    let v = if v_over {
        clamp_length(v.into(), step.max_linear_speed).into()
    } else {
        v
    };
    let w = if w_over {
        clamp_length(w.into(), step.max_angular_speed).into()
    } else {
        w
    };
    (v, w)
}

/// Symplectic Euler, position half: x += h·v; q += ½·h·(ω, 0)·q, renormalised, for a body whose
/// principal moments are equal (ω is then its momentum over one moment, and stays). One whose moments
/// differ turns as a free body does, keeping its angular momentum ([`free_rotation`]), and ω follows.
#[inline(never)]
pub(crate) fn integrate_positions(bodies: &mut [SolverBody], motions: &mut [SolverMotion], h: f32) {
    let n = bodies.len().min(motions.len());
    let (bodies, motions) = (&mut bodies[1.min(n)..n], &mut motions[1.min(n)..n]);
    for (sb, m) in bodies.iter_mut().zip(motions) {
        sb.dp += h * sb.v;
        sb.dtheta += h * sb.w;
        if m.gyroscopic
            && let Some((q, w)) = free_rotation(m.rotation, sb.w.into(), m.inertia_local, h)
        {
            (m.rotation, sb.w) = (q, w.into());
            continue;
        }
        let q = m.rotation;
        let spin = Quat::from_xyzw(sb.w.x, sb.w.y, sb.w.z, 0.0) * q;
        let q = q + spin * (0.5 * h);
        m.rotation = normalized_or(q, m.rotation);
    }
}

/// `v` scaled down to length `max` (cold path: `v` is longer, its squared length overflowed, or it is
/// not finite, in which case it becomes zero).
#[cold]
fn clamp_length(v: Vec3, max: f32) -> Vec3 {
    if !v.is_finite() {
        return Vec3::ZERO;
    }
    let scale = v.abs().max_element();
    if scale == 0.0 {
        return v;
    }
    let u = v / scale;
    let len = scale * u.length();
    if len <= max {
        v
    } else {
        u * (max / u.length())
    }
}

/// `q / |q|`, or `fallback` when q is zero or not finite.
#[inline]
pub(crate) fn normalized_or(q: Quat, fallback: Quat) -> Quat {
    let len2 = q.length_squared();
    if len2 > f32::MIN_POSITIVE && len2.is_finite() {
        q * len2.sqrt().recip()
    } else {
        fallback
    }
}

/// The cross-product matrix: skew(a)·b = a × b (also the point drive's compliance).
#[inline]
pub(super) fn skew(a: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, a.z, -a.y),
        Vec3::new(-a.z, 0.0, a.x),
        Vec3::new(a.y, -a.x, 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn skew_matrix_is_the_cross_product() {
        let a = Vec3::new(1.0, -2.0, 3.0);
        let b = Vec3::new(0.5, 4.0, -1.0);
        assert!((skew(a) * b - a.cross(b)).length() < 1e-6);
    }

    /// The velocity half step written with scalar `Vec3`s and separate NaN tests: what
    /// `integrate_velocities` computes lane by lane, kept here as its specification.
    fn integrate_velocity_scalar(
        v: Vec3,
        w: Vec3,
        m: &SolverMotion,
        step: &VelocityStep,
    ) -> (Vec3, Vec3) {
        let h = step.h;
        let mut v = (v + h * Vec3::from(m.linear_accel)) * step.linear_damping;
        let mut w = (w + h * Vec3::from(m.angular_accel)) * step.angular_damping;
        let max_v2 = step.max_linear_speed * step.max_linear_speed;
        let max_w2 = step.max_angular_speed * step.max_angular_speed;
        if v.length_squared() > max_v2 || v.is_nan() {
            v = clamp_length(v, step.max_linear_speed);
        }
        if w.length_squared() > max_w2 || w.is_nan() {
            w = clamp_length(w, step.max_angular_speed);
        }
        (v, w)
    }

    fn bits(v: Vec3A) -> [u32; 3] {
        Vec3::from(v).to_array().map(f32::to_bits)
    }

    #[test]
    fn simd_velocity_integration_matches_the_scalar_one_bit_for_bit_even_on_nan_and_infinity() {
        let values = [
            0.0,
            -0.0,
            1.5,
            -3.25e-3,
            700.0,
            -1e20,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        let vectors: Vec<Vec3> = (0..values.len() * 3)
            .map(|i| {
                let pick = |k: usize| values[(i * 7 + k * 5) % values.len()];
                Vec3::new(pick(0), pick(1), pick(2))
            })
            .collect();
        let caps = [100.0, 0.0, f32::INFINITY, f32::NAN, 1e30];
        let motion = |k: usize| SolverMotion {
            rotation: Quat::from_rotation_y(0.3 * k as f32),
            linear_accel: Vec3A::new(0.0, -9.81, 0.25 * k as f32),
            angular_accel: Vec3A::new(-0.5, 0.0, 1e-3 * k as f32),
            inertia_local: if k % 2 == 0 {
                Vec3::splat(0.4)
            } else {
                Vec3::new(0.1, 0.7, 1.3)
            },
            gyroscopic: k % 2 == 1,
            ..SolverMotion::DUMMY
        };
        for (c, &cap) in caps.iter().enumerate() {
            let step = VelocityStep {
                h: 1.0 / 240.0,
                linear_damping: if c % 2 == 0 { 1.0 } else { 0.99 },
                angular_damping: if c % 3 == 0 { 1.0 } else { 0.98 },
                max_linear_speed: cap,
                max_angular_speed: caps[(c + 2) % caps.len()],
            };
            let mut bodies = vec![SolverBody::DUMMY];
            let mut motions = vec![SolverMotion::DUMMY];
            for (k, pair) in vectors.windows(2).enumerate() {
                bodies.push(SolverBody {
                    v: pair[0].into(),
                    w: pair[1].into(),
                    ..SolverBody::DUMMY
                });
                motions.push(motion(k));
            }
            let before = bodies.clone();
            integrate_velocities(&mut bodies, &motions, &step);
            for (i, (after, start)) in bodies.iter().zip(&before).enumerate().skip(1) {
                let (v, w) =
                    integrate_velocity_scalar(start.v.into(), start.w.into(), &motions[i], &step);
                assert_eq!(bits(after.v), bits(v.into()), "v of body {i}, cap {cap}");
                assert_eq!(bits(after.w), bits(w.into()), "w of body {i}, cap {cap}");
            }
        }
    }

    #[test]
    fn the_motion_keeps_what_the_integrators_read_in_its_first_cache_line() {
        assert_eq!(std::mem::size_of::<SolverMotion>(), 128);
        assert_eq!(std::mem::align_of::<SolverMotion>(), 64);
        assert!(std::mem::offset_of!(SolverMotion, gyroscopic) < 64);
        assert!(std::mem::offset_of!(SolverMotion, inertia_local) + 12 <= 64);
        assert_eq!(std::mem::offset_of!(SolverMotion, inv_inertia), 64);
    }
}
