//! Broad phase against an O(N²) brute force on random sets: mixed kinds, huge statics, clusters,
//! duplicates, very different sizes, far-away and degenerate boxes, and the raining-pit scene.
//! Exact agreement is required (both use the same `Aabb::overlaps`).

use glam::Vec3;
use nudge::geometry::Aabb;
use nudge::physics::broad_phase::{BodyKind, BroadPhase};
use nudge::scene::cases;
use nudge::scene::cases::SplitMix64 as Rng;

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
