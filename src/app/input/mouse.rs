//! The mouse: a click pushes, pulls, grabs or freezes the body under the pointer (or is answered
//! "nothing there"), a drag follows, the wheel zooms or moves a held body; motion highlights the
//! body under the pointer. Kept apart from the keys because it reads where it points, which the
//! key table cannot say.

use crossterm::event::{KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

use super::action::ZOOM_STEP;
use super::hand::{self, HandMode};
use super::picking;
use crate::app::App;

impl App {
    pub(crate) fn handle_mouse(&mut self, mouse: &MouseEvent) {
        let cell = (mouse.column, mouse.row);
        self.selection.point_at(cell);
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
                    self.selection.hover(None);
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
                self.selection.click(pick.body);
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
        if self.selection.hover(under) {
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
