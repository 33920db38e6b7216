//! Per-frame render settings.

use crate::color::Rgb;

use super::RenderMode;

/// What to draw and how; cheap to copy, may change every frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// How surfaces are coloured.
    pub mode: RenderMode,
    /// Render at 2× in each direction and box-filter the colours down (ids stay exact, see
    /// [`crate::render::Renderer::render`]). Roughly 4× the fill cost.
    pub supersample: bool,
    /// Shadows of every drawable on every other, from a shadow map along the key light (ignored in
    /// depth, normals and wireframe modes; see [`crate::render::shadow`]).
    pub shadows: bool,
    /// Colour of pixels that no drawable covers.
    pub background: Rgb,
    /// Colour of the outline drawn just inside highlighted drawables' silhouettes.
    pub outline: Rgb,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            mode: RenderMode::default(),
            supersample: false,
            shadows: true,
            background: Rgb::new(0x1c, 0x20, 0x28),
            outline: Rgb::new(0xff, 0xe0, 0x60),
        }
    }
}
