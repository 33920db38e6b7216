//! Sphere–sphere and box–sphere contact, checked against exact f64 signed distances.
//! Tolerances: 1e-5 m for hand-built cases, 1e-4 m (relative to unit sizes) for random ones.

use glam::{DVec3, Quat, Vec3};
use nudge::geometry::{Pose, Shape};
use nudge::physics::narrow::collide::collide;
use nudge::util::SplitMix64 as Rng;

/// Exact signed distance from a box-local point to the box surface (negative inside), f64.
fn box_signed_distance(p: DVec3, h: DVec3) -> f64 {
    let q = p.abs() - h;
    q.max(DVec3::ZERO).length() + q.max_element().min(0.0)
}

#[test]
fn random_sphere_pairs_match_the_exact_distance() {
    let mut rng = Rng(1);
    for _ in 0..2000 {
        let (ra, rb) = (rng.range(0.05, 2.0), rng.range(0.05, 2.0));
        let pa = Vec3::new(
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let pb = pa
            + Vec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            );
        let margin = rng.range(0.0, 0.2);
        let m = collide(
            &Shape::sphere(ra),
            &Pose::from_position(pa),
            &Shape::sphere(rb),
            &Pose::from_position(pb),
            margin,
        );
        let exact = pa.as_dvec3().distance(pb.as_dvec3()) - ra as f64 - rb as f64;
        if exact > margin as f64 + 1e-5 {
            assert!(m.is_empty());
        } else if exact < margin as f64 - 1e-5 {
            assert_eq!(m.len, 1);
            assert!((m.points[0].separation as f64 - exact).abs() < 1e-4);
            assert!((m.normal.length() - 1.0).abs() < 1e-5);
            assert!(m.normal.dot(pb - pa) >= 0.0);
        }
    }
}

#[test]
fn sphere_centre_inside_a_box_is_pushed_out_of_each_nearest_side() {
    let half = Vec3::new(1.0, 0.5, 2.0);
    let pose = Pose::new(Vec3::new(-3000.0, 10.0, 4000.0), Quat::from_rotation_y(0.7));
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let mut c_local = Vec3::new(0.05, -0.02, 0.03);
            c_local[axis] = sign * (half[axis] - 0.1);
            let m = collide(
                &Shape::cuboid(half),
                &pose,
                &Shape::sphere(0.3),
                &Pose::from_position(pose.transform_point(c_local)),
                0.0,
            );
            assert_eq!(m.len, 1);
            let mut expected = Vec3::ZERO;
            expected[axis] = sign;
            let n_local = pose.inverse_transform_vector(m.normal);
            assert!(
                (n_local - expected).length() < 1e-4,
                "axis {axis} sign {sign}: {n_local}"
            );
            // 0.1 inside the face plus the radius; positions near 5000 carry ~5e-4 m of rounding.
            assert!((m.points[0].separation + 0.4).abs() < 2e-3);
        }
    }
}

#[test]
fn sphere_box_contact_id_survives_crossing_the_face() {
    let half = Vec3::splat(0.5);
    let id_at = |y: f32| {
        let m = collide(
            &Shape::cuboid(half),
            &Pose::IDENTITY,
            &Shape::sphere(0.2),
            &Pose::from_position(Vec3::new(0.1, y, 0.2)),
            0.0,
        );
        assert_eq!(m.len, 1);
        m.points[0].id
    };
    assert_eq!(id_at(0.51), id_at(0.49));
}

#[test]
fn random_box_sphere_pairs_match_the_exact_distance_in_both_orders() {
    let mut rng = Rng(7);
    let mut compared = 0;
    for _ in 0..4000 {
        let half = Vec3::new(
            rng.range(0.05, 2.0),
            rng.range(0.05, 2.0),
            rng.range(0.05, 2.0),
        );
        let radius = rng.range(0.02, 1.5);
        let pose_box = Pose::new(
            Vec3::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
            ),
            rng.rotation(),
        );
        let c_local = Vec3::new(
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        );
        let center = pose_box.transform_point(c_local);
        let margin = rng.range(0.0, 0.3);
        let ab = collide(
            &Shape::cuboid(half),
            &pose_box,
            &Shape::sphere(radius),
            &Pose::from_position(center),
            margin,
        );
        let ba = collide(
            &Shape::sphere(radius),
            &Pose::from_position(center),
            &Shape::cuboid(half),
            &pose_box,
            margin,
        );
        let exact = box_signed_distance(
            pose_box.inverse_transform_point(center).as_dvec3(),
            half.as_dvec3(),
        ) - radius as f64;
        assert_eq!(ab.len, ba.len);
        if exact > margin as f64 + 1e-4 {
            assert!(ab.is_empty());
        } else if exact < margin as f64 - 1e-4 {
            compared += 1;
            assert_eq!(ab.len, 1);
            let p = ab.points[0];
            assert!(
                (p.separation as f64 - exact).abs() < 1e-4,
                "{} vs {exact}",
                p.separation
            );
            assert!((ab.normal.length() - 1.0).abs() < 1e-5);
            assert!((ab.normal + ba.normal).length() < 1e-6);
            // The point lies on the normal line through the sphere centre, half the separation from the
            // sphere's surface.
            let expected = center - ab.normal * (radius + 0.5 * p.separation);
            assert!((p.point - expected).length() < 1e-3);
        }
    }
    assert!(compared > 1000, "only {compared} contacts compared");
}
