//! The colours a terminal shows at 256 and 16 colours, held in the spaces we match them in (OKLab)
//! and mix them in (linear light), and the perceptual cost of showing one colour as another.
//!
//! - 256: only the fixed part of the xterm palette, never the themable 0..=15: the 6×6×6 cube
//!   (index `16 + 36·r + 6·g + b`, channel levels `0, 95, 135, 175, 215, 255`) and the grey ramp
//!   (index `232 + k`, value `8 + 10k`).
//! - 16: the ANSI colours at xterm's default values (users may theme them; there is no way to know).
//!
//! **The cost** of showing `target` as `shown` is their squared OKLab difference split into lightness,
//! chroma and hue, ΔL² + ΔC² + [`HUE_WEIGHT`]·ΔH² (as CIE94 splits CIELAB), plus
//! [`CHROMA_LOSS_WEIGHT`] × the squared chroma `shown` lacks (unless the target reads as grey itself,
//! chroma under [`GREY_CHROMA`]). Plain distance lets a shaded colour fall
//! to the nearest grey (a dark orange sits about as far from a grey as from a red, and the grey wins
//! on lightness) or turn into another hue of nearer lightness. The eye reads either as a different
//! object; a lightness error it forgives. Only chroma *lost* is charged extra, so greys still match
//! greys, and a colour may come out more saturated than asked.
//!
//! **Why OKLab** and not CIEDE2000: as even in hue for these colours, a matrix and a cube root
//! instead of a page of trigonometry, and Euclidean, so a search for the nearest entry can prune.

use std::sync::LazyLock;

use ratatui::style::Color;

use super::color_depth::ColorDepth;
use super::quantize::{ANSI16_COLORS, ansi256_rgb};
use crate::color::Rgb;
use crate::color::oklab::{Oklab, to_linear, to_oklab};

/// Weight of a turn of hue (ΔH², the part of the OKLab difference that is not lightness or chroma).
/// At 1 (plain OKLab), the default scene's dark green ball is nearer xterm's red than its light green
/// at 16 colours: lightness outweighs hue. At 3 a hue turn of 90° costs about what it looks like.
pub const HUE_WEIGHT: f32 = 3.0;

/// Extra weight on chroma lost (see the module docs), on top of ΔC². Tuned on the built-in scenes at
/// 16 colours (with [`HUE_WEIGHT`] 3): at 6, up to 12 % of coloured 2×2 blocks of a scene came out
/// grey; at 12, at most 5 %, for 0.1 more mean OKLab error (×100).
pub const CHROMA_LOSS_WEIGHT: f32 = 12.0;

/// Chroma below which a colour reads as grey (OKLab): a target this grey pays nothing extra for losing
/// its chroma, so a bluish-grey floor (#808488, chroma 0.008) is shown a plain grey, flat, instead of
/// a grey speckled with blue.
pub const GREY_CHROMA: f32 = 0.01;

/// One colour a terminal can show.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// What to send the terminal.
    pub color: Color,
    /// Its value (xterm's default for 0..=15).
    pub rgb: Rgb,
    /// `rgb` in linear light.
    pub linear: [f32; 3],
    /// `rgb` in OKLab.
    pub lab: Oklab,
    /// `lab.chroma()`.
    pub chroma: f32,
}

impl Entry {
    fn new(color: Color, rgb: Rgb) -> Self {
        let lab = to_oklab(rgb);
        Self {
            color,
            rgb,
            linear: to_linear(rgb),
            lab,
            chroma: lab.chroma(),
        }
    }
}

/// A terminal palette: its entries in a fixed order (for 256, position `i` is index `16 + i`; for 16,
/// position = index).
#[derive(Debug)]
pub struct Palette {
    /// Never empty; at most 255 entries (positions fit a `u8` with 0xFF to spare).
    pub entries: Vec<Entry>,
}

static XTERM_256: LazyLock<Palette> = LazyLock::new(|| Palette {
    entries: (16..=255u8)
        .map(|i| Entry::new(Color::Indexed(i), ansi256_rgb(i)))
        .collect(),
});

static ANSI_16: LazyLock<Palette> = LazyLock::new(|| Palette {
    entries: (0..16u8)
        .map(|i| Entry::new(ANSI16_COLORS[usize::from(i)], ansi256_rgb(i)))
        .collect(),
});

/// The palette of `depth`, or `None` for truecolor (which shows every colour as it is).
pub fn palette(depth: ColorDepth) -> Option<&'static Palette> {
    match depth {
        ColorDepth::TrueColor => None,
        ColorDepth::Ansi256 => Some(&XTERM_256),
        ColorDepth::Ansi16 => Some(&ANSI_16),
    }
}

