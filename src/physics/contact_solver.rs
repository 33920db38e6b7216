//! Contact constraints and the sequential-impulse kernels that solve them.
//!
//! # The contact row
//! For a point with anchors r_a = p − x_a, r_b = p − x_b (world, relative to the centres of mass — never
//! absolute positions, so a stack at x = 5000 m solves like one at the origin) and normal n (A → B), the
//! relative normal velocity is
//!
//!   v_n = n · (v_b + ω_b × r_b − v_a − ω_a × r_a) = n·(v_b − v_a) + ω_b·(r_b × n) − ω_a·(r_a × n),
//!
//! so the Jacobian is J = [−nᵀ, −(r_a × n)ᵀ, nᵀ, (r_b × n)ᵀ] and the effective mass m = 1 / (J M⁻¹ Jᵀ) with
//!
//!   J M⁻¹ Jᵀ = 1/m_a + 1/m_b + (r_a × n)·I_a⁻¹(r_a × n) + (r_b × n)·I_b⁻¹(r_b × n).
//!
//! The friction rows are the same with the two tangents t₁, t₂ in place of n.
//!
//! # Sequential impulses (Catto, GDC 2006/2014; Box2D v3 `contact_solver.c`)
//! Each row keeps its accumulated impulse λ and clamps the *total*, not the increment: λ_n ≥ 0, and the
//! friction pair (λ₁, λ₂) inside the circle of radius μ·λ_n (a round friction cone, no pyramid bias).
//! Impulses are warm-started from last step by feature id.
//!
//! # Soft step (Catto, "Solver2D" 2024 / Box2D v3)
//! The current separation is s = s₀ + n·(Δp_b − Δp_a) + Δθ_b·(r_b × n) − Δθ_a·(r_a × n), updated from the
//! bodies' position deltas each sub-step (first order in rotation) instead of re-running collision. Then
//!   s > 0 (speculative):  bias = s / h, rigid — the bodies may close the gap exactly, never more;
//!   s ≤ 0, solve pass:    bias = max(β·min(s + slop, 0), −v_push), soft (see `softness.rs`);
//!   s ≤ 0, relax pass:    bias = 0, rigid — removes the velocity the bias added, so push-out adds no
//!                         energy.
//! and Δλ = −m·mass_scale·(v_n + bias) − impulse_scale·λ.
//! Restitution runs once per step after the sub-steps, on points whose pre-solve approach speed exceeded
//! the threshold: target v_n = −e·v_n(pre-solve).
//!
//! # The heavy-on-light problem and shock propagation
//! A soft contact is a spring of stiffness k = m_eff·ω² (see `softness.rs`), and the effective mass of a
//! contact between a 1000 kg box and a 1 kg box is ≈ 1 kg. Holding 9810 N then needs ≈ 0.28 m of
//! penetration, and Gauss–Seidel iterations barely move the heavy body anyway: this is why Rapier sinks.
//! Options considered:
//! - more iterations for islands with a large mass ratio: convergence of Gauss–Seidel is governed by the
//!   ratio, so 1000:1 needs thousands of iterations; the spring stiffness problem stays.
//! - an exact (direct, LCP/Cholesky) solve for small islands: exact, but a second solver with its own
//!   friction model and a cliff in cost and behaviour at the island-size cutoff.
//! - **shock propagation** (Guendelman, Bridson & Fedkiw 2003; Erleben 2005), chosen: each step the
//!   contact graph is layered by breadth-first distance from static bodies, constraints are solved in
//!   that order, and after the biased solve of every sub-step one extra pass visits the manifolds bottom
//!   up treating the lower body as infinitely heavy: if the points of a manifold still approach (on
//!   average) faster than the bias allows, the upper body alone is pushed along n by the missing amount,
//!   with a matching friction impulse so the push cannot make it slide. It is a one-sided velocity
//!   projection: where Gauss–Seidel converged it does nothing; where it did not (mass ratios, tall
//!   stacks) the stack becomes rigid from the ground up, so positions never integrate a sinking velocity.
//!   Cost: one cheap pass over the manifolds per sub-step, a BFS and a sort per step. Trade-offs: the
//!   shock impulses get no reaction, so momentum is not conserved by that residual (a heavy body dropped
//!   on a light one is stopped "by the ground"); layering follows the contact graph, not gravity, so a
//!   body hit from the side by a body deeper in the graph is treated as the lighter one; the push is
//!   translational (an angular push per corner made stacks lean and walk), so tilt is left to the
//!   regular rows; its friction acts on linear velocity only, so a sliding ball spins up a little
//!   less than exact (it ends rolling ≈ 1% under 5/7 of its speed).

