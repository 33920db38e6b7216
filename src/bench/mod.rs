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
use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use crate::render::{Frame, RenderMode, RenderOptions, Renderer};
use crate::sim::median;
use crate::term::{ColorDepth, HalfBlocks};

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

/// One render-mode row: the rasterizer alone and with the half-block mapping.
#[derive(Clone, Debug)]
pub struct RenderRow {
    pub mode: RenderMode,
    pub render_ms: f64,
    pub render_and_map_ms: f64,
}

/// Median time to render the 210-box pyramid into 200×100 pixels and map it to a 200×50 cell buffer.
pub fn render_rows(frames: usize) -> Vec<RenderRow> {
    let scene = crate::scene::cases::pyramid(20);
    let drawables = render::drawables_from_scene(&scene);
    let (width, height) = render::BENCH_SIZE;
    let viewport = crate::geometry::Viewport::new(width, height, 1.0);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(width, height);
    let area = Rect::new(0, 0, width as u16, (height / 2) as u16);
    let mut buffer = Buffer::empty(area);
    let rasterizer_only = render::bench_render(frames);
    RenderMode::ALL
        .iter()
        .map(|&mode| {
            let options = RenderOptions {
                mode,
                ..RenderOptions::default()
            };
            let mut samples = Vec::with_capacity(frames);
            for _ in 0..frames {
                let start = Instant::now();
                renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
                HalfBlocks::new(frame.pixels(), width, height, ColorDepth::TrueColor)
                    .render(area, &mut buffer);
                samples.push(start.elapsed().as_secs_f64() * 1e3);
            }
            let render_ms = rasterizer_only
                .iter()
                .find(|row| row.mode == mode)
                .map_or(f64::NAN, |row| row.median_ms);
            RenderRow {
                mode,
                render_ms,
                render_and_map_ms: median(&mut samples),
            }
        })
        .collect()
}

/// Runs the chosen benchmarks and prints tables (or JSON) to `out`.
pub fn run(which: Which, json: bool, quick: bool, out: &mut dyn Write) -> anyhow::Result<()> {
    let mut sections: Vec<String> = Vec::new();
    if matches!(which, Which::All | Which::Render) {
        let rows = render_rows(if quick { 20 } else { 200 });
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
                        "{{\"scene\":\"{}\",\"cols\":{},\"rows\":{},\"frame_ms\":{:.4},\"bytes_per_frame\":{:.1},\"bytes_per_second_at_30fps\":{:.1}}}",
                        r.scene, r.cols, r.rows, r.frame_ms, r.bytes_per_frame, r.bytes_per_second_at_30fps
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
                "app: end-to-end frame (2 physics steps + render + map + diff), 256 colours"
            )?;
            writeln!(
                out,
                "| scene | terminal | frame ms | bytes/frame | bytes/s at 30 fps |"
            )?;
            writeln!(out, "|---|---|---:|---:|---:|")?;
            for r in &rows {
                writeln!(
                    out,
                    "| {} | {}x{} | {:.3} | {:.0} | {:.0} |",
                    r.scene,
                    r.cols,
                    r.rows,
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
