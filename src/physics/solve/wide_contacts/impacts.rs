//! Restitution as impacts: what a collision does to the velocities, decided from the velocities at
//! the moment of impact, passed on through chains of touching bodies in the order the impacts
//! happen, then enforced on the velocities the step ends with.
//!
//! The sub-steps solve every contact as plastic: a falling ball stops on the floor, a cradle's
//! striker and row move off together. Once per step, after them, for the steps in which some point
//! of a manifold with restitution was hit faster than the threshold (a *primary* impact):
//!
//! 1. **The moment of impact.** A point's approach speed c₀ = −v_n is read from the velocities at
//!    the start of the step. Within the step the bodies close their separation s₀ under their
//!    relative normal acceleration α, so they meet at c = √(c₀² + 2·α·s₀): energy in free flight,
//!    exact for a ball falling on a floor whatever the sub-step count. α is read from the first
//!    sub-step: each body's velocity change over gravity, applied forces and the warm start (a box
//!    resting on the floor does not accelerate, a falling ball does), over h. The symplectic
//!    sub-steps put positions on the parabola of a body whose velocity is the stored one plus
//!    ½·α·h (h the sub-step), so c₀ is read from that velocity, and a rebound is written back the
//!    same way.
//! 2. **Impacts in the order they happen** (sequential impacts, Guendelman, Bridson & Fedkiw 2003,
//!    "Nonconvex rigid bodies with stacking", §5), on a copy of the start velocities: the rows are
//!    the points that pushed this step, in the islands (through dynamic bodies) of the primary
//!    ones. The first event is every primary point at once, each with Newton's law
//!    v_n⁺ ≥ e·c (simultaneous: a box landing flat hits with four corners). Each later event is
//!    every point that the one before left approaching, with e·(its approach) if that is over the
//!    threshold, else plastic: a cradle's struck ball stops and the next one leaves, so the speed
//!    walks down the row. Points that carried load at the start of the step (a box resting on the
//!    floor) take part in every event as plastic supports (v_n⁺ ≥ 0): resting contacts never
//!    bounce, and a ball dropped on a box on the floor bounces as from the floor. Each event is a
//!    few Gauss–Seidel sweeps over its points and the supports; events stop when nothing
//!    approaches (or after [`MAX_EVENTS`], then one plastic solve of all the points).
//! 3. **Enforcing it.** At every point that took part (supports aside), the events' summed impulse
//!    replaces the sub-steps' plastic one, applied to the end velocities directly; then sweeps over
//!    the same rows set each point's relative normal velocity at the end of the step to the one the
//!    impacts left (corrected for where the rebound leaves from), the point's impulse over the
//!    whole step kept ≥ 0. A support starts from its sub-steps' impulse, which also held up the
//!    weight over the step, and never goes below it.
//!    Positions are the sub-steps': the bodies end the step touching, as they should after an
//!    impact within it. The impulses stored for next step's warm start stay the sub-steps' (a
//!    rebound's impulse would kick bodies that have already parted).
//! 4. **Friction for the rebound.** The sub-steps' friction was bounded by μ times the plastic part
//!    of the normal impulse; the rebound phases 2–3 added, (1 + e)·m·c in all for a ball, gets its
//!    own Coulomb friction at each manifold's centroid, bounded by μ times that added impulse
//!    (Gauss–Seidel sweeps over the rebounding manifolds), and phase 3's sweeps run once more, since
//!    friction at a box's centroid turns it and moves its corners' normal velocities. Without it a
//!    ball sliding through an elastic bounce lost half the tangential impulse of the impact.
//! 5. **Lift-off.** A body the impacts lift off every (static) support it rested on enters free
//!    flight: its velocity is written on the positions' parabola, −½·g·h off the one it leaves
//!    with, as phase 3 writes a rebound.
//!
//! Why not simultaneous impacts (Newton's law at every point against its own approach, as Box2D,
//! Jolt and Rapier do): the cradle's resting points have no approach of their own, so they hold
//! the row together as one body and it moves off as one. Why not impulse propagation over the
//! contact graph's layers (Smith et al. 2012 discuss both): it needs a direction of propagation,
//! which a head-on meeting or a cradle in zero gravity does not have.
//!
//! Why only with restitution: a plastic blow (a 20 g ball of restitution 0 landing at 3.1 m/s on
//! the bench's running-bond wall, `nudge bench rest`) is left to the sub-steps, which one sweep a
//! pass would carry down a course at a time while the wall sinks into its slop band; a resting
//! pile carries it instead, its struck body immovable for the landing's rows
//! (`prepare::preload::blows`, whose rows these events then read: a ball dropped on a box on the
//! floor bounces as from the floor). Run through these events (every contact given a restitution
//! of 10⁻⁹, 2026-12-01, the pile as built, before piles carried blows), the wall woken at 2
//! sub-steps stood (27 mm from where it slept; it fell), but at 4 and 8 it ended further off (9.6
//! and 15.5 mm, against 5.8 and 5.3): the events end the step with the wall still, but its
//! positions are the sub-steps', already sunk.

