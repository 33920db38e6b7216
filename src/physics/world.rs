//! The world: bodies, their persistent contacts, and the step that moves them.
//!
//! This file holds the [`World`] type, its API and [`World::step`], which is the list of stages below;
//! each stage is a folder of `physics` named after it (`broad`, `narrow`, `prepare`, `solve`,
//! `sleep`), holding its `impl World` step and the code only it uses, in the spirit of Box2D v3's
//! world, solver, contact solver and island files. Each stage owns its state between steps (a
//! field of `Scratch` per stage: `broad::PairFinder`, `prepare::SolverArrays`, `Statics`,
//! `MassRatio`, ...), with what it reads from the others in its signatures.
//!
//! # The step (Box2D v3 soft step with shock propagation)
//! 1. **Broad phase** (`broad/mod.rs`, over `broad::broad_phase::BroadPhase`): world AABBs (awake bodies'
//!    boxes swept by v·dt and grown by the speculative distance and gravity's reach, `fast_bodies`)
//!    → candidate pairs, sorted by `(a, b)` and held to bounded counts (`contact_cap`). A pair of an
//!    awake body and a sleeping one wakes the sleeper's island (and the broad phase runs again for its
//!    pairs). The broad phase runs on fat boxes and its pairs are reused while no box leaves its fat
//!    box (a resting pile skips it); the exact boxes filter them, so the pairs are those of a fresh run.
//! 2. **Collide** (`narrow/mod.rs`, over `narrow::collide`), once per step: each pair with an awake body
//!    gets a manifold with margin `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance`
//!    (speculative contacts: continuous collision without time of impact); points inherit last step's
//!    impulses by feature id. A pair whose bodies have not moved more than `manifold_reuse_distance`
//!    relative to each other since its manifold was computed keeps it, followed to where they are
//!    (`Contact::follow`). Coincident bodies are told apart first (`coincident`).
//! 3. **Prepare** (`prepare/mod.rs`): solver bodies (awake dynamic only; static and sleeping bodies
//!    are the shared dummy 0), contact graph layers (BFS from static bodies) and a greedy graph
//!    colouring (`constraint_order`), and constraints in (colour, layer) order with anchors, effective
//!    masses and pre-solve normal velocities, packed four manifolds to a SIMD lane group
//!    (`wide_contacts`). Layers, colours and orders are kept from the last step while the contact graph
//!    is the same. The contacts around a mass ratio and the shock pass's rows are chosen in
//!    `solve/mass_ratio.rs`; the overlaps too deep for the soft row are listed for `push_out`.
//!    The feed-forward statics (`prepare/preload.rs`, `Settings::preload`) then give each resting
//!    contact the load, friction and moment statics say it carries, so the sub-steps start from
//!    them instead of finding them again from last step's impulses.
//! 4. **Sub-steps** (`solve/mod.rs`; h = dt / substeps), each: integrate velocities (gravity,
//!    forces) → held points (`point_drive`) → joints (`joint`: warm start and solve, before the
//!    contacts; again before the relax) → warm start → solve with soft bias (× iterations, then ×
//!    `mass_ratio_iterations` over the contacts around a mass ratio) → shock pass → integrate
//!    positions (a body with unequal moments turns as a free body, keeping its angular momentum:
//!    `free_rotation`) → push deep overlaps out in position space → relax (rigid, no bias; the
//!    mass-ratio contacts again extra times).
//! 5. **Impacts** (restitution from the velocities at the moment of impact, `solve/wide_contacts/impacts.rs`),
//!    then **store impulses** for next step's warm start (`solve/mod.rs`).
//! 6. **Write back** poses and velocities (speeds capped), clear forces (`solve/mod.rs`); **sleep**
//!    (`sleep/mod.rs`): islands whose bodies all rested for `time_to_sleep` go to sleep.
//!
//! In debug builds the solver bodies and the bodies are checked finite between stages (`finite`).
//!
//! # Sign conventions
//! Manifold normals point from body A to body B (A has the lower index); separation is positive when
//! apart, negative when penetrating; an accumulated normal impulse is ≥ 0 and pushes B along +n, A along −n.

#[cfg(test)]
mod tests;

use glam::Vec3;

use crate::physics::narrow::contact::Contact;
use crate::physics::prepare::ContactFacts;
use crate::physics::prepare::constraint_order::ConstraintOrder;
use crate::physics::prepare::preload::reuse::SeenAt;

