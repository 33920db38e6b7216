//! The modal layers of the key table: while the help, the live settings or the overlay menu is
//! open, its keys are looked up here first and ask for their own [`Action`]s, which [`App::apply`]
//! does like any other. The help takes every key and click (it hides what is under it); a key the
//! menus lack closes them and falls through to the main table ([`crate::app::input::keys`]), so
//! `o` from the settings switches to the overlay menu.
//!
//! [`App::apply`]: crate::app::App

use crossterm::event::{KeyCode, MouseEventKind};

use crate::app::input::action::Action;
use crate::app::panels::overlays::OverlayKind;

/// The help's keys: ↑↓, PageUp/PageDown and Space scroll it where it does not fit; any other key
/// closes it, q and Esc too (the box says so), and does nothing else.
const HELP: &[(KeyCode, Action)] = &[
    (KeyCode::Up, Action::ScrollHelp { rows: -1 }),
    (KeyCode::Down, Action::ScrollHelp { rows: 1 }),
    (KeyCode::PageUp, Action::ScrollHelp { rows: -8 }),
    (KeyCode::PageDown, Action::ScrollHelp { rows: 8 }),
    (KeyCode::Char(' '), Action::ScrollHelp { rows: 8 }),
];

/// What `code` asks for while the help is open.
pub fn help_action(code: KeyCode) -> Action {
    look_up(HELP, code).unwrap_or(Action::CloseHelp)
}

/// What the mouse asks for while the help is open: the wheel scrolls it, a click closes it (and
/// does nothing else); the pointer's moves do nothing.
pub fn help_mouse_action(kind: MouseEventKind) -> Option<Action> {
    match kind {
        MouseEventKind::ScrollUp => Some(Action::ScrollHelp { rows: -3 }),
        MouseEventKind::ScrollDown => Some(Action::ScrollHelp { rows: 3 }),
        MouseEventKind::Down(_) => Some(Action::CloseHelp),
        _ => None,
    }
}

/// The live settings' keys: ↑ ↓ choose a row, ← → (or - +, Enter) change it, `t` or Esc close.
const SETTINGS: &[(KeyCode, Action)] = &[
    (KeyCode::Up, Action::SettingsRow { down: false }),
    (KeyCode::Down, Action::SettingsRow { down: true }),
    (KeyCode::Left, Action::ChangeSetting { up: false }),
    (KeyCode::Char('-'), Action::ChangeSetting { up: false }),
    (KeyCode::Char('_'), Action::ChangeSetting { up: false }),
    (KeyCode::Right, Action::ChangeSetting { up: true }),
    (KeyCode::Char('+'), Action::ChangeSetting { up: true }),
    (KeyCode::Char('='), Action::ChangeSetting { up: true }),
    (KeyCode::Enter, Action::ChangeSetting { up: true }),
    (KeyCode::Char('t'), Action::CloseSettings),
    (KeyCode::Esc, Action::CloseSettings),
];

/// The overlay menu's keys besides its digits (one per overlay, [`OverlayKind::key`]).
const OVERLAY_MENU: &[(KeyCode, Action)] = &[
    (KeyCode::Char('o'), Action::CloseOverlayMenu),
    (KeyCode::Esc, Action::CloseOverlayMenu),
    (KeyCode::Enter, Action::CloseOverlayMenu),
];

fn look_up(layer: &[(KeyCode, Action)], code: KeyCode) -> Option<Action> {
    layer
        .iter()
        .find_map(|&(key, action)| (key == code).then_some(action))
}

/// What `code` asks for while the live settings are open; `None`: it closes them and acts as usual.
pub fn settings_action(code: KeyCode) -> Option<Action> {
    look_up(SETTINGS, code)
}

/// What `code` asks for while the overlay menu is open; `None`: it closes it and acts as usual.
pub fn overlay_menu_action(code: KeyCode) -> Option<Action> {
    match code {
        KeyCode::Char(c) => OverlayKind::from_key(c).map(Action::ToggleOverlay),
        _ => None,
    }
    .or_else(|| look_up(OVERLAY_MENU, code))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_help_takes_every_key_and_click_but_not_the_pointers_moves() {
        assert_eq!(help_action(KeyCode::Char('q')), Action::CloseHelp);
        assert_eq!(
            help_action(KeyCode::Char(' ')),
            Action::ScrollHelp { rows: 8 }
        );
        assert_eq!(help_mouse_action(MouseEventKind::Moved), None);
        assert_eq!(
            help_mouse_action(MouseEventKind::Down(crossterm::event::MouseButton::Left)),
            Some(Action::CloseHelp)
        );
    }

    #[test]
    fn every_overlay_has_its_digit_and_the_menu_keys_close_it() {
        for kind in OverlayKind::ALL {
            assert_eq!(
                overlay_menu_action(KeyCode::Char(kind.key())),
                Some(Action::ToggleOverlay(kind))
            );
        }
        assert_eq!(overlay_menu_action(KeyCode::Char('0')), None);
        assert_eq!(
            overlay_menu_action(KeyCode::Esc),
            Some(Action::CloseOverlayMenu)
        );
        assert_eq!(settings_action(KeyCode::Char('o')), None);
        assert_eq!(settings_action(KeyCode::Esc), Some(Action::CloseSettings));
    }
}
