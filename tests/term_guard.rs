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
fn a_termination_signal_sets_the_flag_instead_of_killing_the_process() {
    let flag = nudge::term::install_signal_flags().expect("signal handlers install");
    assert!(!flag.load(Ordering::Relaxed));
    signal_hook::low_level::raise(signal_hook::consts::SIGHUP).expect("raise SIGHUP");
    assert!(flag.load(Ordering::Relaxed));
}