use crate::geometry::{Ray, RayHit};
use crate::physics::finite::{debug_check_bodies, debug_check_solver};
use crate::physics::input::WorldInput;
use crate::physics::profile::{Stage, Stopwatch};
use crate::physics::solve::point_drive::PointHold;
use crate::physics::solve::push_out::DeepOverlaps;
use crate::physics::solve::wide_contacts::WideContacts;
use crate::physics::{Body, BodyDesc, BodyId, Settings};

/// Reused per-step buffers: no allocation once the world has reached its steady-state size. Only a
/// cache: what a step computes does not depend on it (a world restored with fresh scratch steps
/// bit for bit as the original, see `snapshot`).
#[derive(Debug, Default)]
pub(super) struct Scratch {
    /// Stage 1's broad phase and its output, the step's pairs.
    pub(super) pair_finder: crate::physics::broad::PairFinder,
    /// The narrow phase's merge buffer: last step's contacts merged with this step's pairs.
    pub(super) merged: Vec<Contact>,
    /// The awake bodies as the solver sees them (stage 3).
    pub(super) solver: crate::physics::prepare::SolverArrays,
    /// The constraints, prepared, in lane groups: the velocity passes, restitution and the impulse
    /// store run on them.
    pub(super) wide: WideContacts,
    /// The contact graph's keys, layers, colouring and orders, and each constraint's bodies in
    /// solve order (`constraint_order`).
    pub(super) graph: ConstraintOrder,
    /// What the statics give each constraint when the step begins, and their working buffers
    /// (`prepare::preload`).
    pub(super) statics: crate::physics::prepare::preload::Statics,
    /// Who gets the extra sweeps around mass ratios, and the shock pass (`solve::mass_ratio`).
    pub(super) mass_ratio: crate::physics::solve::mass_ratio::MassRatio,
    /// The deep overlaps pushed out in position space (`push_out`).
    pub(super) deep: DeepOverlaps,
    /// The sleep stage's islands and buffers (stage 6b).
    pub(super) sleep: crate::physics::sleep::SleepState,
    /// The step's holds and what each applied (`World::hold_force`).
    pub(super) holds: crate::physics::solve::StepHolds,
    /// The joints' rows as this step prepared them (`joint::rows`).
    pub(super) joint_rows: crate::physics::joint::rows::JointRows,
    /// Per body, whether a joint holds it (filled only while the world has joints): its contacts'
    /// friction is not anchored (see `contact_solver`, "Friction anchors"), nor relaxed twice
    /// ("The symmetric relax").
    pub(super) jointed: Vec<bool>,
    /// Per solver body, how many contacts it has this step (see `LaneSource::rolling_held`).
    pub(super) contact_count: Vec<u32>,
    /// Per constraint, what the lanes need of its contact.
    pub(super) contact_facts: Vec<ContactFacts>,
}

/// A set of rigid bodies and the contacts between them.
pub struct World {
    pub(super) settings: Settings,
    pub(super) bodies: Vec<Body>,
    /// Persistent contacts sorted by `(a, b)`, `a < b`.
    pub(super) contacts: Vec<Contact>,
    /// Per body, where the statics last saw it (`prepare::preload::reuse`); beside the bodies,
    /// not in them, so that the bodies the hot loops walk stay as small as they were.
    pub(super) statics_seen: Vec<Option<SeenAt>>,
    pub(super) scratch: Scratch,
    /// Deepest penetration at the end of the last step, m.
    pub(super) max_penetration: f32,
    /// Contacts the solver saw in the last step.
    pub(super) active_contacts: usize,
    /// Steps taken since the world was made (or reset): the clock inputs are tagged with.
    pub(super) steps: u64,
    /// Every input applied through this API, with the step it came before, while journaling (see
    /// `input`); `settings_touched` marks a `settings_mut` borrow, journaled at the next step.
    pub(super) journal: Option<Vec<(u64, WorldInput)>>,
    pub(super) settings_touched: bool,
    /// Points held for the next step (`World::hold_point`), cleared by it.
    pub(super) holds: Vec<PointHold>,
    /// Joints, in the order they were added, with last step's impulses.
    pub(super) joints: Vec<crate::physics::joint::Joint>,
    /// Times the step's stages while profiling is on (see `profile`): no part of the state, the
    /// trace or a snapshot.
    pub(super) stopwatch: Stopwatch,
}

