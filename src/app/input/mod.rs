//! Input: keys and the mouse in, actions out. A key is looked up in the key table ([`keys`]) and
//! the [`action::Action`] it asks for is applied in one place; the mouse is the hand ([`hand`],
//! [`grab`], [`pointer_track`]) and picks bodies ([`picking`]). Keys act on press (and repeat),
//! never on release. Leaving a changed world asks first ([`leaving`]); late terminal replies are
//! dropped before they can pass for keys ([`colour_probe`]).

pub mod action;
pub mod colour_probe;
pub mod grab;
pub mod hand;
pub mod keys;
pub mod leaving;
pub mod nudge;
pub mod picking;
pub mod pointer_track;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::layout::Rect;

use crate::app::App;
use action::{Action, ZOOM_STEP};
use hand::HandMode;

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
        if self.handle_menu_key(key) {
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
            self.help_key(key.code);
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

    fn handle_mouse(&mut self, mouse: &MouseEvent) {
        let cell = (mouse.column, mouse.row);
        self.pointer = Some(cell);
        if self.replay.is_some() {
            // A replay's world changes only as recorded.
            return;
        }
        let ctrl = mouse.modifiers.contains(KeyModifiers::CONTROL);
        if self.help.is_open() {
            self.help_mouse(mouse.kind);
            return;
        }
        if let MouseEventKind::Down(_) = mouse.kind
            && let Some(hint) = self.popup_under(cell)
        {
            self.say(hint);
            return;
        }
        match mouse.kind {
            MouseEventKind::Down(button) => {
                self.dirty = true;
                // A click is not the second press a request to leave waits for.
                self.ui.take_leave_asked();
                let armed = self.ui.take_freeze_armed();
                let freeze = button == MouseButton::Middle || ctrl || armed;
                let Some(pick) = self.pick_at(cell) else {
                    // The pointer is over nothing now (--hover named the body it was last over).
                    self.highlighted = None;
                    if hand::cell_in(self.viewport_area(), cell).is_some() {
                        // Every click is answered, a miss too.
                        self.say(if armed {
                            "freeze cancelled (nothing there)"
                        } else {
                            "nothing there"
                        });
                    }
                    return;
                };
                self.selected = Some(pick.body);
                self.highlighted = Some(pick.body);
                if freeze {
                    self.toggle_frozen(pick.body);
                    return;
                }
                let name = self.body_name(pick.body);
                if self.world.body(pick.body).is_static() {
                    let scenery = self.looks.get(pick.body.index()).is_some_and(|l| l.scenery);
                    self.say(if scenery {
                        format!("{name} is part of the scenery")
                    } else {
                        // Ctrl+click never reaches the app in a stock xterm: name what works everywhere.
                        format!("{name} is frozen (middle button, or f then click, unfreezes)")
                    });
                    return;
                }
                let mode = if button == MouseButton::Right {
                    HandMode::Pull
                } else {
                    HandMode::Push
                };
                let strong = self.ui.strong() || mouse.modifiers.contains(KeyModifiers::SHIFT);
                if mode == HandMode::Push && self.ui.grab_mode() {
                    self.start_grab(&pick, cell, strong);
                    return;
                }
                self.hand.press(mode, cell, strong);
                let verb = if mode == HandMode::Push {
                    "pushing"
                } else {
                    "pulling"
                };
                let (speed, max) = hand::push_limits(self.world.body(pick.body).mass(), strong);
                self.say(format!(
                    "{verb} {name} (to {speed:.1} m/s, at most {max:.0} N)"
                ));
            }
            MouseEventKind::Drag(_) => {
                self.hand.drag(cell);
                self.update_highlight(cell);
            }
            MouseEventKind::Up(_) => self.release_hand(),
            MouseEventKind::Moved => {
                // Motion without a button: the button came up where the terminal could not see it.
                if self.hand.grab().is_some() {
                    self.release_hand();
                }
                self.update_highlight(cell);
            }
            MouseEventKind::ScrollUp if self.move_grab(true) => {}
            MouseEventKind::ScrollDown if self.move_grab(false) => {}
            MouseEventKind::ScrollUp => self.zoom(ZOOM_STEP),
            MouseEventKind::ScrollDown => self.zoom(1.0 / ZOOM_STEP),
            _ => {}
        }
    }

    fn update_highlight(&mut self, cell: (u16, u16)) {
        let under = self.pick_at(cell).map(|p| p.body);
        if under != self.highlighted {
            self.highlighted = under;
            self.dirty = true;
        }
    }

    /// The body under an absolute terminal cell, if the cell is in the 3D view.
    pub(crate) fn pick_at(&self, cell: (u16, u16)) -> Option<picking::Pick> {
        let (col, row) = hand::cell_in(self.viewport_area(), cell)?;
        picking::pick_cell(&self.world, &self.camera, &self.viewport(), col, row)
    }

    fn toggle_frozen(&mut self, id: crate::physics::BodyId) {
        let looks_scenery = self.looks.get(id.index()).is_some_and(|l| l.scenery);
        if looks_scenery {
            self.say(format!("{} is part of the scenery", self.body_name(id)));
            return;
        }
        let frozen = !self.world.body(id).is_static();
        self.world.set_static(id, frozen);
        let verb = if frozen { "froze" } else { "unfroze" };
        self.say(format!("{verb} {}", self.body_name(id)));
    }
}
