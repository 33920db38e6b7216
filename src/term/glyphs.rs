//! Mosaic glyphs: which character shows which pattern of a cell's pixels, for each [`CellMode`].
//!
//! A cell of mode `(cols, rows)` pixels (see [`CellMode::pixels_per_cell`]) is a pattern: bit
//! `row · cols + col` set where the glyph paints its foreground, row 0 on top. That is Unicode's own
//! numbering of sextant and octant cells (`1 2 / 3 4 / 5 6 / 7 8`, bit k for cell k + 1), and the
//! quadrants follow it (upper left 1, upper right 2, lower left 4, lower right 8).
//!
//! The sets, as Unicode lays them out:
//!
//! - half (1×2): space, `▀`, `▄`, `█` (Block Elements, U+2580–U+259F, in every font).
//! - quadrant (2×2): the half blocks, `▌`, `▐` and the ten quadrants U+2596–U+259F (Block Elements).
//! - sextant (2×3): U+1FB00–U+1FB3B (Symbols for Legacy Computing, Unicode 13) hold patterns 1 to
//!   62 in ascending order, skipping the two that exist already: 21 (left half, `▌`) and 42 (right
//!   half, `▐`); 0 and 63 are the space and `█`.
//! - octant (2×4): U+1CD00–U+1CDE5 (Symbols for Legacy Computing Supplement, Unicode 16) hold 230
//!   patterns in ascending order; the other 26 are characters that existed before and that the
//!   standard names as the octant for them (its chart's cross references): the space, `█`, the
//!   half and quadrant blocks, the upper and lower one- and three-quarter blocks (U+1FB82, U+2582,
//!   U+1FB85, U+2586), the four one-octant corner blocks of U+1CEA0–U+1CEAB, and the middle left and
//!   right one-quarter blocks (U+1FBE6, U+1FBE7). [`OCTANT_REUSED`] lists them.
//!
//! `/work/shared/tools/mosaic.py` (outside the crate) decodes the same sets independently; the tests
//! below pin the tables' anchors (first, last and the reused characters) against the standard.

use super::cells::CellMode;

/// The octant patterns Unicode 16 gives to characters outside U+1CD00–U+1CDE5, as `(pattern, char)`.
pub const OCTANT_REUSED: [(u8, char); 26] = [
    (0b0000_0000, ' '),
    (0b1111_1111, '█'),
    (0b0000_1111, '▀'),
    (0b1111_0000, '▄'),
    (0b0101_0101, '▌'),
    (0b1010_1010, '▐'),
    (0b0000_0101, '▘'),
    (0b0000_1010, '▝'),
    (0b0101_0000, '▖'),
    (0b1010_0000, '▗'),
    (0b1010_0101, '▚'),
    (0b0101_1010, '▞'),
    (0b0101_1111, '▛'),
    (0b1010_1111, '▜'),
    (0b1111_0101, '▙'),
    (0b1111_1010, '▟'),
    (0b0000_0011, '\u{1FB82}'), // UPPER ONE QUARTER BLOCK
    (0b1100_0000, '▂'),         // LOWER ONE QUARTER BLOCK
    (0b0011_1111, '\u{1FB85}'), // UPPER THREE QUARTERS BLOCK
    (0b1111_1100, '▆'),         // LOWER THREE QUARTERS BLOCK
    (0b0000_0001, '\u{1CEA8}'), // LEFT HALF UPPER ONE QUARTER BLOCK
    (0b0000_0010, '\u{1CEAB}'), // RIGHT HALF UPPER ONE QUARTER BLOCK
    (0b0100_0000, '\u{1CEA3}'), // LEFT HALF LOWER ONE QUARTER BLOCK
    (0b1000_0000, '\u{1CEA0}'), // RIGHT HALF LOWER ONE QUARTER BLOCK
    (0b0001_0100, '\u{1FBE6}'), // MIDDLE LEFT ONE QUARTER BLOCK
    (0b0010_1000, '\u{1FBE7}'), // MIDDLE RIGHT ONE QUARTER BLOCK
];

/// Half blocks by pattern (bit 0 the upper pixel).
const HALF: [char; 4] = [' ', '▀', '▄', '█'];

/// Quadrants by pattern (upper left 1, upper right 2, lower left 4, lower right 8).
const QUADRANT: [char; 16] = [
    ' ', '▘', '▝', '▀', '▖', '▌', '▞', '▛', '▗', '▚', '▐', '▜', '▄', '▙', '▟', '█',
];

/// Sextants by pattern (see the module docs).
const SEXTANT: [char; 64] = {
    let mut table = [' '; 64];
    let mut pattern = 1u32;
    while pattern < 63 {
        // Patterns 21 and 42 are skipped in the block, so the ones after them sit lower.
        let skipped = (pattern > 21) as u32 + (pattern > 42) as u32;
        table[pattern as usize] = match pattern {
            21 => '▌',
            42 => '▐',
            _ => match char::from_u32(0x1FB00 + pattern - 1 - skipped) {
                Some(c) => c,
                None => panic!("sextants are valid code points"),
            },
        };
        pattern += 1;
    }
    table[63] = '█';
    table
};

