//! Fragment stage: per covered pixel, the depth test, then the colour of the surface there, written
//! with the depth and the drawable's id.

use glam::{Vec2, Vec3};

use super::Material;
use super::clip::{ClipVertex, Varying};
use super::post;
use super::raster::{Cull, TriangleSetup};
use super::shade::{Lights, Look, to_rgb};
use super::texture;
use super::view::View;
use crate::color::Rgb;

/// What the fragment stage computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Pass {
    /// Depth and id only (wireframe and depth modes colour afterwards).
    Ids,
    /// One lit colour per triangle.
    Flat,
    /// Per-pixel Blinn–Phong from interpolated normals.
    Smooth,
    /// Smooth lighting of a procedurally textured albedo.
    Textured,
    /// The interpolated normal as a colour.
    Normals,
}

/// The target's buffers, split so the fragment stage can write them.
pub(crate) struct Buffers<'a> {
    /// Colour, clip depth and id per pixel, `width × height` each, row-major.
    pub(crate) pixels: &'a mut [Rgb],
    pub(crate) depth: &'a mut [f32],
    pub(crate) ids: &'a mut [u32],
    /// Image size in pixels.
    pub(crate) width: u32,
    pub(crate) height: u32,
}

/// Fragment stage of one drawable: colours covered pixels and does the depth test and writes.
pub(crate) struct FragmentStage<'a> {
    /// What to compute per pixel.
    pub(crate) pass: Pass,
    /// The drawable's albedo and material.
    pub(crate) look: Look,
    pub(crate) lights: &'a Lights,
    pub(crate) view: &'a View,
    /// Written to the id buffer.
    pub(crate) id: u32,
}

impl FragmentStage<'_> {
    /// Divides, maps to the viewport, sets up, culls back faces and shades one clipped triangle
    /// (every `w ≥ W_MIN`).
    ///
    /// Perspective-correct interpolation: clip depth `z/w` is affine in screen space, so it takes the
    /// screen weights `l` directly; an attribute `a` is `Σ lᵢ aᵢ/wᵢ / Σ lᵢ /wᵢ`.
    #[inline]
    pub(crate) fn triangle(&self, tri: &[ClipVertex; 3], bufs: &mut Buffers) {
        let s = tri.map(|v| self.view.to_screen(v.clip));
        let Some(setup) = TriangleSetup::new(
            [s[0].0, s[1].0, s[2].0],
            bufs.width,
            bufs.height,
            Cull::Back,
        ) else {
            return;
        };
        let z = [s[0].1, s[1].1, s[2].1];
        let id = self.id;
        let Buffers {
            pixels, depth, ids, ..
        } = bufs;
        match self.pass {
            Pass::Ids => setup.for_each_pixel(|i, l| {
                let zp = l[0] * z[0] + l[1] * z[1] + l[2] * z[2];
                if zp < depth[i] {
                    depth[i] = zp;
                    ids[i] = id;
                }
            }),
            Pass::Flat => {
                let n = (attr3(&tri[0], Varying::NORMAL)
                    + attr3(&tri[1], Varying::NORMAL)
                    + attr3(&tri[2], Varying::NORMAL))
                .normalize_or_zero();
                let color = to_rgb(self.look.base * self.lights.diffuse(n));
                setup.for_each_pixel(|i, l| {
                    let zp = l[0] * z[0] + l[1] * z[1] + l[2] * z[2];
                    if zp < depth[i] {
                        depth[i] = zp;
                        ids[i] = id;
                        pixels[i] = color;
                    }
                });
            }
            Pass::Normals | Pass::Smooth | Pass::Textured => {
                let inv_w = tri.map(|v| 1.0 / v.clip.w);
                // `q_i = l_i / w_i` per pixel step: `l` is affine in screen space.
                let (dl_dx, dl_dy) = setup.weight_steps();
                let dq = [0, 1, 2].map(|k| Vec2::new(dl_dx[k], dl_dy[k]) * inv_w[k]);
                setup.for_each_pixel(|i, l| {
                    let zp = l[0] * z[0] + l[1] * z[1] + l[2] * z[2];
                    if zp >= depth[i] {
                        return;
                    }
                    depth[i] = zp;
                    ids[i] = id;
                    let q = [l[0] * inv_w[0], l[1] * inv_w[1], l[2] * inv_w[2]];
                    // 1 / Σ lᵢ/wᵢ is the interpolated w: the view depth in perspective, 1 in
                    // orthographic.
                    let w = 1.0 / (q[0] + q[1] + q[2]);
                    let m = [q[0] * w, q[1] * w, q[2] * w];
                    pixels[i] = self.shade(tri, m, || Footprint::of_triangle(tri, m, w, dq));
                });
            }
        }
    }

    /// Colour of the point with perspective-correct weights `m`; `footprint` is asked for only by
    /// textures.
    #[inline]
    fn shade(
        &self,
        tri: &[ClipVertex; 3],
        m: [f32; 3],
        footprint: impl FnOnce() -> Footprint,
    ) -> Rgb {
        let n = interp3(tri, m, Varying::NORMAL).normalize_or_zero();
        self.surface(
            n,
            || interp3(tri, m, Varying::WORLD),
            || interp3(tri, m, Varying::LOCAL),
            || {
                Vec2::new(
                    interp1(tri, m, Varying::UV),
                    interp1(tri, m, Varying::UV + 1),
                )
            },
            footprint,
        )
    }

    /// Colour of a surface point with unit world normal `n` (for the smooth, textured and normals
    /// passes), its world and body-space positions, texture coordinates and the pixel's footprint
    /// asked for only when the pass and material need them.
    #[inline]
    pub(crate) fn surface(
        &self,
        n: Vec3,
        p_world: impl FnOnce() -> Vec3,
        p_local: impl FnOnce() -> Vec3,
        uv: impl FnOnce() -> Vec2,
        footprint: impl FnOnce() -> Footprint,
    ) -> Rgb {
        if self.pass == Pass::Normals {
            return post::normal_color(n);
        }
        let to_eye = if self.view.perspective {
            (self.view.eye - p_world()).normalize_or_zero()
        } else {
            -self.view.forward
        };
        let mut base = self.look.base;
        if self.pass == Pass::Textured {
            let factor = match self.look.material {
                Material::Wood => {
                    let (p, f) = (p_local(), footprint());
                    let grain = texture::wood(p, f.local);
                    if self.look.is_sphere {
                        grain * texture::sphere_stripes(uv(), p, f.local)
                    } else {
                        grain * texture::face_border(uv(), f.uv)
                    }
                }
                Material::Checker => texture::checker(p_local(), footprint().local),
                Material::Plain if self.look.is_sphere => {
                    texture::sphere_stripes(uv(), p_local(), footprint().local)
                }
                Material::Plain => 1.0,
            };
            base *= factor;
        }
        to_rgb(self.lights.shade(base, n, to_eye))
    }
}

