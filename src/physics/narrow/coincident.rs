//! Bodies whose centres coincide have no direction to separate along.
//!
//! Every narrow-phase routine picks one anyway (the first of the tied face axes, +y for two
//! concentric balls), the same for every pair, so N bodies spawned at one point were pushed apart
//! along one line: body i by all the others in the same direction, the line growing N times faster
//! than one pair separates. A crowd should spread out like a pile instead. So a pair whose centres
//! coincide is collided as if each body sat a hair's breadth off the common point, at a place of its
//! own drawn from its index (deterministic): B is taken `NUDGE_PER_SIZE` of its size off A's centre
//! along the difference of the two places. The places are those of one consistent jittered cloud,
//! so the pairs of a crowd separate along axes that agree with each other (pair-by-pair directions
//! did not: three bodies could each be told to pass the next, a cycle no velocities satisfy), and
//! once the bodies have moved, their real offsets decide as usual. The contact points move by half
//! the nudge, far below the slop.
//!
//! Under gravity the cloud is a disc across it: of all the equally short ways apart, the sideways
//! ones lift nothing, so the crowd spreads over what it stands on instead of stacking itself into a
//! tower that then topples (50 boxes in a ball-shaped cloud climbed four layers high, and the ones
//! that slid off the top hit the ground at 5.3 m/s). Without gravity it is a ball.
//!
//! The disc only decides the first step. After it the centres are a few millimetres apart, the
//! floor has stopped the lowest bodies and gravity has moved the others, so the offsets left are as
//! often vertical as sideways, and the separating axis the narrow phase picks is the one of least
//! overlap: vertical whenever the offset is more up than across, and always for boxes turned about
//! the vertical (a box turned by 45° reaches 0.71 across, so two such boxes overlap 1.21 across
//! against 1.0 up). Each such pair was pushed out upwards, the floor held the lower body, and a
//! crowd sorted itself into columns: 35 aligned boxes built one 3.4 box heights tall whose top box
//! fell off at 5.8 m/s, 10 boxes each turned 0.37 rad from the last one 4.8 m tall (8.6 m/s). How far
//! apart two bodies are is no guide to how they should come apart while each holds the other's
//! centre, and of all ways apart the sideways ones lift nothing. So under gravity a pair of movable
//! bodies where one holds the other's centre is not collided: its contact ([`across_gravity`]) has
//! the normal across gravity, along the centres' offset (or the disc's direction when that offset
//! is vertical), and the depth the two bodies overlap along it. Once the centres are out of each
//! other the narrow phase decides as usual, and by then the offset is mostly across, so it agrees
//! (for aligned boxes exactly: a centre leaves the other box through a side face). A body sunk in a
//! static one, or one merely resting on another (centres outside each other), is collided as it is.

use glam::Vec3;

use crate::geometry::{Pose, Shape};
use crate::physics::narrow::manifold::{ContactPoint, Manifold};

/// How far B is taken off A's centre, as a fraction of the smaller bounding radius.
const NUDGE_PER_SIZE: f32 = 1e-4;

/// Centres closer than this fraction of the smaller bounding radius count as coincident.
const COINCIDENT_PER_SIZE: f32 = 1e-5;

/// The pose to collide body B (index `b`, `shape_b` at `pose_b`) with against body A (index `a`):
/// `pose_b` itself, or nudged off A's centre when the two centres coincide. `up` is the unit vector
/// against gravity, or zero without gravity.
#[inline]
pub(crate) fn collision_pose_b(
    (a, shape_a, pose_a): (u32, &Shape, &Pose),
    (b, shape_b, pose_b): (u32, &Shape, &Pose),
    up: Vec3,
) -> Pose {
    let size = shape_a.bounding_radius().min(shape_b.bounding_radius());
    let d = pose_b.position - pose_a.position;
    let tie = COINCIDENT_PER_SIZE * size;
    if d.length_squared() >= tie * tie {
        return *pose_b;
    }
    let apart = (jitter(b, up) - jitter(a, up)).normalize_or(Vec3::Y);
    Pose {
        position: pose_a.position + NUDGE_PER_SIZE * size * apart,
        rotation: pose_b.rotation,
    }
}

