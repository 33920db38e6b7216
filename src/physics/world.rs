//! The world: bodies, their persistent contacts, and the step that moves them.
//!
//! # The step (Box2D v3 soft step with shock propagation)
//! 1. **Broad phase** (`broad_phase::BroadPhase`): world AABBs (awake bodies' boxes swept by v·dt and
//!    grown by the speculative distance) → candidate pairs, sorted by `(a, b)`. A pair of an awake body
//!    and a sleeping one wakes the sleeper's island (and the broad phase runs again for its pairs).
//!    The broad phase runs on fat boxes and its pairs are reused while no box leaves its fat box (a
//!    resting pile skips it); the exact boxes filter them, so the pairs are those of a fresh run.
//! 2. **Collide**, once per step: each pair with an awake body gets a manifold with margin
//!    `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance` (speculative contacts: continuous
//!    collision without time of impact); points inherit last step's impulses by feature id. A pair whose
//!    bodies have not moved more than `manifold_reuse_distance` since its manifold was computed keeps it
//!    (its separations are moved with the bodies when prepared).
//! 3. **Prepare**: solver bodies (awake dynamic only; static and sleeping bodies are the shared dummy 0),
//!    contact graph layers (BFS from static bodies) and a greedy graph colouring (`constraint_order`),
//!    and constraints in (colour, layer) order with anchors, effective masses and pre-solve normal velocities, packed four
//!    manifolds to a SIMD lane group (`wide_contacts`). Layers, colours and orders are kept from the last
//!    step while the contact graph is the same.
//! 4. **Sub-steps** (h = dt / substeps), each: integrate velocities (gravity, forces, implicit gyroscopic
//!    term) → warm start → solve with soft bias (× iterations, then × `mass_ratio_iterations` over the
//!    contacts around a mass ratio) → shock pass → integrate positions → relax (rigid, no bias; the
//!    mass-ratio contacts again extra times).
//! 5. **Restitution**, then **store impulses** for next step's warm start.
//! 6. **Write back** poses and velocities, clear forces; **sleep**: islands whose bodies all rested for
//!    `time_to_sleep` go to sleep.
//!
//! # Sign conventions
//! Manifold normals point from body A to body B (A has the lower index); separation is positive when
//! apart, negative when penetrating; an accumulated normal impulse is ≥ 0 and pushes B along +n, A along −n.

use glam::{Vec3, Vec3A};

use super::body::NO_BODY;
use super::broad_phase::{BodyKind, BroadPhase};
use super::collide::collide;
use super::constraint_order::{ConstraintOrder, SERIAL_COLOR};
use super::contact::{Contact, mix_friction, mix_restitution, moved_since, rolling_limit};
use super::contact_cap::ContactCap;
use super::contact_solver::{self, PassParams, ShockRow, Side, shock_pass};
use super::fast_bodies::{cap_speeds, gravity_reach};
use super::finite::{debug_check_bodies, debug_check_solver};
use super::input::WorldInput;
use super::island::Islands;
use super::softness::Softness;
use super::solver_body::{
    SolverBody, SolverMotion, VelocityStep, integrate_positions, integrate_velocities,
};
use super::wide_contacts::{GroupRef, LaneSource, PointOrder, WideContacts, kind_of};
use super::{Body, BodyDesc, BodyId, Settings};
use crate::geometry::{Aabb, Ray, RayHit};

/// Reused per-step buffers: no allocation once the world has reached its steady-state size. Only a
/// cache: what a step computes does not depend on it (a world restored with fresh scratch steps
/// bit for bit as the original, see `snapshot`).
#[derive(Debug, Default)]
pub(super) struct Scratch {
    broad_phase: BroadPhase,
    aabbs: Vec<Aabb>,
    kinds: Vec<BodyKind>,
    pairs: Vec<(u32, u32)>,
    /// Holds the pairs to bounded counts (see `contact_cap`).
    cap: ContactCap,
    /// Enlarged ("fat") boxes the broad phase last ran on, the kinds it saw, and the pairs it found:
    /// reused while every body's box stays inside its fat box (see `World::find_pairs`).
    fat_aabbs: Vec<Aabb>,
    fat_kinds: Vec<BodyKind>,
    candidates: Vec<(u32, u32)>,
    /// Steps the current candidates were reused, and how many grid runs in a row were never reused
    /// (a scene where something always moves: there fat boxes only cost, see `FAT_GIVE_UP`).
    reuses: u32,
    unused_runs: u32,
    contacts: Vec<Contact>,
    solver_index: Vec<u32>,
    solver_bodies: Vec<SolverBody>,
    motions: Vec<SolverMotion>,
    /// Solver indices of each constraint's bodies, in solve order (constraint i is `links[i]`).
    links: Vec<(u32, u32)>,
    /// Per solver body: the mass of its dynamic neighbours, then of the bodies resting on it, kg (see
    /// `mark_heavy_loads`).
    load: Vec<f32>,
    /// The constraints, prepared, in lane groups: the velocity passes, restitution and the impulse
    /// store run on them.
    wide: WideContacts,
    /// The lane groups holding `mass_ratio_constraints`, in solve order.
    mass_ratio_groups: Vec<GroupRef>,
    /// Layers, colouring and orders of the contact graph (`constraint_order`).
    graph: ConstraintOrder,
    /// The constraints the shock pass visits, in layer order.
    shock_order: Vec<u32>,
    /// Per constraint: its index in `shock_rows`, or `u32::MAX` when the shock pass skips it.
    shock_slot: Vec<u32>,
    /// Scalar copies of the constraints the shock pass visits (in solve order), and the visit order
    /// as indices into them.
    shock_rows: Vec<ShockRow>,
    shock_visit: Vec<u32>,
    /// Per contact: solver indices of its bodies and its lane-group kind (by point count), from
    /// which the layers, the colouring and both orders are computed. When it equals last step's (a
    /// resting pile), those are reused as they are.
    graph_key: Vec<(u32, u32, u8)>,
    previous_graph_key: Vec<(u32, u32, u8)>,
    /// Per solver body: whether it has a contact with a mass ratio ≥ `mass_ratio_threshold`.
    mass_ratio_bodies: Vec<bool>,
    /// Constraint indices (ascending: solve order) of the contacts touching such a body, which get the
    /// extra `mass_ratio_iterations` sweeps.
    mass_ratio_constraints: Vec<u32>,
    islands: Islands,
    sleep_times: Vec<f32>,
    sleepy: Vec<u32>,
}

