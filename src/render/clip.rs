//! Clipping stage: polygons against the view volume in homogeneous clip space.
//!
//! The volume kept is (glam `*_rh` clip space, depth in [0, 1]):
//! - near `z ≥ 0` and far `z ≤ w`,
//! - `w ≥ W_MIN` (a guard for orthographic and degenerate matrices: the divide never sees w ≤ 0),
//! - a guard band `|x| ≤ g·w`, `|y| ≤ g·w` with `g` ≫ 1, so projected coordinates stay small enough
//!   for the rasterizer's fixed-point edge functions. Triangles are clipped against the band only when
//!   they poke out of it; the visible image is the band's middle `[-1, 1]²`.
//!
//! Sutherland–Hodgman (Foley et al. 3.14; Blinn & Newell 1978 for the homogeneous form): walk the
//! polygon's edges once per plane with signed distance `d(v) = plane · v`; keep inside vertices and add
//! the crossing point where an edge changes side. The crossing is always interpolated from the inside
//! vertex toward the outside one, so two triangles sharing an edge get bit-identical new vertices.

use glam::Vec4;

/// Number of interpolated attributes carried by a vertex (see [`Varying`]).
pub const VARYINGS: usize = 11;

/// Offsets of the attributes in [`ClipVertex::var`].
pub struct Varying;

impl Varying {
    /// World-space normal (3).
    pub const NORMAL: usize = 0;
    /// World-space position, metres (3).
    pub const WORLD: usize = 3;
    /// Body-space position, metres (3): what solid textures are functions of.
    pub const LOCAL: usize = 6;
    /// Texture coordinates (2).
    pub const UV: usize = 9;
}

/// A vertex after the vertex stage: homogeneous clip position plus attributes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ClipVertex {
    /// Homogeneous clip-space position (glam `*_rh`: visible where `0 ≤ z ≤ w`, `|x|, |y| ≤ w`).
    pub clip: Vec4,
    /// Attributes interpolated across the triangle, laid out as [`Varying`] says.
    pub var: [f32; VARYINGS],
}

/// A polygon vertex: a homogeneous position that clipping tests, plus whatever must follow it.
pub trait Clippable: Copy + Default {
    /// The position plane distances are measured on.
    fn position(&self) -> Vec4;
    /// `self + t (other - self)`, for the position and everything carried along.
    fn lerp(&self, other: &Self, t: f32) -> Self;
}

impl Clippable for ClipVertex {
    #[inline]
    fn position(&self) -> Vec4 {
        self.clip
    }

    #[inline]
    fn lerp(&self, other: &ClipVertex, t: f32) -> ClipVertex {
        let mut var = self.var;
        for (v, o) in var.iter_mut().zip(other.var.iter()) {
            *v += t * (o - *v);
        }
        ClipVertex {
            clip: self.clip + t * (other.clip - self.clip),
            var,
        }
    }
}

/// A bare position (shadow-map triangles carry no attributes: `(X, Y, D, 1)` in texel space).
impl Clippable for Vec4 {
    #[inline]
    fn position(&self) -> Vec4 {
        *self
    }

    #[inline]
    fn lerp(&self, other: &Vec4, t: f32) -> Vec4 {
        *self + t * (*other - *self)
    }
}

/// Smallest `w` a kept vertex may have.
pub const W_MIN: f32 = 1e-6;

/// Outcode bits: which planes a vertex is outside of.
const NEAR: u8 = 1;
const FAR: u8 = 2;
const LEFT: u8 = 4;
const RIGHT: u8 = 8;
const BOTTOM: u8 = 16;
const TOP: u8 = 32;
const W_GUARD: u8 = 64;
/// Set when a coordinate is NaN or infinite; such triangles are skipped, never clipped.
pub const NON_FINITE: u8 = 128;

/// The most vertices a polygon can hold: a triangle clipped by the 7 planes of the view volume, or by
/// the 4 sides of the shadow map (a convex polygon gains at most one vertex per plane).
pub const MAX_POLYGON: usize = 16;

/// A convex polygon held inline (no allocation).
#[derive(Clone, Copy, Debug)]
pub struct Polygon<V: Clippable = ClipVertex> {
    verts: [V; MAX_POLYGON],
    len: usize,
}

impl<V: Clippable> Default for Polygon<V> {
    fn default() -> Self {
        Self {
            verts: [V::default(); MAX_POLYGON],
            len: 0,
        }
    }
}

