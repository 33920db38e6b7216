//! Keys and mouse: what each does. Keys act on press (and repeat), never on release.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use glam::Vec3;
use ratatui::layout::Rect;

use super::App;
use super::hand::{self, HandMode, KEY_FORCE_N};
use super::picking;
use crate::geometry::{Pose, Shape};
use crate::physics::BodyDesc;
use crate::scene::cases::PALETTE;

/// Orbit step per arrow key, radians.
const ORBIT_STEP: f32 = 0.08;
/// Zoom factor per key or wheel notch.
const ZOOM_STEP: f32 = 0.9;

/// Every control, for the help overlay and the README; an empty key continues the action above (the
/// overlay fits 80 columns).
pub const CONTROLS: &[(&str, &str)] = &[
    ("left button", "push the body under the pointer"),
    ("", "(hold to push harder, drag to follow)"),
    ("right button", "pull it toward you"),
    ("middle button", "freeze / unfreeze"),
    (
        "f then click, Ctrl+click",
        "freeze / unfreeze (no middle button)",
    ),
    ("x", "toggle the strong hand (4× force)"),
    ("wheel, + / -", "zoom"),
    ("arrows", "orbit the camera"),
    (
        "w a d, Shift+s / e",
        "nudge the last clicked body (Shift: 4×) / lift it",
    ),
    ("b / s", "spawn a box / sphere under the pointer"),
    ("space / .", "pause / single step"),
    ("m, Tab / Shift+Tab", "next / previous render mode"),
    ("p", "perspective / orthographic"),
    ("g", "gravity on / off"),
    ("r", "reset the scene"),
    ("[ / ]", "rewind / forward 0.25 s (hold to scrub)"),
    ("< / >", "shrink / grow the selected body 10 %"),
    ("Ctrl+S", "save the world as a scene file"),
    ("?", "this help"),
    ("q, Esc, Ctrl+C", "quit"),
];

impl App {
    /// Reacts to one terminal event.
    pub fn handle_event(&mut self, event: &Event) {
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
        let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
        let shift = key.modifiers.contains(KeyModifiers::SHIFT);
        if !self.replay_allows(key) {
            self.say("replaying: space pauses, . steps, [ ] rewind, q quits");
            return;
        }
        if self.show_help && !matches!(key.code, KeyCode::Char('q') | KeyCode::Char('c')) {
            // Any key closes the help overlay.
            self.show_help = false;
            return;
        }
        match key.code {
            KeyCode::Char('c') if ctrl => self.quit = true,
            KeyCode::Char('q') | KeyCode::Esc => self.quit = true,
            KeyCode::Char(' ') => {
                self.paused = !self.paused;
                self.say(if self.paused {
                    "paused (. steps)"
                } else {
                    "running"
                });
            }
            KeyCode::Char('.') => {
                self.paused = true;
                self.single_step = true;
                self.say("single step");
            }
            KeyCode::Char('r') => self.reset(),
            KeyCode::Char('m') | KeyCode::Tab => self.cycle_mode(true),
            KeyCode::BackTab => self.cycle_mode(false),
            KeyCode::Char('p') => self.toggle_projection(),
            KeyCode::Char('g') => self.toggle_gravity(),
            KeyCode::Char('x') => {
                self.strong = !self.strong;
                self.say(if self.strong {
                    "strong hand"
                } else {
                    "gentle hand"
                });
            }
            KeyCode::Char('f') => {
                self.freeze_armed = true;
                self.say("click a body to freeze or unfreeze it");
            }
            KeyCode::Char('?') => self.show_help = true,
            KeyCode::Char('+') | KeyCode::Char('=') => self.camera.zoom(ZOOM_STEP),
            KeyCode::Char('-') | KeyCode::Char('_') => self.camera.zoom(1.0 / ZOOM_STEP),
            KeyCode::Left => self.camera.orbit(-ORBIT_STEP, 0.0),
            KeyCode::Right => self.camera.orbit(ORBIT_STEP, 0.0),
            KeyCode::Up => self.camera.orbit(0.0, ORBIT_STEP),
            KeyCode::Down => self.camera.orbit(0.0, -ORBIT_STEP),
            KeyCode::Char('s') if ctrl => self.save_world(),
            KeyCode::Char('[') => self.rewind_back(),
            KeyCode::Char(']') => self.rewind_forward(),
            KeyCode::Char('<') => self.resize_selected(false),
            KeyCode::Char('>') => self.resize_selected(true),
            KeyCode::Char('b') => self.spawn(Shape::cuboid(Vec3::splat(0.5))),
            KeyCode::Char('s') if !shift => self.spawn(Shape::sphere(0.5)),
            KeyCode::Char(c) if "wasdeWASDE".contains(c) => self.nudge_selected(c, shift),
            _ => {}
        }
    }

