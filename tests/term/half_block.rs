//! Pictures of the half-block widget: pixel images in, ratatui buffers out (exact comparisons).

use nudge::color::Rgb;
use nudge::term::dither::with_quantizer;
use nudge::term::{ColorDepth, Dither, HalfBlocks, quantize};
use ratatui::buffer::{Buffer, Cell};
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::widgets::Widget;

const R: Rgb = Rgb::new(255, 0, 0);
const G: Rgb = Rgb::new(0, 255, 0);
const B: Rgb = Rgb::new(0, 0, 255);
const W: Rgb = Rgb::WHITE;
const K: Rgb = Rgb::BLACK;

/// Pixels from a picture, one letter per pixel (R, G, B, W = white, K = black).
fn image(rows: &[&str]) -> (Vec<Rgb>, u32, u32) {
    let width = rows.first().map_or(0, |r| r.len()) as u32;
    let pixels = rows
        .iter()
        .flat_map(|row| {
            assert_eq!(row.len() as u32, width, "ragged picture");
            row.chars().map(|c| match c {
                'R' => R,
                'G' => G,
                'B' => B,
                'W' => W,
                'K' => K,
                other => panic!("unknown pixel letter {other}"),
            })
        })
        .collect();
    (pixels, width, rows.len() as u32)
}

fn tc(c: Rgb) -> Color {
    Color::Rgb(c.r, c.g, c.b)
}

fn render(pixels: &[Rgb], w: u32, h: u32, depth: ColorDepth, area: Rect, buf: &mut Buffer) {
    HalfBlocks::new(pixels, w, h, depth).render(area, buf);
}

/// Sets fg/bg of cell (x, y) in an expected buffer.
fn paint(buf: &mut Buffer, x: u16, y: u16, fg: Color, bg: Color) {
    buf[(x, y)].set_fg(fg).set_bg(bg);
}

#[test]
fn each_cell_shows_top_pixel_as_fg_and_bottom_pixel_as_bg() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RGB",
        "GBR",
        "WKR",
        "KWG",
    ]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 3, 2));
    render(&px, w, h, ColorDepth::TrueColor, buf.area, &mut buf);

    #[rustfmt::skip]
    let mut expected = Buffer::with_lines([
        "▀▀▀",
        "▀▀▀",
    ]);
    paint(&mut expected, 0, 0, tc(R), tc(G));
    paint(&mut expected, 1, 0, tc(G), tc(B));
    paint(&mut expected, 2, 0, tc(B), tc(R));
    paint(&mut expected, 0, 1, tc(W), tc(K));
    paint(&mut expected, 1, 1, tc(K), tc(W));
    paint(&mut expected, 2, 1, tc(R), tc(G));
    assert_eq!(buf, expected);
}

#[test]
fn equal_halves_become_a_blank_cell_with_only_a_background() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RRG",
        "RBG",
    ]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 3, 1));
    render(&px, w, h, ColorDepth::TrueColor, buf.area, &mut buf);

    let mut expected = Buffer::with_lines([" ▀ "]);
    paint(&mut expected, 0, 0, Color::Reset, tc(R));
    paint(&mut expected, 1, 0, tc(R), tc(B));
    paint(&mut expected, 2, 0, Color::Reset, tc(G));
    assert_eq!(buf, expected);
}

#[test]
fn halves_that_quantise_alike_become_blank_at_256_colours() {
    // Both are nearest to cube (5, 0, 0) = 196, so no half block is needed.
    let px = [Rgb::new(255, 0, 0), Rgb::new(250, 10, 5)];
    let mut buf = Buffer::empty(Rect::new(0, 0, 1, 1));
    render(&px, 1, 2, ColorDepth::Ansi256, buf.area, &mut buf);
    let mut expected = Buffer::with_lines([" "]);
    paint(&mut expected, 0, 0, Color::Reset, Color::Indexed(196));
    assert_eq!(buf, expected);

    // In truecolor they differ and need the half block.
    render(&px, 1, 2, ColorDepth::TrueColor, buf.area, &mut buf);
    assert_eq!(buf[(0, 0)].symbol(), "▀");
}

