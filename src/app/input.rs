//! Keys and mouse: what each does. Keys act on press (and repeat), never on release.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use glam::Vec3;
use ratatui::layout::Rect;

use super::App;
use super::hand::{self, HandMode};
use super::leaving::Leave;
use super::picking;
use crate::geometry::Shape;

/// Orbit step per arrow key, radians.
const ORBIT_STEP: f32 = 0.08;
/// Zoom factor per key or wheel notch.
const ZOOM_STEP: f32 = 0.9;

/// What the status bar says while `f` waits for a click; a user without a middle button freezes
/// this way.
pub const FREEZE_PROMPT: &str = "click a body to freeze or unfreeze it (Esc cancels)";

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

/// Every control, for the help overlay and the README; an empty key continues the action above (the
/// overlay fits 80 columns).
pub const CONTROLS: &[(&str, &str)] = &[
    (
        "left / right button",
        "push / pull the body under the pointer",
    ),
    ("", "(hold to keep pushing, drag to follow)"),
    ("h", "left button: grab and drag / push"),
    // Ctrl+click never reaches the app in a stock xterm, which opens its own menu.
    (
        "middle, f then click",
        "freeze / unfreeze (Ctrl+click: not xterm)",
    ),
    ("x", "strong hand on / off (4× force)"),
    ("wheel, + / -", "zoom (grabbing: hold it nearer / farther)"),
    ("arrows / c, Home", "orbit the camera / reset it"),
    (
        "w a d, Shift+s / e",
        "nudge the last clicked body / lift it",
    ),
    ("b / s", "drop a box / sphere where the pointer is"),
    ("space / .", "pause / single step"),
    // Sharing a line: the overlay fits 80 × 24 without scrolling.
    (
        "m, Tab / Shift+Tab; v",
        "next / previous render mode; cell mode",
    ),
    ("p / g", "perspective ↔ orthographic / gravity on, off"),
    ("r", "reset the bodies (the camera stays)"),
    ("n / N", "next / previous built-in scene"),
    ("[ / ]", "rewind / forward 0.25 s (hold to scrub)"),
    ("< / >", "shrink / grow the selected body 10 %"),
    ("Ctrl+S", "save the world as a scene file"),
    ("o then 1-8, i, t", "overlays, inspector, live settings"),
    ("?, F1 / Ctrl+L", "this help / redraw the screen"),
    ("Esc", "close the open panel, else quit"),
    (
        "q / Ctrl+C / Ctrl+Z",
        "quit (asks if changed) / at once / suspend",
    ),
];

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

    fn handle_key(&mut self, key: &KeyEvent) {
        if key.kind == KeyEventKind::Release {
            return;
        }
        self.dirty = true;
        // A request to leave stands for the very next key only.
        let leave_asked = self.ui.leave_asked.take();
        let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
        let shift = key.modifiers.contains(KeyModifiers::SHIFT);
        // While a body is held, + and - move it, even with the live settings open (where they
        // otherwise change a setting): the hand is what the user is busy with.
        let depth_key =
            !self.ui.show_help && matches!(key.code, KeyCode::Char('+' | '=' | '-' | '_'));
        if depth_key && self.move_grab(matches!(key.code, KeyCode::Char('+' | '='))) {
            return;
        }
        if self.handle_inspection_key(key) {
            return;
        }
        if ctrl && key.code == KeyCode::Char('c') {
            // The terminal's interrupt: leaves at once, whatever is open.
            self.quit = true;
            return;
        }
        if !self.replay_allows(key) {
            self.say("replaying: space pauses, . steps, [ ] rewind, q quits");
            return;
        }
        if self.ui.show_help {
            let rows = match key.code {
                KeyCode::Up => Some(-1),
                KeyCode::Down => Some(1),
                KeyCode::PageUp => Some(-8),
                KeyCode::PageDown | KeyCode::Char(' ') => Some(8),
                _ => None,
            };
            if let Some(rows) = rows
                && self.scroll_help(rows)
            {
                return;
            }
            // Any other key closes the help overlay, q and Esc too: the box says so.
            self.close_help();
            return;
        }
        match key.code {
            KeyCode::Char('l') if ctrl => {
                self.request_repaint();
                self.say("screen redrawn");
            }
            KeyCode::Char('s') if ctrl => self.save_world(),
            // Ctrl with any other letter is not that letter: Ctrl+R reset the world, Ctrl+D (a
            // shell's "end") nudged the body.
            KeyCode::Char(c) if ctrl => self.say(format!("Ctrl+{c}: no such key (? for help)")),
            KeyCode::Char('c') | KeyCode::Home => self.reset_camera(),
            KeyCode::Char('n') => self.leave(Leave::Scene { forward: true }, leave_asked, "n"),
            KeyCode::Char('N') => self.leave(Leave::Scene { forward: false }, leave_asked, "N"),
            KeyCode::F(1) => self.open_help(),
            KeyCode::Esc if self.close_topmost() => {}
            KeyCode::Esc => self.leave(Leave::Quit, leave_asked, "Esc"),
            KeyCode::Char('q') => self.leave(Leave::Quit, leave_asked, "q"),
            KeyCode::Char(' ') => {
                self.ui.paused = !self.ui.paused;
                self.say(if self.ui.paused {
                    "paused (. steps)"
                } else {
                    "running"
                });
            }
            KeyCode::Char('.') => {
                self.ui.paused = true;
                self.ui.single_step = true;
                self.say("single step");
            }
            KeyCode::Char('r') => self.reset(),
            KeyCode::Char('m') | KeyCode::Tab => self.cycle_mode(true),
            KeyCode::BackTab => self.cycle_mode(false),
            KeyCode::Char('p') => self.toggle_projection(),
            KeyCode::Char('v') => self.cycle_cells(),
            KeyCode::Char('g') => self.toggle_gravity(),
            KeyCode::Char('h') => self.toggle_grab_mode(),
            KeyCode::Char('x') => {
                self.ui.strong = !self.ui.strong;
                self.say(if self.ui.strong {
                    "strong hand"
                } else {
                    "gentle hand"
                });
            }
            KeyCode::Char('f') => {
                self.ui.freeze_armed = true;
                self.say(FREEZE_PROMPT);
            }
            KeyCode::Char('?') => self.open_help(),
            KeyCode::Char('+') | KeyCode::Char('=') => self.zoom(ZOOM_STEP),
            KeyCode::Char('-') | KeyCode::Char('_') => self.zoom(1.0 / ZOOM_STEP),
            KeyCode::Left => self.orbit(-ORBIT_STEP, 0.0),
            KeyCode::Right => self.orbit(ORBIT_STEP, 0.0),
            KeyCode::Up => self.orbit(0.0, ORBIT_STEP),
            KeyCode::Down => self.orbit(0.0, -ORBIT_STEP),
            KeyCode::Char('[') => self.rewind_back(),
            KeyCode::Char(']') => self.rewind_forward(),
            KeyCode::Char('<') => self.resize_selected(false),
            KeyCode::Char('>') => self.resize_selected(true),
            KeyCode::Char('b') => self.spawn(Shape::cuboid(Vec3::splat(0.5))),
            KeyCode::Char('s') if !shift => self.spawn(Shape::sphere(0.5)),
            KeyCode::Char(c) if "wasdeWASDE".contains(c) => self.nudge_selected(c),
            // Every key is answered, one that does nothing too.
            code => self.say(format!("{}: no such key (? for help)", key_name(code))),
        }
    }

    /// Esc: closes the topmost thing open (the menus close in `handle_inspection_key`): the freeze
    /// prompt, then the inspector. False if nothing was open.
    fn close_topmost(&mut self) -> bool {
        if std::mem::take(&mut self.ui.freeze_armed) {
            self.say("freeze cancelled");
        } else if self.inspect.panel_open {
            self.toggle_inspector();
        } else {
            return false;
        }
        true
    }

    fn open_help(&mut self) {
        self.ui.show_help = true;
        self.ui.help_scroll = 0;
    }

    fn close_help(&mut self) {
        self.ui.show_help = false;
        self.say("help closed");
    }

    /// Scrolls the help overlay by `rows` if it does not show every row; false if it does (the key
    /// or notch then closes it, as any other).
    fn scroll_help(&mut self, rows: i32) -> bool {
        let max = super::help::HelpOverlay::max_scroll(super::view::viewport_area(self.area));
        if max == 0 {
            return false;
        }
        let scroll = (i32::from(self.ui.help_scroll) + rows).clamp(0, i32::from(max));
        self.ui.help_scroll = scroll as u16;
        self.dirty = true;
        true
    }

    /// Arrow keys: turns the camera about its target, and says how to undo it.
    fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.camera.orbit(yaw, pitch);
        self.say("camera turned (c resets it)");
    }

    fn cycle_mode(&mut self, forward: bool) {
        let mode = self.render_options.mode;
        self.render_options.mode = if forward { mode.next() } else { mode.prev() };
        let name = self.render_options.mode.name();
        self.say(format!("render mode: {name}"));
    }

    /// `v`: the next cell mode (half, quadrant, sextant, octant, half ...). The viewport follows
    /// (`App::viewport`), so the next frame renders at the new resolution and picks through it.
    fn cycle_cells(&mut self) {
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
        if self.ui.show_help {
            // The overlay hides the bodies under it: a click (or a scroll) closes it and does
            // nothing else.
            let scrolled = match mouse.kind {
                MouseEventKind::ScrollUp => self.scroll_help(-3),
                MouseEventKind::ScrollDown => self.scroll_help(3),
                _ => false,
            };
            if !scrolled
                && matches!(
                    mouse.kind,
                    MouseEventKind::Down(_) | MouseEventKind::ScrollUp | MouseEventKind::ScrollDown
                )
            {
                self.close_help();
            }
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
                self.ui.leave_asked = None;
                let armed = std::mem::take(&mut self.ui.freeze_armed);
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
                let strong = self.ui.strong || mouse.modifiers.contains(KeyModifiers::SHIFT);
                if mode == HandMode::Push && self.ui.grab_mode {
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