use glam::Vec3A;

use crate::physics::narrow::contact::Contact;
use crate::physics::solve::contact_solver::FrictionRows;
use crate::physics::solve::solver_body::SolverBody;
use crate::physics::solve::wide_contacts::{
    ColdLanes, GroupKind, GroupRef, ManifoldLanes, SideLanes, WideContacts, with_groups,
};
use crate::physics::union_find;

/// Sweeps at most per event and in the final enforcement: a support chain (a stack) of n points
/// needs about n.
const MAX_SWEEPS: usize = 64;

/// Events at most per step: a cradle of n balls needs n − 1; a body wedged between two elastic
/// walls would exchange forever without a cap.
const MAX_EVENTS: usize = 32;

/// Sweeps stop when no row's impulse changed by more than its effective mass times this, m/s.
const SETTLED_SPEED: f32 = 1e-4;

/// A body whose velocity along a point's normal the impacts changed by less than this did not move
/// there, m/s.
const UNMOVED: f32 = 1e-3;

/// A point approaching slower than this after an event is at rest, m/s.
const APPROACHING: f32 = 1e-4;

/// What the impact pass needs besides the contacts and bodies.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ImpactParams {
    /// Approach speed above which a point bounces, m/s.
    pub threshold: f32,
    /// Sub-step length, s.
    pub h: f32,
    /// Points this close at the start of the step touch (they take part in an impact whether or
    /// not the sub-steps reached them), m.
    pub touching: f32,
    /// Gravity, m/s².
    pub gravity: Vec3A,
}

/// What a row is in the events of phase 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// Hit faster than the threshold at the moment of impact: the first event.
    Primary,
    /// Carried load at the start of the step: plastic in every event.
    Support,
    /// Touching, unloaded: takes part when an event leaves it approaching.
    Free,
}

/// One point, scalar.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ImpactRow {
    a: u32,
    b: u32,
    n: Vec3A,
    rn_a: Vec3A,
    rn_b: Vec3A,
    irn_a: Vec3A,
    irn_b: Vec3A,
    inv_mass_a: f32,
    inv_mass_b: f32,
    normal_mass: f32,
    restitution: f32,
    role: Role,
    /// Added to the start velocities' relative normal velocity to give it at the moment of impact,
    /// m/s.
    shift: f32,
    /// ½·(relative normal acceleration)·h: stored velocity minus the velocity of the positions'
    /// parabola, m/s.
    half_kick: f32,
    /// Whether it takes part in the current event (supports always do).
    in_event: bool,
    /// The relative normal velocity the current event asks at least (phase 2), then the one phase 3
    /// enforces, m/s.
    target: f32,
    /// The current event's accumulated impulse, then phase 3's (starting from the sub-steps'), N·s.
    impulse: f32,
    /// The impulse of every event of phase 2 so far, summed, N·s.
    events_impulse: f32,
    /// The least accumulated impulse a sweep may leave, N·s: 0, but in phase 3 a support's impulse
    /// over the sub-steps.
    least_impulse: f32,
    /// Separation at the start of the step, m.
    separation: f32,
    /// Relative normal acceleration over the first sub-step (gravity, forces, warm start), m/s².
    accel: f32,
    /// Where the row lives: group, lane, point.
    group: GroupRef,
    lane: u8,
    point: u8,
}

impl ImpactRow {
    fn normal_velocity(&self, v: &[(Vec3A, Vec3A)]) -> f32 {
        let (va, wa) = v[self.a as usize];
        let (vb, wb) = v[self.b as usize];
        self.n.dot(vb - va) + wb.dot(self.rn_b) - wa.dot(self.rn_a)
    }

