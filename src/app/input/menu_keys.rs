//! The modal layers of the key table: while the live settings or the overlay menu is open, its
//! keys are looked up here first and ask for their own [`Action`]s, which [`App::apply`] does like
//! any other. A key a layer lacks closes the menu and falls through to the main table
//! ([`crate::app::input::keys`]), so `o` from the settings switches to the overlay menu.
//!
//! [`App::apply`]: crate::app::App

use crossterm::event::KeyCode;

use crate::app::input::action::Action;
use crate::app::panels::overlays::OverlayKind;

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
    fn every_overlay_has_its_digit_and_the_menu_keys_close_it() {
        for kind in OverlayKind::ALL {
            assert_eq!(
                overlay_menu_action(KeyCode::Char(kind.key())),
                Some(Action::ToggleOverlay(kind))
            );
        }
        assert_eq!(overlay_menu_action(KeyCode::Char('9')), None);
        assert_eq!(
            overlay_menu_action(KeyCode::Esc),
            Some(Action::CloseOverlayMenu)
        );
        assert_eq!(settings_action(KeyCode::Char('o')), None);
        assert_eq!(settings_action(KeyCode::Esc), Some(Action::CloseSettings));
    }
}
