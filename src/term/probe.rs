//! Asking the terminal itself whether it shows 24-bit colour, for when the environment cannot say
//! (ssh forwards neither `COLORTERM` nor `TERM_PROGRAM`).
//!
//! Three questions, then a sentinel, in one write (as notcurses and Neovim ask):
//!
//! 1. **DECRQSS after a direct colour**: set the background to `48;2;1;2;3`, ask for the current SGR
//!    (`DCS $ q m ST`), reset (`CSI 0 m`). A terminal that keeps 24-bit colours reports them back
//!    (`DCS 1 $ r 0;48:2::1:2:3m ST`, separators vary); one that maps them to its palette reports
//!    `48;5;16` or nothing of the kind. This is the question xterm answers truthfully whatever its
//!    `TERM` says.
//! 2. **XTGETTCAP** for the terminfo capabilities `RGB` and `Tc` (`DCS + q 524742;5463 ST`, names in
//!    hex): `DCS 1 + r 524742… ST` means the terminal's own terminfo has it (kitty, foot, WezTerm).
//! 3. **XTVERSION** (`CSI > 0 q`): the terminal's name (`DCS > | name ST`). xterm.js, the terminal
//!    of VS Code and ttyd, answers DECRQSS with a fixed `0m` whatever colour is set, but has shown
//!    24-bit colour since version 3 and names itself here (`xterm.js(6.0.0)`); so do other
//!    terminals that always keep 24-bit colour ([`TRUECOLOR_TERMINALS`]).
//! 4. **DA1** (`CSI c`), which every terminal answers, last: terminals answer in order, so once its
//!    reply (`CSI ? … c`) is in, every reply is in, and a terminal that ignores the questions costs
//!    one round trip instead of the whole timeout.
//!
//! The replies are read with a deadline of at most [`PROBE_TIMEOUT`] (100 ms), in raw mode, before the
//! event loop starts reading. No reply, a garbled one or a late one means "not truecolor". Nothing
//! is printed: the questions are control strings a terminal that does not know them ignores, and
//! the SGR state is reset. A reply that comes after the deadline is still on its way to the event
//! loop; [`ProbeOutcome::complete`] tells the app to drop it there (crossterm reads a DCS reply as
//! `Alt+P`, its characters as keys, and `Alt+\`; it drops a DA1 reply itself).
//!
//! Only worth asking when the guess is uncertain (a `TERM` that is neither `*-direct` nor backed by
//! `COLORTERM` or a known `TERM_PROGRAM`), and never on a `linux` console, which reads `ESC P` as
//! "set palette" ([`safe_to_ask`]).

use std::io::{self, Write};
use std::time::{Duration, Instant};

/// Whether a terminal with this `TERM` may be asked at all: the Linux console takes `ESC P` for
/// "set palette" and would show garbage (`linux`, `linux-16color`, ...).
pub fn safe_to_ask(term: Option<&str>) -> bool {
    !term.is_some_and(|t| t.trim() == "linux" || t.trim().starts_with("linux-"))
}

/// The longest the probe waits for the terminal's replies.
pub const PROBE_TIMEOUT: Duration = Duration::from_millis(100);

/// The questions, in the order sent (see the module docs).
pub const QUERY: &[u8] =
    b"\x1b[48;2;1;2;3m\x1bP$qm\x1b\\\x1b[0m\x1bP+q524742;5463\x1b\\\x1b[>0q\x1b[c";

/// Terminals that show 24-bit colour in every version that answers XTVERSION, by the name they
/// give (matched at the start of the reply, ignoring case): xterm.js cannot say so any other way.
pub const TRUECOLOR_TERMINALS: &[&str] = &["xterm.js", "kitty", "WezTerm", "foot", "ghostty"];

/// Most reply bytes kept: far more than the three replies take; anything beyond is junk.
const MAX_REPLY: usize = 4096;

/// What the terminal said.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// It keeps a 24-bit colour (DECRQSS) or its terminfo says `RGB`/`Tc` (XTGETTCAP).
    TrueColor,
    /// It answered (at least DA1) but not with 24-bit colour.
    NotTrueColor,
    /// Nothing usable before the deadline.
    Silent,
}

/// The result of [`probe`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProbeOutcome {
    pub answer: Answer,
    /// A cell's size in pixels, height and width, if it was asked for ([`Questions::cell_size`])
    /// and the terminal said.
    pub cell_px: Option<(u16, u16)>,
    /// The DA1 reply came in before the deadline, so no reply is still on its way. When `false`,
    /// late replies may reach the event loop and must be dropped there.
    pub complete: bool,
}

