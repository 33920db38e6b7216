//! How faithfully half-block cells show a picture: a frame of cells measured against the truecolor
//! frame of the same picture, as the eye sees both from a normal distance.
//!
//! Both are decoded back to pixels (a cell is two: `▀` shows fg over bg, a blank cell bg twice;
//! `Reset` counts as black), averaged over 2×2-pixel blocks in linear light (so a dither pattern
//! counts as the colour it blends to), and compared in OKLab:
//!
//! - `mean_de`, `p95_de`: the mean and 95th-percentile OKLab distance over blocks, ×100 (about 1 is a
//!   just-noticeable difference);
//! - `coloured_mean_de`: the mean over the coloured blocks alone (chroma ≥ [`COLOURED`] in the
//!   reference), the objects;
//! - `hue_lost`: the share of coloured blocks (chroma ≥ [`COLOURED`] in the reference) shown grey
//!   (chroma < [`GREY`]);
//! - `speckle`: how much a pattern shows up close: the mean OKLab distance of a pixel from its
//!   block's blend, ×100, in the frame minus in the reference (0 for a flat frame of a flat picture;
//!   textures and edges are in both, so what remains is what dithering added); `speckled`, the share
//!   of blocks where that addition exceeds [`SPECKLED`], where a pattern shows at all.
//!
//! `nudge bench render` reports these for every built-in scene at each depth; `tests/term/colour.rs`
//! holds the default scene and the pyramid to them.

use ratatui::buffer::Buffer;
use ratatui::style::Color;

use super::quantize::{ANSI16_COLORS, XTERM_ANSI16, ansi256_rgb};
use crate::color::Rgb;
use crate::color::oklab::{linear_to_oklab, to_linear};

/// OKLab chroma from which a reference block counts as coloured.
pub const COLOURED: f32 = 0.05;
/// OKLab chroma below which a shown block counts as grey.
pub const GREY: f32 = 0.02;

/// Added within-block spread (OKLab) from which a block counts as speckled.
pub const SPECKLED: f32 = 0.04;

/// The colour error of a frame against its reference (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Fidelity {
    /// Mean OKLab distance over 2×2 blocks, ×100.
    pub mean_de: f64,
    /// Mean OKLab distance over the coloured blocks alone, ×100: the objects, where the whole frame's
    /// mean is mostly flat background and floor.
    pub coloured_mean_de: f64,
    /// 95th-percentile OKLab distance over 2×2 blocks, ×100.
    pub p95_de: f64,
    /// Share (0 to 1) of coloured reference blocks shown grey; 0 when none is coloured.
    pub hue_lost: f64,
    /// Within-block variation added by the frame, OKLab ×100 (see the module docs).
    pub speckle: f64,
    /// Share (0 to 1) of blocks whose pixels sit more than [`SPECKLED`] further from their blend than
    /// the reference's do: where a pattern shows.
    pub speckled: f64,
    /// Reference blocks that are coloured.
    pub coloured_blocks: usize,
    /// Blocks compared.
    pub blocks: usize,
}

/// The sRGB value a terminal shows for a cell colour (xterm's defaults for 0..=15; `Reset` as black).
pub fn shown_rgb(color: Color) -> Rgb {
    match color {
        Color::Rgb(r, g, b) => Rgb::new(r, g, b),
        Color::Indexed(i) => ansi256_rgb(i),
        named => ANSI16_COLORS
            .iter()
            .position(|&c| c == named)
            .map_or(Rgb::BLACK, |i| XTERM_ANSI16[i]),
    }
}

/// The pixels a buffer of half-block cells shows: `(pixels, width, height)`, row-major, two pixel
/// rows per cell row.
pub fn cell_pixels(buf: &Buffer) -> (Vec<Rgb>, usize, usize) {
    let (width, rows) = (usize::from(buf.area.width), usize::from(buf.area.height));
    let mut pixels = vec![Rgb::BLACK; width * rows * 2];
    for r in 0..rows {
        for x in 0..width {
            let cell = &buf.content[r * width + x];
            let (fg, bg) = (shown_rgb(cell.fg), shown_rgb(cell.bg));
            let (top, bottom) = match cell.symbol() {
                "▀" => (fg, bg),
                "▄" => (bg, fg),
                "█" => (fg, fg),
                _ => (bg, bg),
            };
            pixels[2 * r * width + x] = top;
            pixels[(2 * r + 1) * width + x] = bottom;
        }
    }
    (pixels, width, rows * 2)
}

