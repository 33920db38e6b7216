//! Ray casts against random rotated boxes and spheres, checked against an f64 reference written here;
//! degenerate rays; grazing and inside-origin semantics (see the docs of `geometry::ray`).
//!
//! Tolerances: entry distance within 1e-4 relative to the f64 value; point within 1e-4 × t; normal
//! within 1e-4 in direction. Rays within 1e-5 (relative) of grazing an edge or a silhouette, or whose
//! origin is within 1e-5 of the surface, are excluded from the hit/miss comparison (both answers are
//! right to f32 precision); they must still be finite.

use glam::{DMat3, DVec3, Quat, Vec3};
use nudge::geometry::{Pose, Ray, RayHit, Shape};
use nudge::util::SplitMix64 as Rng;

/// The f64 answer: entry distance, normal, and how close the ray is to an ambiguous case.
struct Reference {
    hit: Option<(f64, DVec3)>,
    /// True when a tiny perturbation could flip hit/miss (grazing, or origin on the surface).
    ambiguous: bool,
    /// True when the entry is so close to an edge that the entry face is ambiguous.
    edge_entry: bool,
}

fn reference_box(origin: DVec3, dir: DVec3, pose: &Pose, h: DVec3) -> Reference {
    let r = DMat3::from_quat(pose.rotation.as_dquat());
    let o = r.transpose() * (origin - pose.position.as_dvec3());
    let d = r.transpose() * dir;
    let (mut t_enter, mut t_exit) = (f64::NEG_INFINITY, f64::INFINITY);
    let mut nears = [f64::NEG_INFINITY; 3];
    let mut axis = 0;
    let mut miss = false;
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k].abs() > h[k] {
                miss = true;
            }
            continue;
        }
        let (t1, t2) = ((-h[k] - o[k]) / d[k], (h[k] - o[k]) / d[k]);
        let (near, far) = (t1.min(t2), t1.max(t2));
        nears[k] = near;
        if near > t_enter {
            t_enter = near;
            axis = k;
        }
        t_exit = t_exit.min(far);
    }
    let scale = 1.0 + t_enter.abs().min(1e6) + h.max_element();
    let ambiguous = (t_exit - t_enter).abs() < 1e-5 * scale || t_enter.abs() < 1e-5 * scale;
    let mut second = f64::NEG_INFINITY;
    for (k, near) in nears.iter().enumerate() {
        if k != axis {
            second = second.max(*near);
        }
    }
    let edge_entry = (t_enter - second).abs() < 1e-4 * scale;
    let hit = (!miss && t_enter <= t_exit && t_enter >= 0.0).then(|| {
        let mut n = DVec3::ZERO;
        n[axis] = -d[axis].signum();
        (t_enter, r * n)
    });
    Reference {
        hit,
        ambiguous,
        edge_entry,
    }
}

fn reference_sphere(origin: DVec3, dir: DVec3, center: DVec3, radius: f64) -> Reference {
    let m = origin - center;
    let b = m.dot(dir);
    let c = m.dot(m) - radius * radius;
    let disc = b * b - c;
    let scale = radius * radius + m.length() * radius;
    let ambiguous = disc.abs() < 1e-5 * scale || c.abs() < 1e-5 * scale;
    let hit = (disc >= 0.0 && c > 0.0 && b < 0.0).then(|| {
        let t = -b - disc.sqrt();
        (t, (origin + dir * t - center).normalize())
    });
    Reference {
        hit,
        ambiguous,
        edge_entry: false,
    }
}

fn assert_finite(hit: &RayHit) {
    assert!(hit.t.is_finite() && hit.point.is_finite() && hit.normal.is_finite());
}

