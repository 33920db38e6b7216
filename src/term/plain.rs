//! `--plain` output: the image as ASCII characters, one per cell, no colour and no escapes, so it can
//! be diffed, grepped and read on any terminal.
//!
//! A cell covers the same two pixels as in the half-block view (pixel rows 2r and 2r + 1; the last
//! cell row of an odd-height image covers one pixel). Its character comes from the mean luminance of
//! those pixels on the density ramp [`RAMP`], darkest first.

use crate::color::Rgb;

/// Characters from dark (index 0) to bright; ten steps.
pub const RAMP: &[u8; 10] = b" .:-=+*#%@";

/// Relative luminance of `c` on 0..=255 in display space, with the Rec. 709 weights
/// (integer: `(2126 r + 7152 g + 722 b) / 10000`, exact for greys).
#[inline]
pub fn luma(c: Rgb) -> u32 {
    (2126 * u32::from(c.r) + 7152 * u32::from(c.g) + 722 * u32::from(c.b)) / 10_000
}

/// The ramp character for a luminance on 0..=255: ramp index `luma · 10 / 256`, so each character
/// covers an equal span of 25.6 levels.
#[inline]
pub fn density_char(luma: u32) -> char {
    let index = (luma.min(255) as usize * RAMP.len()) / 256;
    char::from(RAMP[index])
}

/// The image as `ceil(height / 2)` lines of exactly `width` characters each (no newlines; trailing
/// spaces kept so every line has the same width).
///
/// `pixels` is row-major, y down; if it is shorter than `width × height` the missing pixels are
/// skipped (a cell with neither pixel present shows `' '`).
pub fn plain_lines(pixels: &[Rgb], width: u32, height: u32) -> Vec<String> {
    let pixel = |x: u32, y: u32| -> Option<Rgb> {
        if y >= height {
            return None;
        }
        let index = (y as usize)
            .checked_mul(width as usize)?
            .checked_add(x as usize)?;
        pixels.get(index).copied()
    };
    let rows = height.div_ceil(2);
    (0..rows)
        .map(|row| {
            (0..width)
                .map(|x| {
                    let (top, bottom) = (pixel(x, 2 * row), pixel(x, 2 * row + 1));
                    match (top, bottom) {
                        (Some(t), Some(b)) => density_char((luma(t) + luma(b)) / 2),
                        (Some(c), None) | (None, Some(c)) => density_char(luma(c)),
                        (None, None) => ' ',
                    }
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luma_is_exact_for_greys_and_weights_green_most() {
        for v in [0u8, 1, 127, 128, 254, 255] {
            assert_eq!(luma(Rgb::new(v, v, v)), u32::from(v));
        }
        assert!(luma(Rgb::new(0, 255, 0)) > luma(Rgb::new(255, 0, 0)));
        assert!(luma(Rgb::new(255, 0, 0)) > luma(Rgb::new(0, 0, 255)));
    }

    #[test]
    fn the_ramp_runs_from_space_to_at_sign_in_equal_steps() {
        assert_eq!(density_char(0), ' ');
        assert_eq!(density_char(25), ' ');
        assert_eq!(density_char(26), '.');
        assert_eq!(density_char(128), '+');
        assert_eq!(density_char(255), '@');
        assert_eq!(density_char(10_000), '@');
    }

    #[test]
    fn a_cell_averages_its_two_pixels() {
        // Black over white: mean 127 → ramp index 4 ('=').
        let lines = plain_lines(&[Rgb::BLACK, Rgb::WHITE], 1, 2);
        assert_eq!(lines, vec!["=".to_owned()]);
    }

    #[test]
    fn an_odd_last_row_uses_its_single_pixel() {
        let lines = plain_lines(&[Rgb::WHITE, Rgb::WHITE, Rgb::WHITE], 1, 3);
        assert_eq!(lines, vec!["@".to_owned(), "@".to_owned()]);
    }

    #[test]
    fn empty_and_short_inputs_do_not_panic() {
        assert!(plain_lines(&[], 0, 0).is_empty());
        assert_eq!(plain_lines(&[], 3, 0), Vec::<String>::new());
        assert_eq!(plain_lines(&[], 0, 4), vec![String::new(), String::new()]);
        // Claims 2×2 but holds one white pixel.
        assert_eq!(plain_lines(&[Rgb::WHITE], 2, 2), vec!["@ ".to_owned()]);
    }
}