impl<V: Clippable> Polygon<V> {
    /// The triangle as a three-vertex polygon (its winding is kept by every clip).
    pub fn from_triangle(tri: [V; 3]) -> Self {
        let mut p = Self::default();
        p.verts[..3].copy_from_slice(&tri);
        p.len = 3;
        p
    }

    /// The vertices in order (0 or at least 3).
    pub fn vertices(&self) -> &[V] {
        &self.verts[..self.len]
    }

    fn push(&mut self, v: V) {
        // A convex polygon gains at most one vertex per plane, so this never overflows; the check
        // keeps a malformed input from writing out of bounds.
        if self.len < MAX_POLYGON {
            self.verts[self.len] = v;
            self.len += 1;
        }
    }

    /// Keeps the part where `distance(v.position()) ≥ 0` (one Sutherland–Hodgman pass).
    pub fn clip_by(&self, distance: impl Fn(Vec4) -> f32) -> Polygon<V> {
        let mut out = Polygon::default();
        let n = self.len;
        for i in 0..n {
            let a = &self.verts[i];
            let b = &self.verts[(i + 1) % n];
            let (da, db) = (distance(a.position()), distance(b.position()));
            if da >= 0.0 {
                out.push(*a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                // Interpolate from the inside vertex, whichever it is.
                let v = if da >= 0.0 {
                    a.lerp(b, da / (da - db))
                } else {
                    b.lerp(a, db / (db - da))
                };
                out.push(v);
            }
        }
        if out.len < 3 {
            out.len = 0;
        }
        out
    }
}

/// Signed distance of a clip position to one plane, given the guard-band half-width; inside where ≥ 0.
type PlaneDistance = fn(Vec4, f32) -> f32;

/// Each plane's outcode bit and signed distance.
const PLANES: [(u8, PlaneDistance); 7] = [
    (W_GUARD, |c, _| c.w - W_MIN),
    (NEAR, |c, _| c.z),
    (FAR, |c, _| c.w - c.z),
    (LEFT, |c, g| g * c.w + c.x),
    (RIGHT, |c, g| g * c.w - c.x),
    (BOTTOM, |c, g| g * c.w + c.y),
    (TOP, |c, g| g * c.w - c.y),
];

/// The view volume with its guard band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVolume {
    /// Guard-band half-width in NDC units, ≥ 1.
    pub guard: f32,
}

impl ClipVolume {
    /// A volume whose guard band keeps projected pixel coordinates of a `width × height` image within
    /// ±(2²⁰ + size / 2), inside what [`crate::render::raster`]'s fixed point accepts
    /// ([`crate::render::raster::MAX_COORDINATE`] = 2²¹) for any image up to 2²⁰ pixels across.
    pub fn for_image(width: u32, height: u32) -> Self {
        let size = width.max(height).max(1) as f32;
        Self {
            guard: (2_097_152.0 / size).max(2.0),
        }
    }

    /// Which planes `c` is outside of, or [`NON_FINITE`].
    #[inline]
    pub fn outcode(&self, c: Vec4) -> u8 {
        if !c.is_finite() {
            return NON_FINITE;
        }
        let g = self.guard * c.w;
        let mut code = 0;
        code |= if c.z < 0.0 { NEAR } else { 0 };
        code |= if c.z > c.w { FAR } else { 0 };
        code |= if c.x < -g { LEFT } else { 0 };
        code |= if c.x > g { RIGHT } else { 0 };
        code |= if c.y < -g { BOTTOM } else { 0 };
        code |= if c.y > g { TOP } else { 0 };
        code |= if c.w < W_MIN { W_GUARD } else { 0 };
        code
    }

    /// Clips a triangle whose vertices have the given outcodes (not all zero, none non-finite)
    /// against each plane that some vertex is outside of. That suffices: every plane distance is
    /// linear in homogeneous coordinates, so a point interpolated between two vertices inside a plane
    /// is inside it too, whatever the sign of their `w`.
    pub fn clip_triangle<V: Clippable>(&self, tri: [V; 3], codes: u8) -> Polygon<V> {
        self.clip_polygon(Polygon::from_triangle(tri), codes)
    }

