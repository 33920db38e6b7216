//! The key table: every key and button, what it asks for, how the help overlay lists it and how
//! the README names it. It is the one key map: [`action_of`] dispatches through it, the help
//! overlay's rows ([`CONTROLS`]) are read from it, and `tests/app/controls_readme.rs` checks the
//! README's controls table against it, so a new key is one row here.

use crossterm::event::{KeyCode, KeyModifiers};

use crate::app::input::action::{Action, Turn};
use crate::app::input::nudge::NudgeDir;

/// Whether a chord needs Ctrl held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ctrl {
    /// Ctrl with a letter is never taken for the letter (Ctrl+R reset the world, Ctrl+D nudged).
    Without,
    With,
    /// Keys that are not letters (arrows, F1, Esc) mean the same with Ctrl; so do the panels'
    /// letters, which were read before Ctrl was looked at.
    Any,
}

/// Whether a chord needs Shift held (only `s` tells: a sphere, or Shift+`s` the back nudge).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shift {
    Without,
    With,
    Any,
}

/// A key with the modifiers that matter to it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chord {
    pub code: KeyCode,
    pub ctrl: Ctrl,
    pub shift: Shift,
}

impl Chord {
    /// Whether a press of `code` with `modifiers` is this chord.
    pub fn matches(&self, code: KeyCode, modifiers: KeyModifiers) -> bool {
        let held = |wanted, modifier| match wanted {
            Ctrl::Any => true,
            Ctrl::With => modifiers.contains(modifier),
            Ctrl::Without => !modifiers.contains(modifier),
        };
        let shift = match self.shift {
            Shift::Any => Ctrl::Any,
            Shift::With => Ctrl::With,
            Shift::Without => Ctrl::Without,
        };
        self.code == code
            && held(self.ctrl, KeyModifiers::CONTROL)
            && held(shift, KeyModifiers::SHIFT)
    }
}

/// One input of a control.
#[derive(Clone, Copy, Debug)]
pub enum Input {
    /// A key, and what it asks for.
    Key(Chord, Action),
    /// A mouse button or the wheel: its action carries where it points, so it is listed here for
    /// the help and the README and dispatched by [`crate::app::input::mouse::action_of`].
    Mouse,
}

/// An input and the README's name for it ("" for an alias the README leaves out, as `=` for `+`).
#[derive(Clone, Copy, Debug)]
pub struct Binding {
    pub input: Input,
    pub readme: &'static str,
}

/// One row of the help overlay: its keys, what they do, and the inputs behind them.
#[derive(Clone, Copy, Debug)]
pub struct Control {
    /// The keys as the overlay shows them; empty: the row continues the action above.
    pub keys: &'static str,
    /// What they do, as the overlay says it (it fits 80 columns beside the keys).
    pub does: &'static str,
    pub bindings: &'static [Binding],
}

/// A letter (or sign) without Ctrl.
const fn key(c: char, action: Action, readme: &'static str) -> Binding {
    chord(KeyCode::Char(c), Ctrl::Without, Shift::Any, action, readme)
}

/// A letter with Ctrl.
const fn ctrl(c: char, action: Action, readme: &'static str) -> Binding {
    chord(KeyCode::Char(c), Ctrl::With, Shift::Any, action, readme)
}

/// A key that is not a letter: Ctrl does not change it.
const fn special(code: KeyCode, action: Action, readme: &'static str) -> Binding {
    chord(code, Ctrl::Any, Shift::Any, action, readme)
}

const fn chord(
    code: KeyCode,
    ctrl: Ctrl,
    shift: Shift,
    action: Action,
    readme: &'static str,
) -> Binding {
    Binding {
        input: Input::Key(Chord { code, ctrl, shift }, action),
        readme,
    }
}

const fn mouse(readme: &'static str) -> Binding {
    Binding {
        input: Input::Mouse,
        readme,
    }
}

