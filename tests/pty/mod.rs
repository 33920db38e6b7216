//! The real binary on a real pseudo-terminal, for the tests of what only a terminal can show:
//! signals, job control, a terminal that never answers a query. util-linux's `script` makes the
//! pseudo-terminal (the crate forbids `unsafe`, which opening one ourselves would need): what the
//! test writes to `script`'s stdin is typed into the terminal, and everything the sandbox writes
//! comes back on `script`'s stdout. Nothing on the other side answers a query such as `ESC[6n`:
//! every test here runs on a silent terminal, unless it types the answers in ahead
//! ([`Sandbox::start_answering`]). `COLORTERM` and `TERM_PROGRAM` are unset, so the sandbox asks the
//! terminal whether it does truecolor (`term::probe`, raw mode, before the event loop) every time.
#![allow(dead_code)] // each test file uses its own part

use std::io::{Read, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How long the sandbox may take to start drawing (a loaded CI machine), and to do anything else.
pub const START_TIMEOUT: Duration = Duration::from_secs(30);
pub const TIMEOUT: Duration = Duration::from_secs(10);
/// The alternate-screen sequence the sandbox writes once its terminal is set up, and the one that
/// leaves it, last in the restore sequence.
pub const ENTER: &[u8] = b"\x1b[?1049h";
pub const LEAVE: &[u8] = b"\x1b[?1049l";
/// Turning press/release mouse reporting off, part of the restore sequence.
pub const MOUSE_OFF: &[u8] = b"\x1b[?1000l";
/// The last of the truecolor probe's colour questions (XTVERSION, after DECRQSS and XTGETTCAP), in
/// the one write that ends with the cell size (where the pty reports no pixels) and DA1.
pub const PROBE_LAST_QUESTION: &[u8] = b"\x1bP+q524742;5463\x1b\\\x1b[>0q";
/// What a truecolor terminal answers the probe: the direct colour kept, `RGB` in its terminfo, DA1.
pub const TRUECOLOR_REPLIES: &[u8] = b"\x1bP1$r0;48:2::1:2:3m\x1b\\\x1bP0+r524742\x1b\\\x1b[?64;1c";
/// The end of a synchronized update, which closes every frame the sandbox draws.
pub const FRAME_END: &[u8] = b"\x1b[?2026l";
/// Fewer bytes than any whole frame of the default scene on a 100×30 terminal (about 20 kB): a
/// frame this large after a mark repainted the screen.
pub const WHOLE_FRAME_BYTES: usize = 3_000;

/// The sandbox running on a pseudo-terminal.
pub struct Sandbox {
    script: Child,
    keys: ChildStdin,
    output: Arc<Mutex<Vec<u8>>>,
    /// The sandbox's own process (a child of `script`), found by a marker in its command line.
    pub pid: u32,
}

/// A command run by `script` on a fresh pseudo-terminal: its keyboard (`keys`) and everything it
/// has written so far (`output`, drained by a thread so that it never blocks writing).
pub struct Pty {
    pub script: Child,
    pub keys: ChildStdin,
    pub output: Arc<Mutex<Vec<u8>>>,
}

impl Pty {
    /// Runs the shell command `command` under `script` with `TERM=xterm-256color` and neither
    /// `COLORTERM` nor `TERM_PROGRAM`; with `exit_status`, `script` exits with the command's status.
    pub fn open(command: &str, exit_status: bool) -> Pty {
        let mut args = vec!["-q", "-f"];
        if exit_status {
            args.push("-e");
        }
        args.extend(["-c", command, "/dev/null"]);
        let mut script = Command::new("script")
            .args(&args)
            .env("TERM", "xterm-256color")
            .env_remove("COLORTERM")
            .env_remove("TERM_PROGRAM")
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("util-linux `script` runs (it provides the pseudo-terminal)");
        let keys = script.stdin.take().expect("piped stdin");
        let mut out = script.stdout.take().expect("piped stdout");
        let output = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&output);
        std::thread::spawn(move || {
            let mut buf = [0u8; 8192];
            while let Ok(n @ 1..) = out.read(&mut buf) {
                sink.lock().unwrap().extend_from_slice(&buf[..n]);
            }
        });
        Pty {
            script,
            keys,
            output,
        }
    }
}

