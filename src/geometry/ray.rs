//! Rays and ray casts against shapes.
//!
//! A cast reports where the ray *enters* the solid. A ray whose origin is inside a shape (its entry lies
//! behind `t_min`) does not hit it: seen from inside, a closed surface shows only back faces, which the
//! renderer culls, so picking must not see it either.
//!
//! Edge cases, all deterministic:
//! - Shapes are closed: a ray running exactly in a face's plane, or along an edge, touches the solid and
//!   enters it where it crosses the other slabs (the entry face is the last slab crossed).
//! - An origin exactly on the surface with the ray pointing inward hits at t = 0; pointing outward or
//!   along the surface from inside the closed box, it does not hit (its entry is behind it).
//! - `dir` need not be unit length for [`Ray::cast`]: it is normalised there (scaled by its largest
//!   component first, so 1e-30 and 1e30 directions work) and `t` is always in metres. A zero or
//!   non-finite direction or origin, a non-finite pose, an invalid shape (see [`Shape::is_valid`]) or
//!   `t_min > t_max` gives no hit. A hit is never NaN: every field of a returned [`RayHit`] is finite.

use glam::Vec3;

use super::{Pose, Shape};

/// A half-line `origin + t * dir`, `t >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    /// Unit length.
    pub dir: Vec3,
}

/// Where a ray enters a shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayHit {
    /// Ray parameter of the entry point, metres along the ray.
    pub t: f32,
    /// Entry point, world space.
    pub point: Vec3,
    /// Outward surface normal at the entry point, world space, unit length.
    pub normal: Vec3,
}

impl Ray {
    /// A ray from `origin` along `dir` (normalised here, also when tiny or huge); `None` when `dir` is
    /// zero or not finite or `origin` is not finite.
    pub fn new(origin: Vec3, dir: Vec3) -> Option<Self> {
        let dir = robust_normalize(dir)?;
        origin.is_finite().then_some(Self { origin, dir })
    }

    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }

    /// Casts against `shape` at `pose`; the entry point must lie in `[t_min, t_max]` (metres along the
    /// ray). See the module docs for the edge cases.
    pub fn cast(&self, shape: &Shape, pose: &Pose, t_min: f32, t_max: f32) -> Option<RayHit> {
        // `!(a <= b)` is also true for NaN bounds.
        let bounds_ok = t_min <= t_max;
        if !bounds_ok || !self.origin.is_finite() || !pose.is_finite() {
            return None;
        }
        let ray = Ray {
            origin: self.origin,
            dir: robust_normalize(self.dir)?,
        };
        if !shape.is_valid() {
            return None;
        }
        // Cheap rejection against the bounding sphere first: most bodies in a scene are nowhere near
        // the ray, and this costs a fraction of the slab test's two quaternion rotations.
        let radius = shape.bounding_radius();
        let to_center = pose.position - ray.origin;
        let along = to_center.dot(ray.dir);
        if along + radius < t_min
            || along - radius > t_max
            || (to_center - along * ray.dir).length_squared() > radius * radius * (1.0 + 1e-4)
        {
            return None;
        }
        let hit = match *shape {
            Shape::Cuboid { half_extents } => ray.cast_cuboid(half_extents, pose),
            Shape::Sphere { radius } => ray.cast_sphere(radius, pose.position),
        }?;
        let finite = hit.t.is_finite() && hit.point.is_finite() && hit.normal.is_finite();
        (finite && hit.t >= t_min && hit.t <= t_max).then_some(hit)
    }

    /// Slab test in the box's local frame (Kay–Kajiya; Ericson 5.3.3). A direction component that is
    /// zero or tiny is treated as parallel to that slab pair, so no 0·∞ NaN can appear.
    fn cast_cuboid(&self, half_extents: Vec3, pose: &Pose) -> Option<RayHit> {
        let origin_local = pose.inverse_transform_point(self.origin);
        let dir_local = pose.inverse_transform_vector(self.dir);
        let mut t_enter = f32::NEG_INFINITY;
        let mut t_exit = f32::INFINITY;
        let mut enter_axis = 0;
        for axis in 0..3 {
            let o = origin_local[axis];
            let d = dir_local[axis];
            let h = half_extents[axis];
            if d.abs() < 1e-12 {
                if o < -h || o > h {
                    return None;
                }
                continue;
            }
            let inv = 1.0 / d;
            let (t_near, t_far) = {
                let t1 = (-h - o) * inv;
                let t2 = (h - o) * inv;
                if t1 <= t2 { (t1, t2) } else { (t2, t1) }
            };
            if t_near > t_enter {
                t_enter = t_near;
                enter_axis = axis;
            }
            t_exit = t_exit.min(t_far);
            if t_enter > t_exit {
                return None;
            }
        }
        if !t_enter.is_finite() || t_enter < 0.0 {
            return None;
        }
        let mut n_local = Vec3::ZERO;
        n_local[enter_axis] = -dir_local[enter_axis].signum();
        Some(RayHit {
            t: t_enter,
            point: self.at(t_enter),
            normal: pose.transform_vector(n_local),
        })
    }

    /// Analytic ray–sphere entry. The discriminant is computed from the closest-approach vector rather
    /// than as b² − c, which keeps precision when the ray starts far from the sphere.
    fn cast_sphere(&self, radius: f32, center: Vec3) -> Option<RayHit> {
        let m = self.origin - center;
        let b = m.dot(self.dir);
        let closest = m - b * self.dir;
        let disc = radius * radius - closest.length_squared();
        // `!(>=)` also rejects a NaN discriminant (overflow at absurd distances).
        let real_roots = disc >= 0.0;
        if !real_roots {
            return None;
        }
        let t = -b - disc.sqrt();
        if t < 0.0 {
            return None;
        }
        let point = self.at(t);
        let normal = (point - center).try_normalize().unwrap_or(-self.dir);
        Some(RayHit { t, point, normal })
    }
}

