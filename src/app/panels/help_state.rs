//! Whether the help overlay is open and how far it is scrolled: it is modal (it hides the bodies
//! under it), so it owns its state apart from the switches in `ui_flags`, and only the methods
//! here open, scroll or close it. What keys and the mouse ask for while it is open is its layer
//! of the key table, in [`crate::app::input::menu_keys`].

use super::help::HelpOverlay;
use super::view::viewport_area;
use crate::app::App;

/// The help overlay's state: closed, or open and scrolled down some rows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HelpState {
    open: bool,
    /// Rows scrolled down (where the terminal is too short for all of it).
    scroll: u16,
}

impl HelpState {
    pub fn is_open(self) -> bool {
        self.open
    }

    pub fn scroll(self) -> u16 {
        self.scroll
    }
}

impl App {
    /// `?`, F1: opens the help at its top.
    pub(crate) fn open_help(&mut self) {
        self.help = HelpState {
            open: true,
            scroll: 0,
        };
    }

    pub(crate) fn close_help(&mut self) {
        self.help.open = false;
        self.say("help closed");
    }

    /// A scroll while the help is open (its keys and the wheel are in
    /// [`crate::app::input::menu_keys`]): where the help does not fit it scrolls, else the key or
    /// notch closes it, as any other.
    pub(crate) fn scroll_or_close_help(&mut self, rows: i32) {
        if !self.scroll_help(rows) {
            self.close_help();
        }
    }

    /// Scrolls the help overlay by `rows` if it does not show every row; false if it does (the key
    /// or notch then closes it, as any other).
    fn scroll_help(&mut self, rows: i32) -> bool {
        let max = HelpOverlay::max_scroll(viewport_area(self.area));
        if max == 0 {
            return false;
        }
        let scroll = (i32::from(self.help.scroll) + rows).clamp(0, i32::from(max));
        self.help.scroll = scroll as u16;
        self.dirty = true;
        true
    }
}