    /// Separation at the end of the sub-steps, to first order as the solver moves it, m.
    fn separation_now(&self, bodies: &[SolverBody]) -> f32 {
        let (a, b) = (&bodies[self.a as usize], &bodies[self.b as usize]);
        self.separation + self.n.dot(b.dp - a.dp) + b.dtheta.dot(self.rn_b)
            - a.dtheta.dot(self.rn_a)
    }

    /// The separation a rebound leaves from: [`Self::separation_now`], but a side the impacts did
    /// not move along the normal (velocities `start` and `post` agree there) is taken where it
    /// started the step. The sub-steps pushed it (a box held by the floor under a falling ball
    /// sinks into its soft supports) and it will come back; the rebound must not leave from where
    /// it sank to.
    fn separation_leaving(
        &self,
        bodies: &[SolverBody],
        start: &[(Vec3A, Vec3A)],
        post: &[(Vec3A, Vec3A)],
    ) -> f32 {
        let moved = |i: u32, rn: Vec3A| {
            let (s, p) = (start[i as usize], post[i as usize]);
            (self.n.dot(p.0 - s.0) + rn.dot(p.1 - s.1)).abs() > UNMOVED
        };
        let (a, b) = (&bodies[self.a as usize], &bodies[self.b as usize]);
        let mut s = self.separation;
        if moved(self.a, self.rn_a) {
            s -= self.n.dot(a.dp) + a.dtheta.dot(self.rn_a);
        }
        if moved(self.b, self.rn_b) {
            s += self.n.dot(b.dp) + b.dtheta.dot(self.rn_b);
        }
        s
    }

    fn apply(&self, v: &mut [(Vec3A, Vec3A)], impulse: f32) {
        let a = &mut v[self.a as usize];
        a.0 -= self.n * (self.inv_mass_a * impulse);
        a.1 -= self.irn_a * impulse;
        let b = &mut v[self.b as usize];
        b.0 += self.n * (self.inv_mass_b * impulse);
        b.1 += self.irn_b * impulse;
    }

    /// One Gauss–Seidel update towards v_n ≥ `target` (with `shift` added to v_n), the accumulated
    /// impulse kept at least `least_impulse`; returns whether it moved by more than its row's
    /// settle amount.
    fn relax(&mut self, v: &mut [(Vec3A, Vec3A)], shift: f32) -> bool {
        let vn = self.normal_velocity(v) + shift;
        let total = (self.impulse + self.normal_mass * (self.target - vn)).max(self.least_impulse);
        let delta = total - self.impulse;
        self.impulse = total;
        self.apply(v, delta);
        delta.abs() > SETTLED_SPEED * self.normal_mass
    }
}

/// Coulomb friction for the rebound of one manifold (phase 4 of the module docs): its friction
/// rows at the centroid, and the bound μ·(the normal impulse the impacts added there).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ReboundFriction {
    a: u32,
    b: u32,
    group: GroupRef,
    lane: u8,
    rows: FrictionRows,
    /// The normal impulse phases 2–3 added over the sub-steps', summed over the points, N·s.
    rebound: f32,
    /// The accumulated tangential impulse along each tangent, N·s.
    impulse: [f32; 2],
}

impl ReboundFriction {
    /// One update of the tangential impulse pair towards no slip at the centroid, clamped as a
    /// pair to μ·rebound; returns whether it moved by more than its settle amount.
    fn relax(&mut self, v: &mut [(Vec3A, Vec3A)]) -> bool {
        let r = &self.rows;
        let ((va, wa), (vb, wb)) = (v[self.a as usize], v[self.b as usize]);
        let slip = |j: usize| r.tangents[j].dot(vb - va) + wb.dot(r.rt_b[j]) - wa.dot(r.rt_a[j]);
        let mut pair = [0, 1].map(|j| self.impulse[j] - r.tangent_mass[j] * slip(j));
        let max = r.friction * self.rebound.max(0.0);
        let length = (pair[0] * pair[0] + pair[1] * pair[1]).sqrt();
        if length > max {
            pair = pair.map(|l| l * (max / length));
        }
        let delta = [pair[0] - self.impulse[0], pair[1] - self.impulse[1]];
        self.impulse = pair;
        let linear = r.tangents[0] * delta[0] + r.tangents[1] * delta[1];
        let a = &mut v[self.a as usize];
        a.0 -= linear * r.inv_mass_a;
        a.1 -= r.irt_a[0] * delta[0] + r.irt_a[1] * delta[1];
        let b = &mut v[self.b as usize];
        b.0 += linear * r.inv_mass_b;
        b.1 += r.irt_b[0] * delta[0] + r.irt_b[1] * delta[1];
        let mass = r.tangent_mass[0].max(r.tangent_mass[1]);
        delta[0].abs().max(delta[1].abs()) > SETTLED_SPEED * mass
    }
}

