//! Blows a pile carries (`Settings::piles_carry_blows`): a body landing from above on a resting
//! pile is stopped by the pile as by the ground, where the pile can carry the blow as it carries
//! its weight.
//!
//! A pile of rigid bodies resting on the ground passes a blow from above straight down to the
//! ground: nothing in it moves, and the body that landed stops (or bounces) as if it had hit the
//! floor. The sub-steps cannot do that: one Gauss–Seidel sweep a pass hands the blow down a layer
//! a pass, and meanwhile the struck bodies move into the ones below them. A 20 g ball landing at
//! 3.1 m/s on the bench's running-bond wall (bricks of 16 g) sank the struck brick and the two
//! under it 3.4–3.6 mm in the step it landed and set them turning; the wall settled 6 to 12 mm
//! from where it slept at 4 sub-steps, and fell at 2 (`nudge bench rest`). Converging the sweeps
//! does not save it: with 64 biased and 64 relax passes a sub-step it still settled 0.74 mm off
//! (the soft rows give under the blow; `solve::mass_ratio`, "Not for a blow on a pile").
//!
//! So where statics say the pile carries the blow, the landing contact's rows take the struck body
//! as immovable, for the step in which it lands (its contact carried nothing last step and closes
//! faster than restitution's threshold by the step's end: the statics' impact, see `preload`):
//! zero inverse mass and inertia on that side of its lanes (`wide_contacts::build`), in the
//! sub-steps and in restitution's impacts alike, which then bounce the body as from the floor, as
//! they already did a ball dropped on a box on the floor. From the next step the contact is a
//! support like any other and the pile carries the body's weight. The pile carries the blow when:
//! - the contact is a level face's (its normal within `LEVEL_MIN_COS` of vertical) and the body
//!   strikes from above;
//! - the struck body rests: it moves slower than the sleep thresholds when the step begins (statics
//!   hold for a pile at rest; a heap still landing answers a blow with motion, and carried in it
//!   the blows changed how a heap dropped into a pit landed: at 2 sub-steps a ball came to rest on
//!   a saddle of two balls and rolled off it seconds after the heap was taken as settled, in every
//!   copy of `nudge bench rest`);
//! - it rests on supports whose chain reaches a static body (`grounded`), on level faces only (on
//!   a heap's tilted faces a blow may roll or slide what it hits), and no hand holds it; the
//!   striking body rests on nothing (it is in flight);
//! - every point of the landing contact is over the struck body's supports (within the convex
//!   hull of their points, seen from above): a blow outside it tips the body, as a ball landing on
//!   the overhanging end of a plank should;
//! - friction can hold the blow's slant at each support: μ at least the tangent of the angle
//!   between the blow and that support's normal;
//! - and so on down: each body under the struck one that the blow passes through is grounded, on
//!   level faces, within friction, with the patch the blow comes in through over its own supports
//!   (a ball on a box standing on a plank's overhanging end tips the plank). Each patch is checked
//!   whole, not where the statics would put its share: a pile passes when the blow could land
//!   anywhere on it. The walk visits each body's supports once, and at most [`MOST_WALKED`]
//!   bodies.
//!
//! Measured (`nudge bench rest`, 2026-12-01, medians of eight copies): woken by the ball, the
//! running-bond wall settles 0.16 mm from where it slept at 4 sub-steps (10.7 mm before) and
//! 0.17 mm at 8 (5.3 mm), the crossed tower within a micrometre at 2 to 8 (1.5 mm at 2 before),
//! pyramids and columns within 0.14 mm in every copy; the ball-on-a-box and ball-on-a-stack
//! families of `nudge bench corpus` bounce within 0.01 % of the floor's answer at 4 sub-steps
//! (0.03 and 0.2 % before). At 2 sub-steps the wall carries the blow but not then the ball's
//! weight: it sinks and leans over the next seconds (2 of 8 copies hold). That is the load, not
//! the blow or the sleep: the ball set down on the wall, touching, leaves it within 1 mm in 4 of 8
//! copies, awake or woken alike. The ball is round: the joints under it give, the top tilts, and it
//! rolls along the top course the way it tilts, taking its load with it (in one copy off the end);
//! a 20 g cube set down in its place moves the wall 0.2 to 4.9 mm in the first four copies, where
//! the ball moved it 0.5 to 170 mm. Dropped into its pit the heap lands nearly as before (kept awake,
//! it rests within the same micrometres), its blows falling on bodies still moving or on tilted
//! faces, which do not carry them; woken by the ball it rests as before at 2, 8 and 4 × 4
//! sub-steps (3, 6 and 7 copies of 8 within 1 mm); at 4, in 7 of 8 (8 before): asleep, one copy
//! lands a little differently, its top box tilted 10°, and the ball landing on that tilted face
//! knocks it 2.1 mm (a pile at rest is chaotic, `bench::rest`). Pinned by
//! `a_sleeping_running_bond_wall_woken_by_a_ball_stands_only_when_piles_carry_blows` and
//! `a_blow_beside_the_supports_rocks_a_balanced_plank_and_one_over_them_does_not`
//! (`tests/physics/rest.rs`).

