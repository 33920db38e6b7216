//! Broad phase against an O(N²) brute force on random sets: mixed kinds, huge statics, clusters,
//! duplicates, very different sizes, far-away and degenerate boxes, and the raining-pit scene.
//! Exact agreement is required (both use the same `Aabb::overlaps`).

use glam::Vec3;
use nudge::geometry::Aabb;
use nudge::physics::broad::broad_phase::{BodyKind, BroadPhase};
use nudge::scene::cases;
use nudge::util::SplitMix64 as Rng;

fn brute_force(aabbs: &[Aabb], kinds: &[BodyKind]) -> Vec<(u32, u32)> {
    let mut pairs = Vec::new();
    for i in 0..aabbs.len() {
        for j in (i + 1)..aabbs.len() {
            if kinds[i].may_touch(kinds[j]) && aabbs[i].overlaps(&aabbs[j]) {
                pairs.push((i as u32, j as u32));
            }
        }
    }
    pairs
}

fn check(broad: &mut BroadPhase, aabbs: &[Aabb], kinds: &[BodyKind], label: &str) -> usize {
    let mut pairs = vec![(7, 7)]; // stale content must be cleared
    broad.find_pairs(aabbs, kinds, &mut pairs);
    let expected = brute_force(aabbs, kinds);
    assert_eq!(pairs.len(), expected.len(), "{label}: pair count");
    assert_eq!(pairs, expected, "{label}");
    pairs.len()
}

fn random_kind(rng: &mut Rng) -> BodyKind {
    match rng.below(10) {
        0 => BodyKind::Static,
        1..=3 => BodyKind::Sleeping,
        _ => BodyKind::Dynamic,
    }
}

#[test]
fn random_sets_match_brute_force() {
    let mut rng = Rng(42);
    let mut broad = BroadPhase::new();
    let mut total = 0;
    for round in 0..60 {
        let n = 1 + rng.below(400) as usize;
        let world = rng.range(2.0, 60.0);
        let mut aabbs = Vec::with_capacity(n);
        let mut kinds = Vec::with_capacity(n);
        for _ in 0..n {
            let kind = random_kind(&mut rng);
            let half = match rng.below(20) {
                // Huge floors and walls.
                0 => Vec3::new(
                    rng.range(5.0, 50.0),
                    rng.range(0.1, 3.0),
                    rng.range(5.0, 50.0),
                ),
                // Tiny.
                1 => Vec3::splat(rng.range(1e-4, 1e-2)),
                // Long sticks.
                2 => Vec3::new(rng.range(2.0, 6.0), 0.1, 0.1),
                _ => Vec3::new(
                    rng.range(0.2, 1.0),
                    rng.range(0.2, 1.0),
                    rng.range(0.2, 1.0),
                ),
            };
            let center = Vec3::new(
                rng.range(-world, world),
                rng.range(-world, world),
                rng.range(-world, world),
            );
            aabbs.push(Aabb::from_center_half_extents(center, half));
            kinds.push(kind);
        }
        // Duplicates and exactly touching neighbours.
        if n > 3 {
            aabbs[1] = aabbs[0];
            let a = aabbs[2];
            aabbs[3] = Aabb::new(
                a.min + Vec3::X * (a.max.x - a.min.x),
                a.max + Vec3::X * (a.max.x - a.min.x),
            );
        }
        total += check(&mut broad, &aabbs, &kinds, &format!("round {round}"));
    }
    assert!(total > 1000, "only {total} pairs in all rounds");
}

#[test]
fn dense_cluster_and_far_away_bodies_match_brute_force() {
    let mut rng = Rng(3);
    let mut aabbs = Vec::new();
    let mut kinds = Vec::new();
    for _ in 0..600 {
        let center = Vec3::new(
            rng.range(-3.0, 3.0),
            rng.range(0.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        aabbs.push(Aabb::from_center_half_extents(center, Vec3::splat(0.4)));
        kinds.push(random_kind(&mut rng));
    }
    for x in [1e6f32, -3e7, 1e30, -1e30] {
        aabbs.push(Aabb::from_center_half_extents(
            Vec3::new(x, 0.0, x),
            Vec3::splat(0.4),
        ));
        kinds.push(BodyKind::Dynamic);
        aabbs.push(Aabb::from_center_half_extents(
            Vec3::new(x, 0.3, x),
            Vec3::splat(0.4),
        ));
        kinds.push(BodyKind::Dynamic);
    }
    let pairs = check(&mut BroadPhase::new(), &aabbs, &kinds, "cluster");
    assert!(pairs > 1000);
}

#[test]
fn degenerate_bounds_match_brute_force() {
    let mut aabbs = vec![
        Aabb::new(Vec3::splat(f32::NAN), Vec3::ONE),
        Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY)),
        Aabb::new(Vec3::ZERO, Vec3::ZERO),
        Aabb::new(Vec3::ZERO, Vec3::ZERO),
        Aabb::new(Vec3::ONE, Vec3::ZERO), // inverted: overlaps nothing it does not straddle
    ];
    let mut kinds = vec![BodyKind::Dynamic; aabbs.len()];
    check(&mut BroadPhase::new(), &aabbs, &kinds, "degenerate");
    // No non-static body at all, and an empty input.
    kinds.iter_mut().for_each(|k| *k = BodyKind::Static);
    check(&mut BroadPhase::new(), &aabbs, &kinds, "all static");
    aabbs.clear();
    kinds.clear();
    check(&mut BroadPhase::new(), &aabbs, &kinds, "empty");
}

