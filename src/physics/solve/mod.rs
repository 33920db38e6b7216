//! Stages 4 to 6a, solve: the sub-steps (integrate velocities, warm start, the soft solve, the shock
//! pass, integrate positions, push deep overlaps out, relax), the impacts (restitution), storing
//! impulses for the next warm start, and writing the results back to the bodies.

pub(crate) mod contact_solver;
pub(crate) mod free_rotation;
pub(crate) mod lanes;
pub(crate) mod mass_ratio;
pub mod point_drive;
pub(crate) mod push_out;
pub(crate) mod softness;
pub(crate) mod solver_body;
pub(crate) mod wide_contacts;

use glam::Vec3;

use crate::physics::BodyId;
use crate::physics::fast_bodies::cap_speeds;
use crate::physics::profile::Stage;
use crate::physics::solve::contact_solver::PassParams;
use crate::physics::solve::point_drive::PointHold;
use crate::physics::solve::softness::capped_hertz;
use crate::physics::solve::solver_body::{VelocityStep, integrate_positions, integrate_velocities};
use crate::physics::solve::wide_contacts::{ImpactParams, LayerOrder, PointOrder};
use crate::physics::world::{Scratch, World};

/// The holds of one step: each with its body's solver index and centre at the step's start
/// (`active`), and what each applied over the step, summed over its sub-steps (`impulses`, kept for
/// `World::hold_force` and the next step's statics).
#[derive(Debug, Default)]
pub(in crate::physics) struct StepHolds {
    pub(in crate::physics) active: Vec<(PointHold, u32, Vec3)>,
    pub(in crate::physics) impulses: Vec<(BodyId, Vec3)>,
}

impl World {
    /// Steps 4 and 5: the sub-steps, the impacts and storing impulses.
    pub(in crate::physics) fn solve(&mut self, dt: f32) {
        let set = &self.settings;
        let substeps = set.substep_count();
        let h = dt / substeps as f32;
        let velocity_step = VelocityStep {
            h,
            linear_damping: 1.0 / (1.0 + h * set.linear_damping.max(0.0)),
            angular_damping: 1.0 / (1.0 + h * set.angular_damping.max(0.0)),
            max_linear_speed: set.max_linear_speed,
            max_angular_speed: set.max_angular_speed,
        };
        let params = PassParams {
            inv_h: 1.0 / h,
            linear_slop: set.linear_slop,
            spread_row: set.spread_row,
            symmetric_relax: set.symmetric_relax,
            symmetric_bias: set.symmetric_biased_pass
                && substeps < crate::physics::solve::wide_contacts::DOWN_MIN_SUBSTEPS,
        };
        let s = &mut self.scratch;
        let hertz = capped_hertz(set.contact_hertz, h);
        s.joint_rows.prepare(
            &self.joints,
            &self.bodies,
            &s.solver.index,
            &s.solver.motions,
            (hertz, h),
            set.joint_tree,
        );
        let joints = !s.joint_rows.is_empty();
        if joints {
            s.joint_rows.mark_untouched_trees(
                s.solver.bodies.len(),
                &s.graph.links,
                self.holds
                    .iter()
                    .map(|hold| s.solver.index[hold.body.index()]),
                set.linear_damping != 0.0 || set.angular_damping != 0.0,
            );
        }
        // Each hold on an awake body, with its solver copy and its centre at the step's start.
        s.holds.active.clear();
        s.holds.impulses.clear();
        for hold in self.holds.drain(..) {
            let index = s.solver.index[hold.body.index()];
            if index != 0 {
                s.holds
                    .active
                    .push((hold, index, self.bodies[hold.body.index()].pose.position));
                s.holds.impulses.push((hold.body, Vec3::ZERO));
            }
        }
        let watch = &mut self.stopwatch;
        // With nothing awake (only the static dummy) the sub-steps are empty loops: no laps inside
        // them, whose clock reads would cost more than the loops (their nanoseconds go to the solve).
        let lap = s.solver.bodies.len() > 1;
        s.wide.remember_start_velocities(&s.solver.bodies);
        for substep in 0..substeps {
            // Numbered over the world's life, not the step: with an odd number of sub-steps the
            // alternations go on across steps, and the step counter is in snapshots.
            let number = self.steps * u64::from(substeps) + u64::from(substep);
            let mut last_order =
                PointOrder::before_substep(number, set.iteration_count(), set.alternate_sub_steps);
            let biased_layers =
                |pass| LayerOrder::of_pass(number, pass, substeps, set.alternate_layer_order);
            integrate_velocities(&mut s.solver.bodies, &s.solver.motions, &velocity_step);
            let t = substep as f32 * h;
            for ((hold, index, start), (_, sum)) in s.holds.active.iter().zip(&mut s.holds.impulses)
            {
                let i = *index as usize;
                let centre = *start + Vec3::from(s.solver.bodies[i].dp);
                *sum += hold.solve_substep(
                    &mut s.solver.bodies[i],
                    &s.solver.motions[i],
                    centre,
                    set.gravity,
                    t,
                    h,
                    dt,
                );
            }
            if lap {
                watch.lap(Stage::Integrate);
            }
            // The loose joints before the contacts, the tree after them (see `joint`).
            if joints {
                s.joint_rows
                    .warm_start(&mut s.solver.bodies, &s.solver.motions);
                s.joint_rows
                    .solve_loose::<true>(&mut s.solver.bodies, &s.solver.motions, h);
            }
            s.wide.warm_start(&mut s.solver.bodies);
            if substep == 0 {
                s.wide.remember_kicked_velocities(&s.solver.bodies);
            }
            s.solve_passes::<true>(
                &params,
                set.iteration_count(),
                set.mass_ratio_iterations,
                set.alternate_point_order,
                &mut last_order,
                biased_layers,
            );
            if set.shock_propagation && s.mass_ratio.has_shock_rows() {
                s.mass_ratio.run_shock_pass(&s.wide, &mut s.solver.bodies);
            }
            if joints {
                s.joint_rows.solve_tree::<true>(
                    &mut s.solver.bodies,
                    &s.solver.motions,
                    h,
                    (false, set.joint_scalar_rows_last),
                );
            }
            if lap {
                watch.lap(Stage::Solve);
            }
            integrate_positions(&mut s.solver.bodies, &mut s.solver.motions, h);
            if lap {
                watch.lap(Stage::Integrate);
            }
            if !s.deep.is_empty() {
                s.deep.push_apart(
                    &mut s.solver.bodies,
                    set.linear_slop,
                    set.max_push_out_velocity,
                    h,
                );
            }
            if joints {
                s.joint_rows
                    .solve_loose::<false>(&mut s.solver.bodies, &s.solver.motions, h);
            }
            s.solve_passes::<false>(
                &params,
                1,
                set.mass_ratio_iterations,
                set.alternate_point_order,
                &mut last_order,
                |_| LayerOrder::Up,
            );
            if joints {
                // Only the last sub-step's relax pass is solved for trees nothing else touches.
                let skip_untouched = substep + 1 < substeps;
                s.joint_rows.solve_tree::<false>(
                    &mut s.solver.bodies,
                    &s.solver.motions,
                    h,
                    (skip_untouched, set.joint_scalar_rows_last),
                );
            }
            if s.wide.any_bouncy() {
                s.wide.add_step_impulses();
            }
            if lap {
                watch.lap(Stage::Solve);
            }
        }
        if !lap {
            watch.lap(Stage::Solve);
        }
        let impact = ImpactParams {
            threshold: set.restitution_threshold,
            h,
            touching: set.linear_slop,
            gravity: set.gravity.into(),
        };
        s.wide
            .apply_impacts(&mut s.solver.bodies, &self.contacts, &impact);
        self.max_penetration = s.wide.store_impulses(&mut self.contacts);
        s.joint_rows.store(&mut self.joints);
        self.stopwatch.lap(Stage::RestitutionStore);
    }

