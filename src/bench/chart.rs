//! `nudge bench physics --chart`: speed against error as a picture. For each hard case, its first
//! numeric error metric against ms per step on log–log axes, one point per sub-steps × iterations
//! setting, the points of one iteration count joined in sub-step order, the default setting (4
//! sub-steps, 1 iteration) drawn as a block. A grid of ratatui `Chart`s in one `Buffer`, printed as
//! ANSI text like `nudge snapshot` (or characters only with `--plain`), so it works in a pipe.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Axis, Block, Chart, Dataset, GraphType, Widget};

use super::physics::{CaseRow, Value};
use crate::physics::Settings;

/// One chart's size in cells.
pub const CHART_COLS: u16 = 40;
pub const CHART_ROWS: u16 = 14;
/// Charts side by side.
pub const CHARTS_PER_ROW: u16 = 3;

/// Colours of the iteration counts 1, 2 and 4 (others: white).
fn iteration_color(iterations: u32) -> Color {
    match iterations {
        1 => Color::LightCyan,
        2 => Color::LightMagenta,
        4 => Color::LightYellow,
        _ => Color::White,
    }
}

/// The points of one case: (log10 ms/step, log10 error, sub-steps, iterations).
struct CasePoints {
    name: String,
    metric: String,
    points: Vec<(f64, f64, u32, u32)>,
    /// Every run's error is exactly zero: no log scale to place them on, so they are drawn on a
    /// line of their own, labelled 0.
    all_zero: bool,
}

/// The first numeric metric of each case, with every run's point; cases with no numeric metric are
/// left out. A zero error (a perfect run) is drawn at a tenth of the case's smallest positive one, so
/// it stays on the log axis, at the bottom; a case whose runs are all perfect is drawn at zero.
fn case_points(rows: &[CaseRow]) -> Vec<CasePoints> {
    let mut out: Vec<CasePoints> = Vec::new();
    for row in rows {
        let Some((index, metric)) = row
            .metrics
            .iter()
            .enumerate()
            .find(|(_, m)| matches!(m.value, Value::Number(_)))
        else {
            continue;
        };
        let label = if metric.unit.is_empty() {
            metric.name.to_string()
        } else {
            format!("{} ({})", metric.name, metric.unit)
        };
        if out.last().is_none_or(|c| c.name != row.case) {
            out.push(CasePoints {
                name: row.case.clone(),
                metric: label,
                points: Vec::new(),
                all_zero: false,
            });
        }
        let value = match row.metrics[index].value {
            Value::Number(v) => v,
            _ => f64::NAN,
        };
        if let Some(case) = out.last_mut()
            && row.ms_per_step > 0.0
            && value.is_finite()
            && value >= 0.0
        {
            case.points
                .push((row.ms_per_step.log10(), value, row.substeps, row.iterations));
        }
    }
    for case in &mut out {
        let floor = case
            .points
            .iter()
            .map(|p| p.1)
            .filter(|&v| v > 0.0)
            .fold(f64::INFINITY, f64::min)
            / 10.0;
        case.all_zero = !floor.is_finite();
        for p in &mut case.points {
            p.1 = if case.all_zero {
                0.0
            } else {
                p.1.max(floor).log10()
            };
        }
    }
    out.retain(|c| !c.points.is_empty());
    out
}

/// Bounds widened to whole decades (at least one decade wide).
fn decades(values: impl Iterator<Item = f64>) -> [f64; 2] {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let (lo, hi) = (lo.floor(), hi.ceil());
    if hi > lo { [lo, hi] } else { [lo, lo + 1.0] }
}

/// A power of ten as a short label: 0.001, 0.1, 1, 100, 1e5.
fn decade_label(exponent: f64) -> String {
    let e = exponent as i32;
    match e {
        -3..=-1 => format!("{}", 10f64.powi(e)),
        0..=4 => format!("{}", 10i64.pow(e as u32)),
        _ => format!("1e{e}"),
    }
}