/// Octants by pattern (see the module docs).
const OCTANT: [char; 256] = {
    let mut table = ['\0'; 256];
    let mut i = 0;
    while i < OCTANT_REUSED.len() {
        table[OCTANT_REUSED[i].0 as usize] = OCTANT_REUSED[i].1;
        i += 1;
    }
    let mut next = 0x1CD00;
    let mut pattern = 0;
    while pattern < 256 {
        if table[pattern] == '\0' {
            table[pattern] = match char::from_u32(next) {
                Some(c) => c,
                None => panic!("octants are valid code points"),
            };
            next += 1;
        }
        pattern += 1;
    }
    assert!(next == 0x1CDE6, "230 octants in U+1CD00..=U+1CDE5");
    table
};

/// The glyph that shows `pattern` (bits beyond the mode's pixels are ignored).
#[inline]
pub fn glyph(mode: CellMode, pattern: u8) -> char {
    match mode {
        CellMode::Half => HALF[usize::from(pattern & 0b11)],
        CellMode::Quadrant => QUADRANT[usize::from(pattern & 0b1111)],
        CellMode::Sextant => SEXTANT[usize::from(pattern & 0b11_1111)],
        CellMode::Octant => OCTANT[usize::from(pattern)],
    }
}

/// The pattern `symbol` shows in `mode`, or `None` for a symbol that is not one of its glyphs.
pub fn pattern_of(mode: CellMode, symbol: &str) -> Option<u8> {
    let mut chars = symbol.chars();
    let (Some(c), None) = (chars.next(), chars.next()) else {
        return None;
    };
    let table: &[char] = match mode {
        CellMode::Half => &HALF,
        CellMode::Quadrant => &QUADRANT,
        CellMode::Sextant => &SEXTANT,
        CellMode::Octant => &OCTANT,
    };
    table.iter().position(|&g| g == c).map(|p| p as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_set_has_one_distinct_glyph_per_pattern() {
        for mode in CellMode::ALL {
            let (cols, rows) = mode.pixels_per_cell();
            let patterns = 1u32 << (cols * rows);
            let mut seen = std::collections::HashSet::new();
            for p in 0..patterns {
                let g = glyph(mode, p as u8);
                assert!(seen.insert(g), "{mode:?}: {g:?} twice");
                assert_eq!(pattern_of(mode, &g.to_string()), Some(p as u8), "{mode:?}");
            }
        }
    }

    #[test]
    fn the_tables_sit_where_the_standard_puts_them() {
        // Sextant: 1 is SEXTANT-1, 20 the last before the skipped left half, 22 the next, 62 last.
        assert_eq!(glyph(CellMode::Sextant, 1), '\u{1FB00}');
        assert_eq!(glyph(CellMode::Sextant, 20), '\u{1FB13}');
        assert_eq!(glyph(CellMode::Sextant, 22), '\u{1FB14}');
        assert_eq!(glyph(CellMode::Sextant, 62), '\u{1FB3B}');
        assert_eq!(glyph(CellMode::Sextant, 0b01_0101), '▌');
        // Octant: U+1CD00 is BLOCK OCTANT-3, U+1CD01 OCTANT-23, U+1CD03 OCTANT-4, U+1CDE5
        // OCTANT-2345678 (cells numbered from 1, bit k for cell k + 1).
        assert_eq!(glyph(CellMode::Octant, 0b100), '\u{1CD00}');
        assert_eq!(glyph(CellMode::Octant, 0b110), '\u{1CD01}');
        assert_eq!(glyph(CellMode::Octant, 0b1000), '\u{1CD03}');
        assert_eq!(glyph(CellMode::Octant, 0b1111_1110), '\u{1CDE5}');
        // The reused ones: the quadrant of an octant is the quadrant block.
        assert_eq!(glyph(CellMode::Octant, 0b1010_0000), '▗');
        assert_eq!(glyph(CellMode::Quadrant, 0b1000), '▗');
        assert_eq!(glyph(CellMode::Octant, 0b0000_1111), '▀');
        assert_eq!(glyph(CellMode::Half, 0b01), '▀');
    }

    #[test]
    fn text_is_not_a_pattern() {
        assert_eq!(pattern_of(CellMode::Octant, "x"), None);
        assert_eq!(pattern_of(CellMode::Quadrant, "\u{1FB00}"), None);
        assert_eq!(pattern_of(CellMode::Octant, "▀▀"), None);
        assert_eq!(pattern_of(CellMode::Half, ""), None);
    }
}
