//! A ratatui [`Buffer`] printed as ANSI text (for `nudge snapshot`): characters with SGR colour
//! escapes, no raw mode, no cursor movement, so the output can go to a file or a pipe and be `cat`ed
//! back later.
//!
//! Format, per buffer row: the cells left to right, with one SGR sequence (`ESC [ … m`) before a cell
//! only when its style differs from the one in effect; then `ESC[0m` and `\n`. Every row starts from
//! the default style (the previous one ended with a reset), so the text ends with a reset and a
//! newline, and an empty buffer gives an empty string.
//!
//! - Colours are converted to the requested [`ColorDepth`] first (so `Rgb` cells print as 256- or
//!   16-colour codes, and two colours that land on the same palette entry need no new escape).
//! - Modifiers (bold, dim, italic, underline, blink, reverse, hidden, crossed out) are printed; when
//!   one is removed the sequence starts with `0` (reset) and restates the rest.
//! - A wide symbol (e.g. CJK, width 2) is printed once and the cells it covers are skipped, as a
//!   terminal shows them. Cells marked to be skipped by the diff, and empty symbols, print as `' '`.
//!   Control characters inside symbols print as `'?'`, so a cell can never smuggle in an escape.
//! - The underline colour is not printed.

use ratatui::buffer::{Buffer, CellDiffOption, CellWidth};
use ratatui::style::{Color, Modifier};

use super::color_depth::ColorDepth;
use super::quantize::{ANSI16_COLORS, ansi16_index, ansi256_rgb, quantize};
use crate::color::Rgb;

/// The style that escapes track: colours already converted to the output depth.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Pen {
    fg: Color,
    bg: Color,
    modifier: Modifier,
}

const DEFAULT_PEN: Pen = Pen {
    fg: Color::Reset,
    bg: Color::Reset,
    modifier: Modifier::empty(),
};

/// SGR parameter for each printable modifier.
const MODIFIER_CODES: [(Modifier, u8); 9] = [
    (Modifier::BOLD, 1),
    (Modifier::DIM, 2),
    (Modifier::ITALIC, 3),
    (Modifier::UNDERLINED, 4),
    (Modifier::SLOW_BLINK, 5),
    (Modifier::RAPID_BLINK, 6),
    (Modifier::REVERSED, 7),
    (Modifier::HIDDEN, 8),
    (Modifier::CROSSED_OUT, 9),
];

/// `color` as the nearest colour a `depth` terminal can show: `Rgb` is quantised; at 16 colours an
/// `Indexed` colour becomes the named colour nearest its xterm value; named colours and `Reset` stay.
pub fn color_for_depth(color: Color, depth: ColorDepth) -> Color {
    match (color, depth) {
        (Color::Rgb(r, g, b), _) => quantize(Rgb::new(r, g, b), depth),
        (Color::Indexed(i), ColorDepth::Ansi16) => {
            ANSI16_COLORS[usize::from(ansi16_index(ansi256_rgb(i)))]
        }
        (other, _) => other,
    }
}

/// Appends the SGR parameters selecting `color` as foreground (`base` 30) or background (`base` 40).
fn push_color(params: &mut Vec<String>, color: Color, base: u8) {
    if let Some(i) = ANSI16_COLORS.iter().position(|&c| c == color) {
        // 0..=7: 30..=37 / 40..=47; 8..=15: 90..=97 / 100..=107.
        let i = i as u8;
        let code = if i < 8 { base + i } else { base + 60 + i - 8 };
        params.push(code.to_string());
        return;
    }
    match color {
        Color::Indexed(n) => params.push(format!("{};5;{n}", base + 8)),
        Color::Rgb(r, g, b) => params.push(format!("{};2;{r};{g};{b}", base + 8)),
        // Reset, and anything a future ratatui adds: the terminal default.
        _ => params.push((base + 9).to_string()),
    }
}

/// The SGR sequence taking the terminal from `from` to `to` (empty if they are equal).
fn transition(from: Pen, to: Pen) -> String {
    if from == to {
        return String::new();
    }
    let mut params = Vec::new();
    let mut from = from;
    if !to.modifier.contains(from.modifier) {
        params.push("0".to_owned());
        from = DEFAULT_PEN;
    }
    for (modifier, code) in MODIFIER_CODES {
        if to.modifier.contains(modifier) && !from.modifier.contains(modifier) {
            params.push(code.to_string());
        }
    }
    if to.fg != from.fg {
        push_color(&mut params, to.fg, 30);
    }
    if to.bg != from.bg {
        push_color(&mut params, to.bg, 40);
    }
    format!("\x1b[{}m", params.join(";"))
}

