//! The pipeline driver: vertex → clip → divide → viewport → rasterize → fragment → depth test/write,
//! then the whole-image passes (shadows, depth grey, 2× filter, outline).

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::clip::{ClipVertex, ClipVolume, NON_FINITE, Polygon, Varying};
use super::line::for_each_line_pixel;
use super::post::{self, ViewDepth};
use super::raster::{Cull, TriangleSetup};
use super::shade::{Lights, Look, to_rgb};
use super::shadow::{SHADOW_FACTOR, ShadowReceiver};
use super::texture;
use super::{Drawable, Frame, Material, Mesh, RenderMode, RenderOptions};
use crate::color::Rgb;
use crate::geometry::{Camera, Projection, Shape, Viewport};

/// Sphere meshes by level of detail: (slices, stacks, largest projected radius in pixels it is used
/// for). The last one is used for anything larger.
const SPHERE_LODS: [(u32, u32, f32); 3] = [(10, 6, 5.0), (20, 12, 20.0), (36, 20, f32::INFINITY)];

/// Draws [`Drawable`]s into a [`Frame`]. Holds the unit meshes and every scratch buffer, so rendering
/// allocates nothing once the buffers have grown to the scene and image size.
pub struct Renderer {
    box_mesh: Mesh,
    spheres: [Mesh; 3],
    lights: Lights,
    /// Vertex-stage output of the current drawable, and each vertex's outcode.
    verts: Vec<ClipVertex>,
    codes: Vec<u8>,
    /// World positions of the current shadow caster.
    world: Vec<Vec3>,
    /// The 2× target of supersampling.
    hi: Frame,
    /// Pixels in shadow, one per pixel of the target.
    mask: Vec<bool>,
    highlighted: Vec<u32>,
    receivers: Vec<ShadowReceiver>,
}

impl Default for Renderer {
    fn default() -> Self {
        Self::new()
    }
}

/// What the fragment stage computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pass {
    /// Depth and id only.
    Ids,
    Flat,
    Smooth,
    Textured,
    Normals,
}

/// Per-target constants of a pass.
struct View {
    viewport: Viewport,
    clip_from_world: Mat4,
    volume: ClipVolume,
    /// World-space frustum planes `(n, d)`, `|n| = 1`, inside where `n·p + d ≥ 0`.
    frustum: [Vec4; 6],
    eye: Vec3,
    forward: Vec3,
    perspective: bool,
    /// Pixels per metre at view depth 1 (perspective) or at any depth (orthographic), vertically.
    pixels_per_metre: f32,
    near: f32,
}

impl View {
    fn new(camera: &Camera, viewport: Viewport) -> Self {
        let aspect = viewport.aspect();
        let clip_from_view = camera.clip_from_view(aspect);
        let clip_from_world = clip_from_view * camera.view_from_world();
        // Gribb & Hartmann: the planes of the clip volume in world space are sums of matrix rows.
        let (r0, r1, r2, r3) = (
            clip_from_world.row(0),
            clip_from_world.row(1),
            clip_from_world.row(2),
            clip_from_world.row(3),
        );
        let frustum = [r2, r3 - r2, r3 + r0, r3 - r0, r3 + r1, r3 - r1].map(|p| {
            let len = p.truncate().length();
            if len > 0.0 { p / len } else { Vec4::ZERO }
        });
        Self {
            viewport,
            clip_from_world,
            volume: ClipVolume::for_image(viewport.width, viewport.height),
            frustum,
            eye: camera.position,
            forward: camera.basis().forward,
            perspective: matches!(camera.projection, Projection::Perspective { .. }),
            pixels_per_metre: clip_from_view.y_axis.y * 0.5 * viewport.height as f32,
            near: camera.near,
        }
    }

    /// True when a sphere is wholly outside the view frustum.
    fn culls(&self, centre: Vec3, radius: f32) -> bool {
        let c = centre.extend(1.0);
        self.frustum.iter().any(|p| p.dot(c) < -radius)
    }