#[test]
fn sixteen_colour_cells_use_named_ansi_colours() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RK",
        "BK",
    ]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    render(&px, w, h, ColorDepth::Ansi16, buf.area, &mut buf);
    let mut expected = Buffer::with_lines(["▀ "]);
    // xterm blue is #0000ee, far nearer #0000ff than bright blue #5c5cff.
    paint(&mut expected, 0, 0, Color::LightRed, Color::Blue);
    paint(&mut expected, 1, 0, Color::Reset, Color::Black);
    assert_eq!(buf, expected);
}

#[test]
fn an_odd_height_leaves_the_last_bottom_half_to_the_terminal_background() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RG",
        "BB",
        "WK",
    ]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 2));
    render(&px, w, h, ColorDepth::TrueColor, buf.area, &mut buf);

    #[rustfmt::skip]
    let mut expected = Buffer::with_lines([
        "▀▀",
        "▀▀",
    ]);
    paint(&mut expected, 0, 0, tc(R), tc(B));
    paint(&mut expected, 1, 0, tc(G), tc(B));
    paint(&mut expected, 0, 1, tc(W), Color::Reset);
    paint(&mut expected, 1, 1, tc(K), Color::Reset);
    assert_eq!(buf, expected);
}

#[test]
fn cells_beyond_a_small_image_are_reset_even_over_old_content() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RG",
        "BW",
    ]);
    let junk = Style::new()
        .fg(Color::Yellow)
        .bg(Color::Magenta)
        .add_modifier(Modifier::BOLD);
    #[rustfmt::skip]
    let mut buf = Buffer::with_lines([
        "xxxx",
        "xxxx",
        "xxxx",
    ]);
    buf.set_style(buf.area, junk);
    render(&px, w, h, ColorDepth::TrueColor, buf.area, &mut buf);

    #[rustfmt::skip]
    let mut expected = Buffer::with_lines([
        "▀▀  ",
        "    ",
        "    ",
    ]);
    paint(&mut expected, 0, 0, tc(R), tc(B));
    paint(&mut expected, 1, 0, tc(G), tc(W));
    assert_eq!(buf, expected);
    assert!(buf.content.iter().all(|c| c.modifier.is_empty()));
}

#[test]
fn pixels_outside_the_area_are_clipped() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RGBW",
        "GBWR",
        "BWRG",
        "WRGB",
    ]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    render(&px, w, h, ColorDepth::TrueColor, buf.area, &mut buf);
    let mut expected = Buffer::with_lines(["▀▀"]);
    paint(&mut expected, 0, 0, tc(R), tc(G));
    paint(&mut expected, 1, 0, tc(G), tc(B));
    assert_eq!(buf, expected);
}

#[test]
fn the_image_is_anchored_at_the_area_and_cells_outside_it_are_untouched() {
    #[rustfmt::skip]
    let (px, w, h) = image(&[
        "RG",
        "BW",
    ]);
    #[rustfmt::skip]
    let mut buf = Buffer::with_lines([
        "abcd",
        "efgh",
        "ijkl",
    ]);
    render(
        &px,
        w,
        h,
        ColorDepth::TrueColor,
        Rect::new(1, 1, 3, 1),
        &mut buf,
    );
    #[rustfmt::skip]
    let mut expected = Buffer::with_lines([
        "abcd",
        "e▀▀ ",
        "ijkl",
    ]);
    paint(&mut expected, 1, 1, tc(R), tc(B));
    paint(&mut expected, 2, 1, tc(G), tc(W));
    assert_eq!(buf, expected);
}

#[test]
fn an_area_hanging_off_the_buffer_is_clipped_to_it() {
    let (px, w, h) = image(&["RG", "BW"]);
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    render(
        &px,
        w,
        h,
        ColorDepth::TrueColor,
        Rect::new(1, 0, 10, 10),
        &mut buf,
    );
    let mut expected = Buffer::with_lines([" ▀"]);
    paint(&mut expected, 1, 0, tc(R), tc(B));
    assert_eq!(buf, expected);

    // Entirely outside: nothing happens.
    let before = buf.clone();
    render(
        &px,
        w,
        h,
        ColorDepth::TrueColor,
        Rect::new(5, 5, 3, 3),
        &mut buf,
    );
    assert_eq!(buf, before);
}

#[test]
fn a_one_by_one_image_fills_the_top_half_of_one_cell() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 2));
    render(&[G], 1, 1, ColorDepth::TrueColor, buf.area, &mut buf);
    #[rustfmt::skip]
    let mut expected = Buffer::with_lines([
        "▀ ",
        "  ",
    ]);
    paint(&mut expected, 0, 0, tc(G), Color::Reset);
    assert_eq!(buf, expected);
}

