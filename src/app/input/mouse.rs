//! The mouse: a click pushes, pulls, grabs or freezes the body under the pointer (or is answered
//! "nothing there"), a drag follows, the wheel zooms or moves a held body; motion highlights the
//! body under the pointer. [`action_of`] turns an event into an [`Action`] that carries where it
//! points (which the key table cannot say), and `App::apply` does it as it does a key's; what
//! the hand holds stays with the hand ([`super::hand`], [`super::grab`]).

use crossterm::event::{KeyModifiers, MouseButton, MouseEvent, MouseEventKind};

use super::action::Action;
use super::hand::{self, HandMode};
use super::picking;
use crate::app::App;

/// What a mouse button asks of the body under it, before `h` (grab) and `f` (the next click
/// freezes) have their say.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Press {
    /// The left button.
    Push,
    /// The right button.
    Pull,
    /// The middle button, or any with Ctrl.
    Freeze,
}

/// What a mouse event asks for; `None` for one the app has no use for (a sideways scroll).
pub fn action_of(mouse: &MouseEvent) -> Option<Action> {
    let cell = (mouse.column, mouse.row);
    Some(match mouse.kind {
        MouseEventKind::Down(button) => {
            let press = if button == MouseButton::Middle
                || mouse.modifiers.contains(KeyModifiers::CONTROL)
            {
                Press::Freeze
            } else if button == MouseButton::Right {
                Press::Pull
            } else {
                Press::Push
            };
            Action::Click {
                cell,
                press,
                strong: mouse.modifiers.contains(KeyModifiers::SHIFT),
            }
        }
        MouseEventKind::Drag(_) => Action::Drag { cell },
        MouseEventKind::Up(_) => Action::Release,
        MouseEventKind::Moved => Action::Hover { cell },
        MouseEventKind::ScrollUp => Action::Zoom { closer: true },
        MouseEventKind::ScrollDown => Action::Zoom { closer: false },
        _ => return None,
    })
}

impl App {
    /// A mouse event: a replay ignores it, the help and the menus drawn over the view take it
    /// first (they hide what is under them); otherwise it is an action like a key's.
    pub(crate) fn handle_mouse(&mut self, mouse: &MouseEvent) {
        let cell = (mouse.column, mouse.row);
        self.selection.point_at(cell);
        if self.replay.is_some() {
            // A replay's world changes only as recorded.
            return;
        }
        if self.help.is_open() {
            if let Some(action) = super::menu_keys::help_mouse_action(mouse.kind) {
                self.apply(action, "", None);
            }
            return;
        }
        if let MouseEventKind::Down(_) = mouse.kind
            && let Some(hint) = self.popup_under(cell)
        {
            self.say(hint);
            return;
        }
        if let Some(action) = action_of(mouse) {
            self.apply(action, "", None);
        }
    }

    /// A click on `cell`: freezes the body there (the middle button, Ctrl, or `f` armed), grabs it
    /// (`h`), or pushes or pulls it; every click is answered, a miss or scenery too.
    pub(crate) fn click(&mut self, cell: (u16, u16), press: Press, shift: bool) {
        self.dirty = true;
        // A click is not the second press a request to leave waits for.
        self.ui.take_leave_asked();
        let armed = self.ui.take_freeze_armed();
        let freeze = press == Press::Freeze || armed;
        let Some(pick) = self.pick_at(cell) else {
            // The pointer is over nothing now (--hover named the body it was last over).
            self.selection.hover(None);
            if hand::cell_in(self.viewport_area(), cell).is_some() {
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
        let mode = if press == Press::Pull {
            HandMode::Pull
        } else {
            HandMode::Push
        };
        let strong = self.ui.strong() || shift;
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

    /// A drag: the hand follows the pointer.
    pub(crate) fn drag_hand(&mut self, cell: (u16, u16)) {
        self.hand.drag(cell);
        self.update_highlight(cell);
    }

    /// Motion without a button.
    pub(crate) fn hover(&mut self, cell: (u16, u16)) {
        // The button came up where the terminal could not see it.
        if self.hand.grab().is_some() {
            self.release_hand();
        }
        self.update_highlight(cell);
    }

    fn update_highlight(&mut self, cell: (u16, u16)) {
        let under = self.pick_at(cell).map(|p| p.body);
        if self.selection.hover(under) {
            self.dirty = true;
        }
    }

    /// The body under an absolute terminal cell, if the cell is in the 3D view.
    pub(crate) fn pick_at(&self, cell: (u16, u16)) -> Option<picking::Pick> {
        self.screen_view().pick(&self.world, cell)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn down(button: MouseButton, modifiers: KeyModifiers) -> Option<Action> {
        action_of(&MouseEvent {
            kind: MouseEventKind::Down(button),
            column: 3,
            row: 4,
            modifiers,
        })
    }

    #[test]
    fn the_middle_button_or_ctrl_freezes_the_right_pulls_and_shift_is_strong() {
        let click = |press, strong| {
            Some(Action::Click {
                cell: (3, 4),
                press,
                strong,
            })
        };
        let none = KeyModifiers::NONE;
        assert_eq!(down(MouseButton::Left, none), click(Press::Push, false));
        assert_eq!(down(MouseButton::Right, none), click(Press::Pull, false));
        assert_eq!(down(MouseButton::Middle, none), click(Press::Freeze, false));
        assert_eq!(
            down(MouseButton::Right, KeyModifiers::CONTROL),
            click(Press::Freeze, false)
        );
        assert_eq!(
            down(MouseButton::Left, KeyModifiers::SHIFT),
            click(Press::Push, true)
        );
    }
}
