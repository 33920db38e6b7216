//! Signals the sandbox answers, so that none of them leaves the user's terminal broken.
//!
//! In raw mode Ctrl-C and Ctrl-Z are keys, not signals, but `kill`, a closed ssh session, the
//! shell's job control and a stray `kill -USR1` still arrive, and their default actions would end
//! or stop the process with the terminal in the alternate screen, raw mode and mouse reporting.
//! [`Signals::install`] replaces those actions with flags the event loop polls:
//!
//! - **Fatal** ones (SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2, SIGALRM): the loop
//!   restores the terminal and the process exits with status 128 + the signal's number (129, 130,
//!   131, 143, ...), what a shell reports for a process the signal killed. A second fatal signal
//!   while the first is still pending exits at once with that status (terminal not restored;
//!   `reset` fixes it), so a stuck loop can still be killed.
//! - **SIGTSTP** (`kill -TSTP`; Ctrl+Z arrives as a key and is handled the same way): the loop
//!   restores the terminal, then stops the process ([`stop_self`]).
//! - **SIGCONT**: the loop enters raw mode and the alternate screen again and repaints everything,
//!   whether it stopped itself or someone else stopped it (`kill -STOP`): a shell puts the terminal
//!   back into cooked mode while a job is stopped.
//!
//! A hang-up needs more: once the terminal is gone, crossterm 0.29's event source reads end-of-file
//! from it forever without returning to the caller (crossterm issue #793), so the loop never sees
//! the flag and the orphaned process spins a core until someone kills it. [`exit_after_hangup`]
//! ends the process a moment after SIGHUP if the loop has not: there is no terminal left to
//! restore.
//!
//! On platforms without these signals only SIGINT and SIGTERM are answered.

use std::fmt;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use signal_hook::consts;

/// The signals that end the sandbox (after it restores the terminal).
#[cfg(unix)]
pub const FATAL_SIGNALS: &[i32] = &[
    consts::SIGHUP,
    consts::SIGINT,
    consts::SIGQUIT,
    consts::SIGTERM,
    consts::SIGUSR1,
    consts::SIGUSR2,
    consts::SIGALRM,
];
#[cfg(not(unix))]
pub const FATAL_SIGNALS: &[i32] = &[consts::SIGINT, consts::SIGTERM];

/// What a signal asks of the event loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SignalRequest {
    /// Restore the terminal and exit with [`exit_status`] of this signal.
    Exit(i32),
    /// Restore the terminal and stop the process (SIGTSTP).
    Suspend,
    /// The process was continued after a stop: set the terminal up again and repaint (SIGCONT).
    Resume,
}

/// The flags the installed handlers set; the event loop polls them with [`Signals::take`].
#[derive(Debug)]
pub struct Signals {
    /// Any fatal signal is pending (for the immediate exit on a second one).
    fatal_pending: Arc<AtomicBool>,
    /// The number of the last fatal signal, 0 when none.
    fatal: Arc<AtomicUsize>,
    suspend: Arc<AtomicBool>,
    resume: Arc<AtomicBool>,
}

impl Signals {
    /// Installs the handlers (see the module docs). Call once per event loop; the handlers stay
    /// installed for the life of the process.
    ///
    /// Errors: the OS refused to install a handler.
    pub fn install() -> io::Result<Self> {
        let signals = Self {
            fatal_pending: Arc::new(AtomicBool::new(false)),
            fatal: Arc::new(AtomicUsize::new(0)),
            suspend: Arc::new(AtomicBool::new(false)),
            resume: Arc::new(AtomicBool::new(false)),
        };
        for &signal in FATAL_SIGNALS {
            // Order matters: actions run in registration order, so the shutdown check sees the flag
            // as it was before this signal set it.
            signal_hook::flag::register_conditional_shutdown(
                signal,
                exit_status(signal),
                Arc::clone(&signals.fatal_pending),
            )?;
            signal_hook::flag::register(signal, Arc::clone(&signals.fatal_pending))?;
            signal_hook::flag::register_usize(signal, Arc::clone(&signals.fatal), signal as usize)?;
        }
        #[cfg(unix)]
        {
            signal_hook::flag::register(consts::SIGTSTP, Arc::clone(&signals.suspend))?;
            signal_hook::flag::register(consts::SIGCONT, Arc::clone(&signals.resume))?;
        }
        Ok(signals)
    }

    /// The most urgent request pending, cleared as it is returned: an exit before a suspend
    /// before a resume.
    pub fn take(&self) -> Option<SignalRequest> {
        match self.fatal.load(Ordering::Relaxed) {
            0 => {}
            signal => return Some(SignalRequest::Exit(signal as i32)),
        }
        if self.suspend.swap(false, Ordering::Relaxed) {
            return Some(SignalRequest::Suspend);
        }
        if self.resume.swap(false, Ordering::Relaxed) {
            return Some(SignalRequest::Resume);
        }
        None
    }

    /// Forgets a pending resume: the loop has just set the terminal up again itself.
    pub fn clear_resume(&self) {
        self.resume.store(false, Ordering::Relaxed);
    }
}

/// The exit status for a process ended by `signal`: 128 + its number, as shells report it.
pub fn exit_status(signal: i32) -> i32 {
    128 + signal
}

/// The error the event loop returns when a signal ended it; the command line turns it into
/// [`exit_status`] without a message (the user sent the signal, nothing went wrong).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EndedBySignal(pub i32);

impl fmt::Display for EndedBySignal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = signal_hook::low_level::signal_name(self.0).unwrap_or("a signal");
        write!(f, "ended by {name}")
    }
}

impl std::error::Error for EndedBySignal {}

/// Stops the process as SIGTSTP's default action would (the terminal must already be restored);
/// returns once something continues it. Elsewhere than unix it does nothing.
///
/// Errors: the OS refused to raise the stop signal.
pub fn stop_self() -> io::Result<()> {
    #[cfg(unix)]
    signal_hook::low_level::emulate_default_handler(consts::SIGTSTP)?;
    Ok(())
}

/// After SIGHUP, gives the process `grace` to end on its own (the event loop sees the flag of
/// [`Signals`] and restores the terminal), then exits with status 129 from a watcher thread. See
/// the module docs for why the loop may never get there. On other platforms it does nothing.
///
/// Errors: the OS refused to install the handler or to start the thread.
pub fn exit_after_hangup(grace: Duration) -> io::Result<()> {
    #[cfg(unix)]
    {
        let mut signals = signal_hook::iterator::Signals::new([consts::SIGHUP])?;
        std::thread::Builder::new()
            .name("hangup".into())
            .spawn(move || {
                if signals.forever().next().is_some() {
                    std::thread::sleep(grace);
                    std::process::exit(exit_status(consts::SIGHUP));
                }
            })?;
    }
    #[cfg(not(unix))]
    let _ = grace;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_statuses_are_what_a_shell_reports_for_a_killed_process() {
        assert_eq!(exit_status(consts::SIGINT), 130);
        assert_eq!(exit_status(consts::SIGTERM), 143);
        #[cfg(unix)]
        {
            assert_eq!(exit_status(consts::SIGHUP), 129);
            assert_eq!(exit_status(consts::SIGQUIT), 131);
        }
    }

    #[test]
    fn the_message_names_the_signal() {
        assert_eq!(
            EndedBySignal(consts::SIGTERM).to_string(),
            "ended by SIGTERM"
        );
    }
}
