//! The shape of a terminal cell: its height divided by its width (dimensionless, > 0).
//!
//! The rasterizer needs it so a sphere stays round: a half-block pixel is one cell wide and half a
//! cell high, so its aspect (height / width) is `cell_aspect / 2`. Typical fonts give 2.0–2.4.
//!
//! Sources, first usable wins:
//! 1. an explicit setting (`--cell-aspect` / config), if finite and within [`MIN_CELL_ASPECT`,
//!    `MAX_CELL_ASPECT`];
//! 2. the terminal's reported pixel size (`TIOCGWINSZ`: many terminals fill it in, ssh forwards
//!    it, some report 0): `(height_px / rows) / (width_px / columns)`, if all four are non-zero and
//!    the ratio is plausible (same range);
//! 3. [`DEFAULT_CELL_ASPECT`].

use crossterm::terminal::WindowSize;

/// The usual cell shape: twice as high as wide.
pub const DEFAULT_CELL_ASPECT: f32 = 2.0;
/// Smallest accepted cell aspect; anything flatter is a misreport or a typo.
pub const MIN_CELL_ASPECT: f32 = 0.5;
/// Largest accepted cell aspect; anything taller is a misreport or a typo.
pub const MAX_CELL_ASPECT: f32 = 4.0;

/// `aspect` if it is a cell aspect a real terminal could have.
pub fn plausible(aspect: f32) -> Option<f32> {
    (aspect.is_finite() && (MIN_CELL_ASPECT..=MAX_CELL_ASPECT).contains(&aspect)).then_some(aspect)
}

/// The cell aspect from the terminal's reported size, if it reports pixels and the result is
/// plausible.
pub fn reported_cell_aspect(window_size: &WindowSize) -> Option<f32> {
    let WindowSize {
        rows,
        columns,
        width,
        height,
    } = *window_size;
    if rows == 0 || columns == 0 || width == 0 || height == 0 {
        return None;
    }
    let cell_h_px = f32::from(height) / f32::from(rows);
    let cell_w_px = f32::from(width) / f32::from(columns);
    plausible(cell_h_px / cell_w_px)
}

/// The cell aspect to use: `setting` if valid, else the reported one, else
/// [`DEFAULT_CELL_ASPECT`] (see the module docs). Always finite and within
/// [`MIN_CELL_ASPECT`, `MAX_CELL_ASPECT`].
pub fn cell_aspect(window_size: Option<WindowSize>, setting: Option<f32>) -> f32 {
    setting
        .and_then(plausible)
        .or_else(|| window_size.as_ref().and_then(reported_cell_aspect))
        .unwrap_or(DEFAULT_CELL_ASPECT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn size(columns: u16, rows: u16, width: u16, height: u16) -> Option<WindowSize> {
        Some(WindowSize {
            rows,
            columns,
            width,
            height,
        })
    }

    #[test]
    fn an_explicit_setting_wins() {
        assert_eq!(cell_aspect(size(80, 24, 800, 480), Some(2.3)), 2.3);
        assert_eq!(cell_aspect(None, Some(1.0)), 1.0);
    }

    #[test]
    fn reported_pixels_give_the_cell_shape() {
        // 80×24 cells of 9×20 px.
        assert_eq!(cell_aspect(size(80, 24, 720, 480), None), 20.0 / 9.0);
        // 100×50 cells of 8×16 px.
        assert_eq!(cell_aspect(size(100, 50, 800, 800), None), 2.0);
    }

    #[test]
    fn missing_or_zero_pixel_sizes_fall_back_to_two() {
        assert_eq!(cell_aspect(None, None), DEFAULT_CELL_ASPECT);
        assert_eq!(cell_aspect(size(80, 24, 0, 0), None), 2.0);
        assert_eq!(cell_aspect(size(80, 24, 720, 0), None), 2.0);
        assert_eq!(cell_aspect(size(0, 0, 720, 480), None), 2.0);
    }

    #[test]
    fn invalid_settings_are_ignored() {
        for bad in [f32::NAN, f32::INFINITY, 0.0, -2.0, 0.1, 50.0] {
            assert_eq!(cell_aspect(size(80, 24, 720, 480), Some(bad)), 20.0 / 9.0);
            assert_eq!(cell_aspect(None, Some(bad)), DEFAULT_CELL_ASPECT, "{bad}");
        }
    }

    #[test]
    fn implausible_reports_are_ignored() {
        // 1 px per column, 100 px per row: a broken report, not a font.
        assert_eq!(
            cell_aspect(size(80, 24, 80, 2400), None),
            DEFAULT_CELL_ASPECT
        );
        assert_eq!(
            cell_aspect(size(80, 24, 8000, 24), None),
            DEFAULT_CELL_ASPECT
        );
    }
}