/// Where the terminal's replies come from (the tty, or a fake one in tests).
pub trait ReplySource {
    /// Reads what is available into `buf`, waiting until `deadline` at most; `Ok(0)` when the
    /// deadline passed with nothing to read.
    fn read_before(&mut self, buf: &mut [u8], deadline: Instant) -> io::Result<usize>;
}

/// XTWINOPS 16, the size of a cell in pixels, for a terminal whose pty reports none (xterm.js):
/// answered `CSI 6 ; height ; width t`.
pub const CELL_SIZE_QUESTION: &[u8] = b"\x1b[16t";

/// What to ask the terminal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Questions {
    /// Whether it shows 24-bit colour (the questions of [`QUERY`]).
    pub truecolor: bool,
    /// Its cell size in pixels ([`CELL_SIZE_QUESTION`]).
    pub cell_size: bool,
}

impl Questions {
    /// The bytes to send: the questions asked, then DA1, the sentinel.
    pub fn bytes(self) -> Vec<u8> {
        let mut out = Vec::new();
        if self.truecolor {
            out.extend_from_slice(QUERY.strip_suffix(DA1_QUESTION).unwrap_or(QUERY));
        }
        if self.cell_size {
            out.extend_from_slice(CELL_SIZE_QUESTION);
        }
        out.extend_from_slice(DA1_QUESTION);
        out
    }
}

/// DA1, which every terminal answers: sent last (see the module docs).
const DA1_QUESTION: &[u8] = b"\x1b[c";

/// Sends [`QUERY`] to `out` and reads the replies from `replies` for at most `timeout` (capped at
/// [`PROBE_TIMEOUT`]). The terminal must be in raw mode, and nothing else may read its input
/// meanwhile.
pub fn probe(
    out: &mut dyn Write,
    replies: &mut dyn ReplySource,
    timeout: Duration,
) -> io::Result<ProbeOutcome> {
    let truecolor_only = Questions {
        truecolor: true,
        cell_size: false,
    };
    ask(out, replies, timeout, truecolor_only)
}

/// [`probe`] with the questions chosen: a colour depth that is certain need not be asked, a pty that
/// reports its pixel size need not be asked the cell size.
pub fn ask(
    out: &mut dyn Write,
    replies: &mut dyn ReplySource,
    timeout: Duration,
    questions: Questions,
) -> io::Result<ProbeOutcome> {
    out.write_all(&questions.bytes())?;
    out.flush()?;
    let deadline = Instant::now() + timeout.min(PROBE_TIMEOUT);
    let mut received = Vec::new();
    let mut chunk = [0u8; 512];
    let mut complete = false;
    while received.len() < MAX_REPLY {
        let n = replies.read_before(&mut chunk, deadline)?;
        if n == 0 {
            break;
        }
        received.extend_from_slice(&chunk[..n.min(chunk.len())]);
        if has_device_attributes(&received) {
            complete = true;
            break;
        }
    }
    let answer = if says_truecolor(&received) {
        Answer::TrueColor
    } else if complete {
        Answer::NotTrueColor
    } else {
        Answer::Silent
    };
    let cell_px = questions
        .cell_size
        .then(|| cell_size_px(&received))
        .flatten();
    Ok(ProbeOutcome {
        answer,
        cell_px,
        complete,
    })
}

/// The cell size an XTWINOPS report in `bytes` gives (`CSI 6 ; height ; width t`), height and
/// width in pixels, if whole and not zero.
pub fn cell_size_px(bytes: &[u8]) -> Option<(u16, u16)> {
    let start = bytes.windows(4).position(|w| w == b"\x1b[6;")? + 4;
    let rest = &bytes[start..];
    let end = rest.iter().position(|&b| b == b't')?;
    let text = std::str::from_utf8(&rest[..end]).ok()?;
    let (height, width) = text.split_once(';')?;
    let (height, width) = (height.parse::<u16>().ok()?, width.parse::<u16>().ok()?);
    (height > 0 && width > 0).then_some((height, width))
}

/// Whether `bytes` hold a whole DA1 reply, `CSI ? params c`.
fn has_device_attributes(bytes: &[u8]) -> bool {
    bytes.windows(3).enumerate().any(|(i, w)| {
        w == b"\x1b[?"
            && bytes[i + 3..]
                .iter()
                .find(|b| !(b.is_ascii_digit() || **b == b';'))
                .is_some_and(|&end| end == b'c')
    })
}