/// Draws every case's chart into one buffer, [`CHARTS_PER_ROW`] across, under a two-line legend.
pub fn chart_buffer(rows: &[CaseRow]) -> Buffer {
    let cases = case_points(rows);
    let grid_rows = (cases.len() as u16).div_ceil(CHARTS_PER_ROW);
    let area = Rect::new(
        0,
        0,
        CHART_COLS * CHARTS_PER_ROW,
        3 + grid_rows * CHART_ROWS,
    );
    let mut buf = Buffer::empty(area);
    let defaults = Settings::default();
    let legends = [
        Line::from(
            " Error against ms per step, both on log scales: each point a setting, left to right \
             1, 2, 4 and 8 sub-steps.",
        ),
        Line::from(vec![
            Span::raw(" Iterations per sub-step: "),
            Span::styled("• 1", Style::default().fg(iteration_color(1))),
            Span::raw("  "),
            Span::styled("• 2", Style::default().fg(iteration_color(2))),
            Span::raw("  "),
            Span::styled("• 4", Style::default().fg(iteration_color(4))),
            Span::raw(format!(
                ";  █ the default: {} sub-steps, {} iteration.",
                defaults.substeps, defaults.iterations
            )),
        ]),
    ];
    for (y, legend) in legends.iter().enumerate() {
        legend.render(Rect::new(0, y as u16, area.width, 1), &mut buf);
    }
    for (i, case) in cases.iter().enumerate() {
        let (col, row) = (i as u16 % CHARTS_PER_ROW, i as u16 / CHARTS_PER_ROW);
        let cell = Rect::new(
            col * CHART_COLS,
            3 + row * CHART_ROWS,
            CHART_COLS,
            CHART_ROWS,
        );
        draw_case(case, &defaults, cell, &mut buf);
    }
    buf
}

fn draw_case(case: &CasePoints, defaults: &Settings, area: Rect, buf: &mut Buffer) {
    let mut iteration_counts: Vec<u32> = case.points.iter().map(|p| p.3).collect();
    iteration_counts.sort_unstable();
    iteration_counts.dedup();
    // Per iteration count: the curve in sub-step order (braille), and its points on top.
    let curves: Vec<(u32, Vec<(f64, f64)>)> = iteration_counts
        .iter()
        .map(|&it| {
            let mut pts: Vec<(u32, (f64, f64))> = case
                .points
                .iter()
                .filter(|p| p.3 == it)
                .map(|p| (p.2, (p.0, p.1)))
                .collect();
            pts.sort_by_key(|p| p.0);
            (it, pts.into_iter().map(|p| p.1).collect())
        })
        .collect();
    let default_point: Vec<(f64, f64)> = case
        .points
        .iter()
        .filter(|p| p.2 == defaults.substeps && p.3 == defaults.iterations)
        .map(|p| (p.0, p.1))
        .collect();
    let mut datasets = Vec::new();
    for (it, pts) in &curves {
        let style = Style::default().fg(iteration_color(*it));
        datasets.push(
            Dataset::default()
                .marker(Marker::Braille)
                .graph_type(GraphType::Line)
                .style(style)
                .data(pts),
        );
        datasets.push(
            Dataset::default()
                .marker(Marker::Dot)
                .graph_type(GraphType::Scatter)
                .style(style)
                .data(pts),
        );
    }
    datasets.push(
        Dataset::default()
            .marker(Marker::Block)
            .graph_type(GraphType::Scatter)
            .style(Style::default().fg(Color::White))
            .data(&default_point),
    );
    let x = decades(case.points.iter().map(|p| p.0));
    let labels = |b: [f64; 2]| vec![decade_label(b[0]), decade_label(b[1])];
    // A case at zero is drawn on a line across the middle: on the bottom row, the x axis's title
    // was drawn over whichever point sat under it (the default's block, as the timings fell).
    let (y, y_labels) = if case.all_zero {
        (
            [-1.0, 1.0],
            vec![String::new(), "0".to_string(), String::new()],
        )
    } else {
        let y = decades(case.points.iter().map(|p| p.1));
        (y, labels(y))
    };
    Chart::new(datasets)
        .block(Block::bordered().title(format!(" {} ", case.name)))
        .x_axis(
            Axis::default()
                .title("ms/step")
                .bounds(x)
                .labels(labels(x))
                .style(Style::default().fg(Color::Gray)),
        )
        .y_axis(
            Axis::default()
                .title(case.metric.clone())
                .bounds(y)
                .labels(y_labels)
                .style(Style::default().fg(Color::Gray)),
        )
        .render(area, buf);
}

