//! ANSI text output of ratatui buffers (`nudge snapshot`): exact byte strings.

use nudge::color::Rgb;
use nudge::term::{ColorDepth, HalfBlocks, buffer_to_ansi, plain_lines};
use ratatui::buffer::{Buffer, CellDiffOption};
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::widgets::Widget;

const RESET_NL: &str = "\x1b[0m\n";

/// A 2×1-cell half-block picture: red over blue, then a cell whose halves are both green.
fn two_cells(depth: ColorDepth) -> Buffer {
    let px = [
        Rgb::new(255, 0, 0),
        Rgb::new(0, 255, 0),
        Rgb::new(0, 0, 255),
        Rgb::new(0, 255, 0),
    ];
    let mut buf = Buffer::empty(Rect::new(0, 0, 2, 1));
    HalfBlocks::new(&px, 2, 2, depth).render(buf.area, &mut buf);
    buf
}

#[test]
fn truecolor_half_blocks_print_24_bit_codes() {
    let text = buffer_to_ansi(&two_cells(ColorDepth::TrueColor), ColorDepth::TrueColor);
    assert_eq!(
        text,
        "\x1b[38;2;255;0;0;48;2;0;0;255m▀\x1b[39;48;2;0;255;0m \x1b[0m\n"
    );
}

#[test]
fn a_truecolor_buffer_prints_at_256_colours_when_asked() {
    let text = buffer_to_ansi(&two_cells(ColorDepth::TrueColor), ColorDepth::Ansi256);
    assert_eq!(text, "\x1b[38;5;196;48;5;21m▀\x1b[39;48;5;46m \x1b[0m\n");
    // Same bytes as rendering at 256 colours in the first place.
    assert_eq!(
        text,
        buffer_to_ansi(&two_cells(ColorDepth::Ansi256), ColorDepth::Ansi256)
    );
}

#[test]
fn sixteen_colour_output_uses_the_short_codes() {
    let text = buffer_to_ansi(&two_cells(ColorDepth::Ansi256), ColorDepth::Ansi16);
    // Red → bright red (91); #0000ff → blue (44); #00ff00 → bright green (102).
    assert_eq!(text, "\x1b[91;44m▀\x1b[39;102m \x1b[0m\n");
}

#[test]
fn escapes_appear_only_when_the_style_changes() {
    let mut buf = Buffer::with_lines(["aaab"]);
    buf.set_style(Rect::new(0, 0, 3, 1), Style::new().fg(Color::Red));
    let text = buffer_to_ansi(&buf, ColorDepth::TrueColor);
    assert_eq!(text, "\x1b[31maaa\x1b[39mb\x1b[0m\n");
}

#[test]
fn every_row_starts_from_the_default_style_and_ends_with_a_reset() {
    #[rustfmt::skip]
    let mut buf = Buffer::with_lines([
        "ab",
        "cd",
    ]);
    buf.set_style(buf.area, Style::new().bg(Color::Blue));
    let text = buffer_to_ansi(&buf, ColorDepth::Ansi16);
    assert_eq!(text, "\x1b[44mab\x1b[0m\n\x1b[44mcd\x1b[0m\n");
    assert!(text.ends_with(RESET_NL));
    // No cursor movement or screen control, only SGR ('m') sequences.
    for (i, _) in text.match_indices('\x1b') {
        let rest = &text[i + 2..];
        let end = rest.find(|c: char| c.is_ascii_alphabetic()).unwrap();
        assert_eq!(&rest[end..=end], "m", "non-SGR escape in {text:?}");
    }
}

#[test]
fn unstyled_text_has_only_the_line_resets() {
    #[rustfmt::skip]
    let buf = Buffer::with_lines([
        "hello",
        "     ",
    ]);
    assert_eq!(
        buffer_to_ansi(&buf, ColorDepth::TrueColor),
        "hello\x1b[0m\n     \x1b[0m\n"
    );
}

#[test]
fn modifiers_are_printed_and_reset_when_dropped() {
    let mut buf = Buffer::with_lines(["xyz"]);
    buf.set_style(
        Rect::new(0, 0, 1, 1),
        Style::new().add_modifier(Modifier::BOLD | Modifier::REVERSED),
    );
    buf.set_style(
        Rect::new(1, 0, 1, 1),
        Style::new().add_modifier(Modifier::BOLD),
    );
    let text = buffer_to_ansi(&buf, ColorDepth::TrueColor);
    assert_eq!(text, "\x1b[1;7mx\x1b[0;1my\x1b[0mz\x1b[0m\n");
}

#[test]
fn wide_symbols_cover_the_next_cell() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 4, 1));
    buf.set_string(0, 0, "日x", Style::new());
    assert_eq!(buf[(1, 0)].symbol(), " ");
    let text = buffer_to_ansi(&buf, ColorDepth::TrueColor);
    assert_eq!(text, "日x \x1b[0m\n");
}

#[test]
fn control_characters_and_skipped_cells_cannot_break_the_output() {
    let mut buf = Buffer::empty(Rect::new(0, 0, 3, 1));
    buf[(0, 0)].set_symbol("\x1b");
    buf[(1, 0)].set_symbol("");
    buf[(2, 0)]
        .set_symbol("q")
        .set_diff_option(CellDiffOption::Skip);
    assert_eq!(buffer_to_ansi(&buf, ColorDepth::TrueColor), "?  \x1b[0m\n");
}

#[test]
fn an_empty_buffer_prints_nothing_and_an_offset_buffer_prints_its_own_area() {
    assert_eq!(
        buffer_to_ansi(&Buffer::empty(Rect::new(0, 0, 0, 0)), ColorDepth::TrueColor),
        ""
    );
    assert_eq!(
        buffer_to_ansi(&Buffer::empty(Rect::new(3, 4, 0, 2)), ColorDepth::TrueColor),
        "\x1b[0m\n\x1b[0m\n"
    );
    let mut buf = Buffer::empty(Rect::new(5, 7, 2, 1));
    buf.set_string(5, 7, "ok", Style::new().fg(Color::Green));
    assert_eq!(
        buffer_to_ansi(&buf, ColorDepth::TrueColor),
        "\x1b[32mok\x1b[0m\n"
    );
}

#[test]
fn plain_lines_of_a_gradient_read_dark_to_bright() {
    // A 10×2 horizontal grey ramp: the density ramp left to right, one line.
    let px: Vec<Rgb> = (0..2)
        .flat_map(|_| (0..10u8).map(|i| Rgb::new(i * 26 + 12, i * 26 + 12, i * 26 + 12)))
        .collect();
    assert_eq!(plain_lines(&px, 10, 2), vec![" .:-=+*#%@".to_owned()]);
}
