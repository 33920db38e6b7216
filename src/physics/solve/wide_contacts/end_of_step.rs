//! Once per step, after the sub-steps and restitution (`impacts`): storing the impulses for next step's
//! warm start.

use glam::Vec4;

use crate::physics::narrow::contact::Contact;
use crate::physics::solve::wide_contacts::{ColdLanes, ManifoldLanes};

/// Stores the impulses of `groups` (their parts, index by index) in their contacts; returns the deepest
/// penetration per lane, m.
pub(super) fn store<const P: usize, const M: usize>(
    groups: &[ManifoldLanes<P, M>],
    colds: &[ColdLanes<P>],
    contacts: &mut [Contact],
) -> Vec4 {
    let mut deepest = Vec4::ZERO;
    for (g, cold) in groups.iter().zip(colds) {
        // The last relax pass left the separations at the final positions.
        for p in &g.points {
            let real = p.mean_weight.cmpgt(Vec4::ZERO);
            deepest = deepest.max(Vec4::select(real, -p.separation_now, Vec4::ZERO));
        }
        for (k, &contact) in cold.contact.iter().enumerate() {
            if contact == u32::MAX {
                continue;
            }
            let cached = &mut contacts[contact as usize].impulses;
            let (l1, l2) = (g.tangent_impulse[0][k], g.tangent_impulse[1][k]);
            cached.tangent = (l1 * g.tangents[0].lane(k) + l2 * g.tangents[1].lane(k)).into();
            cached.twist = g.twist_impulse[k];
            cached.anchor = (g.anchor_now[0][k] * g.tangents[0].lane(k)
                + g.anchor_now[1][k] * g.tangents[1].lane(k))
            .into();
            cached.twist_anchor = g.twist_anchor_now[k];
            for (i, p) in g.impulses.iter().enumerate().take(cold.count[k] as usize) {
                cached.normal[i] = p.normal_impulse[k];
            }
        }
    }
    deepest
}