/// A `--max-bytes-per-second` value no other process has, to find a sandbox among the processes.
pub fn unique_marker() -> String {
    static COUNT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    format!("{}", 1_000_000 + std::process::id() * 64 + n)
}

/// Pids of live (not zombie) `nudge` processes whose command line contains `marker` (`script`,
/// and the shell before its `exec`, have it in theirs too).
pub fn processes_with(marker: &str) -> Vec<u32> {
    let Ok(entries) = std::fs::read_dir("/proc") else {
        return Vec::new();
    };
    entries
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .filter(|pid| {
            let cmdline = std::fs::read(format!("/proc/{pid}/cmdline")).unwrap_or_default();
            let program = cmdline.split(|&b| b == 0).next().unwrap_or_default();
            program.ends_with(b"nudge")
                && String::from_utf8_lossy(&cmdline).contains(marker)
                && process_state(*pid).is_some_and(|s| s != 'Z')
        })
        .collect()
}

/// The state letter of `/proc/PID/stat` (R, S, T for stopped, Z, ...), `None` once it is gone.
pub fn process_state(pid: u32) -> Option<char> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The state follows the parenthesised command name: "pid (comm) S ...".
    stat.rsplit(')').next()?.trim_start().chars().next()
}

/// Finds `needle` in `haystack` at or after `from`; the index just past it.
fn find_from(haystack: &[u8], needle: &[u8], from: usize) -> Option<usize> {
    haystack
        .get(from..)?
        .windows(needle.len())
        .position(|w| w == needle)
        .map(|i| from + i + needle.len())
}

impl Sandbox {
    /// Starts `nudge ARGS` on a fresh 100×30 pseudo-terminal with `TERM=xterm-256color` and waits for its
    /// first frame. Panics if it does not draw within [`START_TIMEOUT`].
    pub fn start(args: &[&str]) -> Sandbox {
        Self::start_answering(args, b"")
    }

    /// [`Sandbox::start`], with `replies` typed into the terminal at once, as a terminal answering
    /// the queries the sandbox sends at start-up would (they wait in its input until read).
    pub fn start_answering(args: &[&str], replies: &[u8]) -> Sandbox {
        let marker = unique_marker();
        let command = format!(
            // `script` gives its terminal the size of its own, none here: set one.
            "stty rows 30 cols 100; exec {} {} --max-bytes-per-second {marker}",
            env!("CARGO_BIN_EXE_nudge"),
            args.join(" ")
        );
        let Pty {
            script,
            keys,
            output,
        } = Pty::open(&command, true);
        let mut sandbox = Sandbox {
            script,
            keys,
            output,
            pid: 0,
        };
        if !replies.is_empty() {
            sandbox.type_keys(replies);
        }
        let drawn = sandbox.wait_for_whole_frame(0, START_TIMEOUT);
        let pids = processes_with(&marker);
        assert!(
            drawn.is_some() && pids.len() == 1,
            "the sandbox did not draw on the pseudo-terminal ({} bytes, sandboxes {pids:?}): {:?}",
            sandbox.mark(),
            sandbox.text()
        );
        sandbox.pid = pids[0];
        sandbox
    }

    /// Everything the sandbox wrote so far.
    pub fn output(&self) -> Vec<u8> {
        self.output.lock().unwrap().clone()
    }

    /// The output as text, for failure messages (the last 2 kB).
    pub fn text(&self) -> String {
        let out = self.output();
        String::from_utf8_lossy(&out[out.len().saturating_sub(2000)..]).into_owned()
    }

    /// Output length so far: a mark to look for what comes after it.
    pub fn mark(&self) -> usize {
        self.output.lock().unwrap().len()
    }

