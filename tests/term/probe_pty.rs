//! The truecolor probe on a real pseudo-terminal (util-linux's `script` makes it; this test plays the
//! terminal emulator): a terminal that answers gets truecolor and "terminal says", one that stays
//! silent gets 256 colours and "guessed", and the sandbox runs on either way.
#![cfg(target_os = "linux")]

use std::io::Write;
use std::process::{Child, ChildStdin};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::pty::Pty;

/// Generous: the machine may be busy. The probe itself waits 100 ms at most.
const TIMEOUT: Duration = Duration::from_secs(20);

/// The sandbox on a pseudo-terminal whose output this test reads and whose input it writes.
struct Sandbox {
    script: Child,
    input: ChildStdin,
    output: Arc<Mutex<Vec<u8>>>,
    /// How many cursor-position requests have been answered (ratatui asks at start-up).
    answered_cpr: usize,
}

impl Sandbox {
    fn start() -> Self {
        Self::start_with("")
    }

    /// The sandbox with `args` after `--scene default`.
    fn start_with(args: &str) -> Self {
        // `script` makes a 0×0 terminal, which reports no pixel size; give it a size first.
        let sandbox = format!(
            "stty cols 100 rows 30; exec {} --scene default {args}",
            env!("CARGO_BIN_EXE_nudge")
        );
        let Pty {
            script,
            keys: input,
            output,
        } = Pty::open(&sandbox, false);
        Self {
            script,
            input,
            output,
            answered_cpr: 0,
        }
    }

    fn contains(&self, needle: &[u8]) -> bool {
        let out = self.output.lock().unwrap();
        out.windows(needle.len()).any(|w| w == needle)
    }

    /// Waits until the output contains `needle`, answering cursor-position requests meanwhile.
    fn wait_for(&mut self, needle: &[u8]) {
        let start = Instant::now();
        while !self.contains(needle) {
            self.answer_cursor_requests();
            assert!(
                start.elapsed() < TIMEOUT,
                "no {:?} in {:?}",
                String::from_utf8_lossy(needle),
                String::from_utf8_lossy(&self.output.lock().unwrap())
            );
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    fn answer_cursor_requests(&mut self) {
        let asked = {
            let out = self.output.lock().unwrap();
            out.windows(4).filter(|w| w == b"\x1b[6n").count()
        };
        while self.answered_cpr < asked {
            self.send(b"\x1b[1;1R");
            self.answered_cpr += 1;
        }
    }

    fn send(&mut self, bytes: &[u8]) {
        self.input.write_all(bytes).expect("write to the terminal");
        self.input.flush().expect("flush");
    }

    fn quit(mut self) {
        self.send(b"q");
        let start = Instant::now();
        loop {
            if let Some(status) = self.script.try_wait().expect("wait") {
                assert!(status.success(), "{status}");
                return;
            }
            self.answer_cursor_requests();
            if start.elapsed() > TIMEOUT {
                let _ = self.script.kill();
                panic!("the sandbox did not quit");
            }
            std::thread::sleep(Duration::from_millis(10));
        }
    }
}

/// The end of the probe's colour questions: XTVERSION, in the one write that ends with DA1.
// (The cell-size question and DA1 follow in the same write; a pty that reports its pixel size is
// not asked the first.)
const LAST_QUESTION: &[u8] = b"\x1bP+q524742;5463\x1b\\\x1b[>0q";

#[test]
fn a_terminal_that_keeps_a_direct_colour_gets_truecolor() {
    let mut sandbox = Sandbox::start();
    // Answered at once, before the questions even arrive: the replies wait in the terminal's input,
    // so a slow machine cannot make them late.
    sandbox.send(b"\x1bP1$r0;48:2::1:2:3m\x1b\\\x1bP0+r524742\x1b\\\x1b[?64;1c");
    sandbox.wait_for(LAST_QUESTION);
    sandbox.wait_for(b"truecolor (terminal says)");
    sandbox.wait_for(b"\x1b[38;2;");
    sandbox.quit();
}

#[test]
fn a_silent_terminal_gets_256_colours_and_a_hint() {
    let mut sandbox = Sandbox::start();
    sandbox.wait_for(LAST_QUESTION);
    sandbox.wait_for(b"256 (guessed; try --colors truecolor)");
    sandbox.wait_for(b"\x1b[38;5;");
    assert!(!sandbox.contains(b"\x1b[38;2;"));
    sandbox.quit();
}

/// xterm.js's pty reports no pixel size and nudge drew for 2.0-high cells in its 8×19 px ones
/// (issue 28). Here too the pty says no pixels: the sandbox asks XTWINOPS 16 (and nothing about
/// colour, which `--colors` settled), and the answer, 20×8 px, sets the cell aspect it draws for,
/// as the settings panel shows: one notch up from 2.50 is 2.55.
#[test]
fn a_pty_without_pixel_sizes_asks_the_terminal_for_its_cell_size() {
    let mut sandbox = Sandbox::start_with("--colors truecolor");
    sandbox.send(b"\x1b[6;20;8t\x1b[?1;2c");
    sandbox.wait_for(b"\x1b[16t\x1b[c");
    assert!(
        !sandbox.contains(LAST_QUESTION),
        "the colour depth was given"
    );
    sandbox.wait_for(b"\x1b[?2026l");
    // The settings, up to their last row (the cell aspect), one notch up.
    sandbox.send(b"t");
    sandbox.wait_for(b"settings: ");
    sandbox.send(b"\x1b[A");
    sandbox.send(b"\x1b[C");
    sandbox.wait_for(b"cell aspect 2.55");
    sandbox.quit();
}
