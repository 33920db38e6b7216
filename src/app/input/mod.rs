//! Input: keys and the mouse in, actions out. A key is looked up in the key table ([`keys`]), or
//! in an open menu's layer of it first ([`menu_keys`]), and the [`action::Action`] it asks for is
//! applied in one place; a mouse event becomes an action too ([`mouse`]), one that carries the
//! cell it points at. The mouse is the hand ([`hand`], [`grab`], [`pointer_track`]), picks bodies
//! ([`picking`]) and moves the pointer and the selection ([`selection`]). Keys act on press (and
//! repeat), never on release. Leaving a changed world asks first ([`leaving`]); late terminal replies are
//! dropped before they can pass for keys ([`colour_probe`]).

pub mod action;
pub mod colour_probe;
pub mod grab;
pub mod hand;
pub mod keys;
pub mod leaving;
pub mod menu_keys;
pub mod mouse;
pub mod nudge;
pub mod picking;
pub mod pointer_track;
pub mod selection;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers};
use ratatui::layout::Rect;

use crate::app::App;
use action::Action;

pub use action::FREEZE_PROMPT;
pub use keys::CONTROLS;

/// A key's name as the status bar says it: "F5", "PageUp", "Delete".
fn key_name(code: KeyCode) -> String {
    match code {
        KeyCode::Char(c) => c.to_string(),
        KeyCode::F(n) => format!("F{n}"),
        KeyCode::PageUp => "PageUp".into(),
        KeyCode::PageDown => "PageDown".into(),
        KeyCode::Insert => "Insert".into(),
        KeyCode::Delete => "Delete".into(),
        KeyCode::End => "End".into(),
        KeyCode::Backspace => "Backspace".into(),
        KeyCode::Enter => "Enter".into(),
        other => format!("{other:?}"),
    }
}

impl App {
    /// Reacts to one terminal event.
    pub fn handle_event(&mut self, event: &Event) {
        if self.late_replies.swallow(event, std::time::Instant::now()) {
            return;
        }
        match event {
            Event::Key(key) => self.handle_key(key),
            Event::Mouse(mouse) => self.handle_mouse(mouse),
            Event::Resize(cols, rows) => self.resize(Rect::new(0, 0, *cols, *rows)),
            _ => {}
        }
    }

    /// A key: the open menus and the help read it first (they are modal); otherwise the key table
    /// says what it asks for and [`App::apply`] does it.
    fn handle_key(&mut self, key: &KeyEvent) {
        if key.kind == KeyEventKind::Release {
            return;
        }
        self.dirty = true;
        // A request to leave stands for the very next key only.
        let leave_asked = self.ui.take_leave_asked();
        let action = keys::action_of(key.code, key.modifiers);
        // While a body is held, + and - move it (Ctrl or not), even with the live settings open
        // (where they otherwise change a setting): the hand is what the user is busy with.
        if !self.help.is_open()
            && let Some(Action::Zoom { closer }) = keys::action_of(key.code, KeyModifiers::NONE)
            && self.move_grab(closer)
        {
            return;
        }
        if self.handle_menu_key(key, &key_name(key.code)) {
            return;
        }
        if let Some(panel) = action.filter(|a| a.is_panel())
            && !self.help.is_open()
        {
            self.apply(panel, &key_name(key.code), leave_asked);
            return;
        }
        if action == Some(Action::Interrupt) {
            // The terminal's interrupt: leaves at once, whatever is open.
            self.apply(Action::Interrupt, "c", leave_asked);
            return;
        }
        let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
        if !self.replay_allows(ctrl, action) {
            self.say("replaying: space pauses, . steps, [ ] rewind, q quits");
            return;
        }
        if self.help.is_open() {
            self.apply(menu_keys::help_action(key.code), "", None);
            return;
        }
        match (action, key.code) {
            (Some(action), code) => self.apply(action, &key_name(code), leave_asked),
            // Every key is answered, one that does nothing too; Ctrl with a letter is not that
            // letter.
            (None, KeyCode::Char(c)) if ctrl => {
                self.say(format!("Ctrl+{c}: no such key (? for help)"))
            }
            (None, code) => self.say(format!("{}: no such key (? for help)", key_name(code))),
        }
    }

    /// Esc: closes the topmost thing open (the menus close in `handle_menu_key`): the freeze
    /// prompt, then the inspector. False if nothing was open.
    pub(crate) fn close_topmost(&mut self) -> bool {
        if self.ui.take_freeze_armed() {
            self.say("freeze cancelled");
        } else if self.inspector_open() {
            self.toggle_inspector();
        } else {
            return false;
        }
        true
    }

    /// Arrow keys: turns the camera about its target, and says how to undo it.
    pub(crate) fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.camera.orbit(yaw, pitch);
        self.say("camera turned (c resets it)");
    }

    pub(crate) fn cycle_mode(&mut self, forward: bool) {
        let mode = self.render_options.mode;
        self.render_options.mode = if forward { mode.next() } else { mode.prev() };
        let name = self.render_options.mode.name();
        self.say(format!("render mode: {name}"));
    }

    /// `v`: the next cell mode (half, quadrant, sextant, octant, half ...). The viewport follows
    /// (`App::viewport`), so the next frame renders at the new resolution and picks through it.
    pub(crate) fn cycle_cells(&mut self) {
        self.config.cells = self.config.cells.next();
        let (w, h) = self.config.cells.pixels_per_cell();
        self.say(format!("cells: {} ({w}x{h})", self.config.cells));
    }
}