#[test]
fn an_empty_image_resets_the_whole_area() {
    let mut buf = Buffer::with_lines(["ab", "cd"]);
    render(&[], 0, 0, ColorDepth::Ansi256, buf.area, &mut buf);
    assert_eq!(buf, Buffer::empty(buf.area));
}

#[test]
fn a_short_pixel_slice_shows_what_exists_and_resets_the_rest() {
    // Claims 2×2 but holds 3 pixels: pixel (1, 1) is missing, so cell 1 shows its top only.
    let px = [R, G, B];
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    render(&px, 2, 2, ColorDepth::TrueColor, buf.area, &mut buf);
    let mut expected = Buffer::with_lines(["▀▀"]);
    paint(&mut expected, 0, 0, tc(R), tc(B));
    paint(&mut expected, 1, 0, tc(G), Color::Reset);
    assert_eq!(buf, expected);
}

#[test]
fn no_size_combination_panics_and_coverage_matches_the_image() {
    for depth in ColorDepth::ALL {
        for w in 0..5u32 {
            for h in 0..6u32 {
                let px: Vec<Rgb> = (0..w * h)
                    .map(|i| Rgb::new((i * 37) as u8, (i * 91) as u8, (i * 13) as u8))
                    .collect();
                for aw in 0..5u16 {
                    for ah in 0..4u16 {
                        let mut buf = Buffer::filled(Rect::new(0, 0, 6, 5), Cell::new("x"));
                        let area = Rect::new(1, 1, aw, ah);
                        render(&px, w, h, depth, area, &mut buf);
                        for y in 0..5u16 {
                            for x in 0..6u16 {
                                let cell = &buf[(x, y)];
                                let inside = area.contains((x, y).into());
                                let (c, r) =
                                    (u32::from(x.wrapping_sub(1)), u32::from(y.wrapping_sub(1)));
                                if !inside {
                                    assert_eq!(cell.symbol(), "x");
                                } else if c < w && 2 * r < h {
                                    // Dithered by default: pixel (c, y) shows its colour's plan
                                    // entry for that position.
                                    let at = |y: u32| {
                                        with_quantizer(depth, Dither::Ordered, |q| {
                                            q.color(c, y, px[(y * w + c) as usize])
                                        })
                                    };
                                    if 2 * r + 1 < h {
                                        let (top, bottom) = (at(2 * r), at(2 * r + 1));
                                        if top == bottom {
                                            assert_eq!(
                                                (cell.symbol(), cell.fg),
                                                (" ", Color::Reset)
                                            );
                                        } else {
                                            assert_eq!((cell.symbol(), cell.fg), ("▀", top));
                                        }
                                        assert_eq!(cell.bg, bottom);
                                    } else {
                                        assert_eq!(cell.symbol(), "▀");
                                        assert_eq!((cell.fg, cell.bg), (at(2 * r), Color::Reset));
                                    }
                                } else {
                                    assert_eq!(
                                        cell,
                                        &Cell::EMPTY,
                                        "{w}x{h} in {area:?} at ({x}, {y})"
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn runs_of_repeated_colours_render_like_isolated_ones() {
    // Flat-shaded rows (the widget caches the last quantisation): every cell must still match the
    // quantisation of its own two pixels.
    let palette = [R, R, Rgb::new(250, 10, 5), G, G, G, K, R];
    let (w, h) = (8u32, 6u32);
    let px: Vec<Rgb> = (0..w * h)
        .map(|i| palette[((i * 3 + i / w) % 8) as usize])
        .collect();
    for depth in ColorDepth::ALL {
        let mut buf = Buffer::empty(Rect::new(0, 0, 8, 3));
        render(&px, w, h, depth, buf.area, &mut buf);
        for r in 0..3u32 {
            for c in 0..8u32 {
                let top = quantize(px[(2 * r * w + c) as usize], depth);
                let bottom = quantize(px[((2 * r + 1) * w + c) as usize], depth);
                let cell = &buf[(c as u16, r as u16)];
                let expected_fg = if top == bottom { Color::Reset } else { top };
                assert_eq!(
                    (cell.fg, cell.bg),
                    (expected_fg, bottom),
                    "{depth} ({c}, {r})"
                );
            }
        }
    }
}
