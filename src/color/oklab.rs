//! OKLab (Björn Ottosson, 2020): a perceptual colour space where straight-line distance tracks how
//! different two colours look, and linear light, where colours mix the way the eye blends them.
//!
//! Why OKLab rather than CIELAB/CIEDE2000 or DIN99d: it is as even in hue as CIEDE2000 for the
//! saturated, shaded colours a renderer makes (CIELAB bends blues toward purple), it is a matrix, a
//! cube root and a matrix (CIEDE2000 is a page of trigonometry per pair), and plain Euclidean distance
//! works in it, so palette searches can prune and sum. Units: `l` 0 (black) to 1 (white); `a`
//! green(−)/red(+), `b` blue(−)/yellow(+), about ±0.3 at most for sRGB. A just-noticeable difference
//! is about 0.01.
//!
//! OKLab is homogeneous of degree ⅓ in linear light: scaling a linear colour by `s` scales all three
//! coordinates by `∛s`. So a colour darkened by mixing it with black keeps its hue angle exactly.

use std::sync::LazyLock;

use super::Rgb;

/// A colour in OKLab (see the module docs for units).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Oklab {
    /// Perceived lightness, 0 (black) to 1 (white).
    pub l: f32,
    /// Green (−) to red (+).
    pub a: f32,
    /// Blue (−) to yellow (+).
    pub b: f32,
}

impl Oklab {
    /// Colourfulness: distance from the grey axis (0 for greys; up to about 0.32 in sRGB).
    #[inline]
    pub fn chroma(self) -> f32 {
        self.a.hypot(self.b)
    }

    /// Squared Euclidean distance.
    #[inline]
    pub fn distance_sq(self, other: Oklab) -> f32 {
        let (dl, da, db) = (self.l - other.l, self.a - other.a, self.b - other.b);
        dl * dl + da * da + db * db
    }

    /// Euclidean distance (ΔE in OKLab; ×100 it is the unit `nudge bench render` reports).
    #[inline]
    pub fn distance(self, other: Oklab) -> f32 {
        self.distance_sq(other).sqrt()
    }
}

/// Linear-light value of every 8-bit sRGB channel value (the sRGB transfer function, IEC 61966-2-1).
static SRGB_TO_LINEAR: LazyLock<[f32; 256]> = LazyLock::new(|| {
    let mut table = [0.0; 256];
    for (v, slot) in table.iter_mut().enumerate() {
        let c = v as f32 / 255.0;
        *slot = if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        };
    }
    table
});

/// `c` in linear light, channels in [0, 1].
#[inline]
pub fn to_linear(c: Rgb) -> [f32; 3] {
    let table = &*SRGB_TO_LINEAR;
    [
        table[usize::from(c.r)],
        table[usize::from(c.g)],
        table[usize::from(c.b)],
    ]
}

/// The sRGB colour of a linear-light one (channels clamped to [0, 1], rounded to nearest).
pub fn from_linear(linear: [f32; 3]) -> Rgb {
    let encode = |v: f32| {
        let v = v.clamp(0.0, 1.0);
        if v <= 0.003_130_8 {
            v * 12.92
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        }
    };
    Rgb::from_unit(linear.map(encode))
}

/// The OKLab coordinates of a linear-light colour (channels in [0, 1]; negative values are allowed
/// and map through a signed cube root).
#[inline]
pub fn linear_to_oklab([r, g, b]: [f32; 3]) -> Oklab {
    let l = 0.412_221_46 * r + 0.536_332_55 * g + 0.051_445_995 * b;
    let m = 0.211_903_5 * r + 0.680_699_5 * g + 0.107_396_96 * b;
    let s = 0.088_302_46 * r + 0.281_718_85 * g + 0.629_978_7 * b;
    let (l, m, s) = (l.cbrt(), m.cbrt(), s.cbrt());
    Oklab {
        l: 0.210_454_26 * l + 0.793_617_8 * m - 0.004_072_047 * s,
        a: 1.977_998_5 * l - 2.428_592_2 * m + 0.450_593_7 * s,
        b: 0.025_904_037 * l + 0.782_771_77 * m - 0.808_675_77 * s,
    }
}