    /// Approximate radius in pixels of a sphere's image.
    fn projected_radius(&self, centre: Vec3, radius: f32) -> f32 {
        let scale = if self.perspective {
            self.pixels_per_metre / (centre - self.eye).dot(self.forward).max(self.near)
        } else {
            self.pixels_per_metre
        };
        radius * scale.abs()
    }

    /// Pixel position (x right, y down) and clip depth of a clip-space point with `w > 0`.
    #[inline]
    fn to_screen(&self, clip: Vec4) -> (Vec2, f32) {
        let inv_w = 1.0 / clip.w;
        let ndc = Vec2::new(clip.x * inv_w, clip.y * inv_w);
        (self.viewport.pixel_from_ndc(ndc), clip.z * inv_w)
    }
}

impl Renderer {
    pub fn new() -> Self {
        Self {
            box_mesh: Mesh::unit_box(),
            spheres: SPHERE_LODS.map(|(slices, stacks, _)| Mesh::uv_sphere(slices, stacks)),
            lights: Lights::default(),
            verts: Vec::new(),
            codes: Vec::new(),
            world: Vec::new(),
            hi: Frame::default(),
            mask: Vec::new(),
            highlighted: Vec::new(),
            receivers: Vec::new(),
        }
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
    /// `camera.visible_range` (up to mesh approximation of spheres and 1/256-pixel vertex snapping).
    ///
    /// With `options.supersample`, colours are rendered at 2 × 2 samples per pixel (at offsets
    /// ¼ and ¾) and box-filtered; ids and depth instead come from a second, depth-and-id-only pass at
    /// 1×, i.e. from a sample exactly at the pixel centre (the nearest possible to it), so picking
    /// agrees with the image whether or not supersampling is on.
    pub fn render(
        &mut self,
        frame: &mut Frame,
        viewport: &Viewport,
        camera: &Camera,
        drawables: &[Drawable],
        options: &RenderOptions,
    ) {
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
                self.cast_shadows(target, view, camera, drawables)
            }
            _ => {}
        }
    }

    /// The unit mesh for `d` and the scale that sizes it.
    fn mesh_for<'m>(
        box_mesh: &'m Mesh,
        spheres: &'m [Mesh; 3],
        view: &View,
        d: &Drawable,
    ) -> (&'m Mesh, Vec3) {
        match d.shape {
            Shape::Cuboid { half_extents } => (box_mesh, half_extents),
            Shape::Sphere { radius } => {
                let px = view.projected_radius(d.pose.position, radius);
                let lod = SPHERE_LODS
                    .iter()
                    .position(|&(_, _, limit)| px < limit)
                    .unwrap_or(SPHERE_LODS.len() - 1);
                (&spheres[lod], Vec3::splat(radius))
            }
        }
    }

    /// Vertex stage: unit mesh → clip space, with world normals (rotation only), world and body
    /// positions and UVs as attributes, and each vertex's outcode.
    fn vertex_stage(
        mesh: &Mesh,
        d: &Drawable,
        scale: Vec3,
        view: &View,
        verts: &mut Vec<ClipVertex>,
        codes: &mut Vec<u8>,
    ) {
        let rotation = d.pose.rotation.normalize();
        let world_from_unit =
            Mat4::from_scale_rotation_translation(scale, rotation, d.pose.position);
        let clip_from_unit = view.clip_from_world * world_from_unit;
        let world_from_unit_normal = Mat3::from_quat(rotation);
        verts.clear();
        codes.clear();
        for ((&p, &n), &uv) in mesh
            .positions
            .iter()
            .zip(mesh.normals.iter())
            .zip(mesh.uvs.iter())
        {
            let clip = clip_from_unit * p.extend(1.0);
            let n_world = world_from_unit_normal * n;
            let p_world = world_from_unit.transform_point3(p);
            let p_local = p * scale;
            verts.push(ClipVertex {
                clip,
                var: [
                    n_world.x, n_world.y, n_world.z, p_world.x, p_world.y, p_world.z, p_local.x,
                    p_local.y, p_local.z, uv.x, uv.y,
                ],
            });
            codes.push(view.volume.outcode(clip));
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
            box_mesh,
            spheres,
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
            if !d.is_drawable() || view.culls(d.pose.position, d.shape.bounding_radius()) {
                continue;
            }
            let (mesh, scale) = Self::mesh_for(box_mesh, spheres, view, d);
            Self::vertex_stage(mesh, d, scale, view, verts, codes);
            let fragment = FragmentStage {
                pass,
                look: Look::of(d),
                lights,
                view,
                id: d.id,
            };
            for t in &mesh.triangles {
                let [a, b, c] = t.map(|i| i as usize);
                let (ca, cb, cc) = (codes[a], codes[b], codes[c]);
                let any = ca | cb | cc;
                if any & NON_FINITE != 0 || ca & cb & cc != 0 {
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
    /// are not behind a surface (within 2 % of view depth + 2 cm, so edges on the surface show).
    fn draw_edges(
        &mut self,
        target: &mut Frame,
        view: &View,
        camera: &Camera,
        drawables: &[Drawable],
    ) {
        let Self {
            box_mesh,
            spheres,
            verts,
            codes,
            ..
        } = self;
        let view_depth = ViewDepth::new(camera);
        let (w, h) = (view.viewport.width, view.viewport.height);
        let (pixels, depth, _) = target.buffers_mut();
        for d in drawables {
            if !d.is_drawable() || view.culls(d.pose.position, d.shape.bounding_radius()) {
                continue;
            }
            let (mesh, scale) = Self::mesh_for(box_mesh, spheres, view, d);
            Self::vertex_stage(mesh, d, scale, view, verts, codes);
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
                    let surface = depth[i];
                    if !surface.is_finite()
                        || view_depth.of(z) <= view_depth.of(surface) * 1.02 + 0.02
                    {
                        pixels[i] = color;
                    }
                });
            }
        }
    }

    /// Planar shadows of every caster on every receiver (see [`super::shadow`]).
    fn cast_shadows(
        &mut self,
        target: &mut Frame,
        view: &View,
        camera: &Camera,
        drawables: &[Drawable],
    ) {
        let Self {
            box_mesh,
            spheres,
            lights,
            world,
            mask,
            receivers,
            ..
        } = self;
        receivers.clear();
        receivers.extend(
            drawables
                .iter()
                .enumerate()
                .filter_map(|(i, d)| ShadowReceiver::new(d, i, lights.key_dir, camera)),
        );
        if receivers.is_empty() {
            return;
        }
        let (w, h) = (view.viewport.width, view.viewport.height);
        mask.clear();
        mask.resize(w as usize * h as usize, false);
        let ids = target.ids();
        for r in receivers.iter() {
            for (j, c) in drawables.iter().enumerate() {
                let radius = c.shape.bounding_radius();
                if j == r.index
                    || !c.casts_shadow
                    || !c.is_drawable()
                    || r.height(c.pose.position) < -radius
                {
                    continue;
                }
                // Shadows are soft-edged at terminal resolution anyway: the coarse sphere will do.
                let (mesh, scale) = match c.shape {
                    Shape::Cuboid { half_extents } => (&*box_mesh, half_extents),
                    Shape::Sphere { radius } => (&spheres[0], Vec3::splat(radius)),
                };
                let world_from_unit = Mat4::from_scale_rotation_translation(
                    scale,
                    c.pose.rotation.normalize(),
                    c.pose.position,
                );
                world.clear();
                world.extend(
                    mesh.positions
                        .iter()
                        .map(|&p| world_from_unit.transform_point3(p)),
                );
                for t in &mesh.triangles {
                    let [pa, pb, pc] = t.map(|i| world[i as usize]);
                    if !r.faces_light((pb - pa).cross(pc - pa)) {
                        continue;
                    }
                    let at = |p: Vec3| ClipVertex {
                        clip: p.extend(1.0),
                        var: [0.0; super::clip::VARYINGS],
                    };
                    let mut poly = Polygon::from_triangle([at(pa), at(pb), at(pc)])
                        .clip_by(|v| r.plane.dot(v));
                    if poly.is_empty() {
                        continue;
                    }
                    poly = poly.map(|v| at(r.project(v.clip.truncate())));
                    for side in r.sides {
                        poly = poly.clip_by(|v| side.dot(v));
                    }
                    let mut any = 0;
                    poly = poly.map(|v| {
                        let clip = view.clip_from_world * v.clip;
                        any |= view.volume.outcode(clip);
                        ClipVertex { clip, var: v.var }
                    });
                    if poly.is_empty() || any & NON_FINITE != 0 {
                        continue;
                    }
                    if any != 0 {
                        poly = view.volume.clip_polygon(poly, any);
                    }
                    let v = poly.vertices();
                    for i in 1..v.len().saturating_sub(1) {
                        let screen = [v[0], v[i], v[i + 1]].map(|p| view.to_screen(p.clip).0);
                        if let Some(setup) = TriangleSetup::new(screen, w, h, Cull::None) {
                            setup.for_each_pixel(|k, _| {
                                if ids[k] == r.id {
                                    mask[k] = true;
                                }
                            });
                        }
                    }
                }
            }
        }
        post::darken_masked(target, mask, SHADOW_FACTOR);
    }
}