#[test]
fn random_rays_agree_with_an_f64_reference() {
    let mut rng = Rng(2024);
    let (mut compared_hits, mut compared_misses, mut skipped, mut inside) = (0, 0, 0, 0);
    for case in 0..10_000 {
        let is_box = case % 2 == 0;
        let h = Vec3::new(
            rng.range(0.05, 3.0),
            rng.range(0.05, 3.0),
            rng.range(0.05, 3.0),
        );
        let radius = rng.range(0.05, 3.0);
        let shape = if is_box {
            Shape::cuboid(h)
        } else {
            Shape::sphere(radius)
        };
        let pose = Pose::new(
            Vec3::new(
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
                rng.range(-50.0, 50.0),
            ),
            Quat::from_axis_angle(rng.direction(), rng.range(0.0, 6.3)),
        );
        let size = shape.bounding_radius();
        let origin_inside = case % 10 == 1 || case % 10 == 2;
        let origin = if origin_inside {
            let local = if is_box {
                h * Vec3::new(
                    rng.range(-0.9, 0.9),
                    rng.range(-0.9, 0.9),
                    rng.range(-0.9, 0.9),
                )
            } else {
                rng.direction() * radius * rng.range(0.0, 0.9)
            };
            pose.transform_point(local)
        } else {
            pose.position + rng.direction() * rng.range(1.5 * size, 60.0)
        };
        let target = pose.position + rng.direction() * size * rng.range(0.0, 1.5);
        let Some(ray) = Ray::new(origin, target - origin) else {
            continue;
        };

        let got = ray.cast(&shape, &pose, 0.0, f32::INFINITY);
        if let Some(hit) = &got {
            assert_finite(hit);
            assert!((hit.normal.length() - 1.0).abs() < 1e-5);
        }
        let (o64, d64) = (ray.origin.as_dvec3(), ray.dir.as_dvec3().normalize());
        let expected = if is_box {
            reference_box(o64, d64, &pose, h.as_dvec3())
        } else {
            reference_sphere(o64, d64, pose.position.as_dvec3(), radius as f64)
        };
        if origin_inside {
            inside += 1;
            assert!(got.is_none(), "case {case}: a ray starting inside hit");
            continue;
        }
        if expected.ambiguous {
            skipped += 1;
            continue;
        }
        match (got, expected.hit) {
            (None, None) => compared_misses += 1,
            (Some(hit), Some((t, n))) => {
                compared_hits += 1;
                let dt = (hit.t as f64 - t).abs();
                assert!(dt <= 1e-4 * t, "case {case}: t {} vs {t}", hit.t);
                let p = o64 + d64 * t;
                assert!(
                    (hit.point.as_dvec3() - p).length() <= 1e-4 * t.max(1.0),
                    "case {case}"
                );
                if !expected.edge_entry {
                    assert!(
                        hit.normal.as_dvec3().dot(n) > 1.0 - 1e-4,
                        "case {case}: normal {} vs {n}",
                        hit.normal
                    );
                }
            }
            (got, want) => panic!("case {case}: got {got:?}, expected {:?}", want.map(|h| h.0)),
        }
    }
    assert!(compared_hits > 3000, "{compared_hits} hits compared");
    assert!(compared_misses > 1000, "{compared_misses} misses compared");
    assert!(inside > 1000);
    assert!(skipped < 100, "{skipped} ambiguous rays skipped");
}

fn degenerate_values() -> Vec<f32> {
    vec![
        0.0,
        -0.0,
        1e-30,
        -1e-30,
        1e-45,
        1.0,
        -1.0,
        1e30,
        -1e30,
        f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
    ]
}

