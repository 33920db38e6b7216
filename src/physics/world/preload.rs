//! Stage 3b, the feed-forward load (`Settings::preload`, off by default): what each resting contact
//! carries when everything above it is at rest, the preload of its soft spring.
//!
//! The soft step's row is Δλ = −m_eff·s_m·(v_n + b) − s_i·λ (Catto, "Solver2D: soft step", 2024):
//! the leak −s_i·λ relaxes λ towards the spring force k·(depth − slop), so a contact carrying the
//! load L at rest sits at depth − slop = L/(m_eff·ω²·h) — 0.55 mm per box above it at the defaults,
//! 16.5 mm at the bottom of a column of 30. With a preload λ₀ the leak acts on λ − λ₀ instead: the
//! rest point is λ = λ₀ at depth = slop, so a contact whose preload is its true static load does not
//! sink at all, and the spring only answers the residual. λ₀ is found feed-forward, top down over
//! the contact graph's layers: each body hands its weight (and applied forces) plus what rests on it
//! to its supports, shared in proportion to the load each carried last step (the solver's own
//! torque balance), the vertical part scaled by the normal's cosine. The warm start is rescaled to
//! λ₀, sharing it among a manifold's points as last step's impulses were. The spring itself is
//! preloaded with λ₀ less the top body's own weight, shared evenly among the points: every contact
//! then rests as a lone body of its own weight does (0.55 mm past the slop for a unit box), deep in
//! the spring's linear range whatever is stacked on it. (Preloaded with all of λ₀ it rested at the
//! slop, where the row's law changes: the side of a pushed box that unloaded lost its stiffness and
//! a pushed stack of ten pitched and swayed, 2.5·10⁻⁴ off Coulomb over its push; shared as last
//! step's impulses, each point's rest force followed its own load, and a box had no stiffness
//! against rocking at all.) Not preloaded (they keep the plain leak): fresh impacts faster than the
//! restitution threshold (restitution owns them), overlaps deeper than the soft range (rigid rows,
//! the position pass owns them), and contacts of mass-ratio-marked bodies (the shock pass and extra
//! sweeps own them) — which still hand their top body's weight down, or the supports below would be
//! preloaded short of their load and have their warm start cut every step: a stack under a light
//! ball sank 3.5 mm. A held body (`World::hold_point`) is taken to pull as it did last step: a hand
//! holding a box up takes its weight off the floor.
//!
//! Measured with it on (2026-11-27): columns of 10 to 50 boxes rest within a lone box's depth (5.3
//! to 32 mm without), and every behaviour test passes but one (the determinism hashes and the
//! on/off pins of `tests/physics_convergence_fixes.rs` aside): a stack of ten pushed along the floor
//! gets ahead of ½·a·t² by 12.3 % (10 % allowed, 9.7 % off). Its contacts rest in the slop band,
//! where the row neither pushes nor leaks: nothing holds a contact at a depth there, so as the
//! pushed boxes rock their contacts ratchet deeper, the column shortens 2 mm in five steps, and
//! while it does the floor carries less than the stack's weight and friction is short. Off by
//! default until the band has a design of its own.

use super::Scratch;
use crate::physics::contact::Contact;
use crate::physics::point_drive::PointHold;
use crate::physics::push_out::SOFT_DEPTH;
use crate::physics::settings::Settings;

/// Cosine of the steepest contact normal (from vertical) through which a body counts as resting on
/// another: 45°.
pub(super) const RESTING_MIN_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// `preload` of a constraint that supports nothing (not resting, or no gravity): the spring leaks to
/// zero as before.
pub(crate) const NO_PRELOAD: f32 = -1.0;

/// One constraint as the preload sees it: `top` rests on `bottom` (solver indices; `top == 0` when
/// it is not a support), through a normal at `cos` from vertical, having carried `warm` last step.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Support {
    bottom: u32,
    top: u32,
    cos: f32,
    warm: f32,
    /// Whether the contact takes its load as a preload. A support that does not (a mass-ratio
    /// contact, whose extra sweeps and shock pass own it) still hands its top body's weight down:
    /// the contacts below carry it either way, and a preload that left it out would be rescaling
    /// their warm start below their load every step, so the pile would sink step after step.
    preloaded: bool,
}

