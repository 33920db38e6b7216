//! The render target: colour, depth and id buffers of one image.

use crate::color::Rgb;

/// A `width × height` image with a depth and an id per pixel, stored row-major with y down
/// (index `y * width + x`).
///
/// Invariants: `pixels`, `depth` and `ids` all hold exactly `width * height` entries. After
/// [`crate::render::Renderer::render`], `depth` holds clip-space depth in [0, 1] (0 at the near plane)
/// where a drawable covers the pixel and `f32::INFINITY` elsewhere, and `ids` holds the covering
/// drawable's id or [`Frame::NO_ID`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    width: u32,
    height: u32,
    pixels: Vec<Rgb>,
    depth: Vec<f32>,
    ids: Vec<u32>,
}

impl Frame {
    /// The id of a pixel that no drawable covers. Drawables must not use it as their id.
    pub const NO_ID: u32 = u32::MAX;

    /// A black frame with no depth and no ids.
    pub fn new(width: u32, height: u32) -> Self {
        let mut frame = Self::default();
        frame.resize(width, height);
        frame
    }

    /// Changes the size, keeping the allocations when they are large enough. The contents are
    /// cleared to black, infinite depth and [`Frame::NO_ID`].
    pub fn resize(&mut self, width: u32, height: u32) {
        self.set_size(width, height);
        self.clear(Rgb::BLACK);
    }

    /// Changes the size without clearing (contents are unspecified until the next [`Frame::clear`]).
    pub(crate) fn set_size(&mut self, width: u32, height: u32) {
        self.width = width;
        self.height = height;
        let len = width as usize * height as usize;
        self.pixels.resize(len, Rgb::BLACK);
        self.depth.resize(len, f32::INFINITY);
        self.ids.resize(len, Self::NO_ID);
    }

    /// Fills every pixel with `background`, depth with infinity and ids with [`Frame::NO_ID`].
    pub fn clear(&mut self, background: Rgb) {
        self.pixels.fill(background);
        self.depth.fill(f32::INFINITY);
        self.ids.fill(Self::NO_ID);
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// True when the frame holds no pixel.
    pub fn is_empty(&self) -> bool {
        self.pixels.is_empty()
    }

    /// Row-major index of pixel `(x, y)`, or `None` outside the frame.
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> Option<usize> {
        (x < self.width && y < self.height).then(|| y as usize * self.width as usize + x as usize)
    }

    /// Colour of pixel `(x, y)`; black outside the frame.
    pub fn pixel(&self, x: u32, y: u32) -> Rgb {
        self.index(x, y).map_or(Rgb::BLACK, |i| self.pixels[i])
    }

    /// Id of the drawable covering pixel `(x, y)`; `None` for background or outside the frame.
    pub fn id_at(&self, x: u32, y: u32) -> Option<u32> {
        let id = self.ids[self.index(x, y)?];
        (id != Self::NO_ID).then_some(id)
    }

    /// Clip-space depth in [0, 1] at pixel `(x, y)`; `None` for background or outside the frame.
    pub fn depth_at(&self, x: u32, y: u32) -> Option<f32> {
        let d = self.depth[self.index(x, y)?];
        d.is_finite().then_some(d)
    }

    /// All pixels, row-major, y down.
    pub fn pixels(&self) -> &[Rgb] {
        &self.pixels
    }

    /// All depths, row-major, y down (see the type's invariants).
    pub fn depths(&self) -> &[f32] {
        &self.depth
    }

    /// All ids, row-major, y down.
    pub fn ids(&self) -> &[u32] {
        &self.ids
    }

    /// The three buffers at once, mutably, for the rasterizer: (pixels, depth, ids).
    pub(crate) fn buffers_mut(&mut self) -> (&mut [Rgb], &mut [f32], &mut [u32]) {
        (&mut self.pixels, &mut self.depth, &mut self.ids)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_frame_is_background_everywhere() {
        let frame = Frame::new(3, 2);
        assert_eq!(frame.pixels().len(), 6);
        assert_eq!(frame.id_at(2, 1), None);
        assert_eq!(frame.depth_at(0, 0), None);
    }

    #[test]
    fn out_of_range_reads_are_harmless() {
        let frame = Frame::new(0, 0);
        assert_eq!(frame.pixel(0, 0), Rgb::BLACK);
        assert_eq!(frame.id_at(5, 5), None);
        let frame = Frame::new(1, 2);
        assert_eq!(frame.index(0, 1), Some(1));
        assert_eq!(frame.index(1, 0), None);
    }

    #[test]
    fn resize_changes_every_buffer() {
        let mut frame = Frame::new(4, 4);
        frame.resize(2, 5);
        assert_eq!((frame.width(), frame.height()), (2, 5));
        assert_eq!(frame.depths().len(), 10);
        assert_eq!(frame.ids().len(), 10);
    }
}