/// A colour being matched: its OKLab value and chroma, computed once.
#[derive(Clone, Copy, Debug)]
pub struct Target {
    pub lab: Oklab,
    pub chroma: f32,
}

impl Target {
    pub fn new(lab: Oklab) -> Self {
        Self {
            lab,
            chroma: lab.chroma(),
        }
    }

    /// The perceptual cost of showing this target as `shown` (see the module docs).
    #[inline]
    pub fn cost(&self, shown: Oklab) -> f32 {
        self.cost_with_chroma(shown, shown.chroma())
    }

    /// [`Target::cost`] when `shown`'s chroma is already known.
    #[inline]
    pub fn cost_with_chroma(&self, shown: Oklab, shown_chroma: f32) -> f32 {
        let dl = self.lab.l - shown.l;
        let (da, db) = (self.lab.a - shown.a, self.lab.b - shown.b);
        let dc = self.chroma - shown_chroma;
        // ΔH² = Δa² + Δb² − ΔC²: the part of the colour difference that is a turn of hue.
        let dh_sq = (da * da + db * db - dc * dc).max(0.0);
        // A target that reads as grey (chroma under GREY_CHROMA) has no hue to lose; the charge
        // fades in over the next GREY_CHROMA so that plans change smoothly with chroma.
        let has_hue = ((self.chroma - GREY_CHROMA) / GREY_CHROMA).clamp(0.0, 1.0);
        let lost = dc.max(0.0) * has_hue;
        dl * dl + dc * dc + HUE_WEIGHT * dh_sq + CHROMA_LOSS_WEIGHT * lost * lost
    }
}

impl Palette {
    /// The position of the entry that shows `target` at least cost (the first on ties).
    pub fn nearest(&self, target: &Target) -> usize {
        let mut best = 0;
        let mut best_cost = f32::INFINITY;
        for (i, e) in self.entries.iter().enumerate() {
            let cost = target.cost_with_chroma(e.lab, e.chroma);
            if cost < best_cost {
                best_cost = cost;
                best = i;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nearest_rgb(depth: ColorDepth, c: Rgb) -> Rgb {
        let p = palette(depth).unwrap();
        p.entries[p.nearest(&Target::new(to_oklab(c)))].rgb
    }

    #[test]
    fn the_palettes_hold_the_fixed_256_entries_and_the_16_ansi_colours() {
        let p256 = palette(ColorDepth::Ansi256).unwrap();
        assert_eq!(p256.entries.len(), 240);
        assert_eq!(p256.entries[0].color, Color::Indexed(16));
        assert_eq!(p256.entries[239].color, Color::Indexed(255));
        let p16 = palette(ColorDepth::Ansi16).unwrap();
        assert_eq!(p16.entries.len(), 16);
        assert_eq!(p16.entries[9].color, Color::LightRed);
        assert!(palette(ColorDepth::TrueColor).is_none());
    }

    #[test]
    fn greys_still_match_greys() {
        assert_eq!(
            nearest_rgb(ColorDepth::Ansi256, Rgb::new(100, 100, 100)),
            Rgb::new(98, 98, 98)
        );
        assert_eq!(
            nearest_rgb(ColorDepth::Ansi16, Rgb::new(120, 120, 120)),
            Rgb::new(127, 127, 127)
        );
    }

    #[test]
    fn losing_chroma_costs_more_than_gaining_it() {
        let orange = Target::new(to_oklab(Rgb::new(0xc0, 0x80, 0x40)));
        let grey = to_oklab(Rgb::new(0x80, 0x80, 0x80));
        assert!(orange.cost(grey) > orange.lab.distance_sq(grey));
        // Same hue, more chroma: charged no more than the plain distance.
        let lab = orange.lab;
        let vivid = Oklab {
            l: lab.l,
            a: lab.a * 1.5,
            b: lab.b * 1.5,
        };
        assert!((orange.cost(vivid) - lab.distance_sq(vivid)).abs() < 1e-6);
    }

    #[test]
    fn a_dark_green_is_shown_green_not_a_red_of_nearer_lightness() {
        // In plain OKLab, xterm red (205, 0, 0) is nearer (30, 80, 30) than xterm green.
        let dark_green = Rgb::new(30, 80, 30);
        let lab = to_oklab(dark_green);
        let (red, green) = (to_oklab(Rgb::new(205, 0, 0)), to_oklab(Rgb::new(0, 205, 0)));
        assert!(lab.distance(red) < lab.distance(green));
        let shown = nearest_rgb(ColorDepth::Ansi16, dark_green);
        assert!(shown.g > shown.r && shown.g > shown.b, "{shown:?}");
    }
}
