//! Shadows from a light-space map: every drawable that casts shadows darkens every other drawable
//! that receives them, wherever it stands between that surface and the key light.
//!
//! A deferred pass after rasterization, in two steps.
//!
//! 1. **The map** (Williams, "Casting curved shadows on curved surfaces", 1978). An orthographic view
//!    along the key light, with texel coordinates `(X, Y)` (x right, y down, texel `(i, j)` centred at
//!    `(i + ½, j + ½)`) and a depth `D` in metres along the light. It is fitted to where a shadow can
//!    fall: the union, over casters `C`, of `C`'s footprint (its bounding rectangle seen from the
//!    light) intersected with the bounding rectangle of the footprints of the *other* receivers. So it
//!    depends on the bodies only, never on the camera (shadows do not swim when the camera orbits), and
//!    a huge floor does not stretch it: the floor's own footprint only counts where another body stands.
//!    The texel size is rounded up to a power of 2^¼ and the origin snapped to whole texels, so a
//!    moving body does not make still shadows shimmer unless the fit's scale changes. The light-facing
//!    triangles of every caster's mesh (back faces are culled: for a closed convex mesh the front ones
//!    are the surface nearest the light) are rasterized with [`TriangleSetup`] into a depth buffer and
//!    a *face* buffer: the index of the nearest triangle, whose entry holds its drawable's id and its
//!    depth plane `D = a X + b Y + c`.
//! 2. **The lookup**, per pixel of the frame showing a receiver. Its world point is rebuilt from its
//!    clip depth through the inverse of the camera's `clip_from_world` (composed with the map's
//!    `texel_from_world`, in f64, so one 4 × 4 product per pixel gives `(X, Y, D)`). The four texels
//!    around `(X, Y)` are tested and their verdicts weighted bilinearly (percentage-closer filtering,
//!    Reeves, Salesin & Cook 1987). A texel shadows the point when its face belongs to **another**
//!    drawable (priority-buffer shadows, Hourcade & Nicolas 1985: a convex body never shadows itself,
//!    so there is no self-shadow acne, and its own side away from the light is dark from Lambert
//!    shading already) and that face's plane, extended to the point's exact `(X, Y)`, is nearer the
//!    light than the point by more than [`DEPTH_BIAS`] plus half a texel. Extending the plane rather
//!    than comparing with the texel's depth means two coplanar neighbours (the tops of a row of boxes)
//!    compare exactly, with no slope-scaled bias.
//!
//! A shadow hides the key light, whose share of a surface's brightness fades with the cosine of its
//! incidence; so the darkening, [`SHADOW_FACTOR`] on a fully lit face, fades linearly below a cosine of
//! [`FULL_SHADOW_COS`] and is nothing on a surface facing away from the light (which is not darkened
//! twice). The cosine comes from the receiver's exact shape: the nearest face of its box, or the
//! sphere's normal at the point.

use glam::{DMat4, DVec4, Mat3, Mat4, Vec2, Vec3, Vec4};

use super::clip::Polygon;
use super::mesh::MeshSet;
use super::raster::{Cull, TriangleSetup};
use super::shade::Lights;
use super::view::View;
use super::{Drawable, Frame};
use crate::color::Rgb;
use crate::geometry::Shape;

/// Brightness factor of a fully shadowed pixel of a surface that faces the key light squarely.
pub const SHADOW_FACTOR: f32 = 0.58;

/// Cosine of the key light's incidence from which a shadow darkens by the full [`SHADOW_FACTOR`];
/// below it the darkening fades linearly to none at grazing incidence, as the key light's share does.
pub const FULL_SHADOW_COS: f32 = 0.5;

/// How much nearer the light (metres) an occluding plane must be than a point to shadow it, besides
/// half a texel: covers depth-buffer precision and bodies that rest a few millimetres apart.
pub const DEPTH_BIAS: f32 = 0.01;

/// Texels along the map's longer side, per pixel along the frame's longer side (before clamping to
/// [`MAP_SIDE_MIN`, `MAP_SIDE_MAX`]). The map spans the casters, which usually fill less than the
/// picture, so its texels come out about as fine as the pixels showing them, and the bilinear taps
/// smooth the rest; a finer map costs fill (its rasterization is a third of the pass) for no visible
/// gain at terminal resolution.
const MAP_TEXELS_PER_PIXEL: f32 = 0.75;
const MAP_SIDE_MIN: u32 = 128;
const MAP_SIDE_MAX: u32 = 1024;

