//! The one camera: it gives the matrices the rasterizer draws with and the rays picking casts.
//!
//! Right-handed view space looking down −z (glam `look_at_rh`); clip depth in [0, 1].

use glam::{Mat4, Vec2, Vec3};

use super::Ray;

/// How view space is flattened onto the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Vertical field of view in radians, in (0, π).
    Perspective { fov_y: f32 },
    /// Height of the visible slab in metres, > 0; the width follows from the image aspect.
    Orthographic { view_height: f32 },
}

/// A camera at `position` looking at `target`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub position: Vec3,
    /// Point looked at; differs from `position`.
    pub target: Vec3,
    /// Approximate up direction; not parallel to `target - position`.
    pub up: Vec3,
    pub projection: Projection,
    /// Near and far plane distances along the view direction, `0 < near < far`.
    pub near: f32,
    pub far: f32,
}

/// The camera's orthonormal frame in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraBasis {
    pub forward: Vec3,
    pub right: Vec3,
    pub up: Vec3,
}

impl Camera {
    pub fn perspective(position: Vec3, target: Vec3, fov_y: f32) -> Self {
        Self {
            position,
            target,
            up: Vec3::Y,
            projection: Projection::Perspective { fov_y },
            near: 0.1,
            far: 500.0,
        }
    }

    /// Forward, right and up unit vectors. Falls back to a fixed frame if the camera is degenerate
    /// (target on top of position, or looking straight along `up`).
    pub fn basis(&self) -> CameraBasis {
        let forward = (self.target - self.position)
            .try_normalize()
            .unwrap_or(Vec3::NEG_Z);
        let right = forward
            .cross(self.up)
            .try_normalize()
            .or_else(|| forward.cross(Vec3::Z).try_normalize())
            .unwrap_or(Vec3::X);
        let up = right.cross(forward);
        CameraBasis { forward, right, up }
    }

    pub fn view_from_world(&self) -> Mat4 {
        let b = self.basis();
        Mat4::look_to_rh(self.position, b.forward, b.up)
    }

    /// Projection for an image of displayed aspect `aspect` (width / height).
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        match self.projection {
            Projection::Perspective { fov_y } => {
                Mat4::perspective_rh(fov_y, aspect, self.near, self.far)
            }
            Projection::Orthographic { view_height } => {
                let half_h = 0.5 * view_height;
                let half_w = half_h * aspect;
                Mat4::orthographic_rh(-half_w, half_w, -half_h, half_h, self.near, self.far)
            }
        }
    }

    pub fn clip_from_world(&self, aspect: f32) -> Mat4 {
        self.clip_from_view(aspect) * self.view_from_world()
    }

    /// The ray through a point of the image given in NDC, for an image of displayed `aspect`
    /// (see [`ImageRays::through_ndc`]).
    pub fn ray_through_ndc(&self, ndc: Vec2, aspect: f32) -> Ray {
        self.image_rays(aspect).through_ndc(ndc)
    }

    /// The `t` range of `ray` (from [`Camera::ray_through_ndc`]) that lies between the near and far planes.
    pub fn visible_range(&self, ray: &Ray) -> (f32, f32) {
        self.image_rays(1.0).visible_range(ray)
    }

    /// The rays through an image of displayed `aspect`, the camera's frame worked out once: what
    /// picking casts, and what the rasterizer intersects balls with, pixel by pixel.
    pub fn image_rays(&self, aspect: f32) -> ImageRays {
        let b = self.basis();
        let (half_h, orthographic) = match self.projection {
            Projection::Perspective { fov_y } => ((0.5 * fov_y).tan(), false),
            Projection::Orthographic { view_height } => (0.5 * view_height, true),
        };
        ImageRays {
            position: self.position,
            basis: b,
            half_h,
            aspect,
            orthographic,
            near: self.near,
            far: self.far,
        }
    }

    /// Turns the camera about its target: `yaw` about world up, `pitch` about the camera's right axis,
    /// radians. Pitch stops short of the poles so the view never flips.
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        let offset = self.position - self.target;
        let radius = offset.length();
        if radius <= 0.0 || !radius.is_finite() {
            return;
        }
        let current_pitch = (offset.y / radius).clamp(-1.0, 1.0).asin();
        let limit = 89f32.to_radians();
        let new_pitch = (current_pitch + pitch).clamp(-limit, limit);
        let current_yaw = offset.z.atan2(offset.x);
        let new_yaw = current_yaw - yaw;
        let horizontal = radius * new_pitch.cos();
        self.position = self.target
            + Vec3::new(
                horizontal * new_yaw.cos(),
                radius * new_pitch.sin(),
                horizontal * new_yaw.sin(),
            );
    }

    /// Moves toward the target by `factor` (< 1 zooms in); orthographic cameras scale their view height.
    pub fn zoom(&mut self, factor: f32) {
        if !(factor.is_finite() && factor > 0.0) {
            return;
        }
        match &mut self.projection {
            Projection::Perspective { .. } => {
                let offset = (self.position - self.target) * factor;
                if offset.length() > 1e-3 && offset.length() < 0.5 * self.far {
                    self.position = self.target + offset;
                }
            }
            Projection::Orthographic { view_height } => {
                *view_height = (*view_height * factor).clamp(1e-2, 1e4)
            }
        }
    }

    /// The same view with the other projection: an orthographic view sized to show, at the target's
    /// distance, what the perspective view shows there (and back).
    pub fn toggled_projection(&self, default_fov_y: f32) -> Camera {
        let distance = (self.target - self.position).length().max(1e-3);
        let projection = match self.projection {
            Projection::Perspective { fov_y } => Projection::Orthographic {
                view_height: 2.0 * distance * (0.5 * fov_y).tan(),
            },
            Projection::Orthographic { .. } => Projection::Perspective {
                fov_y: default_fov_y,
            },
        };
        Camera {
            projection,
            ..*self
        }
    }
}

