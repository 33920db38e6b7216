//! Box–box contact scenarios: resting, rotated, edge–edge, exact and deep contact, far from the origin,
//! feature-id stability. Tolerances: 1e-5 m near the origin, 1e-3 m at x = 5000 (f32 spacing there is
//! 4.9e-4 m).

use std::f32::consts::{FRAC_PI_4, SQRT_2};

use glam::{Quat, Vec3};
use nudge::geometry::{Pose, Shape};
use nudge::physics::Manifold;
use nudge::physics::narrow::collide::collide;

fn cube() -> Shape {
    Shape::cuboid(Vec3::splat(0.5))
}

fn ids(m: &Manifold) -> Vec<u32> {
    let mut ids: Vec<u32> = m.points().iter().map(|p| p.id).collect();
    ids.sort_unstable();
    ids
}

fn assert_close(a: Vec3, b: Vec3, tol: f32) {
    assert!((a - b).length() <= tol, "{a} vs {b} (tol {tol})");
}

#[test]
fn resting_cube_on_cube_gives_four_corner_points_at_the_right_depth() {
    let a = Pose::IDENTITY;
    let b = Pose::from_position(Vec3::new(0.0, 0.98, 0.0));
    let m = collide(&cube(), &a, &cube(), &b, 0.0);
    assert_eq!(m.len, 4);
    assert_close(m.normal, Vec3::Y, 1e-6);
    for p in m.points() {
        assert!((p.separation + 0.02).abs() < 1e-5, "{p:?}");
        // Midway between A's top (0.5) and B's bottom (0.48).
        assert!((p.point.y - 0.49).abs() < 1e-5);
        assert!((p.point.x.abs() - 0.5).abs() < 1e-5 && (p.point.z.abs() - 0.5).abs() < 1e-5);
    }
    assert_eq!(ids(&m).windows(2).filter(|w| w[0] == w[1]).count(), 0);
}

#[test]
fn swapping_the_boxes_flips_the_normal_and_keeps_the_depth() {
    let a = Pose::IDENTITY;
    let b = Pose::new(Vec3::new(0.2, 0.97, -0.1), Quat::from_rotation_y(0.3));
    let ab = collide(&cube(), &a, &cube(), &b, 0.0);
    let ba = collide(&cube(), &b, &cube(), &a, 0.0);
    assert_eq!(ab.len, 4);
    assert_eq!(ba.len, 4);
    assert_close(ab.normal, -ba.normal, 1e-5);
    let deepest = |m: &Manifold| {
        m.points()
            .iter()
            .map(|p| p.separation)
            .fold(f32::INFINITY, f32::min)
    };
    assert!((deepest(&ab) - deepest(&ba)).abs() < 1e-5);
    assert!((deepest(&ab) + 0.03).abs() < 1e-5);
}

#[test]
fn cube_turned_45_degrees_about_the_vertical_on_a_face_gives_an_upward_normal_and_four_points() {
    let a = Pose::IDENTITY;
    let b = Pose::new(Vec3::new(0.0, 0.99, 0.0), Quat::from_rotation_y(FRAC_PI_4));
    let m = collide(&cube(), &a, &cube(), &b, 0.0);
    assert_close(m.normal, Vec3::Y, 1e-5);
    // The clipped octagon is reduced to four points spanning it.
    assert_eq!(m.len, 4);
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
        assert!(p.point.x.abs() <= 0.5 + 1e-5 && p.point.z.abs() <= 0.5 + 1e-5);
    }
    // The four kept points span a large part of the octagon (area 2(√2 − 1) ≈ 0.83 m²).
    let p: Vec<Vec3> = m.points().iter().map(|p| p.point).collect();
    let area = 0.5
        * ((p[1] - p[0]).cross(p[2] - p[0]).length() + (p[2] - p[0]).cross(p[3] - p[0]).length());
    assert!(area > 0.5, "area {area}");
}

#[test]
fn cube_standing_on_an_edge_gives_two_points_along_that_edge() {
    let a = Pose::IDENTITY;
    // Turned 45° about z: its lowest feature is an edge along z at height y − √2/2.
    let b = Pose::new(
        Vec3::new(0.0, 0.5 + 0.5 * SQRT_2 - 0.01, 0.0),
        Quat::from_rotation_z(FRAC_PI_4),
    );
    let m = collide(&cube(), &a, &cube(), &b, 0.0);
    assert_close(m.normal, Vec3::Y, 1e-5);
    assert_eq!(m.len, 2);
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
        assert!(p.point.x.abs() < 1e-5);
        assert!((p.point.z.abs() - 0.5).abs() < 1e-5);
    }
}