/// How far (texels) a caster's triangle may reach outside the map before it is clipped to it (a
/// huge floor or ramp would otherwise overflow the rasterizer's fixed point).
const MAP_GUARD: f32 = 4096.0;

/// Sphere meshes are fitted at most this much outside the true radius (see [`MeshSet`]).
const MESH_SLACK: f32 = 1.1;

/// Marks a texel no caster covers.
const NO_FACE: u32 = u32::MAX;

/// A rectangle in light-plane coordinates (metres along the light's right and up axes).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    lo: Vec2,
    hi: Vec2,
}

impl Rect {
    const EMPTY: Rect = Rect {
        lo: Vec2::INFINITY,
        hi: Vec2::NEG_INFINITY,
    };

    fn is_empty(&self) -> bool {
        !(self.lo.x <= self.hi.x && self.lo.y <= self.hi.y)
    }

    fn intersection(&self, other: &Rect) -> Rect {
        Rect {
            lo: self.lo.max(other.lo),
            hi: self.hi.min(other.hi),
        }
    }

    fn union(&self, other: &Rect) -> Rect {
        Rect {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }
}

/// The largest value pushed and the largest among the others, so that the maximum over "all but
/// one" costs O(1).
#[derive(Clone, Copy, Debug)]
struct TopTwo {
    first: f32,
    first_index: usize,
    second: f32,
}

impl TopTwo {
    const NONE: TopTwo = TopTwo {
        first: f32::NEG_INFINITY,
        first_index: usize::MAX,
        second: f32::NEG_INFINITY,
    };

    fn push(&mut self, value: f32, index: usize) {
        if value > self.first {
            self.second = self.first;
            self.first = value;
            self.first_index = index;
        } else if value > self.second {
            self.second = value;
        }
    }

    /// The maximum over every value pushed with an index other than `index`.
    fn excluding(&self, index: usize) -> f32 {
        if self.first_index == index {
            self.second
        } else {
            self.first
        }
    }
}

/// What the lookup needs of one drawable: whether it receives, and its shape for the normal.
#[derive(Clone, Copy, Debug)]
struct Receiver {
    receives: bool,
    centre: Vec3,
    body_from_world: Mat3,
    kind: ReceiverKind,
}

#[derive(Clone, Copy, Debug)]
enum ReceiverKind {
    /// Half-extents (metres) and, per body axis `i`, `−axisᵢ · L` (the cosine of the incidence on
    /// the face with outward normal `+axisᵢ`).
    Box {
        half: Vec3,
        cos: Vec3,
    },
    Sphere,
}

impl Receiver {
    /// Cosine of the key light's incidence on the surface at `p_world` (negative facing away).
    #[inline]
    fn cos_incidence(&self, p_world: Vec3, light_dir: Vec3) -> f32 {
        let d = p_world - self.centre;
        match self.kind {
            ReceiverKind::Box { half, cos } => {
                // The face whose plane the point is nearest to, relative to the box's size.
                let p_local = self.body_from_world * d;
                let r = p_local.abs() / half;
                let k = if r.x >= r.y && r.x >= r.z {
                    0
                } else if r.y >= r.z {
                    1
                } else {
                    2
                };
                if p_local[k] < 0.0 { -cos[k] } else { cos[k] }
            }
            ReceiverKind::Sphere => -d.normalize_or_zero().dot(light_dir),
        }
    }
}

/// One light-facing caster triangle in the map.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Face {
    /// Id of the drawable it belongs to.
    id: u32,
    /// Its depth plane: `D = a X + b Y + c` at texel coordinates `(X, Y)`, metres.
    plane: Vec3,
}

impl Face {
    /// The face of the triangle with texel-space vertices `(X, Y, D)`; `None` when it is edge-on.
    fn new(id: u32, t: [Vec3; 3]) -> Option<Self> {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let (a, b) = (-n.x / n.z, -n.y / n.z);
        let plane = Vec3::new(a, b, t[0].z - a * t[0].x - b * t[0].y);
        plane.is_finite().then_some(Self { id, plane })
    }

