//! The pixel grid a frame is drawn into, and the map between its pixels and NDC.
//!
//! Drawing and picking both go through this type, so what you click is what was drawn.

use glam::Vec2;

/// A `width × height` pixel grid whose pixels are `pixel_aspect` times taller than wide on screen.
///
/// A half-block terminal cell holds two pixels stacked vertically, so with a cell aspect (height/width)
/// of 2.0 each pixel is square: `pixel_aspect = cell_aspect / 2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    pub width: u32,
    pub height: u32,
    /// Displayed pixel height / pixel width; finite, > 0.
    pub pixel_aspect: f32,
}

impl Viewport {
    pub fn new(width: u32, height: u32, pixel_aspect: f32) -> Self {
        let pixel_aspect = if pixel_aspect.is_finite() && pixel_aspect > 0.0 {
            pixel_aspect
        } else {
            1.0
        };
        Self {
            width,
            height,
            pixel_aspect,
        }
    }

    /// Displayed width / height of the whole image (what the projection needs). 1 for an empty grid.
    pub fn aspect(&self) -> f32 {
        if self.width == 0 || self.height == 0 {
            return 1.0;
        }
        self.width as f32 / (self.height as f32 * self.pixel_aspect)
    }

    pub fn is_empty(&self) -> bool {
        self.width == 0 || self.height == 0
    }

    /// Continuous pixel coordinates (x right, y down) → NDC (x right, y up, [-1, 1] across the grid).
    pub fn ndc_from_pixel(&self, p: Vec2) -> Vec2 {
        Vec2::new(
            p.x / self.width.max(1) as f32 * 2.0 - 1.0,
            1.0 - p.y / self.height.max(1) as f32 * 2.0,
        )
    }

    /// NDC → continuous pixel coordinates; the inverse of [`Viewport::ndc_from_pixel`].
    pub fn pixel_from_ndc(&self, ndc: Vec2) -> Vec2 {
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * self.width as f32,
            (1.0 - ndc.y) * 0.5 * self.height as f32,
        )
    }

    /// NDC of the centre of pixel `(x, y)`.
    pub fn ndc_of_pixel_center(&self, x: u32, y: u32) -> Vec2 {
        self.ndc_from_pixel(Vec2::new(x as f32 + 0.5, y as f32 + 0.5))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_map_to_ndc_corners_and_back() {
        let v = Viewport::new(200, 100, 1.0);
        assert_eq!(v.ndc_from_pixel(Vec2::ZERO), Vec2::new(-1.0, 1.0));
        assert_eq!(
            v.ndc_from_pixel(Vec2::new(200.0, 100.0)),
            Vec2::new(1.0, -1.0)
        );
        let p = Vec2::new(37.5, 81.25);
        assert!((v.pixel_from_ndc(v.ndc_from_pixel(p)) - p).length() < 1e-4);
    }

    #[test]
    fn tall_pixels_narrow_the_aspect() {
        assert_eq!(Viewport::new(100, 50, 1.0).aspect(), 2.0);
        assert_eq!(Viewport::new(100, 50, 2.0).aspect(), 1.0);
    }
}
