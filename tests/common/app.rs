//! Driving the App headless with synthetic events.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseEvent, MouseEventKind};
use glam::{Vec2, Vec3};
use nudge::app::{App, AppConfig};
use nudge::scene;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// A key press without modifiers.
pub fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

/// The terminal cell over which world point `p` is drawn.
pub fn cell_of(app: &App, p: Vec3) -> (u16, u16) {
    let viewport = app.viewport();
    let clip = app.camera().clip_from_world(viewport.aspect()) * p.extend(1.0);
    let ndc = Vec2::new(clip.x / clip.w, clip.y / clip.w);
    let cell = viewport.cell_from_pixel(viewport.pixel_from_ndc(ndc));
    (cell.x as u16, cell.y as u16)
}

/// A character key press without modifiers.
pub fn char_key(c: char) -> Event {
    key(KeyCode::Char(c))
}

/// The sandbox on built-in scene `name`, laid out for a `cols × rows` terminal, without
/// supersampling (so frames are cheap and pixels are the cells' own).
pub fn app_on(name: &str, cols: u16, rows: u16) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load(name).unwrap(), config);
    app.resize(Rect::new(0, 0, cols, rows));
    app
}

/// The app drawn into a `cols × rows` buffer, row by row.
pub fn screen(app: &mut App, cols: u16, rows: u16) -> Vec<String> {
    let area = Rect::new(0, 0, cols, rows);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    (0..rows)
        .map(|y| {
            (0..cols)
                .map(|x| buf[(x, y)].symbol().to_string())
                .collect()
        })
        .collect()
}

/// The status bar (the bottom row), trailing blanks trimmed.
pub fn status_line(app: &mut App, cols: u16, rows: u16) -> String {
    let screen = screen(app, cols, rows);
    screen
        .last()
        .map_or(String::new(), |line| line.trim_end().to_string())
}

/// A mouse event without modifiers at `cell` (column, row).
pub fn mouse(kind: MouseEventKind, cell: (u16, u16)) -> Event {
    Event::Mouse(MouseEvent {
        kind,
        column: cell.0,
        row: cell.1,
        modifiers: KeyModifiers::NONE,
    })
}
