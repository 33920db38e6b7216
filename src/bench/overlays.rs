//! What the debug overlays cost: a frame of the settled 210-box pyramid (400 contact manifolds)
//! drawn by the app at 200 × 50 cells, plain and with every overlay on, with and without the
//! app's 2× supersampling. The issue asks for at most 1.5× the plain frame.

use std::time::Instant;

use ratatui::layout::Rect;

use crate::app::panels::overlays::OverlaySet;
use crate::app::{App, AppConfig};
use crate::scene::cases;
use crate::util::median;

/// One row: the median ms of a frame (rasterize, overlays) plain and with every overlay.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct OverlayBenchRow {
    pub supersample: bool,
    pub plain_ms: f64,
    pub overlays_ms: f64,
    /// `overlays_ms / plain_ms`.
    pub ratio: f64,
}

/// Times `frames` frames of each kind, after settling the pyramid for a second.
pub fn bench_overlays(frames: usize) -> Vec<OverlayBenchRow> {
    [false, true]
        .into_iter()
        .map(|supersample| {
            let config = AppConfig {
                supersample,
                ..AppConfig::default()
            };
            let mut app = App::new(cases::pyramid(20), config);
            app.resize(Rect::new(0, 0, 200, 51));
            for _ in 0..60 {
                app.world_mut().step();
            }
            let time = |app: &mut App, set: OverlaySet| {
                app.set_overlays(set);
                for _ in 0..3 {
                    app.render_scene();
                }
                let mut ms: Vec<f64> = (0..frames.max(1))
                    .map(|_| {
                        let start = Instant::now();
                        app.render_scene();
                        start.elapsed().as_secs_f64() * 1e3
                    })
                    .collect();
                median(&mut ms)
            };
            let plain_ms = time(&mut app, OverlaySet::default());
            let overlays_ms = time(&mut app, OverlaySet::ALL);
            OverlayBenchRow {
                supersample,
                plain_ms,
                overlays_ms,
                ratio: overlays_ms / plain_ms,
            }
        })
        .collect()
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(
    rows: &[OverlayBenchRow],
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "overlays: the app's frame (rasterize + overlays) of the settled pyramid at 200x50 cells, plain and with all 8 debug overlays on, median (the issue asks at most 1.5x)"
    )?;
    let mut table = Table::new(&["supersampled", "plain ms", "every overlay ms", "ratio"]);
    for r in rows {
        table.push(vec![
            if r.supersample { "yes" } else { "no" }.to_string(),
            format!("{:.3}", r.plain_ms),
            format!("{:.3}", r.overlays_ms),
            format!("{:.2}x", r.ratio),
        ]);
    }
    table.write(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_rows_time_a_plain_and_an_overlaid_frame() {
        let rows = bench_overlays(1);
        assert_eq!(
            rows.iter().map(|r| r.supersample).collect::<Vec<_>>(),
            [false, true]
        );
        for r in &rows {
            assert!(r.plain_ms > 0.0 && r.overlays_ms > 0.0, "{r:?}");
            assert_eq!(r.ratio, r.overlays_ms / r.plain_ms);
        }
    }
}
