//! Planar shadows: each caster's mesh flattened along the key light onto a receiver's lit face.
//!
//! For a receiver box, take the face whose outward normal `n` looks most toward the light; its plane is
//! `n·p = d`. A caster point `p` above the plane lands at
//!     p' = p − L (n·p − d) / (n·L)
//! where `L` is the direction the light travels (Blinn, "Me and my (fake) shadow", 1988). Only caster
//! triangles facing the light are flattened (for a convex body their images tile its shadow), after
//! clipping them to the half-space above the plane; the flattened polygon is then clipped to the face's
//! rectangle. A shadow fragment darkens a pixel only where the id buffer shows the receiver: since the
//! camera is on the outer side of the face and the fragment lies on the face, the receiver being
//! visible there means its face is, so no depth comparison is needed.

use glam::{Mat3, Mat4, Vec3, Vec4};

use super::clip::{NON_FINITE, Polygon};
use super::mesh::MeshSet;
use super::post;
use super::raster::{Cull, TriangleSetup};
use super::shade::Lights;
use super::view::View;
use super::{Drawable, Frame};
use crate::geometry::{Camera, Projection, Shape};

/// Brightness factor of shadowed receiver pixels.
pub const SHADOW_FACTOR: f32 = 0.58;

/// The face of one receiver that shadows fall on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowReceiver {
    /// Id the receiver writes to the id buffer.
    pub id: u32,
    /// Index of the receiver in the drawables slice (a drawable never shadows itself).
    pub index: usize,
    /// Face plane `(n, −d)`: `plane · (p, 1)` is the signed height of `p` above the face, metres.
    pub plane: Vec4,
    /// The four side planes bounding the face, each `≥ 0` inside.
    pub sides: [Vec4; 4],
    /// Direction the key light travels, unit length, with `n·L ≤ −MIN_SLOPE`.
    pub light_dir: Vec3,
    /// 1 / (n·L).
    inv_n_dot_l: f32,
}

/// How far below the face plane (metres) a caster vertex may sink and still take the fast path: a body
/// resting on the receiver penetrates it a little, and flattening such a vertex "up" the light moves
/// its shadow by a negligible amount.
const RESTING_SLACK: f32 = 0.01;

/// Faces lit more grazingly than this (cosine) receive no shadows: the projection would stretch to
/// infinity.
const MIN_SLOPE: f32 = 0.1;

impl ShadowReceiver {
    /// The shadow-receiving face of `d` (index `index`) under a light travelling along `light_dir`, seen
    /// by `camera`; `None` for spheres, non-receivers, faces the camera cannot see, or grazing light.
    pub fn new(d: &Drawable, index: usize, light_dir: Vec3, camera: &Camera) -> Option<Self> {
        let Shape::Cuboid { half_extents: h } = d.shape else {
            return None;
        };
        if !(d.receives_shadow && d.is_drawable()) {
            return None;
        }
        let axes = Mat3::from_quat(d.pose.rotation);
        let axes = [axes.x_axis, axes.y_axis, axes.z_axis];
        let (mut best, mut best_cos) = (0, 0.0f32);
        for (k, axis) in axes.iter().enumerate() {
            let c = -axis.dot(light_dir);
            if c.abs() > best_cos.abs() {
                best = k;
                best_cos = c;
            }
        }
        let n = axes[best] * best_cos.signum();
        let n_dot_l = n.dot(light_dir);
        if n_dot_l > -MIN_SLOPE {
            return None;
        }
        let face_centre = d.pose.position + n * h[best];
        let sees_face = match camera.projection {
            Projection::Perspective { .. } => (camera.position - face_centre).dot(n) > 0.0,
            Projection::Orthographic { .. } => camera.basis().forward.dot(n) < 0.0,
        };
        if !sees_face {
            return None;
        }
        let mut sides = [Vec4::ZERO; 4];
        let mut s = 0;
        for (k, axis) in axes.iter().enumerate() {
            if k == best {
                continue;
            }
            let c = axis.dot(d.pose.position);
            // |a·p − c| ≤ h  ⇔  h + c − a·p ≥ 0  and  h − c + a·p ≥ 0.
            sides[s] = (-*axis).extend(h[k] + c);
            sides[s + 1] = axis.extend(h[k] - c);
            s += 2;
        }
        Some(Self {
            id: d.id,
            index,
            plane: n.extend(-n.dot(face_centre)),
            sides,
            light_dir,
            inv_n_dot_l: 1.0 / n_dot_l,
        })
    }

    /// Signed height of `p` above the face plane, metres.
    #[inline]
    pub fn height(&self, p: Vec3) -> f32 {
        self.plane.dot(p.extend(1.0))
    }

    /// `p` moved along the light onto the face plane.
    #[inline]
    pub fn project(&self, p: Vec3) -> Vec3 {
        p - self.light_dir * (self.height(p) * self.inv_n_dot_l)
    }

    /// How much flattening stretches lengths at most: `1 / |n·L|`.
    #[inline]
    pub fn stretch(&self) -> f32 {
        -self.inv_n_dot_l
    }

