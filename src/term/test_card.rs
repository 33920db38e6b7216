//! `nudge cells`: a test card showing every cell mode's glyphs beside its name, and a shaded ball
//! drawn in that mode, so one glance tells which modes a terminal and its font draw.
//!
//! A set the terminal lacks shows as boxes, question marks or blanks, and its ball comes out ragged
//! or misaligned (a glyph drawn two cells wide shifts the rest of its row). The ball is drawn by the
//! same widget as the sandbox ([`CellView`]), so what the card shows is what `--cells` will.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::widgets::Widget;

use super::cells::{CellMode, CellView};
use super::color_depth::ColorDepth;
use super::dither::Dither;
use super::glyphs::glyph;
use crate::color::Rgb;

/// Columns of the name column.
const LABEL: u16 = 12;
/// Glyphs per row of a set.
const GLYPHS_PER_ROW: u16 = 32;
/// Size of each mode's ball, cells.
const BALL: (u16, u16) = (16, 5);
/// Rows of the heading above the sets.
const HEADING: u16 = 2;

/// How the glyphs are painted: light on dark, so each one's shape reads.
const GLYPH_STYLE: Style = Style::new()
    .fg(Color::Rgb(0xf0, 0xe0, 0xa0))
    .bg(Color::Rgb(0x20, 0x30, 0x60));

/// What a mode's label says under its name: the cell's pixels and where its glyphs come from.
fn origin(mode: CellMode) -> &'static str {
    match mode {
        CellMode::Half => "1x2 blocks",
        CellMode::Quadrant => "2x2 blocks",
        CellMode::Sextant => "2x3 Uni 13",
        CellMode::Octant => "2x4 Uni 16",
    }
}

/// Rows the section of `mode` takes.
fn section_rows(mode: CellMode) -> u16 {
    let (w, h) = mode.pixels_per_cell();
    let glyphs = 1u16 << (w * h);
    glyphs.div_ceil(GLYPHS_PER_ROW).max(BALL.1)
}

/// The card's size in cells.
pub fn size() -> (u16, u16) {
    let rows = CellMode::ALL
        .iter()
        .map(|&m| section_rows(m) + 1)
        .sum::<u16>();
    (LABEL + GLYPHS_PER_ROW + 2 + BALL.0, HEADING + rows + 1)
}

/// The card at `depth`, in a buffer of [`size`].
pub fn test_card(depth: ColorDepth) -> Buffer {
    let (cols, rows) = size();
    let mut buf = Buffer::empty(Rect::new(0, 0, cols, rows));
    buf.set_string(
        0,
        0,
        "nudge cells: each mode's glyphs and a ball drawn with them.",
        Style::new(),
    );
    let mut y = HEADING;
    for mode in CellMode::ALL {
        buf.set_string(0, y, mode.name(), Style::new());
        buf.set_string(0, y + 1, origin(mode), Style::new());
        let (w, h) = mode.pixels_per_cell();
        for pattern in 0..(1u16 << (w * h)) {
            let (col, row) = (pattern % GLYPHS_PER_ROW, pattern / GLYPHS_PER_ROW);
            buf[(LABEL + col, y + row)]
                .set_char(glyph(mode, pattern as u8))
                .set_style(GLYPH_STYLE);
        }
        let ball = ball(mode);
        let (width, height) = mode.pixel_size_for(BALL.0, BALL.1);
        CellView {
            pixels: &ball,
            width,
            height,
            mode,
            depth,
            dither: Dither::default(),
        }
        .render(
            Rect::new(LABEL + GLYPHS_PER_ROW + 2, y, BALL.0, BALL.1),
            &mut buf,
        );
        y += section_rows(mode) + 1;
    }
    buf.set_string(
        0,
        y,
        "Boxes, '?' or a ragged ball: that set is missing.",
        Style::new(),
    );
    buf
}

/// A lit ball on a dark ground, filling [`BALL`] cells of `mode` (cells twice as tall as wide).
fn ball(mode: CellMode) -> Vec<Rgb> {
    let (width, height) = mode.pixel_size_for(BALL.0, BALL.1);
    let (w, h) = mode.pixels_per_cell();
    // Screen units: a cell is 1 wide and 2 tall.
    let (unit_x, unit_y) = (1.0 / w as f32, 2.0 / h as f32);
    let centre = (f32::from(BALL.0) / 2.0, f32::from(BALL.1));
    let radius = f32::from(BALL.1) * 0.9;
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let dx = ((x as f32 + 0.5) * unit_x - centre.0) / radius;
            let dy = ((y as f32 + 0.5) * unit_y - centre.1) / radius;
            let r2 = dx * dx + dy * dy;
            pixels.push(if r2 > 1.0 {
                Rgb::new(0x18, 0x1c, 0x28)
            } else {
                // Lit from the upper left.
                let dz = (1.0 - r2).sqrt();
                let light = (0.2 + 0.8 * (-0.5 * dx - 0.5 * dy + 0.7 * dz).max(0.0)).min(1.0);
                Rgb::from_unit([0.85 * light, 0.3 * light, 0.2 * light])
            });
        }
    }
    pixels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::term::glyphs::pattern_of;

    #[test]
    fn the_card_shows_every_glyph_of_every_set_once_beside_its_name() {
        let buf = test_card(ColorDepth::TrueColor);
        let text: Vec<String> = (0..buf.area.height)
            .map(|y| {
                (0..buf.area.width)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect()
            })
            .collect();
        let mut y = usize::from(HEADING);
        for mode in CellMode::ALL {
            assert!(text[y].starts_with(mode.name()), "{}", text[y]);
            let (w, h) = mode.pixels_per_cell();
            let glyphs: String = (0..section_rows(mode))
                .map(|row| {
                    (0..GLYPHS_PER_ROW)
                        .map(|col| buf[(LABEL + col, y as u16 + row)].symbol().to_string())
                        .collect::<String>()
                })
                .collect();
            let patterns: Vec<Option<u8>> = glyphs
                .chars()
                .take(1 << (w * h))
                .map(|c| pattern_of(mode, &c.to_string()))
                .collect();
            let expected: Vec<Option<u8>> = (0..1u16 << (w * h)).map(|p| Some(p as u8)).collect();
            assert_eq!(patterns, expected, "{mode}");
            // The ball uses the set's glyphs beyond blanks and half blocks.
            let ball: Vec<&str> = (0..BALL.1)
                .flat_map(|row| {
                    (0..BALL.0).map(move |col| (LABEL + GLYPHS_PER_ROW + 2 + col, y as u16 + row))
                })
                .map(|at| buf[at].symbol())
                .collect();
            assert!(ball.iter().all(|s| pattern_of(mode, s).is_some()), "{mode}");
            if mode != CellMode::Half {
                assert!(
                    ball.iter().any(|s| !matches!(*s, " " | "▀" | "▄" | "█")),
                    "{mode}: {ball:?}"
                );
            }
            y += usize::from(section_rows(mode)) + 1;
        }
    }
}