use glam::Vec3;

use super::contact::{CachedImpulse, Contact};
use super::manifold::MAX_MANIFOLD_POINTS;
use super::softness::Softness;
use super::solver_body::SolverBody;

/// One solver row set for a contact point.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ConstraintPoint {
    /// Anchors from the centres of mass, world, m.
    pub r_a: Vec3,
    pub r_b: Vec3,
    /// r × n, m.
    pub rn_a: Vec3,
    pub rn_b: Vec3,
    /// I⁻¹(r × n), the angular velocity change per unit normal impulse, 1/(kg·m).
    pub irn_a: Vec3,
    pub irn_b: Vec3,
    /// Separation at the start of the step, m (negative = penetration).
    pub separation: f32,
    /// Effective masses, kg.
    pub normal_mass: f32,
    pub tangent_mass: [f32; 2],
    /// Accumulated impulses, N·s.
    pub normal_impulse: f32,
    pub tangent_impulse: [f32; 2],
    /// Largest normal impulse increment this step, N·s: restitution applies only to points that pushed.
    pub max_normal_impulse: f32,
    /// Relative normal velocity before the solve, m/s (negative = approaching).
    pub relative_velocity: f32,
}

/// A contact manifold prepared for the solver.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ContactConstraint {
    /// Solver body indices; 0 is the static dummy.
    pub a: u32,
    pub b: u32,
    /// Index of the persistent contact, to store impulses back.
    pub contact: u32,
    /// Unit normal A → B and two unit tangents, world.
    pub normal: Vec3,
    pub tangents: [Vec3; 2],
    pub friction: f32,
    pub restitution: f32,
    pub softness: Softness,
    /// 1 or 0: whether the shock pass may move A (0 when A is the lower, "infinitely heavy" body).
    pub shock_scale_a: f32,
    pub shock_scale_b: f32,
    /// 1 / (scale_a / m_a + scale_b / m_b): translational mass of the shock pass, kg.
    pub shock_mass: f32,
    pub len: usize,
    pub points: [ConstraintPoint; MAX_MANIFOLD_POINTS],
}

/// What `prepare` needs to know about one side of a contact.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side {
    /// Solver index (0 = static dummy).
    pub index: u32,
    /// Centre of mass, world, m.
    pub position: Vec3,
    /// Shock-propagation layer: 0 for static bodies, BFS depth from them otherwise.
    pub level: u32,
}

/// Per-pass constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PassParams {
    /// 1 / sub-step, 1/s.
    pub inv_h: f32,
    /// Fastest push-out, m/s.
    pub max_push_out: f32,
    /// Penetration left uncorrected, m.
    pub linear_slop: f32,
}

/// Two unit tangents orthogonal to unit `n` (Duff et al. 2017, "Building an orthonormal basis, revisited").
#[inline]
pub(crate) fn tangent_basis(n: Vec3) -> [Vec3; 2] {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    [
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    ]
}

#[inline]
fn inverse_or_zero(k: f32) -> f32 {
    if k > 0.0 { 1.0 / k } else { 0.0 }
}