/// What gathering reads besides the group.
struct GatherFrom<'a> {
    start: &'a [(Vec3A, Vec3A)],
    kicked: &'a [(Vec3A, Vec3A)],
    contacts: &'a [Contact],
    params: ImpactParams,
}

/// Gathers the rows of group `group` (parts `g`, `a`, `cold`): with `all`, every point that pushed
/// this step, touched at its start or carried load then; without, only the primary ones (to learn
/// whether there are any).
#[allow(clippy::needless_range_loop)] // point i indexes the lanes' arrays and the stored impulses
fn gather<const P: usize, const M: usize>(
    (g, a, cold): (&ManifoldLanes<P, M>, &SideLanes<P>, &ColdLanes<P>),
    group: GroupRef,
    from: &GatherFrom,
    all: bool,
    rows: &mut Vec<ImpactRow>,
) {
    let h = from.params.h;
    for k in 0..crate::physics::solve::wide_contacts::LANES {
        let contact = cold.contact[k];
        if contact == u32::MAX {
            continue;
        }
        let restitution = cold.restitution[k];
        if !all && restitution <= 0.0 {
            continue;
        }
        let (ia, ib) = (a.a[k], g.b[k]);
        let n = g.normal.lane(k);
        // The relative normal acceleration the first sub-step gave (before any solve).
        let dv = |i: u32| from.kicked[i as usize].0 - from.start[i as usize].0;
        let a_n = n.dot(dv(ib) - dv(ia)) / h;
        let half_kick = 0.5 * a_n * h;
        let stored = &from.contacts[contact as usize].impulses.normal;
        for i in 0..(cold.count[k] as usize).min(P) {
            let pushed = if group.bouncy {
                cold.max_normal_impulse[i][k] > 0.0
            } else {
                g.impulses[i].normal_impulse[k] > 0.0
            };
            let loaded = stored[i] > 0.0;
            let touching = g.points[i].separation[k] <= from.params.touching;
            if !pushed && !loaded && !touching {
                continue;
            }
            let mut row = ImpactRow {
                a: ia,
                b: ib,
                n,
                rn_a: a.rn_a[i].lane(k),
                rn_b: g.points[i].rn_b.lane(k),
                irn_a: a.irn_a[i].lane(k),
                irn_b: g.impulses[i].irn_b.lane(k),
                inv_mass_a: a.inv_mass_a[k],
                inv_mass_b: g.inv_mass_b[k],
                normal_mass: g.points[i].normal_mass[k],
                restitution,
                role: Role::Free,
                shift: half_kick,
                half_kick,
                in_event: false,
                target: 0.0,
                impulse: 0.0,
                events_impulse: 0.0,
                least_impulse: 0.0,
                group,
                separation: g.points[i].separation[k],
                accel: a_n,
                lane: k as u8,
                point: i as u8,
            };
            // The approach at the moment of impact: c₀ from the parabola's velocity, grown over the
            // separation closed under the approach acceleration −a_n.
            let vn = row.normal_velocity(from.start);
            let c0 = -(vn + half_kick);
            let (closing, gap) = (-a_n, g.points[i].separation[k].max(0.0));
            // A point parting at the start of the step (c₀ < 0) is not struck at it: squared, its
            // parting speed read as an approach, and a cradle's ball leaving its neighbour was
            // pushed off it again at twice its speed. Turning round under its own closing
            // acceleration takes (c + |c₀|)/closing, over a step unless that acceleration is above
            // threshold/dt (60 m/s² at the defaults); what turns it round within a step is another
            // point's blow, which the events meet in their order.
            let c = if c0 > 0.0 || (c0 >= 0.0 && closing > 0.0) {
                (c0 * c0 + 2.0 * closing * gap).max(0.0).sqrt()
            } else {
                c0
            };
            if pushed && restitution > 0.0 && c > from.params.threshold {
                row.role = Role::Primary;
                row.shift = -c - vn;
                row.in_event = true;
                row.target = restitution * c;
            } else if !all {
                continue;
            } else if loaded {
                row.role = Role::Support;
                row.in_event = true;
            }
            rows.push(row);
        }
    }
}

