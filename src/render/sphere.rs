//! Balls drawn exactly: each pixel whose centre may see a ball intersects its ray with the sphere (a
//! ray-cast impostor), and the hit gives the depth, normal and body-space point the fragment stage
//! shades. Perfectly round balls at any size and cell mode, and no mesh to choose a detail level for.
//!
//! Why not the tessellated mesh the balls used to be drawn with: picking casts rays at the physics
//! shape, the analytic sphere, and a mesh's outline is a polygon straddling that circle. Along every
//! ball's outline some pixel centres hit the sphere but not the drawn polygon, or the other way
//! round; with a ball large in the picture that was a whole cell off its silhouette, and a click there
//! picked what was not drawn (`tests/app/picking.rs`). Picking against the mesh instead would need
//! the renderer's level of detail in picking and would make clicks agree with a picture that is
//! wrong. Here the renderer casts the same ray ([`crate::geometry::ImageRays::through_ndc`] of the
//! pixel centre, within the same visible range) with the same cast ([`crate::geometry::Ray::cast`])
//! as picking, so what you click is what was drawn by construction, up to depth ties.
//!
//! Per ball: the screen rectangle of its bounding cube (the whole image when the cube reaches behind
//! the eye), then for each pixel centre in it:
//!
//! ```text
//! ray = rays.through_ndc(ndc of the pixel centre); (t0, t1) = rays.visible_range(ray)
//! hit = ray.cast(ball, t0, t1)             else skip      (entry point only: from inside, nothing)
//! z   = clip depth of hit.point            if z ≥ depth[pixel] skip
//! write z, id, and the colour of (hit.normal, hit.point, body-space point, uv)
//! ```
//!
//! The body-space point and uv (u = longitude / 2π, v = colatitude / π, as [`super::mesh::Mesh::uv_sphere`]
//! lays them) turn wood and stripes with the ball. Flat mode shades each pixel with the normal of the
//! UV-sphere facet it falls in, so flat balls keep their facets. The cost is one ray cast per pixel of
//! the rectangle (4/π of the ball's pixels) instead of a vertex stage, clipping and triangle setup;
//! `nudge bench render` times a scene of balls.

use glam::{Vec2, Vec3};

use super::Drawable;
use super::fragment::{Buffers, Footprint, FragmentStage, Pass};
use super::mesh::sphere_facets;
use super::post;
use super::shade::to_rgb;
use super::view::View;

/// Draws ball `d` (a sphere of `radius` metres) through `fragment` into `bufs`.
pub(crate) fn draw_ball(fragment: &FragmentStage, d: &Drawable, radius: f32, bufs: &mut Buffers) {
    let view = fragment.view;
    let Some((x0, y0, x1, y1)) = screen_rect(view, d.pose.position, radius, bufs) else {
        return;
    };
    let rotation = d.pose.rotation.normalize();
    let (slices, stacks) = sphere_facets(view.projected_radius(d));
    let row_from_clip = view.clip_from_world.row(2);
    let w_from_clip = view.clip_from_world.row(3);
    let width = bufs.width as usize;
    for y in y0..=y1 {
        for x in x0..=x1 {
            let ray = view
                .rays
                .through_ndc(view.viewport.ndc_of_pixel_center(x, y));
            let (t_min, t_max) = view.rays.visible_range(&ray);
            let Some(hit) = ray.cast(&d.shape, &d.pose, t_min, t_max) else {
                continue;
            };
            let p = hit.point.extend(1.0);
            let w = w_from_clip.dot(p);
            let z = row_from_clip.dot(p) / w;
            let i = y as usize * width + x as usize;
            // `!(<)` also skips a NaN depth.
            let nearer = z < bufs.depth[i];
            if !nearer {
                continue;
            }
            bufs.depth[i] = z;
            bufs.ids[i] = d.id;
            let n = hit.normal;
            bufs.pixels[i] = match fragment.pass {
                Pass::Ids => continue,
                Pass::Normals => post::normal_color(n),
                Pass::Flat => {
                    let facet = rotation * facet_normal(rotation.inverse() * n, slices, stacks);
                    to_rgb(fragment.look.base * fragment.lights.diffuse(facet))
                }
                Pass::Smooth | Pass::Textured => {
                    let n_local = rotation.inverse() * n;
                    // No triangle to differentiate: the pixel's size at the ball's depth, over
                    // the cosine of its slant (the most foreshortened direction).
                    let footprint = || {
                        let to_eye = if fragment.view.perspective {
                            (fragment.view.eye - hit.point).normalize_or_zero()
                        } else {
                            -fragment.view.forward
                        };
                        let slant = n.dot(to_eye).abs().max(0.05);
                        Footprint::isotropic(w / (fragment.view.pixels_per_metre * slant))
                    };
                    fragment.surface(
                        n,
                        || hit.point,
                        || n_local * radius,
                        || uv(n_local),
                        footprint,
                    )
                }
            };
        }
    }
}

