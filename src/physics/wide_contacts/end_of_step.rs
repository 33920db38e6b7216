//! Once per step, after the sub-steps: restitution, and storing the impulses for next step's warm start.

use glam::Vec4;

use super::body_lanes::{gather, scatter};
use super::{ColdLanes, ManifoldLanes, SideLanes};
use crate::physics::contact::Contact;
use crate::physics::solver_body::SolverBody;

/// Restitution of one group: the scalar rule of `WideContacts::apply_restitution` in lanes, point by
/// point.
pub(super) fn restitution<const P: usize, const M: usize>(
    g: &mut ManifoldLanes<P, M>,
    a: &SideLanes<P>,
    cold: &ColdLanes<P>,
    bodies: &mut [SolverBody],
    threshold: f32,
) {
    let zero = Vec4::ZERO;
    if !cold.restitution.cmpgt(zero).any() {
        return;
    }
    let mut sa = gather::<false>(bodies, &a.a);
    let mut sb = gather::<false>(bodies, &g.b);
    let n = g.normal;
    for (i, (p, row)) in g.impulses.iter_mut().zip(&g.points).enumerate() {
        let relative_velocity = cold.relative_velocity[i];
        let bounces = relative_velocity.cmple(Vec4::splat(-threshold))
            & cold.max_normal_impulse[i].cmpne(zero)
            & cold.restitution.cmpgt(zero);
        if !bounces.any() {
            continue;
        }
        let vn = n.dot(sb.v - sa.v) + (sb.w.dot(row.rn_b) - sa.w.dot(a.rn_a[i]));
        let delta = -row.normal_mass * (vn + cold.restitution * relative_velocity);
        let total = Vec4::select(
            bounces,
            (p.normal_impulse + delta).max(zero),
            p.normal_impulse,
        );
        let delta = total - p.normal_impulse;
        p.normal_impulse = total;
        sa.v -= n * (a.inv_mass_a * delta);
        sa.w -= a.irn_a[i] * delta;
        sb.v += n * (g.inv_mass_b * delta);
        sb.w += p.irn_b * delta;
    }
    scatter(bodies, &a.a, &sa);
    scatter(bodies, &g.b, &sb);
}

/// Stores the impulses of `groups` (their parts, index by index) in their contacts; returns the deepest
/// penetration per lane, m.
pub(super) fn store<const P: usize, const M: usize>(
    groups: &[ManifoldLanes<P, M>],
    sides_a: &[SideLanes<P>],
    colds: &[ColdLanes<P>],
    bodies: &[SolverBody],
    contacts: &mut [Contact],
) -> Vec4 {
    let mut deepest = Vec4::ZERO;
    for ((g, a), cold) in groups.iter().zip(sides_a).zip(colds) {
        let sa = gather::<true>(bodies, &a.a);
        let sb = gather::<true>(bodies, &g.b);
        let d_p = g.normal.dot(sb.dp - sa.dp);
        for (i, p) in g.points.iter().enumerate() {
            let s = p.separation + d_p + (sb.dtheta.dot(p.rn_b) - sa.dtheta.dot(a.rn_a[i]));
            let real = p.mean_weight.cmpgt(Vec4::ZERO);
            deepest = deepest.max(Vec4::select(real, -s, Vec4::ZERO));
        }
        for (k, &contact) in cold.contact.iter().enumerate() {
            if contact == u32::MAX {
                continue;
            }
            let cached = &mut contacts[contact as usize].impulses;
            let (l1, l2) = (g.tangent_impulse[0][k], g.tangent_impulse[1][k]);
            cached.tangent = (l1 * g.tangents[0].lane(k) + l2 * g.tangents[1].lane(k)).into();
            cached.twist = g.twist_impulse[k];
            for (i, p) in g.impulses.iter().enumerate().take(cold.count[k] as usize) {
                cached.normal[i] = p.normal_impulse[k];
            }
        }
    }
    deepest
}
