//! Mapping an [`Rgb`] to the single nearest colour a terminal of a given [`ColorDepth`] can show,
//! perceptually: the least [`palette`](super::palette) cost (OKLab, hue turns and chroma lost charged
//! extra). [`dither`](super::dither)'s `none` mode is the same match, memoised per colour bucket.
//!
//! - TrueColor: the colour itself.
//! - 256: only the fixed part of the xterm palette, never the themable 0..=15: the 6×6×6 cube
//!   (index `16 + 36·r + 6·g + b`, channel levels `0, 95, 135, 175, 215, 255`) and the grey ramp
//!   (index `232 + k`, value `8 + 10k`).
//! - 16: the nearest of the 16 ANSI colours, taking xterm's default palette values as what they look
//!   like (users may theme them; there is no way to know).

use ratatui::style::Color;

use super::color_depth::ColorDepth;
use super::palette::{Target, palette};
use crate::color::Rgb;
use crate::color::oklab::to_oklab;

/// Channel values of the xterm 6×6×6 colour cube, by level 0..=5.
pub const CUBE_LEVELS: [u8; 6] = [0, 95, 135, 175, 215, 255];

/// xterm's default values for the 16 ANSI colours, by index 0..=15
/// (black, red, green, yellow, blue, magenta, cyan, white, then the bright variants).
pub const XTERM_ANSI16: [Rgb; 16] = [
    Rgb::new(0, 0, 0),
    Rgb::new(205, 0, 0),
    Rgb::new(0, 205, 0),
    Rgb::new(205, 205, 0),
    Rgb::new(0, 0, 238),
    Rgb::new(205, 0, 205),
    Rgb::new(0, 205, 205),
    Rgb::new(229, 229, 229),
    Rgb::new(127, 127, 127),
    Rgb::new(255, 0, 0),
    Rgb::new(0, 255, 0),
    Rgb::new(255, 255, 0),
    Rgb::new(92, 92, 255),
    Rgb::new(255, 0, 255),
    Rgb::new(0, 255, 255),
    Rgb::new(255, 255, 255),
];

/// ratatui's names for ANSI colours 0..=15, in index order (ratatui calls 7 `Gray`, 8 `DarkGray`,
/// 15 `White`).
pub const ANSI16_COLORS: [Color; 16] = [
    Color::Black,
    Color::Red,
    Color::Green,
    Color::Yellow,
    Color::Blue,
    Color::Magenta,
    Color::Cyan,
    Color::Gray,
    Color::DarkGray,
    Color::LightRed,
    Color::LightGreen,
    Color::LightYellow,
    Color::LightBlue,
    Color::LightMagenta,
    Color::LightCyan,
    Color::White,
];

/// The terminal colour to draw `c` with at `depth`, undithered: `Color::Rgb` for truecolor,
/// `Color::Indexed(16..=255)` for 256, one of [`ANSI16_COLORS`] for 16. Exact (no memo buckets): for
/// the odd colour; [`HalfBlocks`](super::HalfBlocks) quantises whole images through
/// [`with_quantizer`](super::dither::with_quantizer).
pub fn quantize(c: Rgb, depth: ColorDepth) -> Color {
    match palette(depth) {
        None => Color::Rgb(c.r, c.g, c.b),
        Some(p) => p.entries[p.nearest(&Target::new(to_oklab(c)))].color,
    }
}

/// The xterm-256 index (16..=255) that shows `c` best, undithered.
pub fn ansi256_index(c: Rgb) -> u8 {
    match quantize(c, ColorDepth::Ansi256) {
        Color::Indexed(i) => i,
        other => unreachable!("the 256-colour palette holds only indexed colours, not {other:?}"),
    }
}

/// The colour xterm shows for 256-palette `index` (0..=15 at xterm's defaults, then cube and ramp).
pub fn ansi256_rgb(index: u8) -> Rgb {
    match index {
        0..=15 => XTERM_ANSI16[usize::from(index)],
        16..=231 => {
            let i = index - 16;
            Rgb::new(
                CUBE_LEVELS[usize::from(i / 36)],
                CUBE_LEVELS[usize::from(i / 6 % 6)],
                CUBE_LEVELS[usize::from(i % 6)],
            )
        }
        232..=255 => {
            let v = 8 + 10 * (index - 232);
            Rgb::new(v, v, v)
        }
    }
}