    #[inline]
    fn depth_at(&self, x: f32, y: f32) -> f32 {
        self.plane.x * x + self.plane.y * y + self.plane.z
    }
}

/// The fitted light view: where the map lies and how big its texels are.
#[derive(Clone, Copy, Debug)]
struct LightView {
    /// World → `(X, Y, D)`: texel coordinates and metres along the light from a reference depth.
    texel_from_world: DMat4,
    width: u32,
    height: u32,
    /// Texel edge, metres.
    texel: f32,
}

/// The light's frame: `right × up = −light` (a right-handed view looking along the light).
fn light_basis(light_dir: Vec3) -> (Vec3, Vec3) {
    let right = light_dir
        .cross(Vec3::Y)
        .try_normalize()
        .unwrap_or_else(|| light_dir.any_orthonormal_vector());
    (right, right.cross(light_dir))
}

/// Footprint of `d` seen from the light (right, up axes): its bounding rectangle, metres. A sphere's
/// reaches as far as its mesh may.
fn footprint(d: &Drawable, right: Vec3, up: Vec3) -> Rect {
    let c = Vec2::new(right.dot(d.pose.position), up.dot(d.pose.position));
    let rotation = d.pose.rotation.normalize();
    let slack = match d.shape {
        Shape::Cuboid { .. } => 1.0,
        Shape::Sphere { .. } => MESH_SLACK,
    };
    let half = slack * Vec2::new(d.shape.reach(rotation, right), d.shape.reach(rotation, up));
    Rect {
        lo: c - half,
        hi: c + half,
    }
}

/// How far (metres) a receiver may sink below a light-facing face of a box and still count as wholly
/// in front of it: bodies resting on a floor penetrate it by a few millimetres.
const RESTING_SLACK: f32 = 0.02;

/// The least of `n · p` over the points `p` of `d`'s true shape (a sphere's mesh reaches a few per
/// cent further, but what it adds below a floor is hidden inside the floor).
fn lowest_along(d: &Drawable, n: Vec3) -> f32 {
    n.dot(d.pose.position) - d.shape.reach(d.pose.rotation.normalize(), n)
}

/// False when drawable `i` cannot shadow any other receiver: it is a box with a light-facing face
/// whose plane every other receiver lies in front of (up to [`RESTING_SLACK`]), like a floor under
/// everything. Its shadow volume, the box swept along the light, lies behind that plane.
fn shadows_another(i: usize, drawables: &[Drawable], light_dir: Vec3) -> bool {
    let d = &drawables[i];
    let Shape::Cuboid { half_extents: h } = d.shape else {
        return true;
    };
    let axes = Mat3::from_quat(d.pose.rotation.normalize());
    for (axis, half) in [(axes.x_axis, h.x), (axes.y_axis, h.y), (axes.z_axis, h.z)] {
        let cos = axis.dot(light_dir);
        if cos == 0.0 {
            continue;
        }
        // The face toward the light, outward normal n, plane n · p = n · centre + half.
        let n = -axis * cos.signum();
        let plane = n.dot(d.pose.position) + half - RESTING_SLACK;
        let in_front = drawables.iter().enumerate().all(|(j, r)| {
            j == i || !r.receives_shadow || !r.is_drawable() || lowest_along(r, n) >= plane
        });
        if in_front {
            return false;
        }
    }
    true
}

/// The shadow pass and its buffers (kept between frames, so once sized it allocates nothing).
#[derive(Debug, Default)]
pub(crate) struct ShadowPass {
    /// Per drawable: its footprint if it takes part (drawable and casting or receiving).
    footprints: Vec<Option<Rect>>,
    /// Per drawable, what the lookup needs; and (id, drawable index) sorted by id.
    receivers: Vec<Receiver>,
    by_id: Vec<(u32, u32)>,
    /// The map: depth (metres along the light) and face index per texel, row-major, y down.
    depth: Vec<f32>,
    faces: Vec<u32>,
    /// Light-facing triangles rasterized this frame.
    face_table: Vec<Face>,
    /// The current caster's mesh vertices in texel space `(X, Y, D)`.
    verts: Vec<Vec3>,
}

