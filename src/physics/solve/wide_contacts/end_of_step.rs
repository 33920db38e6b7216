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
        // The friction impulse and the anchor's offset as world vectors, four lanes at a time (each
        // lane's products and sum as they were one lane at a time).
        let [t1, t2] = g.tangents;
        let tangent = (t1 * g.tangent_impulse[0] + t2 * g.tangent_impulse[1]).lanes();
        let anchor = (t1 * g.anchor_now[0] + t2 * g.anchor_now[1]).lanes();
        for (k, &contact) in cold.contact.iter().enumerate() {
            if contact == u32::MAX {
                continue;
            }
            let cached = &mut contacts[contact as usize].impulses;
            cached.tangent = tangent[k].into();
            cached.twist = g.twist_impulse[k];
            cached.anchor = anchor[k].into();
            cached.twist_anchor = g.twist_anchor_now[k];
            // The manifold's points, the first `count` (compared as a float: its conversion to an
            // integer, saturating, took as many instructions as the copies).
            for (i, p) in g.impulses.iter().enumerate() {
                if i as f32 >= cold.count[k] {
                    break;
                }
                cached.normal[i] = p.normal_impulse[k];
            }
        }
    }
    deepest
}