impl Scratch {
    /// Per constraint (solve order), the normal impulse per sub-step of length `h` it carries in static
    /// equilibrium under the settings' gravity, or [`NO_PRELOAD`] (all of them when
    /// `Settings::preload` is off): a body's weight plus what rests on it is shared by its supports
    /// in proportion to the load each carried last step (equally if none did), top down through the
    /// contact graph's layers. `holds` are the step's holds (see `World::hold_point`).
    pub(super) fn compute_preloads(
        &mut self,
        contacts: &[Contact],
        holds: &[PointHold],
        settings: &Settings,
        h: f32,
    ) {
        let impact_speed = settings.restitution_threshold;
        let soft_limit = settings.linear_slop + SOFT_DEPTH;
        let s = self;
        let n_constraints = s.links.len();
        s.preload.clear();
        s.preload.resize(n_constraints, NO_PRELOAD);
        s.spring_preload.clear();
        s.spring_preload.resize(n_constraints, NO_PRELOAD);
        let Some(up) = (-settings.gravity)
            .try_normalize()
            .filter(|_| settings.preload)
        else {
            return;
        };
        let n = s.motions.len();
        // Per body: the vertical impulse to hand down (its weight, then plus what rests on it), and
        // over its supports the sums of last step's vertical loads and of the normals' vertical parts.
        s.weight_above.clear();
        // Gravity and the applied forces (a hand pressing a box down presses on its supports too).
        s.weight_above.extend(s.motions.iter().map(|m| {
            if m.inv_mass > 0.0 {
                -m.linear_accel.dot(up.into()) * h / m.inv_mass
            } else {
                0.0
            }
        }));
        // A hold's pull is solved in the sub-steps, so it is not known yet: a body held again this
        // step is taken to pull as it did over the last one (a hand that holds a box up takes its
        // weight off the floor, one dragging it into the floor adds to it).
        for &(body, impulse) in &s.hold_impulses {
            let i = s.solver_index[body.index()] as usize;
            if i != 0 && holds.iter().any(|hold| hold.body == body) {
                s.weight_above[i] -= impulse.dot(up) / settings.substep_count() as f32;
            }
        }
        for weight in &mut s.weight_above {
            *weight = weight.max(0.0);
        }
        s.own_weight.clone_from(&s.weight_above);
        s.support_warm.clear();
        s.support_warm.resize(n, 0.0);
        s.support_cos.clear();
        s.support_cos.resize(n, 0.0);
        s.support.clear();
        for (i, &(a, b)) in s.links.iter().enumerate() {
            let c = &contacts[s.graph.contact(i)];
            let tilt = c.manifold.normal.dot(up);
            // The normal points from A to B: B rests on A when it points up.
            let (bottom, top) = if tilt >= RESTING_MIN_COS && b != 0 {
                (a, b)
            } else if tilt <= -RESTING_MIN_COS && a != 0 {
                (b, a)
            } else {
                s.support.push(Support::default());
                continue;
            };
            let cos = tilt.abs();
            let warm: f32 = c.impulses.normal[..c.manifold.len]
                .iter()
                .map(|l| l.max(0.0))
                .sum();
            // A contact that carried nothing and closes faster than restitution's threshold is an
            // impact, not a support: restitution owns it.
            let n = glam::Vec3A::from(c.manifold.normal);
            let closing = -n.dot(s.solver_bodies[b as usize].v - s.solver_bodies[a as usize].v);
            let deepest = c
                .manifold
                .points()
                .iter()
                .fold(0.0f32, |d, p| d.min(p.separation));
            if (warm == 0.0 && closing > impact_speed) || deepest < -soft_limit {
                s.support.push(Support::default());
                continue;
            }
            let marked = s.mass_ratio_bodies[a as usize] || s.mass_ratio_bodies[b as usize];
            s.support_warm[top as usize] += warm * cos;
            s.support_cos[top as usize] += 1.0;
            s.support.push(Support {
                bottom,
                top,
                cos,
                warm,
                preloaded: !marked,
            });
        }
        for &i in s.graph.layer_order.iter().rev() {
            let Support {
                bottom,
                top,
                cos,
                warm,
                preloaded,
            } = s.support[i as usize];
            if top == 0 {
                continue;
            }
            let (t, b) = (top as usize, bottom as usize);
            let weight = s.weight_above[t];
            // This support's share of the weight: friction carries its part along the surface, the
            // normal impulse the rest (a box on a 30° ramp: W·cos 30°).
            let share = if s.support_warm[t] > 0.0 {
                warm * cos / s.support_warm[t]
            } else {
                1.0 / s.support_cos[t]
            };
            if preloaded {
                s.preload[i as usize] = weight * share * cos;
                s.spring_preload[i as usize] = (weight - s.own_weight[t]) * share * cos;
            }
            if b != 0 {
                s.weight_above[b] += weight * share;
            }
        }
    }
}
