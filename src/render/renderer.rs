//! The pipeline driver: for each drawable, vertex stage → clip → divide and viewport → rasterize →
//! fragment stage (depth test and writes); then the whole-image passes (shadows, depth grey, 2×
//! filter, outline).

use std::time::Instant;

use glam::Vec3;

use super::clip::{ClipVertex, NON_FINITE, Varying};
use super::fragment::{Buffers, FragmentStage, Pass, attr3};
use super::line::for_each_line_pixel;
use super::mesh::MeshSet;
use super::post::{self, ViewDepth};
use super::shade::{Lights, Look, to_rgb};
use super::shadow::ShadowPass;
use super::sphere::draw_ball;
use super::vertex::vertex_stage;
use super::view::View;
use super::{Drawable, Frame, RenderMode, RenderOptions};
use crate::geometry::{Camera, Shape, Viewport};

/// Draws [`Drawable`]s into a [`Frame`]. Holds the unit meshes and every scratch buffer, so rendering
/// allocates nothing once the buffers have grown to the scene and image size.
#[derive(Debug)]
pub struct Renderer {
    meshes: MeshSet,
    lights: Lights,
    /// Vertex-stage output of the current drawable, and each vertex's outcode.
    verts: Vec<ClipVertex>,
    codes: Vec<u8>,
    /// The 2× target of supersampling.
    hi: Frame,
    highlighted: Vec<u32>,
    shadows: ShadowPass,
    /// Where the last [`Renderer::render`] spent its time.
    timings: RenderTimings,
}

/// Wall time of the last frame's stages, ms: the shadow pass, and everything else (vertex, clip,
/// raster, fragment, supersampling filter, id pass, outline) as `raster`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderTimings {
    pub raster_ms: f64,
    pub shadow_ms: f64,
}

impl Default for Renderer {
    fn default() -> Self {
        Self::new()
    }
}

impl Renderer {
    /// A renderer with its meshes built, the default lights and empty scratch buffers.
    pub fn new() -> Self {
        Self {
            meshes: MeshSet::new(),
            lights: Lights::default(),
            verts: Vec::new(),
            codes: Vec::new(),
            hi: Frame::default(),
            highlighted: Vec::new(),
            shadows: ShadowPass::default(),
            timings: RenderTimings::default(),
        }
    }

    /// Where the last frame spent its time.
    pub fn timings(&self) -> RenderTimings {
        self.timings
    }

    /// The lights shading uses.
    pub fn lights(&self) -> &Lights {
        &self.lights
    }

    /// Replaces the lights (the key light's direction is normalised; a zero one is ignored).
    pub fn set_lights(&mut self, lights: Lights) {
        if let (Some(key), Some(fill)) = (
            lights.key_dir.try_normalize(),
            lights.fill_dir.try_normalize(),
        ) {
            self.lights = Lights {
                key_dir: key,
                fill_dir: fill,
                ..lights
            };
        }
    }

    /// Draws `drawables` seen by `camera` into `frame`, which is resized to the viewport.
    ///
    /// Afterwards every pixel holds the colour of the nearest front-facing surface at its centre (or
    /// `options.background`), its clip depth and the id of that drawable (or [`Frame::NO_ID`]),
    /// computed with `camera.clip_from_world(viewport.aspect())` and the viewport's pixel mapping,
    /// exactly as picking casts rays: the id at a pixel is the body that
    /// `camera.ray_through_ndc(viewport.ndc_of_pixel_center(x, y), aspect)` enters first within
    /// `camera.visible_range` (exactly for balls, which are ray cast the same way; up to 1/256-pixel
    /// vertex snapping for boxes).
    ///
    /// With `options.supersample`, colours are rendered at 2 × 2 samples per pixel (at offsets
    /// ¼ and ¾) and box-filtered; ids and depth instead come from a second, depth-and-id-only pass at
    /// 1×, i.e. from a sample exactly at the pixel centre (the nearest possible to it). A body
    /// thinner than a pixel may then show in the colours and not in the ids: picking samples a
    /// cell where the colours did (`app::input::picking::pick_cell_sampled`).
    pub fn render(
        &mut self,
        frame: &mut Frame,
        viewport: &Viewport,
        camera: &Camera,
        drawables: &[Drawable],
        options: &RenderOptions,
    ) {
        let start = Instant::now();
        self.timings.shadow_ms = 0.0;
        frame.set_size(viewport.width, viewport.height);
        frame.clear(options.background);
        if viewport.is_empty() {
            return;
        }
        self.highlighted.clear();
        self.highlighted.extend(
            drawables
                .iter()
                .filter(|d| d.highlighted && d.is_drawable())
                .map(|d| d.id),
        );
        let view = View::new(camera, *viewport);
        if options.supersample {
            let mut hi = std::mem::take(&mut self.hi);
            let hi_viewport = Viewport::new(
                viewport.width.saturating_mul(2),
                viewport.height.saturating_mul(2),
                viewport.pixel_aspect,
            );
            hi.set_size(hi_viewport.width, hi_viewport.height);
            hi.clear(options.background);
            let hi_view = View::new(camera, hi_viewport);
            self.draw(&mut hi, &hi_view, camera, drawables, options);
            post::box_filter_2x(&hi, frame);
            self.hi = hi;
            self.raster_scene(frame, &view, drawables, Pass::Ids);
        } else {
            self.draw(frame, &view, camera, drawables, options);
        }
        post::outline(frame, &self.highlighted, options.outline);
        self.timings.raster_ms = start.elapsed().as_secs_f64() * 1e3 - self.timings.shadow_ms;
    }

