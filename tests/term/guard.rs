//! Process-wide parts of the terminal guard that need no terminal: the chained panic hook and the
//! signal flags. (The escape sequences themselves are unit-tested in `src/term/guard.rs`.)

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use nudge::term::guard::install_panic_hook;

#[test]
fn the_panic_hook_chains_to_the_previous_one_and_installs_once() {
    let calls = Arc::new(AtomicUsize::new(0));
    let seen = Arc::clone(&calls);
    std::panic::set_hook(Box::new(move |_| {
        seen.fetch_add(1, Ordering::SeqCst);
    }));
    install_panic_hook();
    install_panic_hook(); // a second call must not wrap the hook twice

    let result = std::panic::catch_unwind(|| panic!("boom"));
    assert!(result.is_err());
    assert_eq!(calls.load(Ordering::SeqCst), 1);
    // No guard was entered, so restoring is a no-op and must not fail.
    assert!(nudge::term::restore_terminal().is_ok());
}

#[cfg(unix)]
#[test]
fn a_fatal_signal_becomes_a_request_to_exit_instead_of_killing_the_process() {
    use nudge::term::{SignalRequest, Signals};
    use signal_hook::consts::{SIGCONT, SIGTERM, SIGTSTP};
    let signals = Signals::install().expect("signal handlers install");
    assert_eq!(signals.take(), None);
    // SIGTSTP would stop this test process by default: the handler replaced that.
    signal_hook::low_level::raise(SIGTSTP).expect("raise SIGTSTP");
    signal_hook::low_level::raise(SIGCONT).expect("raise SIGCONT");
    assert_eq!(signals.take(), Some(SignalRequest::Suspend));
    assert_eq!(signals.take(), Some(SignalRequest::Resume));
    assert_eq!(signals.take(), None);
    signal_hook::low_level::raise(SIGTERM).expect("raise SIGTERM");
    assert_eq!(signals.take(), Some(SignalRequest::Exit(SIGTERM)));
}