use glam::{Vec2, Vec3};

use super::{LEVEL_MIN_COS, Statics};
use crate::physics::narrow::contact::Contact;
use crate::physics::prepare::constraint_order::ConstraintOrder;
use crate::physics::scratch::refill;
use crate::physics::solve::wide_contacts::StruckPile;

/// The most bodies a blow is followed down through (see [`Statics::carried_to_the_ground`]):
/// every body of a 20-row pyramid struck at its top, and of the bench's walls; a pile larger under
/// the blow is taken not to carry it, and passes it down as any pile did before.
const MOST_WALKED: usize = 256;

/// A contact that may land a blow on a pile: a level face's impact, with the body below and the
/// body landing on it (solver indices).
#[derive(Clone, Copy, Debug)]
pub(super) struct Blow {
    pub(super) constraint: u32,
    pub(super) struck: u32,
    pub(super) striker: u32,
}

impl Blow {
    /// The contact as a blow, if it is a level face's with a dynamic body below: `(a, b)` its
    /// bodies (solver indices, 0 static), `up` against gravity.
    pub(super) fn of(
        constraint: u32,
        contact: &Contact,
        (a, b): (u32, u32),
        up: Vec3,
    ) -> Option<Blow> {
        let tilt = contact.manifold.normal.dot(up);
        // The normal points from A to B: B lands on A when it points up.
        let (struck, striker) = if tilt >= LEVEL_MIN_COS {
            (a, b)
        } else if tilt <= -LEVEL_MIN_COS {
            (b, a)
        } else {
            return None;
        };
        (struck != 0 && striker != 0).then_some(Blow {
            constraint,
            struck,
            striker,
        })
    }
}

impl Statics {
    /// Which of the step's `blows` the piles carry (see the module docs), into `struck_pile`; after
    /// `find_supports`, which found who rests on what.
    pub(super) fn find_struck_piles(
        &mut self,
        contacts: &[Contact],
        graph: &ConstraintOrder,
        up: Vec3,
        margin: f32,
    ) {
        if self.blows.is_empty() {
            return;
        }
        refill(&mut self.walked, self.body.len(), false);
        self.walked_list.clear();
        let blows = std::mem::take(&mut self.blows);
        for blow in &blows {
            // A striker resting on something else is not landing in free flight.
            if self.body[blow.striker as usize].grounded {
                continue;
            }
            if self.carried_to_the_ground(blow, contacts, graph, up, margin) {
                let (a, _) = graph.links[blow.constraint as usize];
                self.struck_pile[blow.constraint as usize] = if a == blow.struck {
                    StruckPile::A
                } else {
                    StruckPile::B
                };
            }
        }
        self.blows = blows;
    }

    /// Whether the pile under `blow`'s struck body carries it to the ground: walking down from the
    /// struck body through its supports, every body the blow passes through rests on level faces
    /// that hold its slant within friction, and the patch it comes in through (the landing's, then
    /// each support's above) is over that body's supports. At most [`MOST_WALKED`] bodies.
    fn carried_to_the_ground(
        &mut self,
        blow: &Blow,
        contacts: &[Contact],
        graph: &ConstraintOrder,
        up: Vec3,
        margin: f32,
    ) -> bool {
        let (e1, e2) = up.any_orthonormal_pair();
        let seen_from_above = |p: Vec3| Vec2::new(p.dot(e1), p.dot(e2));
        let direction = contacts[graph.contact(blow.constraint as usize)]
            .manifold
            .normal;
        for &body in &self.walked_list {
            self.walked[body as usize] = false;
        }
        self.walked_list.clear();
        self.walk.clear();
        self.walk.push((blow.struck, blow.constraint));
        while let Some((body, through)) = self.walk.pop() {
            if self.walked_list.len() >= MOST_WALKED {
                return false;
            }
            let loaded = &self.body[body as usize];
            let resting =
                loaded.grounded && !loaded.off_level && !loaded.held_above && loaded.supports > 0;
            let first = loaded.first_support as usize;
            let supports = &self.supports_list[first..first + loaded.supports as usize];
            let within_friction = supports.iter().all(|&j| {
                let s = &self.support[j as usize];
                s.friction >= slant(direction, s.normal)
            });
            if !resting || !within_friction {
                return false;
            }
            self.hull_points.clear();
            for &j in supports {
                let points = contacts[graph.contact(j as usize)].manifold.points();
                self.hull_points
                    .extend(points.iter().map(|p| seen_from_above(p.point)));
            }
            convex_hull(&mut self.hull_points, &mut self.hull);
            let coming_in = contacts[graph.contact(through as usize)].manifold.points();
            if !coming_in
                .iter()
                .all(|p| inside(&self.hull, seen_from_above(p.point), margin))
            {
                return false;
            }
            if !self.walked[body as usize] {
                self.walked[body as usize] = true;
                self.walked_list.push(body);
                for &j in supports {
                    let below = self.support[j as usize].bottom;
                    if below != 0 {
                        self.walk.push((below, j));
                    }
                }
            }
        }
        true
    }
}