/// The inclusive pixel range `(x0, y0, x1, y1)` whose centres may see the ball at `centre` of
/// `radius`: the image of its bounding cube, clamped to the image; the whole image when a corner is
/// at or behind the eye plane. `None` when it is off the image.
fn screen_rect(
    view: &View,
    centre: Vec3,
    radius: f32,
    bufs: &Buffers,
) -> Option<(u32, u32, u32, u32)> {
    let (w, h) = (bufs.width, bufs.height);
    if w == 0 || h == 0 {
        return None;
    }
    let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
    for i in 0..8 {
        let corner = centre
            + radius
                * Vec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { -1.0 } else { 1.0 },
                );
        let clip = view.clip_from_world * corner.extend(1.0);
        let in_front = clip.w > 1e-6;
        if !in_front {
            return Some((0, 0, w - 1, h - 1));
        }
        let (pixel, _) = view.to_screen(clip);
        lo = lo.min(pixel);
        hi = hi.max(pixel);
    }
    // Pixel x is sampled at x + ½: the first centre at or after lo, the last at or before hi.
    let first = |v: f32| (v - 0.5).ceil().max(0.0);
    let last = |v: f32, n: u32| (v - 0.5).floor().min(n as f32 - 1.0);
    let (x0, y0) = (first(lo.x), first(lo.y));
    let (x1, y1) = (last(hi.x, w), last(hi.y, h));
    if !(x0 <= x1 && y0 <= y1) {
        return None;
    }
    Some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
}

/// Texture coordinates of the body-space unit direction `n` as [`super::mesh::Mesh::uv_sphere`] lays
/// them: the mesh's point at (u, v) is (sin πv cos 2πu, cos πv, −sin πv sin 2πu).
#[inline]
fn uv(n: Vec3) -> Vec2 {
    let u = (-n.z).atan2(n.x) * (0.5 / std::f32::consts::PI);
    Vec2::new(
        u - u.floor(),
        n.y.clamp(-1.0, 1.0).acos() / std::f32::consts::PI,
    )
}

/// The normal at the middle of the facet of a `slices × stacks` UV sphere that body-space unit
/// direction `n` falls in (body space).
#[inline]
fn facet_normal(n: Vec3, slices: u32, stacks: u32) -> Vec3 {
    use std::f32::consts::{PI, TAU};
    let t = uv(n);
    let u = ((t.x * slices as f32).floor() + 0.5) / slices as f32;
    let v = (((t.y * stacks as f32).floor()).min(stacks as f32 - 1.0) + 0.5) / stacks as f32;
    let (sin_phi, cos_phi) = (v * PI).sin_cos();
    let (sin_theta, cos_theta) = (u * TAU).sin_cos();
    Vec3::new(sin_phi * cos_theta, cos_phi, -sin_phi * sin_theta)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uv_inverts_the_uv_spheres_layout() {
        for (u, v) in [(0.1, 0.3), (0.6, 0.8), (0.95, 0.5), (0.25, 0.1)] {
            let (phi, theta) = (v * std::f32::consts::PI, u * std::f32::consts::TAU);
            let n = Vec3::new(phi.sin() * theta.cos(), phi.cos(), -phi.sin() * theta.sin());
            let back = uv(n);
            assert!((back - Vec2::new(u, v)).length() < 1e-5, "{u} {v}: {back}");
        }
    }

    #[test]
    fn a_facet_normal_is_near_the_direction_it_stands_for() {
        let n = Vec3::new(0.3, 0.5, -0.8).normalize();
        let facet = facet_normal(n, 20, 12);
        assert!((facet.length() - 1.0).abs() < 1e-5);
        assert!(facet.dot(n) > (std::f32::consts::PI / 12.0).cos());
    }
}
