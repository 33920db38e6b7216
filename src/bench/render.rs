//! Rasterizer benchmark: the 210-box pyramid in a 200 × 100 frame, every render mode, alone and with
//! the half-block mapping into a 200 × 50 cell buffer; and scenes of balls (which are ray cast, not
//! rasterized: `render::sphere`), textured, plain and supersampled.

use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use crate::app::panels::look::{self, BodyLook};
use crate::geometry::Viewport;
use crate::render::{Frame, RenderMode, RenderOptions, Renderer};
use crate::scene::cases;
use crate::term::{ColorDepth, HalfBlocks};
use crate::util::median;

/// Width and height of the benchmark frame, pixels (square pixels).
pub const BENCH_SIZE: (u32, u32) = (200, 100);

/// Timing of one render mode.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct RenderBenchRow {
    /// In JSON by its name (`RenderMode::name`).
    #[serde(serialize_with = "mode_name")]
    pub mode: RenderMode,
    /// Median wall time of one `Renderer::render`, milliseconds.
    pub render_ms: f64,
    /// Median wall time of rendering plus mapping the frame to half-block cells (truecolor), ms.
    pub render_and_map_ms: f64,
    /// The same with the mapping at 256 colours, dithered (what an ssh session gets), ms.
    pub render_and_map_256_ms: f64,
}

fn mode_name<S: serde::Serializer>(mode: &RenderMode, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(mode.name())
}

/// Renders `pyramid(20)` `frames` times per mode (after a few warm-up frames) with shadows on and no
/// supersampling, and returns one row per mode in [`RenderMode::ALL`] order. The drawables come from
/// the same conversion the app uses.
pub fn bench_render(frames: usize) -> Vec<RenderBenchRow> {
    let scene = cases::pyramid(20);
    let world = scene.build_world();
    let mut drawables = Vec::new();
    look::drawables(&world, &BodyLook::of_scene(&scene), None, &mut drawables);
    let (width, height) = BENCH_SIZE;
    let viewport = Viewport::new(width, height, 1.0);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(width, height);
    let area = Rect::new(0, 0, width as u16, (height / 2) as u16);
    let mut buffer = Buffer::empty(area);
    let frames = frames.max(1);
    RenderMode::ALL
        .iter()
        .map(|&mode| {
            let options = RenderOptions {
                mode,
                ..RenderOptions::default()
            };
            for _ in 0..3 {
                renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
            }
            let mut render_ms = Vec::with_capacity(frames);
            let mut total_ms = Vec::with_capacity(frames);
            let mut total_256_ms = Vec::with_capacity(frames);
            // Warm the 256-colour plan memo, as a running app has.
            HalfBlocks::new(frame.pixels(), width, height, ColorDepth::Ansi256)
                .render(area, &mut buffer);
            for _ in 0..frames {
                let start = Instant::now();
                renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
                let rendered = start.elapsed().as_secs_f64() * 1e3;
                render_ms.push(rendered);
                HalfBlocks::new(frame.pixels(), width, height, ColorDepth::TrueColor)
                    .render(area, &mut buffer);
                total_ms.push(start.elapsed().as_secs_f64() * 1e3);
                let start_256 = Instant::now();
                HalfBlocks::new(frame.pixels(), width, height, ColorDepth::Ansi256)
                    .render(area, &mut buffer);
                total_256_ms.push(rendered + start_256.elapsed().as_secs_f64() * 1e3);
            }
            RenderBenchRow {
                mode,
                render_ms: median(&mut render_ms),
                render_and_map_ms: median(&mut total_ms),
                render_and_map_256_ms: median(&mut total_256_ms),
            }
        })
        .collect()
}

/// Timing of one scene of balls.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct BallsBenchRow {
    pub scene: String,
    /// Balls in the scene.
    pub balls: usize,
    /// Median wall time of one textured `Renderer::render` without supersampling, ms.
    pub render_ms: f64,
    /// The same, supersampled (2 × 2 samples a pixel and a 1× id pass), ms.
    pub supersampled_ms: f64,
}

/// Scenes of balls, settled as the tests and the app see them: the default scene (two balls, large
/// in its picture) after 300 steps, and `rain(1000)` (500 balls, small) after 90, each rendered
/// `frames` times textured with shadows, plain and supersampled, in a 200 × 100 frame through the
/// scene's own camera.
pub fn bench_balls(frames: usize) -> Vec<BallsBenchRow> {
    let scenes = [
        (crate::scene::load("default").expect("built in"), 300),
        (cases::rain(1000), 90),
    ];
    let (width, height) = BENCH_SIZE;
    let viewport = Viewport::new(width, height, 1.0);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(width, height);
    scenes
        .into_iter()
        .map(|(scene, steps)| {
            let mut world = scene.build_world();
            for _ in 0..steps {
                world.step();
            }
            let mut drawables = Vec::new();
            look::drawables(&world, &BodyLook::of_scene(&scene), None, &mut drawables);
            let mut time = |supersample: bool| {
                let options = RenderOptions {
                    mode: RenderMode::Textured,
                    supersample,
                    ..RenderOptions::default()
                };
                for _ in 0..3 {
                    renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
                }
                let mut ms: Vec<f64> = (0..frames.max(1))
                    .map(|_| {
                        let start = Instant::now();
                        renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
                        start.elapsed().as_secs_f64() * 1e3
                    })
                    .collect();
                median(&mut ms)
            };
            let (render_ms, supersampled_ms) = (time(false), time(true));
            BallsBenchRow {
                scene: scene.name.clone(),
                balls: drawables
                    .iter()
                    .filter(|d| matches!(d.shape, crate::geometry::Shape::Sphere { .. }))
                    .count(),
                render_ms,
                supersampled_ms,
            }
        })
        .collect()
}

/// The balls section's table, as `nudge bench` prints it.
pub(super) fn print_balls(
    rows: &[BallsBenchRow],
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "balls: scenes of balls (ray cast per pixel), textured with shadows, 200x100 px, median"
    )?;
    let mut table = Table::new(&["scene", "balls", "render ms", "supersampled ms"]);
    for r in rows {
        table.push(vec![
            r.scene.clone(),
            r.balls.to_string(),
            format!("{:.3}", r.render_ms),
            format!("{:.3}", r.supersampled_ms),
        ]);
    }
    table.write(out)
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(
    rows: &[RenderBenchRow],
    frames: usize,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
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
    for r in rows {
        table.push(vec![
            r.mode.name().to_string(),
            format!("{:.3}", r.render_ms),
            format!("{:.3}", r.render_and_map_ms),
            format!("{:.3}", r.render_and_map_256_ms),
        ]);
    }
    table.write(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_of_balls_gets_a_finite_timing() {
        let rows = bench_balls(1);
        assert_eq!(rows.len(), 2);
        assert!(rows.iter().all(|r| r.balls > 0 && r.render_ms.is_finite()));
    }

    #[test]
    fn every_mode_gets_a_finite_timing() {
        let rows = bench_render(1);
        assert_eq!(rows.len(), RenderMode::ALL.len());
        assert!(
            rows.iter()
                .all(|r| r.render_ms.is_finite() && r.render_and_map_ms >= r.render_ms)
        );
    }
}