/// The tangent of the angle between a blow along `blow` and a contact's `normal` (either way
/// round): the friction coefficient that contact needs to hold the blow's slant.
fn slant(blow: Vec3, normal: Vec3) -> f32 {
    let cos = blow.dot(normal).abs().min(1.0);
    (1.0 - cos * cos).max(0.0).sqrt() / cos.max(f32::MIN_POSITIVE)
}

/// The convex hull of `points` (sorted in place) into `hull`, counter-clockwise (Andrew's monotone
/// chain); points on its edges are left out, so points on one line give at most two.
fn convex_hull(points: &mut Vec<Vec2>, hull: &mut Vec<Vec2>) {
    points.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    points.dedup();
    hull.clear();
    if points.len() < 3 {
        hull.extend_from_slice(points);
        return;
    }
    // The lower chain left to right, then the upper one back; each ends where the next begins.
    for &p in points.iter() {
        push_turning_left(hull, 0, p);
    }
    hull.pop();
    let upper = hull.len();
    for &p in points.iter().rev() {
        push_turning_left(hull, upper, p);
    }
    hull.pop();
}

/// Pushes `p` on the chain that begins at `hull[start]`, first dropping its last points until it
/// turns left into `p`.
fn push_turning_left(hull: &mut Vec<Vec2>, start: usize, p: Vec2) {
    while hull.len() >= start + 2 {
        let (o, a) = (hull[hull.len() - 2], hull[hull.len() - 1]);
        if (a - o).perp_dot(p - o) > 0.0 {
            break;
        }
        hull.pop();
    }
    hull.push(p);
}

/// Whether `p` is inside the counter-clockwise convex `hull`, or outside it by at most `margin`
/// (a hull of fewer than three points has no inside).
fn inside(hull: &[Vec2], p: Vec2, margin: f32) -> bool {
    hull.len() >= 3
        && (0..hull.len()).all(|i| {
            let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
            (b - a).perp_dot(p - a) >= -margin * (b - a).length()
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hull_of(mut points: Vec<Vec2>) -> Vec<Vec2> {
        let mut hull = Vec::new();
        convex_hull(&mut points, &mut hull);
        hull
    }

    fn square() -> Vec<Vec2> {
        vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
            // An inner point and one on an edge: neither is a corner of the hull.
            Vec2::new(0.5, 0.5),
            Vec2::new(0.5, 0.0),
        ]
    }

    #[test]
    fn the_hull_of_a_square_with_inner_points_is_its_four_corners() {
        let hull = hull_of(square());
        assert_eq!(hull.len(), 4, "{hull:?}");
        assert!(inside(&hull, Vec2::new(0.25, 0.75), 0.0));
        assert!(
            inside(&hull, Vec2::new(1.0, 0.5), 0.0),
            "on an edge is inside"
        );
        assert!(!inside(&hull, Vec2::new(1.01, 0.5), 0.0));
        assert!(!inside(&hull, Vec2::new(-0.01, -0.01), 0.0));
    }

    #[test]
    fn two_patches_side_by_side_make_one_hull_over_both() {
        // A brick over the joint of two below: the ball over the joint is over its supports.
        let hull = hull_of(vec![
            Vec2::new(1.0, -0.1),
            Vec2::new(1.2, -0.1),
            Vec2::new(1.2, 0.1),
            Vec2::new(1.0, 0.1),
            Vec2::new(1.2, -0.1),
            Vec2::new(1.4, -0.1),
            Vec2::new(1.4, 0.1),
            Vec2::new(1.2, 0.1),
        ]);
        assert!(inside(&hull, Vec2::new(1.2, 0.0), 0.0));
        assert!(!inside(&hull, Vec2::new(1.5, 0.0), 0.0));
    }

    #[test]
    fn points_on_a_line_have_no_inside() {
        let hull = hull_of(vec![Vec2::ZERO, Vec2::X, 2.0 * Vec2::X]);
        assert!(hull.len() <= 2, "{hull:?}");
        assert!(!inside(&hull, Vec2::X, 0.0));
    }

    #[test]
    fn the_slant_of_a_blow_along_the_normal_is_zero_and_grows_as_its_tangent() {
        assert_eq!(slant(Vec3::Y, Vec3::Y), 0.0);
        assert_eq!(slant(Vec3::Y, -Vec3::Y), 0.0);
        let tilted = Vec3::new(0.1, 1.0, 0.0).normalize();
        assert!((slant(tilted, Vec3::Y) - 0.1).abs() < 1e-6);
    }
}
