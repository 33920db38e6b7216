//! Frame statistics and the one-line status bar.

use std::time::{Duration, Instant};

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Paragraph, Widget};

/// Exponential moving average weight of the newest sample.
const SMOOTHING: f64 = 0.1;

/// Running numbers the status bar shows.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Smoothed wall time of one physics step, ms.
    pub physics_ms: f64,
    /// Smoothed time to render and map one frame, ms.
    pub render_ms: f64,
    /// Bytes written to the terminal by the last drawn frame.
    pub bytes_last_frame: u64,
    /// Bytes written during the last whole second.
    pub bytes_per_second: u64,
    /// Frames drawn during the last whole second.
    pub fps: u32,
    /// Nothing moves and nothing is drawn: the status bar says so instead of showing stale rates.
    pub idle: bool,
    /// Frames held back by the byte budget during the last whole second.
    pub held_per_second: u32,
    /// A whole second has been measured: until then the rates are not shown (the first second
    /// used to read "0 fps").
    pub measured: bool,
    window_start: Option<Instant>,
    window_frames: u32,
    window_bytes: u64,
    window_held: u32,
}

fn smooth(old: f64, sample: f64) -> f64 {
    if old == 0.0 {
        sample
    } else {
        old + SMOOTHING * (sample - old)
    }
}

impl Stats {
    pub fn record_physics(&mut self, ms: f64) {
        self.physics_ms = smooth(self.physics_ms, ms);
    }

    pub fn record_render(&mut self, ms: f64) {
        self.render_ms = smooth(self.render_ms, ms);
    }

    /// A frame reached the terminal at `now`, costing `bytes`.
    pub fn record_frame(&mut self, now: Instant, bytes: u64) {
        self.bytes_last_frame = bytes;
        self.window_start.get_or_insert(now);
        self.window_frames += 1;
        self.window_bytes += bytes;
        self.close_window(now);
    }

    /// A frame was due at `now` but held back by the byte budget.
    pub fn record_held(&mut self, now: Instant) {
        self.window_start.get_or_insert(now);
        self.window_held += 1;
        self.close_window(now);
    }

    /// Called when nothing is drawn for a while: an idle second shows 0 fps and 0 B/s.
    pub fn record_idle(&mut self, now: Instant) {
        self.close_window(now);
    }

    /// The world came to rest (the status bar says "idle"): the next motion starts a new second
    /// and shows no rate until it is measured. Without this, the first frame after a rest closed a
    /// window opened before it, and a push after ten idle seconds read "1 fps".
    pub fn rest(&mut self) {
        self.measured = false;
        self.fps = 0;
        self.bytes_per_second = 0;
        self.held_per_second = 0;
        self.window_start = None;
        self.window_frames = 0;
        self.window_bytes = 0;
        self.window_held = 0;
    }

    /// Publishes the rates once a whole second has passed since the window opened.
    fn close_window(&mut self, now: Instant) {
        if let Some(start) = self.window_start
            && now.duration_since(start) >= Duration::from_secs(1)
        {
            self.fps = self.window_frames;
            self.bytes_per_second = self.window_bytes;
            self.held_per_second = self.window_held;
            // A second with no frame (the world at rest) measured no rate: when things move again,
            // nothing is shown until a busy second has (it read "0 fps" for a second).
            self.measured = self.window_frames > 0 || self.window_held > 0;
            self.window_start = Some(now);
            self.window_frames = 0;
            self.window_bytes = 0;
            self.window_held = 0;
        }
    }
}

/// Human-readable byte count: "850 B", "12.3 kB", "1.02 MB".
pub fn format_bytes(bytes: u64) -> String {
    match bytes {
        0..1_000 => format!("{bytes} B"),
        1_000..1_000_000 => format!("{:.1} kB", bytes as f64 / 1e3),
        _ => format!("{:.2} MB", bytes as f64 / 1e6),
    }
}