/// Every control, in the help overlay's order.
pub const KEYS: &[Control] = &[
    Control {
        keys: "left / right button",
        does: "push / pull the body under the pointer",
        bindings: &[mouse("left / right button (hold)")],
    },
    Control {
        keys: "",
        does: "(hold to keep pushing, drag to follow)",
        bindings: &[],
    },
    Control {
        keys: "h",
        does: "left button: grab and drag / push",
        bindings: &[key('h', Action::ToggleGrabMode, "`h`")],
    },
    // Ctrl+click never reaches the app in a stock xterm, which opens its own menu.
    Control {
        keys: "middle, f then click",
        does: "freeze / unfreeze (Ctrl+click: not xterm)",
        bindings: &[
            mouse("middle button"),
            key('f', Action::ArmFreeze, "`f` then click"),
            mouse("Ctrl+click"),
        ],
    },
    Control {
        keys: "x",
        does: "strong hand on / off (4× force)",
        bindings: &[key('x', Action::ToggleStrong, "`x`"), mouse("Shift+click")],
    },
    Control {
        keys: "wheel, + / -",
        does: "zoom (grabbing: hold it nearer / farther)",
        bindings: &[
            mouse("wheel"),
            key('+', Action::Zoom { closer: true }, "`+`"),
            key('=', Action::Zoom { closer: true }, ""),
            key('-', Action::Zoom { closer: false }, "`-`"),
            key('_', Action::Zoom { closer: false }, ""),
        ],
    },
    Control {
        keys: "arrows / c, Home",
        does: "orbit the camera / reset it",
        bindings: &[
            special(KeyCode::Left, Action::Orbit(Turn::Left), "arrows"),
            special(KeyCode::Right, Action::Orbit(Turn::Right), "arrows"),
            special(KeyCode::Up, Action::Orbit(Turn::Up), "arrows"),
            special(KeyCode::Down, Action::Orbit(Turn::Down), "arrows"),
            key('c', Action::ResetCamera, "`c`"),
            special(KeyCode::Home, Action::ResetCamera, "Home"),
        ],
    },
    Control {
        keys: "w a d, Shift+s / e",
        does: "nudge the last clicked body / lift it",
        bindings: &[
            key('w', Action::Nudge(NudgeDir::Away), "`w`"),
            key('a', Action::Nudge(NudgeDir::Left), "`a`"),
            key('d', Action::Nudge(NudgeDir::Right), "`d`"),
            chord(
                KeyCode::Char('s'),
                Ctrl::Without,
                Shift::With,
                Action::Nudge(NudgeDir::Back),
                "Shift+`s`",
            ),
            key('e', Action::Nudge(NudgeDir::Up), "`e`"),
            // Caps lock, or Shift as most terminals send it.
            key('W', Action::Nudge(NudgeDir::Away), ""),
            key('A', Action::Nudge(NudgeDir::Left), ""),
            key('D', Action::Nudge(NudgeDir::Right), ""),
            key('S', Action::Nudge(NudgeDir::Back), ""),
            key('E', Action::Nudge(NudgeDir::Up), ""),
        ],
    },
    Control {
        keys: "b / s",
        does: "drop a box / sphere where the pointer is",
        bindings: &[
            key('b', Action::SpawnBox, "`b`"),
            chord(
                KeyCode::Char('s'),
                Ctrl::Without,
                Shift::Without,
                Action::SpawnSphere,
                "`s`",
            ),
        ],
    },
    Control {
        keys: "space / .",
        does: "pause / single step",
        bindings: &[
            key(' ', Action::TogglePause, "Space"),
            key('.', Action::SingleStep, "`.`"),
        ],
    },
    // Sharing a line: the overlay fits 80 × 24 without scrolling.
    Control {
        keys: "m, Tab / Shift+Tab; v",
        does: "next / previous render mode; cell mode",
        bindings: &[
            key('m', Action::CycleMode { forward: true }, "`m`"),
            special(KeyCode::Tab, Action::CycleMode { forward: true }, "Tab"),
            special(
                KeyCode::BackTab,
                Action::CycleMode { forward: false },
                "Shift+Tab",
            ),
            key('v', Action::CycleCells, "`v`"),
        ],
    },
    Control {
        keys: "p / g",
        does: "perspective ↔ orthographic / gravity on, off",
        bindings: &[
            key('p', Action::ToggleProjection, "`p`"),
            key('g', Action::ToggleGravity, "`g`"),
        ],
    },
    Control {
        keys: "r",
        does: "reset the bodies (the camera stays)",
        bindings: &[key('r', Action::ResetBodies, "`r`")],
    },
    Control {
        keys: "n / N",
        does: "next / previous built-in scene",
        bindings: &[
            key('n', Action::SwitchScene { forward: true }, "`n`"),
            key('N', Action::SwitchScene { forward: false }, "`N`"),
        ],
    },
    Control {
        keys: "[ / ]",
        does: "rewind / forward 0.25 s (hold to scrub)",
        bindings: &[
            key('[', Action::Rewind { forward: false }, "`[`"),
            key(']', Action::Rewind { forward: true }, "`]`"),
        ],
    },
    Control {
        keys: "< / >",
        does: "shrink / grow the selected body 10 %",
        bindings: &[
            key('<', Action::Grow { larger: false }, "`<`"),
            key('>', Action::Grow { larger: true }, "`>`"),
        ],
    },
    Control {
        keys: "Ctrl+S",
        does: "save the world as a scene file",
        bindings: &[ctrl('s', Action::Save, "Ctrl+S")],
    },
    Control {
        keys: "o then 1-9, i, t",
        does: "overlays, inspector, live settings",
        bindings: &[
            chord(
                KeyCode::Char('o'),
                Ctrl::Any,
                Shift::Any,
                Action::OverlayMenu,
                "`o` then `1`–`9`",
            ),
            chord(
                KeyCode::Char('i'),
                Ctrl::Any,
                Shift::Any,
                Action::ToggleInspector,
                "`i`",
            ),
            chord(
                KeyCode::Char('t'),
                Ctrl::Any,
                Shift::Any,
                Action::OpenSettings,
                "`t`",
            ),
        ],
    },
    Control {
        keys: "?, F1 / Ctrl+L",
        does: "this help / redraw the screen",
        bindings: &[
            key('?', Action::OpenHelp, "`?`"),
            special(KeyCode::F(1), Action::OpenHelp, "F1"),
            ctrl('l', Action::Repaint, "Ctrl+L"),
        ],
    },
    Control {
        keys: "Esc",
        does: "close the open panel, else quit",
        bindings: &[special(KeyCode::Esc, Action::Escape, "Esc")],
    },
    Control {
        keys: "q / Ctrl+C / Ctrl+Z",
        does: "quit (asks if changed) / at once / suspend",
        bindings: &[
            key('q', Action::Quit, "`q`"),
            ctrl('c', Action::Interrupt, "Ctrl+C"),
            ctrl('z', Action::Suspend, "Ctrl+Z"),
            ctrl('Z', Action::Suspend, ""),
        ],
    },
];

