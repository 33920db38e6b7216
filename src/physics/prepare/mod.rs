//! Stage 3, prepare: the solver bodies, the contact graph's order (layers and colours, kept while the
//! graph is unchanged), the constraints, packed into SIMD lane groups in solve order, and the deep
//! overlaps the sub-steps push out in position space (`push_out`).

pub(crate) mod constraint_order;
pub(crate) mod preload;

use glam::Vec3A;

use crate::physics::body::inv_inertia_world;
use crate::physics::joint::stiffness::{
    ArticulationLoads, floored, inertia_floor, stiffness_of_ends,
};
use crate::physics::prepare::constraint_order::{NOT_IN_GRAPH, SERIAL_COLOR};
use crate::physics::settings::Settings;
use crate::physics::world::World;

use crate::physics::solve::contact_solver::ANCHOR_MAX_STEP_FRACTION;
use crate::physics::solve::softness::{ContactSoftness, Softness, capped_hertz};
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::solve::wide_contacts::{LaneSource, kind_of};

/// What the lanes need to know of one contact, read in the order the contacts are stored.
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::physics) struct ContactFacts {
    /// Its friction may be anchored as far as the contact tells (two points or more, none too
    /// deep, no jointed body; see `contact_solver`, "Friction anchors").
    pub(in crate::physics) anchorable: bool,
    /// Neither body is held by a joint (see `contact_solver`, "The symmetric relax").
    pub(in crate::physics) unjointed: bool,
    /// A point is deeper than the soft range: the position pass pushes the pair apart (`push_out`).
    pub(in crate::physics) deep: bool,
    /// Its point count.
    pub(in crate::physics) len: u8,
}

/// The awake dynamic bodies as the solver sees them, index 0 being the static dummy: velocities and
/// position deltas (`bodies`, what the passes change), masses and forces (`motions`), and each world
/// body's solver index (`index`, 0 for one not in the solver).
#[derive(Debug, Default)]
pub(in crate::physics) struct SolverArrays {
    pub(in crate::physics) index: Vec<u32>,
    pub(in crate::physics) bodies: Vec<SolverBody>,
    pub(in crate::physics) motions: Vec<SolverMotion>,
    /// Per body (filled only while joints pull on some): the stiffness of the joint ends on it,
    /// `[sum, stiffest]`, kg·m², from which its inertia floor is made (`joint::stiffness`).
    pub(in crate::physics) joint_ends: Vec<[f32; 2]>,
    /// The articulations' loads the floors take (`joint::stiffness`).
    pub(in crate::physics) articulation_loads: ArticulationLoads,
}

/// The springs of a contact between two dynamic bodies and of one with a static side, over the
/// sub-step `h`: the contact's frequency ([`capped_hertz`]), twice that against a static body (as
/// Box2D v3 has it), and the friction anchors between dynamic bodies at most an eighth of the
/// sub-step rate, over the square root of the iterations (`contact_solver`, "How fast an anchor
/// may be").
pub(in crate::physics) fn contact_springs(
    settings: &Settings,
    h: f32,
) -> (ContactSoftness, ContactSoftness) {
    let hertz = capped_hertz(settings.contact_hertz, h);
    let zeta = settings.contact_damping_ratio;
    let anchor_hertz = if settings.anchor_frequency_cap {
        let iterations = settings.iteration_count() as f32;
        hertz.min(ANCHOR_MAX_STEP_FRACTION / (h * iterations.sqrt()))
    } else {
        hertz
    };
    let between_bodies = ContactSoftness {
        normal: Softness::new(hertz, zeta, h),
        anchor: Softness::new(anchor_hertz, zeta, h),
    };
    let with_static = ContactSoftness::uniform(Softness::new(2.0 * hertz, zeta, h));
    (between_bodies, with_static)
}

/// Whether a joint holds world body `body`, by the per-body flags `jointed` (empty while the world
/// has no joints).
pub(in crate::physics) fn held_by_joint(jointed: &[bool], body: u32) -> bool {
    jointed.get(body as usize).copied().unwrap_or(false)
}

impl World {
    /// How many of the last step's contacts had their statics found afresh; the others kept what
    /// was found for them while their island stayed still (`Settings::statics_reuse`,
    /// `prepare::preload::reuse`). A read-only view for tests and benchmarks.
    pub fn statics_found(&self) -> usize {
        self.scratch.statics.found_count()
    }