/// What the status bar shows, gathered by the app.
pub struct StatusLine<'a> {
    pub stats: &'a Stats,
    pub awake: usize,
    pub total: usize,
    pub mode: &'a str,
    pub projection: &'a str,
    pub colors: &'a str,
    pub paused: bool,
    pub strong: bool,
    /// The left button grabs (`h`) instead of pushing.
    pub grab: bool,
    /// Gravity is switched off (`g`): a flag, not just a passing message.
    pub gravity_off: bool,
    /// `f` was pressed: the next click freezes or unfreezes.
    pub freeze_armed: bool,
    /// The body under the pointer and its mass (with `--hover`).
    pub pointing_at: Option<&'a str>,
    /// The byte limit and where it came from ("1.00 MB/s, ssh"), for the note when frames are held;
    /// empty if unknown.
    pub byte_limit: &'a str,
    pub message: &'a str,
}

/// How long a field of the status bar stays when the line is too narrow for all of them: the
/// statistics are dropped in this order, first to last.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Keep {
    DrawTime,
    FrameBytes,
    PhysicsTime,
    /// Outlasts the timings: it tells a user what the terminal was taken for (a long message after
    /// `h` pushed it off a 120-column line).
    ColourDepth,
    Awake,
    /// A standing hint in the message's place (one that ends "? for help", such as the start-up
    /// colour hint) while `--hover` names a body: the name answers what the pointer is doing now,
    /// and the long hint pushed it off a 120-column line until some other message replaced it.
    StandingHint,
    /// The body under the pointer (`--hover`).
    PointingAt,
    /// Outlasts the other statistics: on a slow link the byte rate is why the frame rate is low
    /// (the held-frames note itself is never dropped).
    ByteRate,
    RenderMode,
    /// The frame rate (or "idle"): the last statistic to go. It used to be kept always, and at 60×12
    /// with every flag on it pushed "? help" and the message off the line.
    FrameRate,
    /// Never dropped: the flags (pause, strong hand, grab, gravity off, freeze armed, capped
    /// frames), which shorten instead (see [`FlagStyle`]), "? help" and the message (last on the
    /// line, so a line too narrow even for these cuts the message's end).
    Always,
}

/// How the flags are written: whole words while the line has room, then short words, then a letter
/// each (still in their colours), so the message and "? help" keep their place.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FlagStyle {
    Words,
    Short,
    Letters,
}

/// One flag: whether it is on, its colour and its text in each [`FlagStyle`].
struct Flag {
    on: bool,
    color: Color,
    words: String,
    short: &'static str,
    letter: &'static str,
}

impl Flag {
    fn text(&self, style: FlagStyle) -> String {
        match style {
            FlagStyle::Words => self.words.clone(),
            FlagStyle::Short => self.short.to_string(),
            FlagStyle::Letters => self.letter.to_string(),
        }
    }
}

/// One field of the status bar.
struct Field {
    keep: Keep,
    spans: Vec<Span<'static>>,
}
/// Flags shorten until the message shows at least this many columns (or whole, if shorter).
const MIN_MESSAGE_COLS: usize = 20;
/// Separator between two fields.
const SEPARATOR: &str = " │ ";

impl Field {
    fn new(keep: Keep, spans: Vec<Span<'static>>) -> Self {
        Self { keep, spans }
    }

    fn width(&self) -> usize {
        self.spans.iter().map(Span::width).sum()
    }
}

/// The columns `fields` take on one line.
fn line_width(fields: &[Field]) -> usize {
    fields.iter().map(Field::width).sum::<usize>()
        + SEPARATOR.chars().count() * fields.len().saturating_sub(1)
}

/// Drops the fields a `width`-column line cannot hold, in [`Keep`] order (ties: the rightmost first),
/// keeping the survivors in order. What is left may still be too wide; the line cuts its end.
fn fit(mut fields: Vec<Field>, width: usize) -> Vec<Field> {
    while line_width(&fields) > width {
        let droppable = fields
            .iter()
            .enumerate()
            .filter(|(_, f)| f.keep != Keep::Always)
            .min_by_key(|&(i, f)| (f.keep, std::cmp::Reverse(i)));
        match droppable {
            Some((i, _)) => {
                fields.remove(i);
            }
            None => break,
        }
    }
    fields
}

