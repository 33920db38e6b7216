//! Stage 2, collide: the narrow phase run over the step's pairs, merged with last step's contacts so
//! that resting manifolds are kept and new points inherit their warm-start impulses.

pub(crate) mod coincident;
pub mod collide;
pub(crate) mod contact;
pub mod manifold;

use glam::Vec3;

use crate::physics::fast_bodies::gravity_reach;
use crate::physics::narrow::coincident::{across_gravity, collision_pose_b};
use crate::physics::narrow::collide::{Motion, at_impact, collide};
use crate::physics::narrow::contact::{
    Computed, Contact, mix_friction, mix_restitution, rolling_limit,
};
use crate::physics::solve::push_out::soft_depth;
use crate::physics::world::World;
use crate::physics::{Body, Settings};

impl World {
    /// Step 2: merges the sorted pairs with last step's sorted contacts; runs the narrow phase on pairs
    /// with an awake body; keeps contacts of pairs where neither body is awake (sleeping islands keep
    /// their impulses for when they wake). Kept out of line (called once per step) so profiles show its
    /// cost apart from `step`'s.
    ///
    /// When the pairs are exactly last step's contacts' (a pile at rest or settling: no pair came or
    /// went), the contacts are updated where they are instead: the merge would copy every contact
    /// (over 200 bytes each) into a new list only to end with the same list. Both ways visit the
    /// pairs in the same order and compute the same contacts.
    #[inline(never)]
    pub(in crate::physics) fn update_contacts(&mut self, dt: f32) {
        let pairs = &self.scratch.pair_finder.pairs;
        let same_pairs = pairs.len() == self.contacts.len()
            && pairs
                .iter()
                .zip(&self.contacts)
                .all(|(&pair, c)| pair == (c.a, c.b));
        if same_pairs {
            self.update_contacts_in_place(dt);
        } else {
            self.merge_contacts(dt);
        }
    }

    /// [`Self::update_contacts`] when the pairs are the contacts' own: each contact is kept, replaced
    /// by a fresh one, or (no manifold left) dropped, in place.
    fn update_contacts_in_place(&mut self, dt: f32) {
        let step = PairStep::new(&self.settings, dt);
        let bodies = &self.bodies;
        let mut dropped = false;
        for contact in &mut self.contacts {
            let (ba, bb) = (&bodies[contact.a as usize], &bodies[contact.b as usize]);
            if !ba.is_awake_dynamic() && !bb.is_awake_dynamic() {
                continue;
            }
            if step.reuse(contact, ba, bb) {
                continue;
            }
            match step.collide(bodies, contact.a, contact.b, Some(contact)) {
                Some(fresh) => *contact = fresh,
                None => {
                    // Stored contacts always have points: an empty manifold marks this one dropped.
                    contact.manifold.len = 0;
                    dropped = true;
                }
            }
        }
        if dropped {
            self.contacts.retain(|c| !c.manifold.is_empty());
        }
    }

    /// [`Self::update_contacts`] in general: the sorted pairs merged with last step's sorted contacts
    /// into a new list.
    fn merge_contacts(&mut self, dt: f32) {
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
        let step = PairStep::new(&self.settings, dt);
        let bodies = &self.bodies;
        let s = &mut self.scratch;
        let old = &mut self.contacts;
        let out = &mut s.merged;
        out.clear();
        let inactive = |c: &Contact| {
            !bodies[c.a as usize].is_awake_dynamic() && !bodies[c.b as usize].is_awake_dynamic()
        };
        let mut run = 0..0;
        let mut k = 0;
        for &(a, b) in &s.pair_finder.pairs {
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
                && step.reuse(&mut old[i], ba, bb)
            {
                keep(&mut run, out, old, i);
                continue;
            }
            let Some(contact) = step.collide(bodies, a, b, previous.map(|i| &old[i])) else {
                continue;
            };
            out.extend_from_slice(&old[run.clone()]);
            run = 0..0;
            out.push(contact);
        }
        for i in k.min(old.len())..old.len() {
            if inactive(&old[i]) {
                keep(&mut run, out, old, i);
            }
        }
        out.extend_from_slice(&old[run]);
        std::mem::swap(&mut self.contacts, &mut s.merged);
    }
}

/// What colliding a pair needs of the step.
struct PairStep<'a> {
    settings: &'a Settings,
    dt: f32,
    /// Unit vector against gravity (zero without gravity).
    up: Vec3,
    reuse_tolerance: f32,
}

impl<'a> PairStep<'a> {
    fn new(settings: &'a Settings, dt: f32) -> Self {
        Self {
            settings,
            dt,
            up: (-settings.gravity).normalize_or_zero(),
            reuse_tolerance: settings.manifold_reuse_distance,
        }
    }

    /// Whether `contact`, last step's, still holds for bodies `a` and `b` as they are now, and if
    /// so brings it to where they are (see [`Contact::follow`]).
    ///
    /// Not a face contact between dynamic bodies whose masses differ by the mass-ratio threshold
    /// or more: its manifold is computed afresh every step. A reused manifold follows the bodies
    /// only to first order, and a light box under a heavy one amplifies that error by their
    /// ratio: at 3000:1 and 8 sub-steps, 2 of 12 copies whose masses differ by parts in a
    /// thousand rocked after seconds of calm, the light box's rocking and both its patches'
    /// friction growing 2.5 to 6 times a step until the pair flew apart (6 of 12 at 6 sweeps);
    /// recomputed, none does, and heavy on light sinks half as far or less at every sub-step count
    /// (`nudge bench corpus`, heavy on light; `tests/physics/corpus.rs`). A ball's one point is
    /// kept: a box on four small balls walked off them when its contacts with them were
    /// recomputed every step.
    fn reuse(&self, contact: &mut Contact, a: &Body, b: &Body) -> bool {
        let mass_ratio =
            !a.is_static && !b.is_static && self.settings.is_mass_ratio(a.inv_mass, b.inv_mass);
        !(mass_ratio && contact.manifold.len > 1)
            && contact.follow(&a.pose, &b.pose, &a.shape, &b.shape, self.reuse_tolerance)
    }

