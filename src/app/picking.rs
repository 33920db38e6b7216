//! From a terminal cell to the body under it: the seed chapter's ray cast, through the same viewport and
//! camera the rasterizer draws with.

use glam::Vec2;

use crate::geometry::{Camera, Ray, RayHit, Viewport};
use crate::physics::{BodyId, World};

/// Where a click landed in the 3D view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    pub body: BodyId,
    pub hit: RayHit,
    /// The ray that found it; pushes act along `ray.dir`.
    pub ray: Ray,
}

/// The centre of viewport cell `(col, row)` in pixel coordinates: a cell holds pixels `2·row` (top half)
/// and `2·row + 1` (bottom half), so its centre lies on the line between them.
pub fn cell_center_pixel(col: u16, row: u16) -> Vec2 {
    Vec2::new(col as f32 + 0.5, 2.0 * row as f32 + 1.0)
}

/// The world ray through continuous pixel coordinates `pixel` of `viewport`.
pub fn ray_through_pixel(camera: &Camera, viewport: &Viewport, pixel: Vec2) -> Ray {
    camera.ray_through_ndc(viewport.ndc_from_pixel(pixel), viewport.aspect())
}

/// The nearest body drawn under viewport cell `(col, row)` (cell coordinates relative to the viewport).
pub fn pick_cell(
    world: &World,
    camera: &Camera,
    viewport: &Viewport,
    col: u16,
    row: u16,
) -> Option<Pick> {
    pick_pixel(world, camera, viewport, cell_center_pixel(col, row))
}

/// The nearest body drawn at continuous pixel coordinates `pixel`.
pub fn pick_pixel(
    world: &World,
    camera: &Camera,
    viewport: &Viewport,
    pixel: Vec2,
) -> Option<Pick> {
    if viewport.is_empty()
        || pixel.x < 0.0
        || pixel.y < 0.0
        || pixel.x > viewport.width as f32
        || pixel.y > viewport.height as f32
    {
        return None;
    }
    let ray = ray_through_pixel(camera, viewport, pixel);
    let (t_min, t_max) = camera.visible_range(&ray);
    world
        .cast_ray(&ray, t_min, t_max)
        .map(|(body, hit)| Pick { body, hit, ray })
}
