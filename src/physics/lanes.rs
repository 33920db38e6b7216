//! Four 3-vectors side by side: the structure-of-arrays vector of the wide contact kernels.
//!
//! `Vec3x4 { x, y, z }` holds vector k in lane k of three `Vec4`s, so a dot product, a cross product or a
//! scale by per-lane factors is a handful of 4-wide operations for four vectors at once, with no
//! horizontal shuffles (Box2D v3's `b2Vec2W`, one dimension up). Converting from and to four `Vec3A`s is
//! a 4×4 transpose: done once per body per kernel, not per operation.

use std::ops::{Add, AddAssign, Mul, Sub, SubAssign};

use glam::{Vec3A, Vec4};

/// Four 3-vectors, vector k in lane k of `x`, `y` and `z`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Vec3x4 {
    pub x: Vec4,
    pub y: Vec4,
    pub z: Vec4,
}

impl Vec3x4 {
    pub const ZERO: Vec3x4 = Vec3x4 {
        x: Vec4::ZERO,
        y: Vec4::ZERO,
        z: Vec4::ZERO,
    };

    /// The transpose of four vectors: lane k is `v[k]`.
    #[inline(always)]
    pub fn from_lanes(v: [Vec3A; 4]) -> Self {
        Self {
            x: Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x),
            y: Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y),
            z: Vec4::new(v[0].z, v[1].z, v[2].z, v[3].z),
        }
    }

    /// Vector `k` (k < 4).
    #[inline(always)]
    pub fn lane(&self, k: usize) -> Vec3A {
        Vec3A::new(self.x[k], self.y[k], self.z[k])
    }

    /// Sets vector `k` (k < 4).
    #[inline(always)]
    pub fn set_lane(&mut self, k: usize, v: Vec3A) {
        self.x[k] = v.x;
        self.y[k] = v.y;
        self.z[k] = v.z;
    }

    /// Lane-wise dot products.
    #[inline(always)]
    pub fn dot(self, other: Self) -> Vec4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }
}

/// Lane-wise square root (LLVM turns the four lanes into one `sqrtps`).
#[inline(always)]
pub(crate) fn sqrt(v: Vec4) -> Vec4 {
    Vec4::from_array(v.to_array().map(f32::sqrt))
}

impl Add for Vec3x4 {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }
}

impl Sub for Vec3x4 {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
}

impl AddAssign for Vec3x4 {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl SubAssign for Vec3x4 {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

/// Each vector scaled by its lane's factor.
impl Mul<Vec4> for Vec3x4 {
    type Output = Self;
    #[inline(always)]
    fn mul(self, s: Vec4) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_round_trip_and_dot_matches_the_scalar_dot() {
        let v = [
            Vec3A::new(1.0, 2.0, 3.0),
            Vec3A::new(-4.0, 0.5, 2.0),
            Vec3A::ZERO,
            Vec3A::new(7.0, -1.0, 0.25),
        ];
        let u = [Vec3A::X, Vec3A::Y, Vec3A::Z, Vec3A::new(1.0, 1.0, 1.0)];
        let (wide_v, wide_u) = (Vec3x4::from_lanes(v), Vec3x4::from_lanes(u));
        let dots = wide_v.dot(wide_u);
        let scaled = wide_v * Vec4::new(2.0, 0.0, 1.0, -1.0);
        for k in 0..4 {
            assert_eq!(wide_v.lane(k), v[k]);
            assert_eq!(dots[k], v[k].dot(u[k]));
            assert_eq!(scaled.lane(k), v[k] * [2.0, 0.0, 1.0, -1.0][k]);
        }
        let mut set = Vec3x4::ZERO;
        set.set_lane(3, v[3]);
        assert_eq!(set.lane(3), v[3]);
        assert_eq!((wide_v - wide_v + wide_u).lane(1), u[1]);
        assert_eq!(
            sqrt(Vec4::new(4.0, 0.0, 2.25, 1e6)),
            Vec4::new(2.0, 0.0, 1.5, 1e3)
        );
    }
}
