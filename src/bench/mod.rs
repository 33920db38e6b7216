//! `nudge bench`: speed beside error. Every number the README claims comes from here.
//!
//! The benchmarks reuse the scenes of the tests and the app (`scene::cases`, the built-ins).

/// Writes a progress note to stderr, only when stderr is a terminal: the notes end in `\r` so each
/// overwrites the last, and redirected to a file they piled up into one long line.
macro_rules! progress {
    ($($arg:tt)*) => {
        if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
            eprint!($($arg)*);
        }
    };
}
pub(crate) use progress;

pub mod app;
pub mod cells;
pub mod chart;
pub mod colour;
pub mod corpus;
pub mod fixes;
pub mod hands;
pub mod kernels;
pub mod mechanisms;
pub mod overlays;
pub mod physics;
pub mod render;
pub mod rest;
pub mod rewind;
pub mod stages;
pub mod table;

use std::io::Write;

use serde::Serialize;

use crate::scene::piles::Pile;

/// Which benchmarks to run (`nudge bench WHAT`; clap takes the names from the variants).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Which {
    All,
    Render,
    Physics,
    App,
    Rewind,
    Kernels,
    Mechanisms,
    Corpus,
    Rest,
    Cells,
}

/// `nudge bench physics --chart`: runs the hard-case sweep and prints it as charts (see [`chart`]).
pub fn run_chart(
    quick: bool,
    plain: bool,
    depth: crate::term::ColorDepth,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let cases = physics::run_cases(quick);
    progress!("bench physics: done{}\n", " ".repeat(40));
    out.write_all(chart::chart_text(&cases, plain, depth).as_bytes())?;
    Ok(())
}

/// Runs the chosen benchmarks and prints tables (or JSON) to `out`: one section per benchmark, in
/// this order. `piles` are what `rest` measures (`None`: every pile of `scene::piles`).
pub fn run(
    which: Which,
    json: bool,
    quick: bool,
    piles: Option<Vec<Pile>>,
    out: &mut dyn Write,
) -> anyhow::Result<()> {
    let mut report = JsonReport::default();
    let runs = |section: Which| which == section || (which == Which::All && section.in_all());
    if runs(Which::Render) {
        let frames = if quick { 20 } else { 200 };
        let rows = render::bench_render(frames);
        section(json, out, &mut report.render, rows, |r: &[_], o| {
            render::print_table(r, frames, o)
        })?;
        let rows = render::bench_balls(if quick { 10 } else { 60 });
        section(json, out, &mut report.balls, rows, render::print_balls)?;
        let rows = overlays::bench_overlays(if quick { 10 } else { 60 });
        section(json, out, &mut report.overlays, rows, overlays::print_table)?;
        let rows = colour::run()?;
        section(json, out, &mut report.colour, rows, colour::print_table)?;
        let marks = colour::mark_rows();
        section(
            json,
            out,
            &mut report.colour_marks,
            marks,
            colour::print_marks,
        )?;
    }
    if runs(Which::Physics) {
        let rows = physics::run(quick);
        section(json, out, &mut report.physics, rows, physics::print_table)?;
        section(
            json,
            out,
            &mut report.fixes,
            fixes::run(),
            fixes::print_table,
        )?;
    }
    if runs(Which::Rest) {
        let rows = rest::run(&piles.unwrap_or_else(crate::scene::piles::all), quick);
        progress!("bench rest: done{}\n", " ".repeat(40));
        section(json, out, &mut report.rest, rows, rest::print_table)?;
    }
    if runs(Which::Corpus) {
        section(
            json,
            out,
            &mut report.corpus,
            corpus::run(),
            corpus::print_table,
        )?;
    }
    if runs(Which::Rewind) {
        let rows = rewind::run(quick);
        section(json, out, &mut report.rewind, rows, rewind::print_table)?;
    }
    if runs(Which::App) {
        let (frames, picking) = app::run(quick)?;
        let rows = AppReport { frames, picking };
        section(json, out, &mut report.app, rows, |r: &AppReport, o| {
            app::print_table(&r.frames, &r.picking, o)
        })?;
        section(
            json,
            out,
            &mut report.hands,
            hands::figures(),
            hands::print_table,
        )?;
    }
    if runs(Which::Mechanisms) {
        let rows = mechanisms::run(quick);
        section(
            json,
            out,
            &mut report.mechanisms,
            rows,
            mechanisms::print_table,
        )?;
    }
    if runs(Which::Kernels) {
        let rows = kernels::run(quick);
        section(json, out, &mut report.kernels, rows, kernels::print_table)?;
    }
    if runs(Which::Cells) {
        let cells = cells::run(quick)?;
        progress!("{}\r", " ".repeat(40));
        if json {
            report.cells = Some(cells);
        } else {
            cells::write_tables(&cells, out)?;
        }
    }
    if json {
        serde_json::to_writer_pretty(&mut *out, &report)?;
        writeln!(out)?;
    }
    Ok(())
}