/// What a press of `code` with `modifiers` asks for; `None` for a key the table lacks.
pub fn action_of(code: KeyCode, modifiers: KeyModifiers) -> Option<Action> {
    KEYS.iter()
        .flat_map(|control| control.bindings)
        .find_map(|binding| match binding.input {
            Input::Key(chord, action) if chord.matches(code, modifiers) => Some(action),
            _ => None,
        })
}

/// Every name the README's controls table should give an input, each once.
pub fn readme_names() -> Vec<&'static str> {
    let mut names: Vec<&str> = KEYS
        .iter()
        .flat_map(|control| control.bindings)
        .map(|binding| binding.readme)
        .filter(|name| !name.is_empty())
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

const ROWS: usize = KEYS.len();

/// The help overlay's rows, (keys, what they do), read from [`KEYS`].
pub const CONTROLS: &[(&str, &str)] = &{
    let mut rows = [("", ""); ROWS];
    let mut i = 0;
    while i < ROWS {
        rows[i] = (KEYS[i].keys, KEYS[i].does);
        i += 1;
    }
    rows
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_chord_is_bound_twice() {
        let chords: Vec<Chord> = KEYS
            .iter()
            .flat_map(|control| control.bindings)
            .filter_map(|binding| match binding.input {
                Input::Key(chord, _) => Some(chord),
                Input::Mouse => None,
            })
            .collect();
        for (i, a) in chords.iter().enumerate() {
            for b in &chords[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }

    #[test]
    fn ctrl_with_a_letter_is_not_the_letter_but_ctrl_with_an_arrow_is_the_arrow() {
        assert_eq!(action_of(KeyCode::Char('r'), KeyModifiers::CONTROL), None);
        assert_eq!(
            action_of(KeyCode::Left, KeyModifiers::CONTROL),
            Some(Action::Orbit(Turn::Left))
        );
        assert_eq!(
            action_of(KeyCode::Char('s'), KeyModifiers::SHIFT),
            Some(Action::Nudge(NudgeDir::Back))
        );
        assert_eq!(
            action_of(KeyCode::Char('s'), KeyModifiers::NONE),
            Some(Action::SpawnSphere)
        );
    }
}