impl World {
    /// An empty world with these settings.
    pub fn new(settings: Settings) -> Self {
        Self {
            settings,
            bodies: Vec::new(),
            contacts: Vec::new(),
            statics_seen: Vec::new(),
            scratch: Scratch::default(),
            max_penetration: 0.0,
            active_contacts: 0,
            steps: 0,
            journal: None,
            settings_touched: false,
            holds: Vec::new(),
            joints: Vec::new(),
            stopwatch: Stopwatch::default(),
        }
    }

    /// The settings the next step uses.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Settings, to change between steps (changing gravity this way does not wake sleeping bodies; see
    /// [`World::set_gravity`]).
    pub fn settings_mut(&mut self) -> &mut Settings {
        self.settings_touched = true;
        self.forget_kept_statics();
        &mut self.settings
    }

    /// Drops what the contacts kept of the statics (`prepare::preload::reuse`): found under other
    /// settings (a sub-step, gravity), they are found afresh at the next step.
    pub(crate) fn forget_kept_statics(&mut self) {
        for contact in &mut self.contacts {
            contact.statics = None;
        }
    }

    /// Adds a body; ids are handed out in order, starting at 0.
    pub fn add_body(&mut self, desc: BodyDesc) -> BodyId {
        self.log(WorldInput::AddBody(desc));
        self.bodies.push(Body::from_desc(&desc));
        BodyId(self.bodies.len() as u32 - 1)
    }

    /// Number of bodies, static ones included.
    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    /// True when the world has no bodies.
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    /// The body with this id. Panics if `id` was not handed out by this world.
    pub fn body(&self, id: BodyId) -> &Body {
        &self.bodies[id.index()]
    }

    /// All bodies, indexed by `BodyId`.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Dynamic bodies that are not asleep.
    pub fn awake_count(&self) -> usize {
        self.bodies.iter().filter(|b| b.is_awake_dynamic()).count()
    }

    /// Deepest penetration between any two bodies at the end of the last step, m (≥ 0).
    pub fn max_penetration(&self) -> f32 {
        self.max_penetration
    }

    /// Contacts (body pairs with at least one manifold point, speculative ones included) the solver
    /// handled in the last step.
    pub fn contact_count(&self) -> usize {
        self.active_contacts
    }

    /// Pairs of touching bodies the last step ignored because a body or the world had too many
    /// (see `contact_cap`): 0 in any ordinary scene.
    pub fn pairs_over_cap(&self) -> usize {
        self.scratch.pair_finder.cap.dropped()
    }

    /// Applies `force` (N, world) at `point` (world) during the next step only; wakes the body.
    /// Ignored for static bodies and non-finite input or sums.
    pub fn apply_force_at_point(&mut self, id: BodyId, force: Vec3, point: Vec3) {
        let Some(body) = self.bodies.get(id.index()) else {
            return;
        };
        if body.is_static || !force.is_finite() || !point.is_finite() {
            return;
        }
        self.log(WorldInput::Force {
            body: id,
            force,
            point,
        });
        self.wake_island(id.0);
        let body = &mut self.bodies[id.index()];
        let f = body.force + force;
        let t = body.torque + (point - body.pose.position).cross(force);
        if f.is_finite() && t.is_finite() {
            body.force = f;
            body.torque = t;
        }
    }

    /// Applies `impulse` (N·s, world) at `point` (world) now: Δv = J/m, Δω = I⁻¹(r × J). Wakes the body.
    /// Ignored for static bodies and non-finite input or results.
    pub fn apply_impulse_at_point(&mut self, id: BodyId, impulse: Vec3, point: Vec3) {
        let Some(body) = self.bodies.get(id.index()) else {
            return;
        };
        if body.is_static || !impulse.is_finite() || !point.is_finite() {
            return;
        }
        self.log(WorldInput::Impulse {
            body: id,
            impulse,
            point,
        });
        self.wake_island(id.0);
        let body = &mut self.bodies[id.index()];
        let v = body.linear_velocity + body.inv_mass * impulse;
        let w = body.angular_velocity
            + body.inv_inertia_world() * (point - body.pose.position).cross(impulse);
        if v.is_finite() && w.is_finite() {
            body.linear_velocity = v;
            body.angular_velocity = w;
        }
    }

