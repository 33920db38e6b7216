//! Persistent contacts: one per overlapping body pair, kept from step to step so the solver can warm start.
//!
//! The world keeps its contacts sorted by `(a, b)` with `a < b` (body indices). Each step the broad phase's
//! pairs, also sorted, are merged with last step's list; a point of the new manifold inherits the normal
//! impulse of the old point with the same feature id, and the manifold inherits its friction impulses
//! (friction acts at the manifold's centroid, see `contact_solver`). The friction impulse is kept as a
//! world vector, so it survives a change of tangent basis when the normal turns.
//!
//! Points whose feature id is new share the load of the old points that found no successor (see
//! [`Contact::inherit_impulses`]): the pair's normal load does not depend on how the clipper labels its
//! points.

use glam::{Vec3, Vec3A, Vec4};

use crate::geometry::{Pose, Shape};

use crate::physics::narrow::manifold::{MAX_MANIFOLD_POINTS, Manifold};
use crate::physics::prepare::preload::reuse::KeptStatics;

/// Impulses a contact manifold carried at the end of the last step, for warm starting.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct CachedImpulses {
    /// Accumulated normal impulse of each point, N·s, ≥ 0; `normal[i]` belongs to `manifold.points[i]`.
    pub normal: [f32; MAX_MANIFOLD_POINTS],
    /// Accumulated friction impulse on B at the centroid, world frame, N·s, orthogonal to the normal.
    pub tangent: Vec3,
    /// Accumulated twist-friction impulse on B about the normal, N·m·s.
    pub twist: f32,
    /// Accumulated rolling-resistance impulse on B, world frame, N·m·s, across the normal.
    pub rolling: Vec3,
    /// The static friction on B that the preload's statics asked of this contact when the step
    /// began, N·s per sub-step (zero when it was not a support): what the next step's demand is
    /// compared with (see `prepare::preload`, "friction").
    pub fed_tangent: Vec3,
    /// The normal load the preload's statics asked of this contact when the step began, where
    /// statics do not determine it (`None` elsewhere): what the next step's is compared with (see
    /// `prepare::preload`, "Load changes").
    pub fed_load: Option<FedLoad>,
    /// The moment the statics asked its points' pressure to carry last step, where they fed its
    /// change (see `prepare::preload`, "Moment changes").
    pub fed_offset: Option<Vec3>,
    /// Where static friction holds the patch: B's displacement from its anchor at the centroid,
    /// along the surface, world frame, m (see `contact_solver`, "Friction anchors").
    pub anchor: Vec3,
    /// B's turn about the normal from where twist friction holds the patch, rad.
    pub twist_anchor: f32,
}

/// An indeterminate support's load as the preload's statics gave it (see `prepare::preload`,
/// "Load changes"), N·s per sub-step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FedLoad {
    /// Its preload: the lever rule's share of what its top body hands down.
    pub preload: f32,
    /// What its top body hands down with each body's load shared evenly among its supports:
    /// unchanged unless something was set down or lifted off, a support came or went, or a hand's
    /// pull changed.
    pub carried: f32,
}

/// Cosine of the largest turn of the normal (≈ 25°) over which points with new feature ids inherit
/// the load of the points that disappeared (see [`Contact::inherit_impulses`]).
pub(crate) const LOAD_CARRY_MIN_COS: f32 = 0.9;