/// Builds the constraint of `contact` between sides `sa` and `sb`.
pub(crate) fn prepare(
    contact_index: u32,
    contact: &Contact,
    sa: &Side,
    sb: &Side,
    bodies: &[SolverBody],
    contact_softness: Softness,
    static_softness: Softness,
) -> ContactConstraint {
    let ba = &bodies[sa.index as usize];
    let bb = &bodies[sb.index as usize];
    let n = contact.manifold.normal;
    let tangents = tangent_basis(n);
    let (shock_scale_a, shock_scale_b) = match sa.level.cmp(&sb.level) {
        std::cmp::Ordering::Less => (0.0, 1.0),
        std::cmp::Ordering::Greater => (1.0, 0.0),
        std::cmp::Ordering::Equal => (1.0, 1.0),
    };
    let softness = if sa.index == 0 || sb.index == 0 {
        static_softness
    } else {
        contact_softness
    };
    let mut c = ContactConstraint {
        a: sa.index,
        b: sb.index,
        contact: contact_index,
        normal: n,
        tangents,
        friction: contact.friction,
        restitution: contact.restitution,
        softness,
        shock_scale_a,
        shock_scale_b,
        shock_mass: inverse_or_zero(shock_scale_a * ba.inv_mass + shock_scale_b * bb.inv_mass),
        len: contact.manifold.len,
        points: [ConstraintPoint::default(); MAX_MANIFOLD_POINTS],
    };
    let m_sum = ba.inv_mass + bb.inv_mass;
    for (i, mp) in contact.manifold.points().iter().enumerate() {
        let r_a = mp.point - sa.position;
        let r_b = mp.point - sb.position;
        let rn_a = r_a.cross(n);
        let rn_b = r_b.cross(n);
        let irn_a = ba.inv_inertia * rn_a;
        let irn_b = bb.inv_inertia * rn_b;
        let k_a = ba.inv_mass + rn_a.dot(irn_a);
        let k_b = bb.inv_mass + rn_b.dot(irn_b);
        let mut tangent_mass = [0.0; 2];
        for (t, tm) in tangents.iter().zip(&mut tangent_mass) {
            let rt_a = r_a.cross(*t);
            let rt_b = r_b.cross(*t);
            let k = m_sum + rt_a.dot(ba.inv_inertia * rt_a) + rt_b.dot(bb.inv_inertia * rt_b);
            *tm = inverse_or_zero(k);
        }
        let dv = bb.v + bb.w.cross(r_b) - ba.v - ba.w.cross(r_a);
        let cached: CachedImpulse = contact.impulses[i];
        c.points[i] = ConstraintPoint {
            r_a,
            r_b,
            rn_a,
            rn_b,
            irn_a,
            irn_b,
            separation: mp.separation,
            normal_mass: inverse_or_zero(k_a + k_b),
            tangent_mass,
            normal_impulse: cached.normal.max(0.0),
            tangent_impulse: [
                cached.tangent.dot(tangents[0]),
                cached.tangent.dot(tangents[1]),
            ],
            max_normal_impulse: 0.0,
            relative_velocity: n.dot(dv),
        };
    }
    c
}

/// Current separation of a point from the bodies' deltas since the start of the step.
#[inline]
fn current_separation(p: &ConstraintPoint, d_p: f32, ba: &SolverBody, bb: &SolverBody) -> f32 {
    p.separation + d_p + bb.dtheta.dot(p.rn_b) - ba.dtheta.dot(p.rn_a)
}

/// Applies last step's impulses.
pub(crate) fn warm_start(constraints: &[ContactConstraint], bodies: &mut [SolverBody]) {
    for c in constraints {
        let (ia, ib) = (c.a as usize, c.b as usize);
        let mut ba = bodies[ia];
        let mut bb = bodies[ib];
        for p in &c.points[..c.len] {
            let impulse = p.normal_impulse * c.normal
                + p.tangent_impulse[0] * c.tangents[0]
                + p.tangent_impulse[1] * c.tangents[1];
            ba.v -= ba.inv_mass * impulse;
            ba.w -= ba.inv_inertia * p.r_a.cross(impulse);
            bb.v += bb.inv_mass * impulse;
            bb.w += bb.inv_inertia * p.r_b.cross(impulse);
        }
        bodies[ia] = ba;
        bodies[ib] = bb;
    }
}