    /// A fresh contact between bodies `a < b` (at least one awake), inheriting the impulses of
    /// `previous` (the pair's contact of last step, if any); `None` when they are farther apart than
    /// their contact margin.
    fn collide(
        &self,
        bodies: &[Body],
        a: u32,
        b: u32,
        previous: Option<&Contact>,
    ) -> Option<Contact> {
        let (ba, bb) = (&bodies[a as usize], &bodies[b as usize]);
        let (settings, dt, up) = (self.settings, self.dt, self.up);
        let margin = contact_margin(ba, bb, dt, settings);
        if out_of_reach(ba, bb, margin) {
            return None;
        }
        let (body_a, body_b) = ((a, &ba.shape, &ba.pose), (b, &bb.shape, &bb.pose));
        let mixed = if ba.is_static() || bb.is_static() {
            None
        } else {
            across_gravity(body_a, body_b, up)
        };
        let manifold = mixed.unwrap_or_else(|| {
            let pose_b = collision_pose_b(body_a, body_b, up);
            let manifold = collide(&ba.shape, &ba.pose, &bb.shape, &pose_b, margin);
            // A speculative point of approaching bodies is taken at the moment they meet.
            at_impact(
                (&ba.shape, &ba.pose, motion(ba)),
                (&bb.shape, &pose_b, motion(bb)),
                dt,
                manifold,
            )
        });
        if manifold.is_empty() {
            return None;
        }
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
            soft_depth: soft_depth(&ba.shape, &bb.shape, settings.thin_soft_range),
            computed: Computed::of(&manifold),
            pose_a: ba.pose,
            pose_b: bb.pose,
            statics: None,
        };
        if let Some(old) = previous {
            contact.inherit_impulses(old);
        }
        Some(contact)
    }
}

/// Whether bodies `a` and `b` are farther apart than `margin` along the line through their centres:
/// the gap between their extents on that line (their bounding spheres' first, the cheaper test) is
/// a lower bound on the distance between them, so such a pair has no contact this step. Most pairs
/// the broad phase hands over in a rain are such misses (their boxes' bounds overlap, the boxes do
/// not: three in four of rain(4000)'s five thousand a step), and this settles them without building
/// the pair's frames for the separating-axis test or sweeping it for an impact.
fn out_of_reach(a: &Body, b: &Body, margin: f32) -> bool {
    let offset = b.pose.position - a.pose.position;
    let distance = offset.length();
    if distance - a.shape.bounding_radius() - b.shape.bounding_radius() > margin {
        return true;
    }
    // A body reaches at least half its thickness along any line: nearer than that, and the pair
    // touches or nearly does (every resting contact), the extents cannot leave a gap.
    if !distance.is_normal()
        || distance <= margin + a.shape.half_thickness() + b.shape.half_thickness()
    {
        return false;
    }
    let axis = offset / distance;
    distance - a.shape.reach(a.pose.rotation, axis) - b.shape.reach(b.pose.rotation, axis) > margin
}

/// A body's velocities as the narrow phase sweeps them over the step.
fn motion(body: &Body) -> Motion {
    Motion {
        linear: body.linear_velocity,
        angular: body.angular_velocity,
    }
}

/// How far apart two bodies' surfaces may be and still get (speculative) contact points this step:
/// `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance`, m.
///
/// A moving body against a static or sleeping one gets gravity's reach too (see `fast_bodies`).
pub(in crate::physics) fn contact_margin(
    ba: &Body,
    bb: &Body,
    dt: f32,
    settings: &Settings,
) -> f32 {
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

#[cfg(test)]
mod tests {
    use glam::{Quat, Vec3};

    use super::out_of_reach;
    use crate::geometry::{Pose, Shape};
    use crate::physics::narrow::collide::collide;
    use crate::physics::{Body, BodyDesc};

    fn unit_box(position: Vec3, rotation: Quat) -> Body {
        let pose = Pose { position, rotation };
        Body::from_desc(&BodyDesc::dynamic(
            Shape::cuboid(Vec3::splat(0.5)),
            pose,
            1.0,
        ))
    }

    #[test]
    fn boxes_whose_bounds_overlap_but_whose_extents_on_the_centre_line_do_not_are_out_of_reach() {
        // Two unit boxes turned 45° about z, corner towards corner along the diagonal: their
        // bounding boxes overlap, their bounding spheres overlap, the boxes are 0.1 m apart.
        let turn = Quat::from_rotation_z(std::f32::consts::FRAC_PI_4);
        let reach = 0.5 * std::f32::consts::SQRT_2;
        let a = unit_box(Vec3::ZERO, turn);
        let b = unit_box(Vec3::new(2.0 * reach + 0.1, 0.0, 0.0), turn);
        let margin = 0.02;
        assert!(out_of_reach(&a, &b, margin));
        assert!(collide(&a.shape, &a.pose, &b.shape, &b.pose, margin).is_empty());
        // Within the margin they are not out of reach, and they do collide.
        let near = unit_box(Vec3::new(2.0 * reach + 0.01, 0.0, 0.0), turn);
        assert!(!out_of_reach(&a, &near, margin));
        assert!(!collide(&a.shape, &a.pose, &near.shape, &near.pose, margin).is_empty());
        // Coincident centres are never out of reach.
        assert!(!out_of_reach(&a, &a, margin));
    }
}
