//! Live charts of the last 10 s of simulation: total energy, momentum, deepest penetration and the
//! wall time of each step, one sample per physics step, drawn with ratatui's `Chart` (energy, as a
//! braille line: drift shows as a slope) and `Sparkline`s (the others: peaks matter more than shape).

use std::collections::VecDeque;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Chart, Dataset, GraphType, Sparkline, Widget};

use crate::app::panels::inspector::short;
use crate::physics::World;

/// Simulated seconds the charts span.
pub const HISTORY_SECONDS: f32 = 10.0;
/// Rows a chart needs: its title and at least two rows of graph.
pub const CHART_MIN_ROWS: u16 = 3;

/// The figures of one step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// Kinetic + potential energy of the dynamic bodies, J (see `World::potential_energy`).
    pub energy: f32,
    /// |Σ m v|, kg·m/s.
    pub momentum: f32,
    /// Deepest penetration at the end of the step, m.
    pub penetration: f32,
    /// Wall time of the step (with the app's input handling around it), ms.
    pub step_ms: f32,
}

impl Sample {
    /// The world's figures after a step that took `step_ms`.
    pub fn of(world: &World, step_ms: f32) -> Self {
        Self {
            energy: world.kinetic_energy() + world.potential_energy(),
            momentum: world.linear_momentum().length(),
            penetration: world.max_penetration(),
            step_ms,
        }
    }
}

/// The last [`HISTORY_SECONDS`] of samples, oldest first.
#[derive(Clone, Debug, Default)]
pub struct History {
    samples: VecDeque<Sample>,
    /// Steps in [`HISTORY_SECONDS`] at the step length last recorded with (0 before the first).
    capacity: usize,
}

/// Steps of `dt_s` in [`HISTORY_SECONDS`] (at least 1, at most 100,000).
fn steps_in_history(dt_s: f32) -> usize {
    if dt_s > 0.0 && dt_s.is_finite() {
        (HISTORY_SECONDS / dt_s).ceil().clamp(1.0, 100_000.0) as usize
    } else {
        1
    }
}

impl History {
    /// Room for [`HISTORY_SECONDS`] of steps of `dt_s`.
    pub fn new(dt_s: f32) -> Self {
        let capacity = steps_in_history(dt_s);
        Self {
            samples: VecDeque::with_capacity(capacity),
            capacity,
        }
    }

    /// Adds the sample of a step of `dt_s`, dropping what is older than [`HISTORY_SECONDS`].
    pub fn record(&mut self, sample: Sample, dt_s: f32) {
        self.capacity = steps_in_history(dt_s);
        while self.samples.len() >= self.capacity {
            self.samples.pop_front();
        }
        self.samples.push_back(sample);
    }

    pub fn samples(&self) -> &VecDeque<Sample> {
        &self.samples
    }

    /// Steps the charts span when full.
    pub fn capacity(&self) -> usize {
        self.capacity
    }
}

/// One charted figure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Series {
    Energy,
    Momentum,
    Penetration,
    StepTime,
}

impl Series {
    pub const ALL: [Series; 4] = [
        Series::Energy,
        Series::StepTime,
        Series::Penetration,
        Series::Momentum,
    ];

    fn value(self, s: &Sample) -> f32 {
        match self {
            Series::Energy => s.energy,
            Series::Momentum => s.momentum,
            Series::Penetration => s.penetration,
            Series::StepTime => s.step_ms,
        }
    }

    /// Title with the newest value and the largest in the window.
    fn title(self, newest: f32, max: f32) -> String {
        match self {
            Series::Energy => format!("energy {} J", short(newest)),
            Series::Momentum => format!("momentum {} (max {})", short(newest), short(max)),
            Series::Penetration => format!("depth {:.2} mm (max {:.2})", newest * 1e3, max * 1e3),
            Series::StepTime => format!("ms/step {:.3} (max {:.3})", newest, max),
        }
    }

    fn color(self) -> Color {
        match self {
            Series::Energy => Color::LightYellow,
            Series::Momentum => Color::LightCyan,
            Series::Penetration => Color::LightMagenta,
            Series::StepTime => Color::LightGreen,
        }
    }
}

/// Squeezes a window of `capacity` steps whose last `values.len()` are known (the newest at the
/// right) into `width` columns: each column's largest value, so a one-step spike survives, or `None`
/// for a column before the first sample. Every chart thus puts the same step in the same column.
pub fn column_peaks(values: &[f32], capacity: usize, width: usize) -> Vec<Option<f32>> {
    let capacity = capacity.max(values.len());
    if capacity == 0 || width == 0 {
        return Vec::new();
    }
    let columns = width.min(capacity);
    let missing = capacity - values.len();
    (0..columns)
        .map(|c| {
            let (from, to) = (c * capacity / columns, (c + 1) * capacity / columns);
            let (from, to) = (from.max(missing) - missing, to.max(missing) - missing);
            values[from..to.min(values.len())]
                .iter()
                .copied()
                .reduce(f32::max)
        })
        .collect()
}

/// The inspector panel's background, which every chart cell sets too.
const PANEL_BG: Color = Color::Black;

/// The charts, stacked: as many as fit at [`CHART_MIN_ROWS`] rows each, sharing the rows left.
pub struct Charts<'a> {
    pub history: &'a History,
}