/// A contact between bodies `a < b`.
///
/// One struct of 432 bytes, seven cache lines, though most passes read only part of it. Split in
/// two (tried 2026-12-02), the four fields that only reuse reads (`computed`, `pose_a`, `pose_b`,
/// `statics`: 180 bytes) went to a parallel list in the same order, so that the rest, 252 bytes,
/// was all the merge, the statics, the lanes' build and the impulse store walked. It was not
/// faster. rain(1000) took 2 to 6 % longer: every copied run and every fresh contact became two
/// copies, and following a manifold read two lists. That is 1.1 % more instructions in callgrind
/// over 150 steps. The spread rain(4000), whose working set is past the L2 cache, moved within the
/// machine's noise.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Contact {
    pub a: u32,
    pub b: u32,
    /// Normal from A to B; `len > 0` for every stored contact.
    pub manifold: Manifold,
    pub impulses: CachedImpulses,
    /// Combined friction coefficient (geometric mean), ≥ 0.
    pub friction: f32,
    /// Combined restitution (maximum), in [0, 1].
    pub restitution: f32,
    /// Largest rolling couple per unit normal impulse, m (see [`rolling_limit`]); 0 for none.
    pub rolling_resistance: f32,
    /// Penetration past the slop its soft rows push out, m; deeper, the position pass does (see
    /// `push_out::soft_depth`).
    pub soft_depth: f32,
    /// The manifold's geometry as the narrow phase computed it, at `pose_a` and `pose_b`: what
    /// [`Contact::follow`] carries to where the bodies are now, in one step (so that a pair rocking
    /// back and forth finds the same separations each time it passes the same relative pose).
    pub computed: Computed,
    /// Poses of A and B when the manifold was computed.
    pub pose_a: Pose,
    pub pose_b: Pose,
    /// What the statics last gave it, kept while its island stays still (`prepare::preload::reuse`);
    /// none for a manifold computed since.
    pub statics: Option<KeptStatics>,
}

/// A manifold's geometry as computed, world space: what following it needs (its feature ids,
/// patch and the impulses stay in the contact).
///
/// In this order, each vector is followed by a float: [`Contact::follow`] reads each into a SIMD
/// register, and the compiler loads the four bytes after it into the unused lane and computes on
/// them (the results never read them). In the compiler's own order the approach came last, before
/// the bodies' indices, small integers that read as subnormal floats: arithmetic on a subnormal
/// takes a microcode assist, and `follow` took a quarter longer than the scalar code it replaced
/// (a fifth less in this order; perf, touching pyramid).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub(crate) struct Computed {
    pub normal: Vec3,
    pub approach: Vec3,
    pub points: [Vec3; MAX_MANIFOLD_POINTS],
    pub separations: [f32; MAX_MANIFOLD_POINTS],
}

impl Computed {
    pub fn of(manifold: &Manifold) -> Self {
        let mut computed = Computed {
            normal: manifold.normal,
            approach: manifold.approach,
            ..Default::default()
        };
        for (i, p) in manifold.points().iter().enumerate() {
            (computed.points[i], computed.separations[i]) = (p.point, p.separation);
        }
        computed
    }
}

/// How far, as a multiple of the reuse tolerance, either body of a reused manifold may move (any
/// point of it) from where the manifold was computed, however still the pair stays relative to
/// each other. Within it the manifold is followed in the pair's relative frame (to first order,
/// see [`Contact::follow`]); the cap keeps what depends on the pair's absolute pose (a side
/// contact's construction across gravity, see `coincident`) from going stale.
pub(crate) const REUSE_ABSOLUTE_FACTOR: f32 = 5.0;

impl Contact {
    /// The separation below which a point of this contact is past the slop and its soft range, m
    /// (negative): deeper, its row is rigid and the position pass pushes the pair apart
    /// (`push_out`), the statics take it for no support, and no friction anchor holds it.
    pub fn deep_limit(&self, linear_slop: f32) -> f32 {
        -(linear_slop + self.soft_depth)
    }