#[test]
fn degenerate_rays_never_panic_and_never_return_nan() {
    let shapes = [Shape::cuboid(Vec3::new(0.5, 1.0, 2.0)), Shape::sphere(0.7)];
    let poses = [
        Pose::IDENTITY,
        Pose::new(Vec3::new(3.0, -1.0, 2.0), Quat::from_rotation_y(0.7)),
    ];
    let values = degenerate_values();
    let mut hits = 0;
    for &dx in &values {
        for &dy in &[0.0f32, 1e-30, 1.0, f32::NAN] {
            for &ox in &values {
                let ray = Ray {
                    origin: Vec3::new(ox, 0.1, -5.0),
                    dir: Vec3::new(dx, dy, 1.0),
                };
                let flat = Ray {
                    origin: Vec3::new(ox, 0.1, -5.0),
                    dir: Vec3::new(dx, dy, 0.0),
                };
                for shape in &shapes {
                    for pose in &poses {
                        for r in [&ray, &flat] {
                            for (t_min, t_max) in
                                [(0.0, f32::INFINITY), (0.0, f32::NAN), (5.0, 1.0)]
                            {
                                if let Some(hit) = r.cast(shape, pose, t_min, t_max) {
                                    assert_finite(&hit);
                                    assert!(hit.t >= t_min && hit.t <= t_max);
                                    hits += 1;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(hits > 0, "the finite rays in the set must hit");
}

#[test]
fn zero_direction_rays_hit_nothing_even_from_the_surface() {
    let ray = Ray {
        origin: Vec3::new(0.5, 0.0, 0.0),
        dir: Vec3::ZERO,
    };
    assert!(
        ray.cast(&Shape::cuboid(Vec3::splat(0.5)), &Pose::IDENTITY, 0.0, 10.0)
            .is_none()
    );
    let ray = Ray {
        origin: Vec3::new(1.0, 0.0, 0.0),
        dir: Vec3::ZERO,
    };
    assert!(
        ray.cast(&Shape::sphere(1.0), &Pose::IDENTITY, 0.0, 10.0)
            .is_none()
    );
}

#[test]
fn tiny_and_huge_directions_give_the_same_hit_as_a_unit_one() {
    let cube = Shape::cuboid(Vec3::splat(0.5));
    let pose = Pose::new(Vec3::new(0.2, 0.1, 0.0), Quat::from_rotation_z(0.3));
    let origin = Vec3::new(-5.0, 0.3, 0.1);
    let unit = Ray::new(origin, Vec3::X).expect("ray");
    let expected = unit.cast(&cube, &pose, 0.0, 100.0).expect("hit");
    for scale in [1e-30f32, 1e-20, 1e20, 1e30] {
        let ray = Ray {
            origin,
            dir: Vec3::X * scale,
        };
        assert_eq!(
            ray.cast(&cube, &pose, 0.0, 100.0),
            Some(expected),
            "scale {scale}"
        );
    }
}

#[test]
fn a_ray_grazing_exactly_along_a_face_or_edge_enters_the_closed_box_deterministically() {
    let cube = Shape::cuboid(Vec3::splat(0.5));
    for origin in [Vec3::new(-5.0, 0.5, 0.0), Vec3::new(-5.0, 0.5, 0.5)] {
        let ray = Ray::new(origin, Vec3::X).expect("ray");
        let first = ray
            .cast(&cube, &Pose::IDENTITY, 0.0, 100.0)
            .expect("closed box");
        assert_eq!(first.t, 4.5);
        assert_eq!(first.normal, Vec3::NEG_X);
        assert_eq!(ray.cast(&cube, &Pose::IDENTITY, 0.0, 100.0), Some(first));
    }
    // In the face's plane but beside the face: a miss.
    let beside = Ray::new(Vec3::new(-5.0, 0.5, 0.6), Vec3::X).expect("ray");
    assert!(beside.cast(&cube, &Pose::IDENTITY, 0.0, 100.0).is_none());
    // Tangent to a sphere: touches at one point.
    let tangent = Ray::new(Vec3::new(-5.0, 1.0, 0.0), Vec3::X).expect("ray");
    let hit = tangent
        .cast(&Shape::sphere(1.0), &Pose::IDENTITY, 0.0, 100.0)
        .expect("tangent");
    assert!((hit.t - 5.0).abs() < 1e-6);
}

#[test]
fn rays_from_inside_or_leaving_the_surface_do_not_hit_and_entering_it_hit_at_zero() {
    let cube = Shape::cuboid(Vec3::splat(0.5));
    let ball = Shape::sphere(0.5);
    for shape in [&cube, &ball] {
        let inside = Ray::new(Vec3::new(0.1, 0.2, 0.0), Vec3::X).expect("ray");
        assert!(inside.cast(shape, &Pose::IDENTITY, 0.0, 100.0).is_none());
        let leaving = Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::X).expect("ray");
        assert!(leaving.cast(shape, &Pose::IDENTITY, 0.0, 100.0).is_none());
        let entering = Ray::new(Vec3::new(0.5, 0.0, 0.0), Vec3::NEG_X).expect("ray");
        let hit = entering
            .cast(shape, &Pose::IDENTITY, 0.0, 100.0)
            .expect("entering");
        assert_eq!(hit.t, 0.0);
        assert_eq!(hit.normal, Vec3::X);
    }
}

#[test]
fn the_t_window_bounds_the_hit() {
    let cube = Shape::cuboid(Vec3::splat(0.5));
    let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X).expect("ray");
    assert!(ray.cast(&cube, &Pose::IDENTITY, 0.0, 4.4).is_none());
    assert!(ray.cast(&cube, &Pose::IDENTITY, 4.6, 10.0).is_none());
    assert!(ray.cast(&cube, &Pose::IDENTITY, 10.0, 0.0).is_none());
    assert!(ray.cast(&cube, &Pose::IDENTITY, 4.5, 4.5).is_some());
}