    /// Step 6a: copies solver results back to the bodies and clears forces.
    ///
    /// Only awake dynamic bodies can hold a force or torque (`apply_force_at_point` wakes the body
    /// and ignores static ones, `set_static` clears them), and every one of them has a solver body:
    /// clearing those is clearing all, without touching the sleeping and static bodies.
    #[inline(never)]
    pub(in crate::physics) fn write_back(&mut self) {
        let s = &self.scratch;
        let n = s.solver.bodies.len().min(s.solver.motions.len());
        for (sb, m) in s.solver.bodies[1.min(n)..n]
            .iter()
            .zip(&s.solver.motions[1.min(n)..n])
        {
            let body = &mut self.bodies[m.body as usize];
            body.pose.position += Vec3::from(sb.dp);
            body.pose.rotation = m.rotation;
            // Restitution's bounce comes after the sub-steps' caps: cap what the step reports.
            (body.linear_velocity, body.angular_velocity) = cap_speeds(
                sb.v.into(),
                sb.w.into(),
                self.settings.max_linear_speed,
                self.settings.max_angular_speed,
            );
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
        debug_assert!(
            self.bodies
                .iter()
                .all(|b| b.force == Vec3::ZERO && b.torque == Vec3::ZERO)
        );
    }
}

impl Scratch {
    /// `full_passes` Gauss–Seidel passes over every contact (soft and biased when `BIAS`, else the
    /// rigid relax), then `mass_ratio_passes` more over the lane groups of the contacts around a mass
    /// ratio (packed apart from the others: `WideContacts::push`).
    ///
    /// Each pass visits the manifolds' points in the direction opposite to the pass before it when
    /// `alternate` (else always forward), `order` being the last pass's on entry and this call's last
    /// on return (see [`PointOrder`]). Full pass `p` visits the layers in `layers(p)` (see
    /// [`LayerOrder`]); the mass-ratio passes go up.
    fn solve_passes<const BIAS: bool>(
        &mut self,
        params: &PassParams,
        full_passes: u32,
        mass_ratio_passes: u32,
        alternate: bool,
        order: &mut PointOrder,
        layers: impl Fn(u32) -> LayerOrder,
    ) {
        for pass in 0..full_passes {
            *order = order.next(alternate);
            self.wide
                .solve::<BIAS>(&mut self.solver.bodies, params, *order, layers(pass));
        }
        self.mass_ratio.passes::<BIAS>(
            &mut self.wide,
            &mut self.solver.bodies,
            params,
            mass_ratio_passes,
            alternate,
            order,
        );
    }
}
