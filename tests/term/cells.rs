//! The cell modes, headless: pixel images in, ratatui buffers out, and every cell decoded back through
//! its glyph's pattern (`term::glyphs::pattern_of`) to the pixels it shows, then checked against the
//! pixels it was given.

use nudge::app::snapshot::{SnapshotOptions, render_buffer};
use nudge::color::Rgb;
use nudge::color::oklab::to_oklab;
use nudge::render::RenderMode;
use nudge::scene;
use nudge::term::fidelity::shown_rgb;
use nudge::term::glyphs::pattern_of;
use nudge::term::quantize::ANSI16_COLORS;
use nudge::term::{CellMode, CellView, ColorDepth, Dither};
use nudge::util::SplitMix64;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

const K: Rgb = Rgb::BLACK;
const W: Rgb = Rgb::WHITE;
const R: Rgb = Rgb::new(200, 40, 30);
const B: Rgb = Rgb::new(40, 90, 210);

/// The modes with more than two pixels a cell.
const MOSAICS: [CellMode; 3] = [CellMode::Quadrant, CellMode::Sextant, CellMode::Octant];

/// Draws a `cols × rows`-cell picture whose pixel (x, y) is `pixel(x, y)`; returns the pixels too.
fn draw(
    mode: CellMode,
    cols: u16,
    rows: u16,
    depth: ColorDepth,
    pixel: impl Fn(u32, u32) -> Rgb,
) -> (Buffer, Vec<Rgb>) {
    let (w, h) = mode.pixel_size_for(cols, rows);
    let pixels: Vec<Rgb> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| pixel(x, y))
        .collect();
    let mut buf = Buffer::empty(Rect::new(0, 0, cols, rows));
    CellView {
        pixels: &pixels,
        width: w,
        height: h,
        mode,
        depth,
        dither: Dither::Ordered,
    }
    .render(buf.area, &mut buf);
    (buf, pixels)
}

/// What cell (col, row) shows at each of its pixels, row-major: its glyph decoded to a pattern, the
/// foreground where the pattern is set and the background elsewhere.
fn shown(buf: &Buffer, mode: CellMode, col: u16, row: u16) -> Vec<Rgb> {
    let cell = &buf[(col, row)];
    let pattern = pattern_of(mode, cell.symbol())
        .unwrap_or_else(|| panic!("{mode}: {:?} is not one of its glyphs", cell.symbol()));
    let (w, h) = mode.pixels_per_cell();
    (0..w * h)
        .map(|i| {
            if pattern & (1 << i) != 0 {
                shown_rgb(cell.fg)
            } else {
                shown_rgb(cell.bg)
            }
        })
        .collect()
}

/// The pixels of cell (col, row), row-major.
fn cell_pixels(pixels: &[Rgb], mode: CellMode, cols: u16, col: u16, row: u16) -> Vec<Rgb> {
    let (w, h) = mode.pixels_per_cell();
    let stride = u32::from(cols) * w;
    (0..h)
        .flat_map(|dy| (0..w).map(move |dx| (dx, dy)))
        .map(|(dx, dy)| {
            let (x, y) = (u32::from(col) * w + dx, u32::from(row) * h + dy);
            pixels[(y * stride + x) as usize]
        })
        .collect()
}

#[test]
fn a_cell_of_one_colour_is_a_space_or_a_full_block_in_that_colour() {
    for mode in CellMode::ALL {
        // Colour regions aligned to cells: each cell is one colour.
        let (w, h) = mode.pixels_per_cell();
        let colours = [K, W, R, B];
        let (buf, _) = draw(mode, 6, 3, ColorDepth::TrueColor, |x, y| {
            colours[((x / w + y / h) % 4) as usize]
        });
        for row in 0..3u16 {
            for col in 0..6u16 {
                let cell = &buf[(col, row)];
                let expected = colours[usize::from((col + row) % 4)];
                assert!(
                    matches!(cell.symbol(), " " | "█"),
                    "{mode} ({col}, {row}): {:?}",
                    cell.symbol()
                );
                assert!(
                    shown(&buf, mode, col, row).iter().all(|&c| c == expected),
                    "{mode} ({col}, {row})"
                );
            }
        }
    }
}

