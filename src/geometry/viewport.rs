//! The pixel grid a frame is drawn into, and the map between its pixels and NDC.
//!
//! Drawing and picking both go through this type, so what you click is what was drawn.

use glam::Vec2;

/// Pixels one terminal cell shows: `cols` across and `rows` down.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellPixels {
    /// Pixels across a cell; ≥ 1.
    pub cols: u32,
    /// Pixels down a cell; ≥ 1.
    pub rows: u32,
}

impl CellPixels {
    /// A half-block cell: one pixel across, two down.
    pub const HALF: CellPixels = CellPixels { cols: 1, rows: 2 };
}

/// A `width × height` pixel grid whose pixels are `pixel_aspect` times taller than wide on screen,
/// shown `cell` pixels to a terminal cell.
///
/// A half-block terminal cell holds two pixels stacked vertically, so with a cell aspect (height/width)
/// of 2.0 each pixel is square: `pixel_aspect = cell_aspect / 2`. In general a cell of `c × r` pixels
/// gives `pixel_aspect = cell_aspect · c / r` (an octant cell, 2 × 4, has square pixels too).
///
/// Cells and pixels: cell (col, row) covers pixels `[col · c, (col + 1) · c) × [row · r, (row + 1) · r)`,
/// so a click on a cell picks through the centre of that block ([`Viewport::pixel_of_cell_center`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Viewport {
    pub width: u32,
    pub height: u32,
    /// Displayed pixel height / pixel width; finite, > 0.
    pub pixel_aspect: f32,
    /// Pixels one terminal cell shows ([`CellPixels::HALF`] unless made by [`Viewport::of_cells`]).
    pub cell: CellPixels,
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
            cell: CellPixels::HALF,
        }
    }

    /// The grid that fills `cols × rows` terminal cells of `cell` pixels each, the cells
    /// `cell_aspect` (height / width) times taller than wide.
    pub fn of_cells(cols: u16, rows: u16, cell: CellPixels, cell_aspect: f32) -> Self {
        let cell = CellPixels {
            cols: cell.cols.max(1),
            rows: cell.rows.max(1),
        };
        Self {
            cell,
            ..Self::new(
                u32::from(cols) * cell.cols,
                u32::from(rows) * cell.rows,
                cell_aspect * cell.cols as f32 / cell.rows as f32,
            )
        }
    }

    /// Continuous pixel coordinates of a place in cells (cell (c, r) spans [c, c + 1) × [r, r + 1)).
    pub fn pixel_from_cell(&self, at: Vec2) -> Vec2 {
        Vec2::new(at.x * self.cell.cols as f32, at.y * self.cell.rows as f32)
    }

    /// The place in cells of continuous pixel coordinates; the inverse of
    /// [`Viewport::pixel_from_cell`].
    pub fn cell_from_pixel(&self, pixel: Vec2) -> Vec2 {
        Vec2::new(
            pixel.x / self.cell.cols as f32,
            pixel.y / self.cell.rows as f32,
        )
    }

    /// The centre of cell `(col, row)` in pixel coordinates.
    pub fn pixel_of_cell_center(&self, col: u16, row: u16) -> Vec2 {
        self.pixel_from_cell(Vec2::new(f32::from(col) + 0.5, f32::from(row) + 0.5))
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
    fn every_cell_shape_shows_the_same_picture_aspect() {
        // 120 × 40 cells twice as tall as wide: 120 / 80 across / down, whatever the cell's pixels.
        for (cols, rows) in [(1, 2), (2, 2), (2, 3), (2, 4)] {
            let v = Viewport::of_cells(120, 40, CellPixels { cols, rows }, 2.0);
            assert_eq!((v.width, v.height), (120 * cols, 40 * rows));
            assert!(
                (v.aspect() - 1.5).abs() < 1e-6,
                "{cols}x{rows}: {}",
                v.aspect()
            );
        }
    }

    #[test]
    fn a_cell_centre_is_the_middle_of_its_pixels() {
        let v = Viewport::of_cells(10, 10, CellPixels { cols: 2, rows: 3 }, 2.0);
        assert_eq!(v.pixel_of_cell_center(4, 1), Vec2::new(9.0, 4.5));
        assert_eq!(v.cell_from_pixel(Vec2::new(9.0, 4.5)), Vec2::new(4.5, 1.5));
        let half = Viewport::new(10, 20, 1.0);
        assert_eq!(half.pixel_of_cell_center(3, 2), Vec2::new(3.5, 5.0));
    }

    #[test]
    fn tall_pixels_narrow_the_aspect() {
        assert_eq!(Viewport::new(100, 50, 1.0).aspect(), 2.0);
        assert_eq!(Viewport::new(100, 50, 2.0).aspect(), 1.0);
    }
}
