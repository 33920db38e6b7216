//! **Reuse** (`Settings::statics_reuse`). The statics read where a pile's bodies are, what they
//! weigh and what else acts on them, and how its contacts touch; on a pile at rest none of that
//! changes, and finding the same loads again every step was a sixth of a resting pyramid's
//! instructions. So each contact keeps what the statics gave it ([`KeptStatics`]) and the world
//! where they saw each body ([`SeenAt`]), and an island is given its kept results, nothing fed, while
//! it stays still: every body in it has moved and will move over the step less than
//! [`STILL_TOLERANCE`] from where they last saw it, is acted on by gravity and its contacts alone
//! (no applied force or torque, hold, joint or mass-ratio mark, then or now) and has the same
//! number of contacts, and every contact kept its manifold (a rebuilt one starts with nothing
//! kept) and its ends' standing (awake or not). One body that fails makes its whole island's
//! statics found afresh, since a load set down at its top reaches every support under it.
//!
//! What the statics feed is a change since they last fed it (a friction demand, an indeterminate
//! support's load, a level face's moment, each compared with what the contact kept of the last
//! one), so a still step feeds nothing and the next step found afresh feeds what changed over
//! both: a pile that leans by a micrometre is fed its lean once it adds up to the tolerance, not
//! lost. What is not a change is reused as found: the preloads, a determinate support's whole
//! moment (`pressure_offset`) and which supports are determinate. An island kept awake at rest
//! moves a nanometre or two a step, so its statics are found only every so often: on 7 of the
//! spaced 20-row pyramid's first 120 steps, on 121 of the touching one's first 600 (one of its
//! 210 boxes passes the tolerance every few steps), on 2 of 600 for two touching pyramids of six
//! rows (2026-12-02). A pile struck, pushed, held or still settling has them found every step
//! as before. The kept results are world state (in the contacts, and beside the bodies in
//! `World::statics_seen`; snapshots copy both), so a restored world steps bit for bit as the
//! original; new settings forget them (`World::forget_kept_statics`).
//!
//! **The lanes are not kept** (tried 2026-12-02). On a step on which every island's statics are
//! kept and the contact graph is the one of the last step, the prepared lane groups could be kept
//! too (only their per-step fields reset: the separations moved to where the last relax pass left
//! them, the anchors to where they ended, the impact and shock-pass buffers zeroed), skipping the
//! contacts' facts, the packing and `WideContacts::build`. On the touching 20-row pyramid that is
//! 19 % fewer instructions over 600 steps (the spaced one 18 % over 120), 10 to 22 % less time in
//! alternated runs, every test of `tests/physics/rest.rs` and `towers.rs` but one passing. The one
//! is the reason: the lanes are scratch, a cache that a step must not depend on, and a world
//! restored into fresh scratch rebuilt them from its poses where the original kept them, and
//! stepped to other bits
//! (`a_still_pile_keeps_its_statics_and_stands_as_when_they_are_found_every_step`). What can be
//! kept exactly is a lane's geometry computed from world state alone (the contact's manifold and
//! the poses it was followed at, not followed while still, and each body's inertia at that pose's
//! rotation, not the solver's): about half of `build` by callgrind's line counts (an estimate; that
//! variant was not built), some 8 % of the touching pyramid's instructions less the inertias it
//! would compute, against the 21 % its speed target needs.

use glam::{Vec3, Vec3A};

use crate::geometry::Pose;
use crate::physics::narrow::contact::{Contact, moved_since};
use crate::physics::prepare::constraint_order::NOT_IN_GRAPH;
use crate::physics::scratch::refill;
use crate::physics::settings::Settings;
use crate::physics::solve::point_drive::PointHold;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::union_find;
use crate::physics::{Body, prepare::held_by_joint};

use super::Statics;

/// How far a body may move from where the statics last saw it, over that time and the step to
/// come (any point of it: translation plus turn times its bounding radius), for its island's
/// statics to be kept, m. A resting pile moves a nanometre or two a step; kept through 100 nm or
/// more, the statics' moments lagged the lean they balance and fed it back in a burst, and a wall
/// of real bricks kept awake at 2 sub-steps stirred at 2.7 µm/s where it stood at 0.2
/// (`a_wall_built_at_two_sub_steps_stands_only_with_balanced_new_supports`); at 10 nm every rest
/// test holds as with the statics found every step. 10 nm is under a float's rounding step for a
/// coordinate of 0.125 m or more (15 nm there, 1.9 µm at 20 m), so for most bodies it means a
/// position that has not changed at all, where the statics would hand down the
/// same loads again: reuse then saves the work, not the accuracy. Far from the origin a body that
/// stirs by a rounding step has its island's statics found, as before.
pub(crate) const STILL_TOLERANCE: f32 = 1e-8;

