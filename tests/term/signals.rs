//! Every signal leaves the terminal usable: the sandbox on a real pseudo-terminal (see
//! `tests/pty/mod.rs`) is sent each fatal signal and must restore the terminal and exit with the
//! shell's status for it; job control (Ctrl+Z, `kill -TSTP`, `kill -STOP`, then continuing) must
//! give the terminal back in cooked mode while stopped and take it again, repainted, after.
#![cfg(target_os = "linux")]

use crate::pty;

use pty::{ENTER, LEAVE, MOUSE_OFF, PROBE_LAST_QUESTION, Sandbox, TIMEOUT, TRUECOLOR_REPLIES};

/// Sends `kill -NAME` and expects the terminal restored and exit status `status`.
fn ends_with_status(name: &str, status: i32) {
    let mut sandbox = Sandbox::start(&[]);
    let mark = sandbox.mark();
    sandbox.signal(name);
    let code = sandbox.wait_exit(TIMEOUT);
    let out = sandbox.output();
    let after = &out[mark..];
    assert_eq!(code, Some(status), "SIG{name}: {:?}", sandbox.text());
    let mouse_off = after.windows(MOUSE_OFF.len()).any(|w| w == MOUSE_OFF);
    assert!(
        mouse_off && after.ends_with(LEAVE),
        "SIG{name} left the terminal in the sandbox's modes: {:?}",
        sandbox.text()
    );
}

#[test]
fn sigquit_restores_the_terminal_and_exits_131() {
    ends_with_status("QUIT", 131);
}

#[test]
fn sigusr1_restores_the_terminal_and_exits_138() {
    ends_with_status("USR1", 138);
}

#[test]
fn sigterm_restores_the_terminal_and_exits_143() {
    ends_with_status("TERM", 143);
}

#[test]
fn sigint_restores_the_terminal_and_exits_130() {
    ends_with_status("INT", 130);
}

#[test]
fn sighup_restores_the_terminal_and_exits_129() {
    ends_with_status("HUP", 129);
}

/// Continues the stopped sandbox and checks that it had restored the terminal before stopping
/// (output after `mark`), then took it again (raw mode, alternate screen) and repainted it whole.
fn comes_back(sandbox: &mut Sandbox, mark: usize) {
    sandbox.continue_job();
    assert!(
        sandbox.wait_state(|s| s != 'T'),
        "the sandbox did not continue"
    );
    let entered = sandbox.wait_for(ENTER, mark, TIMEOUT);
    let Some(entered) = entered else {
        panic!("no alternate screen after continuing: {:?}", sandbox.text());
    };
    assert!(
        sandbox.wait_for_whole_frame(entered, TIMEOUT).is_some(),
        "not repainted after continuing: {:?}",
        sandbox.text()
    );
    assert!(sandbox.is_raw(), "{}", sandbox.tty_settings());
    let out = sandbox.output();
    let stopped = &out[mark..entered];
    assert!(
        stopped.windows(MOUSE_OFF.len()).any(|w| w == MOUSE_OFF)
            && stopped.windows(LEAVE.len()).any(|w| w == LEAVE),
        "stopped without restoring the terminal: {:?}",
        String::from_utf8_lossy(stopped)
    );
}

/// Stops the sandbox with `stop`, checks the terminal is in cooked mode while it is stopped, then
/// continues it ([`comes_back`]).
fn stops_and_comes_back(sandbox: &mut Sandbox, stop: impl FnOnce(&mut Sandbox)) {
    let mark = sandbox.mark();
    stop(sandbox);
    assert!(sandbox.wait_state(|s| s == 'T'), "the sandbox did not stop");
    assert!(sandbox.is_cooked(), "{}", sandbox.tty_settings());
    comes_back(sandbox, mark);
}

#[test]
fn ctrl_z_and_kill_tstp_suspend_and_continuing_restores_raw_mode_and_redraws() {
    let mut sandbox = Sandbox::start(&[]);
    assert!(sandbox.is_raw(), "{}", sandbox.tty_settings());
    // The truecolor probe asked this silent terminal first, and gave up on it.
    assert!(
        sandbox.wait_for(PROBE_LAST_QUESTION, 0, TIMEOUT).is_some(),
        "no probe: {:?}",
        sandbox.text()
    );
    stops_and_comes_back(&mut sandbox, |s| s.type_keys(b"\x1a"));
    stops_and_comes_back(&mut sandbox, |s| s.signal("TSTP"));
    // Still answering keys after both round trips: q quits normally.
    sandbox.type_keys(b"q");
    assert_eq!(sandbox.wait_exit(TIMEOUT), Some(0), "{:?}", sandbox.text());
}

#[test]
fn after_a_terminal_answers_the_truecolor_probe_job_control_and_signals_still_work() {
    // The probe reads the terminal's replies itself, in raw mode, before the event loop: what it
    // leaves behind must not get in the way of Ctrl+Z, continuing, or a fatal signal.
    let mut sandbox = Sandbox::start_answering(&[], TRUECOLOR_REPLIES);
    assert!(
        sandbox
            .wait_for(b"truecolor (terminal says)", 0, TIMEOUT)
            .is_some(),
        "the answer was not taken: {:?}",
        sandbox.text()
    );
    stops_and_comes_back(&mut sandbox, |s| s.type_keys(b"\x1a"));
    stops_and_comes_back(&mut sandbox, |s| s.signal("TSTP"));
    let mark = sandbox.mark();
    sandbox.signal("TERM");
    assert_eq!(
        sandbox.wait_exit(TIMEOUT),
        Some(143),
        "{:?}",
        sandbox.text()
    );
    let out = sandbox.output();
    let after = &out[mark..];
    assert!(
        after.windows(MOUSE_OFF.len()).any(|w| w == MOUSE_OFF) && after.ends_with(LEAVE),
        "SIGTERM left the terminal in the sandbox's modes: {:?}",
        sandbox.text()
    );
}

#[test]
fn a_stop_from_outside_is_repaired_on_continue() {
    let mut sandbox = Sandbox::start(&[]);
    let mark = sandbox.mark();
    // SIGSTOP cannot be caught: the sandbox stops in its modes, the test puts the terminal in
    // cooked mode as a shell would, and continuing must take it again.
    sandbox.signal("STOP");
    assert!(sandbox.wait_state(|s| s == 'T'), "the sandbox did not stop");
    let tty = std::fs::read_link(format!("/proc/{}/fd/0", sandbox.pid)).unwrap();
    let cooked = std::process::Command::new("stty")
        .arg("-F")
        .arg(&tty)
        .arg("sane")
        .status()
        .unwrap();
    assert!(cooked.success() && sandbox.is_cooked());
    sandbox.continue_job();
    let entered = sandbox.wait_for(ENTER, mark, TIMEOUT);
    let Some(entered) = entered else {
        panic!("no alternate screen after continuing: {:?}", sandbox.text());
    };
    assert!(sandbox.wait_for_whole_frame(entered, TIMEOUT).is_some());
    assert!(sandbox.is_raw(), "{}", sandbox.tty_settings());
    sandbox.type_keys(b"q");
    assert_eq!(sandbox.wait_exit(TIMEOUT), Some(0), "{:?}", sandbox.text());
}