    /// True when a disc on the face plane (centre, radius) reaches into the face's rectangle's
    /// bounding slabs (a cheap, conservative overlap test).
    #[inline]
    pub fn disc_touches_face(&self, centre: Vec3, radius: f32) -> bool {
        let c = centre.extend(1.0);
        self.sides.iter().all(|s| s.dot(c) >= -radius)
    }

    /// True when a disc on the face plane lies wholly inside the face's rectangle.
    #[inline]
    pub fn disc_inside_face(&self, centre: Vec3, radius: f32) -> bool {
        let c = centre.extend(1.0);
        self.sides.iter().all(|s| s.dot(c) >= radius)
    }

    /// True when the normal `n_world` of a caster face points toward the light.
    #[inline]
    pub fn faces_light(&self, n_world: Vec3) -> bool {
        n_world.dot(self.light_dir) < 0.0
    }
}

/// Points on the silhouette circle of a sphere caster (its shadow is drawn as this polygon, flattened).
const SPHERE_SHADOW_SEGMENTS: usize = 16;

/// The shadow pass and its scratch buffers (kept between frames so it allocates nothing).
#[derive(Debug, Default)]
pub(crate) struct ShadowPass {
    /// World positions of the current caster's mesh vertices, and the same flattened onto the face.
    world: Vec<Vec3>,
    feet: Vec<Vec3>,
    /// Pixels in shadow, one per pixel of the target.
    mask: Vec<bool>,
    receivers: Vec<ShadowReceiver>,
}

impl ShadowPass {
    /// Capacities and addresses of the scratch buffers (for checking that they stop growing).
    #[cfg(test)]
    pub(crate) fn capacities(&self) -> [(usize, usize); 4] {
        [
            (self.world.capacity(), self.world.as_ptr() as usize),
            (self.feet.capacity(), self.feet.as_ptr() as usize),
            (self.mask.capacity(), self.mask.as_ptr() as usize),
            (self.receivers.capacity(), self.receivers.as_ptr() as usize),
        ]
    }

    /// Darkens `target` where casters' shadows fall on visible receiver faces.
    ///
    /// Per receiver and caster: skip the caster unless its bounding sphere's footprint (a disc of
    /// radius `R / |n·L|` around its flattened centre) touches the face and the view. A sphere
    /// wholly above the face is drawn as its exact shadow, the flattened circle where the light
    /// grazes it. Otherwise the mesh's light-facing triangles are flattened; when every vertex is
    /// above the face and lands inside it they need no clipping but the view volume's, else each
    /// is first clipped to the half-space above the face and, flattened, to the face's rectangle.
    pub(crate) fn cast(
        &mut self,
        target: &mut Frame,
        view: &View,
        camera: &Camera,
        drawables: &[Drawable],
        meshes: &MeshSet,
        lights: &Lights,
    ) {
        let Self {
            world,
            feet,
            mask,
            receivers,
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
            let mut mark = |clip: [Vec4; 3]| {
                let screen = clip.map(|c| view.to_screen(c).0);
                if let Some(setup) = TriangleSetup::new(screen, w, h, Cull::None) {
                    setup.for_each_pixel(|k, _| {
                        if ids[k] == r.id {
                            mask[k] = true;
                        }
                    });
                }
            };
            for (j, c) in drawables.iter().enumerate() {
                // 10 % to spare: sphere meshes are fitted slightly outside the true surface.
                let bound = 1.1 * c.shape.bounding_radius();
                if j == r.index || !c.casts_shadow || !c.is_drawable() {
                    continue;
                }
                let centre = c.pose.position;
                let height = r.height(centre);
                let foot = r.project(centre);
                let foot_radius = bound * r.stretch();
                if height < -bound
                    || !r.disc_touches_face(foot, foot_radius)
                    || view.culls_sphere(foot, foot_radius)
                {
                    continue;
                }
                if let Shape::Sphere { radius } = c.shape
                    && height >= radius
                {
                    let (u, v) = r.light_dir.any_orthonormal_pair();
                    let ring = radius * fit_scale(SPHERE_SHADOW_SEGMENTS);
                    let inside = r.disc_inside_face(foot, ring * r.stretch());
                    let mut previous = r.project(centre + ring * u);
                    for k in 1..=SPHERE_SHADOW_SEGMENTS {
                        let angle =
                            k as f32 / SPHERE_SHADOW_SEGMENTS as f32 * std::f32::consts::TAU;
                        let (sin, cos) = angle.sin_cos();
                        let next = r.project(centre + ring * (cos * u + sin * v));
                        flat_triangle([foot, previous, next], inside, r, view, &mut mark);
                        previous = next;
                    }
                    continue;
                }
                // Shadows are soft-edged at terminal resolution anyway: the coarsest sphere will do.
                let (mesh, scale) = meshes.for_shape(&c.shape, 0.0);
                let world_from_unit = Mat4::from_scale_rotation_translation(
                    scale,
                    c.pose.rotation.normalize(),
                    centre,
                );
                world.clear();
                feet.clear();
                let mut simple = true;
                for &p in &mesh.positions {
                    let p_world = world_from_unit.transform_point3(p);
                    let p_foot = r.project(p_world);
                    simple &= r.height(p_world) >= -RESTING_SLACK
                        && r.sides.iter().all(|s| s.dot(p_foot.extend(1.0)) >= 0.0);
                    world.push(p_world);
                    feet.push(p_foot);
                }
                for t in &mesh.triangles {
                    let [a, b, d] = t.map(|i| i as usize);
                    if !r.faces_light((world[b] - world[a]).cross(world[d] - world[a])) {
                        continue;
                    }
                    if simple {
                        flat_triangle([feet[a], feet[b], feet[d]], true, r, view, &mut mark);
                        continue;
                    }
                    let above = Polygon::from_triangle(
                        [world[a], world[b], world[d]].map(|p| p.extend(1.0)),
                    )
                    .clip_by(|v| r.plane.dot(v));
                    let v = above.vertices();
                    for i in 1..v.len().saturating_sub(1) {
                        let tri = [v[0], v[i], v[i + 1]].map(|p| r.project(p.truncate()));
                        flat_triangle(tri, false, r, view, &mut mark);
                    }
                }
            }
        }
        post::darken_masked(target, mask, SHADOW_FACTOR);
    }
}