/// The bodies of the complete DCS strings in `bytes` (between `ESC P` and `ESC \` or BEL).
fn dcs_bodies(bytes: &[u8]) -> Vec<&[u8]> {
    let mut bodies = Vec::new();
    let mut rest = bytes;
    while let Some(start) = rest.windows(2).position(|w| w == b"\x1bP") {
        let body = &rest[start + 2..];
        let end = body
            .iter()
            .enumerate()
            .find(|&(i, &b)| b == 0x07 || (b == 0x1b && body.get(i + 1) == Some(&b'\\')))
            .map(|(i, _)| i);
        let Some(end) = end else { break };
        bodies.push(&body[..end]);
        rest = &body[end..];
    }
    bodies
}

/// Whether any reply in `bytes` says 24-bit colour (see the module docs).
pub fn says_truecolor(bytes: &[u8]) -> bool {
    dcs_bodies(bytes).into_iter().any(|body| {
        if let Some(sgr) = body.strip_prefix(b"1$r") {
            reports_direct_background(sgr)
        } else if let Some(caps) = body.strip_prefix(b"1+r") {
            names_a_truecolor_capability(caps)
        } else if let Some(name) = body.strip_prefix(b">|") {
            names_a_truecolor_terminal(name)
        } else {
            false
        }
    })
}

/// Whether a DECRQSS SGR report (`0;48:2::1:2:3m`) holds the background we set, 48;2;1;2;3 (the
/// colour-space field of the colon form may be empty or absent).
fn reports_direct_background(sgr: &[u8]) -> bool {
    let Some(params) = sgr.strip_suffix(b"m") else {
        return false;
    };
    let numbers: Vec<&[u8]> = params
        .split(|&b| b == b';' || b == b':')
        .filter(|p| !p.is_empty())
        .collect();
    let wanted: [&[u8]; 5] = [b"48", b"2", b"1", b"2", b"3"];
    numbers.windows(5).any(|w| w == wanted)
}

/// Whether an XTGETTCAP success (`524742=…;5463`) names `RGB` or `Tc`.
fn names_a_truecolor_capability(caps: &[u8]) -> bool {
    caps.split(|&b| b == b';').any(|cap| {
        let name = cap.split(|&b| b == b'=').next().unwrap_or_default();
        let upper = name.to_ascii_uppercase();
        upper == b"524742" || upper == b"5463"
    })
}

/// Whether an XTVERSION reply (`xterm.js(6.0.0)`, `kitty(0.35.2)`, `WezTerm 20240203`) names one
/// of [`TRUECOLOR_TERMINALS`].
fn names_a_truecolor_terminal(name: &[u8]) -> bool {
    let name = String::from_utf8_lossy(name).to_ascii_lowercase();
    TRUECOLOR_TERMINALS.iter().any(|known| {
        name.strip_prefix(&known.to_ascii_lowercase())
            .is_some_and(|rest| rest.is_empty() || rest.starts_with(['(', ' ', '-']))
    })
}

/// The terminal's replies on standard input (which must be the terminal, in raw mode).
#[cfg(unix)]
pub struct StdinReplies(pub io::Stdin);