/// Gauss–Seidel sweeps, alternating direction, of `step` over `rows` until no row moves by more
/// than its settle amount (`step` says whether it did), or [`MAX_SWEEPS`].
fn sweep<T>(rows: &mut [T], mut step: impl FnMut(&mut T) -> bool) {
    for s in 0..MAX_SWEEPS {
        let mut moved = false;
        let mut visit = |row: &mut T| moved |= step(row);
        if s % 2 == 0 {
            rows.iter_mut().for_each(&mut visit);
        } else {
            rows.iter_mut().rev().for_each(&mut visit);
        }
        if !moved {
            return;
        }
    }
}

/// Keeps the rows connected through dynamic bodies to a primary row (`parent` and `hit`: scratch).
fn keep_hit_islands(
    rows: &mut Vec<ImpactRow>,
    parent: &mut Vec<u32>,
    hit: &mut Vec<bool>,
    bodies: usize,
) {
    union_find::reset(parent, bodies);
    hit.clear();
    hit.resize(bodies, false);
    // The static dummy (0) joins nothing: a floor does not connect what rests on it.
    let body_of = |row: &ImpactRow| if row.a == 0 { row.b } else { row.a };
    for row in rows.iter() {
        if row.a != 0 && row.b != 0 {
            union_find::union(parent, row.a, row.b);
        }
    }
    for row in rows.iter().filter(|r| r.role == Role::Primary) {
        hit[union_find::find(parent, body_of(row)) as usize] = true;
    }
    rows.retain(|row| hit[union_find::find(parent, body_of(row)) as usize]);
}

impl WideContacts {
    /// Remembers the velocities at the start of the step, for [`Self::apply_impacts`] (only if some
    /// group has restitution).
    pub(crate) fn remember_start_velocities(&mut self, bodies: &[SolverBody]) {
        self.start_velocities.clear();
        if self.schedule.iter().any(|g| g.bouncy) {
            self.start_velocities
                .extend(bodies.iter().map(|b| (b.v, b.w)));
        }
    }

    /// Remembers the velocities after the first sub-step's kick and warm start, for
    /// [`Self::apply_impacts`] (only if [`Self::remember_start_velocities`] kept the start).
    pub(crate) fn remember_kicked_velocities(&mut self, bodies: &[SolverBody]) {
        self.kicked_velocities.clear();
        if !self.start_velocities.is_empty() {
            self.kicked_velocities
                .extend(bodies.iter().map(|b| (b.v, b.w)));
        }
    }

    /// Gathers rows from every group (`all`) or the bouncy ones.
    fn gather_rows(&self, from: &GatherFrom, all: bool, rows: &mut Vec<ImpactRow>) {
        for &g in &self.schedule {
            if !all && !g.bouncy {
                continue;
            }
            let i = g.index as usize;
            with_groups!(&self, g, |gs, _STATIC_A| gather(
                (&gs.hot[i], &gs.side_a[i], &gs.cold[i]),
                g,
                from,
                all,
                rows
            ));
        }
    }

