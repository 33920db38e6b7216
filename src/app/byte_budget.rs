//! A cap on the bytes per second the sandbox sends to its terminal, so a slow link (ssh, mosh, a
//! serial console) never queues frames it cannot carry: a frame late in a backed-up pipe is worse
//! than a frame skipped.
//!
//! A token bucket over bytes (the shape of a network traffic shaper):
//!
//! ```text
//! balance += rate · elapsed, at most `burst`     (every turn of the loop)
//! draw only while balance ≥ 0, then balance −= bytes written
//! ```
//!
//! A frame is never cut: it is sent whole or not drawn at all (the physics keeps running, the next
//! frame shows where things went). So over any window of T seconds the terminal receives at most
//! `burst + rate·T` plus the one frame that took the balance below zero. With `rate` = 90 % of the
//! limit and `burst` = a thirtieth of it, any one second carries at most 93 % of the limit plus one
//! frame: under the limit for frames up to 7 % of it (70 kB at 1 MB/s; a 200 × 50 truecolor collapse
//! sends about 30 kB a frame). Frames that repaint the whole screen (the first one, and after a
//! resize) are not charged: they are the price of having a picture at all.

use std::fmt;
use std::time::Duration;

/// The budget over SSH: what a polished tool may ask of a remote link, 1 MB/s.
pub const SSH_MAX_BYTES_PER_SECOND: u64 = 1_000_000;

/// Where the byte limit came from, for the status bar's note when it holds frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitOrigin {
    /// The session is remote (SSH's environment variables are set): [`SSH_MAX_BYTES_PER_SECOND`].
    Ssh,
    /// A local terminal: no limit (a big window of rain was held to a few frames a second).
    Local,
    /// `--max-bytes-per-second`.
    Flag,
}

impl LimitOrigin {
    /// The link `var` (an environment lookup) describes: remote when sshd set any of its variables.
    pub fn of_env(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> Self {
        let remote = ["SSH_CONNECTION", "SSH_CLIENT", "SSH_TTY"]
            .iter()
            .any(|name| var(name).is_some_and(|v| !v.is_empty()));
        if remote {
            LimitOrigin::Ssh
        } else {
            LimitOrigin::Local
        }
    }

    /// The limit this link gets when no flag sets one, bytes per second (0 = no limit).
    pub fn default_limit(self) -> u64 {
        match self {
            LimitOrigin::Ssh => SSH_MAX_BYTES_PER_SECOND,
            LimitOrigin::Local | LimitOrigin::Flag => 0,
        }
    }
}

/// The limit as the status bar's held-frames note gives it: "1.00 MB/s, ssh".
pub fn limit_note(limit: u64, origin: LimitOrigin) -> String {
    format!(
        "{}/s, {origin}",
        crate::app::panels::status::format_bytes(limit)
    )
}

impl fmt::Display for LimitOrigin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            LimitOrigin::Ssh => "ssh",
            LimitOrigin::Local => "local",
            LimitOrigin::Flag => "--max-bytes-per-second",
        })
    }
}

/// Share of the limit that refills each second.
const RATE_SHARE: f64 = 0.9;
/// Largest balance, as a share of the limit: one frame's share at 30 fps.
const BURST_SHARE: f64 = 1.0 / 30.0;

/// The byte budget of a terminal.
#[derive(Clone, Debug, PartialEq)]
pub struct ByteBudget {
    /// Bytes per second refilled; infinite for no limit.
    rate: f64,
    /// Largest balance, bytes.
    burst: f64,
    /// Bytes that may still be sent; below zero after a frame that overdrew.
    balance: f64,
}

impl ByteBudget {
    /// A budget holding the terminal under `limit` bytes per second (0 = no limit).
    pub fn new(limit: u64) -> Self {
        if limit == 0 {
            return Self::unlimited();
        }
        let limit = limit as f64;
        let burst = BURST_SHARE * limit;
        Self {
            rate: RATE_SHARE * limit,
            burst,
            balance: burst,
        }
    }

    /// No limit: every frame may be drawn.
    pub fn unlimited() -> Self {
        Self {
            rate: f64::INFINITY,
            burst: f64::INFINITY,
            balance: f64::INFINITY,
        }
    }