    /// Copies awake dynamic bodies into the solver arrays (index 0 = static dummy). Kept out of line
    /// (once per step) so profiles show its cost.
    #[inline(never)]
    pub(in crate::physics) fn build_solver_bodies(&mut self) {
        let s = &mut self.scratch;
        let gravity = Vec3A::from(self.settings.gravity);
        stiffness_of_ends(
            (&mut s.solver.joint_ends, &mut s.solver.articulation_loads),
            &self.joints,
            &self.bodies,
            &self.settings,
        );
        let joint_ends = &s.solver.joint_ends;
        let (solver_bodies, motions) = (&mut s.solver.bodies, &mut s.solver.motions);
        solver_bodies.clear();
        motions.clear();
        // At most every body plus the dummy: the pushes below never reallocate.
        solver_bodies.reserve(self.bodies.len() + 1);
        motions.reserve(self.bodies.len() + 1);
        solver_bodies.push(SolverBody::DUMMY);
        motions.push(SolverMotion::DUMMY);
        s.solver.index.clear();
        s.solver
            .index
            .extend(self.bodies.iter().enumerate().map(|(i, body)| {
                if !body.is_awake_dynamic() {
                    return 0;
                }
                let index = solver_bodies.len() as u32;
                let inertia_floor = joint_ends.get(i).copied().map_or(0.0, inertia_floor);
                // Its own inertia turns it under an applied torque; the rows weigh it with its
                // joints' floor (`joint::stiffness`).
                let own_inv_inertia = body.inv_inertia_world_simd();
                let inv_inertia = if inertia_floor > body.inertia_local.min_element() {
                    let moments = floored(body.inertia_local, inertia_floor);
                    inv_inertia_world(body.pose.rotation, moments.recip())
                } else {
                    own_inv_inertia
                };
                solver_bodies.push(SolverBody {
                    v: body.linear_velocity.into(),
                    w: body.angular_velocity.into(),
                    dp: Vec3A::ZERO,
                    dtheta: Vec3A::ZERO,
                });
                motions.push(SolverMotion {
                    rotation: body.pose.rotation,
                    linear_accel: gravity + body.inv_mass * Vec3A::from(body.force),
                    angular_accel: own_inv_inertia * Vec3A::from(body.torque),
                    inertia_local: body.inertia_local,
                    gyroscopic: body.inertia_local.min_element()
                        != body.inertia_local.max_element(),
                    inv_inertia,
                    body: i as u32,
                    inv_mass: body.inv_mass,
                    inertia_floor,
                });
                index
            }));
    }

