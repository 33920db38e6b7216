//! From a terminal cell to the body under it: the seed chapter's ray cast, through the same viewport and
//! camera the rasterizer draws with.

use glam::{Vec2, Vec3};
use ratatui::layout::Rect;

use crate::app::input::hand::cell_in;
use crate::geometry::{Camera, Ray, RayHit, Viewport};
use crate::physics::{BodyId, World};

/// The 3D view as the terminal shows it: the camera and pixel grid it is drawn with and the cells
/// it sits in. The hand and the grab ask it what a terminal cell points at and where a world point
/// is drawn, in absolute terminal cells (fractional: cell (c, r) spans [c, c + 1) × [r, r + 1)).
#[derive(Clone, Copy, Debug)]
pub struct ScreenView {
    pub camera: Camera,
    pub viewport: Viewport,
    /// Where the view sits in the terminal.
    pub cells: Rect,
    /// Colour samples per pixel side the view is drawn with: 2 supersampled, else 1 (see
    /// [`pick_cell_sampled`]).
    pub samples: u32,
}

impl ScreenView {
    /// The world ray through `at` (terminal cells). A place outside the view gives the ray its
    /// image would have if the view went on: a drag may leave the view and come back.
    pub fn ray_through(&self, at: Vec2) -> Ray {
        let col = at.x - f32::from(self.cells.x);
        let row = at.y - f32::from(self.cells.y);
        ray_through_pixel(
            &self.camera,
            &self.viewport,
            self.viewport.pixel_from_cell(Vec2::new(col, row)),
        )
    }

    /// Where world point `p` is drawn, in terminal cells.
    pub fn cell_position_of(&self, p: Vec3) -> Vec2 {
        let clip = self.camera.clip_from_world(self.viewport.aspect()) * p.extend(1.0);
        let pixel = self
            .viewport
            .pixel_from_ndc(Vec2::new(clip.x / clip.w, clip.y / clip.w));
        let cell = self.viewport.cell_from_pixel(pixel);
        Vec2::new(
            f32::from(self.cells.x) + cell.x,
            f32::from(self.cells.y) + cell.y,
        )
    }

    /// The body drawn under terminal cell `cell`, if the cell is in the view (see
    /// [`pick_cell_sampled`]).
    pub fn pick(&self, world: &World, cell: (u16, u16)) -> Option<Pick> {
        let cell = cell_in(self.cells, cell)?;
        pick_cell_sampled(world, &self.camera, &self.viewport, cell, self.samples)
    }
}

/// Where a click landed in the 3D view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pick {
    pub body: BodyId,
    pub hit: RayHit,
    /// The ray that found it; pushes act along `ray.dir`.
    pub ray: Ray,
}

/// The world ray through continuous pixel coordinates `pixel` of `viewport`.
pub fn ray_through_pixel(camera: &Camera, viewport: &Viewport, pixel: Vec2) -> Ray {
    camera.ray_through_ndc(viewport.ndc_from_pixel(pixel), viewport.aspect())
}

/// The body drawn under viewport cell `(col, row)` (cell coordinates relative to the viewport), in
/// whatever cell mode the viewport is laid out for, its pixels sampled at their centres (see
/// [`pick_cell_sampled`]).
pub fn pick_cell(
    world: &World,
    camera: &Camera,
    viewport: &Viewport,
    col: u16,
    row: u16,
) -> Option<Pick> {
    pick_cell_sampled(world, camera, viewport, (col, row), 1)
}

/// The body drawn under viewport cell `cell`, its pixels' colours sampled at `samples` ×
/// `samples` points each, as the rasterizer samples them (2 supersampled: at ¼ and ¾ of a pixel).
///
/// The click goes through the cell's centre, if what it hits is drawn in the cell: hit by the ray
/// through one of the cell's samples. When the centre's body is not among those, the body most of
/// the samples' rays hit wins, a tie going to the nearer hit, with the ray of its sample nearest
/// the centre. (In a 2 × 2 cell the centre is the corner of four pixels: through a gap between
/// two boxes narrower than a pixel, which the frame never shows, it picked what was behind; see
/// `tests/app/picking.rs`, `a_click_does_not_pick_through_a_gap_narrower_than_a_pixel`.)
///
/// A static body is a candidate only where the cell shows no movable one: the hands act on what
/// moves. Sampled at the pixels' centres alone, and with the floor a candidate, a body thinner than
/// a pixel that the supersampled colours show could not be clicked: the built-in chain's links,
/// 9 cm across at about 7 cm a pixel, answered "nothing there", and its end link, a few samples
/// of a cell whose centre shows the floor, "floor is part of the scenery" (`tests/app/picking.rs`,
/// `every_link_of_the_chain_the_view_shows_can_be_clicked`).
pub fn pick_cell_sampled(
    world: &World,
    camera: &Camera,
    viewport: &Viewport,
    (col, row): (u16, u16),
    samples: u32,
) -> Option<Pick> {
    let (cell, samples) = (viewport.cell, samples.max(1));
    let center = viewport.pixel_of_cell_center(col, row);
    let corner = viewport.pixel_from_cell(Vec2::new(f32::from(col), f32::from(row)));
    let (across, down) = (cell.cols * samples, cell.rows * samples);
    let mut drawn: Vec<(Pick, f32)> = Vec::with_capacity((across * down) as usize);
    let step = 1.0 / samples as f32;
    for dy in 0..down {
        for dx in 0..across {
            let at = corner + step * Vec2::new(dx as f32 + 0.5, dy as f32 + 0.5);
            if let Some(pick) = pick_pixel(world, camera, viewport, at) {
                drawn.push((pick, at.distance_squared(center)));
            }
        }
    }
    // A click acts on what can move: where the cell shows a movable body beside a static one,
    // the static one is not a candidate.
    let movable = |p: &Pick| !world.body(p.body).is_static();
    if drawn.iter().any(|(p, _)| movable(p)) {
        drawn.retain(|(p, _)| movable(p));
    }
    if let Some(pick) = pick_pixel(world, camera, viewport, center)
        && drawn.iter().any(|(p, _)| p.body == pick.body)
    {
        return Some(pick);
    }
    let votes = |body: BodyId| drawn.iter().filter(|(p, _)| p.body == body).count();
    let winner = drawn
        .iter()
        .map(|(p, _)| (votes(p.body), p.hit.t, p.body))
        .min_by(|a, b| b.0.cmp(&a.0).then(a.1.total_cmp(&b.1)))?
        .2;
    drawn
        .iter()
        .filter(|(p, _)| p.body == winner)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(p, _)| *p)
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
