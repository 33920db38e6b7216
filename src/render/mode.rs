//! Render modes: how surfaces are coloured.

use std::fmt;

/// How the rasterizer colours what it draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RenderMode {
    /// Visible mesh edges only (hidden lines removed by a depth pre-pass).
    Wireframe,
    /// One lit colour per triangle (diffuse key + fill + ambient).
    Flat,
    /// Per-pixel lighting from interpolated normals, with a specular highlight.
    Smooth,
    /// Smooth lighting times procedural textures (wood, checker, sphere stripes).
    #[default]
    Textured,
    /// Greyscale distance from the camera, near = bright, normalised over the frame.
    Depth,
    /// World-space normal as colour: `rgb = n / 2 + 1/2`.
    Normals,
}

impl RenderMode {
    /// Every mode, in the order [`RenderMode::next`] cycles through.
    pub const ALL: [RenderMode; 6] = [
        RenderMode::Wireframe,
        RenderMode::Flat,
        RenderMode::Smooth,
        RenderMode::Textured,
        RenderMode::Depth,
        RenderMode::Normals,
    ];

    fn position(self) -> usize {
        Self::ALL.iter().position(|&m| m == self).unwrap_or(0)
    }

    /// The following mode, wrapping around.
    pub fn next(self) -> Self {
        Self::ALL[(self.position() + 1) % Self::ALL.len()]
    }

    /// The preceding mode, wrapping around.
    pub fn prev(self) -> Self {
        Self::ALL[(self.position() + Self::ALL.len() - 1) % Self::ALL.len()]
    }

    /// Lower-case name: what `--mode` accepts (see `cli`) and the status bar shows.
    pub fn name(self) -> &'static str {
        match self {
            RenderMode::Wireframe => "wireframe",
            RenderMode::Flat => "flat",
            RenderMode::Smooth => "smooth",
            RenderMode::Textured => "textured",
            RenderMode::Depth => "depth",
            RenderMode::Normals => "normals",
        }
    }
}

impl fmt::Display for RenderMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_and_prev_cycle_through_all_modes() {
        let mut mode = RenderMode::Wireframe;
        for _ in 0..RenderMode::ALL.len() {
            assert_eq!(mode.next().prev(), mode);
            mode = mode.next();
        }
        assert_eq!(mode, RenderMode::Wireframe);
        assert_eq!(RenderMode::Wireframe.prev(), RenderMode::Normals);
    }
}
