//! Deep overlap is pushed out in position space, each body at a bounded speed.
//!
//! The soft contact (see `softness`) turns penetration into a separating velocity, a damped spring
//! capped at a push-out speed. That speed is one contact's, relative: a body overlapping k others is
//! pushed by each of them, and the pushes add up along every chain of overlapping bodies, so N boxes
//! spawned at one point flew apart at about N metres per second (20 reached 17 m/s, 50 reached
//! 46 m/s) and kept that speed: one relax sweep over a crowd that dense cannot take the bias velocity
//! back out, and a pile's floor hands every layer's push to the layer above. The spring is right for
//! what a contact at rest carries (millimetres); an overlap of centimetres to metres is an error to
//! undo, not a load.
//!
//! So the soft bias acts within a contact's soft range past the slop ([`SOFT_DEPTH`], less between
//! thin bodies: [`soft_depth`]), pushing out at `bias_rate · depth` (at most 0.45–0.9 m/s at the
//! defaults); a contact deeper than that is a rigid
//! row in velocity (it stops approach and carries any load, but pushes nothing: left pushing at the
//! soft range's edge, such pushes chained up to 1 m/s through a crowd of 50 and stayed), and the
//! overlap is removed in position space once per sub-step, after the positions are integrated: nonlinear
//! Gauss–Seidel over the deep contacts in layer order (Catto's position solver in Box2D 2.4, Jolt's
//! penetration recovery), moving the bodies apart along the normal by their inverse masses, without
//! touching their velocities, so the correction is never kinetic energy. The limit holds per body:
//! each body's push-out displacement within a sub-step stays inside a ball of radius
//! `max_push_out_velocity · h`, however many contacts push it, so no body is pushed out faster than
//! `max_push_out_velocity` and a crowd opens up at that speed whatever its size. The push is
//! translational (the deepest point's depth, for the manifold as a whole); turning is left to the
//! velocity rows. Contacts within their soft range (every resting stack and pile) never reach
//! this pass, so it costs nothing where nothing is deep. A body the pass moved is not resting,
//! whatever its velocity (a crowd must not fall asleep overlapping).

use glam::{Vec3, Vec3A};

use crate::geometry::Shape;
use crate::physics::narrow::contact::Contact;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};

/// Penetration past the slop that the soft contact pushes out through velocity, m; deeper, its
/// spring has bottomed out (a rigid row) and the overlap is pushed out in position space (see the
/// module docs). Deeper than any loaded contact goes: the soft spring's compression grows with the
/// load it carries (the lowest contact of a column of 50 unit boxes rests 32 mm deep), and a loaded
/// contact pushed back in position space chatters between the spring and the stop (at 2 cm, columns of
/// 40 and 50 boxes wobbled and fell).
pub(crate) const SOFT_DEPTH: f32 = 0.05;

/// The fraction of the depth at which two bodies' centres cross that their contact's soft range may
/// reach (see [`soft_depth`]).
const THIN_SOFT_FRACTION: f32 = 0.25;

/// The soft range of a contact between shapes `a` and `b`, m: [`SOFT_DEPTH`], or with `thin`
/// (`Settings::thin_soft_range`) a quarter of their half thicknesses' sum where that is less.
///
/// Why: two bodies that overlap by their half thicknesses' sum have their centres level along the
/// normal, and past that the separating axis points the other way and pushes them on through. A
/// spring soft to 5 cm lets bodies thinner than that reach it: ten 2 cm plates asleep, hit by a
/// 20 g ball (a plate's mass) dropped from 5 m at 4 sub-steps or from 0.5 m at 2, had plates
/// pass into each other and one squeezed 0.36 m out of the stack. With the range a quarter of the
/// crossing depth (5 mm between two plates) the deep rows and the position pass stop them first
/// and the stack settles back within 0.05 mm (`tests/physics/rest.rs`; `nudge bench physics`,
/// fixes). Boxes and balls 20 cm thick or more keep the whole range, so nothing else changes.
/// (Half the crossing depth still let the plates through at 2 sub-steps. A faster ball still drives
/// them through, dropped 10 m at 4 sub-steps or 2 m at 2: nothing in one sub-step stops an
/// approach deeper than a plate.)
pub(crate) fn soft_depth(a: &Shape, b: &Shape, thin: bool) -> f32 {
    if thin {
        SOFT_DEPTH.min(THIN_SOFT_FRACTION * (a.half_thickness() + b.half_thickness()))
    } else {
        SOFT_DEPTH
    }
}

