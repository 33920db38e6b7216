//! Rasterizer benchmark: the 210-box pyramid in a 200 × 100 frame, every render mode.

use std::time::Instant;

use crate::geometry::{Shape, Viewport};
use crate::render::{Drawable, Frame, Material, RenderMode, RenderOptions, Renderer};
use crate::scene::Scene;
use crate::scene::cases;

/// Width and height of the benchmark frame, pixels (square pixels).
pub const BENCH_SIZE: (u32, u32) = (200, 100);

/// Timing of one render mode.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderBenchRow {
    pub mode: RenderMode,
    /// Median wall time of one `Renderer::render`, milliseconds.
    pub median_ms: f64,
    /// Mean wall time, milliseconds.
    pub mean_ms: f64,
}

/// The scene's bodies as drawables, id = body index: dynamic boxes in wood, static bodies in checker
/// (they receive shadows and cast none), spheres plain.
pub fn drawables_from_scene(scene: &Scene) -> Vec<Drawable> {
    scene
        .bodies
        .iter()
        .enumerate()
        .map(|(i, body)| {
            let fixed = body.desc.is_static;
            let mut d = Drawable::new(body.desc.shape, body.desc.pose, body.color, i as u32);
            d.material = match (fixed, body.desc.shape) {
                (true, _) => Material::Checker,
                (false, Shape::Cuboid { .. }) => Material::Wood,
                (false, Shape::Sphere { .. }) => Material::Plain,
            };
            d.casts_shadow = !fixed;
            d.receives_shadow = fixed;
            d
        })
        .collect()
}

/// Renders `pyramid(20)` `frames` times per mode (after a few warm-up frames) with shadows on and no
/// supersampling, and returns one row per mode in [`RenderMode::ALL`] order.
pub fn bench_render(frames: usize) -> Vec<RenderBenchRow> {
    let scene = cases::pyramid(20);
    let drawables = drawables_from_scene(&scene);
    let viewport = Viewport::new(BENCH_SIZE.0, BENCH_SIZE.1, 1.0);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(viewport.width, viewport.height);
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
            let mut times: Vec<f64> = (0..frames)
                .map(|_| {
                    let start = Instant::now();
                    renderer.render(&mut frame, &viewport, &scene.camera, &drawables, &options);
                    start.elapsed().as_secs_f64() * 1e3
                })
                .collect();
            times.sort_by(f64::total_cmp);
            RenderBenchRow {
                mode,
                median_ms: times[times.len() / 2],
                mean_ms: times.iter().sum::<f64>() / times.len() as f64,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_drawables_are_wood_boxes_on_a_checker_floor() {
        let drawables = drawables_from_scene(&cases::pyramid(3));
        assert_eq!(drawables.len(), 7);
        assert_eq!(drawables[0].material, Material::Checker);
        assert!(drawables[0].receives_shadow && !drawables[0].casts_shadow);
        assert!(
            drawables[1..]
                .iter()
                .all(|d| d.material == Material::Wood && d.casts_shadow)
        );
        assert!(drawables.iter().enumerate().all(|(i, d)| d.id == i as u32));
    }
}
