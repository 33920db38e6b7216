//! A terminal that never answers a query (serial consoles, some web terminals, slow links) is not
//! fatal: the sandbox must not depend on the cursor-position report (`ESC[6n`), which crossterm
//! waits two seconds for and then fails. The pseudo-terminal of `tests/pty/mod.rs` answers nothing.
#![cfg(target_os = "linux")]

use crate::pty;

use std::time::Duration;

use pty::{Sandbox, TIMEOUT};

#[test]
fn a_terminal_that_never_answers_does_not_stop_the_sandbox() {
    let mut sandbox = Sandbox::start(&[]);
    // Longer than crossterm's two-second wait for a cursor position.
    std::thread::sleep(Duration::from_secs(3));
    assert!(
        pty::process_state(sandbox.pid).is_some(),
        "the sandbox gave up on a silent terminal: {:?}",
        sandbox.text()
    );
    let out = sandbox.output();
    assert!(
        !out.windows(4).any(|w| w == b"\x1b[6n"),
        "the sandbox asked for the cursor position"
    );
    sandbox.type_keys(b"q");
    assert_eq!(sandbox.wait_exit(TIMEOUT), Some(0), "{:?}", sandbox.text());
}

#[test]
fn term_dumb_is_refused_with_a_message() {
    let out = std::process::Command::new("script")
        .args([
            "-q",
            "-e",
            "-c",
            concat!(env!("CARGO_BIN_EXE_nudge"), " --scene default"),
            "/dev/null",
        ])
        .env("TERM", "dumb")
        .stdin(std::process::Stdio::null())
        .output()
        .expect("script runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(2), "{text}");
    assert!(text.contains("TERM=dumb"), "{text}");
    assert!(
        !text.contains("\x1b[?1049h"),
        "entered the alternate screen: {text:?}"
    );
}