/// One deep contact, for the position pass: its deepest point, seen from both bodies.
#[derive(Clone, Copy, Debug)]
struct DeepRow {
    /// Solver body indices (0 = static dummy).
    a: u32,
    b: u32,
    /// Unit normal A → B.
    normal: Vec3A,
    /// r × n of the deepest point for each body, m.
    rn_a: Vec3A,
    rn_b: Vec3A,
    /// Its separation at the start of the step, m (< 0).
    separation: f32,
    /// Its contact's soft range, m (`Contact::soft_depth`): it is pushed out past the slop and that.
    soft_depth: f32,
    /// Each body's share of a correction: 1/m over the pair's sum (0 for the dummy).
    share_a: f32,
    share_b: f32,
}

/// The deep contacts of a step and the per-body push-out of the current sub-step.
#[derive(Debug, Default)]
pub(crate) struct DeepOverlaps {
    rows: Vec<DeepRow>,
    /// Per solver body: push-out displacement so far in this sub-step, m.
    pushed: Vec<Vec3A>,
    /// Per solver body: whether the pass moved it this step (it is not resting, whatever its
    /// velocity says: a crowd pushed apart in position space must not fall asleep overlapping).
    moved: Vec<bool>,
}

impl DeepOverlaps {
    /// Collects, in `layer_order` (constraint indices; `contact_of(i)` is constraint i's contact, one
    /// of `contacts`, and `links[i]` its solver bodies), the contacts whose deepest point lies more
    /// than the slop and their soft range deep (`Contact::deep_limit`). `positions` are the world
    /// positions of the bodies.
    pub(crate) fn collect<'c>(
        &mut self,
        contacts: &[Contact],
        layer_order: &[u32],
        links: &[(u32, u32)],
        contact_of: impl Fn(usize) -> &'c Contact,
        positions: impl Fn(u32) -> Vec3,
        motions: &[SolverMotion],
        linear_slop: f32,
    ) {
        self.rows.clear();
        self.moved.clear();
        // Almost every step has nothing that deep: one pass over the contacts, in storage order,
        // says so before the layer order is walked.
        let deep = |c: &Contact| {
            let limit = c.deep_limit(linear_slop);
            c.manifold.points().iter().any(|p| p.separation < limit)
        };
        if layer_order.is_empty() || !contacts.iter().any(deep) {
            return;
        }
        for &i in layer_order {
            let c = contact_of(i as usize);
            let Some(deepest) = c
                .manifold
                .points()
                .iter()
                .min_by(|p, q| p.separation.total_cmp(&q.separation))
            else {
                continue;
            };
            if deepest.separation >= c.deep_limit(linear_slop) {
                continue;
            }
            let (a, b) = links[i as usize];
            let (inv_a, inv_b) = (motions[a as usize].inv_mass, motions[b as usize].inv_mass);
            let sum = inv_a + inv_b;
            if sum <= 0.0 {
                continue;
            }
            let n = Vec3A::from(c.manifold.normal);
            let p = Vec3A::from(deepest.point);
            self.rows.push(DeepRow {
                a,
                b,
                normal: n,
                rn_a: (p - Vec3A::from(positions(c.a))).cross(n),
                rn_b: (p - Vec3A::from(positions(c.b))).cross(n),
                separation: deepest.separation,
                soft_depth: c.soft_depth,
                share_a: inv_a / sum,
                share_b: inv_b / sum,
            });
        }
        // Against a static body last: a body pushed into the floor by the crowd above it is then put
        // back (towards where the pass found it, which its reach always allows), so nothing is ever
        // pushed through a static body.
        let dynamic = self.rows.iter().filter(|r| r.a != 0 && r.b != 0).count();
        self.rows.sort_by_key(|r| r.a == 0 || r.b == 0);
        debug_assert!(self.rows[..dynamic].iter().all(|r| r.a != 0 && r.b != 0));
        if self.pushed.len() < motions.len() {
            self.pushed.resize(motions.len(), Vec3A::ZERO);
        }
        self.moved.resize(motions.len(), false);
    }

    /// Whether the position pass moved solver body `index` this step.
    #[inline]
    pub(crate) fn moved(&self, index: usize) -> bool {
        self.moved.get(index).copied().unwrap_or(false)
    }

    /// Whether there is anything to push out this step.
    pub(crate) fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// One sub-step's position pass: each deep contact's depth past the slop and its soft range, at the
    /// bodies' current positions, is removed by moving them apart along the normal, each body
    /// staying within `max_speed · h` of where the pass found it.
    pub(crate) fn push_apart(
        &mut self,
        bodies: &mut [SolverBody],
        linear_slop: f32,
        max_speed: f32,
        h: f32,
    ) {
        let reach = max_speed * h;
        for row in &self.rows {
            self.pushed[row.a as usize] = Vec3A::ZERO;
            self.pushed[row.b as usize] = Vec3A::ZERO;
        }
        for row in &self.rows {
            let (ba, bb) = (&bodies[row.a as usize], &bodies[row.b as usize]);
            let n = row.normal;
            let separation = row.separation + n.dot(bb.dp - ba.dp) + bb.dtheta.dot(row.rn_b)
                - ba.dtheta.dot(row.rn_a);
            let excess = -(separation + linear_slop + row.soft_depth);
            if excess <= 0.0 {
                continue;
            }
            if row.a != 0 {
                let step = within_reach(
                    self.pushed[row.a as usize],
                    -excess * row.share_a * n,
                    reach,
                );
                self.pushed[row.a as usize] += step;
                self.moved[row.a as usize] = true;
                bodies[row.a as usize].dp += step;
            }
            if row.b != 0 {
                let step =
                    within_reach(self.pushed[row.b as usize], excess * row.share_b * n, reach);
                self.pushed[row.b as usize] += step;
                self.moved[row.b as usize] = true;
                bodies[row.b as usize].dp += step;
            }
        }
    }
}

