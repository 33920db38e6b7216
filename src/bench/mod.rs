//! `nudge bench`: speed beside error. Every number the README claims comes from here.
//!
//! The benchmarks reuse the scenes of the tests and the app (`scene::cases`, the built-ins).

pub mod app;
pub mod hard_case;
pub mod penetration;
pub mod physics;
pub mod poke;
pub mod render;
pub mod table;

use std::io::Write;

/// Which benchmarks to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Which {
    All,
    Render,
    Physics,
    App,
}

impl std::str::FromStr for Which {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "all" => Ok(Which::All),
            "render" => Ok(Which::Render),
            "physics" => Ok(Which::Physics),
            "app" => Ok(Which::App),
            other => Err(format!(
                "unknown benchmark '{other}' (all, render, physics or app)"
            )),
        }
    }
}

/// Runs the chosen benchmarks and prints tables (or JSON) to `out`.
pub fn run(which: Which, json: bool, quick: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let mut sections: Vec<String> = Vec::new();
    if matches!(which, Which::All | Which::Render) {
        let rows = render::bench_render(if quick { 20 } else { 200 });
        if json {
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"mode\":\"{}\",\"render_ms\":{:.4},\"render_and_map_ms\":{:.4}}}",
                        r.mode.name(),
                        r.render_ms,
                        r.render_and_map_ms
                    )
                })
                .collect();
            sections.push(format!("\"render\":[{}]", items.join(",")));
        } else {
            writeln!(
                out,
                "render: 210-box pyramid, 200x100 px (200x50 cells), median of {} frames",
                if quick { 20 } else { 200 }
            )?;
            writeln!(out, "| mode | render ms | render + half-block map ms |")?;
            writeln!(out, "|---|---:|---:|")?;
            for r in &rows {
                writeln!(
                    out,
                    "| {} | {:.3} | {:.3} |",
                    r.mode.name(),
                    r.render_ms,
                    r.render_and_map_ms
                )?;
            }
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
    if matches!(which, Which::All | Which::App) {
        let (rows, pick) = app::run(quick)?;
        if json {
            let items: Vec<String> = rows
                .iter()
                .map(|r| {
                    format!(
                        "{{\"scene\":\"{}\",\"colors\":\"{}\",\"cols\":{},\"rows\":{},\"frame_ms\":{:.4},\"bytes_per_frame\":{:.1},\"bytes_per_second_at_30fps\":{:.1}}}",
                        r.scene, r.colors.name(), r.cols, r.rows, r.frame_ms, r.bytes_per_frame, r.bytes_per_second_at_30fps
                    )
                })
                .collect();
            sections.push(format!(
                "\"app\":{{\"frames\":[{}],\"picking\":{{\"bodies\":{},\"us_per_pick\":{:.3},\"hit_fraction\":{:.3}}}}}",
                items.join(","),
                pick.bodies,
                pick.us_per_pick,
                pick.hit_fraction
            ));
        } else {
            writeln!(
                out,
                "app: end-to-end frame (2 physics steps + render + map + diff); pyramid rows: its bottom row knocked out"
            )?;
            writeln!(
                out,
                "| scene | terminal | colours | frame ms | bytes/frame | bytes/s at 30 fps |"
            )?;
            writeln!(out, "|---|---|---|---:|---:|---:|")?;
            for r in &rows {
                writeln!(
                    out,
                    "| {} | {}x{} | {} | {:.3} | {:.0} | {:.0} |",
                    r.scene,
                    r.cols,
                    r.rows,
                    r.colors.name(),
                    r.frame_ms,
                    r.bytes_per_frame,
                    r.bytes_per_second_at_30fps
                )?;
            }
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
