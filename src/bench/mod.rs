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
use table::Table;

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

/// Runs the chosen benchmarks and prints tables (or JSON) to `out`.
pub fn run(which: Which, json: bool, quick: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let mut report = JsonReport::default();
    if matches!(which, Which::All | Which::Render) {
        let frames = if quick { 20 } else { 200 };
        let rows = render::bench_render(frames);
        if json {
            report.render = Some(rows);
        } else {
            writeln!(
                out,
                "render: 210-box pyramid, 200x100 px (200x50 cells), median of {frames} frames"
            )?;
            let mut table = Table::new(&[
                "mode",
                "render ms",
                "render + half-block map ms",
                "same, 256 colours dithered",
            ]);
            for r in &rows {
                table.push(vec![
                    r.mode.name().to_string(),
                    format!("{:.3}", r.render_ms),
                    format!("{:.3}", r.render_and_map_ms),
                    format!("{:.3}", r.render_and_map_256_ms),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
        let rows = overlays::bench_overlays(if quick { 10 } else { 60 });
        if json {
            report.overlays = Some(rows);
        } else {
            writeln!(
                out,
                "overlays: the app's frame (rasterize + overlays) of the settled pyramid at 200x50 cells, plain and with all 8 debug overlays on, median (the issue asks at most 1.5x)"
            )?;
            let mut table = Table::new(&["supersampled", "plain ms", "every overlay ms", "ratio"]);
            for r in &rows {
                table.push(vec![
                    if r.supersample { "yes" } else { "no" }.to_string(),
                    format!("{:.3}", r.plain_ms),
                    format!("{:.3}", r.overlays_ms),
                    format!("{:.2}x", r.ratio),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
        let rows = colour::run()?;
        if json {
            report.colour = Some(rows);
        } else {
            let (cols, rows_) = colour::FIDELITY_SIZE;
            writeln!(
                out,
                "colour: built-in scenes at {cols}x{rows_}, textured, {} steps in, against their truecolor frame in 2x2-pixel blends (hue lost: coloured blocks shown grey; OKLab distance x100; added speckle: pixels' distance from their block's blend beyond the truecolor frame's; speckled: blocks where that exceeds 4)",
                colour::FIDELITY_STEPS
            )?;
            let mut table = Table::new(&[
                "scene",
                "colours",
                "dither",
                "hue lost",
                "mean OKLab error",
                "on coloured blocks",
                "95th percentile",
                "added speckle",
                "speckled",
            ]);
            for r in &rows {
                table.push(vec![
                    r.scene.clone(),
                    r.colors.name().to_string(),
                    r.dither.name().to_string(),
                    format!("{:.1}%", r.fidelity.hue_lost * 100.0),
                    format!("{:.2}", r.fidelity.mean_de),
                    format!("{:.2}", r.fidelity.coloured_mean_de),
                    format!("{:.2}", r.fidelity.p95_de),
                    format!("{:.2}", r.fidelity.speckle),
                    format!("{:.1}%", r.fidelity.speckled * 100.0),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
        let marks = colour::mark_rows();
        if json {
            report.colour_marks = Some(marks);
        } else {
            writeln!(
                out,
                "colour marks: the default scene's overlay marks (--overlay, all but the tints) and a grab's tether, pixel by pixel against the colours they are drawn in (off colour: coloured mark pixels shown grey or turned over {} degrees in hue; hidden: mark pixels shown within {} (OKLab x100) of what is shown there without them)",
                crate::term::fidelity::MARK_HUE_TURN_DEG,
                crate::term::fidelity::MARK_CONTRAST * 100.0
            )?;
            let mut table = Table::new(&[
                "marks",
                "colours",
                "dither",
                "pixels",
                "off colour",
                "hidden",
                "mean OKLab error",
            ]);
            for r in &marks {
                table.push(vec![
                    r.marks.to_string(),
                    r.colors.name().to_string(),
                    r.dither.name().to_string(),
                    r.fidelity.pixels.to_string(),
                    format!("{:.1}%", r.fidelity.off_colour * 100.0),
                    format!("{:.1}%", r.fidelity.hidden * 100.0),
                    format!("{:.2}", r.fidelity.mean_de),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Physics) {
        let physics_report = physics::run(quick);
        let fix_rows = fixes::run();
        if json {
            report.physics = Some(physics_report);
            report.fixes = Some(fix_rows);
        } else {
            physics::print_table(&physics_report, out)?;
            writeln!(out)?;
            writeln!(
                out,
                "physics: each convergence fix on its hard case, on (the defaults) and off"
            )?;
            let mut table = Table::new(&["fix", "case", "on", "off"]);
            for r in &fix_rows {
                table.push(vec![
                    r.fix.to_string(),
                    r.case.to_string(),
                    format!("{:.3} {}", r.on, r.unit),
                    format!("{:.3} {}", r.off, r.unit),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if which == Which::Rest {
        let rows = rest::run(quick);
        progress!("bench rest: done{}\n", " ".repeat(40));
        if json {
            report.rest = Some(rows);
        } else {
            rest::print_table(&rows, out)?;
            writeln!(out)?;
        }
    }
    if which == Which::Corpus {
        let rows = corpus::run();
        if json {
            report.corpus = Some(rows);
        } else {
            corpus::print_table(&rows, out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Rewind) {
        let rows = rewind::run(quick);
        if json {
            report.rewind = Some(rows);
        } else {
            writeln!(
                out,
                "rewind: the timeline's keyframes (one every {} steps) over the run; cost per step is the keyframes' time spread over every step",
                crate::app::time::timeline::KEYFRAME_STEPS
            )?;
            let mut table = Table::new(&[
                "scene",
                "bodies",
                "steps",
                "bytes held",
                "keyframes",
                "seconds kept",
                "us/step",
                "us/keyframe",
                "rewind 1 s, ms",
            ]);
            for r in &rows {
                table.push(vec![
                    r.scene.clone(),
                    r.bodies.to_string(),
                    r.steps.to_string(),
                    r.bytes.to_string(),
                    r.keyframes.to_string(),
                    format!("{:.1}", r.seconds),
                    format!("{:.2}", r.us_per_step),
                    format!("{:.1}", r.us_per_keyframe),
                    format!("{:.2}", r.rewind_1s_ms),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::App) {
        let (rows, pick) = app::run(quick)?;
        if json {
            report.app = Some(AppReport {
                frames: rows,
                picking: pick,
            });
        } else {
            writeln!(
                out,
                "app: end-to-end frame (2 physics steps + render + map + diff) at 30 frame slots a second through the default 1 MB/s byte budget (held: slots it skipped); pyramid rows: its bottom row knocked out"
            )?;
            let mut table = Table::new(&[
                "scene",
                "terminal",
                "colours",
                "dither",
                "frame ms",
                "bytes/frame",
                "bytes/s at 30 fps",
                "worst second, bytes",
                "held",
            ]);
            for r in &rows {
                table.push(vec![
                    r.scene.clone(),
                    format!("{}x{}", r.cols, r.rows),
                    r.colors.name().to_string(),
                    if r.colors == crate::term::ColorDepth::TrueColor {
                        "-".to_string()
                    } else {
                        r.dither.name().to_string()
                    },
                    format!("{:.3}", r.frame_ms),
                    format!("{:.0}", r.bytes_per_frame),
                    format!("{:.0}", r.bytes_per_second_at_30fps),
                    r.peak_bytes_per_second.to_string(),
                    format!("{}/{}", r.held_frames, r.frames),
                ]);
            }
            table.write(out)?;
            writeln!(
                out,
                "picking: {:.2} us per ray cast over {} bodies ({:.0}% of rays hit)\n",
                pick.us_per_pick,
                pick.bodies,
                pick.hit_fraction * 100.0
            )?;
        }
        hands_report(json, out, &mut report)?;
    }
    if matches!(which, Which::All | Which::Mechanisms) {
        let rows = mechanisms::run(quick);
        if json {
            report.mechanisms = Some(rows);
        } else {
            writeln!(
                out,
                "mechanisms: what the contact mechanisms cost, each on its own (noisy)"
            )?;
            let mut table = Table::new(&["mechanism", "measured on", "cost", "unit", "note"]);
            for r in &rows {
                table.push(vec![
                    r.mechanism.to_string(),
                    r.case.clone(),
                    format!("{:.4}", r.value),
                    r.unit.to_string(),
                    r.note.clone(),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Kernels) {
        let rows = kernels::run(quick);
        if json {
            report.kernels = Some(rows);
        } else {
            writeln!(
                out,
                "kernels: one call at a time, median over batches (see bench/kernels.rs for the inputs)"
            )?;
            let mut table = Table::new(&["kernel", "input", "ns/call", "output"]);
            for r in &rows {
                table.push(vec![
                    r.kernel.to_string(),
                    r.case.clone(),
                    format!("{:.0}", r.ns_per_call),
                    format!("{} {}", r.output, r.output_unit),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Cells) {
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

/// `nudge bench --json`: one object with a member per section that ran.
#[derive(Default, Serialize)]
struct JsonReport {
    #[serde(skip_serializing_if = "Option::is_none")]
    render: Option<Vec<render::RenderBenchRow>>,
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

/// The hands' figures (see [`hands`]), as a table or a JSON section.
fn hands_report(json: bool, out: &mut dyn Write, report: &mut JsonReport) -> anyhow::Result<()> {
    let figures = hands::figures();
    if json {
        report.hands = Some(figures);
        return Ok(());
    }
    writeln!(
        out,
        "hands: the headless app driven with synthetic mouse events, 120x40, 30 frames a second"
    )?;
    let mut table = Table::new(&["figure", "unit", "perspective", "orthographic", "issue"]);
    for f in &figures {
        table.push(vec![
            f.name.clone(),
            f.unit.to_string(),
            format!("{:.2}", f.perspective),
            format!("{:.2}", f.orthographic),
            f.target.to_string(),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::RenderMode;

    /// `--json` prints one JSON document with a member per section that ran, and nothing else.
    #[test]
    fn the_json_report_is_one_document_holding_only_the_sections_run() {
        let mut out = Vec::new();
        run(Which::Render, true, true, &mut out).unwrap();
        let json: serde_json::Value = serde_json::from_slice(&out).expect("valid JSON");
        let sections: Vec<&String> = json.as_object().unwrap().keys().collect();
        // `nudge bench render` measures colour fidelity and the overlays beside the frame times.
        assert_eq!(sections, ["colour", "colour_marks", "overlays", "render"]);
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
