//! A sandbox whose terminal hangs up (an ssh session drops, a tmux pane is killed) must end, not
//! spin a core forever: crossterm 0.29 reads end-of-file from a dead terminal without returning (its
//! issue #793), so the process relies on `term::exit_after_hangup`. Runs the real binary on a
//! pseudo-terminal made by util-linux's `script`, kills `script` (closing the terminal's master
//! side, so the kernel sends SIGHUP), and watches the sandbox's process in `/proc`.
#![cfg(target_os = "linux")]

use std::process::Command;
use std::time::{Duration, Instant};

use crate::pty::{ENTER, Pty, START_TIMEOUT, processes_with, unique_marker};

/// How long the sandbox may take to be gone after the hang-up.
const EXIT_TIMEOUT: Duration = Duration::from_secs(5);

#[test]
fn the_sandbox_exits_when_its_terminal_hangs_up() {
    let marker = unique_marker();
    let sandbox = format!(
        "exec {} --max-bytes-per-second {marker}",
        env!("CARGO_BIN_EXE_nudge")
    );
    let Pty {
        mut script, output, ..
    } = Pty::open(&sandbox, false);
    let entered = || {
        output
            .lock()
            .unwrap()
            .windows(ENTER.len())
            .any(|w| w == ENTER)
    };
    let start = Instant::now();
    while !entered() && start.elapsed() < START_TIMEOUT {
        std::thread::sleep(Duration::from_millis(20));
    }
    let pids = processes_with(&marker);
    assert!(
        entered() && !pids.is_empty(),
        "the sandbox did not start on the pseudo-terminal"
    );

    script.kill().expect("kill script");
    let _ = script.wait();
    let hung_up = Instant::now();
    while !processes_with(&marker).is_empty() && hung_up.elapsed() < EXIT_TIMEOUT {
        std::thread::sleep(Duration::from_millis(50));
    }
    let left = processes_with(&marker);
    for pid in &left {
        let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
    }
    assert!(
        left.is_empty(),
        "still running {EXIT_TIMEOUT:?} after the hang-up: {left:?}"
    );
}
