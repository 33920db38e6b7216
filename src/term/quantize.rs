//! Mapping an [`Rgb`] to the nearest colour a terminal of a given [`ColorDepth`] can show.
//!
//! "Nearest" is plain squared Euclidean distance in 8-bit sRGB (unweighted, as tmux's `colour.c`
//! does it): cheap, deterministic, and good enough for flat-shaded solids.
//!
//! - TrueColor: the colour itself.
//! - 256: only the fixed part of the xterm palette, never the themable 0..=15:
//!   the 6×6×6 cube, index `16 + 36·r + 6·g + b` with channel levels `0, 95, 135, 175, 215, 255`,
//!   and the grey ramp, index `232 + k` with value `8 + 10k` (k = 0..=23).
//!   Because the distance is a sum over channels, the nearest cube entry is found channel by
//!   channel, and the nearest ramp grey is the ramp step nearest the channel mean (the mean
//!   minimises Σ(cᵢ − g)²; the parabola is symmetric, so the nearest step to it wins). We compute
//!   both arithmetically and keep the nearer (the cube on ties): O(1), no loop over 256 entries.
//! - 16: the nearest of the 16 ANSI colours, taking xterm's default palette values as what they look
//!   like (users may theme them; there is no way to know).

use ratatui::style::Color;

use super::color_depth::ColorDepth;
use crate::color::Rgb;

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

/// The terminal colour to draw `c` with at `depth`: `Color::Rgb` for truecolor, `Color::Indexed(16..=255)`
/// for 256, one of [`ANSI16_COLORS`] for 16.
#[inline]
pub fn quantize(c: Rgb, depth: ColorDepth) -> Color {
    match depth {
        ColorDepth::TrueColor => Color::Rgb(c.r, c.g, c.b),
        ColorDepth::Ansi256 => Color::Indexed(ansi256_index(c)),
        ColorDepth::Ansi16 => ANSI16_COLORS[usize::from(ansi16_index(c))],
    }
}

/// Level 0..=5 of the cube channel value nearest `v`. Midpoints between levels: 47.5, 115, 155,
/// 195, 235; from 115 up the levels are 40 apart, so `(v − 35) / 40`.
#[inline]
fn cube_level(v: u8) -> u8 {
    if v < 48 {
        0
    } else if v < 115 {
        1
    } else {
        (v - 35) / 40
    }
}

#[inline]
fn distance_sq(a: Rgb, b: Rgb) -> u32 {
    let d = |x: u8, y: u8| {
        let t = i32::from(x) - i32::from(y);
        (t * t) as u32
    };
    d(a.r, b.r) + d(a.g, b.g) + d(a.b, b.b)
}