#[test]
fn crossed_edges_give_one_edge_edge_point_between_them() {
    // A's top edge runs along z at y = √2/2; B's bottom edge runs along x at y_B − √2/2.
    let a = Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4));
    let b = Pose::new(
        Vec3::new(0.0, SQRT_2 - 0.02, 0.0),
        Quat::from_rotation_x(FRAC_PI_4),
    );
    let m = collide(&cube(), &a, &cube(), &b, 0.0);
    assert_eq!(m.len, 1);
    assert_close(m.normal, Vec3::Y, 1e-5);
    let p = m.points[0];
    assert!((p.separation + 0.02).abs() < 1e-5);
    assert_close(p.point, Vec3::new(0.0, 0.5 * SQRT_2 - 0.01, 0.0), 1e-5);
    // The id names one edge of each box (A's in the low six bits): swapped boxes, swapped halves.
    let swapped = collide(&cube(), &b, &cube(), &a, 0.0);
    assert_eq!(swapped.points[0].id, (p.id >> 6) | ((p.id & 0x3f) << 6));
}

#[test]
fn crossed_edges_within_the_margin_give_a_speculative_point_and_beyond_it_nothing() {
    let a = Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4));
    let b = Pose::new(
        Vec3::new(0.0, SQRT_2 + 0.05, 0.0),
        Quat::from_rotation_x(FRAC_PI_4),
    );
    let m = collide(&cube(), &a, &cube(), &b, 0.1);
    assert_eq!(m.len, 1);
    assert!((m.points[0].separation - 0.05).abs() < 1e-5);
    assert!(collide(&cube(), &a, &cube(), &b, 0.04).is_empty());
}

#[test]
fn exact_face_on_face_contact_reports_four_points_at_zero_separation() {
    let b = Pose::from_position(Vec3::new(0.0, 1.0, 0.0));
    let m = collide(&cube(), &Pose::IDENTITY, &cube(), &b, 0.0);
    assert_eq!(m.len, 4);
    for p in m.points() {
        assert!(p.separation.abs() < 1e-6);
    }
}

#[test]
fn boxes_sharing_a_parallel_edge_give_finite_contacts() {
    let b = Pose::from_position(Vec3::new(0.99, 0.99, 0.0));
    let m = collide(&cube(), &Pose::IDENTITY, &cube(), &b, 0.0);
    assert!(!m.is_empty());
    assert!((m.normal.length() - 1.0).abs() < 1e-5);
    for p in m.points() {
        assert!(p.point.is_finite());
        assert!((p.separation + 0.01).abs() < 1e-5);
    }
}

#[test]
fn coincident_boxes_give_a_finite_deep_contact() {
    for rotation in [Quat::IDENTITY, Quat::from_rotation_y(0.3)] {
        let pose = Pose::new(Vec3::new(1.0, 2.0, 3.0), rotation);
        let m = collide(&cube(), &pose, &cube(), &pose, 0.0);
        assert!(!m.is_empty());
        assert!((m.normal.length() - 1.0).abs() < 1e-5);
        for p in m.points() {
            assert!(p.point.is_finite());
            assert!((p.separation + 1.0).abs() < 1e-4, "{p:?}");
        }
    }
}

#[test]
fn small_box_on_a_huge_floor_and_tiny_boxes_give_consistent_depths() {
    let floor = Shape::cuboid(Vec3::new(1000.0, 0.5, 1000.0));
    let m = collide(
        &floor,
        &Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        &cube(),
        &Pose::new(Vec3::new(300.0, 0.499, -200.0), Quat::from_rotation_y(1.0)),
        0.0,
    );
    assert_eq!(m.len, 4);
    assert_close(m.normal, Vec3::Y, 1e-5);
    for p in m.points() {
        assert!((p.separation + 0.001).abs() < 1e-4);
    }

    let tiny = Shape::cuboid(Vec3::splat(1e-4));
    let m = collide(
        &tiny,
        &Pose::IDENTITY,
        &tiny,
        &Pose::from_position(Vec3::new(0.0, 1.9e-4, 0.0)),
        0.0,
    );
    assert_eq!(m.len, 4);
    for p in m.points() {
        assert!((p.separation + 1e-5).abs() < 1e-9);
    }
}