    /// Refills the budget for `elapsed` wall time.
    pub fn refill(&mut self, elapsed: Duration) {
        if self.rate.is_finite() {
            self.balance = (self.balance + self.rate * elapsed.as_secs_f64()).min(self.burst);
        }
    }

    /// Whether a frame may be drawn now.
    pub fn may_draw(&self) -> bool {
        self.balance >= 0.0
    }

    /// Charges a drawn frame's bytes.
    pub fn spend(&mut self, bytes: u64) {
        if self.rate.is_finite() {
            self.balance -= bytes as f64;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ssh_variables_make_the_link_remote_and_its_default_a_megabyte_a_second() {
        for var in ["SSH_CONNECTION", "SSH_CLIENT", "SSH_TTY"] {
            let origin = LimitOrigin::of_env(|name| (name == var).then(|| "192.0.2.1 22".into()));
            assert_eq!(origin, LimitOrigin::Ssh, "{var}");
            assert_eq!(origin.default_limit(), 1_000_000);
        }
        let local = LimitOrigin::of_env(|name| (name == "TERM").then(|| "xterm".into()));
        assert_eq!(local, LimitOrigin::Local);
        assert_eq!(local.default_limit(), 0, "no limit in a local terminal");
        let empty = LimitOrigin::of_env(|name| (name == "SSH_TTY").then(Default::default));
        assert_eq!(empty, LimitOrigin::Local, "an empty variable says nothing");
        assert_eq!(limit_note(1_000_000, LimitOrigin::Ssh), "1.00 MB/s, ssh");
        assert_eq!(
            limit_note(20_000, LimitOrigin::Flag),
            "20.0 kB/s, --max-bytes-per-second"
        );
    }

    const FRAME: Duration = Duration::from_nanos(1_000_000_000 / 30);

    /// Draws `frames` frames of `bytes` each at 30 fps through the budget; returns the bytes sent in
    /// each frame slot (0 where the frame was skipped).
    fn run(budget: &mut ByteBudget, frames: usize, bytes: u64) -> Vec<u64> {
        (0..frames)
            .map(|_| {
                budget.refill(FRAME);
                if budget.may_draw() {
                    budget.spend(bytes);
                    bytes
                } else {
                    0
                }
            })
            .collect()
    }

    fn worst_second(sent: &[u64]) -> u64 {
        sent.windows(30).map(|w| w.iter().sum()).max().unwrap_or(0)
    }

    #[test]
    fn frames_within_the_limit_are_all_drawn() {
        let mut budget = ByteBudget::new(1_000_000);
        // 30 kB × 30 fps = 900 kB/s: just within the refill rate.
        let sent = run(&mut budget, 300, 29_000);
        assert!(sent.iter().all(|&b| b == 29_000));
    }

    #[test]
    fn heavy_frames_are_skipped_so_every_second_stays_under_the_limit() {
        for bytes in [40_000, 60_000, 70_000] {
            let mut budget = ByteBudget::new(1_000_000);
            let sent = run(&mut budget, 600, bytes);
            let worst = worst_second(&sent);
            assert!(
                worst < 1_000_000,
                "{bytes} B frames: worst second {worst} B"
            );
            // And the link is still used: no more than two frames' worth below the rate.
            let mean = sent.iter().sum::<u64>() as f64 / 20.0;
            assert!(
                mean > 900_000.0 - 2.0 * bytes as f64,
                "{bytes} B frames: {mean} B/s"
            );
        }
    }

    #[test]
    fn a_burst_after_a_quiet_spell_is_bounded_too() {
        let mut budget = ByteBudget::new(1_000_000);
        let mut sent = run(&mut budget, 90, 0);
        sent.extend(run(&mut budget, 300, 50_000));
        assert!(worst_second(&sent) < 1_000_000);
    }

    #[test]
    fn no_limit_draws_everything() {
        let mut budget = ByteBudget::new(0);
        assert_eq!(budget, ByteBudget::unlimited());
        let sent = run(&mut budget, 60, 10_000_000);
        assert!(sent.iter().all(|&b| b == 10_000_000));
    }
}
