//! Box–sphere contact by the closest point on the box (Ericson 5.1.4), in the box's local frame.
//!
//! ```text
//! c = sphere centre in box frame; q = clamp(c, -h, h)
//! c outside the box: n = (c - q)/|c - q|, separation = |c - q| - r, box surface point q
//! c inside the box:  push out through the face of least penetration: axis k = argmin (h - |c|),
//!                    n = sign(c_k) e_k, separation = -(h_k - |c_k|) - r
//! ```
//! The inside case is what makes a sphere that tunnelled into a box leave through the side it entered,
//! not always through the top.
//!
//! Feature id: the Voronoi region of the box that holds the centre, `r_x + 3 r_y + 9 r_z` with
//! `r_k = 0` inside the slab `|c_k| <= h_k`, 1 below it, 2 above it (so 0..=26: faces, edges, vertices).
//! A centre inside the box takes the id of the face it is pushed through, which is the id it had just
//! outside that face, so a contact keeps its id as it crosses the surface.

use glam::Vec3;

use crate::geometry::Pose;
use crate::physics::narrow::collide::{sign_nonzero, unit_or};
use crate::physics::{ContactPoint, Manifold};

/// Contact between a box (`half_extents` at `pose_box`; A) and a sphere (`radius`, centre `center`; B).
///
/// The normal points from the box to the sphere. One point, id = Voronoi region (see module docs).
/// Empty when the surfaces are more than `margin` apart.
pub fn box_sphere(
    half_extents: Vec3,
    pose_box: &Pose,
    radius: f32,
    center: Vec3,
    margin: f32,
) -> Manifold {
    let mut manifold = Manifold::default();
    let h = half_extents;
    let c = pose_box.inverse_transform_point(center);
    if !c.is_finite() {
        return manifold;
    }
    let q = c.clamp(-h, h);
    let d = c - q;
    let dist_sq = d.length_squared();

    let (n_local, separation, p_box_local, id) = if dist_sq > 0.0 {
        let reach = radius + margin;
        if dist_sq > reach * reach {
            return manifold;
        }
        // `d` is nonzero here; the fallback only guards an underflowed length.
        let n = unit_or(d, Vec3::Y);
        (n, d.dot(n) - radius, q, region_id(c, h))
    } else {
        let gap = h - c.abs();
        let axis = if gap.x <= gap.y && gap.x <= gap.z {
            0
        } else if gap.y <= gap.z {
            1
        } else {
            2
        };
        let s = sign_nonzero(c[axis]);
        let mut n = Vec3::ZERO;
        n[axis] = s;
        let mut p = c;
        p[axis] = s * h[axis];
        let separation = -gap[axis] - radius;
        if separation > margin {
            // Only a degenerate (zero-radius) sphere exactly on the surface with margin 0 gets here.
            return manifold;
        }
        let mut region = [0u32; 3];
        region[axis] = if s < 0.0 { 1 } else { 2 };
        (n, separation, p, region[0] + 3 * region[1] + 9 * region[2])
    };

    // Midpoint of the box surface point and the sphere's deepest point c − n r.
    let mid_local = 0.5 * (p_box_local + c - n_local * radius);
    manifold.normal = pose_box.transform_vector(n_local);
    manifold.push(ContactPoint {
        point: pose_box.transform_point(mid_local),
        separation,
        id,
    });
    manifold
}

/// Voronoi region code of a box-local point `c` (see module docs).
fn region_id(c: Vec3, h: Vec3) -> u32 {
    let code = |x: f32, h: f32| -> u32 {
        if x < -h {
            1
        } else if x > h {
            2
        } else {
            0
        }
    };
    code(c.x, h.x) + 3 * code(c.y, h.y) + 9 * code(c.z, h.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn sphere_resting_on_top_face_touches_at_the_face() {
        let m = box_sphere(
            Vec3::splat(0.5),
            &Pose::IDENTITY,
            0.25,
            Vec3::new(0.1, 0.74, 0.0),
            0.0,
        );
        assert_eq!(m.len, 1);
        assert!((m.normal - Vec3::Y).length() < 1e-6);
        assert!((m.points[0].separation + 0.01).abs() < 1e-6);
        assert_eq!(m.points[0].id, 2 * 3);
    }

    #[test]
    fn sphere_centre_inside_is_pushed_out_of_the_nearest_side_not_up() {
        let m = box_sphere(
            Vec3::splat(1.0),
            &Pose::IDENTITY,
            0.2,
            Vec3::new(-0.9, 0.3, 0.1),
            0.0,
        );
        assert_eq!(m.len, 1);
        assert!((m.normal - Vec3::NEG_X).length() < 1e-6);
        assert!((m.points[0].separation + 0.3).abs() < 1e-6);
    }

    #[test]
    fn corner_region_normal_points_along_the_diagonal() {
        let pose = Pose::new(Vec3::new(5000.0, 0.0, 0.0), Quat::from_rotation_y(0.3));
        let c_local = Vec3::splat(0.5 + 0.1 / 3f32.sqrt());
        let m = box_sphere(
            Vec3::splat(0.5),
            &pose,
            0.2,
            pose.transform_point(c_local),
            0.0,
        );
        assert_eq!(m.len, 1);
        let n_local = pose.inverse_transform_vector(m.normal);
        assert!((n_local - Vec3::ONE.normalize()).length() < 1e-3);
        assert!((m.points[0].separation + 0.1).abs() < 1e-3);
        assert_eq!(m.points[0].id, 2 + 6 + 18);
    }
}
