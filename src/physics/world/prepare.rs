//! Stage 3, prepare: the solver bodies, the contact graph's order (layers and colours, kept while the
//! graph is unchanged), the constraints, packed into SIMD lane groups in solve order, and the deep
//! overlaps the sub-steps push out in position space (`push_out`).

use glam::Vec3A;

use super::World;
use crate::physics::constraint_order::SERIAL_COLOR;

use crate::physics::softness::Softness;
use crate::physics::solver_body::{SolverBody, SolverMotion};
use crate::physics::wide_contacts::{GroupKind, LaneSource, kind_of};

impl World {
    /// Copies awake dynamic bodies into the solver arrays (index 0 = static dummy). Kept out of line
    /// (once per step) so profiles show its cost.
    #[inline(never)]
    pub(super) fn build_solver_bodies(&mut self) {
        let s = &mut self.scratch;
        let gravity = Vec3A::from(self.settings.gravity);
        let (solver_bodies, motions) = (&mut s.solver_bodies, &mut s.motions);
        solver_bodies.clear();
        motions.clear();
        // At most every body plus the dummy: the pushes below never reallocate.
        solver_bodies.reserve(self.bodies.len() + 1);
        motions.reserve(self.bodies.len() + 1);
        solver_bodies.push(SolverBody::DUMMY);
        motions.push(SolverMotion::DUMMY);
        s.solver_index.clear();
        s.solver_index
            .extend(self.bodies.iter().enumerate().map(|(i, body)| {
                if !body.is_awake_dynamic() {
                    return 0;
                }
                let index = solver_bodies.len() as u32;
                let inv_inertia = body.inv_inertia_world_simd();
                solver_bodies.push(SolverBody {
                    v: body.linear_velocity.into(),
                    w: body.angular_velocity.into(),
                    dp: Vec3A::ZERO,
                    dtheta: Vec3A::ZERO,
                });
                motions.push(SolverMotion {
                    rotation: body.pose.rotation,
                    linear_accel: gravity + body.inv_mass * Vec3A::from(body.force),
                    angular_accel: inv_inertia * Vec3A::from(body.torque),
                    inertia_local: body.inertia_local,
                    gyroscopic: body.inertia_local.min_element()
                        != body.inertia_local.max_element(),
                    inv_inertia,
                    body: i as u32,
                    inv_mass: body.inv_mass,
                });
                index
            }));
    }

    /// Step 3: layers the contact graph by BFS from static bodies and builds the constraints in layer
    /// order.
    pub(super) fn prepare_constraints(&mut self, dt: f32) {
        let h = dt / self.settings.substep_count() as f32;
        let hertz = self.settings.contact_hertz.min(0.25 / h);
        let zeta = self.settings.contact_damping_ratio;
        let contact_softness = Softness::new(hertz, zeta, h);
        let static_softness = Softness::new(2.0 * hertz, zeta, h);
        let s = &mut self.scratch;
        let n = s.solver_bodies.len();

        s.graph_key.clear();
        s.graph_key.extend(self.contacts.iter().map(|c| {
            (
                s.solver_index[c.a as usize],
                s.solver_index[c.b as usize],
                kind_of(c.manifold.len),
            )
        }));
        let same_graph = s.graph_key == s.previous_graph_key && s.graph.levels.len() == n;
        std::mem::swap(&mut s.graph_key, &mut s.previous_graph_key);
        if !same_graph {
            self.order_constraints();
        }
        let s = &mut self.scratch;

        // The constraints' bodies in solve order, before anything is prepared: the mass-ratio marks
        // and the shock pass's list depend on them alone.
        s.links.clear();
        s.links.extend(s.graph.solve_order().map(|(_, k)| {
            let c = &self.contacts[k];
            (s.solver_index[c.a as usize], s.solver_index[c.b as usize])
        }));
        self.active_contacts = s.links.len();

        s.mass_ratio.select(
            &s.links,
            &s.graph,
            &s.solver_index,
            &s.motions,
            &self.contacts,
            &self.settings,
        );
        s.compute_preloads(&self.contacts, &self.bodies, &self.holds, &self.settings, h);

        s.wide.clear();
        for (i, (color, k)) in s.graph.solve_order().enumerate() {
            let c = &mut self.contacts[k];
            c.impulses.fed_tangent = s.statics.tangent_demand[i];
            let (a, b) = s.links[i];
            let source = LaneSource {
                contact: k as u32,
                a,
                b,
                preload: s.statics.preload[i],
                spring_preload: s.statics.spring_preload[i],
                tangent_warm: s.statics.tangent_warm[i],
                pressure_offset: s.statics.pressure_offset[i],
                determinate: s.statics.determinate[i],
                softness: if a == 0 || b == 0 {
                    static_softness
                } else {
                    contact_softness
                },
            };
            s.wide.push(color, SERIAL_COLOR, c.manifold.len, source);
        }
        s.wide
            .build(&self.contacts, &self.bodies, &s.solver_bodies, &s.motions);
        s.mass_ratio
            .prepare_rows(&s.links, &s.graph, &s.wide, &self.contacts, &self.bodies);
        // The contacts too deep for the soft row, pushed out in position space each sub-step.
        let (contacts, bodies, graph) = (&self.contacts, &self.bodies, &s.graph);
        s.deep.collect(
            contacts,
            &graph.layer_order,
            &s.links,
            |i| &contacts[graph.contact(i)],
            |body| bodies[body as usize].pose.position,
            &s.motions,
            self.settings.linear_slop,
        );
    }

    /// Step 3a: the layers, colouring and orders of the contact graph, from the graph key
    /// `prepare_constraints` has just computed and swapped into `previous_graph_key` (per contact:
    /// its bodies' solver indices and its lane-group kind).
    #[inline(never)]
    fn order_constraints(&mut self) {
        let s = &mut self.scratch;
        let keys: &[(u32, u32, GroupKind)] = &s.previous_graph_key;
        debug_assert_eq!(keys.len(), self.contacts.len());
        debug_assert!(keys.iter().zip(&self.contacts).all(|(&key, c)| {
            key == (
                s.solver_index[c.a as usize],
                s.solver_index[c.b as usize],
                kind_of(c.manifold.len),
            )
        }));
        s.graph.rebuild(keys, s.solver_bodies.len());
    }
}
