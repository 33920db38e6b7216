//! What a pass needs to know about the camera and the image: matrices, frustum, the NDC → pixel map.

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::Drawable;
use super::clip::ClipVolume;
use crate::geometry::{Camera, ImageRays, Projection, Viewport};

/// Per-target constants of a pass: the camera's matrices for one image size.
pub(crate) struct View {
    /// The target's pixel grid.
    pub(crate) viewport: Viewport,
    /// `camera.clip_from_world(viewport.aspect())`.
    pub(crate) clip_from_world: Mat4,
    /// Clip volume with a guard band sized for the viewport.
    pub(crate) volume: ClipVolume,
    /// World-space frustum planes `(n, d)`, `|n| = 1`, inside where `n·p + d ≥ 0`.
    pub(crate) frustum: [Vec4; 6],
    /// Camera position, world.
    pub(crate) eye: Vec3,
    /// Unit view direction, world.
    pub(crate) forward: Vec3,
    /// Perspective (rays from `eye`) or orthographic (rays along `forward`).
    pub(crate) perspective: bool,
    /// Pixels per metre at view depth 1 (perspective) or at any depth (orthographic), along the
    /// image axis with the finer pixels.
    pub(crate) pixels_per_metre: f32,
    /// Near plane distance, metres.
    pub(crate) near: f32,
    /// The ray through each pixel centre, as picking casts it.
    pub(crate) rays: ImageRays,
}

impl View {
    /// The constants for drawing `camera`'s view into `viewport`.
    pub(crate) fn new(camera: &Camera, viewport: Viewport) -> Self {
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
            pixels_per_metre: (clip_from_view.x_axis.x * 0.5 * viewport.width as f32)
                .max(clip_from_view.y_axis.y * 0.5 * viewport.height as f32),
            near: camera.near,
            rays: camera.image_rays(aspect),
        }
    }

    /// True when `d`'s bounding sphere (with 10 % to spare for meshes fitted around the surface) is
    /// wholly outside the view frustum.
    pub(crate) fn culls(&self, d: &Drawable) -> bool {
        self.culls_sphere(d.pose.position, 1.1 * d.shape.bounding_radius())
    }

    /// True when the sphere (world centre, radius in metres) is wholly outside the view frustum.
    pub(crate) fn culls_sphere(&self, centre: Vec3, radius: f32) -> bool {
        let c = centre.extend(1.0);
        self.frustum.iter().any(|p| p.dot(c) < -radius)
    }

    /// Approximate radius in pixels of the image of `d`'s bounding sphere.
    pub(crate) fn projected_radius(&self, d: &Drawable) -> f32 {
        let scale = if self.perspective {
            self.pixels_per_metre
                / (d.pose.position - self.eye)
                    .dot(self.forward)
                    .max(self.near)
        } else {
            self.pixels_per_metre
        };
        d.shape.bounding_radius() * scale.abs()
    }

    /// Pixel position (x right, y down) and clip depth of a clip-space point with `w > 0`.
    #[inline]
    pub(crate) fn to_screen(&self, clip: Vec4) -> (Vec2, f32) {
        let inv_w = 1.0 / clip.w;
        let ndc = Vec2::new(clip.x * inv_w, clip.y * inv_w);
        (self.viewport.pixel_from_ndc(ndc), clip.z * inv_w)
    }
}