/// The target's buffers, split so the fragment stage can write them.
struct Buffers<'a> {
    pixels: &'a mut [Rgb],
    depth: &'a mut [f32],
    ids: &'a mut [u32],
    width: u32,
    height: u32,
}

/// Fragment stage of one drawable: colours covered pixels and does the depth test and writes.
struct FragmentStage<'a> {
    pass: Pass,
    look: Look,
    lights: &'a Lights,
    view: &'a View,
    id: u32,
}

impl FragmentStage<'_> {
    /// Divides, maps to the viewport, sets up, culls back faces and shades one clipped triangle
    /// (every `w ≥ W_MIN`).
    ///
    /// Perspective-correct interpolation: clip depth `z/w` is affine in screen space, so it takes the
    /// screen weights `l` directly; an attribute `a` is `Σ lᵢ aᵢ/wᵢ / Σ lᵢ /wᵢ`.
    #[inline]
    fn triangle(&self, tri: &[ClipVertex; 3], bufs: &mut Buffers) {
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
                setup.for_each_pixel(|i, l| {
                    let zp = l[0] * z[0] + l[1] * z[1] + l[2] * z[2];
                    if zp >= depth[i] {
                        return;
                    }
                    depth[i] = zp;
                    ids[i] = id;
                    let q = [l[0] * inv_w[0], l[1] * inv_w[1], l[2] * inv_w[2]];
                    let norm = 1.0 / (q[0] + q[1] + q[2]);
                    let m = [q[0] * norm, q[1] * norm, q[2] * norm];
                    pixels[i] = self.shade(tri, m);
                });
            }
        }
    }

    /// Colour of the point with perspective-correct weights `m`.
    #[inline]
    fn shade(&self, tri: &[ClipVertex; 3], m: [f32; 3]) -> Rgb {
        let n = interp3(tri, m, Varying::NORMAL).normalize_or_zero();
        if self.pass == Pass::Normals {
            return post::normal_color(n);
        }
        let p_world = interp3(tri, m, Varying::WORLD);
        let to_eye = if self.view.perspective {
            (self.view.eye - p_world).normalize_or_zero()
        } else {
            -self.view.forward
        };
        let mut base = self.look.base;
        if self.pass == Pass::Textured {
            let uv = Vec2::new(
                interp1(tri, m, Varying::UV),
                interp1(tri, m, Varying::UV + 1),
            );
            let factor = match self.look.material {
                Material::Wood => {
                    let grain = texture::wood(interp3(tri, m, Varying::LOCAL));
                    if self.look.is_sphere {
                        grain * texture::sphere_stripes(uv)
                    } else {
                        grain * texture::face_border(uv)
                    }
                }
                Material::Checker => texture::checker(interp3(tri, m, Varying::LOCAL)),
                Material::Plain if self.look.is_sphere => texture::sphere_stripes(uv),
                Material::Plain => 1.0,
            };
            base *= factor;
        }
        to_rgb(self.lights.shade(base, n, to_eye))
    }
}

#[inline]
fn attr3(v: &ClipVertex, at: usize) -> Vec3 {
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