    fn cycle_mode(&mut self, forward: bool) {
        let mode = self.render_options.mode;
        self.render_options.mode = if forward { mode.next() } else { mode.prev() };
        let name = self.render_options.mode.name();
        self.say(format!("render mode: {name}"));
    }

    /// WASD push the selected body along the camera's horizontal forward/right; E lifts it.
    fn nudge_selected(&mut self, key: char, shift: bool) {
        let Some(id) = self.selected else {
            self.say("click a body first to select it");
            return;
        };
        let basis = self.camera.basis();
        let forward = Vec3::new(basis.forward.x, 0.0, basis.forward.z).normalize_or(Vec3::Z);
        let right = Vec3::new(basis.right.x, 0.0, basis.right.z).normalize_or(Vec3::X);
        let mass = self.world.body(id).mass();
        let direction = match key.to_ascii_lowercase() {
            'w' => forward,
            's' => -forward,
            'a' => -right,
            'd' => right,
            _ => Vec3::Y * (1.0 + 9.81 * mass / KEY_FORCE_N),
        };
        let strong = shift || key.is_ascii_uppercase();
        let force = direction * KEY_FORCE_N * if strong { hand::STRONG_FACTOR } else { 1.0 };
        self.hand.nudge(id, force);
    }

    fn handle_mouse(&mut self, mouse: &MouseEvent) {
        let cell = (mouse.column, mouse.row);
        self.pointer = Some(cell);
        if self.replay.is_some() {
            // A replay's world changes only as recorded.
            return;
        }
        let ctrl = mouse.modifiers.contains(KeyModifiers::CONTROL);
        match mouse.kind {
            MouseEventKind::Down(button) => {
                self.dirty = true;
                let freeze = button == MouseButton::Middle || ctrl || self.freeze_armed;
                self.freeze_armed = false;
                let Some(pick) = self.pick_at(cell) else {
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
                        format!("{name} is frozen (middle-click, Ctrl+click or f to unfreeze)")
                    });
                    return;
                }
                let mode = if button == MouseButton::Right {
                    HandMode::Pull
                } else {
                    HandMode::Push
                };
                let strong = self.strong || mouse.modifiers.contains(KeyModifiers::SHIFT);
                self.hand.press(mode, cell, strong);
                let verb = if mode == HandMode::Push {
                    "pushing"
                } else {
                    "pulling"
                };
                let mass = self.world.body(pick.body).mass();
                let (from, to) = (
                    hand::hand_force(mass, 0.0, strong),
                    hand::hand_force(mass, f32::INFINITY, strong),
                );
                self.say(format!("{verb} {name} ({from:.0} N, {to:.0} N held)"));
            }
            MouseEventKind::Drag(_) => {
                self.hand.drag(cell);
                self.update_highlight(cell);
            }
            MouseEventKind::Up(_) => {
                self.hand.release();
                self.dirty = true;
            }
            MouseEventKind::Moved => self.update_highlight(cell),
            MouseEventKind::ScrollUp => {
                self.camera.zoom(ZOOM_STEP);
                self.dirty = true;
            }
            MouseEventKind::ScrollDown => {
                self.camera.zoom(1.0 / ZOOM_STEP);
                self.dirty = true;
            }
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

    /// Drops a new body onto whatever is under the pointer (or in front of the camera).
    fn spawn(&mut self, shape: Shape) {
        let size = shape.bounding_radius();
        let position = match self.pointer.and_then(|cell| self.pick_at(cell)) {
            Some(pick) => pick.hit.point + pick.hit.normal * (size + 0.05) + Vec3::Y * size,
            None => self.camera.target + Vec3::Y * 2.0,
        };
        // The representable range holds for the sandbox as for files (`physics::limits`).
        if self.world.len() >= crate::physics::limits::MAX_BODIES {
            let most = crate::physics::limits::MAX_BODIES;
            self.say(format!(
                "not spawned: the world holds {most} bodies at most"
            ));
            return;
        }
        if let Err(why) = crate::physics::limits::check_position("spawn position", position) {
            self.say(format!("not spawned: {why}"));
            return;
        }
        let color = PALETTE[self.world.len() % PALETTE.len()];
        let desc = BodyDesc::dynamic(shape, Pose::from_position(position), shape.volume());
        let id = self.world.add_body(desc);
        // After a rewind the looks of bodies of the cut-off future are still there.
        self.looks.truncate(id.index());
        self.looks.push(super::look::BodyLook {
            color,
            scenery: false,
        });
        self.selected = Some(id);
        let name = self.body_name(id);
        self.say(format!("spawned {name}"));
    }
}