impl ShadowPass {
    /// Capacities and addresses of the buffers (for checking that they stop growing).
    #[cfg(test)]
    pub(crate) fn capacities(&self) -> [(usize, usize); 7] {
        [
            (
                self.footprints.capacity(),
                self.footprints.as_ptr() as usize,
            ),
            (self.receivers.capacity(), self.receivers.as_ptr() as usize),
            (self.by_id.capacity(), self.by_id.as_ptr() as usize),
            (self.depth.capacity(), self.depth.as_ptr() as usize),
            (self.faces.capacity(), self.faces.as_ptr() as usize),
            (
                self.face_table.capacity(),
                self.face_table.as_ptr() as usize,
            ),
            (self.verts.capacity(), self.verts.as_ptr() as usize),
        ]
    }

    /// Darkens the pixels of `target` (drawn with `view`) where another drawable stands between them
    /// and the key light (see the module docs).
    pub(crate) fn cast(
        &mut self,
        target: &mut Frame,
        view: &View,
        drawables: &[Drawable],
        meshes: &MeshSet,
        lights: &Lights,
    ) {
        let light_dir = lights.key_dir;
        let side =
            (MAP_TEXELS_PER_PIXEL * view.viewport.width.max(view.viewport.height) as f32) as u32;
        let Some(light) = self.fit(drawables, light_dir, side.clamp(MAP_SIDE_MIN, MAP_SIDE_MAX))
        else {
            return;
        };
        self.draw_map(&light, drawables, meshes);
        self.prepare_receivers(drawables, light_dir);
        self.darken(target, view, &light, light_dir);
    }

    /// Fits the light view to where shadows can fall (see the module docs); `None` when no caster
    /// overlaps another receiver.
    fn fit(&mut self, drawables: &[Drawable], light_dir: Vec3, side: u32) -> Option<LightView> {
        let (right, up) = light_basis(light_dir);
        self.footprints.clear();
        self.footprints.extend(drawables.iter().map(|d| {
            (d.is_drawable() && (d.casts_shadow || d.receives_shadow))
                .then(|| footprint(d, right, up))
                .filter(|r| r.lo.is_finite() && r.hi.is_finite())
        }));
        // The receivers' bounding rectangle with any one of them left out: each side's extreme and
        // runner-up (minima as maxima of negated values).
        let mut sides = [TopTwo::NONE; 4];
        for (i, (d, f)) in drawables.iter().zip(&self.footprints).enumerate() {
            if let Some(f) = f
                && d.receives_shadow
            {
                for (s, v) in sides.iter_mut().zip([-f.lo.x, -f.lo.y, f.hi.x, f.hi.y]) {
                    s.push(v, i);
                }
            }
        }
        let mut fit = Rect::EMPTY;
        let (mut depth_lo, mut depth_hi) = (f32::INFINITY, f32::NEG_INFINITY);
        for (i, (d, f)) in drawables.iter().zip(self.footprints.iter_mut()).enumerate() {
            let Some(rect) = f else { continue };
            let others = Rect {
                lo: -Vec2::new(sides[0].excluding(i), sides[1].excluding(i)),
                hi: Vec2::new(sides[2].excluding(i), sides[3].excluding(i)),
            };
            let reach = rect.intersection(&others);
            if !d.casts_shadow || reach.is_empty() || !shadows_another(i, drawables, light_dir) {
                // Kept as a marker: this drawable is not drawn into the map.
                *f = None;
                continue;
            }
            fit = fit.union(&reach);
            let centre = light_dir.dot(d.pose.position);
            let r = d.shape.bounding_radius() * MESH_SLACK;
            depth_lo = depth_lo.min(centre - r);
            depth_hi = depth_hi.max(centre + r);
        }
        if fit.is_empty() {
            return None;
        }
        // Square texels, one spare texel on each side, rounded up to a power of 2^¼.
        let extent = (fit.hi - fit.lo).max_element() as f64;
        let raw = (extent / (side.max(3) - 2) as f64).max(1e-6);
        let texel = (4.0 * raw.log2()).ceil() / 4.0;
        let texel = texel.exp2();
        let x0 = (fit.lo.x as f64 / texel).floor() - 1.0;
        let y0 = (fit.hi.y as f64 / texel).ceil() + 1.0;
        let width = ((fit.hi.x as f64 / texel).ceil() + 1.0 - x0).clamp(1.0, side as f64) as u32;
        let height = (y0 - (fit.lo.y as f64 / texel).floor() + 1.0).clamp(1.0, side as f64) as u32;
        let depth_origin = 0.5 * (depth_lo as f64 + depth_hi as f64);
        let (r, u, l) = (
            right.as_dvec3() / texel,
            up.as_dvec3() / texel,
            light_dir.as_dvec3(),
        );
        let texel_from_world = DMat4::from_cols(
            DVec4::new(r.x, -u.x, l.x, 0.0),
            DVec4::new(r.y, -u.y, l.y, 0.0),
            DVec4::new(r.z, -u.z, l.z, 0.0),
            DVec4::new(-x0, y0, -depth_origin, 1.0),
        );
        texel_from_world.is_finite().then_some(LightView {
            texel_from_world,
            width,
            height,
            texel: texel as f32,
        })
    }