impl StatusLine<'_> {
    /// The fields in display order. The message answers what the user just did, so it outlasts
    /// every statistic. A message that says "? for help" stands for the "? help" field unless
    /// `help_field` (the line is too narrow to show the message's end). Flags are written in
    /// `flag_style`.
    fn fields(&self, help_field: bool, flag_style: FlagStyle) -> Vec<Field> {
        let dim = Style::default().fg(Color::Gray);
        let key = Style::default()
            .fg(Color::White)
            .add_modifier(Modifier::BOLD);
        let s = self.stats;
        let mut fields = Vec::new();
        // Nothing is shown for a rate until a whole second has measured it.
        if s.idle {
            fields.push(Field::new(Keep::FrameRate, vec![Span::styled("idle", key)]));
        } else if s.measured {
            fields.push(Field::new(
                Keep::FrameRate,
                vec![Span::styled(format!("{:>2} fps", s.fps), key)],
            ));
        }
        if s.physics_ms > 0.0 {
            fields.push(Field::new(
                Keep::PhysicsTime,
                vec![Span::styled(format!("phys {:.2} ms", s.physics_ms), dim)],
            ));
        }
        if s.render_ms > 0.0 {
            fields.push(Field::new(
                Keep::DrawTime,
                vec![Span::styled(format!("draw {:.2} ms", s.render_ms), dim)],
            ));
        }
        fields.push(Field::new(
            Keep::Awake,
            vec![Span::styled(
                format!("awake {}/{}", self.awake, self.total),
                dim,
            )],
        ));
        fields.push(Field::new(
            Keep::RenderMode,
            vec![
                Span::styled(self.mode.to_string(), key),
                Span::styled(format!(" {}", self.projection), dim),
            ],
        ));
        fields.push(Field::new(
            Keep::ColourDepth,
            vec![Span::styled(self.colors.to_string(), dim)],
        ));
        if s.idle {
            fields.push(Field::new(Keep::ByteRate, vec![Span::styled("0 B/s", dim)]));
        } else if s.measured {
            fields.push(Field::new(
                Keep::FrameBytes,
                vec![Span::styled(
                    format!("{}/f", format_bytes(s.bytes_last_frame)),
                    dim,
                )],
            ));
            fields.push(Field::new(
                Keep::ByteRate,
                vec![Span::styled(
                    format!("{}/s", format_bytes(s.bytes_per_second)),
                    dim,
                )],
            ));
        }
        if let Some(pointing_at) = self.pointing_at {
            fields.push(Field::new(
                Keep::PointingAt,
                vec![Span::styled(pointing_at.to_string(), dim)],
            ));
        }
        // Frames skipped to hold the byte budget: the link sets the frame rate, and says so.
        let capped = !s.idle && s.held_per_second > 0;
        let flags = [
            Flag {
                on: capped,
                color: Color::Yellow,
                words: if self.byte_limit.is_empty() {
                    format!("capped, {} held", s.held_per_second)
                } else {
                    format!("capped at {}, {} held", self.byte_limit, s.held_per_second)
                },
                short: "capped",
                letter: "C",
            },
            Flag {
                on: self.paused,
                color: Color::Yellow,
                words: "PAUSED".into(),
                short: "PAUSE",
                letter: "P",
            },
            Flag {
                on: self.strong,
                color: Color::Red,
                words: "STRONG".into(),
                short: "STRONG",
                letter: "S",
            },
            Flag {
                on: self.grab,
                color: Color::Green,
                words: "GRAB".into(),
                short: "GRAB",
                letter: "G",
            },
            Flag {
                on: self.gravity_off,
                color: Color::Magenta,
                words: "NO GRAVITY".into(),
                short: "0 g",
                letter: "0",
            },
            Flag {
                on: self.freeze_armed,
                color: Color::LightBlue,
                words: "FREEZE: click a body".into(),
                short: "FREEZE",
                letter: "F",
            },
        ];
        let on = flags.iter().filter(|f| f.on);
        if flag_style == FlagStyle::Words {
            for flag in on {
                fields.push(Field::new(
                    Keep::Always,
                    vec![Span::styled(flag.words.clone(), key.fg(flag.color))],
                ));
            }
        } else {
            // Shortened flags share one field, a space apart: a separator each cost three columns.
            let mut spans = Vec::new();
            for (i, flag) in on.enumerate() {
                if i > 0 {
                    spans.push(Span::raw(" "));
                }
                spans.push(Span::styled(flag.text(flag_style), key.fg(flag.color)));
            }
            if !spans.is_empty() {
                fields.push(Field::new(Keep::Always, spans));
            }
        }
        if help_field || !self.message.contains("? for help") {
            // The way to the help stays on the line at any width.
            fields.push(Field::new(Keep::Always, vec![Span::styled("? help", dim)]));
        }
        if !self.message.is_empty() {
            let keep = if self.hint_yields() {
                Keep::StandingHint
            } else {
                Keep::Always
            };
            fields.push(Field::new(
                keep,
                vec![Span::styled(
                    self.message.to_string(),
                    Style::default().fg(Color::Cyan),
                )],
            ));
        }
        fields
    }

    /// The message is a standing hint that gives way to the `--hover` name (see [`Keep::StandingHint`]).
    fn hint_yields(&self) -> bool {
        self.pointing_at.is_some() && self.message.contains("? for help")
    }
}