/// `v` scaled to unit length, or `None` when it is zero or not finite. Divides by the largest component
/// first, so components of 1e-30 (whose squares underflow) and 1e30 (whose squares overflow) work.
fn robust_normalize(v: Vec3) -> Option<Vec3> {
    let scale = v.abs().max_element();
    if !(scale > 0.0 && scale.is_finite() && v.is_finite()) {
        return None;
    }
    let w = v / scale;
    Some(w / w.length())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    #[test]
    fn tiny_and_huge_directions_normalise() {
        for dir in [Vec3::new(1e-30, 0.0, 0.0), Vec3::new(1e30, -1e30, 0.0)] {
            let ray = Ray::new(Vec3::ZERO, dir).expect("finite nonzero direction");
            assert!((ray.dir.length() - 1.0).abs() < 1e-6);
        }
        assert!(Ray::new(Vec3::ZERO, Vec3::ZERO).is_none());
        assert!(Ray::new(Vec3::ZERO, Vec3::new(f32::NAN, 1.0, 0.0)).is_none());
    }

    #[test]
    fn a_non_unit_direction_still_reports_t_in_metres() {
        let ray = Ray {
            origin: Vec3::new(-5.0, 0.0, 0.0),
            dir: Vec3::new(1e-20, 0.0, 0.0),
        };
        let hit = ray
            .cast(
                &Shape::cuboid(Vec3::splat(0.5)),
                &Pose::IDENTITY,
                0.0,
                100.0,
            )
            .expect("hit");
        assert!((hit.t - 4.5).abs() < 1e-6);
        let hit = ray
            .cast(&Shape::sphere(1.0), &Pose::IDENTITY, 0.0, 100.0)
            .expect("hit");
        assert!((hit.t - 4.0).abs() < 1e-6);
    }

    #[test]
    fn a_nan_pose_is_never_hit() {
        let ray = Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z).expect("ray");
        let pose = Pose::new(Vec3::ZERO, Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0));
        assert!(
            ray.cast(&Shape::cuboid(Vec3::ONE), &pose, 0.0, 100.0)
                .is_none()
        );
    }
}
