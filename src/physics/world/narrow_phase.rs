//! Stage 2, collide: the narrow phase run over the step's pairs, merged with last step's contacts so
//! that resting manifolds are kept and new points inherit their warm-start impulses.

use super::World;
use crate::physics::coincident::{across_gravity, collision_pose_b};
use crate::physics::collide::collide;
use crate::physics::contact::{Contact, mix_friction, mix_restitution, rolling_limit};
use crate::physics::fast_bodies::gravity_reach;
use crate::physics::{Body, Settings};

impl World {
    /// Step 2: merges the sorted pairs with last step's sorted contacts; runs the narrow phase on pairs
    /// with an awake body; keeps contacts of pairs where neither body is awake (sleeping islands keep
    /// their impulses for when they wake). Kept out of line (called once per step) so profiles show its
    /// cost apart from `step`'s.
    #[inline(never)]
    pub(super) fn update_contacts(&mut self, dt: f32) {
        /// Appends `old[i]` by growing the run of old contacts waiting to be copied, or by flushing that
        /// run and starting a new one at `i`: a resting pile copies its contacts in a few large blocks, not
        /// one `Contact` (over 200 bytes) at a time through a stack temporary.
        fn keep(
            run: &mut std::ops::Range<usize>,
            out: &mut Vec<Contact>,
            old: &[Contact],
            i: usize,
        ) {
            if run.end != i {
                out.extend_from_slice(&old[run.clone()]);
                *run = i..i;
            }
            run.end = i + 1;
        }
        let settings = &self.settings;
        let reuse_tolerance = self.settings.manifold_reuse_distance;
        let up = (-self.settings.gravity).normalize_or_zero();
        let bodies = &self.bodies;
        let s = &mut self.scratch;
        let old = &self.contacts;
        let out = &mut s.contacts;
        out.clear();
        let inactive = |c: &Contact| {
            !bodies[c.a as usize].is_awake_dynamic() && !bodies[c.b as usize].is_awake_dynamic()
        };
        let mut run = 0..0;
        let mut k = 0;
        for &(a, b) in &s.pairs {
            while k < old.len() && (old[k].a, old[k].b) < (a, b) {
                if inactive(&old[k]) {
                    keep(&mut run, out, old, k);
                }
                k += 1;
            }
            let previous = if k < old.len() && (old[k].a, old[k].b) == (a, b) {
                k += 1;
                Some(k - 1)
            } else {
                None
            };
            let (ba, bb) = (&bodies[a as usize], &bodies[b as usize]);
            if !ba.is_awake_dynamic() && !bb.is_awake_dynamic() {
                if let Some(i) = previous {
                    keep(&mut run, out, old, i);
                }
                continue;
            }
            if let Some(i) = previous
                && old[i].still_valid(&ba.pose, &bb.pose, &ba.shape, &bb.shape, reuse_tolerance)
            {
                keep(&mut run, out, old, i);
                continue;
            }
            let margin = contact_margin(ba, bb, dt, settings);
            let (body_a, body_b) = ((a, &ba.shape, &ba.pose), (b, &bb.shape, &bb.pose));
            let mixed = if ba.is_static() || bb.is_static() {
                None
            } else {
                across_gravity(body_a, body_b, up)
            };
            let manifold = mixed.unwrap_or_else(|| {
                collide(
                    &ba.shape,
                    &ba.pose,
                    &bb.shape,
                    &collision_pose_b(body_a, body_b, up),
                    margin,
                )
            });
            if manifold.is_empty() {
                continue;
            }
            out.extend_from_slice(&old[run.clone()]);
            run = 0..0;
            let mut contact = Contact {
                a,
                b,
                manifold,
                impulses: Default::default(),
                friction: mix_friction(ba.friction, bb.friction),
                restitution: mix_restitution(ba.restitution, bb.restitution),
                rolling_resistance: rolling_limit(
                    &ba.shape,
                    ba.rolling_resistance,
                    &bb.shape,
                    bb.rolling_resistance,
                ),
                pose_a: ba.pose,
                pose_b: bb.pose,
            };
            if let Some(i) = previous {
                contact.inherit_impulses(&old[i]);
            }
            out.push(contact);
        }
        for i in k.min(old.len())..old.len() {
            if inactive(&old[i]) {
                keep(&mut run, out, old, i);
            }
        }
        out.extend_from_slice(&old[run]);
        std::mem::swap(&mut self.contacts, &mut s.contacts);
    }
}

/// How far apart two bodies' surfaces may be and still get (speculative) contact points this step:
/// `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance`, m.
///
/// A moving body against a static or sleeping one gets gravity's reach too (see `fast_bodies`).
pub(super) fn contact_margin(ba: &Body, bb: &Body, dt: f32, settings: &Settings) -> f32 {
    let v_rel = (bb.linear_velocity - ba.linear_velocity).length();
    let spin = ba.angular_velocity.length() * ba.shape.bounding_radius()
        + bb.angular_velocity.length() * bb.shape.bounding_radius();
    let spec = settings.speculative_distance;
    let falls_onto = ba.is_awake_dynamic() != bb.is_awake_dynamic();
    let reach = if falls_onto {
        gravity_reach(settings.gravity, dt, spec)
    } else {
        0.0
    };
    (v_rel + spin) * dt + spec + reach
}
