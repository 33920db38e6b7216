//! The mosaic view: a pure ratatui widget showing a pixel buffer at 2×2, 2×3 or 2×4 pixels a cell
//! (quadrant, sextant and octant glyphs), two colours a cell.
//!
//! Cell (c, r) of the area shows pixels `[c·w, c·w + w) × [r·h, r·h + h)` for the mode's `(w, h)`.
//! Per cell:
//!
//! 1. all pixels the same colour: a blank cell in that colour (the cheap case: background, flat faces);
//! 2. otherwise the [fit](super::fit): the split of the pixels into two groups and their colours,
//!    in OKLab, drawn as the glyph of the split ([`glyphs`](super::glyphs)) with the top-left pixel's
//!    group as foreground;
//! 3. the two colours become terminal colours; if they are one, the cell is blank in it.
//!
//! At 256 and 16 colours each pixel is first quantised and [dithered](super::dither) at its own
//! position, exactly as half blocks are, and the fit splits the resulting palette colours: a cell of
//! one or two entries (a flat area's dither pattern, an edge) shows them exactly, at the finer pixels.
//! A cell of three or more is fitted and its group colours quantised by the cell's position.
//! Truecolor is never dithered.
//!
//! Pixels a cell lacks at the image's right or bottom edge repeat the nearest pixel of the cell;
//! cells wholly outside the image are reset. Every cell touched is fully overwritten, as
//! [`HalfBlocks`](super::HalfBlocks) does.

use ratatui::buffer::{Buffer, Cell};
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

use super::cells::CellMode;
use super::color_depth::ColorDepth;
use super::dither::{Dither, with_quantizer};
use super::fidelity::shown_rgb;
use super::fit::{FitMethod, MAX_PIXELS, fit};
use super::glyphs::glyph;
use crate::color::Rgb;
use crate::color::oklab::to_oklab;

/// Draws `pixels` (row-major, y down, `width × height`) in mosaic cells; see the module docs.
#[derive(Clone, Copy, Debug)]
pub struct Mosaic<'a> {
    /// Row-major pixels, y down: pixel (x, y) is `pixels[y * width + x]`. If shorter than
    /// `width × height`, the missing rows are outside the image.
    pub pixels: &'a [Rgb],
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// The glyph set and pixels a cell; [`CellMode::Half`] is drawn as half blocks by the same fit.
    pub mode: CellMode,
    /// Palette the colours are quantised to.
    pub depth: ColorDepth,
    /// How colours the palette lacks are shown (ignored in truecolor).
    pub dither: Dither,
    /// How the split is searched.
    pub method: FitMethod,
}

impl<'a> Mosaic<'a> {
    /// A widget over `pixels`, dithered the default way and fitted by [`FitMethod::for_mode`].
    pub fn new(
        pixels: &'a [Rgb],
        width: u32,
        height: u32,
        mode: CellMode,
        depth: ColorDepth,
    ) -> Self {
        Self {
            pixels,
            width,
            height,
            mode,
            depth,
            dither: Dither::default(),
            method: FitMethod::for_mode(mode),
        }
    }

    /// The same widget with `dither`.
    pub fn with_dither(self, dither: Dither) -> Self {
        Self { dither, ..self }
    }

    /// The same widget with `method`.
    pub fn with_method(self, method: FitMethod) -> Self {
        Self { method, ..self }
    }

    /// The image's rows actually present (a short `pixels` cuts it).
    fn rows_present(&self) -> u32 {
        if self.width == 0 {
            return 0;
        }
        let full_rows = self.pixels.len() / self.width as usize;
        self.height
            .min(u32::try_from(full_rows).unwrap_or(u32::MAX))
    }
}

impl Widget for Mosaic<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        (&self).render(area, buf);
    }
}

