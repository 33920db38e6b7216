//! The truecolor probe against fake terminals: one that answers, one that ignores the questions,
//! one that says nothing, one that answers late and one that answers garbage.

use std::collections::VecDeque;
use std::io;
use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use nudge::app::{App, AppConfig};
use nudge::scene;
use nudge::term::ColorDepth;
use nudge::term::probe::{
    Answer, PROBE_TIMEOUT, ProbeOutcome, QUERY, Questions, ReplySource, probe,
};

/// What a fake terminal does when read.
enum Reply {
    /// These bytes are there to read.
    Now(&'static [u8]),
    /// Nothing before the deadline (the bytes come later, to the event loop).
    Late(&'static [u8]),
}

/// A terminal that replies from a script and records how it was asked.
struct FakeTerminal {
    script: VecDeque<Reply>,
    /// Bytes that arrived after the probe's deadline.
    late: Vec<u8>,
    /// Reads the probe made, and the longest wait it asked for.
    reads: usize,
    longest_wait: Duration,
}

impl FakeTerminal {
    fn new(script: Vec<Reply>) -> Self {
        Self {
            script: script.into(),
            late: Vec::new(),
            reads: 0,
            longest_wait: Duration::ZERO,
        }
    }
}

impl ReplySource for FakeTerminal {
    fn read_before(&mut self, buf: &mut [u8], deadline: Instant) -> io::Result<usize> {
        self.reads += 1;
        self.longest_wait = self
            .longest_wait
            .max(deadline.saturating_duration_since(Instant::now()));
        match self.script.pop_front() {
            Some(Reply::Now(bytes)) => {
                buf[..bytes.len()].copy_from_slice(bytes);
                Ok(bytes.len())
            }
            Some(Reply::Late(bytes)) => {
                self.late.extend_from_slice(bytes);
                Ok(0)
            }
            // Silence: the deadline passes.
            None => Ok(0),
        }
    }
}

fn ask(terminal: &mut FakeTerminal) -> (ProbeOutcome, Vec<u8>) {
    let mut written = Vec::new();
    let outcome = probe(&mut written, terminal, Duration::from_secs(10)).expect("probe");
    (outcome, written)
}

const XTERM_DECRQSS: &[u8] = b"\x1bP1$r0;48:2::1:2:3m\x1b\\";
const DA1: &[u8] = b"\x1b[?64;1;2;6;9;15;16;17;18;21;22;28c";

#[test]
fn a_terminal_that_keeps_a_direct_colour_is_truecolor() {
    let mut xterm = FakeTerminal::new(vec![
        Reply::Now(XTERM_DECRQSS),
        Reply::Now(b"\x1bP0+r524742;5463\x1b\\"),
        Reply::Now(DA1),
    ]);
    let (outcome, written) = ask(&mut xterm);
    assert_eq!(written, QUERY);
    assert_eq!(
        outcome,
        ProbeOutcome {
            answer: Answer::TrueColor,
            cell_px: None,
            complete: true
        }
    );
    assert_eq!(xterm.reads, 3, "stops reading at the DA1 reply");
}

#[test]
fn a_terminal_whose_terminfo_says_rgb_is_truecolor_even_in_one_read() {
    let mut kitty = FakeTerminal::new(vec![Reply::Now(
        b"\x1bP0$r\x1b\\\x1bP1+r524742=382F382F38\x1b\\\x1b[?62;c",
    )]);
    let (outcome, _) = ask(&mut kitty);
    assert_eq!(outcome.answer, Answer::TrueColor);
    assert!(outcome.complete);
}

#[test]
fn a_256_colour_terminal_that_answers_is_not_truecolor_and_is_not_waited_for() {
    let mut terminal = FakeTerminal::new(vec![
        Reply::Now(b"\x1bP1$r0;48;5;16m\x1b\\\x1bP0+r524742;5463\x1b\\"),
        Reply::Now(DA1),
    ]);
    let (outcome, _) = ask(&mut terminal);
    assert_eq!(
        outcome,
        ProbeOutcome {
            answer: Answer::NotTrueColor,
            cell_px: None,
            complete: true
        }
    );
    // A terminal that ignores both questions still answers DA1: one read, no timeout.
    let mut ignores = FakeTerminal::new(vec![Reply::Now(b"\x1b[?1;2c")]);
    let (outcome, _) = ask(&mut ignores);
    assert_eq!(
        (outcome.answer, outcome.complete),
        (Answer::NotTrueColor, true)
    );
    assert_eq!(ignores.reads, 1);
}

#[test]
fn a_silent_terminal_is_given_100_ms_at_most_and_means_not_truecolor() {
    let mut silent = FakeTerminal::new(vec![]);
    let (outcome, _) = ask(&mut silent);
    assert_eq!(
        outcome,
        ProbeOutcome {
            answer: Answer::Silent,
            cell_px: None,
            complete: false
        }
    );
    assert!(PROBE_TIMEOUT <= Duration::from_millis(100));
    assert!(
        silent.longest_wait <= PROBE_TIMEOUT,
        "asked to wait {:?}",
        silent.longest_wait
    );
}

#[test]
fn a_garbled_reply_means_not_truecolor() {
    let mut garbled = FakeTerminal::new(vec![
        Reply::Now(b"\x1bP1$r48;2;1;2"),
        Reply::Now(b"\xff\xfe\x1b[?\x1bP1+r52474\x1b\\zz"),
        Reply::Now(DA1),
    ]);
    let (outcome, _) = ask(&mut garbled);
    assert_eq!(
        (outcome.answer, outcome.complete),
        (Answer::NotTrueColor, true)
    );
    // Garbage and no DA1: silent, and the rest may still come.
    let mut garbage = FakeTerminal::new(vec![Reply::Now(b"\x1bP\x1bP\x1b\\\x1b[?12;")]);
    let (outcome, _) = ask(&mut garbage);
    assert_eq!((outcome.answer, outcome.complete), (Answer::Silent, false));
}

#[test]
fn the_questions_print_nothing() {
    // Every byte belongs to a CSI sequence (ESC [ params final) or a DCS string (ESC P … ESC \).
    let mut rest = QUERY;
    while !rest.is_empty() {
        assert_eq!(
            rest[0],
            0x1b,
            "printable byte in {:?}",
            String::from_utf8_lossy(rest)
        );
        rest = match rest[1] {
            b'[' => {
                let end = rest[2..]
                    .iter()
                    .position(|b| (0x40..=0x7e).contains(b))
                    .expect("CSI final byte");
                &rest[end + 3..]
            }
            b'P' => {
                let end = rest.windows(2).position(|w| w == b"\x1b\\").expect("ST");
                &rest[end + 2..]
            }
            other => panic!("unexpected escape {other}"),
        };
    }
    // And the SGR state is reset after the direct colour is set.
    let text = String::from_utf8_lossy(QUERY);
    assert!(text.find("\x1b[0m").unwrap() > text.find("\x1b[48;2;").unwrap());
}

fn guessed_256_app() -> App {
    let config = AppConfig {
        color_depth: ColorDepth::Ansi256,
        color_depth_certain: false,
        probe_truecolor: true,
        ..AppConfig::default()
    };
    App::new(scene::load("default").expect("default scene"), config)
}

fn key(c: char, modifiers: KeyModifiers) -> Event {
    Event::Key(KeyEvent::new(KeyCode::Char(c), modifiers))
}

/// The events crossterm makes of late DCS replies: `ESC P` is Alt+Shift+P, then one key per
/// character, then `ESC \` is Alt+\ (and it drops a DA1 reply itself).
fn crossterm_events_of(dcs_replies: &[u8]) -> Vec<Event> {
    let text = String::from_utf8_lossy(dcs_replies);
    let mut events = Vec::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '\x1b' {
            match chars.next() {
                Some('P') => events.push(key('P', KeyModifiers::ALT | KeyModifiers::SHIFT)),
                Some('\\') => events.push(key('\\', KeyModifiers::ALT)),
                other => panic!("not a DCS reply: {other:?}"),
            }
        } else {
            events.push(key(c, KeyModifiers::NONE));
        }
    }
    events
}

#[test]
fn the_app_switches_to_truecolor_when_the_terminal_says_so_and_says_how_it_knows() {
    let mut app = guessed_256_app();
    assert!(
        app.message()
            .contains("256 (guessed; try --colors truecolor)")
    );
    let mut xterm = FakeTerminal::new(vec![Reply::Now(XTERM_DECRQSS), Reply::Now(DA1)]);
    let (outcome, _) = ask(&mut xterm);
    app.apply_probe(outcome, Instant::now());
    assert_eq!(app.color_depth(), ColorDepth::TrueColor);
    assert!(
        app.message().contains("truecolor (terminal says)"),
        "{}",
        app.message()
    );
}

#[test]
fn a_late_reply_is_dropped_before_it_can_act_as_keys() {
    let mut app = guessed_256_app();
    app.resize(ratatui::layout::Rect::new(0, 0, 80, 24));
    // The replies come after the deadline: 256 colours, still a guess.
    const LATE: &[u8] = b"\x1bP1$r0;48:2::1:2:3m\x1b\\\x1bP1+r524742=382F382F38\x1b\\";
    let mut slow = FakeTerminal::new(vec![Reply::Late(LATE)]);
    let (outcome, _) = ask(&mut slow);
    assert_eq!((outcome.answer, outcome.complete), (Answer::Silent, false));
    app.apply_probe(outcome, Instant::now());
    assert_eq!(app.color_depth(), ColorDepth::Ansi256);
    assert!(app.message().contains("guessed"), "{}", app.message());

    // Then they reach the event loop: 'm' (render mode), '+' (zoom), 'r' (reset), 'b' (spawn)...
    let (mode, eye, bodies) = (app.render_mode(), app.camera().position, app.world().len());
    let events = crossterm_events_of(&slow.late);
    assert!(events.len() > 30);
    for event in &events {
        app.handle_event(event);
    }
    assert_eq!(app.render_mode(), mode);
    assert_eq!(app.camera().position, eye);
    assert_eq!(app.world().len(), bodies);
    assert!(!app.should_quit());
    // The user's own keys still work.
    app.handle_event(&key('m', KeyModifiers::NONE));
    assert_ne!(app.render_mode(), mode);
}

/// xterm.js (VS Code's terminal, ttyd) answers DECRQSS with a fixed `0m` whatever colour is set, so
/// without `COLORTERM` nudge guessed 256 colours in a terminal that has 24-bit colour (issue 28).
/// It names itself to XTVERSION, and that is taken as truecolor; the status bar says how it knows.
#[test]
fn xterm_js_which_names_itself_to_xtversion_comes_up_truecolor() {
    let mut app = guessed_256_app();
    const XTERM_JS: &[u8] = b"\x1bP1$r0m\x1b\\\x1bP>|xterm.js(6.0.0)\x1b\\";
    let mut xterm_js = FakeTerminal::new(vec![Reply::Now(XTERM_JS), Reply::Now(b"\x1b[?1;2c")]);
    let (outcome, written) = ask(&mut xterm_js);
    assert!(String::from_utf8_lossy(&written).contains("\x1b[>0q"));
    assert_eq!(
        (outcome.answer, outcome.complete),
        (Answer::TrueColor, true)
    );
    app.apply_probe(outcome, Instant::now());
    assert_eq!(app.color_depth(), ColorDepth::TrueColor);
    assert!(
        app.message().contains("truecolor (terminal says)"),
        "{}",
        app.message()
    );
    // Late, the same reply is swallowed like the others.
    let mut late_app = guessed_256_app();
    let mut slow = FakeTerminal::new(vec![Reply::Late(XTERM_JS)]);
    let (outcome, _) = ask(&mut slow);
    late_app.apply_probe(outcome, Instant::now());
    let mode = late_app.render_mode();
    for event in crossterm_events_of(&slow.late) {
        late_app.handle_event(&event);
    }
    assert_eq!(
        late_app.render_mode(),
        mode,
        "a late 'm' in 'xterm.js' switched the mode"
    );
    assert_eq!(late_app.color_depth(), ColorDepth::Ansi256);
}

/// xterm.js's pty reports no pixel size, so nudge assumed a cell aspect of 2.0 while its cells are
/// 8×19 px: bodies were drawn 19 % too tall (issue 28). Asked XTWINOPS 16, a terminal that answers
/// sets the aspect; one that does not leaves the 2.0 guess.
#[test]
fn a_terminal_asked_its_cell_size_sets_the_cell_aspect_and_silence_leaves_the_guess() {
    let config = AppConfig {
        ask_cell_size: true,
        ..AppConfig::default()
    };
    let questions = Questions {
        truecolor: false,
        cell_size: true,
    };
    let ask_size = |terminal: &mut FakeTerminal| {
        let mut written = Vec::new();
        let outcome =
            nudge::term::probe::ask(&mut written, terminal, Duration::from_secs(10), questions)
                .expect("probe");
        (outcome, written)
    };
    let mut xterm_js = FakeTerminal::new(vec![Reply::Now(b"\x1b[6;19;8t\x1b[?1;2c")]);
    let (outcome, written) = ask_size(&mut xterm_js);
    assert_eq!(written, b"\x1b[16t\x1b[c", "only the cell size, then DA1");
    assert_eq!(outcome.cell_px, Some((19, 8)));
    let mut app = App::new(
        scene::load("default").expect("default scene"),
        config.clone(),
    );
    let colors = app.color_depth();
    app.apply_probe(outcome, Instant::now());
    assert_eq!(app.cell_aspect(), 19.0 / 8.0);
    assert_eq!(app.color_depth(), colors, "the colour depth was not asked");

    let mut ignores = FakeTerminal::new(vec![Reply::Now(b"\x1b[?1;2c")]);
    let (outcome, _) = ask_size(&mut ignores);
    let mut app = App::new(scene::load("default").expect("default scene"), config);
    app.apply_probe(outcome, Instant::now());
    assert_eq!(app.cell_aspect(), 2.0);
}