    /// Rasterizes the light-facing triangles of every caster the fit kept into the map.
    fn draw_map(&mut self, light: &LightView, drawables: &[Drawable], meshes: &MeshSet) {
        let Self {
            footprints,
            depth,
            faces,
            face_table,
            verts,
            ..
        } = self;
        let (w, h) = (light.width, light.height);
        let len = w as usize * h as usize;
        depth.clear();
        depth.resize(len, f32::INFINITY);
        faces.clear();
        faces.resize(len, NO_FACE);
        face_table.clear();
        let texel_from_world = light.texel_from_world.as_mat4();
        let (wf, hf) = (w as f32, h as f32);
        let inside = |p: Vec3| {
            p.x >= -MAP_GUARD && p.x <= wf + MAP_GUARD && p.y >= -MAP_GUARD && p.y <= hf + MAP_GUARD
        };
        for (d, f) in drawables.iter().zip(footprints.iter()) {
            if f.is_none() {
                continue;
            }
            let (mesh, scale) = meshes.for_shape(&d.shape, d.shape.bounding_radius() / light.texel);
            let world_from_unit = Mat4::from_scale_rotation_translation(
                scale,
                d.pose.rotation.normalize(),
                d.pose.position,
            );
            let texel_from_unit = texel_from_world * world_from_unit;
            verts.clear();
            verts.extend(
                mesh.positions
                    .iter()
                    .map(|&p| texel_from_unit.transform_point3(p)),
            );
            for t in &mesh.triangles {
                let tri = t.map(|i| verts[i as usize]);
                let mut draw = |tri: [Vec3; 3], index: u32| {
                    let screen = tri.map(|p| Vec2::new(p.x, p.y));
                    if let Some(setup) = TriangleSetup::new(screen, w, h, Cull::Back) {
                        setup.for_each_pixel(|k, l| {
                            let z = l[0] * tri[0].z + l[1] * tri[1].z + l[2] * tri[2].z;
                            if z < depth[k] {
                                depth[k] = z;
                                faces[k] = index;
                            }
                        });
                    }
                };
                // Back faces (away from the light) are dropped before any setup.
                let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                if n.z >= 0.0 {
                    continue;
                }
                let Some(face) = Face::new(d.id, tri) else {
                    continue;
                };
                let index = face_table.len() as u32;
                face_table.push(face);
                if tri.iter().all(|&p| inside(p)) {
                    draw(tri, index);
                    continue;
                }
                let poly = Polygon::from_triangle(tri.map(|p| p.extend(1.0)))
                    .clip_by(|p| p.x + 1.0)
                    .clip_by(|p| wf + 1.0 - p.x)
                    .clip_by(|p| p.y + 1.0)
                    .clip_by(|p| hf + 1.0 - p.y);
                let v = poly.vertices();
                for i in 1..v.len().saturating_sub(1) {
                    draw([v[0], v[i], v[i + 1]].map(Vec4::truncate), index);
                }
            }
        }
    }