    /// Sets gravity (m/s², world) and wakes every body, so sleeping piles feel the change. (Writing
    /// `settings_mut().gravity` changes it without waking anything.) Non-finite input is ignored.
    pub fn set_gravity(&mut self, gravity: Vec3) {
        if !gravity.is_finite() {
            return;
        }
        self.log(WorldInput::Gravity(gravity));
        self.settings.gravity = gravity;
        self.forget_kept_statics();
        self.wake_all();
    }

    /// Wakes the body and its whole sleeping island.
    pub fn wake(&mut self, id: BodyId) {
        if id.index() < self.bodies.len() {
            self.log(WorldInput::Wake(id));
            self.wake_island(id.0);
        }
    }

    /// Freezes (`true`) or unfreezes a body. A frozen body keeps its pose with zero velocity and no
    /// pending force; an unfrozen one wakes and falls. Either way the bodies touching it wake (their
    /// support changed).
    pub fn set_static(&mut self, id: BodyId, is_static: bool) {
        if id.index() >= self.bodies.len() {
            return;
        }
        self.log(WorldInput::SetStatic {
            body: id,
            is_static,
        });
        self.wake_island(id.0);
        self.wake_neighbours(id.0);
        let body = &mut self.bodies[id.index()];
        body.is_static = is_static;
        body.linear_velocity = Vec3::ZERO;
        body.angular_velocity = Vec3::ZERO;
        body.force = Vec3::ZERO;
        body.torque = Vec3::ZERO;
        body.sleep_time = 0.0;
        // A joint held still at both ends carries nothing and the solver leaves it out: what it
        // kept from before would be its reported load forever, and the warm start of the first
        // step after an end is let go (tests/physics/joints.rs, frozen ends).
        let bodies = &self.bodies;
        let held = |end: Option<BodyId>| end.is_none_or(|id| bodies[id.index()].is_static);
        for joint in &mut self.joints {
            if held(joint.desc.a) && held(Some(joint.desc.b)) {
                joint.impulses = Default::default();
            }
        }
    }

    /// The nearest body whose surface the ray enters within `[t_min, t_max]`.
    pub fn cast_ray(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(BodyId, RayHit)> {
        let mut best: Option<(BodyId, RayHit)> = None;
        for (i, body) in self.bodies.iter().enumerate() {
            let limit = best.map_or(t_max, |(_, hit)| hit.t);
            if let Some(hit) = ray.cast(&body.shape, &body.pose, t_min, limit) {
                best = Some((BodyId(i as u32), hit));
            }
        }
        best
    }

    /// Advances the world by one fixed step of `settings.dt`. A non-finite or non-positive dt does nothing.
    pub fn step(&mut self) {
        let dt = self.settings.dt;
        if !(dt.is_finite() && dt > 0.0) {
            return;
        }
        if std::mem::take(&mut self.settings_touched) {
            self.log(WorldInput::Settings(Box::new(self.settings.clone())));
        }
        self.steps += 1;
        self.stopwatch.start();
        if !self.settings.sleep {
            self.wake_all();
        }
        self.find_pairs(dt);
        let woke_jointed = !self.joints.is_empty() && self.wake_jointed_sleepers();
        if self.wake_touched_sleepers(dt) | woke_jointed {
            // Pairs inside the woken islands were filtered out as sleeping–sleeping: find them now.
            self.find_pairs(dt);
        }
        self.stopwatch.lap(Stage::BroadPhase);
        self.build_solver_bodies();
        debug_check_solver(&self.scratch.solver.bodies, "gathering the solver bodies");
        self.stopwatch.lap(Stage::Prepare);
        self.update_contacts(dt);
        self.stopwatch.lap(Stage::NarrowPhase);
        self.prepare_constraints(dt);
        self.stopwatch.lap(Stage::Prepare);
        self.solve(dt);
        debug_check_solver(&self.scratch.solver.bodies, "the sub-steps");
        self.write_back();
        debug_check_bodies(&self.bodies, "writing the step back");
        self.stopwatch.lap(Stage::Integrate);
        if self.settings.sleep {
            self.update_sleep(dt);
        }
        self.stopwatch.lap(Stage::Sleep);
        self.stopwatch.stop();
    }
}