/// The OKLab coordinates of an sRGB colour.
#[inline]
pub fn to_oklab(c: Rgb) -> Oklab {
    linear_to_oklab(to_linear(c))
}

/// The linear-light colour of OKLab coordinates (Ottosson's inverse matrices; out-of-gamut
/// colours come out with channels outside [0, 1]).
#[inline]
pub fn oklab_to_linear(lab: Oklab) -> [f32; 3] {
    let l = lab.l + 0.396_337_78 * lab.a + 0.215_803_76 * lab.b;
    let m = lab.l - 0.105_561_346 * lab.a - 0.063_854_17 * lab.b;
    let s = lab.l - 0.089_484_18 * lab.a - 1.291_485_5 * lab.b;
    let (l, m, s) = (l * l * l, m * m * m, s * s * s);
    [
        4.076_741_7 * l - 3.307_711_6 * m + 0.230_969_94 * s,
        -1.268_438 * l + 2.609_757_4 * m - 0.341_319_38 * s,
        -0.004_196_086_3 * l - 0.703_418_6 * m + 1.707_614_7 * s,
    ]
}

/// The sRGB colour of OKLab coordinates, clamped into the sRGB gamut channel by channel.
pub fn from_oklab(lab: Oklab) -> Rgb {
    from_linear(oklab_to_linear(lab))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 2e-4
    }

    #[test]
    fn white_is_lightness_one_and_black_zero_both_grey() {
        let white = to_oklab(Rgb::WHITE);
        assert!(close(white.l, 1.0) && white.chroma() < 2e-4, "{white:?}");
        assert_eq!(to_oklab(Rgb::BLACK), Oklab::default());
    }

    #[test]
    fn primaries_match_ottossons_reference_values() {
        // From the OKLab post: sRGB red, green, blue.
        let red = to_oklab(Rgb::new(255, 0, 0));
        assert!(close(red.l, 0.627_955) && close(red.a, 0.224_863) && close(red.b, 0.125_846));
        let green = to_oklab(Rgb::new(0, 255, 0));
        assert!(close(green.l, 0.866_440) && close(green.a, -0.233_888));
        let blue = to_oklab(Rgb::new(0, 0, 255));
        assert!(close(blue.l, 0.452_014) && close(blue.b, -0.311_528));
    }

    #[test]
    fn darkening_in_linear_light_keeps_the_hue_angle() {
        let orange = to_linear(Rgb::new(0xc0, 0x80, 0x40));
        let dark = orange.map(|v| v * 0.125);
        let (o, d) = (linear_to_oklab(orange), linear_to_oklab(dark));
        assert!(close(d.l, o.l * 0.5) && close(d.a, o.a * 0.5) && close(d.b, o.b * 0.5));
    }

    #[test]
    fn every_srgb_value_round_trips_through_linear_light() {
        for v in 0..=255u8 {
            let c = Rgb::new(v, 255 - v, v / 2);
            assert_eq!(from_linear(to_linear(c)), c);
        }
    }

    #[test]
    fn srgb_colours_round_trip_through_oklab() {
        for c in [
            Rgb::BLACK,
            Rgb::WHITE,
            Rgb::new(0xc0, 0x80, 0x40),
            Rgb::new(0, 0, 255),
            Rgb::new(17, 200, 93),
        ] {
            assert_eq!(from_oklab(to_oklab(c)), c);
        }
    }

    #[test]
    fn the_srgb_curve_has_its_standard_endpoints_and_midpoint() {
        assert_eq!(to_linear(Rgb::BLACK), [0.0; 3]);
        assert_eq!(to_linear(Rgb::WHITE), [1.0; 3]);
        // sRGB 188 is close to half the light of white.
        assert!(close(to_linear(Rgb::new(188, 188, 188))[0], 0.502_886));
    }
}