    /// Restitution, once per step after the sub-steps: phases 1–5 of the module docs.
    /// `contacts` still hold the impulses the step started from.
    pub(crate) fn apply_impacts(
        &mut self,
        bodies: &mut [SolverBody],
        contacts: &[Contact],
        params: &ImpactParams,
    ) {
        if self.start_velocities.len() != bodies.len()
            || self.kicked_velocities.len() != bodies.len()
        {
            return;
        }
        let mut rows = std::mem::take(&mut self.impact_rows);
        rows.clear();
        let from = GatherFrom {
            start: &self.start_velocities,
            kicked: &self.kicked_velocities,
            contacts,
            params: *params,
        };
        self.gather_rows(&from, false, &mut rows);
        if !rows.is_empty() {
            rows.clear();
            self.gather_rows(&from, true, &mut rows);
            let (mut parent, mut hit) = (
                std::mem::take(&mut self.impact_islands),
                std::mem::take(&mut self.impact_hit),
            );
            keep_hit_islands(&mut rows, &mut parent, &mut hit, bodies.len());
            (self.impact_islands, self.impact_hit) = (parent, hit);
            let mut post = std::mem::take(&mut self.post_velocities);
            post.clear();
            post.extend_from_slice(&self.start_velocities);
            resolve_events(&mut rows, &mut post, params.threshold);
            // Phase 3: enforce the relative normal velocities the impacts left, written as stored
            // velocities (the parabola's less ½·a_n·h), on the velocities the sub-steps left.
            for row in &mut rows {
                let mut leaving = row.normal_velocity(&post) + row.shift;
                // A rebound leaves from where the point is, on the parabola of the rebound from
                // contact: the sub-steps' last relax may have stopped it short of touching (its
                // speculative row slows the approach to close the gap in the next sub-step), and
                // a struck body held in place may have sunk into its supports.
                let gap = if row.role == Role::Primary {
                    row.separation_leaving(bodies, &self.start_velocities, &post)
                } else {
                    row.separation_now(bodies).max(0.0)
                };
                if leaving > 0.0 {
                    leaving = (leaving * leaving + 2.0 * row.accel * gap).max(0.0).sqrt();
                }
                row.target = leaving - row.half_kick;
                // The sweeps start from what the point pushed over the whole step and may take
                // all of it back (bounded by its last sub-step's push alone, a chain the sub-steps
                // had pushed as one body kept part of that push: three elastic boxes struck
                // off-centre ended with 2 % more energy than they began). But a support keeps what
                // it carried: the events treat it as plastic on the start velocities, which know
                // nothing of the weight it held up before a body lifted off it (allowed to give it
                // back, the floor under a ball rolling into a wall took away its support for the
                // whole step, and the ball hopped 22 % low).
                row.impulse = self.step_impulse(row);
                if row.role == Role::Support {
                    row.least_impulse = row.impulse;
                }
            }
            let mut v = post;
            v.clear();
            v.extend(bodies.iter().map(|b| (b.v, b.w)));
            // At the points that took part in the impacts, the events' impulses replace the
            // sub-steps' plastic ones, applied directly: the end velocities become the events'
            // result plus whatever else the sub-steps did (gravity, forces, other contacts), and
            // the sweeps only correct the rebound for where it leaves from. (Solved for from the
            // sub-steps' velocities instead, a light block squeezed between a wall and a heavy
            // one, eight rows of two faces on one body, was still 20 % off after 64 sweeps.) A
            // support's sub-step impulse also held up the weight over the step, which the events
            // (on the start velocities) do not see: its rows start from it, as before.
            for row in rows.iter_mut().filter(|r| r.role != Role::Support) {
                row.apply(&mut v, row.events_impulse - row.impulse);
                row.impulse = row.events_impulse;
            }
            sweep(&mut rows, |row| row.relax(&mut v, 0.0));
            // Phase 4: friction for the rebound, then the normal velocities again (friction at a
            // box's centroid turns it, and its corners' normal velocities with it).
            self.rebound_friction(&rows, &mut v);
            sweep(&mut rows, |row| row.relax(&mut v, 0.0));
            self.lift_off(&rows, &mut v, params);
            for (body, (lin, ang)) in bodies.iter_mut().zip(&v).skip(1) {
                (body.v, body.w) = (*lin, *ang);
            }
            self.post_velocities = v;
            // The points that took part in the impacts leave it parting or just touching: next
            // step's warm start must not push them apart again (nor count them as carrying load).
            for row in rows.iter().filter(|r| r.role != Role::Support) {
                *self.normal_impulse_mut(row) = 0.0;
            }
        }
        self.impact_rows = rows;
    }

    /// Phase 4: Coulomb friction for the normal impulse phases 2–3 added, manifold by manifold
    /// (`rows` holds a manifold's points one after another), in Gauss–Seidel sweeps over `v`.
    fn rebound_friction(&mut self, rows: &[ImpactRow], v: &mut [(Vec3A, Vec3A)]) {
        let mut manifolds = std::mem::take(&mut self.impact_friction);
        manifolds.clear();
        for row in rows.iter().filter(|r| r.role != Role::Support) {
            let rebound = row.impulse - self.step_impulse(row);
            match manifolds.last_mut() {
                Some(m) if m.group == row.group && m.lane == row.lane => m.rebound += rebound,
                _ => {
                    let (i, k) = (row.group.index as usize, row.lane as usize);
                    let friction_rows =
                        with_groups!(&self, row.group, |gs, _STATIC_A| gs.friction_rows(i, k));
                    manifolds.push(ReboundFriction {
                        a: row.a,
                        b: row.b,
                        group: row.group,
                        lane: row.lane,
                        rows: friction_rows,
                        rebound,
                        impulse: [0.0; 2],
                    });
                }
            }
        }
        manifolds.retain(|m| m.rebound > 0.0 && m.rows.friction > 0.0);
        sweep(&mut manifolds, |m| m.relax(v));
        self.impact_friction = manifolds;
    }

