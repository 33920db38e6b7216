//! `nudge bench`: speed beside error. Every number the README claims comes from here.
//!
//! The benchmarks reuse the scenes of the tests and the app (`scene::cases`, the built-ins).

pub mod app;
pub mod colour;
pub mod hard_case;
pub mod penetration;
pub mod physics;
pub mod poke;
pub mod render;
pub mod rewind;
pub mod table;

use std::io::Write;

use crate::term::ColorDepth;
use table::{Table, json_number, json_string};

/// Which benchmarks to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    All,
    Render,
    Physics,
    App,
    Rewind,
}

impl std::str::FromStr for Which {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "all" => Ok(Which::All),
            "render" => Ok(Which::Render),
            "physics" => Ok(Which::Physics),
            "app" => Ok(Which::App),
            "rewind" => Ok(Which::Rewind),
            other => Err(format!(
                "unknown benchmark '{other}' (all, render, physics, app or rewind)"
            )),
        }
    }
}

/// Runs the chosen benchmarks and prints tables (or JSON) to `out`.
pub fn run(which: Which, json: bool, quick: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let mut sections: Vec<String> = Vec::new();
    if matches!(which, Which::All | Which::Render) {
        let frames = if quick { 20 } else { 200 };
        let rows = render::bench_render(frames);
        if json {
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"mode\":{},\"render_ms\":{},\"render_and_map_ms\":{},\"render_and_map_256_ms\":{}}}",
                        json_string(r.mode.name()),
                        json_number(r.render_ms),
                        json_number(r.render_and_map_ms),
                        json_number(r.render_and_map_256_ms)
                    )
                })
                .collect();
            sections.push(format!("\"render\":[{}]", items.join(",")));
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
        let rows = colour::run()?;
        if json {
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"scene\":{},\"colors\":{},\"dither\":{},\"hue_lost\":{},\"mean_de\":{},\"p95_de\":{},\"speckle\":{}}}",
                        json_string(&r.scene),
                        json_string(r.colors.name()),
                        json_string(r.dither.name()),
                        json_number(r.fidelity.hue_lost),
                        json_number(r.fidelity.mean_de),
                        json_number(r.fidelity.p95_de),
                        json_number(r.fidelity.speckle)
                    )
                })
                .collect();
            sections.push(format!("\"colour\":[{}]", items.join(",")));
        } else {
            let (cols, rows_) = colour::FIDELITY_SIZE;
            writeln!(
                out,
                "colour: built-in scenes at {cols}x{rows_}, textured, {} steps in, against their truecolor frame in 2x2-pixel blends (hue lost: coloured blocks shown grey; OKLab distance x100; added speckle: pixels' distance from their block's blend beyond the truecolor frame's)",
                colour::FIDELITY_STEPS
            )?;
            let mut table = Table::new(&[
                "scene",
                "colours",
                "dither",
                "hue lost",
                "mean OKLab error",
                "95th percentile",
                "added speckle",
            ]);
            for r in &rows {
                table.push(vec![
                    r.scene.clone(),
                    r.colors.name().to_string(),
                    r.dither.name().to_string(),
                    format!("{:.1}%", r.fidelity.hue_lost * 100.0),
                    format!("{:.2}", r.fidelity.mean_de),
                    format!("{:.2}", r.fidelity.p95_de),
                    format!("{:.2}", r.fidelity.speckle),
                ]);
            }
            table.write(out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Physics) {
        let report = physics::run(quick);
        if json {
            sections.push(format!("\"physics\":{}", physics::to_json(&report)));
        } else {
            physics::print_table(&report, out)?;
            writeln!(out)?;
        }
    }
    if matches!(which, Which::All | Which::Rewind) {
        let rows = rewind::run(quick);
        if json {
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"scene\":{},\"bodies\":{},\"steps\":{},\"bytes\":{},\"keyframes\":{},\"seconds\":{},\"us_per_step\":{},\"us_per_keyframe\":{},\"rewind_1s_ms\":{}}}",
                        json_string(&r.scene),
                        r.bodies,
                        r.steps,
                        r.bytes,
                        r.keyframes,
                        json_number(f64::from(r.seconds)),
                        json_number(r.us_per_step),
                        json_number(r.us_per_keyframe),
                        json_number(r.rewind_1s_ms)
                    )
                })
                .collect();
            sections.push(format!("\"rewind\":[{}]", items.join(",")));
        } else {
            writeln!(
                out,
                "rewind: the timeline's keyframes (one every {} steps) over the run; cost per step is the keyframes' time spread over every step",
                crate::app::timeline::KEYFRAME_STEPS
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
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"scene\":{},\"colors\":{},\"dither\":{},\"cols\":{},\"rows\":{},\"frame_ms\":{},\"bytes_per_frame\":{},\"bytes_per_second_at_30fps\":{},\"peak_bytes_per_second\":{},\"held_frames\":{},\"frames\":{}}}",
                        json_string(&r.scene),
                        json_string(r.colors.name()),
                        json_string(r.dither.name()),
                        r.cols,
                        r.rows,
                        json_number(r.frame_ms),
                        json_number(r.bytes_per_frame),
                        json_number(r.bytes_per_second_at_30fps),
                        r.peak_bytes_per_second,
                        r.held_frames,
                        r.frames
                    )
                })
                .collect();
            sections.push(format!(
                "\"app\":{{\"frames\":[{}],\"picking\":{{\"bodies\":{},\"us_per_pick\":{},\"hit_fraction\":{}}}}}",
                items.join(","),
                pick.bodies,
                json_number(pick.us_per_pick),
                json_number(pick.hit_fraction)
            ));
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
                    if r.colors == ColorDepth::TrueColor {
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
    }
    if json {
        writeln!(out, "{{{}}}", sections.join(","))?;
    }
    Ok(())
}
