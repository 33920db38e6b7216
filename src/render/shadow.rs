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

use glam::{Mat3, Vec3, Vec4};

use super::Drawable;
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
    light_dir: Vec3,
    /// 1 / (n·L).
    inv_n_dot_l: f32,
}

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

    /// True when the normal `n_world` of a caster face points toward the light.
    #[inline]
    pub fn faces_light(&self, n_world: Vec3) -> bool {
        n_world.dot(self.light_dir) < 0.0
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