/// The ANSI colour index (0..=15) whose xterm default value shows `c` best, undithered.
pub fn ansi16_index(c: Rgb) -> u8 {
    let color = quantize(c, ColorDepth::Ansi16);
    ANSI16_COLORS
        .iter()
        .position(|&named| named == color)
        .map_or(0, |i| i as u8)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::oklab::to_oklab;

    #[test]
    fn pure_red_is_cube_196_and_bright_red_in_16() {
        let red = Rgb::new(255, 0, 0);
        assert_eq!(quantize(red, ColorDepth::Ansi256), Color::Indexed(196));
        // xterm's bright red (index 9) is exactly #ff0000; its normal red is #cd0000.
        assert_eq!(quantize(red, ColorDepth::Ansi16), Color::LightRed);
        assert_eq!(
            quantize(Rgb::new(205, 0, 0), ColorDepth::Ansi16),
            Color::Red
        );
    }

    #[test]
    fn truecolor_passes_the_colour_through() {
        assert_eq!(
            quantize(Rgb::new(1, 2, 3), ColorDepth::TrueColor),
            Color::Rgb(1, 2, 3)
        );
    }

    #[test]
    fn greys_go_to_the_grey_ramp() {
        // 128 = 8 + 10·12 exactly: ramp index 244.
        assert_eq!(ansi256_index(Rgb::new(128, 128, 128)), 244);
        assert_eq!(ansi256_index(Rgb::new(100, 100, 100)), 241); // ramp 98
        assert_eq!(ansi256_index(Rgb::new(8, 8, 8)), 232);
        assert_eq!(ansi256_index(Rgb::new(240, 240, 240)), 255); // ramp 238
    }

    #[test]
    fn black_and_white_are_the_cube_corners_and_ansi_extremes() {
        assert_eq!(ansi256_index(Rgb::BLACK), 16);
        assert_eq!(ansi256_index(Rgb::WHITE), 231);
        assert_eq!(quantize(Rgb::BLACK, ColorDepth::Ansi16), Color::Black);
        assert_eq!(quantize(Rgb::WHITE, ColorDepth::Ansi16), Color::White);
    }

    #[test]
    fn palette_entries_quantise_to_themselves() {
        for i in 16..=255u8 {
            let c = ansi256_rgb(i);
            assert_eq!(ansi256_index(c), i, "{c:?}");
        }
        for (i, &c) in XTERM_ANSI16.iter().enumerate() {
            assert_eq!(usize::from(ansi16_index(c)), i, "{c:?}");
        }
    }

    /// Hue of a colour in degrees (OKLab's a/b angle).
    fn hue_deg(c: Rgb) -> f32 {
        let lab = to_oklab(c);
        lab.b.atan2(lab.a).to_degrees()
    }

    #[test]
    fn a_dark_orange_stays_orange_ish_at_256_and_turns_red_or_yellow_at_16_never_grey() {
        // The default scene's orange box (#c08040, hue 66°) in shade, and darker still. The cube has
        // no orange that dark: the nearest single entry may lean to red (29°) or olive (111°) but
        // keeps its colour; the dithered blend (tests/term/colour.rs) is orange itself.
        for orange in [
            Rgb::new(0x80, 0x50, 0x20),
            Rgb::new(0x60, 0x40, 0x20),
            Rgb::new(0x40, 0x2a, 0x14),
        ] {
            let shown = ansi256_rgb(ansi256_index(orange));
            assert!(to_oklab(shown).chroma() >= 0.05, "{orange:?} → {shown:?}");
            assert!(
                (hue_deg(shown) - hue_deg(orange)).abs() < 46.0,
                "{orange:?} → {shown:?}"
            );
            let named = quantize(orange, ColorDepth::Ansi16);
            assert!(
                [
                    Color::Red,
                    Color::Yellow,
                    Color::LightRed,
                    Color::LightYellow
                ]
                .contains(&named),
                "{orange:?} → {named:?}"
            );
        }
        // Where the cube has an orange-brown, it is the match.
        assert_eq!(
            ansi256_rgb(ansi256_index(Rgb::new(0x80, 0x50, 0x20))),
            Rgb::new(135, 95, 0)
        );
    }

    #[test]
    fn a_dark_red_keeps_its_hue_instead_of_becoming_a_ramp_grey() {
        // (47, 0, 0) is nearer ramp grey 18 than cube black in sRGB; perceptually it is a dark red.
        assert_eq!(ansi256_index(Rgb::new(47, 0, 0)), 52); // cube (95, 0, 0)
    }

    #[test]
    fn sixteen_colour_matches_pick_the_obvious_hue() {
        assert_eq!(
            quantize(Rgb::new(0, 0, 180), ColorDepth::Ansi16),
            Color::Blue
        );
        assert_eq!(
            quantize(Rgb::new(130, 130, 130), ColorDepth::Ansi16),
            Color::DarkGray
        );
        assert_eq!(
            quantize(Rgb::new(220, 220, 225), ColorDepth::Ansi16),
            Color::Gray
        );
        assert_eq!(
            quantize(Rgb::new(240, 250, 10), ColorDepth::Ansi16),
            Color::LightYellow
        );
    }
}