impl Widget for StatusLine<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let separator = Span::styled(SEPARATOR, Style::default().fg(Color::Gray));
        let mut spans = Vec::new();
        let width = usize::from(area.width);
        let mut fields = Vec::new();
        // The first layout that keeps the way to the help and fits, or at least shows
        // [`MIN_MESSAGE_COLS`] of the message: whole flags first, the message's own "? for help"
        // before a separate "? help" field; failing all, the shortest.
        let message_cols = self.message.chars().count();
        'layouts: for flag_style in [FlagStyle::Words, FlagStyle::Short, FlagStyle::Letters] {
            for help_field in [false, true] {
                fields = fit(self.fields(help_field, flag_style), width);
                let hint_dropped =
                    self.hint_yields() && !fields.iter().any(|f| f.keep == Keep::StandingHint);
                let over = line_width(&fields).saturating_sub(width);
                // The message cut, and with it the "? for help" it ends with (the start-up colour
                // hint at 40 columns), or given way to the hover name: "? help" keeps the way.
                let help_lost = !help_field && (over > 0 || hint_dropped);
                let message_shown =
                    over == 0 || message_cols.saturating_sub(over) >= MIN_MESSAGE_COLS;
                if !help_lost && message_shown {
                    break 'layouts;
                }
            }
        }
        for (i, field) in fields.into_iter().enumerate() {
            if i > 0 {
                spans.push(separator.clone());
            }
            spans.extend(field.spans);
        }
        Paragraph::new(Line::from(spans))
            .style(Style::default().bg(Color::Black))
            .render(area, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_are_formatted_with_units() {
        assert_eq!(format_bytes(850), "850 B");
        assert_eq!(format_bytes(12_345), "12.3 kB");
        assert_eq!(format_bytes(1_020_000), "1.02 MB");
    }

    #[test]
    fn a_second_of_frames_sets_fps_and_rate() {
        let mut stats = Stats::default();
        let t0 = Instant::now();
        for i in 0..=30 {
            stats.record_frame(t0 + Duration::from_millis(i * 1000 / 30), 100);
        }
        assert_eq!(stats.fps, 31);
        assert_eq!(stats.bytes_per_second, 3100);
    }

    #[test]
    fn after_a_rest_no_rate_is_shown_until_a_new_second_is_measured() {
        let mut stats = Stats::default();
        let t0 = Instant::now();
        for i in 0..=30 {
            stats.record_frame(t0 + Duration::from_millis(i * 1000 / 30), 100);
        }
        assert!(stats.measured);
        stats.rest();
        // Ten idle seconds, then motion at 30 frames a second.
        let t1 = t0 + Duration::from_secs(11);
        stats.record_frame(t1, 100);
        assert!(!stats.measured, "a rate from one frame in ten seconds");
        for i in 1..=30 {
            stats.record_frame(t1 + Duration::from_millis(i * 1000 / 30), 100);
        }
        assert!(stats.measured);
        assert_eq!(stats.fps, 31);
    }

    /// The status line drawn `width` columns wide, trailing blanks trimmed.
    fn line(width: u16, paused: bool, message: &str) -> String {
        let stats = Stats {
            physics_ms: 0.25,
            render_ms: 1.5,
            fps: 30,
            bytes_last_frame: 12_345,
            bytes_per_second: 370_000,
            measured: true,
            ..Stats::default()
        };
        draw(&stats, width, paused, false, message)
    }

    /// The line the tests start from: no flags, three of five bodies awake.
    fn status<'a>(stats: &'a Stats, message: &'a str) -> StatusLine<'a> {
        StatusLine {
            stats,
            awake: 3,
            total: 5,
            mode: "textured",
            projection: "persp",
            colors: "256",
            paused: false,
            strong: false,
            grab: false,
            gravity_off: false,
            freeze_armed: false,
            pointing_at: None,
            byte_limit: "",
            message,
        }
    }

    /// `line` rendered `width` cells wide, trailing blanks trimmed.
    fn rendered(line: StatusLine, width: u16) -> String {
        let area = Rect::new(0, 0, width, 1);
        let mut buf = Buffer::empty(area);
        line.render(area, &mut buf);
        (0..width)
            .map(|x| buf[(x, 0)].symbol().to_string())
            .collect::<String>()
            .trim_end()
            .to_string()
    }

    fn draw(stats: &Stats, width: u16, paused: bool, flags: bool, message: &str) -> String {
        let line = StatusLine {
            paused,
            gravity_off: flags,
            freeze_armed: flags,
            ..status(stats, message)
        };
        rendered(line, width)
    }

    #[test]
    fn a_wide_line_shows_every_field_in_order() {
        let text = line(200, true, "pushing box #3");
        assert_eq!(
            text,
            "30 fps │ phys 0.25 ms │ draw 1.50 ms │ awake 3/5 │ textured persp │ 256 │ \
             12.3 kB/f │ 370.0 kB/s │ PAUSED │ ? help │ pushing box #3"
        );
    }

    #[test]
    fn an_80_column_line_keeps_the_message_whole_and_drops_statistics() {
        let message = "pushing box #3 (50 N, 150 N held)";
        let text = line(80, false, message);
        assert!(text.ends_with(message), "{text}");
        assert!(text.starts_with("30 fps │ "), "{text}");
        assert!(text.contains("textured persp"), "{text}");
        assert!(!text.contains("draw "), "the timings go first: {text}");
        assert!(text.chars().count() <= 80);
    }

    #[test]
    fn a_narrow_line_drops_the_frame_rate_before_the_message_and_keeps_the_flags() {
        let text = line(24, true, "? for help");
        assert_eq!(text, "PAUSED │ ? for help");
        let text = line(36, true, "pushing box #3 (50 N, 150 N held)");
        assert_eq!(text, "P │ ? help │ pushing box #3 (50 N, 1");
    }

    /// Every flag on, as a tester had it at 60×12 (issue 28): fps was never dropped, so the line lost
    /// "? help" and the message, and at 40 columns it ended in "│ FR".
    fn all_flags(width: u16, message: &str) -> String {
        let stats = Stats {
            physics_ms: 0.25,
            render_ms: 1.5,
            fps: 30,
            measured: true,
            ..Stats::default()
        };
        let line = StatusLine {
            paused: true,
            strong: true,
            grab: true,
            gravity_off: true,
            freeze_armed: true,
            ..status(&stats, message)
        };
        rendered(line, width)
    }

    #[test]
    fn with_every_flag_on_statistics_go_then_flags_shorten_and_help_and_the_message_stay() {
        let message = "click a body to freeze or unfreeze it (Esc cancels)";
        let wide = all_flags(160, message);
        assert!(wide.starts_with("30 fps │ "), "{wide}");
        assert!(wide.contains("PAUSED │ STRONG │ GRAB │ NO GRAVITY │ FREEZE: click a body"));
        assert!(wide.ends_with(message), "{wide}");
        assert_eq!(
            all_flags(60, message),
            "PAUSE STRONG GRAB 0 g FREEZE │ ? help │ click a body to free"
        );
        assert_eq!(
            all_flags(40, message),
            "P S G 0 F │ ? help │ click a body to fre"
        );
        // Shortened flags leave room for the frame rate again.
        assert_eq!(
            all_flags(60, "paused"),
            "30 fps │ PAUSE STRONG GRAB 0 g FREEZE │ ? help │ paused"
        );
    }

    #[test]
    fn no_message_leaves_no_dangling_separator() {
        assert!(line(200, false, "").ends_with("370.0 kB/s │ ? help"));
    }

    #[test]
    fn after_an_idle_second_no_rate_is_shown_until_a_busy_second_measures_one() {
        let start = Instant::now();
        let mut stats = Stats::default();
        for i in 0..=30 {
            stats.record_frame(start + Duration::from_millis(i * 34), 500);
        }
        assert!(stats.measured && stats.fps > 0);
        stats.record_idle(start + Duration::from_millis(2500));
        assert!(!stats.measured, "an idle second measured {} fps", stats.fps);
        let text = draw(&stats, 120, false, false, "pushing box #2");
        assert!(!text.contains("fps") && !text.contains("B/s"), "{text}");
    }

    #[test]
    fn the_first_second_shows_no_rate_instead_of_zero_fps() {
        let stats = Stats::default();
        let text = draw(&stats, 120, false, false, "? for help");
        assert!(!text.contains("fps") && !text.contains("B/s"), "{text}");
        assert!(text.starts_with("awake 3/5"), "{text}");
    }

    /// With `--max-bytes-per-second 20000` on rain at 120×40 the sandbox ran at 1–5 fps and the
    /// start-up hint pushed the reason off the line.
    #[test]
    fn the_byte_rate_and_the_capped_note_outlast_the_start_up_hint() {
        let stats = Stats {
            physics_ms: 2.5,
            render_ms: 9.0,
            fps: 3,
            bytes_last_frame: 6_000,
            bytes_per_second: 18_000,
            held_per_second: 27,
            measured: true,
            ..Stats::default()
        };
        let hint = "256 colours (guessed; try --colors truecolor) · ? for help";
        let text = draw(&stats, 120, false, false, hint);
        assert!(text.contains("18.0 kB/s"), "{text}");
        assert!(text.contains("textured persp"), "{text}");
        assert!(text.contains("capped, 27 held"), "{text}");
        assert!(text.ends_with(hint), "{text}");
        let narrow = draw(&stats, 60, false, false, hint);
        assert!(narrow.contains("capped, 27 held"), "{narrow}");
    }

    /// The held-frames note names the limit and why it is what it is (issue 28: 1 MB/s over SSH,
    /// none locally, or the flag's).
    #[test]
    fn the_held_frames_note_names_the_limit_and_its_origin() {
        let stats = Stats {
            fps: 3,
            bytes_per_second: 18_000,
            held_per_second: 27,
            measured: true,
            ..Stats::default()
        };
        let line = StatusLine {
            byte_limit: "1.00 MB/s, ssh",
            ..status(&stats, "? for help")
        };
        let text = rendered(line, 120);
        assert!(text.contains("capped at 1.00 MB/s, ssh, 27 held"), "{text}");
    }

    #[test]
    fn help_stays_on_the_line_down_to_40_columns() {
        for width in [40, 60, 80] {
            let text = line(width, true, "pushing box #3 (50 N, 150 N held)");
            assert!(text.contains("? help"), "{width}: {text}");
        }
    }

    /// The start-up colour hint ends with "? for help", which a narrow line cut off.
    #[test]
    fn help_stays_on_the_line_when_the_start_up_hint_is_cut() {
        let hint = "256 colours (guessed; try --colors truecolor) · ? for help";
        for width in [40, 50] {
            let text = draw(&Stats::default(), width, false, false, hint);
            assert!(text.starts_with("? help │ 256 colours"), "{width}: {text}");
        }
        // Where the hint fits, it says it alone.
        let wide = draw(&Stats::default(), 60, false, false, hint);
        assert_eq!(wide, hint);
    }

    #[test]
    fn gravity_off_and_an_armed_freeze_are_flags_not_passing_messages() {
        let text = draw(&Stats::default(), 120, false, true, "");
        assert!(text.contains("NO GRAVITY"), "{text}");
        assert!(text.contains("FREEZE: click a body"), "{text}");
    }
}