#[test]
fn contact_far_from_the_origin_keeps_its_depth() {
    let offset = Vec3::new(5000.0, 0.0, -5000.0);
    let a = Pose::from_position(offset);
    let b = Pose::new(
        offset + Vec3::new(0.1, 0.99, 0.0),
        Quat::from_rotation_y(0.2),
    );
    let m = collide(&cube(), &a, &cube(), &b, 0.0);
    assert_eq!(m.len, 4);
    assert_close(m.normal, Vec3::Y, 1e-5);
    for p in m.points() {
        assert!((p.separation + 0.01).abs() < 1e-5);
        assert!((p.point.y - 0.495).abs() < 1e-3);
    }
}

#[test]
fn feature_ids_stay_the_same_under_small_motion() {
    let a = Pose::IDENTITY;
    let base = Pose::new(Vec3::new(0.1, 0.99, 0.05), Quat::from_rotation_y(0.2));
    let reference = collide(&cube(), &a, &cube(), &base, 0.0);
    assert_eq!(reference.len, 4);
    for k in 0..50 {
        let s = (k as f32 * 0.7).sin();
        let c = (k as f32 * 1.3).cos();
        let moved = Pose::new(
            base.position + Vec3::new(1e-3 * s, 2e-3 * c, -1e-3 * c),
            Quat::from_rotation_y(1e-3 * c) * Quat::from_rotation_x(1e-3 * s) * base.rotation,
        );
        let m = collide(&cube(), &a, &cube(), &moved, 0.0);
        assert_eq!(ids(&m), ids(&reference), "step {k}");
    }
}

#[test]
fn feature_ids_of_a_tilted_box_stay_the_same_under_small_motion() {
    // A box resting tilted on an edge, so the clipped points include side-plane crossings.
    let a = Pose::IDENTITY;
    let base = Pose::new(
        Vec3::new(0.3, 0.5 + 0.5 * SQRT_2 - 0.02, 0.0),
        Quat::from_rotation_y(0.4) * Quat::from_rotation_z(FRAC_PI_4),
    );
    let reference = collide(&cube(), &a, &cube(), &base, 0.0);
    assert!(!reference.is_empty());
    for k in 0..50 {
        let s = (k as f32 * 0.9).sin();
        let moved = Pose::new(
            base.position + Vec3::new(1e-3 * s, 1e-3 * s, 0.0),
            Quat::from_rotation_y(5e-4 * s) * base.rotation,
        );
        let m = collide(&cube(), &a, &cube(), &moved, 0.0);
        assert_eq!(ids(&m), ids(&reference), "step {k}");
    }
}

#[test]
fn crossed_edge_contact_keeps_its_id_under_small_motion() {
    let a = Pose::new(Vec3::ZERO, Quat::from_rotation_z(FRAC_PI_4));
    let base = Pose::new(
        Vec3::new(0.05, SQRT_2 - 0.02, -0.03),
        Quat::from_rotation_x(FRAC_PI_4),
    );
    let reference = collide(&cube(), &a, &cube(), &base, 0.0);
    assert_eq!(reference.len, 1);
    for k in 0..50 {
        let s = (k as f32 * 0.8).sin();
        let moved = Pose::new(
            base.position + Vec3::new(2e-3 * s, 1e-3 * s, -2e-3 * s),
            Quat::from_rotation_y(2e-3 * s) * base.rotation,
        );
        let m = collide(&cube(), &a, &cube(), &moved, 0.0);
        assert_eq!(ids(&m), ids(&reference), "step {k}");
        assert!((m.normal - reference.normal).length() < 1e-2);
    }
}

#[test]
fn a_box_on_a_floor_gives_four_points_for_any_yaw() {
    let floor = Shape::cuboid(Vec3::new(20.0, 0.5, 20.0));
    let floor_pose = Pose::from_position(Vec3::new(0.0, -0.5, 0.0));
    for k in 0..64 {
        let yaw = k as f32 * 0.1;
        let b = Pose::new(Vec3::new(0.3, 0.49, -0.7), Quat::from_rotation_y(yaw));
        let m = collide(&floor, &floor_pose, &cube(), &b, 0.0);
        assert_eq!(m.len, 4, "yaw {yaw}");
        assert_close(m.normal, Vec3::Y, 1e-5);
        for p in m.points() {
            assert!((p.separation + 0.01).abs() < 1e-5, "yaw {yaw}: {p:?}");
            assert!((p.point.y + 0.005).abs() < 1e-5);
        }
    }
}