/// One Gauss–Seidel sweep: normal rows (soft and biased when `use_bias`, else rigid), then friction.
pub(crate) fn solve(
    constraints: &mut [ContactConstraint],
    bodies: &mut [SolverBody],
    params: &PassParams,
    use_bias: bool,
) {
    for c in constraints {
        let (ia, ib) = (c.a as usize, c.b as usize);
        let mut ba = bodies[ia];
        let mut bb = bodies[ib];
        let n = c.normal;
        let d_p = n.dot(bb.dp - ba.dp);
        let soft = if use_bias {
            c.softness
        } else {
            Softness::RIGID
        };
        for p in &mut c.points[..c.len] {
            let s = current_separation(p, d_p, &ba, &bb);
            let (bias, mass_scale, impulse_scale) = if s > 0.0 {
                (s * params.inv_h, 1.0, 0.0)
            } else if use_bias {
                let bias =
                    (soft.bias_rate * (s + params.linear_slop).min(0.0)).max(-params.max_push_out);
                (bias, soft.mass_scale, soft.impulse_scale)
            } else {
                (0.0, 1.0, 0.0)
            };
            let vn = n.dot(bb.v - ba.v) + bb.w.dot(p.rn_b) - ba.w.dot(p.rn_a);
            let delta =
                -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
            let total = (p.normal_impulse + delta).max(0.0);
            let delta = total - p.normal_impulse;
            p.normal_impulse = total;
            p.max_normal_impulse = p.max_normal_impulse.max(delta);
            ba.v -= (ba.inv_mass * delta) * n;
            ba.w -= delta * p.irn_a;
            bb.v += (bb.inv_mass * delta) * n;
            bb.w += delta * p.irn_b;
        }
        let [t1, t2] = c.tangents;
        for p in &mut c.points[..c.len] {
            let dv = bb.v + bb.w.cross(p.r_b) - ba.v - ba.w.cross(p.r_a);
            let old = p.tangent_impulse;
            let mut new = [
                old[0] - p.tangent_mass[0] * dv.dot(t1),
                old[1] - p.tangent_mass[1] * dv.dot(t2),
            ];
            let max = c.friction * p.normal_impulse;
            let len2 = new[0] * new[0] + new[1] * new[1];
            if len2 > max * max {
                let scale = max / len2.sqrt();
                new = [new[0] * scale, new[1] * scale];
            }
            p.tangent_impulse = new;
            let impulse = (new[0] - old[0]) * t1 + (new[1] - old[1]) * t2;
            ba.v -= ba.inv_mass * impulse;
            ba.w -= ba.inv_inertia * p.r_a.cross(impulse);
            bb.v += bb.inv_mass * impulse;
            bb.w += bb.inv_inertia * p.r_b.cross(impulse);
        }
        bodies[ia] = ba;
        bodies[ib] = bb;
    }
}

/// The shock-propagation pass (see the module docs): constraints are in level order; each normal row
/// pushes only the upper body, only if it still approaches faster than the bias allows. Its impulses
/// are not accumulated (they are a projection, not part of the warm-started solution).
pub(crate) fn shock_pass(
    constraints: &[ContactConstraint],
    bodies: &mut [SolverBody],
    params: &PassParams,
) {
    for c in constraints {
        let (ia, ib) = (c.a as usize, c.b as usize);
        let mut ba = bodies[ia];
        let mut bb = bodies[ib];
        let n = c.normal;
        let d_p = n.dot(bb.dp - ba.dp);
        // Translation only, for the manifold as a whole: the average approach of its points (beyond what
        // the bias allows) is removed by moving the upper body (both, by mass, at equal levels) along n.
        // Per-point angular pushes would tilt bodies one corner at a time and make stacks walk; the
        // tilt is left to the regular rows.
        let mut need = 0.0;
        let (mut r_a, mut r_b) = (Vec3::ZERO, Vec3::ZERO);
        for p in &c.points[..c.len] {
            r_a += p.r_a;
            r_b += p.r_b;
            let s = current_separation(p, d_p, &ba, &bb);
            let bias = if s > 0.0 {
                s * params.inv_h
            } else {
                (c.softness.bias_rate * (s + params.linear_slop).min(0.0)).max(-params.max_push_out)
            };
            let vn = n.dot(bb.v - ba.v) + bb.w.dot(p.rn_b) - ba.w.dot(p.rn_a);
            need -= vn + bias;
        }
        need /= c.len as f32;
        if need <= 0.0 {
            continue;
        }
        // Friction for the push itself. A push along a slightly tilted normal would make the upper body
        // slide, and a leaning stack would push itself over, so the push comes with a friction impulse
        // that cancels the tangential part of the *linear* relative velocity, with a budget of μ times the
        // push, and never more than the slip at the manifold's centroid (so a rolling ball, whose contact
        // point does not slip, is left alone). Linear only: an angular response here would feed the
        // lower body's jitter into the upper one.
        let inv_len = 1.0 / c.len as f32;
        let (r_a, r_b) = (r_a * inv_len, r_b * inv_len);
        let normal_impulse = need * c.shock_mass;
        ba.v -= (c.shock_scale_a * ba.inv_mass * normal_impulse) * n;
        bb.v += (c.shock_scale_b * bb.inv_mass * normal_impulse) * n;
        let dv_linear = bb.v - ba.v;
        let dv_point = dv_linear + bb.w.cross(r_b) - ba.w.cross(r_a);
        let slip_linear = dv_linear - n.dot(dv_linear) * n;
        let slip_point = (dv_point - n.dot(dv_point) * n).length();
        let wanted = slip_linear.length();
        if wanted > 1e-9 {
            let magnitude =
                (c.shock_mass * wanted.min(slip_point)).min(c.friction * normal_impulse);
            let impulse = -(magnitude / wanted) * slip_linear;
            ba.v -= (c.shock_scale_a * ba.inv_mass) * impulse;
            bb.v += (c.shock_scale_b * bb.inv_mass) * impulse;
        }
        bodies[ia] = ba;
        bodies[ib] = bb;
    }
}

