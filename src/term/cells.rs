//! Cell modes: how many pixels one terminal cell shows, and [`CellView`], the widget that draws a
//! pixel buffer in any of them.
//!
//! | mode       | pixels a cell | glyphs                              | drawn by                      |
//! |------------|---------------|-------------------------------------|-------------------------------|
//! | `half`     | 1 × 2         | `▀` (Block Elements)                | every terminal and font       |
//! | `quadrant` | 2 × 2         | `▘▝▖▗▚▞▛▜▙▟▌▐▀▄` (Block Elements)    | nearly all (xterm.js too)     |
//! | `sextant`  | 2 × 3         | U+1FB00–U+1FB3B (Unicode 13)        | kitty, WezTerm, foot, Ghostty, Windows Terminal, or a font with them |
//! | `octant`   | 2 × 4         | U+1CD00–U+1CDE5 and reused blocks (Unicode 16) | recent kitty, WezTerm, foot, Ghostty, or a font with them |
//!
//! The finer modes show two colours a cell, chosen per cell by [`fit`](super::fit); `half` needs
//! no fit (two pixels, two colours). `nudge cells` prints every set beside its name, so a user sees
//! which of them their terminal draws.

use std::fmt;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::color_depth::ColorDepth;
use super::dither::Dither;
use super::half_block::HalfBlocks;
use super::mosaic::Mosaic;
use crate::color::Rgb;

/// How a terminal cell shows pixels (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum CellMode {
    /// 1 × 2 pixels, `▀`: works everywhere.
    #[default]
    Half,
    /// 2 × 2 pixels, the quadrant blocks.
    Quadrant,
    /// 2 × 3 pixels, the sextants of Unicode 13.
    Sextant,
    /// 2 × 4 pixels, the octants of Unicode 16.
    Octant,
}

impl CellMode {
    /// Every mode, coarsest first.
    pub const ALL: [CellMode; 4] = [
        CellMode::Half,
        CellMode::Quadrant,
        CellMode::Sextant,
        CellMode::Octant,
    ];

    /// The command-line and status-bar spelling.
    pub const fn name(self) -> &'static str {
        match self {
            CellMode::Half => "half",
            CellMode::Quadrant => "quadrant",
            CellMode::Sextant => "sextant",
            CellMode::Octant => "octant",
        }
    }

    /// Pixels one cell shows, `(columns, rows)`; at most 8 in all.
    pub const fn pixels_per_cell(self) -> (u32, u32) {
        match self {
            CellMode::Half => (1, 2),
            CellMode::Quadrant => (2, 2),
            CellMode::Sextant => (2, 3),
            CellMode::Octant => (2, 4),
        }
    }

    /// The next finer mode, back to `half` after `octant` (the live key cycles through them).
    pub const fn next(self) -> CellMode {
        match self {
            CellMode::Half => CellMode::Quadrant,
            CellMode::Quadrant => CellMode::Sextant,
            CellMode::Sextant => CellMode::Octant,
            CellMode::Octant => CellMode::Half,
        }
    }

    /// The pixel image size `(width, height)` that exactly fills `cols × rows` cells.
    pub fn pixel_size_for(self, cols: u16, rows: u16) -> (u32, u32) {
        let (w, h) = self.pixels_per_cell();
        (u32::from(cols) * w, u32::from(rows) * h)
    }
}

impl fmt::Display for CellMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Draws `pixels` (row-major, y down, `width × height`) in cells of `mode`: [`HalfBlocks`] for
/// `half`, [`Mosaic`] for the others. The image is anchored at the area's top-left.
#[derive(Clone, Copy, Debug)]
pub struct CellView<'a> {
    /// Row-major pixels, y down: pixel (x, y) is `pixels[y * width + x]`.
    pub pixels: &'a [Rgb],
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// How many pixels a cell shows, and with which glyphs.
    pub mode: CellMode,
    /// Palette the colours are quantised to.
    pub depth: ColorDepth,
    /// How colours the palette lacks are shown (ignored in truecolor).
    pub dither: Dither,
}

impl Widget for CellView<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        match self.mode {
            CellMode::Half => HalfBlocks {
                pixels: self.pixels,
                width: self.width,
                height: self.height,
                depth: self.depth,
                dither: self.dither,
            }
            .render(area, buf),
            mode => Mosaic::new(self.pixels, self.width, self.height, mode, self.depth)
                .with_dither(self.dither)
                .render(area, buf),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn next_visits_every_mode_and_comes_back() {
        let mut mode = CellMode::Half;
        for expected in CellMode::ALL.iter().cycle().skip(1).take(4) {
            mode = mode.next();
            assert_eq!(mode, *expected);
        }
        assert_eq!(mode, CellMode::Half);
    }

    #[test]
    fn a_cell_holds_at_most_eight_pixels_and_half_is_the_default() {
        for mode in CellMode::ALL {
            let (w, h) = mode.pixels_per_cell();
            assert!(w * h <= super::super::fit::MAX_PIXELS as u32);
        }
        assert_eq!(CellMode::default(), CellMode::Half);
        assert_eq!(CellMode::Octant.pixel_size_for(120, 40), (240, 160));
    }
}