    /// One full-resolution render of `options.mode` into `target` (already cleared).
    fn draw(
        &mut self,
        target: &mut Frame,
        view: &View,
        camera: &Camera,
        drawables: &[Drawable],
        options: &RenderOptions,
    ) {
        let pass = match options.mode {
            RenderMode::Wireframe | RenderMode::Depth => Pass::Ids,
            RenderMode::Flat => Pass::Flat,
            RenderMode::Smooth => Pass::Smooth,
            RenderMode::Textured => Pass::Textured,
            RenderMode::Normals => Pass::Normals,
        };
        self.raster_scene(target, view, drawables, pass);
        match options.mode {
            RenderMode::Wireframe => self.draw_edges(target, view, camera, drawables),
            RenderMode::Depth => post::depth_to_grey(target, ViewDepth::new(camera)),
            RenderMode::Flat | RenderMode::Smooth | RenderMode::Textured if options.shadows => {
                let start = Instant::now();
                self.shadows
                    .cast(target, view, drawables, &self.meshes, &self.lights);
                self.timings.shadow_ms += start.elapsed().as_secs_f64() * 1e3;
            }
            _ => {}
        }
    }

    /// Rasterizes every drawable's triangles with the given fragment stage.
    fn raster_scene(
        &mut self,
        target: &mut Frame,
        view: &View,
        drawables: &[Drawable],
        pass: Pass,
    ) {
        let Self {
            meshes,
            lights,
            verts,
            codes,
            ..
        } = self;
        let (w, h) = (view.viewport.width, view.viewport.height);
        let (pixels, depth, ids) = target.buffers_mut();
        let mut bufs = Buffers {
            pixels,
            depth,
            ids,
            width: w,
            height: h,
        };
        for d in drawables {
            if !d.is_drawable() || view.culls(d) {
                continue;
            }
            let fragment = FragmentStage {
                pass,
                look: Look::of(d),
                lights,
                view,
                id: d.id,
            };
            if let Shape::Sphere { radius } = d.shape {
                draw_ball(&fragment, d, radius, &mut bufs);
                continue;
            }
            let (mesh, scale) = meshes.for_shape(&d.shape, view.projected_radius(d));
            vertex_stage(mesh, d, scale, view, verts, codes);
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| i as usize);
                let (ca, cb, cc) = (codes[a], codes[b], codes[c]);
                let any = ca | cb | cc;
                if any & NON_FINITE != 0 || ca & cb & cc != 0 {
                    continue;
                }
                // Early back-face rejection in world space, before any division; the rasterizer's
                // exact test on snapped screen positions still decides the borderline cases.
                let pa = attr3(&verts[a], Varying::WORLD);
                let n = (attr3(&verts[b], Varying::WORLD) - pa)
                    .cross(attr3(&verts[c], Varying::WORLD) - pa);
                let toward_eye = if view.perspective {
                    n.dot(view.eye - pa)
                } else {
                    -n.dot(view.forward)
                };
                if toward_eye < 0.0 {
                    continue;
                }
                let tri = [verts[a], verts[b], verts[c]];
                if any == 0 {
                    fragment.triangle(&tri, &mut bufs);
                } else {
                    let poly = view.volume.clip_triangle(tri, any);
                    let v = poly.vertices();
                    for i in 1..v.len().saturating_sub(1) {
                        fragment.triangle(&[v[0], v[i], v[i + 1]], &mut bufs);
                    }
                }
            }
        }
    }

    /// Wireframe: the meshes' edges over the depth buffer of a preceding id pass, drawn where they
    /// are not behind a surface. A line sample is off the pixel centre where the depth was taken, so
    /// it is compared with the farthest depth in the pixel's 3 × 3 neighbourhood, with a tolerance of
    /// 2 % of view depth + 2 cm: edges on silhouettes and creases show whole, hidden ones do not.
    /// Spheres use a mesh a level coarser than their surface, so their wires stay a few pixels apart.
    fn draw_edges(
        &mut self,
        target: &mut Frame,
        view: &View,
        camera: &Camera,
        drawables: &[Drawable],
    ) {
        let Self {
            meshes,
            verts,
            codes,
            ..
        } = self;
        let view_depth = ViewDepth::new(camera);
        let (w, h) = (view.viewport.width, view.viewport.height);
        let (pixels, depth, _) = target.buffers_mut();
        let farthest_around = |depth: &[f32], i: usize| {
            let (x, y) = (i % w as usize, i / w as usize);
            let mut far = 0.0f32;
            for ny in y.saturating_sub(1)..(y + 2).min(h as usize) {
                for nx in x.saturating_sub(1)..(x + 2).min(w as usize) {
                    far = far.max(depth[ny * w as usize + nx]);
                }
            }
            far
        };
        for d in drawables {
            if !d.is_drawable() || view.culls(d) {
                continue;
            }
            let (mesh, scale) = meshes.for_shape(&d.shape, 0.3 * view.projected_radius(d));
            vertex_stage(mesh, d, scale, view, verts, codes);
            let look = Look::of(d);
            let color = to_rgb(look.base * 0.85 + Vec3::splat(0.15));
            for e in &mesh.edges {
                let [a, b] = e.map(|i| i as usize);
                let any = codes[a] | codes[b];
                if any & NON_FINITE != 0 || codes[a] & codes[b] != 0 {
                    continue;
                }
                let (ca, cb) = if any == 0 {
                    (verts[a].clip, verts[b].clip)
                } else {
                    match view.volume.clip_segment(verts[a].clip, verts[b].clip, any) {
                        Some(s) => s,
                        None => continue,
                    }
                };
                let (sa, za) = view.to_screen(ca);
                let (sb, zb) = view.to_screen(cb);
                for_each_line_pixel(sa.extend(za), sb.extend(zb), w, h, |i, z| {
                    let surface = farthest_around(depth, i);
                    if !surface.is_finite()
                        || view_depth.of(z) <= view_depth.of(surface) * 1.02 + 0.02
                    {
                        pixels[i] = color;
                    }
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::geometry::{Pose, Shape};
    use glam::Vec3;

    #[test]
    fn scratch_buffers_stop_growing_after_the_first_frame() {
        let mut drawables: Vec<Drawable> = (0..20)
            .map(|i| {
                let shape = if i % 2 == 0 {
                    Shape::cuboid(Vec3::splat(0.4))
                } else {
                    Shape::sphere(0.4)
                };
                let position = Vec3::new(i as f32 - 10.0, 0.5, (i % 3) as f32);
                Drawable::new(shape, Pose::from_position(position), Rgb::WHITE, i)
            })
            .collect();
        let floor = Drawable::new(
            Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
            Rgb::WHITE,
            100,
        );
        drawables.push(floor);
        drawables[3].highlighted = true;
        let camera = Camera::perspective(Vec3::new(0.0, 6.0, -14.0), Vec3::ZERO, 1.0);
        let viewport = Viewport::new(64, 40, 1.0);
        let mut renderer = Renderer::new();
        let mut frame = Frame::new(64, 40);
        let footprint = |r: &Renderer, f: &Frame| {
            (
                r.verts.as_ptr(),
                r.verts.capacity(),
                r.codes.capacity(),
                r.highlighted.capacity(),
                r.hi.pixels().as_ptr(),
                f.pixels().as_ptr(),
                format!("{:?}", r.shadows.capacities()),
            )
        };
        let all_modes = |r: &mut Renderer, f: &mut Frame| {
            for mode in RenderMode::ALL {
                for supersample in [false, true] {
                    let options = RenderOptions {
                        mode,
                        supersample,
                        ..RenderOptions::default()
                    };
                    r.render(f, &viewport, &camera, &drawables, &options);
                }
            }
        };
        all_modes(&mut renderer, &mut frame);
        let before = footprint(&renderer, &frame);
        all_modes(&mut renderer, &mut frame);
        assert_eq!(footprint(&renderer, &frame), before);
    }
}