/// A set of rigid bodies and the contacts between them.
pub struct World {
    pub(super) settings: Settings,
    pub(super) bodies: Vec<Body>,
    /// Persistent contacts sorted by `(a, b)`, `a < b`.
    pub(super) contacts: Vec<Contact>,
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
}

impl Scratch {
    /// `full_passes` Gauss–Seidel passes over every contact (soft and biased when `BIAS`, else the
    /// rigid relax), then `mass_ratio_passes` more over the lane groups of the contacts around a mass
    /// ratio (their lane neighbours get the extra sweeps too: harmless, and cheaper than splitting
    /// groups).
    ///
    /// Each pass visits the manifolds' points in the direction opposite to the pass before it, `order`
    /// being the last pass's on entry and this call's last on return (see [`PointOrder`]).
    fn solve_passes<const BIAS: bool>(
        &mut self,
        params: &PassParams,
        full_passes: u32,
        mass_ratio_passes: u32,
        order: &mut PointOrder,
    ) {
        for _ in 0..full_passes {
            *order = order.flipped();
            self.wide
                .solve::<BIAS>(&mut self.solver_bodies, params, *order);
        }
        for _ in 0..mass_ratio_passes {
            if self.mass_ratio_groups.is_empty() {
                return;
            }
            *order = order.flipped();
            self.wide.solve_groups::<BIAS>(
                &self.mass_ratio_groups,
                &mut self.solver_bodies,
                params,
                *order,
            );
        }
    }
}

