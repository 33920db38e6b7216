//! Colours as the renderer produces them and the terminal consumes them: 8-bit sRGB triples, and
//! ([`oklab`]) the perceptual space and linear light the terminal layer matches and mixes them in.

pub mod oklab;

/// An 8-bit-per-channel sRGB colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgb {
    pub r: u8,
    pub g: u8,
    pub b: u8,
}

impl Rgb {
    pub const BLACK: Rgb = Rgb::new(0, 0, 0);
    pub const WHITE: Rgb = Rgb::new(255, 255, 255);

    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// Parses `#rrggbb` (the leading `#` is required).
    pub fn from_hex(text: &str) -> Option<Self> {
        let hex = text.strip_prefix('#')?;
        if hex.len() != 6 || !hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            return None;
        }
        let channel = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Self::new(channel(0)?, channel(2)?, channel(4)?))
    }

    /// Channels as floats in [0, 1] (no gamma conversion: shading works in display space on purpose,
    /// which is what a 256-colour terminal shows anyway).
    pub fn to_unit(self) -> [f32; 3] {
        [
            self.r as f32 / 255.0,
            self.g as f32 / 255.0,
            self.b as f32 / 255.0,
        ]
    }

    /// Builds a colour from floats in [0, 1]; out-of-range and NaN channels are clamped (NaN → 0).
    pub fn from_unit(c: [f32; 3]) -> Self {
        let q = |v: f32| {
            if v.is_nan() {
                0
            } else {
                (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
            }
        };
        Self::new(q(c[0]), q(c[1]), q(c[2]))
    }

    pub fn to_hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

/// What the scene file gives bodies that name no colour (see `scene::file`), and what the built-in
/// scenes and the sandbox's spawned bodies use too.
/// Colour of floors and walls.
pub const FLOOR_COLOR: Rgb = Rgb::new(0x80, 0x84, 0x88);
/// Colours handed to dynamic bodies in turn.
pub const PALETTE: [Rgb; 6] = [
    Rgb::new(0xc0, 0x80, 0x40),
    Rgb::new(0xd0, 0x50, 0x40),
    Rgb::new(0x40, 0x90, 0xd0),
    Rgb::new(0x60, 0xb0, 0x50),
    Rgb::new(0xe0, 0xc0, 0x40),
    Rgb::new(0xa0, 0x60, 0xc0),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_round_trips() {
        let c = Rgb::from_hex("#c08040").unwrap();
        assert_eq!(c, Rgb::new(0xc0, 0x80, 0x40));
        assert_eq!(c.to_hex(), "#c08040");
    }

    #[test]
    fn bad_hex_is_rejected() {
        for bad in ["c08040", "#c0804", "#c0804g", "#c080400", ""] {
            assert_eq!(Rgb::from_hex(bad), None, "{bad}");
        }
    }

    #[test]
    fn unit_conversion_clamps_and_rejects_nan() {
        assert_eq!(Rgb::from_unit([2.0, -1.0, f32::NAN]), Rgb::new(255, 0, 0));
    }
}