/// The xterm-256 index (16..=255) nearest `c`: the nearer of the nearest cube entry and the nearest
/// grey-ramp entry (see the module docs), the cube winning ties.
#[inline]
pub fn ansi256_index(c: Rgb) -> u8 {
    let (lr, lg, lb) = (cube_level(c.r), cube_level(c.g), cube_level(c.b));
    let cube = Rgb::new(
        CUBE_LEVELS[usize::from(lr)],
        CUBE_LEVELS[usize::from(lg)],
        CUBE_LEVELS[usize::from(lb)],
    );
    let cube_index = 16 + 36 * lr + 6 * lg + lb;

    // Ramp step nearest the mean m = s/3: k = round((m − 8) / 10) = floor((s − 24 + 15) / 30).
    let sum = i32::from(c.r) + i32::from(c.g) + i32::from(c.b);
    let k = (sum - 9).div_euclid(30).clamp(0, 23) as u8;
    let grey_value = 8 + 10 * k;
    let grey = Rgb::new(grey_value, grey_value, grey_value);

    if distance_sq(c, grey) < distance_sq(c, cube) {
        232 + k
    } else {
        cube_index
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

/// The ANSI colour index (0..=15) whose xterm default value is nearest `c` (lowest index on ties).
#[inline]
pub fn ansi16_index(c: Rgb) -> u8 {
    let mut best = 0u8;
    let mut best_d = u32::MAX;
    for (i, &p) in XTERM_ANSI16.iter().enumerate() {
        let d = distance_sq(c, p);
        if d < best_d {
            best_d = d;
            best = i as u8;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the nearest index by exhaustive search over 16..=255, cube preferred on ties.
    fn brute_force_256(c: Rgb) -> u8 {
        let mut best = 16u8;
        let mut best_d = u32::MAX;
        for i in 16..=255u8 {
            let d = distance_sq(c, ansi256_rgb(i));
            if d < best_d {
                best_d = d;
                best = i;
            }
        }
        best
    }

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
    fn mid_grey_goes_to_the_grey_ramp() {
        // 128 = 8 + 10·12 exactly: ramp index 244; the nearest cube grey (135) is 3 away per channel.
        assert_eq!(ansi256_index(Rgb::new(128, 128, 128)), 244);
        assert_eq!(ansi256_index(Rgb::new(100, 100, 100)), 241); // 98 is ramp 241; cube 95 is farther
    }

    #[test]
    fn c08040_is_cube_137() {
        // r 192 → 175 (level 3), g 128 → 135 (2), b 64 → 95 (1): 16 + 108 + 12 + 1 = 137 = #af875f.
        let c = Rgb::from_hex("#c08040").unwrap();
        assert_eq!(ansi256_index(c), 137);
        assert_eq!(ansi256_rgb(137), Rgb::new(0xaf, 0x87, 0x5f));
    }

    #[test]
    fn black_and_white_are_the_cube_corners_and_ansi_extremes() {
        assert_eq!(ansi256_index(Rgb::BLACK), 16);
        assert_eq!(ansi256_index(Rgb::WHITE), 231);
        assert_eq!(quantize(Rgb::BLACK, ColorDepth::Ansi16), Color::Black);
        assert_eq!(quantize(Rgb::WHITE, ColorDepth::Ansi16), Color::White);
    }

    #[test]
    fn near_black_grey_uses_the_first_ramp_step() {
        assert_eq!(ansi256_index(Rgb::new(8, 8, 8)), 232);
        assert_eq!(ansi256_index(Rgb::new(240, 240, 240)), 255); // ramp 238 beats cube 255
    }

    #[test]
    fn cube_levels_switch_at_the_midpoints() {
        // Saturated colours, so the grey ramp is never nearer. Level midpoints: 47.5, 115, 155, 195, 235.
        let index = |r: u8| ansi256_index(Rgb::new(r, 255, 0));
        let expect = |level: u8| 16 + 36 * level + 6 * 5;
        for (v, level) in [(47, 0), (48, 1), (114, 1), (116, 2), (154, 2), (155, 3)] {
            assert_eq!(index(v), expect(level), "r = {v}");
        }
        for (v, level) in [(194, 3), (195, 4), (234, 4), (235, 5), (255, 5)] {
            assert_eq!(index(v), expect(level), "r = {v}");
        }
    }

    #[test]
    fn a_dark_red_may_be_nearer_a_ramp_grey_than_black() {
        // (47, 0, 0): cube black is 47² = 2209 away; ramp 18 is 29² + 2·18² = 1489 away.
        assert_eq!(ansi256_index(Rgb::new(47, 0, 0)), 233);
    }

    #[test]
    fn arithmetic_256_lookup_matches_exhaustive_search() {
        // Every colour on a 4-step grid plus every grey: ~270k colours, each checked against the
        // distance of the brute-force winner (ties may pick a different but equally near index).
        let check = |c: Rgb| {
            let fast = ansi256_index(c);
            let slow = brute_force_256(c);
            assert_eq!(
                distance_sq(c, ansi256_rgb(fast)),
                distance_sq(c, ansi256_rgb(slow)),
                "{c:?}: fast {fast}, exhaustive {slow}"
            );
            assert!(fast >= 16);
        };
        for r in (0..=255u8).step_by(4) {
            for g in (0..=255u8).step_by(4) {
                for b in (0..=255u8).step_by(4) {
                    check(Rgb::new(r, g, b));
                }
            }
        }
        for v in 0..=255u8 {
            check(Rgb::new(v, v, v));
        }
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