impl World {
    /// An empty world with these settings.
    pub fn new(settings: Settings) -> Self {
        Self {
            settings,
            bodies: Vec::new(),
            contacts: Vec::new(),
            scratch: Scratch::default(),
            max_penetration: 0.0,
            active_contacts: 0,
            steps: 0,
            journal: None,
            settings_touched: false,
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
        &mut self.settings
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
        self.scratch.cap.dropped()
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
        for i in 0..self.bodies.len() {
            if self.bodies[i].sleeping {
                self.wake_island(i as u32);
            }
        }
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

    /// Wakes body `index` and, if it was asleep, every body of its island.
    pub(super) fn wake_island(&mut self, index: u32) {
        let mut i = index;
        loop {
            let body = &mut self.bodies[i as usize];
            body.sleeping = false;
            body.sleep_time = 0.0;
            let next = body.sleep_next;
            body.sleep_next = NO_BODY;
            if next == NO_BODY || next == index {
                break;
            }
            i = next;
        }
    }

    /// Wakes every body that shared a contact with body `index` last step.
    pub(super) fn wake_neighbours(&mut self, index: u32) {
        for k in 0..self.contacts.len() {
            let (a, b) = (self.contacts[k].a, self.contacts[k].b);
            if a == index && !self.bodies[b as usize].is_static {
                self.wake_island(b);
            } else if b == index && !self.bodies[a as usize].is_static {
                self.wake_island(a);
            }
        }
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
        if !self.settings.sleep {
            for i in 0..self.bodies.len() {
                if self.bodies[i].sleeping {
                    self.wake_island(i as u32);
                }
            }
        }
        self.find_pairs(dt);
        if self.wake_touched_sleepers(dt) {
            // Pairs inside the woken islands were filtered out as sleeping–sleeping: find them now.
            self.find_pairs(dt);
        }
        self.build_solver_bodies();
        debug_check_solver(&self.scratch.solver_bodies, "gathering the solver bodies");
        self.update_contacts(dt);
        self.prepare_constraints(dt);
        self.solve(dt);
        debug_check_solver(&self.scratch.solver_bodies, "the sub-steps");
        self.write_back();
        debug_check_bodies(&self.bodies, "writing the step back");
        if self.settings.sleep {
            self.update_sleep(dt);
        }
    }

    /// Step 1: world AABBs (awake bodies' boxes swept over the step and grown by half the speculative
    /// distance each, so every pair within its contact margin overlaps) into the broad phase. Pairs have
    /// at least one awake dynamic body and come sorted by `(a, b)`, `a < b`.
    ///
    /// The broad phase runs on fat boxes (each awake body's box grown by `FAT_MARGIN` of its size) and
    /// its pairs are kept as candidates while every body's box stays inside its fat box and no body
    /// changed kind: any two overlapping boxes then have overlapping fat boxes, so filtering the
    /// candidates by the exact boxes gives exactly the pairs a fresh broad phase would (Box2D's fat
    /// AABBs, with the whole broad phase rerun when one box leaves). A resting pile skips the broad
    /// phase; a run on exact boxes (a crowd that keeps moving, see `FAT_GIVE_UP`) has nothing to filter.
    fn find_pairs(&mut self, dt: f32) {
        let s = &mut self.scratch;
        let half_margin = 0.5 * self.settings.speculative_distance;
        let reach = gravity_reach(
            self.settings.gravity,
            dt,
            self.settings.speculative_distance,
        );
        s.aabbs.clear();
        s.kinds.clear();
        for body in &self.bodies {
            let mut aabb = body.shape.aabb(&body.pose);
            let kind = if body.is_static {
                BodyKind::Static
            } else if body.sleeping {
                BodyKind::Sleeping
            } else {
                let motion = body.linear_velocity * dt;
                let moved = Aabb::new(aabb.min + motion, aabb.max + motion);
                aabb = aabb.union(&moved).expanded(half_margin + reach);
                BodyKind::Dynamic
            };
            s.aabbs.push(aabb);
            s.kinds.push(kind);
        }
        let still_inside = s.fat_kinds == s.kinds
            && s.fat_aabbs.len() == s.aabbs.len()
            && s.fat_aabbs
                .iter()
                .zip(&s.aabbs)
                .all(|(fat, aabb)| fat.contains(aabb));
        // Whether the candidates came from fat boxes (reused or new) and need filtering by the exact ones.
        let filter = if still_inside {
            s.reuses += 1;
            true
        } else {
            // Only slow bodies get fat boxes: a body that moves more than a quarter of the margin
            // per step would leave it within a few steps anyway, and fat boxes make a rerun
            // costlier (wider rows, more candidates), so a falling crowd is swept as it is.
            s.unused_runs = if s.reuses == 0 { s.unused_runs + 1 } else { 0 };
            s.reuses = 0;
            let fatten = s.unused_runs < FAT_GIVE_UP || s.unused_runs % FAT_RETRY == 0;
            if fatten {
                s.fat_aabbs.clear();
                s.fat_aabbs
                    .extend(s.aabbs.iter().zip(&s.kinds).zip(&self.bodies).map(
                        |((aabb, kind), body)| {
                            let margin = FAT_MARGIN * (aabb.max - aabb.min).max_element();
                            let slow = body.linear_velocity.length() * dt < 0.25 * margin;
                            if *kind == BodyKind::Dynamic && slow {
                                aabb.expanded(margin)
                            } else {
                                *aabb
                            }
                        },
                    ));
            } else {
                s.fat_aabbs.clone_from(&s.aabbs);
            }
            s.fat_kinds.clone_from(&s.kinds);
            s.broad_phase
                .find_pairs(&s.fat_aabbs, &s.fat_kinds, &mut s.candidates);
            fatten
        };
        if filter {
            // Keep the candidates whose exact boxes overlap: each written in place and the count
            // advanced only for a keeper (no branch to mispredict, no capacity checks).
            let aabbs = &s.aabbs;
            s.pairs.clear();
            s.pairs.resize(s.candidates.len(), (0, 0));
            let mut kept = 0;
            for &(a, b) in &s.candidates {
                s.pairs[kept] = (a, b);
                kept += usize::from(aabbs[a as usize].overlaps(&aabbs[b as usize]));
            }
            s.pairs.truncate(kept);
        } else {
            // Exact boxes: the candidates are the pairs.
            s.pairs.clone_from(&s.candidates);
        }
        s.cap.apply(&mut s.pairs, &s.kinds);
    }

    /// A pair of an awake dynamic body and a sleeping one whose shapes are within the pair's contact
    /// margin (a contact would be made) wakes the sleeper's island; repeated until no island wakes, so a
    /// chain of touching sleeping islands all wake together. Overlapping bounding boxes alone are not
    /// enough: two islands a few centimetres apart would wake each other in turn forever. Returns whether
    /// any woke.
    fn wake_touched_sleepers(&mut self, dt: f32) -> bool {
        // Bodies only wake in here, so a body sleeping now was sleeping when the kinds were taken: with
        // no sleeper among them (sleeping off, or all awake) there is nothing to wake, and a pair
        // without one is skipped before its bodies are read.
        if !self.scratch.kinds.contains(&BodyKind::Sleeping) {
            return false;
        }
        let mut any = false;
        loop {
            let mut woke = false;
            for k in 0..self.scratch.pairs.len() {
                let (a, b) = self.scratch.pairs[k];
                let kinds = &self.scratch.kinds;
                if kinds[a as usize] != BodyKind::Sleeping
                    && kinds[b as usize] != BodyKind::Sleeping
                {
                    continue;
                }
                let (ba, bb) = (&self.bodies[a as usize], &self.bodies[b as usize]);
                let sleeper = if ba.is_awake_dynamic() && bb.sleeping {
                    b
                } else if bb.is_awake_dynamic() && ba.sleeping {
                    a
                } else {
                    continue;
                };
                let margin = contact_margin(ba, bb, dt, &self.settings);
                if !collide(&ba.shape, &ba.pose, &bb.shape, &bb.pose, margin).is_empty() {
                    self.wake_island(sleeper);
                    woke = true;
                }
            }
            if !woke {
                return any;
            }
            any = true;
        }
    }

    /// Copies awake dynamic bodies into the solver arrays (index 0 = static dummy). Kept out of line
    /// (once per step) so profiles show its cost.
    #[inline(never)]
    fn build_solver_bodies(&mut self) {
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

    /// Step 2: merges the sorted pairs with last step's sorted contacts; runs the narrow phase on pairs
    /// with an awake body; keeps contacts of pairs where neither body is awake (sleeping islands keep
    /// their impulses for when they wake). Kept out of line (called once per step) so profiles show its
    /// cost apart from `step`'s.
    #[inline(never)]
    fn update_contacts(&mut self, dt: f32) {
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
            let manifold = collide(&ba.shape, &ba.pose, &bb.shape, &bb.pose, margin);
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

    /// Step 3: layers the contact graph by BFS from static bodies and builds the constraints in layer
    /// order.
    fn prepare_constraints(&mut self, dt: f32) {
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
        s.links.extend(s.graph.color_order.iter().map(|&color_key| {
            let rank = (color_key & 0xffff_ffff) as usize;
            let c = &self.contacts[(s.graph.order[rank] & 0xffff_ffff) as usize];
            (s.solver_index[c.a as usize], s.solver_index[c.b as usize])
        }));
        self.active_contacts = s.links.len();

        // Bodies around a mass ratio (see `contact_solver`, "Mass-ratio sweeps"): both bodies of a
        // dynamic–dynamic contact whose masses differ by the threshold or more are marked; so is a
        // body that carries many times its own mass in bodies resting on it (a light plank under a
        // crowd: no single contact has a ratio, but the load has), and the bodies on it.
        let threshold = self.settings.mass_ratio_threshold.max(1.0);
        s.mass_ratio_bodies.clear();
        s.mass_ratio_bodies.resize(n, false);
        // Per body, the mass of its dynamic neighbours: a bound on the load resting on it.
        s.load.clear();
        s.load.resize(n, 0.0);
        let mut any = false;
        for &(a, b) in &s.links {
            let (a, b) = (a as usize, b as usize);
            let (inv_a, inv_b) = (s.motions[a].inv_mass, s.motions[b].inv_mass);
            if a != 0 && b != 0 {
                s.load[a] += 1.0 / inv_b;
                s.load[b] += 1.0 / inv_a;
                if inv_a.max(inv_b) >= threshold * inv_a.min(inv_b) {
                    s.mass_ratio_bodies[a] = true;
                    s.mass_ratio_bodies[b] = true;
                    any = true;
                }
            }
        }
        if let Some(up) = (-self.settings.gravity).try_normalize() {
            any |= mark_heavy_loads(
                &self.contacts,
                &s.solver_index,
                &s.motions,
                up,
                &mut s.load,
                &mut s.mass_ratio_bodies,
            );
        }
        // Every contact touching a marked body gets the extra sweeps.
        s.mass_ratio_constraints.clear();
        if any && self.settings.mass_ratio_iterations > 0 {
            for (i, &(a, b)) in s.links.iter().enumerate() {
                if s.mass_ratio_bodies[a as usize] || s.mass_ratio_bodies[b as usize] {
                    s.mass_ratio_constraints.push(i as u32);
                }
            }
        }
        // The shock pass only matters where one body supports the other (between bodies of one layer it
        // would be a second normal pass), and only around a mass ratio: it removes approach without
        // recording an impulse, so friction cannot see the load it carries. Where masses are alike the
        // soft solve converges on its own (stacks and pyramids stand without it) and friction under a
        // pushed stack stays Coulomb's; where they differ it is what keeps a heavy box on a light one.
        // Filtered every step from the (possibly reused) full layer order. The shock pass reads scalar
        // constraints: `shock_slot` says which constraints keep one, and where.
        let (links, marked, levels) = (&s.links, &s.mass_ratio_bodies, &s.graph.levels);
        s.shock_order.clear();
        s.shock_order
            .extend(s.graph.layer_order.iter().copied().filter(|&i| {
                let (a, b) = links[i as usize];
                levels[a as usize] != levels[b as usize]
                    && (marked[a as usize] || marked[b as usize])
            }));
        s.shock_slot.clear();
        s.shock_slot.resize(s.links.len(), u32::MAX);
        for &i in &s.shock_order {
            s.shock_slot[i as usize] = 0;
        }
        for (kept, slot) in s
            .shock_slot
            .iter_mut()
            .filter(|slot| **slot == 0)
            .enumerate()
        {
            *slot = kept as u32;
        }

        s.wide.clear();
        s.shock_rows.clear();
        for (i, &color_key) in s.graph.color_order.iter().enumerate() {
            let color = (color_key >> 35) as u32;
            let rank = (color_key & 0xffff_ffff) as usize;
            let k = (s.graph.order[rank] & 0xffff_ffff) as usize;
            let c = &self.contacts[k];
            let (a, b) = s.links[i];
            let source = LaneSource {
                contact: k as u32,
                a,
                b,
                x_a: self.bodies[c.a as usize].pose.position,
                x_b: self.bodies[c.b as usize].pose.position,
                moved_a: moved_since(&c.pose_a, &self.bodies[c.a as usize].pose),
                moved_b: moved_since(&c.pose_b, &self.bodies[c.b as usize].pose),
                softness: if a == 0 || b == 0 {
                    static_softness
                } else {
                    contact_softness
                },
            };
            s.wide.push(color, SERIAL_COLOR, c.manifold.len, source);
        }
        s.wide.build(&self.contacts, &s.solver_bodies, &s.motions);
        // The shock pass's rows, in solve order as `shock_slot` numbers them, with the friction rows
        // the lanes prepared.
        if !s.shock_order.is_empty() {
            for (i, &slot) in s.shock_slot.iter().enumerate() {
                if slot == u32::MAX {
                    continue;
                }
                let rank = (s.graph.color_order[i] & 0xffff_ffff) as usize;
                let c = &self.contacts[(s.graph.order[rank] & 0xffff_ffff) as usize];
                let (a, b) = s.links[i];
                let side = |index: u32, body: u32| Side {
                    index,
                    position: self.bodies[body as usize].pose.position,
                    level: s.graph.levels[index as usize],
                };
                s.shock_rows.push(contact_solver::prepare_shock(
                    c,
                    &side(a, c.a),
                    &side(b, c.b),
                    s.wide.friction_rows(i as u32),
                ));
            }
        }
        s.wide
            .groups_of(&s.mass_ratio_constraints, &mut s.mass_ratio_groups);
        s.shock_visit.clear();
        s.shock_visit
            .extend(s.shock_order.iter().map(|&i| s.shock_slot[i as usize]));
    }

    /// Step 3a: the layers, colouring and orders of the contact graph, from the graph key
    /// `prepare_constraints` has just computed and swapped into `previous_graph_key` (per contact:
    /// its bodies' solver indices and its lane-group kind).
    #[inline(never)]
    fn order_constraints(&mut self) {
        let s = &mut self.scratch;
        let keys: &[(u32, u32, u8)] = &s.previous_graph_key;
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

    /// Steps 4 and 5: the sub-steps, restitution and storing impulses.
    fn solve(&mut self, dt: f32) {
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
            max_push_out: set.max_push_out_velocity,
            linear_slop: set.linear_slop,
        };
        let s = &mut self.scratch;
        for _ in 0..substeps {
            // Every sub-step starts alike: as if the pass before had gone forward, its first pass
            // visits the points backward.
            let mut last_order = PointOrder::Forward;
            integrate_velocities(&mut s.solver_bodies, &s.motions, &velocity_step);
            s.wide.warm_start(&mut s.solver_bodies);
            s.solve_passes::<true>(
                &params,
                set.iteration_count(),
                set.mass_ratio_iterations,
                &mut last_order,
            );
            if set.shock_propagation && !s.shock_order.is_empty() {
                for &i in &s.shock_order {
                    let slot = s.shock_slot[i as usize] as usize;
                    s.shock_rows[slot].bias_mean = s.wide.bias_mean(i);
                }
                shock_pass(&s.shock_rows, &s.shock_visit, &mut s.solver_bodies);
            }
            integrate_positions(&mut s.solver_bodies, &mut s.motions, h);
            s.solve_passes::<false>(&params, 1, set.mass_ratio_iterations, &mut last_order);
        }
        s.wide
            .apply_restitution(&mut s.solver_bodies, set.restitution_threshold);
        self.max_penetration = s.wide.store_impulses(&s.solver_bodies, &mut self.contacts);
    }

    /// Step 6a: copies solver results back to the bodies and clears forces.
    ///
    /// Only awake dynamic bodies can hold a force or torque (`apply_force_at_point` wakes the body
    /// and ignores static ones, `set_static` clears them), and every one of them has a solver body:
    /// clearing those is clearing all, without touching the sleeping and static bodies.
    #[inline(never)]
    fn write_back(&mut self) {
        let s = &self.scratch;
        let n = s.solver_bodies.len().min(s.motions.len());
        for (sb, m) in s.solver_bodies[1.min(n)..n]
            .iter()
            .zip(&s.motions[1.min(n)..n])
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

    /// Step 6b: islands over touching contacts between awake bodies; an island whose bodies all rested
    /// for `time_to_sleep` goes to sleep with zero velocity.
    #[inline(never)]
    fn update_sleep(&mut self, dt: f32) {
        let set = &self.settings;
        let s = &mut self.scratch;
        let n = s.solver_bodies.len();
        let (lin2, ang2) = (
            set.sleep_linear_threshold * set.sleep_linear_threshold,
            set.sleep_angular_threshold * set.sleep_angular_threshold,
        );
        s.sleep_times.clear();
        s.sleep_times.push(0.0);
        let mut rested = false;
        for m in &s.motions[1..] {
            let body = &mut self.bodies[m.body as usize];
            if body.linear_velocity.length_squared() < lin2
                && body.angular_velocity.length_squared() < ang2
            {
                body.sleep_time += dt;
            } else {
                body.sleep_time = 0.0;
            }
            s.sleep_times.push(body.sleep_time);
            rested |= body.sleep_time >= set.time_to_sleep;
        }
        // An island sleeps when all its bodies have rested long enough: none has, none sleeps (the
        // usual case in a moving scene, which thus skips the islands).
        if !rested {
            return;
        }
        s.islands.reset(n);
        for &(a, b) in &s.links {
            if a != 0 && b != 0 {
                s.islands.union(a, b);
            }
        }
        s.islands
            .sleepy_members(&s.sleep_times, set.time_to_sleep, &mut s.sleepy);
        if s.sleepy.is_empty() {
            return;
        }
        s.islands.reset_chains(n);
        for &i in &s.sleepy {
            let body_index = s.motions[i as usize].body;
            if let Some(previous) = s.islands.chain(i, body_index) {
                self.bodies[previous as usize].sleep_next = body_index;
            }
            let body = &mut self.bodies[body_index as usize];
            body.sleeping = true;
            body.linear_velocity = Vec3::ZERO;
            body.angular_velocity = Vec3::ZERO;
        }
        for &i in &s.sleepy {
            let (first, last) = s.islands.chain_ends(i);
            self.bodies[last as usize].sleep_next = first;
        }
    }
}

/// Cosine of the steepest contact normal (from vertical) through which a body counts as resting on
/// another: 45°.
const RESTING_MIN_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// A body carrying this many times its own mass in bodies resting on it gets the mass-ratio sweeps.
/// Measured on a plank under 100 one-kilogram balls with no extra sweeps: 6 kg (16.7:1) holds them
/// within 15 µm, 3 kg (33:1) lets them jiggle by 12 mm (0.26 mm with the sweeps). Far above what a
/// pile makes (a 0.27 kg ball would need nine 0.5 kg boxes resting on it), so crowds pay nothing.
const HEAVY_LOAD_RATIO: f32 = 16.0;

/// Marks (in `marked`, per solver body) every awake body carrying at least [`HEAVY_LOAD_RATIO`] times
/// its own mass in awake bodies resting on it directly (contact normal within 45° of `up`), and those
/// bodies; returns whether it marked any. `load` comes in holding, per solver body, the mass of all its
/// dynamic neighbours (a bound on what rests on it) and is then scratch.
///
/// Why: a plank under a crowd of balls has no mass ratio at any one contact, yet Gauss–Seidel
/// converges on it as slowly as under one heavy body (each sweep moves it by its share of the total),
/// so it needs the same extra sweeps.
fn mark_heavy_loads(
    contacts: &[Contact],
    solver_index: &[u32],
    motions: &[SolverMotion],
    up: Vec3,
    load: &mut [f32],
    marked: &mut [bool],
) -> bool {
    // (bottom, top) solver indices of a contact where one body rests on the other.
    let resting = |c: &Contact| {
        let (a, b) = (solver_index[c.a as usize], solver_index[c.b as usize]);
        let tilt = c.manifold.normal.dot(up);
        if a == 0 || b == 0 || tilt.abs() < RESTING_MIN_COS {
            None
        } else if tilt > 0.0 {
            // The normal points from A to B, so B is on top.
            Some((a as usize, b as usize))
        } else {
            Some((b as usize, a as usize))
        }
    };
    let heavy = |load: &[f32], i: usize| load[i] * motions[i].inv_mass >= HEAVY_LOAD_RATIO;
    // The bound rules out almost every step.
    if !(1..motions.len()).any(|i| heavy(load, i)) {
        return false;
    }
    load.fill(0.0);
    for (bottom, top) in contacts.iter().filter_map(resting) {
        load[bottom] += 1.0 / motions[top].inv_mass;
    }
    let mut any = false;
    for (bottom, top) in contacts.iter().filter_map(resting) {
        if heavy(load, bottom) {
            marked[bottom] = true;
            marked[top] = true;
            any = true;
        }
    }
    any
}

/// How much each awake body's broad-phase box is grown for reuse, as a fraction of its largest edge
/// (a 1 m box: 10 cm). Larger keeps the broad phase's pairs valid longer but adds candidates to filter.
const FAT_MARGIN: f32 = 0.1;

/// After this many grid runs in a row whose candidates were never reused (something always
/// leaves its fat box, as in a raining crowd), the boxes stay exact except on every `FAT_RETRY`th
/// run: there fat boxes would only make each run costlier.
const FAT_GIVE_UP: u32 = 4;
const FAT_RETRY: u32 = 16;

/// How far apart two bodies' surfaces may be and still get (speculative) contact points this step:
/// `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance`, m.
///
/// A moving body against a static or sleeping one gets gravity's reach too (see `fast_bodies`).
fn contact_margin(ba: &Body, bb: &Body, dt: f32, settings: &Settings) -> f32 {
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
    use super::*;
    use crate::geometry::{Pose, Shape};

    fn floor(world: &mut World) -> BodyId {
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ))
    }

    fn unit_box_at(y: f32) -> BodyDesc {
        BodyDesc::dynamic(
            Shape::cuboid(Vec3::splat(0.5)),
            Pose::from_position(Vec3::new(0.0, y, 0.0)),
            1.0,
        )
    }

    /// A 2D pyramid of unit boxes, `base` in the bottom row, 5 cm apart, on the floor: the physics
    /// layer's own small copy of `scene::cases::pyramid` (it must not import the scene layer).
    fn pyramid_world(base: usize) -> World {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        for row in 0..base {
            let count = base - row;
            for i in 0..count {
                let x = (i as f32 - 0.5 * (count as f32 - 1.0)) * 1.05;
                let mut desc = unit_box_at(0.5 + row as f32);
                desc.pose.position.x = x;
                world.add_body(desc);
            }
        }
        world
    }

    fn run(world: &mut World, seconds: f32) {
        let steps = (seconds / world.settings().dt).round() as usize;
        for _ in 0..steps {
            world.step();
        }
    }

    /// One body with more contacts than there are colours: the overflow colour's constraints share
    /// that body, so they are solved one per lane group; the balls must rest on the plank all the same,
    /// whether the plank is heavy (100 kg) or light (3 kg under 100 one-kilogram balls: no mass ratio
    /// at any contact, 33:1 in load, which `mark_heavy_loads` finds; without it the balls jiggle by
    /// 12 mm).
    #[test]
    fn a_body_with_more_contacts_than_colours_still_holds_everything_up() {
        for plank_mass in [100.0, 3.0] {
            let mut world = World::new(Settings {
                sleep: false,
                ..Settings::default()
            });
            floor(&mut world);
            let plank = world.add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::new(6.0, 0.1, 6.0)),
                Pose::from_position(Vec3::new(0.0, 0.1, 0.0)),
                plank_mass,
            ));
            let radius = 0.25;
            let mut balls = Vec::new();
            for i in 0..10 {
                for k in 0..10 {
                    let x = -4.5 + i as f32;
                    let z = -4.5 + k as f32;
                    balls.push(world.add_body(BodyDesc::dynamic(
                        Shape::sphere(radius),
                        Pose::from_position(Vec3::new(x, 0.2 + radius, z)),
                        1.0,
                    )));
                }
            }
            run(&mut world, 2.0);
            let serial = world
                .scratch
                .graph
                .color_order
                .iter()
                .filter(|&&key| (key >> 35) as u32 == SERIAL_COLOR)
                .count();
            assert!(serial > 0, "no constraint reached the serial colour");
            let top = world.body(plank).pose.position.y + 0.1;
            for &ball in &balls {
                let y = world.body(ball).pose.position.y;
                assert!(
                    (y - (top + radius)).abs() < 0.001,
                    "{plank_mass} kg plank: ball at {y}, plank top {top}"
                );
            }
            let plank_y = world.body(plank).pose.position.y;
            assert!(
                (plank_y - 0.1).abs() < 0.001,
                "{plank_mass} kg plank at {plank_y}"
            );
            assert!(world.max_penetration() < 0.01);
        }
    }