#[test]
fn a_vertical_edge_through_a_cell_becomes_a_left_right_split() {
    for mode in MOSAICS {
        // Black left of x = 1 in every cell, white right of it: the edge runs down each cell's middle.
        let (w, _) = mode.pixels_per_cell();
        let (buf, _) = draw(mode, 4, 2, ColorDepth::TrueColor, |x, _| {
            if x % w == 0 { K } else { W }
        });
        for row in 0..2u16 {
            for col in 0..4u16 {
                let symbol = buf[(col, row)].symbol();
                assert!(matches!(symbol, "▌" | "▐"), "{mode}: {symbol:?}");
                let shown = shown(&buf, mode, col, row);
                for (i, c) in shown.iter().enumerate() {
                    let left = i as u32 % w == 0;
                    assert_eq!(*c, if left { K } else { W }, "{mode} pixel {i}");
                }
            }
        }
    }
}

#[test]
fn a_horizontal_edge_at_a_cells_middle_becomes_a_top_bottom_split() {
    for mode in [CellMode::Half, CellMode::Quadrant, CellMode::Octant] {
        let (_, h) = mode.pixels_per_cell();
        let (buf, _) = draw(mode, 3, 2, ColorDepth::TrueColor, |_, y| {
            if y % h < h / 2 { R } else { B }
        });
        for row in 0..2u16 {
            for col in 0..3u16 {
                let symbol = buf[(col, row)].symbol();
                assert!(matches!(symbol, "▀" | "▄"), "{mode}: {symbol:?}");
            }
        }
    }
    // A sextant cell's rows are thirds: an edge after its first row is the top third.
    let (buf, _) = draw(CellMode::Sextant, 2, 1, ColorDepth::TrueColor, |_, y| {
        if y == 0 { R } else { B }
    });
    assert_eq!(buf[(0, 0)].symbol(), "\u{1FB02}"); // BLOCK SEXTANT-12
    assert_eq!(buf[(0, 0)].fg, Color::Rgb(R.r, R.g, R.b));
}

#[test]
fn every_two_colour_cell_decodes_back_to_its_pixels_exactly() {
    // Random two-colour patterns: each glyph must show exactly the pixels it was fitted to.
    let mut rng = SplitMix64(29);
    for mode in CellMode::ALL {
        let (cols, rows) = (40u16, 12u16);
        let (w, h) = mode.pixel_size_for(cols, rows);
        let (cw, ch) = mode.pixels_per_cell();
        let bits: Vec<bool> = (0..w * h).map(|_| rng.next_unit() < 0.5).collect();
        let (buf, pixels) = draw(mode, cols, rows, ColorDepth::TrueColor, |x, y| {
            // Two colours per cell, different from cell to cell.
            let tint = ((x / cw + y / ch) % 7) as u8 * 30;
            if bits[(y * w + x) as usize] {
                Rgb::new(tint, 200, 40)
            } else {
                Rgb::new(250, tint, 90)
            }
        });
        let mut patterns = std::collections::HashSet::new();
        for row in 0..rows {
            for col in 0..cols {
                assert_eq!(
                    shown(&buf, mode, col, row),
                    cell_pixels(&pixels, mode, cols, col, row),
                    "{mode} ({col}, {row}): {:?}",
                    buf[(col, row)].symbol()
                );
                patterns.insert(buf[(col, row)].symbol().to_string());
            }
        }
        // Nearly every glyph of the set was exercised (480 cells, 2^(n−1) patterns up to flips).
        let distinct = 1usize << (cw * ch - 1);
        assert!(
            patterns.len() * 10 >= distinct.min(480) * 9,
            "{mode}: only {} glyphs of {distinct}",
            patterns.len()
        );
    }
}