/// The contact of two movable bodies that each hold the other's centre, under gravity (`up` ≠ 0):
/// a single point halfway between the centres, with the normal across gravity along the centres'
/// offset (or their places in the disc when that offset is vertical), and the depth the bodies
/// overlap along it: their reaches along the normal less the offset along it (the separating-axis
/// distance on that axis, exact for boxes and balls). `None` for any other pair, which the narrow
/// phase collides as it is. The normal points from A (index `a`) to B (index `b`).
pub(crate) fn across_gravity(
    (a, shape_a, pose_a): (u32, &Shape, &Pose),
    (b, shape_b, pose_b): (u32, &Shape, &Pose),
    up: Vec3,
) -> Option<Manifold> {
    let d = pose_b.position - pose_a.position;
    // A body holds no point outside its bounding sphere, so centres farther apart than both radii
    // (give or take the rotation's rounding, a part in a thousand) hold neither: almost every
    // pair, settled without turning either centre into the other's frame.
    let radius = shape_a.bounding_radius().max(shape_b.bounding_radius()) * 1.001;
    if up == Vec3::ZERO
        || d.length_squared() > radius * radius
        || !(holds(shape_a, pose_a, pose_b.position) || holds(shape_b, pose_b, pose_a.position))
    {
        return None;
    }
    let across = d - up * d.dot(up);
    let tie = COINCIDENT_PER_SIZE * shape_a.bounding_radius().min(shape_b.bounding_radius());
    let normal = if across.length_squared() >= tie * tie {
        across.normalize()
    } else {
        (jitter(b, up) - jitter(a, up)).normalize_or(up.any_orthonormal_vector())
    };
    let reach = shape_a.reach(pose_a.rotation, normal) + shape_b.reach(pose_b.rotation, normal);
    let mut manifold = Manifold {
        normal,
        ..Manifold::default()
    };
    manifold.push(ContactPoint {
        point: pose_a.position + 0.5 * d,
        separation: d.dot(normal) - reach,
        id: ACROSS_GRAVITY_ID,
    });
    Some(manifold)
}

/// The feature id of the single point [`across_gravity`] makes: one that no pair of features uses.
const ACROSS_GRAVITY_ID: u32 = u32::MAX - 0x4d58;

/// Whether `point` lies inside `shape` at `pose`.
fn holds(shape: &Shape, pose: &Pose, point: Vec3) -> bool {
    let local = pose.rotation.inverse() * (point - pose.position);
    match *shape {
        Shape::Cuboid { half_extents } => local.abs().cmplt(half_extents).all(),
        Shape::Sphere { radius } => local.length_squared() < radius * radius,
    }
}