/// What the statics gave a contact when they were last found for it (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct KeptStatics {
    pub preload: f32,
    pub spring_preload: f32,
    pub pressure_offset: Option<Vec3>,
    pub determinate: bool,
    /// Whether A and B were in the solver (awake and dynamic) then.
    pub in_solver: [bool; 2],
}

/// Where the statics last saw a body, and what acted on it then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SeenAt {
    pub pose: Pose,
    pub inv_mass: f32,
    /// Its contacts in the contact graph.
    pub contacts: u32,
    /// Gravity and its contacts alone acted on it: no applied force or torque, no hold, no joint,
    /// no mass-ratio mark.
    pub quiet: bool,
}

/// What deciding which islands are still reads of the step.
pub(in crate::physics) struct StillInputs<'a> {
    pub contacts: &'a [Contact],
    pub constraint_of: &'a [u32],
    pub links: &'a [(u32, u32)],
    pub solver_bodies: &'a [SolverBody],
    pub motions: &'a [SolverMotion],
    pub solver_index: &'a [u32],
    pub bodies: &'a [Body],
    /// Per body, where the statics last saw it (`World::statics_seen`).
    pub seen: &'a [Option<SeenAt>],
    pub holds: &'a [PointHold],
    pub jointed: &'a [bool],
    pub marked: &'a [bool],
    pub settings: &'a Settings,
}

impl Statics {
    /// Decides per constraint whether its statics are found this step (`fresh`), per solver body
    /// whether its island's are (`body_fresh`) and whether it is quiet (`quiet`); every one is
    /// found when reuse is off.
    pub(super) fn mark_fresh(&mut self, inputs: StillInputs) {
        let StillInputs {
            contacts,
            constraint_of,
            links,
            solver_bodies,
            motions,
            solver_index,
            bodies,
            seen,
            holds,
            jointed,
            marked,
            settings,
        } = inputs;
        let (n_bodies, n) = (motions.len(), links.len());
        let reuse = settings.statics_reuse && settings.preload;
        refill(&mut self.fresh, n, !reuse);
        refill(&mut self.body_fresh, n_bodies, !reuse);
        if !reuse {
            return;
        }
        refill(&mut self.contacts_of, n_bodies, 0);
        for &(a, b) in links {
            self.contacts_of[a as usize] += 1;
            self.contacts_of[b as usize] += 1;
        }
        refill(&mut self.quiet, n_bodies, true);
        refill(&mut self.slow, n_bodies, false);
        for hold in holds {
            self.quiet[solver_index[hold.body.index()] as usize] = false;
        }
        let (dt, gravity) = (settings.dt, Vec3A::from(settings.gravity));
        for k in 1..n_bodies {
            let (m, v) = (&motions[k], &solver_bodies[k]);
            // Read off the solver's copy: a force the accelerations do not show, the statics do
            // not see either.
            let quiet = self.quiet[k]
                && m.linear_accel == gravity
                && m.angular_accel == Vec3A::ZERO
                && !held_by_joint(jointed, m.body)
                && !marked[k];
            self.quiet[k] = quiet;
            // A falling or sliding body is told by its speed alone, without reading the world's.
            let linear = v.v.length() * dt;
            if !(quiet && linear < STILL_TOLERANCE) {
                (self.body_fresh[k], self.slow[k]) = (true, false);
                continue;
            }
            let body = &bodies[m.body as usize];
            let radius = body.shape.bounding_radius();
            let moving = linear + v.w.length() * radius * dt;
            let still = |seen: &SeenAt| {
                let (shift, turn) = moved_since(&seen.pose, &body.pose);
                let moved = shift.length() + turn.length() * radius;
                seen.quiet
                    && seen.inv_mass == body.inv_mass
                    && seen.contacts == self.contacts_of[k]
                    && moved + moving < STILL_TOLERANCE
            };
            self.slow[k] = moving < STILL_TOLERANCE;
            let seen = seen.get(m.body as usize).copied().flatten();
            self.body_fresh[k] = !(self.slow[k] && seen.as_ref().is_some_and(still));
        }
        // Nothing still (a rain): every island is found, and none need be told apart.
        if self.body_fresh[1..].iter().all(|&fresh| fresh) {
            self.fresh.fill(true);
            return;
        }
        // A contact with nothing kept for its ends as they stand makes its island fresh too. Read
        // only between two bodies not fresh already (a contact of a fresh one joins its island to
        // it below): in a rain, where few are still, most contacts are never read.
        for (c, &i) in contacts.iter().zip(constraint_of) {
            if i == NOT_IN_GRAPH {
                continue;
            }
            let (a, b) = links[i as usize];
            let fresh_end = |k: u32| k != 0 && self.body_fresh[k as usize];
            if fresh_end(a) || fresh_end(b) {
                continue;
            }
            if c.statics
                .is_none_or(|kept| kept.in_solver != [a != 0, b != 0])
            {
                self.body_fresh[a as usize] = true;
                self.body_fresh[b as usize] = true;
            }
        }
        // The islands, as far as they hold a body not yet fresh: a contact between two fresh
        // bodies joins nothing that another contact of theirs does not (a still body's path to
        // a fresh one is joined up to the first fresh body on it).
        let island = &mut self.island;
        union_find::reset(island, n_bodies);
        let mut any_still = false;
        for &(a, b) in links {
            let (fresh_a, fresh_b) = (self.body_fresh[a as usize], self.body_fresh[b as usize]);
            any_still |= !(fresh_a || a == 0) || !(fresh_b || b == 0);
            if a != 0 && b != 0 && !(fresh_a && fresh_b) {
                union_find::union(island, a, b);
            }
        }
        if !any_still {
            self.fresh.fill(true);
            return;
        }
        // Fresh islands, by their representative (`body_fresh[0]`, the static dummy's, is not read).
        refill(&mut self.island_fresh, n_bodies, false);
        for k in 1..n_bodies {
            if self.body_fresh[k] {
                self.island_fresh[union_find::find(island, k as u32) as usize] = true;
            }
        }
        for k in 1..n_bodies {
            self.body_fresh[k] = self.island_fresh[union_find::find(island, k as u32) as usize];
        }
        for (fresh, &(a, b)) in self.fresh.iter_mut().zip(links) {
            *fresh = self.body_fresh[a.max(b) as usize];
        }
    }