impl Widget for Charts<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let count = (area.height / CHART_MIN_ROWS).min(Series::ALL.len() as u16);
        let samples = self.history.samples();
        if count == 0 || area.width < 8 {
            return;
        }
        let rows_each = area.height / count;
        for (i, series) in Series::ALL.iter().take(count as usize).enumerate() {
            let slot = Rect {
                y: area.y + i as u16 * rows_each,
                height: rows_each,
                ..area
            };
            let values: Vec<f32> = samples.iter().map(|s| series.value(s)).collect();
            let newest = values.last().copied().unwrap_or(0.0);
            let max = values.iter().copied().fold(0.0f32, f32::max);
            Line::from(Span::styled(
                format!(" {}", series.title(newest, max)),
                Style::default().fg(series.color()),
            ))
            .render(Rect { height: 1, ..slot }, buf);
            let graph = Rect {
                y: slot.y + 1,
                height: slot.height - 1,
                x: slot.x + 1,
                width: slot.width - 1,
            };
            if values.is_empty() {
                continue;
            }
            if *series == Series::Energy {
                energy_chart(&values, self.history.capacity(), graph, buf);
            } else {
                let peaks = column_peaks(&values, self.history.capacity(), graph.width as usize);
                // Sparklines take integers: thousandths of the window's largest value.
                let scale = if max > 0.0 { 1000.0 / max } else { 0.0 };
                let bars: Vec<Option<u64>> = peaks
                    .iter()
                    .map(|v| v.map(|v| (v.max(0.0) * scale).round() as u64))
                    .collect();
                Sparkline::default()
                    .data(bars)
                    .max(1000)
                    .style(Style::default().fg(series.color()).bg(PANEL_BG))
                    .render(graph, buf);
            }
        }
    }
}

/// Energy against time as a braille line, x from the window's start to now, y over the window's
/// range (a flat line when energy is kept).
fn energy_chart(values: &[f32], capacity: usize, area: Rect, buf: &mut Buffer) {
    let start = capacity.saturating_sub(values.len()) as f64;
    let points: Vec<(f64, f64)> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| (start + i as f64, f64::from(v)))
        .collect();
    let (lo, hi) = values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    // A flat series gets a band around it, so it draws as a line across the middle.
    let pad = ((hi - lo) * 0.05).max(1e-3 * lo.abs().max(hi.abs()).max(1.0));
    let dataset = Dataset::default()
        .marker(Marker::Braille)
        .graph_type(GraphType::Line)
        .style(Style::default().fg(Series::Energy.color()))
        .data(&points);
    // The chart clears its area to the default background unless told otherwise: in a terminal
    // with a white default it was a white box in the black panel.
    Chart::new(vec![dataset])
        .style(Style::default().bg(PANEL_BG))
        .x_axis(Axis::default().bounds([0.0, capacity.max(2) as f64 - 1.0]))
        .y_axis(Axis::default().bounds([f64::from(lo - pad), f64::from(hi + pad)]))
        .render(area, buf);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_history_keeps_ten_seconds() {
        let mut history = History::new(1.0 / 60.0);
        assert_eq!(history.capacity(), 600);
        for i in 0..700 {
            history.record(
                Sample {
                    step_ms: i as f32,
                    ..Sample::default()
                },
                1.0 / 60.0,
            );
        }
        assert_eq!(history.samples().len(), 600);
        assert_eq!(history.samples().front().unwrap().step_ms, 100.0);
    }

    #[test]
    fn column_peaks_keep_a_single_spike() {
        let mut values = vec![1.0; 600];
        values[417] = 9.0;
        let peaks = column_peaks(&values, 600, 20);
        assert_eq!(peaks.len(), 20);
        assert_eq!(peaks.iter().filter(|&&p| p == Some(9.0)).count(), 1);
        assert_eq!(peaks[417 * 20 / 600], Some(9.0));
    }

    #[test]
    fn a_short_history_sits_at_the_right_of_the_window() {
        let peaks = column_peaks(&[2.0, 3.0, 4.0], 12, 6);
        assert_eq!(peaks, vec![None, None, None, None, Some(2.0), Some(4.0)]);
        assert_eq!(column_peaks(&[2.0, 3.0], 2, 10), vec![Some(2.0), Some(3.0)]);
    }

    #[test]
    fn every_chart_is_drawn_when_there_is_room() {
        let mut history = History::new(0.1);
        for i in 0..50 {
            history.record(
                Sample {
                    energy: 100.0 - i as f32 * 0.1,
                    momentum: 2.0,
                    penetration: 0.001 * (i % 5) as f32,
                    step_ms: 0.2,
                },
                0.1,
            );
        }
        let area = Rect::new(0, 0, 30, 12);
        let mut buf = Buffer::empty(area);
        Charts { history: &history }.render(area, &mut buf);
        let text: String = (0..12)
            .map(|y| (0..30).map(|x| buf[(x, y)].symbol()).collect::<String>() + "\n")
            .collect();
        for title in [
            "energy 95.10 J",
            "ms/step 0.200",
            "depth 4.00 mm",
            "momentum 2.00",
        ] {
            assert!(text.contains(title), "{title}:\n{text}");
        }
        // Braille dots for the energy line, bars for the sparklines.
        assert!(
            text.chars().any(|c| ('\u{2801}'..='\u{28ff}').contains(&c)),
            "{text}"
        );
        assert!(text.contains('█') || text.contains('▄'), "{text}");
    }
}