    /// Fills the per-drawable lookup data and the id → drawable table.
    fn prepare_receivers(&mut self, drawables: &[Drawable], light_dir: Vec3) {
        self.receivers.clear();
        self.by_id.clear();
        for (i, d) in drawables.iter().enumerate() {
            let rotation = Mat3::from_quat(d.pose.rotation.normalize());
            let kind = match d.shape {
                Shape::Cuboid { half_extents } => ReceiverKind::Box {
                    half: half_extents,
                    cos: -(rotation.transpose() * light_dir),
                },
                Shape::Sphere { .. } => ReceiverKind::Sphere,
            };
            self.receivers.push(Receiver {
                receives: d.receives_shadow && d.is_drawable(),
                centre: d.pose.position,
                body_from_world: rotation.transpose(),
                kind,
            });
            self.by_id.push((d.id, i as u32));
        }
        self.by_id.sort_unstable_by_key(|&(id, _)| id);
    }

    /// The lookup: darkens each receiver pixel by the filtered fraction of the map that shadows it.
    fn darken(&self, target: &mut Frame, view: &View, light: &LightView, light_dir: Vec3) {
        let world_from_clip = view.clip_from_world.as_dmat4().inverse();
        let texel_from_clip = (light.texel_from_world * world_from_clip).as_mat4();
        let world_from_clip = world_from_clip.as_mat4();
        if !texel_from_clip.is_finite() || !world_from_clip.is_finite() {
            return;
        }
        let (w, h) = (view.viewport.width, view.viewport.height);
        let (mw, mh) = (light.width as i32, light.height as i32);
        let bias = DEPTH_BIAS + 0.5 * light.texel;
        let (pixels, depth, ids) = target.buffers_mut();
        let mut cached: (u32, Option<&Receiver>) = (Frame::NO_ID, None);
        let (ndc_dx, ndc_dy) = (2.0 / w as f32, 2.0 / h as f32);
        // Taps stay inside the map: points in its outermost half-texel ring (the fit's spare margin,
        // where no caster's footprint reaches) are left lit.
        let (fx_max, fy_max) = ((mw - 1) as f32, (mh - 1) as f32);
        for y in 0..h {
            let ndc_y = 1.0 - (y as f32 + 0.5) * ndc_dy;
            let row_texel = texel_from_clip.y_axis * ndc_y + texel_from_clip.w_axis;
            let row_world = world_from_clip.y_axis * ndc_y + world_from_clip.w_axis;
            for x in 0..w {
                let i = (y * w + x) as usize;
                let (id, z) = (ids[i], depth[i]);
                if id == Frame::NO_ID || !z.is_finite() {
                    continue;
                }
                let ndc_x = (x as f32 + 0.5) * ndc_dx - 1.0;
                let q = row_texel + texel_from_clip.x_axis * ndc_x + texel_from_clip.z_axis * z;
                let inv_w = 1.0 / q.w;
                let (tx, ty, td) = (q.x * inv_w, q.y * inv_w, q.z * inv_w);
                // Bilinear taps around (tx, ty): texels (ix, iy) … (ix + 1, iy + 1).
                let (fx, fy) = (tx - 0.5, ty - 0.5);
                if !(fx >= 0.0 && fy >= 0.0 && fx < fx_max && fy < fy_max) {
                    continue;
                }
                let (ix, iy) = (fx as usize, fy as usize);
                let (sx, sy) = (fx - ix as f32, fy - iy as f32);
                let base = iy * mw as usize + ix;
                let mut shadow = 0.0;
                for (k, weight) in [
                    (base, (1.0 - sx) * (1.0 - sy)),
                    (base + 1, sx * (1.0 - sy)),
                    (base + mw as usize, (1.0 - sx) * sy),
                    (base + mw as usize + 1, sx * sy),
                ] {
                    let face = self.faces[k];
                    if face == NO_FACE {
                        continue;
                    }
                    let face = &self.face_table[face as usize];
                    if face.id != id && face.depth_at(tx, ty) < td - bias {
                        shadow += weight;
                    }
                }
                if shadow <= 0.0 {
                    continue;
                }
                if cached.0 != id {
                    cached = (id, self.receiver(id));
                }
                let Some(receiver) = cached.1 else { continue };
                let p = row_world + world_from_clip.x_axis * ndc_x + world_from_clip.z_axis * z;
                let p_world = p.truncate() / p.w;
                let cos = receiver.cos_incidence(p_world, light_dir);
                if cos > 0.0 {
                    let k = 1.0 - (1.0 - SHADOW_FACTOR) * shadow * (cos / FULL_SHADOW_COS).min(1.0);
                    pixels[i] = scaled(pixels[i], k);
                }
            }
        }
    }