    /// The layers, layer order, colouring and solve order of the current contact graph, computed the
    /// plain way (lists of neighbours, a `VecDeque`, a comparison sort): `(levels, contact indices in
    /// layer order, color_order, layer_order)`.
    fn reference_order(world: &World) -> (Vec<u32>, Vec<u32>, Vec<u64>, Vec<u32>) {
        let s = &world.scratch;
        let n = s.solver_bodies.len();
        let edges: Vec<(usize, usize, u8)> = world
            .contacts
            .iter()
            .map(|c| {
                (
                    s.solver_index[c.a as usize] as usize,
                    s.solver_index[c.b as usize] as usize,
                    kind_of(c.manifold.len),
                )
            })
            .collect();
        let mut levels = vec![u32::MAX; n];
        levels[0] = 0;
        let mut neighbours = vec![Vec::new(); n];
        let mut queue = std::collections::VecDeque::new();
        for &(a, b, _) in &edges {
            if a != 0 && b != 0 {
                neighbours[a].push(b);
                neighbours[b].push(a);
            } else if a != 0 || b != 0 {
                let d = a | b;
                if levels[d] != 1 {
                    levels[d] = 1;
                    queue.push_back(d);
                }
            }
        }
        while let Some(i) = queue.pop_front() {
            for &j in &neighbours[i] {
                if levels[j] == u32::MAX {
                    levels[j] = levels[i] + 1;
                    queue.push_back(j);
                }
            }
        }
        let mut order: Vec<(u32, usize)> = edges
            .iter()
            .enumerate()
            .filter(|&(_, &(a, b, _))| a != 0 || b != 0)
            .map(|(k, &(a, b, _))| (levels[a].min(levels[b]), k))
            .collect();
        order.sort();
        let mut masks = vec![0u64; n];
        let mut color_order: Vec<u64> = order
            .iter()
            .enumerate()
            .map(|(rank, &(_, k))| {
                let (a, b, kind) = edges[k];
                let color = (!(masks[a] | masks[b])).trailing_zeros().min(SERIAL_COLOR);
                for body in [a, b] {
                    if body != 0 {
                        masks[body] |= 1 << color;
                    }
                }
                let group = 8 * u64::from(color) + 2 * u64::from(kind) + u64::from(a == 0);
                group << 32 | rank as u64
            })
            .collect();
        color_order.sort();
        let mut layer_order = vec![0; order.len()];
        for (position, &key) in color_order.iter().enumerate() {
            layer_order[(key & 0xffff_ffff) as usize] = position as u32;
        }
        let order = order.iter().map(|&(_, k)| k as u32).collect();
        (levels, order, color_order, layer_order)
    }