    /// Step 3: layers the contact graph by BFS from static bodies and builds the constraints in layer
    /// order.
    pub(in crate::physics) fn prepare_constraints(&mut self, dt: f32) {
        let h = dt / self.settings.substep_count() as f32;
        let (contact_softness, static_softness) = contact_springs(&self.settings, h);
        let s = &mut self.scratch;
        let n = s.solver.bodies.len();

        let index = &s.solver.index;
        let keys = self.contacts.iter().map(|c| {
            (
                index[c.a as usize],
                index[c.b as usize],
                kind_of(c.manifold.len),
            )
        });
        // The constraints' bodies in solve order come with it, before anything is prepared: the
        // mass-ratio marks and the shock pass's list depend on them alone.
        s.graph.update(keys, n);
        self.active_contacts = s.graph.links.len();

        s.mass_ratio.weigh_articulations(
            &self.joints,
            s.graph.links.len(),
            &s.solver.index,
            &s.solver.motions,
        );
        s.mass_ratio.select(
            &s.graph,
            &s.solver.index,
            &s.solver.motions,
            &self.contacts,
            &self.settings,
        );
        // The bodies joints hold: the statics leave their supports out, and whatever the anchors,
        // the symmetric relax and the layer order leave them out too.
        s.jointed.clear();
        if !self.joints.is_empty() {
            s.jointed.resize(self.bodies.len(), false);
            for joint in &self.joints {
                if let Some(a) = joint.desc.a {
                    s.jointed[a.index()] = true;
                }
                s.jointed[joint.desc.b.index()] = true;
            }
        }
        s.compute_preloads(
            (&self.contacts, &self.bodies, &self.statics_seen),
            &self.holds,
            &self.settings,
            h,
        );
        let reuse = self.settings.statics_reuse && self.settings.preload;
        if reuse {
            s.statics
                .record_seen(&s.solver.motions, &self.bodies, &mut self.statics_seen);
        }

        s.wide.clear(SERIAL_COLOR);
        let anchors = self.settings.friction_anchors && self.settings.preload;
        let jointed = |body: u32| held_by_joint(&s.jointed, body);
        // What the lanes need of the contacts themselves, read in the order they are stored (in
        // solve order each is a cache miss in a large pile), and the friction the statics asked
        // of each, kept for the next step's comparison.
        s.contact_facts.clear();
        s.contact_facts
            .resize(s.graph.links.len(), ContactFacts::default());
        let mut any_rolling = false;
        for (c, &i) in self.contacts.iter_mut().zip(&s.graph.constraint_of) {
            if i == NOT_IN_GRAPH {
                continue;
            }
            any_rolling |= c.rolling_resistance > 0.0;
            let i = i as usize;
            if reuse && let Some(kept) = s.statics.to_keep(i, s.graph.links[i]) {
                c.statics = Some(kept);
            }
            c.impulses.fed_tangent = s.statics.tangent_demand[i];
            c.impulses.fed_load = s.statics.fed_load[i];
            c.impulses.fed_offset = s.statics.fed_offset[i];
            let unjointed = !jointed(c.a) && !jointed(c.b);
            let deep_limit = c.deep_limit(self.settings.linear_slop);
            let deep = c
                .manifold
                .points()
                .iter()
                .any(|p| p.separation <= deep_limit);
            s.contact_facts[i] = ContactFacts {
                // Deeper than its soft range the position pass pushes the pair apart
                // (`push_out`): an anchor there would hold them together.
                anchorable: anchors && c.manifold.len > 1 && unjointed && !deep,
                unjointed,
                deep,
                len: c.manifold.len as u8,
            };
        }
        // Per solver body, its contacts: the rolling rows' held mass is a lone contact's
        // (`wide_contacts::rolling`). Without rolling resistance there are no rolling rows, and
        // nothing to count.
        let held_anywhere = !self.settings.rolling_held_mass_alone || !any_rolling;
        if !held_anywhere {
            crate::physics::scratch::refill(&mut s.contact_count, n, 0);
            for &(a, b) in &s.graph.links {
                s.contact_count[a as usize] += 1;
                s.contact_count[b as usize] += 1;
            }
        }
        let alone = |body: u32| body == 0 || s.contact_count[body as usize] == 1;
        // The constraints that get the mass-ratio sweeps (ascending, as `i` below).
        let mut swept = s.mass_ratio.swept_constraints().iter().peekable();
        for (i, (color, k)) in s.graph.solve_order().enumerate() {
            let (a, b) = s.graph.links[i];
            let facts = s.contact_facts[i];
            let unmarked = !s.mass_ratio.marked[a as usize] && !s.mass_ratio.marked[b as usize];
            let source = LaneSource {
                contact: k as u32,
                a,
                b,
                preload: s.statics.preload[i],
                spring_preload: s.statics.spring_preload[i],
                tangent_warm: s.statics.tangent_warm[i],
                pressure_offset: s.statics.pressure_offset[i],
                offset_change: s.statics.offset_change[i],
                load_change: s.statics.load_change[i],
                determinate: s.statics.determinate[i],
                struck_pile: s.statics.struck_pile[i],
                touching_spring: s.statics.determinate[i] && self.settings.touching_spring,
                touching_tolerance: self.settings.touching_tolerance,
                anchored: facts.anchorable && unmarked,
                symmetric: facts.unjointed && unmarked,
                deep: facts.deep,
                rolling_held: held_anywhere || (alone(a) && alone(b)),
                softness: if a == 0 || b == 0 {
                    static_softness
                } else {
                    contact_softness
                },
            };
            let is_swept = swept.next_if(|&&j| j as usize == i).is_some();
            s.wide
                .push(i, color, usize::from(facts.len), source, is_swept);
        }
        s.wide.build(
            &self.contacts,
            &self.bodies,
            &s.solver.bodies,
            &s.solver.motions,
        );
        s.mass_ratio.prepare_rows(
            &s.graph,
            &s.wide,
            &self.contacts,
            &self.bodies,
            &s.statics.preload,
        );
        // The contacts too deep for the soft row, pushed out in position space each sub-step.
        let (contacts, bodies, graph) = (&self.contacts, &self.bodies, &s.graph);
        s.deep.collect(
            contacts,
            &graph.layer_order,
            &s.graph.links,
            |i| &contacts[graph.contact(i)],
            |body| bodies[body as usize].pose.position,
            &s.solver.motions,
            self.settings.linear_slop,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The anchor cap binds only below 4 sub-steps of one iteration: at the defaults an eighth of
    /// the sub-step rate is 30 Hz to a float's rounding, which the coefficients do not see, so the
    /// default scenes step as they did before the cap (the determinism hashes did not move). At 2
    /// sub-steps, or 4 iterations, it halves the anchors' frequency.
    #[test]
    fn anchors_are_slower_than_the_contacts_only_below_four_sub_steps_of_one_iteration() {
        let mut settings = Settings::default();
        for substeps in [4, 8] {
            settings.substeps = substeps;
            let h = settings.dt / substeps as f32;
            let (contact, _) = contact_springs(&settings, h);
            assert_eq!(contact.anchor, contact.normal, "at {substeps} sub-steps");
        }
        settings.substeps = 2;
        let h = settings.dt / 2.0;
        let (contact, with_static) = contact_springs(&settings, h);
        let zeta = settings.contact_damping_ratio;
        assert_eq!(contact.anchor, Softness::new(15.0, zeta, h));
        assert_eq!(with_static.anchor, with_static.normal);
        // Four iterations a sub-step halve it (the square root of the iterations).
        settings.substeps = 4;
        settings.iterations = 4;
        let h = settings.dt / 4.0;
        assert_eq!(
            contact_springs(&settings, h).0.anchor,
            Softness::new(15.0, zeta, h)
        );
        settings.anchor_frequency_cap = false;
        let (contact, _) = contact_springs(&settings, h);
        assert_eq!(contact.anchor, contact.normal);
    }
}