impl Which {
    /// Whether `nudge bench` (all) runs it: the rest and the corpus run only on their own (each
    /// takes minutes).
    fn in_all(self) -> bool {
        !matches!(self, Which::Rest | Which::Corpus)
    }
}

/// One benchmark's section of the report: its rows go into the JSON document's `slot`, or are
/// printed by `print` followed by a blank line.
fn section<T: std::borrow::Borrow<R>, R: ?Sized>(
    json: bool,
    out: &mut dyn Write,
    slot: &mut Option<T>,
    rows: T,
    print: impl FnOnce(&R, &mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    if json {
        *slot = Some(rows);
    } else {
        print(rows.borrow(), out)?;
        writeln!(out)?;
    }
    Ok(())
}

#[derive(Default, Serialize)]
struct JsonReport {
    #[serde(skip_serializing_if = "Option::is_none")]
    render: Option<Vec<render::RenderBenchRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    balls: Option<Vec<render::BallsBenchRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    overlays: Option<Vec<overlays::OverlayBenchRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour: Option<Vec<colour::FidelityRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    colour_marks: Option<Vec<colour::MarkRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    physics: Option<physics::PhysicsReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    fixes: Option<Vec<fixes::FixRow>>,
    /// `nudge bench corpus` only (`physics` holds it otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    corpus: Option<Vec<corpus::CorpusRow>>,
    /// `nudge bench rest` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    rest: Option<Vec<rest::RestRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rewind: Option<Vec<rewind::RewindRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    app: Option<AppReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    kernels: Option<Vec<kernels::KernelRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mechanisms: Option<Vec<mechanisms::MechanismRow>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    hands: Option<Vec<hands::Figure>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cells: Option<cells::CellsReport>,
}

/// The app section: end-to-end frames and picking.
#[derive(Serialize)]
struct AppReport {
    frames: Vec<app::FrameRow>,
    picking: app::PickRow,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::RenderMode;

    /// `--json` prints one JSON document with a member per section that ran, and nothing else.
    #[test]
    fn the_json_report_is_one_document_holding_only_the_sections_run() {
        let mut out = Vec::new();
        run(Which::Render, true, true, None, &mut out).unwrap();
        let json: serde_json::Value = serde_json::from_slice(&out).expect("valid JSON");
        let sections: Vec<&String> = json.as_object().unwrap().keys().collect();
        // `nudge bench render` measures balls, colour fidelity and the overlays beside the frame
        // times.
        assert_eq!(
            sections,
            ["balls", "colour", "colour_marks", "overlays", "render"]
        );
        for row in json["overlays"].as_array().unwrap() {
            assert!(row["ratio"].as_f64().unwrap() > 0.0, "{row}");
        }
        for row in json["colour"].as_array().unwrap() {
            assert!(
                ["256", "16"].contains(&row["colors"].as_str().unwrap()),
                "{row}"
            );
            assert!(
                ["ordered", "none"].contains(&row["dither"].as_str().unwrap()),
                "{row}"
            );
            assert!(row["mean_de"].as_f64().unwrap() >= 0.0, "{row}");
        }
        let rows = json["render"].as_array().unwrap();
        assert_eq!(rows.len(), RenderMode::ALL.len());
        for (row, mode) in rows.iter().zip(RenderMode::ALL) {
            assert_eq!(row["mode"], mode.name());
            assert!(row["render_ms"].as_f64().unwrap() > 0.0, "{row}");
            assert!(row["render_and_map_ms"].as_f64().unwrap() > 0.0, "{row}");
        }
    }
}