    /// The kept results of the constraints not found this step: their preloads, moment and
    /// determinacy as kept, and as fed last what the contact kept of it, so that nothing is fed
    /// (see the module docs).
    pub(super) fn fill_kept(&mut self, contacts: &[Contact], constraint_of: &[u32]) {
        for (c, &i) in contacts.iter().zip(constraint_of) {
            if i == NOT_IN_GRAPH || self.fresh[i as usize] {
                continue;
            }
            let i = i as usize;
            let Some(kept) = c.statics else {
                unreachable!("a still island's contacts keep their statics");
            };
            self.preload[i] = kept.preload;
            self.spring_preload[i] = kept.spring_preload;
            self.pressure_offset[i] = kept.pressure_offset;
            self.determinate[i] = kept.determinate;
            self.tangent_demand[i] = c.impulses.fed_tangent;
            self.fed_load[i] = c.impulses.fed_load;
            self.fed_offset[i] = c.impulses.fed_offset;
        }
    }

    /// How many constraints' statics were found this step (the others kept).
    pub(in crate::physics) fn found_count(&self) -> usize {
        self.fresh.iter().filter(|&&fresh| fresh).count()
    }

    /// Whether any constraint's statics are found this step.
    pub(super) fn any_fresh(&self) -> bool {
        self.fresh.contains(&true)
    }

    /// What to keep in the contact of constraint `i` between solver bodies `(a, b)`: what its
    /// statics found this step, if it may be still at the next (both ends slow, the static dummy
    /// always). A contact of a moving body keeps what it kept, which is never read: its island is
    /// found while that body has no pose seen ([`Statics::record_seen`]).
    pub(in crate::physics) fn to_keep(&self, i: usize, (a, b): (u32, u32)) -> Option<KeptStatics> {
        let slow = |k: u32| k == 0 || self.slow[k as usize];
        (self.fresh[i] && slow(a) && slow(b)).then(|| KeptStatics {
            preload: self.preload[i],
            spring_preload: self.spring_preload[i],
            pressure_offset: self.pressure_offset[i],
            determinate: self.determinate[i],
            in_solver: [a != 0, b != 0],
        })
    }

    /// Records in `seen` (per world body) where the statics saw each body of an island they were
    /// found for this step (`motions` are the solver's, `bodies` the world's); none for a body
    /// moving too fast to be still at the next step, so that what is kept never pairs a pose seen
    /// long ago with statics found since. A still island's bodies keep theirs.
    pub(in crate::physics) fn record_seen(
        &self,
        motions: &[SolverMotion],
        bodies: &[Body],
        seen: &mut Vec<Option<SeenAt>>,
    ) {
        seen.resize(bodies.len(), None);
        for (k, motion) in motions.iter().enumerate().skip(1) {
            if !self.body_fresh[k] {
                continue;
            }
            let body = &bodies[motion.body as usize];
            seen[motion.body as usize] = self.slow[k].then(|| SeenAt {
                pose: body.pose,
                inv_mass: body.inv_mass,
                contacts: self.contacts_of[k],
                quiet: self.quiet[k],
            });
        }
    }
}
