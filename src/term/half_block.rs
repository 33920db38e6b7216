//! The half-block view: a pure ratatui widget showing a pixel buffer at two pixels per cell.
//!
//! Cell (c, r) of the area (relative to its top-left corner) shows pixel (c, 2r) in its upper half
//! and pixel (c, 2r + 1) in its lower half. A cell is in exactly one of four states:
//!
//! | pixels present             | symbol | fg                | bg                   |
//! |----------------------------|--------|-------------------|----------------------|
//! | top and bottom, different  | `▀`    | top colour        | bottom colour        |
//! | top and bottom, same (*)   | ` `    | `Reset`           | the shared colour    |
//! | top only (odd height)      | `▀`    | top colour        | `Reset` (terminal's) |
//! | none (outside the image)   | reset cell: ` `, `Reset`, `Reset`                  |
//!
//! (*) "same" is decided after quantising (and dithering) to the [`ColorDepth`], so a 256-colour
//! terminal gets the cheaper blank cell whenever both halves land on one palette entry. A blank cell needs no
//! multi-byte symbol and no foreground colour; its fg is `Reset` (not the colour) so the cell depends
//! only on its own two pixels and stays equal across frames when they do, which keeps ratatui's diff
//! small.
//!
//! At 256 and 16 colours, pixels are [dithered](super::dither) by default: pixel (x, y) of the image
//! (not of the screen) shows its colour's 2×2 pattern at (x mod 2, y mod 2), so the cells depend only
//! on the image. Truecolor is never dithered.
//!
//! Every cell the widget touches is fully overwritten (modifiers cleared), so it can be drawn over
//! anything. Pixels beyond the area are clipped; the image is anchored at the area's top-left.

use ratatui::buffer::{Buffer, Cell};
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::color_depth::ColorDepth;
use super::dither::{Dither, with_quantizer};
use crate::color::Rgb;

/// Draws `pixels` (row-major, y down, `width × height`) as half-block cells; see the module docs.
///
/// If `pixels` is shorter than `width × height` the missing pixels are treated as outside the
/// image (never a panic); extra pixels are ignored.
#[derive(Clone, Copy, Debug)]
pub struct HalfBlocks<'a> {
    /// Row-major pixels, y down: pixel (x, y) is `pixels[y * width + x]`.
    pub pixels: &'a [Rgb],
    /// Image width in pixels (= cells).
    pub width: u32,
    /// Image height in pixels (= 2 × cell rows, rounded up).
    pub height: u32,
    /// Palette the colours are quantised to.
    pub depth: ColorDepth,
    /// How colours the palette lacks are shown (ignored in truecolor).
    pub dither: Dither,
}

impl<'a> HalfBlocks<'a> {
    /// A widget over `pixels` (see the field docs), dithered the default way ([`Dither::Ordered`]).
    pub fn new(pixels: &'a [Rgb], width: u32, height: u32, depth: ColorDepth) -> Self {
        Self {
            pixels,
            width,
            height,
            depth,
            dither: Dither::default(),
        }
    }

    /// The same widget with `dither`.
    pub fn with_dither(self, dither: Dither) -> Self {
        Self { dither, ..self }
    }

    /// The cell size (columns, rows) that shows the whole image: `(width, ceil(height / 2))`,
    /// saturated to `u16`.
    pub fn cell_size(&self) -> (u16, u16) {
        let cols = u16::try_from(self.width).unwrap_or(u16::MAX);
        let rows = u16::try_from(self.height.div_ceil(2)).unwrap_or(u16::MAX);
        (cols, rows)
    }

    /// The pixel image size `(width, height)` that exactly fills `cols × rows` cells:
    /// `(cols, 2 · rows)`. Use it to size the render target for a widget area.
    pub fn pixel_size_for(cols: u16, rows: u16) -> (u32, u32) {
        (u32::from(cols), 2 * u32::from(rows))
    }

    /// Pixel (x, y), or `None` outside the image or past the end of `pixels`.
    #[inline]
    fn pixel(&self, x: u32, y: u32) -> Option<Rgb> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let index = (y as usize)
            .checked_mul(self.width as usize)?
            .checked_add(x as usize)?;
        self.pixels.get(index).copied()
    }
}

impl Widget for HalfBlocks<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        (&self).render(area, buf);
    }
}

impl Widget for &HalfBlocks<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        with_quantizer(self.depth, self.dither, |quantizer| {
            for row in 0..area.height {
                let start = buf.index_of(area.x, area.y + row);
                let cells = &mut buf.content[start..start + usize::from(area.width)];
                let y_top = 2 * u32::from(row);
                for (col, cell) in (0u32..).zip(cells.iter_mut()) {
                    let top = self.pixel(col, y_top);
                    let bottom = self.pixel(col, y_top + 1);
                    match (top, bottom) {
                        (Some(top), Some(bottom)) => {
                            let fg = quantizer.color(col, y_top, top);
                            let bg = quantizer.color(col, y_top + 1, bottom);
                            if fg == bg {
                                *cell = BLANK;
                                cell.bg = bg;
                            } else {
                                *cell = UPPER_HALF;
                                cell.fg = fg;
                                cell.bg = bg;
                            }
                        }
                        (Some(top), None) => {
                            *cell = UPPER_HALF;
                            cell.fg = quantizer.color(col, y_top, top);
                        }
                        // No top pixel means no bottom pixel either: same x, and the bottom's
                        // index and y are larger.
                        (None, _) => cell.reset(),
                    }
                }
            }
        });
    }
}

/// A blank cell: no colours, no modifiers (cheap to copy in: the symbol is stored inline, no
/// allocation, unlike building it with `set_char`).
const BLANK: Cell = Cell::new(" ");
/// An upper-half-block cell with no colours and no modifiers.
const UPPER_HALF: Cell = Cell::new("▀");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_size_rounds_odd_heights_up() {
        let px = [Rgb::BLACK; 15];
        assert_eq!(
            HalfBlocks::new(&px, 5, 3, ColorDepth::TrueColor).cell_size(),
            (5, 2)
        );
        assert_eq!(
            HalfBlocks::new(&[], 0, 0, ColorDepth::TrueColor).cell_size(),
            (0, 0)
        );
        assert_eq!(
            HalfBlocks::new(&[], u32::MAX, u32::MAX, ColorDepth::TrueColor).cell_size(),
            (u16::MAX, u16::MAX)
        );
    }

    #[test]
    fn pixel_size_for_an_area_round_trips_through_cell_size() {
        let (w, h) = HalfBlocks::pixel_size_for(80, 23);
        assert_eq!((w, h), (80, 46));
        let px = vec![Rgb::BLACK; (w * h) as usize];
        assert_eq!(
            HalfBlocks::new(&px, w, h, ColorDepth::Ansi16).cell_size(),
            (80, 23)
        );
    }

    #[test]
    fn pixel_lookup_rejects_coordinates_outside_and_short_slices() {
        let px = [Rgb::WHITE; 5];
        let hb = HalfBlocks::new(&px, 3, 2, ColorDepth::TrueColor);
        assert_eq!(hb.pixel(2, 0), Some(Rgb::WHITE));
        assert_eq!(hb.pixel(3, 0), None);
        assert_eq!(hb.pixel(1, 1), Some(Rgb::WHITE));
        assert_eq!(hb.pixel(2, 1), None); // index 5 is past the slice
        assert_eq!(hb.pixel(0, 2), None);
    }
}