/// Mean linear-light colour of each whole 2×2 block, row-major, with the mean OKLab distance of its
/// four pixels from that blend.
fn blocks(pixels: &[Rgb], width: usize, height: usize) -> Vec<([f32; 3], f32)> {
    let mut out = Vec::with_capacity((width / 2) * (height / 2));
    for y in (0..height.saturating_sub(1)).step_by(2) {
        for x in (0..width.saturating_sub(1)).step_by(2) {
            let four =
                [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| pixels[(y + dy) * width + x + dx]);
            let mut sum = [0.0f32; 3];
            for p in four {
                for (s, v) in sum.iter_mut().zip(to_linear(p)) {
                    *s += v * 0.25;
                }
            }
            let blend = linear_to_oklab(sum);
            let spread = four
                .iter()
                .map(|&p| linear_to_oklab(to_linear(p)).distance(blend))
                .sum::<f32>()
                * 0.25;
            out.push((sum, spread));
        }
    }
    out
}

/// The colour error of `frame` against `reference` (see the module docs). Both buffers should have
/// the same size; only their common blocks are compared.
pub fn fidelity(reference: &Buffer, frame: &Buffer) -> Fidelity {
    let (ref_px, ref_w, ref_h) = cell_pixels(reference);
    let (frame_px, frame_w, frame_h) = cell_pixels(frame);
    let (width, height) = (ref_w.min(frame_w), ref_h.min(frame_h));
    let crop = |px: &[Rgb], w: usize| -> Vec<Rgb> {
        (0..height)
            .flat_map(|y| px[y * w..y * w + width].iter().copied())
            .collect()
    };
    let a = blocks(&crop(&ref_px, ref_w), width, height);
    let b = blocks(&crop(&frame_px, frame_w), width, height);
    let mut distances = Vec::with_capacity(a.len());
    let (mut coloured, mut lost) = (0usize, 0usize);
    let mut coloured_de = 0.0f64;
    let mut speckle = 0.0f64;
    let mut speckled = 0usize;
    for (&(p, p_spread), &(q, q_spread)) in a.iter().zip(&b) {
        speckle += f64::from(q_spread - p_spread) * 100.0;
        if q_spread - p_spread > SPECKLED {
            speckled += 1;
        }
        let (la, lb) = (linear_to_oklab(p), linear_to_oklab(q));
        let de = f64::from(la.distance(lb)) * 100.0;
        distances.push(de);
        if la.chroma() >= COLOURED {
            coloured += 1;
            coloured_de += de;
            if lb.chroma() < GREY {
                lost += 1;
            }
        }
    }
    if distances.is_empty() {
        return Fidelity::default();
    }
    distances.sort_by(f64::total_cmp);
    let n = distances.len();
    Fidelity {
        mean_de: distances.iter().sum::<f64>() / n as f64,
        coloured_mean_de: if coloured == 0 {
            0.0
        } else {
            coloured_de / coloured as f64
        },
        p95_de: distances[(n * 95 / 100).min(n - 1)],
        hue_lost: if coloured == 0 {
            0.0
        } else {
            lost as f64 / coloured as f64
        },
        speckle: speckle / n as f64,
        speckled: speckled as f64 / n as f64,
        coloured_blocks: coloured,
        blocks: n,
    }
}

/// OKLab distance under which a mark pixel is lost in what it covers: about xterm's red from its
/// bright red, a step of the 256-colour grey ramp from the next but three.
pub const MARK_CONTRAST: f32 = 0.12;

/// Hue turn, degrees, beyond which a coloured mark pixel counts as shown in another colour.
pub const MARK_HUE_TURN_DEG: f32 = 30.0;

/// How faithfully thin marks drawn over a picture (debug overlays, the grab tether) are shown. A
/// mark a pixel wide is seen pixel by pixel, not as a blend with its neighbours, so each mark pixel
/// is compared with the colour it was drawn in.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct MarkFidelity {
    /// Pixels the marks changed.
    pub pixels: usize,
    /// Mean OKLab distance of a mark pixel from its colour, ×100.
    pub mean_de: f64,
    /// Share (0 to 1) of coloured mark pixels (chroma ≥ [`COLOURED`]) shown grey (chroma < [`GREY`])
    /// or turned more than [`MARK_HUE_TURN_DEG`] in hue: a mark in another colour.
    pub off_colour: f64,
    /// Share (0 to 1) of mark pixels shown within [`MARK_CONTRAST`] of what the same depth shows
    /// there without the mark: a mark lost in what it is drawn over.
    pub hidden: f64,
}

