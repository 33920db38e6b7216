//! Sphere–sphere contact: one point on the line of centres.

use glam::Vec3;

use crate::physics::narrow::collide::unit_or;
use crate::physics::{ContactPoint, Manifold};

/// Contact between sphere A (`radius_a`, centre `center_a`) and sphere B, world space, metres.
///
/// One point, feature id 0. Concentric spheres (no defined direction) use +y as the normal, so the
/// result is always finite. Empty when the surfaces are more than `margin` apart.
pub fn sphere_sphere(
    radius_a: f32,
    center_a: Vec3,
    radius_b: f32,
    center_b: Vec3,
    margin: f32,
) -> Manifold {
    let mut manifold = Manifold::default();
    let d = center_b - center_a;
    let reach = radius_a + radius_b + margin;
    let dist_sq = d.length_squared();
    if dist_sq > reach * reach || dist_sq.is_nan() {
        return manifold;
    }
    let normal = unit_or(d, Vec3::Y);
    let distance = d.dot(normal);
    let separation = distance - radius_a - radius_b;
    // Midpoint of the surface points a + n r_a and b − n r_b, kept relative to A for precision.
    let point = center_a + 0.5 * (d + normal * (radius_a - radius_b));
    manifold.normal = normal;
    manifold.push(ContactPoint {
        point,
        separation,
        id: 0,
    });
    manifold
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlapping_spheres_report_depth_and_midpoint() {
        let m = sphere_sphere(1.0, Vec3::ZERO, 0.5, Vec3::new(1.4, 0.0, 0.0), 0.0);
        assert_eq!(m.len, 1);
        assert!((m.normal - Vec3::X).length() < 1e-6);
        assert!((m.points[0].separation + 0.1).abs() < 1e-6);
        // Surfaces at x = 1.0 (A) and x = 0.9 (B).
        assert!((m.points[0].point - Vec3::new(0.95, 0.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn concentric_spheres_get_a_finite_unit_normal() {
        let m = sphere_sphere(1.0, Vec3::splat(3.0), 2.0, Vec3::splat(3.0), 0.0);
        assert_eq!(m.len, 1);
        assert!((m.normal.length() - 1.0).abs() < 1e-6);
        assert!((m.points[0].separation + 3.0).abs() < 1e-6);
        assert!(m.points[0].point.is_finite());
    }

    #[test]
    fn spheres_beyond_the_margin_give_nothing_and_within_it_a_speculative_point() {
        let b = Vec3::new(0.0, 2.2, 0.0);
        assert!(sphere_sphere(1.0, Vec3::ZERO, 1.0, b, 0.1).is_empty());
        let m = sphere_sphere(1.0, Vec3::ZERO, 1.0, b, 0.3);
        assert_eq!(m.len, 1);
        assert!((m.points[0].separation - 0.2).abs() < 1e-6);
    }
}