#[cfg(unix)]
impl ReplySource for StdinReplies {
    fn read_before(&mut self, buf: &mut [u8], deadline: Instant) -> io::Result<usize> {
        use rustix::event::{PollFd, PollFlags, Timespec, poll};
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(0);
            }
            let timeout = Timespec::try_from(left).map_err(io::Error::other)?;
            let mut fds = [PollFd::new(&self.0, PollFlags::IN)];
            match poll(&mut fds, Some(&timeout)) {
                Ok(0) => return Ok(0),
                Ok(_) => {}
                Err(rustix::io::Errno::INTR) => continue,
                Err(err) => return Err(err.into()),
            }
            if fds[0].revents().intersects(PollFlags::IN) {
                // Not through `Stdin`'s own buffer: what it keeps the event loop would never see.
                return match rustix::io::read(&self.0, &mut *buf) {
                    Ok(n) => Ok(n),
                    Err(rustix::io::Errno::INTR | rustix::io::Errno::AGAIN) => continue,
                    Err(err) => Err(err.into()),
                };
            }
            // Hung up or in error: nothing will come.
            return Ok(0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xterm_js_naming_itself_is_truecolor_and_tmux_or_xterm_by_name_alone_is_not() {
        // xterm.js 6.0 in Chromium: DECRQSS says a fixed `0m`, no XTGETTCAP, its name, DA1.
        let xterm_js = b"\x1bP1$r0m\x1b\\\x1bP>|xterm.js(6.0.0)\x1b\\\x1b[?1;2c";
        assert!(says_truecolor(xterm_js));
        assert!(says_truecolor(b"\x1bP>|kitty(0.35.2)\x1b\\"));
        assert!(says_truecolor(
            b"\x1bP>|WezTerm 20240203-110809-5046fc22\x1b\\"
        ));
        // tmux's colours depend on the terminal outside it; xterm's own answer is DECRQSS.
        assert!(!says_truecolor(b"\x1bP>|tmux 3.3a\x1b\\"));
        assert!(!says_truecolor(b"\x1bP>|XTerm(390)\x1b\\"));
        assert!(!says_truecolor(b"\x1bP>|kittyish\x1b\\"));
    }

    #[test]
    fn a_cell_size_report_gives_height_and_width_and_anything_else_none() {
        assert_eq!(
            cell_size_px(b"\x1bP1$r0m\x1b\\\x1b[6;19;8t\x1b[?1;2c"),
            Some((19, 8))
        );
        assert_eq!(cell_size_px(b"\x1b[6;0;8t"), None);
        assert_eq!(cell_size_px(b"\x1b[6;19t"), None);
        assert_eq!(cell_size_px(b"\x1b[6;19;8"), None, "cut off");
        assert_eq!(cell_size_px(b"\x1b[?1;2c"), None);
    }

    #[test]
    fn the_truecolor_questions_alone_are_the_query_and_the_cell_size_goes_before_da1() {
        let colour = Questions {
            truecolor: true,
            cell_size: false,
        };
        assert_eq!(colour.bytes(), QUERY);
        let both = Questions {
            cell_size: true,
            ..colour
        };
        assert!(both.bytes().ends_with(b"\x1b[16t\x1b[c"));
        let size = Questions {
            truecolor: false,
            cell_size: true,
        };
        assert_eq!(size.bytes(), b"\x1b[16t\x1b[c");
    }

    #[test]
    fn the_linux_console_is_never_asked_and_an_xterm_is() {
        for term in ["linux", "linux-16color"] {
            assert!(!safe_to_ask(Some(term)), "{term}");
        }
        for term in [Some("xterm"), Some("screen"), Some("xterm-256color"), None] {
            assert!(safe_to_ask(term), "{term:?}");
        }
    }

    #[test]
    fn decrqss_reports_in_either_separator_style_count() {
        assert!(says_truecolor(b"\x1bP1$r0;48:2::1:2:3m\x1b\\"));
        assert!(says_truecolor(b"\x1bP1$r48;2;1;2;3m\x1b\\"));
        assert!(says_truecolor(b"\x1bP1$r0;48:2:1:2:3m\x07"));
        // Mapped to the palette, or refused.
        assert!(!says_truecolor(b"\x1bP1$r0;48;5;16m\x1b\\"));
        assert!(!says_truecolor(b"\x1bP0$r\x1b\\"));
        // Bold, dim, italic: what a 256-colour terminal makes of "48;2;1;2;3".
        assert!(!says_truecolor(b"\x1bP1$r0;1;2;3m\x1b\\"));
    }

    #[test]
    fn xtgettcap_names_rgb_or_tc() {
        assert!(says_truecolor(b"\x1bP1+r524742=382F382F38\x1b\\"));
        assert!(says_truecolor(b"\x1bP1+r5463\x1b\\"));
        assert!(says_truecolor(b"\x1bP0+r524742\x1b\\\x1bP1+r5463\x1b\\"));
        assert!(!says_truecolor(b"\x1bP0+r524742;5463\x1b\\"));
        assert!(!says_truecolor(b"\x1bP1+r636F6C6F7273=323536\x1b\\")); // colors=256
    }

    #[test]
    fn unterminated_or_foreign_strings_say_nothing() {
        assert!(!says_truecolor(b"\x1bP1$r48;2;1;2;3m"));
        assert!(!says_truecolor(b"48;2;1;2;3m 1+r524742"));
        assert!(!says_truecolor(b""));
    }

    #[test]
    fn the_da1_reply_is_recognised_whole() {
        assert!(has_device_attributes(b"\x1b[?62;22c"));
        assert!(has_device_attributes(b"junk\x1b[?1;2c"));
        assert!(!has_device_attributes(b"\x1b[?62;2"));
        assert!(!has_device_attributes(b"\x1b[?62u"));
    }

    #[test]
    fn the_query_asks_decrqss_then_xtgettcap_then_da1_and_resets_the_sgr() {
        let text = String::from_utf8_lossy(QUERY);
        let at = |needle: &str| text.find(needle).unwrap();
        assert!(at("\x1b[48;2;1;2;3m") < at("\x1bP$qm\x1b\\"));
        assert!(at("\x1bP$qm\x1b\\") < at("\x1b[0m"));
        assert!(at("\x1b[0m") < at("\x1bP+q524742;5463\x1b\\"));
        assert!(text.ends_with("\x1b[c"));
    }
}
