//! What the app does with the terminal's answer to the truecolor probe (`term::probe`): switch to
//! 24-bit colour if it said so, say how the depth was found, and drop replies that come too late.
//!
//! A late reply reaches the event loop through crossterm, which reads a DCS string
//! (`ESC P … ESC \`) as `Alt+P`, one key per character, then `Alt+\`. Those keys would reset the
//! scene (`r`), zoom (`+`), spawn (`b`), …, so for a while after a probe that did not finish, such a
//! run of keys is swallowed whole. (crossterm drops a late DA1 reply itself.)

use std::time::{Duration, Instant};

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};

use crate::app::App;
use crate::term::probe::{Answer, ProbeOutcome};
use crate::term::{ColorDepth, guessed_hint};

/// How long after an unfinished probe a reply may still arrive (a slow ssh link's round trips).
pub const LATE_REPLY_WINDOW: Duration = Duration::from_secs(5);
/// Most keys one swallowed reply may hold (the longest we ask for is about 60 characters): a
/// safety net, so a stray `Alt+P` cannot eat the keyboard.
const MAX_REPLY_KEYS: u32 = 256;

/// The status-bar note for a depth the terminal confirmed.
pub fn confirmed_note(depth: ColorDepth) -> String {
    format!("{} (terminal says)", depth.name())
}

/// Drops late probe replies from the input (see the module docs).
#[derive(Clone, Debug, Default)]
pub struct LateReplies {
    /// Replies may arrive until then; `None` when none is expected.
    until: Option<Instant>,
    /// Keys swallowed of the reply being read, if inside one.
    inside: Option<u32>,
}

impl LateReplies {
    /// Expect late replies until `until`.
    pub fn arm(&mut self, until: Instant) {
        self.until = Some(until);
    }

    /// Whether `event`, arriving at `now`, belongs to a late reply (and must be ignored).
    pub fn swallow(&mut self, event: &Event, now: Instant) -> bool {
        let Some(until) = self.until else {
            return false;
        };
        let Event::Key(key) = event else {
            return false;
        };
        if let Some(count) = self.inside {
            if is_alt(key, '\\') || count >= MAX_REPLY_KEYS {
                self.inside = None;
            } else {
                self.inside = Some(count + 1);
            }
            return true;
        }
        if now > until {
            self.until = None;
            return false;
        }
        if is_alt(key, 'P') {
            self.inside = Some(0);
            return true;
        }
        false
    }
}

fn is_alt(key: &KeyEvent, c: char) -> bool {
    key.modifiers.contains(KeyModifiers::ALT) && key.code == KeyCode::Char(c)
}

impl App {
    /// Terminal cell height / width the picture is drawn for.
    pub fn cell_aspect(&self) -> f32 {
        self.config.cell_aspect
    }

    /// The colour depth frames are drawn at.
    pub fn color_depth(&self) -> ColorDepth {
        self.config.color_depth
    }

    /// Takes the terminal's answers to the probe (truecolor, and the cell size if asked), made at
    /// `now`.
    pub fn apply_probe(&mut self, outcome: ProbeOutcome, now: Instant) {
        if outcome.answer == Answer::TrueColor {
            self.config.color_depth = ColorDepth::TrueColor;
            self.config.color_depth_certain = true;
            self.say(format!(
                "{} · ? for help",
                confirmed_note(ColorDepth::TrueColor)
            ));
        } else if !self.config.color_depth_certain {
            self.say(format!(
                "{} · ? for help",
                guessed_hint(self.config.color_depth)
            ));
        }
        if self.config.ask_cell_size
            && let Some((height, width)) = outcome.cell_px
            && let Some(aspect) =
                crate::term::cell_aspect::plausible(f32::from(height) / f32::from(width))
        {
            // The terminal's own answer beats the 2.0 guess (xterm.js's 8×19 px cells: 2.375).
            self.config.cell_aspect = aspect;
        }
        if !outcome.complete {
            self.late_replies.arm(now + LATE_REPLY_WINDOW);
        }
        self.dirty = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crossterm::event::KeyEvent;

    fn key(c: char, modifiers: KeyModifiers) -> Event {
        Event::Key(KeyEvent::new(KeyCode::Char(c), modifiers))
    }

    /// The events crossterm makes of a DCS reply: Alt+P, a key per character, Alt+\.
    fn dcs_events(body: &str) -> Vec<Event> {
        let mut events = vec![key('P', KeyModifiers::ALT | KeyModifiers::SHIFT)];
        events.extend(body.chars().map(|c| key(c, KeyModifiers::NONE)));
        events.push(key('\\', KeyModifiers::ALT));
        events
    }

    #[test]
    fn a_late_reply_is_swallowed_whole_and_keys_after_it_pass() {
        let now = Instant::now();
        let mut late = LateReplies::default();
        late.arm(now + LATE_REPLY_WINDOW);
        for event in dcs_events("1$r0;48:2::1:2:3m") {
            assert!(late.swallow(&event, now), "{event:?}");
        }
        assert!(!late.swallow(&key('r', KeyModifiers::NONE), now));
    }

    #[test]
    fn nothing_is_swallowed_unless_armed_or_after_the_window() {
        let now = Instant::now();
        let mut late = LateReplies::default();
        assert!(!late.swallow(&dcs_events("1+r5463")[0], now));
        late.arm(now);
        assert!(!late.swallow(&dcs_events("1+r5463")[0], now + Duration::from_secs(1)));
    }

    #[test]
    fn a_stray_alt_p_cannot_eat_the_keyboard() {
        let now = Instant::now();
        let mut late = LateReplies::default();
        late.arm(now + LATE_REPLY_WINDOW);
        assert!(late.swallow(&key('P', KeyModifiers::ALT), now));
        let eaten = (0..1000)
            .take_while(|_| late.swallow(&key('x', KeyModifiers::NONE), now))
            .count();
        assert_eq!(eaten as u32, MAX_REPLY_KEYS + 1);
    }
}