/// Measures the marks of `marked` (pixels, `width` wide) that `plain` (the same picture without
/// them) lacks, as `shown` (half-block cells from (0, 0), one column a pixel) shows them, where
/// `shown_plain` shows `plain` at the same depth.
pub fn mark_fidelity(
    plain: &[Rgb],
    marked: &[Rgb],
    width: usize,
    shown: &Buffer,
    shown_plain: &Buffer,
) -> MarkFidelity {
    let (shown_px, shown_w, shown_h) = cell_pixels(shown);
    let (under_px, under_w, under_h) = cell_pixels(shown_plain);
    let (mut pixels, mut coloured, mut off, mut hidden) = (0usize, 0usize, 0usize, 0usize);
    let mut sum_de = 0.0f64;
    for (i, (&before, &mark)) in plain.iter().zip(marked).enumerate() {
        let (x, y) = (i % width.max(1), i / width.max(1));
        if before == mark || x >= shown_w.min(under_w) || y >= shown_h.min(under_h) {
            continue;
        }
        let (want, got, under) = (
            linear_to_oklab(to_linear(mark)),
            linear_to_oklab(to_linear(shown_px[y * shown_w + x])),
            linear_to_oklab(to_linear(under_px[y * under_w + x])),
        );
        pixels += 1;
        if got.distance(under) < MARK_CONTRAST {
            hidden += 1;
        }
        sum_de += f64::from(want.distance(got)) * 100.0;
        if want.chroma() >= COLOURED {
            coloured += 1;
            let turn = (want.b.atan2(want.a) - got.b.atan2(got.a))
                .to_degrees()
                .abs();
            let turn = turn.min(360.0 - turn);
            if got.chroma() < GREY || turn > MARK_HUE_TURN_DEG {
                off += 1;
            }
        }
    }
    MarkFidelity {
        pixels,
        mean_de: if pixels == 0 {
            0.0
        } else {
            sum_de / pixels as f64
        },
        off_colour: if coloured == 0 {
            0.0
        } else {
            off as f64 / coloured as f64
        },
        hidden: if pixels == 0 {
            0.0
        } else {
            hidden as f64 / pixels as f64
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ratatui::layout::Rect;

    fn cells(pairs: &[(&str, Color, Color)]) -> Buffer {
        let mut buf = Buffer::empty(Rect::new(0, 0, pairs.len() as u16, 1));
        for (x, &(symbol, fg, bg)) in pairs.iter().enumerate() {
            buf[(x as u16, 0)].set_symbol(symbol).set_fg(fg).set_bg(bg);
        }
        buf
    }

    #[test]
    fn a_frame_measured_against_itself_has_no_error() {
        let buf = cells(&[
            ("▀", Color::Rgb(200, 40, 40), Color::Rgb(40, 200, 40)),
            (" ", Color::Reset, Color::Rgb(40, 40, 200)),
        ]);
        let f = fidelity(&buf, &buf);
        assert_eq!((f.mean_de, f.hue_lost, f.blocks), (0.0, 0.0, 1));
        assert_eq!(f.coloured_blocks, 1);
    }

    #[test]
    fn a_checkerboard_of_black_and_white_is_seen_as_the_grey_it_blends_to() {
        // Half the light of white is sRGB 188.
        let grey = Color::Rgb(188, 188, 188);
        let reference = cells(&[(" ", Color::Reset, grey), (" ", Color::Reset, grey)]);
        let checker = cells(&[
            ("▀", Color::White, Color::Black),
            ("▀", Color::Black, Color::White),
        ]);
        let f = fidelity(&reference, &checker);
        assert!(f.mean_de < 0.5);
        // Black and white sit about 0.5 either side of their blend, in a flat reference.
        assert!(f.speckle > 40.0, "{f:?}");
        let flat_black = cells(&[(" ", Color::Reset, Color::Black); 2]);
        assert!(fidelity(&reference, &flat_black).mean_de > 50.0);
    }

    #[test]
    fn a_coloured_block_shown_grey_counts_as_hue_lost() {
        let orange = Color::Rgb(0xc0, 0x80, 0x40);
        let reference = cells(&[(" ", Color::Reset, orange); 2]);
        let grey = cells(&[(" ", Color::Reset, Color::Indexed(244)); 2]);
        let f = fidelity(&reference, &grey);
        assert_eq!((f.hue_lost, f.coloured_blocks), (1.0, 1));
        let cube = cells(&[(" ", Color::Reset, Color::Indexed(137)); 2]);
        assert_eq!(fidelity(&reference, &cube).hue_lost, 0.0);
    }

    #[test]
    fn cells_decode_to_the_colours_a_terminal_shows() {
        assert_eq!(shown_rgb(Color::Indexed(196)), Rgb::new(255, 0, 0));
        assert_eq!(shown_rgb(Color::Blue), Rgb::new(0, 0, 238));
        assert_eq!(shown_rgb(Color::Reset), Rgb::BLACK);
        let (px, w, h) = cell_pixels(&cells(&[("▀", Color::Red, Color::Green)]));
        assert_eq!((w, h), (1, 2));
        assert_eq!(px, vec![Rgb::new(205, 0, 0), Rgb::new(0, 205, 0)]);
    }

    #[test]
    fn the_error_on_coloured_blocks_leaves_the_grey_background_out() {
        let (orange, grey) = (Color::Rgb(0xc0, 0x80, 0x40), Color::Rgb(80, 80, 80));
        // Two blocks (two cells each): orange, then grey.
        let reference = cells(&[
            (" ", Color::Reset, orange),
            (" ", Color::Reset, orange),
            (" ", Color::Reset, grey),
            (" ", Color::Reset, grey),
        ]);
        // The grey block shown exactly, the orange one as a darker orange.
        let darker = Color::Rgb(0xa0, 0x60, 0x20);
        let frame = cells(&[
            (" ", Color::Reset, darker),
            (" ", Color::Reset, darker),
            (" ", Color::Reset, grey),
            (" ", Color::Reset, grey),
        ]);
        let f = fidelity(&reference, &frame);
        assert_eq!(f.coloured_blocks, 1);
        assert!((f.coloured_mean_de - 2.0 * f.mean_de).abs() < 1e-9, "{f:?}");
    }

    #[test]
    fn a_checkerboard_where_the_picture_is_flat_counts_as_speckled() {
        let grey = Color::Rgb(188, 188, 188);
        let reference = cells(&[(" ", Color::Reset, grey); 4]);
        let frame = cells(&[
            ("▀", Color::White, Color::Black),
            ("▀", Color::Black, Color::White),
            (" ", Color::Reset, grey),
            (" ", Color::Reset, grey),
        ]);
        assert_eq!(fidelity(&reference, &frame).speckled, 0.5);
    }

    #[test]
    fn a_mark_is_measured_pixel_by_pixel_against_the_colour_it_was_drawn_in() {
        let floor = Rgb::new(100, 100, 100);
        let (red, yellow) = (Rgb::new(255, 0, 0), Rgb::new(255, 255, 0));
        // Two pixels wide, two tall (one cell row): a red mark on the top-left pixel and a yellow
        // one on the top-right.
        let plain = vec![floor; 4];
        let marked = vec![red, yellow, floor, floor];
        let floor_c = Color::Rgb(100, 100, 100);
        let exact = cells(&[
            ("▀", Color::Indexed(196), floor_c),
            ("▀", Color::Indexed(226), floor_c),
        ]);
        let under = cells(&[(" ", Color::Reset, floor_c); 2]);
        let f = mark_fidelity(&plain, &marked, 2, &exact, &under);
        assert_eq!((f.pixels, f.off_colour, f.hidden), (2, 0.0, 0.0));
        assert!(f.mean_de < 1e-6, "{f:?}");
        // Red shown grey and yellow shown green: both in another colour.
        let wrong = cells(&[
            ("▀", Color::Indexed(244), floor_c),
            ("▀", Color::Indexed(46), floor_c),
        ]);
        assert_eq!(
            mark_fidelity(&plain, &marked, 2, &wrong, &under).off_colour,
            1.0
        );
        // The red mark drawn where the picture is shown red is lost in it, though in its colour.
        let red_under = cells(&[
            ("▀", Color::Indexed(160), floor_c),
            (" ", Color::Reset, floor_c),
        ]);
        assert_eq!(
            mark_fidelity(&plain, &marked, 2, &exact, &red_under).hidden,
            0.5
        );
    }
}
