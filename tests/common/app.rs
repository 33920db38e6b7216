//! Driving the App headless with synthetic events.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use glam::{Vec2, Vec3};
use nudge::app::App;

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