/// Restitution, once per step after the sub-steps: points that approached faster than `threshold`
/// (m/s) before the solve and pushed during it leave at e times that speed.
pub(crate) fn apply_restitution(
    constraints: &mut [ContactConstraint],
    bodies: &mut [SolverBody],
    threshold: f32,
) {
    for c in constraints {
        if c.restitution == 0.0 {
            continue;
        }
        let (ia, ib) = (c.a as usize, c.b as usize);
        let mut ba = bodies[ia];
        let mut bb = bodies[ib];
        let n = c.normal;
        for p in &mut c.points[..c.len] {
            if p.relative_velocity > -threshold || p.max_normal_impulse == 0.0 {
                continue;
            }
            let vn = n.dot(bb.v - ba.v) + bb.w.dot(p.rn_b) - ba.w.dot(p.rn_a);
            let delta = -p.normal_mass * (vn + c.restitution * p.relative_velocity);
            let total = (p.normal_impulse + delta).max(0.0);
            let delta = total - p.normal_impulse;
            p.normal_impulse = total;
            ba.v -= (ba.inv_mass * delta) * n;
            ba.w -= delta * p.irn_a;
            bb.v += (bb.inv_mass * delta) * n;
            bb.w += delta * p.irn_b;
        }
        bodies[ia] = ba;
        bodies[ib] = bb;
    }
}

/// Copies the accumulated impulses back to the persistent contacts and returns the deepest penetration
/// at the end of the step, m (≥ 0).
pub(crate) fn store_impulses(
    constraints: &[ContactConstraint],
    bodies: &[SolverBody],
    contacts: &mut [Contact],
) -> f32 {
    let mut deepest = 0.0f32;
    for c in constraints {
        let ba = &bodies[c.a as usize];
        let bb = &bodies[c.b as usize];
        let d_p = c.normal.dot(bb.dp - ba.dp);
        let contact = &mut contacts[c.contact as usize];
        for (i, p) in c.points[..c.len].iter().enumerate() {
            contact.impulses[i] = CachedImpulse {
                normal: p.normal_impulse,
                tangent: p.tangent_impulse[0] * c.tangents[0]
                    + p.tangent_impulse[1] * c.tangents[1],
            };
            deepest = deepest.max(-current_separation(p, d_p, ba, bb));
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_basis_is_orthonormal_for_every_octant() {
        for n in [
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
            Vec3::new(1.0, -2.0, 0.5).normalize(),
            Vec3::new(-0.3, 0.1, -0.9).normalize(),
        ] {
            let [t1, t2] = tangent_basis(n);
            assert!((t1.length() - 1.0).abs() < 1e-5 && (t2.length() - 1.0).abs() < 1e-5);
            assert!(t1.dot(n).abs() < 1e-5 && t2.dot(n).abs() < 1e-5 && t1.dot(t2).abs() < 1e-5);
        }
    }
}