    /// Brings the manifold to bodies now at `pose_a` and `pose_b` if it still holds for them, and
    /// says whether it did (if not, it is left as it was, to be computed afresh). It holds, judged in
    /// the pair's relative frame as parry and Rapier judge theirs, while B has moved no point of
    /// itself by more than `tolerance` (m) from where it would be had it moved with A since the
    /// manifold was computed (translation plus rotation angle × bounding radius, to first order),
    /// and neither body has moved any point by more than [`REUSE_ABSOLUTE_FACTOR`] times that (once
    /// for a pair with a ball). A NaN pose never holds.
    ///
    /// Followed, the manifold's points, normal and approach are carried with A (a ball's by its
    /// translation alone) and each separation is moved by B's motion relative to A, to first order
    /// as the sub-steps move them; always from the manifold as computed, so that what it reads
    /// depends on where the bodies are, not on the path they took there (carried from last step's,
    /// a pair rocking back and forth did not come back to the same separations, and an awake
    /// touching pyramid rocked). Every stage that reads the manifold (the statics' lever arms and
    /// supports, the anchors, the solver's rows) then sees the pair where it is.
    ///
    /// Why relative: judged on each body's own motion, the bricks of a wall swaying by a fraction
    /// of a millimetre refreshed their manifolds every few steps, and each refresh moved the points
    /// the solver leans on. Why followed: left stale, the points and separations lagged the bodies,
    /// and what leans on them moved the pile. Kept awake a minute at 4 sub-steps, eight nudged
    /// copies of the running-bond wall held still in 2 cases, of the touching pyramid in 7;
    /// followed in the pair's frame, 7 and 8 (2026-11-30; the copies of `nudge bench rest`).
    pub fn follow(
        &mut self,
        pose_a: &Pose,
        pose_b: &Pose,
        shape_a: &Shape,
        shape_b: &Shape,
        tolerance: f32,
    ) -> bool {
        // Worked in `Vec3A` (one SIMD register a vector): the same products and sums, component by
        // component and in the same order, as in `Vec3`, so the same bits, in a quarter fewer
        // instructions (callgrind, touching pyramid; see `Computed` for the time).
        let (then_a, then_b) = (&self.pose_a, &self.pose_b);
        let a_is_ball = matches!(shape_a, Shape::Sphere { .. });
        let cap = if a_is_ball || matches!(shape_b, Shape::Sphere { .. }) {
            tolerance
        } else {
            REUSE_ABSOLUTE_FACTOR * tolerance
        };
        // A body that has moved farther than the cap decides at once, without the turns (a rain's
        // falling bodies). Here and below, written so that NaN fails: a lost pose never holds.
        let near = |then: &Pose, now: &Pose| (position(now) - position(then)).length() < cap;
        if !(near(then_b, pose_b) && near(then_a, pose_a)) {
            return false;
        }
        // Each body's own motion (exactly zero for one that has not moved: a static A carries
        // nothing, not even the rounding of q·q⁻¹, which walked a box down a ramp when it did).
        let (shift_a, turn_a) = moved_since(then_a, pose_a);
        let (shift_b, turn_b) = moved_since(then_b, pose_b);
        let (radius_a, radius_b) = (shape_a.bounding_radius(), shape_b.bounding_radius());
        let within = |shift: Vec3A, turn: Vec3A, radius: f32, limit: f32| {
            shift.length() + turn.length() * radius < limit
        };
        // What A carries with it: its turn, none for a ball, whose surface is the same however it
        // turns. B's motion relative to A is then its own less what it would have had riding with
        // A, all to first order: the turns are under a milliradian within the cap, and the
        // second-order terms a micrometre or less.
        let carry = if a_is_ball { Vec3A::ZERO } else { turn_a };
        let dp = shift_b - shift_a - carry.cross(position(then_b) - position(then_a));
        let dtheta = turn_b - carry;
        if !(within(dp, dtheta, radius_b, tolerance)
            && within(shift_a, turn_a, radius_a, cap)
            && within(shift_b, turn_b, radius_b, cap))
        {
            return false;
        }
        let (computed, m) = (&self.computed, &mut self.manifold);
        let carried = |v: Vec3| {
            let v = Vec3A::from(v);
            v + carry.cross(v)
        };
        let normal = carried(computed.normal);
        (m.normal, m.approach) = (normal.into(), carried(computed.approach).into());
        // n·(dp + dθ × r_b) = n·dp + r_b·(n × dθ), r_b from B's centre now.
        let (shift, tilt) = (normal.dot(dp), normal.cross(dtheta));
        let (x_a, x_b) = (position(then_a), position(pose_b));
        let points = m.points[..m.len].iter_mut();
        for ((p, &c), &separation) in points.zip(&computed.points).zip(&computed.separations) {
            let c = Vec3A::from(c);
            let point = c + shift_a + carry.cross(c - x_a);
            p.point = point.into();
            p.separation = separation + shift + tilt.dot(point - x_b);
        }
        true
    }