/// What one pixel covers of a surface, for filtering textures ([`texture`]'s module docs): its
/// extents along the body axes (metres) and in UV, each the root of the squared derivatives along
/// screen x and y (the spread of a pixel-sized box mapped through the surface's local linear map).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Footprint {
    /// Extent along body x, y, z, metres (≥ 0).
    pub(crate) local: Vec3,
    /// Extent along u and v (≥ 0).
    pub(crate) uv: Vec2,
}

impl Footprint {
    /// A footprint of `metres` along every body axis (a ray-cast ball, which has no triangle).
    pub(crate) fn isotropic(metres: f32) -> Self {
        Self {
            local: Vec3::splat(metres),
            uv: Vec2::ZERO,
        }
    }

    /// The footprint at perspective-correct weights `m` (clip `w`) of `tri`, given `dq[i]`, the
    /// screen (x, y) derivatives of `q_i = l_i / w_i`. With `Q = Σ q_i = 1/w` and `m_i = q_i / Q`,
    /// `∂m_i = w (∂q_i − m_i ∂Q)`, and an attribute's derivative is `Σ ∂m_i a_i`.
    #[inline]
    fn of_triangle(tri: &[ClipVertex; 3], m: [f32; 3], w: f32, dq: [Vec2; 3]) -> Self {
        let dq_sum = dq[0] + dq[1] + dq[2];
        let dm = [0, 1, 2].map(|k| w * (dq[k] - m[k] * dq_sum));
        let (dm_dx, dm_dy) = (dm.map(|d| d.x), dm.map(|d| d.y));
        let (local_dx, local_dy) = (
            interp3(tri, dm_dx, Varying::LOCAL),
            interp3(tri, dm_dy, Varying::LOCAL),
        );
        let uv = |dm: [f32; 3]| {
            Vec2::new(
                interp1(tri, dm, Varying::UV),
                interp1(tri, dm, Varying::UV + 1),
            )
        };
        let (uv_dx, uv_dy) = (uv(dm_dx), uv(dm_dy));
        Self {
            local: (local_dx * local_dx + local_dy * local_dy).map(f32::sqrt),
            uv: (uv_dx * uv_dx + uv_dy * uv_dy).map(f32::sqrt),
        }
    }
}

#[inline]
pub(crate) fn attr3(v: &ClipVertex, at: usize) -> Vec3 {
    Vec3::new(v.var[at], v.var[at + 1], v.var[at + 2])
}

#[inline]
fn interp3(tri: &[ClipVertex; 3], m: [f32; 3], at: usize) -> Vec3 {
    attr3(&tri[0], at) * m[0] + attr3(&tri[1], at) * m[1] + attr3(&tri[2], at) * m[2]
}

#[inline]
fn interp1(tri: &[ClipVertex; 3], m: [f32; 3], at: usize) -> f32 {
    tri[0].var[at] * m[0] + tri[1].var[at] * m[1] + tri[2].var[at] * m[2]
}