    /// The receiving drawable with id `id`, if any.
    fn receiver(&self, id: u32) -> Option<&Receiver> {
        let k = self.by_id.binary_search_by_key(&id, |&(i, _)| i).ok()?;
        let r = &self.receivers[self.by_id[k].1 as usize];
        r.receives.then_some(r)
    }
}

/// `c` with each channel multiplied by `k` in [0, 1].
#[inline]
fn scaled(c: Rgb, k: f32) -> Rgb {
    let f = (k.clamp(0.0, 1.0) * 256.0) as u16;
    let s = |v: u8| ((v as u16 * f) >> 8) as u8;
    Rgb::new(s(c.r), s(c.g), s(c.b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;

    fn cube(id: u32, centre: Vec3, half: Vec3) -> Drawable {
        Drawable::new(
            Shape::cuboid(half),
            Pose::from_position(centre),
            Rgb::WHITE,
            id,
        )
    }

    fn light() -> Vec3 {
        Lights::default().key_dir
    }

    #[test]
    fn top_two_leaves_out_only_the_given_index() {
        let mut t = TopTwo::NONE;
        for (i, v) in [3.0, 7.0, 5.0].into_iter().enumerate() {
            t.push(v, i);
        }
        assert_eq!(t.excluding(1), 5.0);
        assert_eq!(t.excluding(0), 7.0);
        assert_eq!(TopTwo::NONE.excluding(0), f32::NEG_INFINITY);
    }

    #[test]
    fn a_floor_under_everything_shadows_nothing_and_a_box_on_it_does() {
        let scene = [
            cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(20.0, 0.5, 20.0)),
            // Resting on the floor, sunk 5 mm into it.
            cube(1, Vec3::new(1.0, 0.495, 0.0), Vec3::splat(0.5)),
        ];
        assert!(!shadows_another(0, &scene, light()));
        assert!(shadows_another(1, &scene, light()));
        let ball = Drawable::new(
            Shape::sphere(0.65),
            Pose::from_position(Vec3::new(-2.0, 0.64, 1.0)),
            Rgb::WHITE,
            2,
        );
        assert!(!shadows_another(0, &[scene[0], scene[1], ball], light()));
    }

    #[test]
    fn a_huge_floor_does_not_stretch_the_map() {
        let fit = |floor_half: f32| {
            let scene = [
                cube(
                    0,
                    Vec3::new(0.0, -0.5, 0.0),
                    Vec3::new(floor_half, 0.5, floor_half),
                ),
                cube(1, Vec3::new(1.0, 0.5, 0.0), Vec3::splat(0.5)),
                cube(2, Vec3::new(-1.0, 1.5, 0.5), Vec3::splat(0.5)),
            ];
            ShadowPass::default().fit(&scene, light(), 256).unwrap()
        };
        let (small, huge) = (fit(5.0), fit(5000.0));
        assert_eq!(small.texel, huge.texel);
        assert!(small.texel < 0.02, "texels of {} m", small.texel);
        assert!(huge.width <= 256 && huge.height <= 256);
    }

    #[test]
    fn a_lone_body_needs_no_map() {
        let lone = [cube(0, Vec3::ZERO, Vec3::ONE)];
        assert!(ShadowPass::default().fit(&lone, light(), 256).is_none());
        assert!(ShadowPass::default().fit(&[], light(), 256).is_none());
    }

    #[test]
    fn a_face_plane_passes_through_its_vertices() {
        let t = [
            Vec3::new(1.0, 2.0, 0.5),
            Vec3::new(9.0, 3.0, -1.0),
            Vec3::new(4.0, 8.0, 2.0),
        ];
        let face = Face::new(7, t).unwrap();
        for p in t {
            assert!((face.depth_at(p.x, p.y) - p.z).abs() < 1e-5);
        }
        assert!(Face::new(7, [t[0], t[1], t[0]]).is_none(), "edge-on");
    }

    #[test]
    fn the_light_basis_is_right_handed_around_the_light() {
        for dir in [light(), Vec3::NEG_Y, Vec3::X] {
            let (right, up) = light_basis(dir);
            assert!((right.cross(up) + dir).length() < 1e-5, "{dir}");
        }
    }
}
