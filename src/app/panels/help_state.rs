//! Whether the help overlay is open and how far it is scrolled, and what keys and the mouse do
//! while it is: it is modal (it hides the bodies under it), so it owns its state apart from the
//! switches in `ui_flags`, and only the methods here open, scroll or close it.

use crossterm::event::{KeyCode, MouseEventKind};

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

    /// A key while the help is open: ↑↓, PageUp/PageDown and Space scroll it where it does not
    /// fit; any other key closes it, q and Esc too (the box says so), and does nothing else.
    pub(crate) fn help_key(&mut self, code: KeyCode) {
        let rows = match code {
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
        self.close_help();
    }

    /// The mouse while the help is open: the overlay hides the bodies under it, so a click (or a
    /// scroll it does not need) closes it and does nothing else.
    pub(crate) fn help_mouse(&mut self, kind: MouseEventKind) {
        let scrolled = match kind {
            MouseEventKind::ScrollUp => self.scroll_help(-3),
            MouseEventKind::ScrollDown => self.scroll_help(3),
            _ => false,
        };
        if !scrolled
            && matches!(
                kind,
                MouseEventKind::Down(_) | MouseEventKind::ScrollUp | MouseEventKind::ScrollDown
            )
        {
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