    /// Phase 5: a body the impacts lift off the static supports it rested on enters free flight,
    /// so its velocity is written as a free body's is: on the positions' parabola, −½·g·h off the
    /// velocity it leaves with (as phase 3 writes a rebound). A supported body's velocity is not:
    /// its supports cancel gravity within each sub-step. Left as it was, a ball hopping off a wall
    /// rose (v²/2g)·(1 − g·h/v), 16 % short for a hop at 0.3 m/s (now 0.9 %). Only bodies whose
    /// every support is static and parting are moved: the static world takes the half sub-step of
    /// weight.
    fn lift_off(&mut self, rows: &[ImpactRow], v: &mut [(Vec3A, Vec3A)], params: &ImpactParams) {
        if params.gravity == Vec3A::ZERO {
            return;
        }
        // Per body: 0 no support row, 1 every one static and parting, 2 otherwise.
        let mut held = std::mem::take(&mut self.impact_islands);
        held.clear();
        held.resize(v.len(), 0);
        for row in rows.iter().filter(|r| r.role == Role::Support) {
            let parting = row.normal_velocity(v) > APPROACHING;
            let static_support = row.a == 0 || row.b == 0;
            for body in [row.a, row.b] {
                if body != 0 {
                    let b = body as usize;
                    held[b] = if parting && static_support && held[b] != 2 {
                        1
                    } else {
                        2
                    };
                }
            }
        }
        let half_kick = params.gravity * (0.5 * params.h);
        for (body, _) in held.iter().enumerate().filter(|&(_, &h)| h == 1) {
            v[body].0 -= half_kick;
        }
        self.impact_islands = held;
    }

    /// The accumulated normal impulse of `row`'s point, to store.
    fn normal_impulse_mut(&mut self, row: &ImpactRow) -> &mut f32 {
        let (i, k, p) = (
            row.group.index as usize,
            row.lane as usize,
            row.point as usize,
        );
        with_groups!(&mut self, row.group, |gs, _STATIC_A| &mut gs.hot[i]
            .impulses[p]
            .normal_impulse[k])
    }

    /// The normal impulse `row`'s point delivered over the step's sub-steps.
    fn step_impulse(&self, row: &ImpactRow) -> f32 {
        let (i, k, p) = (
            row.group.index as usize,
            row.lane as usize,
            row.point as usize,
        );
        with_groups!(&self, row.group, |gs, _STATIC_A| gs.cold[i].step_impulse[p]
            [k])
    }
}

/// Phase 2 on `v` (the start velocities): the primary event, then each event the one before left,
/// until nothing approaches.
fn resolve_events(rows: &mut [ImpactRow], v: &mut [(Vec3A, Vec3A)], threshold: f32) {
    for _ in 0..MAX_EVENTS {
        for row in rows.iter_mut() {
            row.impulse = 0.0;
        }
        sweep(rows, |row| {
            let shift = row.shift;
            row.in_event && row.relax(v, shift)
        });
        for row in rows.iter_mut() {
            row.events_impulse += row.impulse;
        }
        // The next event: the free and primary points left approaching.
        let mut any = false;
        for row in rows.iter_mut() {
            if row.role == Role::Support {
                continue;
            }
            let approach = -(row.normal_velocity(v) + row.shift);
            row.in_event = approach > APPROACHING;
            if row.in_event {
                any = true;
                row.target = if approach > threshold {
                    row.restitution * approach
                } else {
                    0.0
                };
            }
        }
        if !any {
            return;
        }
    }
    // Still exchanging: settle it plastically.
    for row in rows.iter_mut() {
        (row.in_event, row.target, row.impulse) = (true, 0.0, 0.0);
    }
    sweep(rows, |row| {
        let shift = row.shift;
        row.relax(v, shift)
    });
    for row in rows.iter_mut() {
        row.events_impulse += row.impulse;
    }
}