    /// A heap of boxes and balls dropped onto the floor (contacts come and go every step), and
    /// two boxes touching each other high above it (a contact not connected to any static body).
    #[test]
    fn the_constraint_order_is_the_plain_bfs_and_greedy_colouring_of_the_contact_graph() {
        let mut world = World::new(Settings {
            sleep: false,
            ..Settings::default()
        });
        floor(&mut world);
        for i in 0..48 {
            let (x, z, y) = ((i % 4) as f32, ((i / 4) % 4) as f32, (i / 16) as f32);
            let position = Vec3::new(0.9 * x - 1.5, 0.5 + 0.95 * y, 0.9 * z - 1.5);
            let shape = if i % 3 == 0 {
                Shape::sphere(0.45)
            } else {
                Shape::cuboid(Vec3::splat(0.45))
            };
            world.add_body(BodyDesc::dynamic(shape, Pose::from_position(position), 1.0));
        }
        world.add_body(unit_box_at(30.0));
        world.add_body(unit_box_at(31.0));
        let mut unconnected = 0;
        for _ in 0..40 {
            world.step();
            let (levels, order, color_order, layer_order) = reference_order(&world);
            let s = &world.scratch;
            assert_eq!(s.graph.levels, levels);
            let ours: Vec<u32> = s.graph.order.iter().map(|&key| key as u32).collect();
            assert_eq!(ours, order);
            assert_eq!(s.graph.color_order, color_order);
            assert_eq!(s.graph.layer_order, layer_order);
            unconnected += usize::from(levels.contains(&u32::MAX));
        }
        assert!(
            unconnected > 20,
            "the pair in the air was seen {unconnected} times"
        );
    }