/// The largest part t·`step` (t in [0, 1]) of `step` that keeps `pushed + t·step` within `reach` of
/// the origin (`pushed` is already within it).
#[inline]
fn within_reach(pushed: Vec3A, step: Vec3A, reach: f32) -> Vec3A {
    let after = pushed + step;
    if after.length_squared() <= reach * reach {
        return step;
    }
    // |pushed + t·step|² = reach²: the larger root of a quadratic in t, ≥ 0 since |pushed| ≤ reach.
    let (a, b, c) = (
        step.length_squared(),
        pushed.dot(step),
        pushed.length_squared() - reach * reach,
    );
    let t = (-b + (b * b - a * c).max(0.0).sqrt()) / a;
    step * t.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_push_is_cut_where_it_would_leave_the_ball() {
        let reach = 1.0;
        // Inside: whole.
        assert_eq!(
            within_reach(Vec3A::ZERO, Vec3A::X * 0.5, reach),
            Vec3A::X * 0.5
        );
        // From the centre, too far: cut to the sphere.
        let cut = within_reach(Vec3A::ZERO, Vec3A::X * 3.0, reach);
        assert!((cut - Vec3A::X).length() < 1e-6, "{cut}");
        // Sideways from a point already pushed: ends on the sphere.
        let pushed = Vec3A::new(0.6, 0.0, 0.0);
        let step = within_reach(pushed, Vec3A::new(0.0, 2.0, 0.0), reach);
        assert!(((pushed + step).length() - reach).abs() < 1e-5, "{step}");
        assert!((step.y - 0.8).abs() < 1e-5, "{step}");
        // Back the way it came: free (the ball is around the start of the sub-step, not the body).
        assert_eq!(
            within_reach(Vec3A::X, Vec3A::X * -1.5, reach),
            Vec3A::X * -1.5
        );
    }
}
