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

    /// Publishes the rates once a whole second has passed since the window opened.
    fn close_window(&mut self, now: Instant) {
        if let Some(start) = self.window_start
            && now.duration_since(start) >= Duration::from_secs(1)
        {
            self.fps = self.window_frames;
            self.bytes_per_second = self.window_bytes;
            self.held_per_second = self.window_held;
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
    pub message: &'a str,
}

impl Widget for StatusLine<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let dim = Style::default().fg(Color::Gray);
        let key = Style::default()
            .fg(Color::White)
            .add_modifier(Modifier::BOLD);
        let sep = Span::styled(" │ ", dim);
        let s = self.stats;
        let mut spans = vec![
            Span::styled(
                if s.idle {
                    "idle".to_string()
                } else {
                    format!("{:>2} fps", s.fps)
                },
                key,
            ),
            sep.clone(),
            Span::styled(format!("phys {:.2} ms", s.physics_ms), dim),
            sep.clone(),
            Span::styled(format!("draw {:.2} ms", s.render_ms), dim),
            sep.clone(),
            Span::styled(format!("awake {}/{}", self.awake, self.total), dim),
            sep.clone(),
            Span::styled(self.mode.to_string(), key),
            Span::styled(format!(" {}", self.projection), dim),
            sep.clone(),
            Span::styled(self.colors.to_string(), dim),
            sep.clone(),
            Span::styled(
                if s.idle {
                    "0 B/s".to_string()
                } else {
                    let held = if s.held_per_second > 0 {
                        // Frames skipped to hold the byte budget: the link sets the frame rate.
                        format!(" (capped, {} held)", s.held_per_second)
                    } else {
                        String::new()
                    };
                    format!(
                        "{}/f {}/s{held}",
                        format_bytes(s.bytes_last_frame),
                        format_bytes(s.bytes_per_second)
                    )
                },
                dim,
            ),
        ];
        if self.paused {
            spans.push(sep.clone());
            spans.push(Span::styled("PAUSED", key.fg(Color::Yellow)));
        }
        if self.strong {
            spans.push(sep.clone());
            spans.push(Span::styled("STRONG", key.fg(Color::Red)));
        }
        spans.push(sep);
        spans.push(Span::styled(
            self.message.to_string(),
            Style::default().fg(Color::Cyan),
        ));
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
}