    #[test]
    fn a_step_clears_the_force_it_applied() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let id = world.add_body(unit_box_at(0.5));
        world.apply_force_at_point(id, Vec3::new(5.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
        world.step();
        assert_eq!(world.body(id).force, Vec3::ZERO);
        assert_eq!(world.body(id).torque, Vec3::ZERO);
        assert!(world.body(id).linear_velocity().x > 0.0);
    }

    #[test]
    fn a_ball_on_a_frictionless_floor_keeps_its_speed() {
        let mut world = World::new(Settings::default());
        let f = floor(&mut world);
        world.set_static(f, true);
        let mut ball = BodyDesc::dynamic(
            Shape::sphere(0.5),
            Pose::from_position(Vec3::new(-10.0, 0.5, 0.0)),
            1.0,
        );
        ball.friction = 0.0;
        ball.linear_velocity = Vec3::new(3.0, 0.0, 0.0);
        let id = world.add_body(ball);
        run(&mut world, 3.0);
        let v = world.body(id).linear_velocity();
        assert!((v.x - 3.0).abs() < 1e-3, "{v}");
        assert!(v.y.abs() < 1e-2, "{v}");
    }

    #[test]
    fn a_box_dropped_on_the_floor_comes_to_rest_on_it_and_falls_asleep() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let id = world.add_body(unit_box_at(2.0));
        run(&mut world, 3.0);
        let body = world.body(id);
        assert!(
            (body.pose().position.y - 0.5).abs() < 0.01,
            "{:?}",
            body.pose()
        );
        assert!(body.is_sleeping());
        assert_eq!(world.awake_count(), 0);
        assert!(world.max_penetration() < 0.01);
    }