    /// Copies the normal impulses of `old`'s points onto the points of `self` with the same feature id,
    /// and the manifold's friction impulses. Points with a new id share equally the impulse of the old
    /// points that have no successor, when the normal has turned by less than
    /// [`LOAD_CARRY_MIN_COS`]: the total warm-start impulse of the pair is kept.
    ///
    /// Why: two faces of similar size sliding over each other (a box dragged from under another) clip to
    /// a polygon whose kept points swap between the two boxes' corners and edge crossings from one step
    /// to the next, so ids change while the load stays the same. Starting those points at zero dropped
    /// up to the whole load from the warm start for a step; the soft rows win it back only slowly (and
    /// under a heavier body the shock pass carries the deficit, unseen by friction), so friction at that
    /// contact and every support below it was too weak exactly while the bodies slid (the box pulled out
    /// from under an equal box went 6 % too far in 0.3 s). Bullet's persistent manifold matches points by
    /// distance for the same reason; sharing the orphaned load keeps the id matching exact where it holds.
    pub fn inherit_impulses(&mut self, old: &Contact) {
        let mut orphaned = 0.0;
        let mut new_points = 0u32;
        for (j, q) in old.manifold.points().iter().enumerate() {
            if !self.manifold.points().iter().any(|p| p.id == q.id) {
                orphaned += old.impulses.normal[j];
            }
        }
        for (i, p) in self.manifold.points().iter().enumerate() {
            match old.manifold.points().iter().position(|q| q.id == p.id) {
                Some(j) => self.impulses.normal[i] = old.impulses.normal[j],
                None => {
                    self.impulses.normal[i] = 0.0;
                    new_points += 1;
                }
            }
        }
        if new_points > 0
            && orphaned > 0.0
            && self.manifold.normal.dot(old.manifold.normal) >= LOAD_CARRY_MIN_COS
        {
            let share = orphaned / new_points as f32;
            for (i, p) in self.manifold.points().iter().enumerate() {
                if !old.manifold.points().iter().any(|q| q.id == p.id) {
                    self.impulses.normal[i] = share;
                }
            }
        }
        self.impulses.tangent = old.impulses.tangent;
        self.impulses.fed_tangent = old.impulses.fed_tangent;
        self.impulses.fed_load = old.impulses.fed_load;
        self.impulses.fed_offset = old.impulses.fed_offset;
        self.impulses.anchor = old.impulses.anchor;
        self.impulses.rolling = old.impulses.rolling;
        // A one-point manifold has no twist row (a point cannot resist turning about the normal): it
        // inherits no twist. Inherited, the old twist was warm-started every sub-step and never
        // solved, a phantom torque about the normal for as long as the body stood on one point.
        (self.impulses.twist, self.impulses.twist_anchor) = if self.manifold.len > 1 {
            (old.impulses.twist, old.impulses.twist_anchor)
        } else {
            (0.0, 0.0)
        };
    }
}

/// The rolling-resistance limit of a contact between `a` and `b` (coefficients `μr_a`, `μr_b`): the
/// larger coefficient (a ball rolls no better on a soft floor because the ball is hard) times the
/// radius the couple acts through: a ball's radius against a box, the radius of relative curvature
/// r_a·r_b/(r_a + r_b) between two balls, m. Boxes do not roll: 0 between two boxes.
#[inline]
pub(crate) fn rolling_limit(a: &Shape, mu_a: f32, b: &Shape, mu_b: f32) -> f32 {
    let radius = match (a, b) {
        (Shape::Sphere { radius: ra }, Shape::Sphere { radius: rb }) => ra * rb / (ra + rb),
        (Shape::Sphere { radius }, _) | (_, Shape::Sphere { radius }) => *radius,
        _ => 0.0,
    };
    mu_a.max(mu_b) * radius
}

