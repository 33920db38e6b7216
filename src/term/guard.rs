//! The terminal guard: puts the terminal into the state the interactive app needs and guarantees
//! it is put back, however the program ends.
//!
//! Enter, in order: raw mode; then on stdout
//! - `ESC[?1049h` alternate screen, `ESC[?25l` hide cursor;
//! - mouse: `ESC[?1000h` presses/releases, `ESC[?1002h` motion while a button is held (drag),
//!   `ESC[?1003h` all motion **only if hover is asked for**, `ESC[?1006h` SGR coordinates (no 223
//!   column limit). We write these ourselves instead of crossterm's `EnableMouseCapture`, which
//!   always turns on 1003: every mouse move then becomes an event, which floods slow links and which
//!   tmux and mosh drop anyway.
//!
//! Restore, in order: `ESC[?1003l ESC[?1006l ESC[?1002l ESC[?1000l` mouse off (1003 too, harmless
//! if never on), `ESC[0m` default colours, `ESC[?25h` show cursor, `ESC[?1049l` leave the alternate
//! screen; then raw mode off. Restore runs at most once per enter (a process-wide flag), from
//! whichever comes first: [`TerminalGuard::restore`], the guard's `Drop`, or the panic hook (which
//! restores *before* the previous hook prints, so the panic message lands on the normal screen in
//! cooked mode and is readable).
//!
//! Signals and job control are answered in [`super::signals`]; the event loop calls
//! [`TerminalGuard::suspend`] before the process stops and [`TerminalGuard::resume`] after it is
//! continued.

use std::io::{self, Write};
use std::sync::Once;
use std::sync::atomic::{AtomicBool, Ordering};

/// Escape sequences written by [`write_enter`] before the mouse modes.
const ENTER_SCREEN: &[u8] = b"\x1b[?1049h\x1b[?25l";
/// Mouse press/release and drag reporting.
const MOUSE_BUTTONS_ON: &[u8] = b"\x1b[?1000h\x1b[?1002h";
/// All-motion (hover) reporting.
const MOUSE_HOVER_ON: &[u8] = b"\x1b[?1003h";
/// SGR mouse coordinates.
const MOUSE_SGR_ON: &[u8] = b"\x1b[?1006h";
/// Everything [`write_restore`] writes.
const RESTORE: &[u8] = b"\x1b[?1003l\x1b[?1006l\x1b[?1002l\x1b[?1000l\x1b[0m\x1b[?25h\x1b[?1049l";

/// Whether the terminal is currently in the entered state (set by [`TerminalGuard::enter`],
/// cleared by the first restore).
static ACTIVE: AtomicBool = AtomicBool::new(false);
static PANIC_HOOK: Once = Once::new();

/// Writes the enter sequence (alternate screen, hidden cursor, mouse modes; see the module docs)
/// and flushes. Does not touch raw mode.
pub fn write_enter(out: &mut impl Write, hover: bool) -> io::Result<()> {
    out.write_all(ENTER_SCREEN)?;
    out.write_all(MOUSE_BUTTONS_ON)?;
    if hover {
        out.write_all(MOUSE_HOVER_ON)?;
    }
    out.write_all(MOUSE_SGR_ON)?;
    out.flush()
}

/// Writes the restore sequence (mouse modes off, default colours, cursor shown, alternate screen
/// left; see the module docs) and flushes. Does not touch raw mode.
pub fn write_restore(out: &mut impl Write) -> io::Result<()> {
    out.write_all(RESTORE)?;
    out.flush()
}

/// Restores once: if `active` was set, clears it, writes the restore sequence to `out` and calls
/// `disable_raw`; otherwise does nothing. Both steps are attempted even if the first fails; the
/// first error is returned.
fn restore_once(
    active: &AtomicBool,
    out: &mut impl Write,
    disable_raw: impl FnOnce() -> io::Result<()>,
) -> io::Result<()> {
    if !active.swap(false, Ordering::SeqCst) {
        return Ok(());
    }
    let written = write_restore(out);
    let raw = disable_raw();
    written.and(raw)
}

/// Restores the terminal if a [`TerminalGuard`] entered it and nothing has restored it yet
/// (idempotent; safe to call from anywhere, including after the guard is gone).
pub fn restore_terminal() -> io::Result<()> {
    restore_once(
        &ACTIVE,
        &mut io::stdout().lock(),
        crossterm::terminal::disable_raw_mode,
    )
}

/// Installs (once per process) a panic hook that calls [`restore_terminal`] and then the hook that
/// was installed before it. [`TerminalGuard::enter`] calls this; calling it again does nothing.
pub fn install_panic_hook() {
    PANIC_HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let _ = restore_terminal();
            previous(info);
        }));
    });
}

/// Owns the interactive terminal state; restores it when dropped. At most one exists at a time.
///
/// The guard writes to stdout; the app should draw to stdout too (after [`TerminalGuard::enter`]).
#[derive(Debug)]
pub struct TerminalGuard {
    /// Whether all-motion mouse reporting was asked for (set again by [`TerminalGuard::resume`]).
    hover: bool,
}

