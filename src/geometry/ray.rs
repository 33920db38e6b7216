//! Rays and ray casts against shapes.
//!
//! A cast reports where the ray *enters* the solid. A ray whose origin is inside a shape (its entry lies
//! behind `t_min`) does not hit it: seen from inside, a closed surface shows only back faces, which the
//! renderer culls, so picking must not see it either.

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
    /// A ray from `origin` along `dir` (normalised here); `None` when `dir` is zero or not finite.
    pub fn new(origin: Vec3, dir: Vec3) -> Option<Self> {
        let dir = dir.try_normalize()?;
        origin.is_finite().then_some(Self { origin, dir })
    }

    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }

    /// Casts against `shape` at `pose`; the entry point must lie in `[t_min, t_max]`.
    pub fn cast(&self, shape: &Shape, pose: &Pose, t_min: f32, t_max: f32) -> Option<RayHit> {
        if !(self.origin.is_finite() && self.dir.is_finite() && t_min <= t_max) {
            return None;
        }
        let hit = match *shape {
            Shape::Cuboid { half_extents } => self.cast_cuboid(half_extents, pose),
            Shape::Sphere { radius } => self.cast_sphere(radius, pose.position),
        }?;
        (hit.t >= t_min && hit.t <= t_max && hit.point.is_finite()).then_some(hit)
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
        if disc < 0.0 {
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