#[test]
fn raining_pit_matches_brute_force_and_is_deterministic() {
    let scene = cases::rain(1500);
    let aabbs: Vec<Aabb> = scene
        .bodies
        .iter()
        .map(|b| b.desc.shape.aabb(&b.desc.pose).expanded(0.3))
        .collect();
    let kinds: Vec<BodyKind> = scene
        .bodies
        .iter()
        .map(|b| {
            if b.desc.is_static {
                BodyKind::Static
            } else {
                BodyKind::Dynamic
            }
        })
        .collect();
    let mut broad = BroadPhase::new();
    check(&mut broad, &aabbs, &kinds, "rain");
    let (mut first, mut second) = (Vec::new(), Vec::new());
    broad.find_pairs(&aabbs, &kinds, &mut first);
    BroadPhase::new().find_pairs(&aabbs, &kinds, &mut second);
    assert_eq!(first, second);
}

/// One broad phase reused over many calls on a moving crowd, as a world uses it: its last orders, row
/// edge and sweep axis only speed the next call up, so every call must still agree with brute force
/// when bodies drift, teleport, change kind, join and leave, all grow or shrink, and when the crowd's
/// widest axis turns.
#[test]
fn a_reused_broad_phase_follows_a_moving_crowd_exactly() {
    let mut rng = Rng(11);
    let mut broad = BroadPhase::new();
    let mut aabbs: Vec<Aabb> = Vec::new();
    let mut kinds: Vec<BodyKind> = Vec::new();
    let mut velocities: Vec<Vec3> = Vec::new();
    let mut total = 0;
    for call in 0..120 {
        // Join: grow to between 50 and 400 bodies; leave: sometimes drop the tail.
        let target = 50 + rng.below(350) as usize;
        if call % 7 == 3 && aabbs.len() > target {
            aabbs.truncate(target);
            kinds.truncate(target);
            velocities.truncate(target);
        }
        while aabbs.len() < target {
            let center = Vec3::new(
                rng.range(-6.0, 6.0),
                rng.range(0.0, 3.0),
                rng.range(-6.0, 6.0),
            );
            let half = Vec3::new(
                rng.range(0.2, 0.7),
                rng.range(0.2, 0.7),
                rng.range(0.2, 0.7),
            );
            aabbs.push(Aabb::from_center_half_extents(center, half));
            kinds.push(random_kind(&mut rng));
            velocities.push(Vec3::new(
                rng.next_signed(),
                rng.next_signed(),
                rng.next_signed(),
            ));
        }
        // Drift (faster on some calls, back and forth so the crowd stays dense), a few teleports and
        // kind changes.
        let speed = if call % 10 < 5 { 0.05 } else { 0.6 };
        if call % 8 == 0 {
            velocities.iter_mut().for_each(|v| *v = -*v);
        }
        for (aabb, v) in aabbs.iter_mut().zip(&velocities) {
            let d = *v * speed;
            *aabb = Aabb::new(aabb.min + d, aabb.max + d);
        }
        for _ in 0..3 {
            let i = rng.below(aabbs.len() as u64) as usize;
            let d = Vec3::new(rng.range(-5.0, 5.0), 0.0, rng.range(-5.0, 5.0));
            aabbs[i] = Aabb::new(aabbs[i].min + d, aabbs[i].max + d);
            let j = rng.below(kinds.len() as u64) as usize;
            kinds[j] = random_kind(&mut rng);
        }
        // Now and then every box grows (or shrinks back), so the last call's row edge no longer fits.
        if call % 25 == 12 {
            let scale = if call % 50 == 12 { 1.4 } else { 1.0 / 1.4 };
            for aabb in &mut aabbs {
                let (c, half) = (0.5 * (aabb.min + aabb.max), 0.5 * (aabb.max - aabb.min));
                *aabb = Aabb::from_center_half_extents(c, half * scale);
            }
        }
        // Every 30 calls the crowd is stretched along another axis, so the sweep axis turns.
        let axis = (call / 30) % 3;
        let stretched: Vec<Aabb> = aabbs
            .iter()
            .map(|b| {
                let mut scale = Vec3::ONE;
                scale[axis] = 2.5;
                let c = 0.5 * (b.min + b.max);
                let shift = c * scale - c;
                Aabb::new(b.min + shift, b.max + shift)
            })
            .collect();
        total += check(&mut broad, &stretched, &kinds, &format!("call {call}"));
    }
    assert!(total > 5000, "only {total} pairs in all calls");
}

#[test]
fn touching_boxes_far_from_the_origin_are_paired_along_every_axis() {
    for axis in 0..3 {
        for origin in [0.0f32, 1e5, -3e6, 2e7] {
            // A long line of boxes along `axis`, each exactly touching the next, far from the origin.
            let mut aabbs = Vec::new();
            for i in 0..40 {
                let mut min = Vec3::splat(origin);
                min[axis] += i as f32 * 0.75;
                let mut max = min + Vec3::splat(0.5);
                max[axis] = min[axis] + 0.75;
                aabbs.push(Aabb::new(min, max));
            }
            let kinds = vec![BodyKind::Dynamic; aabbs.len()];
            check(
                &mut BroadPhase::new(),
                &aabbs,
                &kinds,
                &format!("axis {axis} at {origin}"),
            );
        }
    }
}