/// A point of the unit disc across `up` (or of the unit ball when `up` is zero) that depends only on
/// the body index: the index mixed (SplitMix64's finaliser) into three uniform numbers, mapped to a
/// uniformly distributed point.
fn jitter(body: u32, up: Vec3) -> Vec3 {
    let mut h = u64::from(body).wrapping_add(0x9e37_79b9_7f4a_7c15);
    h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    h ^= h >> 31;
    let unit = |bits: u64| (bits & 0x1f_ffff) as f32 / (1u32 << 21) as f32;
    let (u, v, w) = (unit(h), unit(h >> 21), unit(h >> 42));
    let angle = std::f32::consts::TAU * v;
    if up == Vec3::ZERO {
        // Archimedes: a uniform height gives a uniform point of the sphere; the cube root of a
        // uniform number a uniform radius in the ball.
        let height = 1.0 - 2.0 * u;
        let ring = (1.0 - height * height).max(0.0).sqrt();
        w.cbrt() * Vec3::new(ring * angle.cos(), height, ring * angle.sin())
    } else {
        let (across, along) = up.any_orthonormal_pair();
        u.sqrt() * (angle.cos() * across + angle.sin() * along)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn jitter_fills_the_ball_without_gravity_and_the_disc_across_it_with() {
        for up in [Vec3::ZERO, Vec3::Y, Vec3::new(0.6, 0.0, 0.8)] {
            let mut sum = Vec3::ZERO;
            let mut octants = [0u32; 8];
            for body in 0..800 {
                let p = jitter(body, up);
                assert!(p.length() <= 1.0 + 1e-5, "{p}");
                assert!(p.dot(up).abs() < 1e-5, "{p} leaves the disc across {up}");
                sum += p;
                let octant = usize::from(p.x > 0.0)
                    | usize::from(p.y > 0.0) << 1
                    | usize::from(p.z > 0.0) << 2;
                octants[octant] += 1;
            }
            // Centred, and spread over every octant the disc or ball reaches.
            assert!(sum.length() / 800.0 < 0.1, "{up}: {sum}");
            let reached = octants.iter().filter(|&&n| n > 40).count();
            assert!(reached >= 4, "{up}: {octants:?}");
            if up == Vec3::ZERO {
                assert_eq!(reached, 8, "{octants:?}");
            }
        }
    }

    #[test]
    fn only_coincident_centres_are_nudged_and_only_by_a_hair() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let here = Pose::from_position(Vec3::new(3.0, 1.0, -2.0));
        let apart = Pose::from_position(Vec3::new(3.001, 1.0, -2.0));
        let pose_b =
            |b: u32, pose: &Pose| collision_pose_b((1, &cube, &here), (b, &cube, pose), Vec3::Y);
        assert_eq!(pose_b(2, &apart), apart);
        let nudged = pose_b(2, &here);
        let shift = nudged.position - here.position;
        assert!(shift.length() > 0.0 && shift.length() < 1e-4, "{shift}");
        assert!(shift.y.abs() < 1e-9, "sideways under gravity: {shift}");
        assert_ne!(pose_b(3, &here).position, nudged.position);
    }

    #[test]
    fn coincident_pairs_are_nudged_as_one_consistent_cloud() {
        // Each pair along the difference of its bodies' own places: the nudges of pairs (3, 5),
        // (5, 7) and (3, 7) are those of one set of per-body offsets.
        let ball = Shape::sphere(0.5);
        let here = Pose::IDENTITY;
        for (a, b) in [(3, 5), (5, 7), (3, 7)] {
            let got = collision_pose_b((a, &ball, &here), (b, &ball, &here), Vec3::ZERO);
            let expected = (jitter(b, Vec3::ZERO) - jitter(a, Vec3::ZERO)).normalize();
            assert!(
                (got.position.normalize() - expected).length() < 1e-4,
                "{a} {b}"
            );
        }
    }

    #[test]
    fn bodies_holding_each_others_centre_come_apart_across_gravity_by_their_overlap() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let a = Pose::from_position(Vec3::new(0.0, 0.5, 0.0));
        // Mostly above, a little to the side, turned 45° about the vertical: the face axes would
        // say up (1.0 − 0.3 = 0.7 deep, against 0.5 + 0.71 − 0.1 = 1.11 across).
        let b = Pose::new(
            Vec3::new(0.1, 0.8, 0.0),
            Quat::from_rotation_y(std::f32::consts::FRAC_PI_4),
        );
        let m = across_gravity((1, &cube, &a), (2, &cube, &b), Vec3::Y).expect("deep pair");
        assert!((m.normal - Vec3::X).length() < 1e-6, "{}", m.normal);
        let depth = 0.5 + std::f32::consts::FRAC_1_SQRT_2 - 0.1;
        assert_eq!(m.len, 1);
        assert!((m.points[0].separation + depth).abs() < 1e-5, "{m:?}");
        assert!((m.points[0].point - Vec3::new(0.05, 0.65, 0.0)).length() < 1e-6);
        // Resting on it (centres outside each other), without gravity, or coincident: collided as
        // they are, as they are, and along the disc.
        let resting = Pose::from_position(Vec3::new(0.1, 1.49, 0.0));
        assert!(across_gravity((1, &cube, &a), (2, &cube, &resting), Vec3::Y).is_none());
        assert!(across_gravity((1, &cube, &a), (2, &cube, &b), Vec3::ZERO).is_none());
        let m = across_gravity((1, &cube, &a), (2, &cube, &a), Vec3::Y).expect("coincident");
        assert!(m.normal.y.abs() < 1e-6 && (m.normal.length() - 1.0).abs() < 1e-5);
        let depth = 2.0 * cube.reach(Quat::IDENTITY, m.normal);
        assert!((m.points[0].separation + depth).abs() < 1e-5, "{m:?}");
    }
}