/// Combined friction of two materials: the geometric mean √(μa·μb). Like Box2D; a frictionless (μ = 0)
/// surface is frictionless against anything.
#[inline]
pub(crate) fn mix_friction(a: f32, b: f32) -> f32 {
    (a * b).sqrt()
}

/// Combined restitution of two materials: the larger. Like Box2D; a bouncy ball bounces on any floor.
#[inline]
pub(crate) fn mix_restitution(a: f32, b: f32) -> f32 {
    a.max(b)
}

/// Translation (m) and rotation vector (rad) that take a body from pose `then` to pose `now`, the
/// rotation to first order (twice the vector part of q_now·q_then⁻¹, on the short way round): how far it
/// moved since a manifold was computed at `then`. Exactly zero when the poses are equal.
pub(crate) fn moved_since(then: &Pose, now: &Pose) -> (Vec3A, Vec3A) {
    let (from, to) = (position(then), position(now));
    // `then == now`, the positions compared in the registers they are in.
    if from == to && then.rotation == now.rotation {
        return (Vec3A::ZERO, Vec3A::ZERO);
    }
    let q = now.rotation * then.rotation.inverse();
    // The vector part, read straight out of the quaternion's register (its w lane is never read).
    let half_angle_axis = Vec3A::from_vec4(Vec4::from(q));
    let sign = if q.w < 0.0 { -2.0 } else { 2.0 };
    (to - from, sign * half_angle_axis)
}

