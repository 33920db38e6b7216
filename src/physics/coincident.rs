//! Bodies whose centres coincide have no direction to separate along.
//!
//! Every narrow-phase routine picks one anyway (the first of the tied face axes, +y for two
//! concentric balls), the same for every pair, so N bodies spawned at one point were pushed apart
//! along one line: body i by all the others in the same direction, the line growing N times faster
//! than one pair separates. A crowd should spread out like a pile instead. So a pair whose centres
//! coincide is collided as if each body sat a hair's breadth off the common point, along a
//! direction of its own drawn from its index (deterministic, uniform over the sphere): B is taken
//! `NUDGE_PER_SIZE` of its size off A's centre along the difference of the two directions. The
//! offsets are those of one consistent jittered cloud, so the pairs of a crowd separate along
//! axes that agree with each other (pair-by-pair directions did not: three bodies could each be
//! told to pass the next, a cycle no velocities satisfy), and once the bodies have moved, their
//! real offsets decide as usual. The contact points move by half the nudge, far below the slop.

use glam::Vec3;

use crate::geometry::{Pose, Shape};

/// How far B is taken off A's centre, as a fraction of the smaller bounding radius.
const NUDGE_PER_SIZE: f32 = 1e-4;

/// Centres closer than this fraction of the smaller bounding radius count as coincident.
const COINCIDENT_PER_SIZE: f32 = 1e-5;

/// The pose to collide body B (index `b`, `shape_b` at `pose_b`) with against body A (index `a`):
/// `pose_b` itself, or nudged off A's centre when the two centres coincide.
#[inline]
pub(crate) fn collision_pose_b(
    a: u32,
    b: u32,
    shape_a: &Shape,
    pose_a: &Pose,
    shape_b: &Shape,
    pose_b: &Pose,
) -> Pose {
    let size = shape_a.bounding_radius().min(shape_b.bounding_radius());
    let d = pose_b.position - pose_a.position;
    let tie = COINCIDENT_PER_SIZE * size;
    if d.length_squared() >= tie * tie {
        return *pose_b;
    }
    let apart = (jitter_direction(b) - jitter_direction(a)).normalize_or(Vec3::Y);
    Pose {
        position: pose_a.position + NUDGE_PER_SIZE * size * apart,
        rotation: pose_b.rotation,
    }
}

/// A unit direction that depends only on the body index: the index mixed (SplitMix64's finaliser)
/// into two uniform numbers, mapped onto the sphere by Archimedes' equal-area projection.
fn jitter_direction(body: u32) -> Vec3 {
    let mut h = u64::from(body).wrapping_add(0x9e37_79b9_7f4a_7c15);
    h = (h ^ (h >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    h ^= h >> 31;
    let unit = |bits: u64| (bits & 0xff_ffff) as f32 / (1u32 << 24) as f32;
    let height = 1.0 - 2.0 * unit(h);
    let angle = std::f32::consts::TAU * unit(h >> 24);
    let ring = (1.0 - height * height).max(0.0).sqrt();
    Vec3::new(ring * angle.cos(), height, ring * angle.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jitter_directions_are_unit_and_spread_over_the_sphere() {
        let mut sum = Vec3::ZERO;
        let mut octants = [0u32; 8];
        for body in 0..800 {
            let d = jitter_direction(body);
            assert!((d.length() - 1.0).abs() < 1e-5, "{d}");
            sum += d;
            let octant =
                usize::from(d.x > 0.0) | usize::from(d.y > 0.0) << 1 | usize::from(d.z > 0.0) << 2;
            octants[octant] += 1;
        }
        // The mean direction is near zero and every octant holds about an eighth.
        assert!(sum.length() / 800.0 < 0.1, "{sum}");
        assert!(octants.iter().all(|&n| n > 70), "{octants:?}");
    }

    #[test]
    fn only_coincident_centres_are_nudged_and_only_by_a_hair() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let here = Pose::from_position(Vec3::new(3.0, 1.0, -2.0));
        let apart = Pose::from_position(Vec3::new(3.001, 1.0, -2.0));
        assert_eq!(collision_pose_b(1, 2, &cube, &here, &cube, &apart), apart);
        let nudged = collision_pose_b(1, 2, &cube, &here, &cube, &here);
        let shift = (nudged.position - here.position).length();
        assert!(shift > 0.0 && shift < 1e-4, "{shift}");
        assert_ne!(
            collision_pose_b(1, 3, &cube, &here, &cube, &here).position,
            nudged.position
        );
    }

    #[test]
    fn coincident_pairs_are_nudged_as_one_consistent_cloud() {
        // Each pair along the difference of its bodies' own directions: the nudges of pairs (3, 5),
        // (5, 7) and (3, 7) are those of one set of per-body offsets.
        let ball = Shape::sphere(0.5);
        for (a, b) in [(3, 5), (5, 7), (3, 7)] {
            let got = collision_pose_b(a, b, &ball, &Pose::IDENTITY, &ball, &Pose::IDENTITY);
            let expected = (jitter_direction(b) - jitter_direction(a)).normalize();
            assert!(
                (got.position.normalize() - expected).length() < 1e-4,
                "{a} {b}"
            );
        }
    }
}