    #[test]
    fn a_force_wakes_a_sleeping_stack_and_torque_is_r_cross_f() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let lower = world.add_body(unit_box_at(0.5));
        let upper = world.add_body(unit_box_at(1.5));
        run(&mut world, 2.0);
        assert!(world.body(lower).is_sleeping() && world.body(upper).is_sleeping());
        // A sideways push at the top face of the upper box: the whole island wakes.
        let force = Vec3::new(50.0, 0.0, 0.0);
        let point = Vec3::new(0.0, 2.0, 0.0);
        world.apply_force_at_point(upper, force, point);
        assert!(!world.body(lower).is_sleeping() && !world.body(upper).is_sleeping());
        let r = point - world.body(upper).pose().position;
        assert!((world.body(upper).torque - r.cross(force)).length() < 1e-4);
    }

    #[test]
    fn changing_gravity_wakes_a_sleeping_body_and_it_follows() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let id = world.add_body(unit_box_at(0.5));
        run(&mut world, 2.0);
        assert!(world.body(id).is_sleeping());
        world.set_gravity(Vec3::new(0.0, 9.81, 0.0));
        assert!(!world.body(id).is_sleeping());
        run(&mut world, 0.5);
        assert!(world.body(id).pose().position.y > 1.0);
    }

    #[test]
    fn an_impulse_at_the_centre_changes_only_the_linear_velocity() {
        let mut world = World::new(Settings {
            gravity: Vec3::ZERO,
            ..Settings::default()
        });
        let id = world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(0.5, 0.25, 1.0)),
            Pose::IDENTITY,
            2.0,
        ));
        world.apply_impulse_at_point(id, Vec3::new(4.0, 0.0, 0.0), Vec3::ZERO);
        assert_eq!(world.body(id).linear_velocity(), Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(world.body(id).angular_velocity(), Vec3::ZERO);
        world.apply_impulse_at_point(id, Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
        assert!(world.body(id).angular_velocity().z > 0.0);
    }

    #[test]
    fn freezing_keeps_the_pose_and_drops_velocity_and_force_unfreezing_falls() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let id = world.add_body(unit_box_at(5.0));
        run(&mut world, 0.5);
        world.apply_force_at_point(id, Vec3::new(100.0, 0.0, 0.0), Vec3::new(0.0, 5.0, 0.0));
        let frozen_at = *world.body(id).pose();
        world.set_static(id, true);
        run(&mut world, 1.0);
        let body = world.body(id);
        assert_eq!(*body.pose(), frozen_at);
        assert_eq!(body.linear_velocity(), Vec3::ZERO);
        assert_eq!(world.awake_count(), 0);
        world.set_static(id, false);
        run(&mut world, 0.2);
        let body = world.body(id);
        assert!(
            body.linear_velocity().y < -1.0,
            "{}",
            body.linear_velocity()
        );
        assert!(body.linear_velocity().x.abs() < 1e-6, "no stale force");
    }

    #[test]
    fn unfreezing_a_support_wakes_the_sleeping_box_on_it() {
        let mut world = World::new(Settings::default());
        let support = world.add_body(unit_box_at(0.5));
        let top = world.add_body(unit_box_at(1.5));
        world.set_static(support, true);
        run(&mut world, 2.0);
        assert!(world.body(top).is_sleeping());
        world.set_static(support, false);
        assert!(!world.body(top).is_sleeping());
        run(&mut world, 0.5);
        assert!(
            world.body(top).pose().position.y < 1.0,
            "falls with its support"
        );
    }

    #[test]
    fn static_bodies_get_no_solver_body() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        world.add_body(unit_box_at(0.5));
        world.step();
        // The dummy plus one dynamic box.
        assert_eq!(world.scratch.solver_bodies.len(), 2);
        assert_eq!(world.contact_count(), 1);
    }

    #[test]
    fn a_fast_ball_stops_at_a_thin_wall_instead_of_tunnelling() {
        let mut world = World::new(Settings {
            gravity: Vec3::ZERO,
            ..Settings::default()
        });
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(0.05, 2.0, 2.0)),
            Pose::from_position(Vec3::new(5.0, 0.0, 0.0)),
        ));
        let mut ball = BodyDesc::dynamic(Shape::sphere(0.1), Pose::IDENTITY, 1.0);
        ball.linear_velocity = Vec3::new(200.0, 0.0, 0.0);
        let id = world.add_body(ball);
        run(&mut world, 0.5);
        let x = world.body(id).pose().position.x;
        assert!(x < 4.95 - 0.1 + 0.01, "ball at x = {x}");
    }

    #[test]
    fn the_same_scene_gives_bit_identical_results() {
        let mut a = pyramid_world(5);
        let mut b = pyramid_world(5);
        run(&mut a, 1.0);
        run(&mut b, 1.0);
        for (x, y) in a.bodies().iter().zip(b.bodies()) {
            assert_eq!(x.pose(), y.pose());
        }
    }

    #[test]
    fn reused_broad_phase_pairs_are_exactly_those_of_a_fresh_broad_phase() {
        let mut world = pyramid_world(6);
        world.settings_mut().sleep = false;
        let mut fresh = BroadPhase::new();
        let mut expected = Vec::new();
        let mut reused_steps = 0;
        for _ in 0..120 {
            let before = world.scratch.candidates.clone();
            world.step();
            let s = &world.scratch;
            if s.candidates == before {
                reused_steps += 1;
            }
            fresh.find_pairs(&s.aabbs, &s.kinds, &mut expected);
            assert_eq!(s.pairs, expected);
        }
        assert!(reused_steps > 60, "reused on {reused_steps} of 120 steps");
    }

    #[test]
    fn bad_input_is_ignored_and_never_produces_nan() {
        let mut world = World::new(Settings::default());
        floor(&mut world);
        let id = world.add_body(unit_box_at(0.5));
        world.apply_force_at_point(id, Vec3::NAN, Vec3::ZERO);
        world.apply_impulse_at_point(id, Vec3::new(1e30, 0.0, 0.0), Vec3::new(0.0, 1e30, 0.0));
        world.apply_force_at_point(BodyId(99), Vec3::ONE, Vec3::ZERO);
        run(&mut world, 1.0);
        let body = world.body(id);
        assert!(body.pose().is_finite() && body.linear_velocity().is_finite());
        assert!(body.linear_velocity().length() <= world.settings().max_linear_speed * 1.001);
    }
}