    /// Clips a convex polygon against the planes named by `codes` (the OR of its vertices' outcodes).
    pub fn clip_polygon<V: Clippable>(&self, mut poly: Polygon<V>, codes: u8) -> Polygon<V> {
        let g = self.guard;
        for (bit, distance) in PLANES {
            if codes & bit != 0 {
                poly = poly.clip_by(|c| distance(c, g));
                if poly.len == 0 {
                    break;
                }
            }
        }
        poly
    }

    /// Clips the segment `a`–`b` (clip positions with outcodes OR-ed into `codes`, none non-finite)
    /// to the volume, parametrically (Liang–Barsky in homogeneous form). `None` when nothing is left.
    pub fn clip_segment(&self, a: Vec4, b: Vec4, codes: u8) -> Option<(Vec4, Vec4)> {
        let (mut t0, mut t1) = (0.0f32, 1.0f32);
        for (bit, distance) in PLANES {
            if codes & bit == 0 {
                continue;
            }
            let (da, db) = (distance(a, self.guard), distance(b, self.guard));
            if da < 0.0 && db < 0.0 {
                return None;
            }
            if da < 0.0 {
                t0 = t0.max(da / (da - db));
            } else if db < 0.0 {
                t1 = t1.min(da / (da - db));
            }
        }
        (t0 < t1).then(|| (a + t0 * (b - a), a + t1 * (b - a)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f32, y: f32, z: f32, w: f32) -> ClipVertex {
        ClipVertex {
            clip: Vec4::new(x, y, z, w),
            var: [z; VARYINGS],
        }
    }

    #[test]
    fn a_triangle_crossing_the_near_plane_becomes_a_quad_in_front_of_it() {
        let volume = ClipVolume { guard: 4.0 };
        let tri = [
            vertex(0.0, 0.0, -0.5, 1.0),
            vertex(0.5, 0.0, 0.5, 1.0),
            vertex(0.0, 0.5, 0.5, 1.0),
        ];
        let codes = tri.iter().fold(0, |c, v| c | volume.outcode(v.clip));
        assert_eq!(codes, NEAR);
        let poly = volume.clip_triangle(tri, codes);
        assert_eq!(poly.vertices().len(), 4);
        for v in poly.vertices() {
            assert!(v.clip.z >= 0.0);
            assert_eq!(v.var[0], v.clip.z, "attributes follow the position");
        }
    }

    #[test]
    fn a_triangle_behind_the_camera_vanishes() {
        let volume = ClipVolume { guard: 4.0 };
        let tri = [
            vertex(0.0, 0.0, -0.5, -1.0),
            vertex(0.5, 0.0, -0.5, -1.0),
            vertex(0.0, 0.5, -0.5, -1.0),
        ];
        let poly = volume.clip_triangle(tri, NEAR | W_GUARD);
        assert!(poly.vertices().is_empty());
    }

    #[test]
    fn non_finite_coordinates_get_their_own_outcode() {
        let volume = ClipVolume { guard: 4.0 };
        assert_eq!(
            volume.outcode(Vec4::new(f32::NAN, 0.0, 0.5, 1.0)),
            NON_FINITE
        );
        assert_eq!(
            volume.outcode(Vec4::new(0.0, 0.0, 0.5, f32::INFINITY)),
            NON_FINITE
        );
        assert_eq!(volume.outcode(Vec4::new(0.0, 0.0, 0.5, 1.0)), 0);
    }

    #[test]
    fn shared_edges_clip_to_identical_points() {
        let volume = ClipVolume { guard: 4.0 };
        let p = vertex(0.3, 0.1, -0.7, 1.0);
        let q = vertex(-0.2, 0.4, 0.9, 1.0);
        let r = vertex(0.8, -0.6, 0.2, 1.0);
        let s = vertex(-0.9, -0.3, 0.4, 1.0);
        let first = volume.clip_triangle([p, q, r], NEAR);
        let second = volume.clip_triangle([q, p, s], NEAR);
        let originals = [p.clip, q.clip, r.clip, s.clip];
        let new_points = |poly: &Polygon<ClipVertex>| {
            poly.vertices()
                .iter()
                .map(|v| v.clip)
                .filter(|c| !originals.contains(c))
                .collect::<Vec<_>>()
        };
        let a = new_points(&first);
        let b = new_points(&second);
        assert_eq!(
            a.iter().filter(|v| b.contains(v)).count(),
            1,
            "{a:?} vs {b:?}"
        );
    }
}
