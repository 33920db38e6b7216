//! Every cell the app draws sets its background (issue 28): the inspector's energy chart was drawn
//! on the terminal's default background, a white box in an xterm with a white default.

use crate::common;

use common::app::char_key;
use nudge::app::{App, AppConfig};
use nudge::scene;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;

/// The cells of a `cols`×`rows` frame left on the terminal's default background.
fn default_background_cells(app: &mut App, cols: u16, rows: u16) -> Vec<(u16, u16, String)> {
    let area = Rect::new(0, 0, cols, rows);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    let mut cells = Vec::new();
    for y in 0..rows {
        for x in 0..cols {
            let cell = &buf[(x, y)];
            if cell.bg == Color::Reset {
                cells.push((x, y, cell.symbol().to_string()));
            }
        }
    }
    cells
}

#[test]
fn the_inspector_its_charts_the_menus_and_the_help_set_every_background() {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load("default").unwrap(), config);
    let (cols, rows) = (140, 44);
    app.resize(Rect::new(0, 0, cols, rows));
    app.handle_event(&char_key('i'));
    // A few seconds of history, so the charts draw their lines.
    for _ in 0..180 {
        app.step_physics();
    }
    let missing = default_background_cells(&mut app, cols, rows);
    assert!(
        missing.is_empty(),
        "inspector: {:?}",
        &missing[..missing.len().min(20)]
    );
    for key in ['o', 't', '?'] {
        app.handle_event(&char_key(key));
        let missing = default_background_cells(&mut app, cols, rows);
        assert!(
            missing.is_empty(),
            "{key}: {:?}",
            &missing[..missing.len().min(20)]
        );
    }
}