#[test]
fn a_rendered_scene_shows_each_pixel_in_the_nearer_of_its_cells_two_colours() {
    for mode in MOSAICS {
        let options = SnapshotOptions {
            cols: 80,
            rows: 24,
            mode: RenderMode::Textured,
            orthographic: None,
            color_depth: ColorDepth::TrueColor,
            dither: Dither::None,
            plain: false,
            steps: 0,
            cell_aspect: 2.0,
            overlays: Default::default(),
            cells: mode,
        };
        let (app, buf) = render_buffer(scene::load("default").unwrap(), &options);
        let frame = app.frame();
        assert_eq!(
            (frame.width(), frame.height()),
            mode.pixel_size_for(80, 24),
            "{mode}: rendered at the mode's resolution"
        );
        let mut split_cells = 0;
        for row in 0..24u16 {
            for col in 0..80u16 {
                let cell = &buf[(col, row)];
                let given = cell_pixels(frame.pixels(), mode, 80, col, row);
                let shown = shown(&buf, mode, col, row);
                let (fg, bg) = (shown_rgb(cell.fg), shown_rgb(cell.bg));
                if matches!(cell.symbol(), " " | "█") {
                    continue;
                }
                split_cells += 1;
                for (p, s) in given.iter().zip(&shown) {
                    let other = if *s == fg { bg } else { fg };
                    let (own, alt) = (to_oklab(*p), to_oklab(*s));
                    // The fitted colours are rounded to 8 bits: a pixel almost equally near both may
                    // go either way by that rounding (1/255 moves OKLab by under 0.004).
                    assert!(
                        own.distance(alt) <= own.distance(to_oklab(other)) + 0.004,
                        "{mode} ({col}, {row}): {p:?} shown {s:?}, nearer {other:?}"
                    );
                }
            }
        }
        assert!(
            split_cells > 80 * 24 / 10,
            "{mode}: only {split_cells} cells use a glyph"
        );
    }
}

#[test]
fn at_256_and_16_colours_every_cell_is_a_glyph_of_its_set_in_palette_colours() {
    for (depth, in_palette) in [
        (
            ColorDepth::Ansi256,
            (|c| matches!(c, Color::Indexed(16..=255))) as fn(Color) -> bool,
        ),
        (ColorDepth::Ansi16, |c| ANSI16_COLORS.contains(&c)),
    ] {
        for mode in MOSAICS {
            let options = SnapshotOptions {
                cols: 60,
                rows: 20,
                mode: RenderMode::Textured,
                orthographic: None,
                color_depth: depth,
                dither: Dither::Ordered,
                plain: false,
                steps: 0,
                cell_aspect: 2.0,
                overlays: Default::default(),
                cells: mode,
            };
            let (_, buf) = render_buffer(scene::load("default").unwrap(), &options);
            let mut glyphs = 0;
            for cell in buf.content() {
                assert!(
                    pattern_of(mode, cell.symbol()).is_some(),
                    "{mode} {depth:?}"
                );
                assert!(in_palette(cell.bg), "{mode} {depth:?}: {:?}", cell.bg);
                if cell.symbol() != " " {
                    glyphs += 1;
                    assert!(in_palette(cell.fg), "{mode} {depth:?}: {:?}", cell.fg);
                    assert_ne!(cell.fg, cell.bg, "{mode} {depth:?}: a glyph of one colour");
                }
            }
            assert!(glyphs > 60 * 20 / 10, "{mode} {depth:?}: {glyphs} glyphs");
        }
    }
}

#[test]
fn at_256_colours_a_dithered_flat_area_keeps_its_pattern_at_the_finer_pixels() {
    // The default scene's shaded orange: dithered at 256 colours (term::dither's own test).
    let c = Rgb::new(0x60, 0x40, 0x20);
    for mode in CellMode::ALL {
        let (cols, rows) = (6u16, 3u16);
        let (buf, _) = draw(mode, cols, rows, ColorDepth::Ansi256, |_, _| c);
        let (w, h) = mode.pixels_per_cell();
        let mut entries = std::collections::HashSet::new();
        nudge::term::dither::with_quantizer(ColorDepth::Ansi256, Dither::Ordered, |q| {
            for row in 0..rows {
                for col in 0..cols {
                    // Each pixel shows what half blocks would show at that pixel.
                    let expected: Vec<Rgb> = (0..h)
                        .flat_map(|dy| (0..w).map(move |dx| (dx, dy)))
                        .map(|(dx, dy)| {
                            let (x, y) = (u32::from(col) * w + dx, u32::from(row) * h + dy);
                            shown_rgb(q.color(x, y, c))
                        })
                        .collect();
                    assert_eq!(
                        shown(&buf, mode, col, row),
                        expected,
                        "{mode} ({col}, {row})"
                    );
                    entries.extend(expected);
                }
            }
        });
        assert!(entries.len() > 1, "{mode}: the colour is dithered");
    }
}