/// `2 / (1 + cos(π / n))`: the circumradius, relative to the circle's radius, of an n-gon fitted so
/// it straddles the circle (see [`MeshSet`]).
fn fit_scale(n: usize) -> f32 {
    2.0 / (1.0 + (std::f32::consts::PI / n as f32).cos())
}

/// Rasterizes a flattened shadow triangle (world points on the face plane) through `mark`, first
/// clipping it to the face's rectangle unless it is known to lie `inside`, then to the view volume.
fn flat_triangle(
    feet: [Vec3; 3],
    inside: bool,
    r: &ShadowReceiver,
    view: &View,
    mark: &mut impl FnMut([Vec4; 3]),
) {
    if inside {
        let clip = feet.map(|p| view.clip_from_world * p.extend(1.0));
        let codes = clip.map(|c| view.volume.outcode(c));
        let any = codes[0] | codes[1] | codes[2];
        if any == 0 {
            mark(clip);
            return;
        }
    }
    let mut poly = Polygon::from_triangle(feet.map(|p| p.extend(1.0)));
    if !inside {
        for side in r.sides {
            poly = poly.clip_by(|v| side.dot(v));
        }
    }
    let mut any = 0;
    let mut all = u8::MAX;
    poly = poly.map(|v| {
        let clip = view.clip_from_world * *v;
        let code = view.volume.outcode(clip);
        any |= code;
        all &= code;
        clip
    });
    if poly.is_empty() || any & NON_FINITE != 0 || all != 0 {
        return;
    }
    if any != 0 {
        poly = view.volume.clip_polygon(poly, any);
    }
    let v = poly.vertices();
    for i in 1..v.len().saturating_sub(1) {
        mark([v[0], v[i], v[i + 1]]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::geometry::Pose;

    fn floor() -> Drawable {
        let mut d = Drawable::new(
            Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
            Rgb::WHITE,
            0,
        );
        d.receives_shadow = true;
        d
    }

    #[test]
    fn points_project_onto_the_top_face_along_the_light() {
        let light = Vec3::new(0.3, -1.0, 0.2).normalize();
        let camera = Camera::perspective(Vec3::new(0.0, 5.0, -10.0), Vec3::ZERO, 1.2);
        let r = ShadowReceiver::new(&floor(), 0, light, &camera).unwrap();
        let p = Vec3::new(1.0, 2.0, 3.0);
        let q = r.project(p);
        assert!(q.y.abs() < 1e-5, "lands on y = 0: {q}");
        assert!(
            (q - p).normalize().dot(light) > 0.9999,
            "moves along the light"
        );
    }

    #[test]
    fn a_camera_below_the_floor_sees_no_shadow_face() {
        let light = Vec3::NEG_Y;
        let camera = Camera::perspective(Vec3::new(0.0, -5.0, -10.0), Vec3::ZERO, 1.2);
        assert!(ShadowReceiver::new(&floor(), 0, light, &camera).is_none());
    }

    #[test]
    fn side_planes_bound_the_face() {
        let light = Vec3::NEG_Y;
        let camera = Camera::perspective(Vec3::new(0.0, 5.0, -10.0), Vec3::ZERO, 1.2);
        let r = ShadowReceiver::new(&floor(), 0, light, &camera).unwrap();
        let inside = |p: Vec3| r.sides.iter().all(|s| s.dot(p.extend(1.0)) >= 0.0);
        assert!(inside(Vec3::new(9.9, 0.0, -9.9)));
        assert!(!inside(Vec3::new(10.1, 0.0, 0.0)));
        assert!(!inside(Vec3::new(0.0, 0.0, -10.1)));
    }
}