/// The chart as text: ANSI colours at `depth`, or the characters alone (trailing blanks trimmed).
pub fn chart_text(rows: &[CaseRow], plain: bool, depth: crate::term::ColorDepth) -> String {
    let buf = chart_buffer(rows);
    if plain {
        let area = buf.area;
        let mut text = String::new();
        for y in 0..area.height {
            let line: String = (0..area.width).map(|x| buf[(x, y)].symbol()).collect();
            text.push_str(line.trim_end());
            text.push('\n');
        }
        text
    } else {
        crate::term::buffer_to_ansi(&buf, depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::physics::Metric;

    fn row(case: &str, substeps: u32, iterations: u32, ms: f64, error: f64) -> CaseRow {
        CaseRow {
            case: case.into(),
            substeps,
            iterations,
            ms_per_step: ms,
            metrics: vec![Metric {
                name: "drift",
                value: Value::Number(error),
                unit: "m",
            }],
        }
    }

    #[test]
    fn every_case_gets_a_chart_with_its_default_marked() {
        let mut rows = Vec::new();
        for (case, scale) in [("stack", 1.0), ("ramp", 0.01)] {
            for (k, sub) in [1, 2, 4, 8].into_iter().enumerate() {
                rows.push(row(case, sub, 1, 0.01 * sub as f64, scale / (k + 1) as f64));
            }
        }
        rows.push(row("flag only", 4, 1, 0.1, f64::NAN));
        let text = chart_text(&rows, true, crate::term::ColorDepth::TrueColor);
        assert!(
            text.contains(" stack ") && text.contains(" ramp "),
            "{text}"
        );
        assert!(!text.contains("flag only"), "{text}");
        assert!(
            text.contains("drift (m)") && text.contains("ms/step"),
            "{text}"
        );
        // One default per case, and the legend's.
        assert_eq!(text.matches('█').count(), 3, "{text}");
        assert!(text.contains('•'), "{text}");
        assert!(!text.contains('\x1b'));
    }

    #[test]
    fn a_case_whose_runs_are_all_perfect_is_drawn_at_zero() {
        let rows = [row("c", 1, 1, 0.1, 0.0), row("c", 2, 1, 0.2, 0.0)];
        let cases = case_points(&rows);
        assert!(cases[0].all_zero);
        assert_eq!(cases[0].points.len(), 2);
        let text = chart_text(&rows, true, crate::term::ColorDepth::TrueColor);
        assert!(text.contains("┌ c "), "{text}");
    }

    /// The default's block stays visible wherever its timing puts it: here the slowest run, under
    /// the x axis's title.
    #[test]
    fn a_perfect_default_is_not_hidden_under_the_axis_title() {
        let defaults = Settings::default();
        let rows = [
            row("c", 1, 1, 0.001, 0.0),
            row("c", 2, 1, 0.002, 0.0),
            row("c", defaults.substeps, defaults.iterations, 0.0095, 0.0),
        ];
        let text = chart_text(&rows, true, crate::term::ColorDepth::TrueColor);
        // The case's default, and the legend's.
        assert_eq!(text.matches('█').count(), 2, "{text}");
    }

    #[test]
    fn a_perfect_run_sits_a_decade_below_the_best_other() {
        let rows = [row("c", 1, 1, 0.1, 0.5), row("c", 2, 1, 0.2, 0.0)];
        let cases = case_points(&rows);
        assert_eq!(cases[0].points[1].1, (0.05f64).log10());
    }

    #[test]
    fn decades_round_outward() {
        assert_eq!(decades([-2.5, -0.3].into_iter()), [-3.0, 0.0]);
        assert_eq!(decades([1.0].into_iter()), [1.0, 2.0]);
        assert_eq!(decade_label(-2.0), "0.01");
        assert_eq!(decade_label(2.0), "100");
        assert_eq!(decade_label(-5.0), "1e-5");
    }
}
