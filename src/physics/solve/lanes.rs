//! Four 3-vectors side by side: the structure-of-arrays vector of the wide contact kernels.
//!
//! `Vec3x4 { x, y, z }` holds vector k in lane k of three `Vec4`s, so a dot product, a cross product or a
//! scale by per-lane factors is a handful of 4-wide operations for four vectors at once, with no
//! horizontal shuffles (Box2D v3's `b2Vec2W`, one dimension up). Converting from and to four `Vec3A`s is
//! a 4×4 transpose: done once per body per kernel, not per operation.

use std::ops::{Add, AddAssign, Mul, Sub, SubAssign};

use glam::{BVec4A, Mat3A, Mat4, Vec3A, Vec4};

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

    /// The transpose of four vectors: lane k is `v[k]`. As glam's 4×4 transpose (eight shuffles):
    /// built element by element, a step of the pyramid took 1.5 % more instructions (callgrind).
    #[inline(always)]
    pub fn from_lanes(v: [Vec3A; 4]) -> Self {
        let t = Mat4::from_cols(widen(v[0]), widen(v[1]), widen(v[2]), widen(v[3])).transpose();
        Self {
            x: t.x_axis,
            y: t.y_axis,
            z: t.z_axis,
        }
    }

    /// The four vectors, lane k as vector k: the inverse of [`Vec3x4::from_lanes`], one transpose
    /// instead of four vectors read out of the lanes element by element.
    #[inline(always)]
    pub fn lanes(self) -> [Vec3A; 4] {
        let t = Mat4::from_cols(self.x, self.y, self.z, self.z).transpose();
        [t.x_axis, t.y_axis, t.z_axis, t.w_axis].map(Vec3A::from_vec4)
    }

    /// Vector `k` (k < 4).
    #[inline(always)]
    pub fn lane(&self, k: usize) -> Vec3A {
        Vec3A::new(self.x[k], self.y[k], self.z[k])
    }

    /// Lane-wise dot products.
    #[inline(always)]
    pub fn dot(self, other: Self) -> Vec4 {
        self.x * other.x + self.y * other.y + self.z * other.z
    }

    /// Lane-wise cross products.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Self {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    /// `self` in the lanes where `mask` is set, zero elsewhere.
    #[inline(always)]
    pub fn masked(self, mask: BVec4A) -> Self {
        Self {
            x: Vec4::select(mask, self.x, Vec4::ZERO),
            y: Vec4::select(mask, self.y, Vec4::ZERO),
            z: Vec4::select(mask, self.z, Vec4::ZERO),
        }
    }
}

/// Four 3×3 matrices, matrix k in lane k of its three columns.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Mat3x4 {
    pub cols: [Vec3x4; 3],
}

impl Mat3x4 {
    /// The transpose of four matrices: lane k is `m[k]`.
    #[inline(always)]
    pub fn from_lanes(m: [Mat3A; 4]) -> Self {
        Self {
            cols: [
                Vec3x4::from_lanes([m[0].x_axis, m[1].x_axis, m[2].x_axis, m[3].x_axis]),
                Vec3x4::from_lanes([m[0].y_axis, m[1].y_axis, m[2].y_axis, m[3].y_axis]),
                Vec3x4::from_lanes([m[0].z_axis, m[1].z_axis, m[2].z_axis, m[3].z_axis]),
            ],
        }
    }
}

/// Lane-wise matrix times vector (summed in `Mat3A * Vec3A`'s order).
impl Mul<Vec3x4> for Mat3x4 {
    type Output = Vec3x4;
    #[inline(always)]
    fn mul(self, v: Vec3x4) -> Vec3x4 {
        self.cols[0] * v.x + self.cols[1] * v.y + self.cols[2] * v.z
    }
}

/// Lane-wise 1/k where k > 0, else 0 (a row with no mass has no effective mass).
#[inline(always)]
pub(crate) fn inverse_or_zero(k: Vec4) -> Vec4 {
    Vec4::select(k.cmpgt(Vec4::ZERO), Vec4::ONE / k, Vec4::ZERO)
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

/// `v` as a `Vec4`, its fourth element unspecified: a register reinterpreted where glam's SIMD
/// layout allows it, built element by element elsewhere.
#[inline(always)]
fn widen(v: Vec3A) -> Vec4 {
    #[cfg(all(target_arch = "x86_64", target_feature = "sse2"))]
    {
        Vec4::from(std::arch::x86_64::__m128::from(v))
    }
    #[cfg(not(all(target_arch = "x86_64", target_feature = "sse2")))]
    {
        v.extend(0.0)
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
        assert_eq!(wide_v.lanes(), v);
        for k in 0..4 {
            assert_eq!(wide_v.lane(k), v[k]);
            assert_eq!(dots[k], v[k].dot(u[k]));
            assert_eq!(scaled.lane(k), v[k] * [2.0, 0.0, 1.0, -1.0][k]);
        }
        let m = [
            Mat3A::from_diagonal(glam::Vec3::new(1.0, 2.0, 3.0)),
            Mat3A::from_rotation_z(0.7),
            Mat3A::ZERO,
            Mat3A::from_cols_array(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 10.0]),
        ];
        let (products, crosses) = (Mat3x4::from_lanes(m) * wide_v, wide_v.cross(wide_u));
        for k in 0..4 {
            assert_eq!(products.lane(k), m[k] * v[k]);
            assert_eq!(crosses.lane(k), v[k].cross(u[k]));
        }
        assert_eq!(
            inverse_or_zero(Vec4::new(2.0, 0.0, -1.0, 0.5)),
            Vec4::new(0.5, 0.0, 0.0, 2.0)
        );
        assert_eq!((wide_v - wide_v + wide_u).lane(1), u[1]);
        assert_eq!(
            sqrt(Vec4::new(4.0, 0.0, 2.25, 1e6)),
            Vec4::new(2.0, 0.0, 1.5, 1e3)
        );
    }
}
