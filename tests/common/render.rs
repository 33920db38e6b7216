//! Scenes for the rasterizer tests.

use glam::Vec3;
use nudge::color::Rgb;
use nudge::geometry::{Pose, Shape};
use nudge::render::{Drawable, RenderMode, RenderOptions};

/// A background no shading produces, so covered pixels can be told from empty ones.
pub const BACKGROUND: Rgb = Rgb::new(1, 2, 3);

/// `mode` over [`BACKGROUND`], without shadows.
pub fn options(mode: RenderMode) -> RenderOptions {
    RenderOptions {
        mode,
        background: BACKGROUND,
        shadows: false,
        ..RenderOptions::default()
    }
}

/// An axis-aligned box of these half extents, centred at `centre`.
pub fn cube(id: u32, centre: Vec3, half: Vec3) -> Drawable {
    Drawable::new(
        Shape::cuboid(half),
        Pose::from_position(centre),
        Rgb::new(180, 140, 90),
        id,
    )
}