/// Appends a cell's (control-free) `symbol` of display `width`, or `' '` for a skipped cell or an
/// empty symbol; returns how many cells the output covers (at least 1).
fn print_symbol(out: &mut String, diff_option: CellDiffOption, symbol: &str, width: u16) -> u16 {
    if diff_option == CellDiffOption::Skip || width == 0 || symbol.is_empty() {
        out.push(' ');
        1
    } else {
        out.push_str(symbol);
        width
    }
}

/// Prints `buf` as ANSI text at `depth`; see the module docs for the exact format.
pub fn buffer_to_ansi(buf: &Buffer, depth: ColorDepth) -> String {
    let area = buf.area;
    let mut out = String::with_capacity(buf.content.len() * 4);
    for y in area.top()..area.bottom() {
        let mut pen = DEFAULT_PEN;
        let mut x = area.left();
        while x < area.right() {
            let cell = &buf[(x, y)];
            let next = Pen {
                fg: color_for_depth(cell.fg, depth),
                bg: color_for_depth(cell.bg, depth),
                modifier: cell.modifier,
            };
            out.push_str(&transition(pen, next));
            pen = next;

            let symbol = cell.symbol();
            let width = if symbol.chars().any(char::is_control) {
                let clean: String = symbol
                    .chars()
                    .map(|c| if c.is_control() { '?' } else { c })
                    .collect();
                print_symbol(&mut out, cell.diff_option, &clean, clean.cell_width())
            } else {
                print_symbol(&mut out, cell.diff_option, symbol, cell.cell_width())
            };
            x = x.saturating_add(width);
        }
        out.push_str("\x1b[0m\n");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pen(fg: Color, bg: Color, modifier: Modifier) -> Pen {
        Pen { fg, bg, modifier }
    }

    #[test]
    fn equal_pens_need_no_escape() {
        assert_eq!(transition(DEFAULT_PEN, DEFAULT_PEN), "");
    }

    #[test]
    fn named_colours_use_the_short_codes() {
        let to = pen(Color::Red, Color::LightBlue, Modifier::empty());
        assert_eq!(transition(DEFAULT_PEN, to), "\x1b[31;104m");
        let to = pen(Color::DarkGray, Color::Gray, Modifier::empty());
        assert_eq!(transition(DEFAULT_PEN, to), "\x1b[90;47m");
    }

    #[test]
    fn indexed_and_rgb_colours_use_extended_codes() {
        let to = pen(Color::Indexed(196), Color::Rgb(1, 2, 3), Modifier::empty());
        assert_eq!(transition(DEFAULT_PEN, to), "\x1b[38;5;196;48;2;1;2;3m");
    }

    #[test]
    fn going_back_to_default_colours_uses_39_and_49() {
        let from = pen(Color::Red, Color::Blue, Modifier::empty());
        assert_eq!(transition(from, DEFAULT_PEN), "\x1b[39;49m");
    }

    #[test]
    fn adding_a_modifier_keeps_the_rest_and_removing_one_resets() {
        let bold = pen(Color::Red, Color::Reset, Modifier::BOLD);
        let bold_italic = pen(Color::Red, Color::Reset, Modifier::BOLD | Modifier::ITALIC);
        assert_eq!(transition(bold, bold_italic), "\x1b[3m");
        assert_eq!(transition(bold_italic, bold), "\x1b[0;1;31m");
    }

    #[test]
    fn colours_are_converted_to_the_depth() {
        assert_eq!(
            color_for_depth(Color::Rgb(255, 0, 0), ColorDepth::Ansi256),
            Color::Indexed(196)
        );
        assert_eq!(
            color_for_depth(Color::Indexed(196), ColorDepth::Ansi16),
            Color::LightRed
        );
        assert_eq!(
            color_for_depth(Color::Indexed(1), ColorDepth::Ansi16),
            Color::Red
        );
        assert_eq!(
            color_for_depth(Color::Indexed(196), ColorDepth::Ansi256),
            Color::Indexed(196)
        );
        assert_eq!(
            color_for_depth(Color::Cyan, ColorDepth::TrueColor),
            Color::Cyan
        );
        assert_eq!(
            color_for_depth(Color::Reset, ColorDepth::Ansi16),
            Color::Reset
        );
    }
}