impl TerminalGuard {
    /// Installs the panic hook, enables raw mode and writes the enter sequence ([`write_enter`]);
    /// `hover` adds all-motion mouse reporting. On failure everything done so far is undone.
    ///
    /// Errors: another guard is active, raw mode cannot be enabled (no controlling terminal), or
    /// writing fails. The caller should check that stdout is a terminal (`std::io::IsTerminal`)
    /// first: the sequences go to stdout.
    pub fn enter(hover: bool) -> io::Result<Self> {
        install_panic_hook();
        if ACTIVE.swap(true, Ordering::SeqCst) {
            return Err(io::Error::other(
                "the terminal is already set up by another TerminalGuard",
            ));
        }
        let setup = crossterm::terminal::enable_raw_mode()
            .and_then(|()| write_enter(&mut io::stdout().lock(), hover));
        match setup {
            Ok(()) => Ok(Self { hover }),
            Err(err) => {
                let _ = restore_terminal();
                Err(err)
            }
        }
    }

    /// Restores the terminal now (see [`restore_terminal`]); dropping the guard later does nothing
    /// more.
    pub fn restore(&mut self) -> io::Result<()> {
        restore_terminal()
    }

    /// Gives the terminal back before the process stops (job control): restores it as
    /// [`restore_terminal`] does, but the guard lives on for [`TerminalGuard::resume`].
    pub fn suspend(&mut self) -> io::Result<()> {
        restore_terminal()
    }

    /// Sets the terminal up again after the process was continued, whatever state the shell left
    /// it in: raw mode is applied afresh (crossterm skips enabling raw mode it believes is on, but
    /// a shell puts a stopped job's terminal back into cooked mode), then the enter sequence is
    /// written again. The caller must repaint the whole screen.
    pub fn resume(&mut self) -> io::Result<()> {
        ACTIVE.store(true, Ordering::SeqCst);
        let _ = crossterm::terminal::disable_raw_mode();
        crossterm::terminal::enable_raw_mode()
            .and_then(|()| write_enter(&mut io::stdout().lock(), self.hover))
    }
}

impl Drop for TerminalGuard {
    fn drop(&mut self) {
        let _ = restore_terminal();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn enter_bytes(hover: bool) -> Vec<u8> {
        let mut out = Vec::new();
        write_enter(&mut out, hover).unwrap();
        out
    }

    #[test]
    fn enter_asks_for_presses_drags_and_sgr_but_not_hover() {
        assert_eq!(
            enter_bytes(false),
            b"\x1b[?1049h\x1b[?25l\x1b[?1000h\x1b[?1002h\x1b[?1006h"
        );
    }

    #[test]
    fn enter_with_hover_adds_all_motion_reporting() {
        assert_eq!(
            enter_bytes(true),
            b"\x1b[?1049h\x1b[?25l\x1b[?1000h\x1b[?1002h\x1b[?1003h\x1b[?1006h"
        );
    }

    #[test]
    fn restore_turns_every_mode_off_in_reverse_order() {
        let mut out = Vec::new();
        write_restore(&mut out).unwrap();
        assert_eq!(
            out,
            b"\x1b[?1003l\x1b[?1006l\x1b[?1002l\x1b[?1000l\x1b[0m\x1b[?25h\x1b[?1049l"
        );
    }

    #[test]
    fn every_private_mode_entered_is_reset_on_restore() {
        let text = String::from_utf8(enter_bytes(true)).unwrap();
        let restore = String::from_utf8(RESTORE.to_vec()).unwrap();
        for set in text.split('\x1b').filter(|s| !s.is_empty()) {
            let reset = if set == "[?25l" {
                "\x1b[?25h".to_owned() // hiding the cursor is undone by showing it
            } else {
                format!("\x1b{}l", set.strip_suffix('h').unwrap())
            };
            assert!(restore.contains(&reset), "{set:?} is not undone");
        }
    }

    #[test]
    fn restore_happens_once_per_enter() {
        let active = AtomicBool::new(true);
        let mut out = Vec::new();
        let mut raw_calls = 0;
        restore_once(&active, &mut out, || {
            raw_calls += 1;
            Ok(())
        })
        .unwrap();
        restore_once(&active, &mut out, || {
            raw_calls += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!(out, RESTORE);
        assert_eq!(raw_calls, 1);
        assert!(!active.load(Ordering::SeqCst));
    }

    #[test]
    fn restore_when_not_entered_writes_nothing() {
        let active = AtomicBool::new(false);
        let mut out = Vec::new();
        restore_once(&active, &mut out, || Err(io::Error::other("must not run"))).unwrap();
        assert!(out.is_empty());
    }

    #[test]
    fn a_failing_write_still_disables_raw_mode_and_reports_the_error() {
        struct Broken;
        impl Write for Broken {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::other("closed"))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let active = AtomicBool::new(true);
        let mut raw_disabled = false;
        let result = restore_once(&active, &mut Broken, || {
            raw_disabled = true;
            Ok(())
        });
        assert!(result.is_err());
        assert!(raw_disabled);
    }
}