/// A pose's position in a SIMD register.
#[inline(always)]
fn position(pose: &Pose) -> Vec3A {
    Vec3A::from(pose.position)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn motion_since_a_pose_is_zero_for_the_same_pose_and_first_order_otherwise() {
        use glam::Quat;
        let then = Pose {
            position: Vec3::new(1.0, 2.0, 3.0),
            rotation: Quat::from_rotation_y(0.4),
        };
        assert_eq!(moved_since(&then, &then), (Vec3A::ZERO, Vec3A::ZERO));
        let turn = Vec3::new(0.001, -0.002, 0.0005);
        let now = Pose {
            position: then.position + Vec3::new(0.0001, 0.0, -0.0002),
            rotation: Quat::from_scaled_axis(turn) * then.rotation,
        };
        let (shift, rotation) = moved_since(&then, &now);
        assert!((shift - Vec3A::new(0.0001, 0.0, -0.0002)).length() < 1e-6);
        assert!(
            (rotation - Vec3A::from(turn)).length() < 1e-6,
            "{rotation} vs {turn}"
        );
    }
    use crate::physics::ContactPoint;

    fn contact_with_ids(ids: &[u32]) -> Contact {
        let mut manifold = Manifold {
            normal: Vec3::Y,
            ..Default::default()
        };
        for &id in ids {
            manifold.push(ContactPoint {
                point: Vec3::ZERO,
                separation: 0.0,
                id,
            });
        }
        Contact {
            a: 0,
            b: 1,
            manifold,
            impulses: Default::default(),
            friction: 0.5,
            restitution: 0.0,
            rolling_resistance: 0.0,
            soft_depth: crate::physics::solve::push_out::SOFT_DEPTH,
            computed: Computed::of(&manifold),
            pose_a: Pose::IDENTITY,
            pose_b: Pose::IDENTITY,
            statics: None,
        }
    }

    #[test]
    fn impulses_follow_feature_ids_and_new_points_share_the_load_of_vanished_ones() {
        let mut old = contact_with_ids(&[7, 9, 11]);
        old.impulses.normal = [1.0, 2.0, 4.0, 0.0];
        let mut new = contact_with_ids(&[9, 3, 5]);
        new.inherit_impulses(&old);
        // Point 9 keeps its own 2; points 7 and 11 (1 + 4) vanished, so 3 and 5 get 2.5 each.
        assert_eq!(new.impulses.normal[..3], [2.0, 2.5, 2.5]);
    }

    #[test]
    fn a_one_point_manifold_inherits_friction_but_no_twist() {
        let mut old = contact_with_ids(&[1, 2, 3, 4]);
        old.impulses.tangent = Vec3::new(0.3, 0.0, -0.1);
        old.impulses.twist = 0.25;
        let mut edge = contact_with_ids(&[1, 2]);
        edge.inherit_impulses(&old);
        assert_eq!(
            (edge.impulses.tangent, edge.impulses.twist),
            (old.impulses.tangent, 0.25)
        );
        let mut corner = contact_with_ids(&[1]);
        corner.inherit_impulses(&old);
        assert_eq!(
            (corner.impulses.tangent, corner.impulses.twist),
            (old.impulses.tangent, 0.0)
        );
    }

    #[test]
    fn new_points_start_at_zero_when_the_normal_has_turned() {
        let mut old = contact_with_ids(&[7, 9]);
        old.impulses.normal = [1.0, 2.0, 0.0, 0.0];
        let mut new = contact_with_ids(&[9, 3]);
        new.manifold.normal = Vec3::new(1.0, 1.0, 0.0).normalize();
        new.inherit_impulses(&old);
        assert_eq!(new.impulses.normal[..2], [2.0, 0.0]);
    }

    #[test]
    fn a_manifold_is_reused_only_while_both_bodies_stay_within_tolerance() {
        let c = contact_with_ids(&[1]);
        let ball = Shape::sphere(1.0);
        let holds = |a: &Pose, b: &Pose| ({ c }).follow(a, b, &ball, &ball, 1e-4);
        let nudged = Pose::from_position(Vec3::new(0.00005, 0.0, 0.0));
        assert!(holds(&nudged, &Pose::IDENTITY));
        let moved = Pose::from_position(Vec3::new(0.0002, 0.0, 0.0));
        assert!(!holds(&Pose::IDENTITY, &moved));
        let turned = Pose::new(Vec3::ZERO, glam::Quat::from_rotation_y(0.001));
        assert!(!holds(&turned, &Pose::IDENTITY));
    }

    #[test]
    fn a_manifold_is_not_reused_for_a_nan_pose() {
        let c = contact_with_ids(&[1]);
        let ball = Shape::sphere(1.0);
        let holds = |a: &Pose, b: &Pose| ({ c }).follow(a, b, &ball, &ball, 1e-4);
        let lost = Pose::from_position(Vec3::new(f32::NAN, 0.0, 0.0));
        assert!(!holds(&lost, &Pose::IDENTITY));
        assert!(!holds(&Pose::IDENTITY, &lost));
        let spun = Pose::new(Vec3::ZERO, glam::Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0));
        assert!(!holds(&Pose::IDENTITY, &spun));
        assert!(!holds(&spun, &Pose::IDENTITY));
    }

    /// Two boxes one on the other, both moved together by 0.3 mm and turned 0.02° (past what B
    /// may move relative to A, within what each may move): the manifold holds, its points
    /// and normal ride with A and its separations stay as computed; B then lowered 0.05 mm onto A
    /// deepens every point by that.
    #[test]
    fn a_followed_manifold_rides_with_the_pair_and_moves_with_b_relative_to_a() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let mut c = contact_with_ids(&[1, 2]);
        c.manifold.points[0].point = Vec3::new(-0.5, 0.5, 0.0);
        c.manifold.points[1].point = Vec3::new(0.5, 0.5, 0.0);
        c.manifold.points[1].separation = -0.001;
        c.pose_b = Pose::from_position(Vec3::Y);
        c.computed = Computed::of(&c.manifold);
        let motion = Pose::new(
            Vec3::new(0.0003, 0.0, 0.0),
            glam::Quat::from_rotation_z(0.02f32.to_radians()),
        );
        let moved = |p: Pose| {
            Pose::new(
                motion.transform_point(p.position),
                motion.rotation * p.rotation,
            )
        };
        let (a, b) = (moved(c.pose_a), moved(c.pose_b));
        assert!(c.follow(&a, &b, &cube, &cube, 2e-4));
        for (p, &then) in c.manifold.points().iter().zip(&c.computed.points) {
            assert!((p.point - motion.transform_point(then)).length() < 1e-6);
        }
        assert!((c.manifold.normal - motion.rotation * Vec3::Y).length() < 1e-6);
        let separations = c.manifold.points().iter().map(|p| p.separation);
        for (got, want) in separations.zip([0.0, -0.001]) {
            assert!((got - want).abs() < 1e-6, "{got} vs {want}");
        }
        let lowered = Pose::new(b.position - 0.00005 * c.manifold.normal, b.rotation);
        assert!(c.follow(&a, &lowered, &cube, &cube, 2e-4));
        let separations = c.manifold.points().iter().map(|p| p.separation);
        for (got, want) in separations.zip([-0.00005, -0.00105]) {
            assert!((got - want).abs() < 1e-6, "{got} vs {want}");
        }
        // A moved alone that far leaves B behind: the manifold no longer holds.
        assert!(!c.follow(&a, &{ c.pose_b }, &cube, &cube, 2e-4));
    }

    /// A ball's surface is the same however it turns: a manifold with a ball as A rides with its
    /// translation alone, and a static A that has not moved leaves the points exactly as computed.
    #[test]
    fn a_ball_carries_its_manifold_by_translation_and_a_still_a_carries_nothing() {
        let (ball, cube) = (Shape::sphere(0.5), Shape::cuboid(Vec3::splat(0.5)));
        let mut c = contact_with_ids(&[1]);
        c.manifold.points[0].point = Vec3::new(0.0, 0.5, 0.0);
        c.pose_b = Pose::from_position(Vec3::Y);
        c.computed = Computed::of(&c.manifold);
        let shift = Vec3::new(0.00002, 0.0, 0.00001);
        let rolled = Pose::new(shift, glam::Quat::from_rotation_z(0.00003));
        let b = Pose::new(c.pose_b.position + shift, c.pose_b.rotation);
        assert!(c.follow(&rolled, &b, &ball, &cube, 2e-4));
        assert_eq!(c.manifold.normal, Vec3::Y);
        assert!((c.manifold.points[0].point - (Vec3::new(0.0, 0.5, 0.0) + shift)).length() < 1e-7);
        let mut still = contact_with_ids(&[1]);
        still.manifold.points[0].point = Vec3::new(0.3, 0.5, -0.2);
        still.pose_b = Pose::from_position(Vec3::Y);
        still.computed = Computed::of(&still.manifold);
        let nudged = Pose::new(
            Vec3::new(0.0, 1.00001, 0.0),
            glam::Quat::from_rotation_x(0.0001),
        );
        assert!(still.follow(&Pose::IDENTITY, &nudged, &cube, &cube, 2e-4));
        assert_eq!(still.manifold.points[0].point, Vec3::new(0.3, 0.5, -0.2));
        assert_eq!(still.manifold.normal, Vec3::Y);
        // B rose 0.01 mm and its turn lifted the point 0.2 m behind its centre by 0.02 mm.
        let separation = still.manifold.points[0].separation;
        assert!((separation - 0.00003).abs() < 1e-7, "{separation}");
    }

    #[test]
    fn frictionless_surface_stays_frictionless_and_bounce_takes_the_larger() {
        assert_eq!(mix_friction(0.0, 0.9), 0.0);
        assert!((mix_friction(0.25, 1.0) - 0.5).abs() < 1e-6);
        assert_eq!(mix_restitution(0.2, 0.5), 0.5);
    }
}