/// The rays of one camera through an image of one aspect ([`Camera::image_rays`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageRays {
    position: Vec3,
    basis: CameraBasis,
    /// Half the image's height: as a slope (tan of half the field of view) in perspective, in
    /// metres in orthographic.
    half_h: f32,
    /// Displayed width / height.
    aspect: f32,
    orthographic: bool,
    near: f32,
    far: f32,
}

impl ImageRays {
    /// The ray through a point of the image given in NDC.
    ///
    /// Perspective rays start at the eye; orthographic rays are parallel to the view direction and start
    /// on the camera plane. Either way, only `t` in [`ImageRays::visible_range`] is drawn.
    #[inline]
    pub fn through_ndc(&self, ndc: Vec2) -> Ray {
        let b = &self.basis;
        if self.orthographic {
            let origin = self.position
                + b.right * (ndc.x * self.half_h * self.aspect)
                + b.up * (ndc.y * self.half_h);
            Ray {
                origin,
                dir: b.forward,
            }
        } else {
            let dir = b.forward
                + b.right * (ndc.x * self.aspect * self.half_h)
                + b.up * (ndc.y * self.half_h);
            Ray {
                origin: self.position,
                dir: dir.normalize_or(b.forward),
            }
        }
    }

    /// The `t` range of `ray` (from [`ImageRays::through_ndc`]) that lies between the near and far
    /// planes.
    #[inline]
    pub fn visible_range(&self, ray: &Ray) -> (f32, f32) {
        let along = ray.dir.dot(self.basis.forward).max(1e-6);
        (self.near / along, self.far / along)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn project(camera: &Camera, aspect: f32, p: Vec3) -> Vec3 {
        let clip = camera.clip_from_world(aspect) * p.extend(1.0);
        clip.truncate() / clip.w
    }

    #[test]
    fn ray_through_a_projected_point_passes_through_it() {
        for projection in [
            Projection::Perspective { fov_y: 1.2 },
            Projection::Orthographic { view_height: 6.0 },
        ] {
            let camera = Camera {
                projection,
                ..Camera::perspective(Vec3::new(1.0, 4.0, -12.0), Vec3::new(0.0, 1.0, 0.0), 1.2)
            };
            let aspect = 1.7;
            let p = Vec3::new(0.7, 1.3, 0.4);
            let ndc = project(&camera, aspect, p);
            assert!(ndc.z > 0.0 && ndc.z < 1.0, "{ndc}");
            let ray = camera.ray_through_ndc(ndc.truncate(), aspect);
            let t = (p - ray.origin).dot(ray.dir);
            assert!((ray.at(t) - p).length() < 1e-4, "{projection:?}");
        }
    }

    #[test]
    fn orbit_keeps_distance_and_target() {
        let mut camera = Camera::perspective(Vec3::new(0.0, 4.0, -12.0), Vec3::Y, 1.2);
        let before = (camera.position - camera.target).length();
        camera.orbit(0.3, 0.2);
        camera.orbit(-1.0, 5.0);
        let after = (camera.position - camera.target).length();
        assert!((before - after).abs() < 1e-4);
        assert!(camera.position.is_finite());
    }
}