    /// Waits until `needle` appears at or after `from`; the index just past it.
    pub fn wait_for(&self, needle: &[u8], from: usize, timeout: Duration) -> Option<usize> {
        let start = Instant::now();
        loop {
            if let Some(end) = find_from(&self.output(), needle, from) {
                return Some(end);
            }
            if start.elapsed() > timeout {
                return None;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Waits until a frame of at least [`WHOLE_FRAME_BYTES`] ends after `from`, i.e. the screen
    /// was painted whole; the index just past it.
    pub fn wait_for_whole_frame(&self, from: usize, timeout: Duration) -> Option<usize> {
        let start = Instant::now();
        loop {
            let out = self.output();
            let mut at = from;
            while let Some(end) = find_from(&out, FRAME_END, at) {
                if end - from >= WHOLE_FRAME_BYTES {
                    return Some(end);
                }
                at = end;
            }
            if start.elapsed() > timeout {
                return None;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Types `bytes` into the terminal.
    pub fn type_keys(&mut self, bytes: &[u8]) {
        self.keys.write_all(bytes).expect("type into the terminal");
        self.keys.flush().expect("flush keys");
    }

    /// Sends `kill -SIGNAL` (a name such as `TSTP`) to the sandbox.
    pub fn signal(&self, name: &str) {
        let status = Command::new("kill")
            .args([&format!("-{name}"), &self.pid.to_string()])
            .status()
            .expect("kill runs");
        assert!(status.success(), "kill -{name} failed");
    }

    /// Continues the stopped sandbox as a shell's `fg` would. `script` stops itself when its child
    /// stops (so it forwards nothing meanwhile) and continues the child when it is continued: the
    /// signal goes to `script`, and to the sandbox directly too. `script` stops a moment after its
    /// child does, when it reads the SIGCHLD: continued before that, it would stop afterwards and
    /// never forward the sandbox's output again (a CI run lost its repaint so), so this waits for
    /// it to stop first (up to [`TIMEOUT`]: a `script` that does not stop itself is continued
    /// after it, late but as before).
    pub fn continue_job(&self) {
        let script = self.script.id();
        let start = Instant::now();
        while process_state(script) != Some('T') && start.elapsed() < TIMEOUT {
            std::thread::sleep(Duration::from_millis(5));
        }
        for pid in [script, self.pid] {
            let status = Command::new("kill")
                .args(["-CONT", &pid.to_string()])
                .status()
                .expect("kill runs");
            assert!(status.success(), "kill -CONT {pid} failed");
        }
    }

    /// Waits until the sandbox's process state is `state` (`'T'` stopped, `'S'` sleeping, ...).
    pub fn wait_state(&self, wanted: impl Fn(char) -> bool) -> bool {
        let start = Instant::now();
        while start.elapsed() < TIMEOUT {
            if process_state(self.pid).is_some_and(&wanted) {
                return true;
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        false
    }

    /// The terminal's line settings as `stty -a` prints them: raw mode shows `-icanon -echo`,
    /// cooked mode `icanon echo`.
    pub fn tty_settings(&self) -> String {
        let tty =
            std::fs::read_link(format!("/proc/{}/fd/0", self.pid)).expect("the sandbox's tty");
        let out = Command::new("stty")
            .arg("-F")
            .arg(&tty)
            .arg("-a")
            .output()
            .expect("stty runs");
        String::from_utf8_lossy(&out.stdout).into_owned()
    }

    /// Whether the terminal is in raw mode (no line editing, no echo).
    pub fn is_raw(&self) -> bool {
        let settings = self.tty_settings();
        let words: Vec<&str> = settings.split_whitespace().collect();
        words.contains(&"-icanon") && words.contains(&"-echo")
    }

    /// Whether the terminal is in cooked mode (line editing and echo, as a shell leaves it).
    pub fn is_cooked(&self) -> bool {
        let settings = self.tty_settings();
        let words: Vec<&str> = settings.split_whitespace().collect();
        words.contains(&"icanon") && words.contains(&"echo")
    }

    /// Waits for the sandbox to exit; its status as `script -e` reports it, `None` on timeout.
    pub fn wait_exit(&mut self, timeout: Duration) -> Option<i32> {
        let start = Instant::now();
        while start.elapsed() < timeout {
            if let Ok(Some(status)) = self.script.try_wait() {
                return status.code();
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        None
    }
}

impl Drop for Sandbox {
    fn drop(&mut self) {
        if process_state(self.pid).is_some() {
            let _ = Command::new("kill")
                .args(["-9", &self.pid.to_string()])
                .status();
        }
        let _ = self.script.kill();
        let _ = self.script.wait();
    }
}
