//! A sandbox whose terminal hangs up (an ssh session drops, a tmux pane is killed) must end, not
//! spin a core forever: crossterm 0.29 reads end-of-file from a dead terminal without returning (its
//! issue #793), so the process relies on `term::exit_after_hangup`. Runs the real binary on a
//! pseudo-terminal made by util-linux's `script`, kills `script` (closing the terminal's master
//! side, so the kernel sends SIGHUP), and watches the sandbox's process in `/proc`.
#![cfg(target_os = "linux")]

use std::io::Read;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long the sandbox may take to start drawing, and to be gone after the hang-up.
const START_TIMEOUT: Duration = Duration::from_secs(20);
const EXIT_TIMEOUT: Duration = Duration::from_secs(5);
/// The alternate-screen sequence the sandbox writes once its terminal is set up.
const ENTERED: &[u8] = b"\x1b[?1049h";

/// Pids of live (not zombie) processes whose command line contains `marker`.
fn live_processes_with(marker: &str) -> Vec<u32> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|pid| {
            let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).unwrap_or_default();
            let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
            // The state follows the parenthesised command name: "pid (comm) S ...".
            let state = stat.rsplit(')').next().unwrap_or("").trim_start();
            String::from_utf8_lossy(&cmdline).contains(marker) && !state.starts_with('Z')
        })
        .collect()
}

#[test]
fn the_sandbox_exits_when_its_terminal_hangs_up() {
    // A flag value no other process has, to find the sandbox among the processes.
    let marker = format!("{}", 1_000_000 + std::process::id());
    let sandbox = format!(
        "exec {} --max-bytes-per-second {marker}",
        env!("CARGO_BIN_EXE_nudge")
    );
    let mut script = Command::new("script")
        .args(["-q", "-f", "-c", &sandbox, "/dev/null"])
        .env("TERM", "xterm-256color")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("util-linux `script` runs (it provides the pseudo-terminal)");

    // Drain the terminal's output (so the sandbox never blocks writing) and report when it entered.
    let mut out = script.stdout.take().expect("piped stdout");
    let (entered_tx, entered_rx) = mpsc::channel();
    std::thread::spawn(move || {
        let (mut seen, mut buf) = (Vec::new(), [0u8; 4096]);
        while let Ok(n @ 1..) = out.read(&mut buf) {
            seen.extend_from_slice(&buf[..n]);
            if seen.windows(ENTERED.len()).any(|w| w == ENTERED) {
                let _ = entered_tx.send(());
                seen.clear();
            }
        }
    });
    let started = entered_rx.recv_timeout(START_TIMEOUT);
    let pids = live_processes_with(&marker);
    assert!(
        started.is_ok() && !pids.is_empty(),
        "the sandbox did not start on the pseudo-terminal"
    );

    script.kill().expect("kill script");
    let _ = script.wait();
    let hung_up = Instant::now();
    while !live_processes_with(&marker).is_empty() && hung_up.elapsed() < EXIT_TIMEOUT {
        std::thread::sleep(Duration::from_millis(50));
    }
    let left = live_processes_with(&marker);
    for pid in &left {
        let _ = Command::new("kill").args(["-9", &pid.to_string()]).status();
    }
    assert!(
        left.is_empty(),
        "still running {EXIT_TIMEOUT:?} after the hang-up: {left:?}"
    );
}