impl Widget for &Mosaic<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let area = area.intersection(buf.area);
        if area.is_empty() {
            return;
        }
        let (cell_w, cell_h) = self.mode.pixels_per_cell();
        let n = (cell_w * cell_h) as usize;
        let (width, height) = (self.width, self.rows_present());
        let stride = self.width as usize;
        let mut rgb = [Rgb::BLACK; MAX_PIXELS];
        let mut shown = [Color::Reset; MAX_PIXELS];
        let palette = self.depth != ColorDepth::TrueColor;
        // Neighbouring pixels often share a colour: one OKLab conversion for a run of them.
        let mut last: Option<(Rgb, [f32; 3])> = None;
        with_quantizer(self.depth, self.dither, |quantizer| {
            for row in 0..area.height {
                let start = buf.index_of(area.x, area.y + row);
                let cells = &mut buf.content[start..start + usize::from(area.width)];
                let y0 = u32::from(row) * cell_h;
                for (col, cell) in (0u32..).zip(cells.iter_mut()) {
                    let x0 = col * cell_w;
                    if x0 >= width || y0 >= height {
                        cell.reset();
                        continue;
                    }
                    // At 256 and 16 colours each pixel is quantised (and dithered) where it is,
                    // as half blocks do; the fit then splits the palette colours, so a dithered
                    // flat area keeps its pattern at the finer pixels.
                    let mut i = 0;
                    for dy in 0..cell_h {
                        let y = (y0 + dy).min(height - 1);
                        for dx in 0..cell_w {
                            let x = (x0 + dx).min(width - 1);
                            let c = self.pixels[y as usize * stride + x as usize];
                            if palette {
                                shown[i] = quantizer.color(x, y, c);
                                rgb[i] = shown_rgb(shown[i]);
                            } else {
                                rgb[i] = c;
                            }
                            i += 1;
                        }
                    }
                    let rgb = &rgb[..n];
                    // The terminal colour of a group's colour: a pixel's own when it has it (a
                    // palette entry stays the entry), else quantised at the cell's position.
                    let mut colour = |c: Rgb| match rgb.iter().position(|&p| p == c) {
                        Some(i) if palette => shown[i],
                        _ => quantizer.color(col, u32::from(row), c),
                    };
                    if rgb.iter().all(|&c| c == rgb[0]) {
                        *cell = BLANK;
                        cell.bg = colour(rgb[0]);
                        continue;
                    }
                    let f = fit(rgb, self.method, &mut |c| match last {
                        Some((seen, p)) if seen == c => p,
                        _ => {
                            let o = to_oklab(c);
                            let p = [o.l, o.a, o.b];
                            last = Some((c, p));
                            p
                        }
                    });
                    let bg = colour(f.bg);
                    let fg = colour(f.fg);
                    if f.pattern == 0 || fg == bg {
                        *cell = BLANK;
                        cell.bg = bg;
                    } else {
                        *cell = BLANK;
                        cell.set_char(glyph(self.mode, f.pattern));
                        cell.fg = fg;
                        cell.bg = bg;
                    }
                }
            }
        });
    }
}

/// A blank cell: no colours, no modifiers.
const BLANK: Cell = Cell::new(" ");

#[cfg(test)]
mod tests {
    use super::*;
    use crate::term::glyphs::pattern_of;
    use ratatui::style::Color;

    #[test]
    fn a_short_pixel_slice_draws_what_it_has_and_never_panics() {
        let px = [Rgb::WHITE; 5];
        let mut buf = Buffer::empty(Rect::new(0, 0, 3, 3));
        Mosaic::new(&px, 4, 8, CellMode::Octant, ColorDepth::TrueColor).render(buf.area, &mut buf);
        // One full row of 4 pixels: the first two cells of the first row, the rest reset.
        assert_eq!(buf[(0, 0)].bg, Color::Rgb(255, 255, 255));
        assert_eq!(buf[(1, 0)].bg, Color::Rgb(255, 255, 255));
        assert_eq!(buf[(2, 0)], Cell::default());
        assert_eq!(buf[(0, 1)], Cell::default());
    }

    #[test]
    fn an_odd_edge_repeats_the_cells_last_pixels() {
        // 3 × 2 pixels in quadrant cells: the second cell has one column, repeated.
        let (k, w) = (Rgb::BLACK, Rgb::WHITE);
        let px = [k, w, k, k, w, w];
        let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
        Mosaic::new(&px, 3, 2, CellMode::Quadrant, ColorDepth::TrueColor)
            .render(buf.area, &mut buf);
        // Cell 0: K W / K W: the left half in front. Cell 1: K K / W W.
        assert_eq!(
            pattern_of(CellMode::Quadrant, buf[(0, 0)].symbol()),
            Some(0b0101)
        );
        assert_eq!(
            pattern_of(CellMode::Quadrant, buf[(1, 0)].symbol()),
            Some(0b0011)
        );
    }
}
