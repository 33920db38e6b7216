//! `nudge bench cells`: each cell mode's picture against a finer one, its draw time, and its bytes.
//!
//! **Error.** The same frame (scene, camera, steps, textured, supersampled as the app draws) is
//! rendered once at 4 × 8 pixels a cell in truecolor: the reference. Each mode's cells are decoded
//! through their glyphs' patterns back to pixels and expanded to 4 × 8 a cell (a pattern pixel covers
//! the reference pixels whose centres fall in it; a sextant's thirds get 3, 2 and 3 of the 8 rows),
//! and compared pixel by pixel in OKLab: the mean ΔE ×100 over every pixel, and over edge pixels only
//! (a reference pixel whose 3 × 3 neighbourhood shows another body id: silhouettes, where the finer
//! modes should gain most). The finer modes are measured with each [`FitMethod`].
//!
//! **Time.** The app's draw of a still frame (rasterize + map to cells), median over frames, and the
//! map alone per fit method: what cycling the mode costs. Whole frames (physics, draw, ratatui's diff)
//! and bytes come from [`super::app::measure_frames_in`] through the default byte budget, with the
//! pyramid collapsing (the worst case on the wire), and idle bytes from a settled scene.

use std::io::{self, Write};
use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::app::{FRAME_SLOT, FrameRow, measure_frames_in};
use super::table::Table;
use crate::app::run::{Screen, tick};
use crate::app::{App, AppConfig};
use crate::color::oklab::{Oklab, to_oklab};
use crate::geometry::{CellPixels, Viewport};
use crate::render::{RenderMode, RenderOptions};
use crate::scene::{self, Scene, cases};
use crate::term::fidelity::shown_rgb;
use crate::term::fit::FitMethod;
use crate::term::glyphs::pattern_of;
use crate::term::{CellMode, CellView, ColorDepth, Dither, Mosaic};
use crate::util::median;

/// Terminal sizes measured, cells.
pub const SIZES: [(u16, u16); 2] = [(120, 40), (200, 50)];
/// Pixels a cell of the reference frame.
pub const REFERENCE_CELL: CellPixels = CellPixels { cols: 4, rows: 8 };
/// Physics steps before the measured frame (the colour bench's: bodies have fallen and settled).
pub const STEPS: u64 = 90;

/// One mode's picture error on one scene and size.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ErrorRow {
    pub scene: String,
    pub cols: u16,
    pub rows: u16,
    #[serde(serialize_with = "mode_name")]
    pub cells: CellMode,
    /// `exhaustive` or `axis` (half blocks need no fit: `exhaustive`).
    pub fit: &'static str,
    /// Rendered supersampled (the app supersamples half blocks only).
    pub supersampled: bool,
    /// The mode's frame expanded pixel by pixel, no glyph limit: what its resolution alone allows.
    pub resolution_de: f64,
    /// Mean OKLab ΔE ×100 over every reference pixel.
    pub mean_de: f64,
    /// The same over edge pixels only.
    pub edge_de: f64,
    /// `mean_de` over half blocks' on the same frame.
    pub ratio_to_half: f64,
    /// Median time of mapping the frame to cells, ms.
    pub map_ms: f64,
}

/// One mode's draw time on one scene and size.
#[derive(Clone, Debug, serde::Serialize)]
pub struct DrawRow {
    pub scene: String,
    pub cols: u16,
    pub rows: u16,
    #[serde(serialize_with = "mode_name")]
    pub cells: CellMode,
    /// Median app draw (rasterize + map), ms.
    pub draw_ms: f64,
    /// `draw_ms` over half blocks'.
    pub ratio_to_half: f64,
}

/// One mode's whole frames and bytes, and what a still picture costs.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BytesRow {
    #[serde(serialize_with = "mode_name")]
    pub cells: CellMode,
    #[serde(flatten)]
    pub frames: FrameRow,
    /// Bytes written over 30 frame slots once the default scene has come to rest.
    pub idle_bytes: u64,
}

/// The least error any two-colour octant picture can have on one scene and size.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BoundRow {
    pub scene: String,
    pub cols: u16,
    pub rows: u16,
    /// Mean OKLab ΔE ×100 of the best two-colour octant picture (`octant_bound`).
    pub bound_de: f64,
    /// `bound_de` over half blocks' error on the same frame.
    pub ratio_to_half: f64,
}

/// The whole cells benchmark.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct CellsReport {
    pub errors: Vec<ErrorRow>,
    pub bounds: Vec<BoundRow>,
    pub draws: Vec<DrawRow>,
    pub bytes: Vec<BytesRow>,
}

fn mode_name<S: serde::Serializer>(mode: &CellMode, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(mode.name())
}

/// The scenes measured: the default and the 210-box pyramid.
fn scenes() -> anyhow::Result<Vec<Scene>> {
    Ok(vec![scene::load("default")?, cases::pyramid(20)])
}

/// An app showing `scene` at `cols × rows` in `cells`, `STEPS` in, its frame rendered as the app
/// renders it, or supersampled whatever the mode when `supersample`.
fn app_at_with(scene: &Scene, cells: CellMode, cols: u16, rows: u16, supersample: bool) -> App {
    let mut app = app_at(scene, cells, cols, rows);
    if supersample && !app.view_render_options().supersample {
        let options = RenderOptions {
            supersample: true,
            ..app.view_render_options()
        };
        let viewport = app.viewport();
        app.renderer.render(
            &mut app.frame,
            &viewport,
            &app.camera,
            &app.drawables,
            &options,
        );
    }
    app
}

/// An app showing `scene` at `cols × rows` in `cells`, `STEPS` in, its frame rendered.
fn app_at(scene: &Scene, cells: CellMode, cols: u16, rows: u16) -> App {
    let config = AppConfig {
        cells,
        ..AppConfig::default()
    };
    let mut app = App::new(scene.clone(), config);
    app.render_options.mode = RenderMode::Textured;
    for _ in 0..STEPS {
        app.world.step();
    }
    // One row more for the status bar, as the snapshot lays it out.
    app.resize(Rect::new(0, 0, cols, rows + 1));
    app.render_scene();
    app
}

/// The reference: the app's frame at 4 × 8 pixels a cell (colours, and ids for the edges).
struct Reference {
    lab: Vec<Oklab>,
    edge: Vec<bool>,
    width: usize,
}

fn reference(scene: &Scene, cols: u16, rows: u16) -> Reference {
    let mut app = app_at(scene, CellMode::Half, cols, rows);
    let viewport = Viewport::of_cells(cols, rows, REFERENCE_CELL, app.config.cell_aspect);
    let options = app.render_options;
    app.renderer.render(
        &mut app.frame,
        &viewport,
        &app.camera,
        &app.drawables,
        &options,
    );
    let (w, h) = (viewport.width as usize, viewport.height as usize);
    let ids = app.frame.ids();
    let lab = app.frame.pixels().iter().map(|&c| to_oklab(c)).collect();
    let edge = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            (y.saturating_sub(1)..(y + 2).min(h)).any(|ny| {
                (x.saturating_sub(1)..(x + 2).min(w)).any(|nx| ids[ny * w + nx] != ids[i])
            })
        })
        .collect();
    Reference {
        lab,
        edge,
        width: w,
    }
}

/// Mean ΔE ×100 of `buf` (cells of `mode`) against the reference, over all pixels and edge pixels.
fn error(buf: &Buffer, mode: CellMode, reference: &Reference) -> (f64, f64) {
    let (cw, ch) = mode.pixels_per_cell();
    let (rw, rh) = (REFERENCE_CELL.cols, REFERENCE_CELL.rows);
    let (mut all, mut edges) = ((0.0f64, 0usize), (0.0f64, 0usize));
    for row in 0..buf.area.height {
        for col in 0..buf.area.width {
            let cell = &buf[(col, row)];
            let pattern = pattern_of(mode, cell.symbol()).unwrap_or(0);
            let (fg, bg) = (to_oklab(shown_rgb(cell.fg)), to_oklab(shown_rgb(cell.bg)));
            for y in 0..rh {
                // The pattern row whose band holds this reference row's centre.
                let band = (((2 * y + 1) * ch) / (2 * rh)).min(ch - 1);
                for x in 0..rw {
                    let column = (x * cw) / rw;
                    let shown = if pattern & (1 << (band * cw + column)) != 0 {
                        fg
                    } else {
                        bg
                    };
                    let i = (u32::from(row) * rh + y) as usize * reference.width
                        + (u32::from(col) * rw + x) as usize;
                    let de = f64::from(reference.lab[i].distance(shown)) * 100.0;
                    all = (all.0 + de, all.1 + 1);
                    if reference.edge[i] {
                        edges = (edges.0 + de, edges.1 + 1);
                    }
                }
            }
        }
    }
    (all.0 / all.1.max(1) as f64, edges.0 / edges.1.max(1) as f64)
}

/// Mean ΔE ×100 of `app`'s frame (cells of `mode`) expanded pixel by pixel against the reference.
fn resolution_error(app: &App, mode: CellMode, reference: &Reference) -> f64 {
    let (cw, ch) = mode.pixels_per_cell();
    let (rw, rh) = (REFERENCE_CELL.cols, REFERENCE_CELL.rows);
    let width = app.frame.width() as usize;
    let pixels = app.frame.pixels();
    let mut sum = 0.0f64;
    for (i, &lab) in reference.lab.iter().enumerate() {
        let (x, y) = ((i % reference.width) as u32, (i / reference.width) as u32);
        let fx = (x / rw) * cw + ((x % rw) * cw) / rw;
        let fy = (y / rh) * ch + (((2 * (y % rh) + 1) * ch) / (2 * rh)).min(ch - 1);
        let shown = to_oklab(pixels[fy as usize * width + fx as usize]);
        sum += f64::from(lab.distance(shown)) * 100.0;
    }
    sum / reference.lab.len().max(1) as f64
}

/// Maps `app`'s frame to cells of `mode` by `method`; `repeats` times, returning the buffer and the
/// median time.
fn map(app: &App, mode: CellMode, method: FitMethod, repeats: usize) -> (Buffer, f64) {
    let (cols, rows) = (app.viewport_area().width, app.viewport_area().height);
    let mut buf = Buffer::empty(Rect::new(0, 0, cols, rows));
    let frame = &app.frame;
    let mut times = Vec::with_capacity(repeats);
    for _ in 0..repeats.max(1) {
        let start = Instant::now();
        if mode == CellMode::Half {
            CellView {
                pixels: frame.pixels(),
                width: frame.width(),
                height: frame.height(),
                mode,
                depth: ColorDepth::TrueColor,
                dither: Dither::None,
            }
            .render(buf.area, &mut buf);
        } else {
            Mosaic::new(
                frame.pixels(),
                frame.width(),
                frame.height(),
                mode,
                ColorDepth::TrueColor,
            )
            .with_method(method)
            .render(buf.area, &mut buf);
        }
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    (buf, median(&mut times))
}

/// Error rows: every scene, size, mode and (for the finer modes) fit method.
pub fn errors(repeats: usize) -> anyhow::Result<(Vec<ErrorRow>, Vec<BoundRow>)> {
    let mut rows = Vec::new();
    let mut bounds = Vec::new();
    for scene in scenes()? {
        for (cols, rows_) in SIZES {
            super::progress!("bench cells: {} {cols}x{rows_}   \r", scene.name);
            let reference = reference(&scene, cols, rows_);
            let mut half_de = f64::NAN;
            for mode in CellMode::ALL {
                // As the app draws it, with each fit; then a finer mode supersampled too.
                let mut runs = vec![(false, FitMethod::for_mode(mode))];
                if mode != CellMode::Half {
                    runs.extend(
                        FitMethod::ALL
                            .into_iter()
                            .filter(|&m| m != FitMethod::for_mode(mode))
                            .map(|m| (false, m)),
                    );
                    runs.push((true, FitMethod::for_mode(mode)));
                }
                for (supersample, method) in runs {
                    let app = app_at_with(&scene, mode, cols, rows_, supersample);
                    let (buf, map_ms) = map(&app, mode, method, repeats);
                    let (mean_de, edge_de) = error(&buf, mode, &reference);
                    if mode == CellMode::Half {
                        half_de = mean_de;
                    }
                    rows.push(ErrorRow {
                        scene: scene.name.clone(),
                        cols,
                        rows: rows_,
                        cells: mode,
                        fit: method.name(),
                        supersampled: app.view_render_options().supersample || supersample,
                        resolution_de: resolution_error(&app, mode, &reference),
                        mean_de,
                        edge_de,
                        ratio_to_half: mean_de / half_de,
                        map_ms,
                    });
                }
            }
            let bound_de = octant_bound(&reference, cols, rows_);
            bounds.push(BoundRow {
                scene: scene.name.clone(),
                cols,
                rows: rows_,
                bound_de,
                ratio_to_half: bound_de / half_de,
            });
        }
    }
    Ok((rows, bounds))
}

/// The least mean ΔE ×100 against the reference that any two-colour octant picture can have: per
/// cell, every split of its eight octant pixels into two sets, each set's colour the geometric
/// median (Weiszfeld's iteration) of the reference pixels it covers, which is the colour that
/// minimises their summed OKLab distance. No fitter, whatever it sees of the scene, does better:
/// the floor under the octant rows of the error table.
fn octant_bound(reference: &Reference, cols: u16, rows: u16) -> f64 {
    let (rw, rh) = (REFERENCE_CELL.cols as usize, REFERENCE_CELL.rows as usize);
    let (cw, ch) = CellMode::Octant.pixels_per_cell();
    let (bw, bh) = (rw / cw as usize, rh / ch as usize);
    let per_pixel = bw * bh;
    let mut total = 0.0f64;
    let mut side = Vec::with_capacity(rw * rh);
    for row in 0..usize::from(rows) {
        for col in 0..usize::from(cols) {
            // The cell's reference pixels, grouped by the octant pixel that covers them.
            let pixel = |k: usize, j: usize| {
                let (x, y) = (k % cw as usize * bw + j % bw, k / cw as usize * bh + j / bw);
                reference.lab[(row * rh + y) * reference.width + col * rw + x]
            };
            let mut best = f64::MAX;
            // A pattern and its complement are the same split: the last pixel always in the second set.
            let octants = (cw * ch) as usize;
            for pattern in 0u32..1 << (octants - 1) {
                let mut cost = 0.0;
                for in_first in [true, false] {
                    side.clear();
                    for k in (0..octants).filter(|&k| (pattern & (1 << k) != 0) == in_first) {
                        side.extend((0..per_pixel).map(|j| pixel(k, j)));
                    }
                    cost += median_distance(&side);
                }
                best = best.min(cost);
            }
            total += best;
        }
    }
    total / reference.lab.len().max(1) as f64
}

/// The summed distance ×100 of `points` from their geometric median (Weiszfeld's iteration from
/// the mean; 0 for none).
fn median_distance(points: &[Oklab]) -> f64 {
    if points.is_empty() {
        return 0.0;
    }
    let inv_n = 1.0 / points.len() as f32;
    let mut c = points.iter().fold(Oklab::default(), |m, p| Oklab {
        l: m.l + p.l * inv_n,
        a: m.a + p.a * inv_n,
        b: m.b + p.b * inv_n,
    });
    for _ in 0..16 {
        let (mut num, mut den) = (Oklab::default(), 0.0f32);
        for p in points {
            let w = 1.0 / p.distance(c).max(1e-7);
            num = Oklab {
                l: num.l + p.l * w,
                a: num.a + p.a * w,
                b: num.b + p.b * w,
            };
            den += w;
        }
        c = Oklab {
            l: num.l / den,
            a: num.a / den,
            b: num.b / den,
        };
    }
    points
        .iter()
        .map(|p| f64::from(p.distance(c)) * 100.0)
        .sum()
}

/// Draw rows: the app's draw of a still frame (rasterize + map), every scene, size and mode. The
/// modes take turns frame by frame, so that a change in the machine's load falls on all of them.
pub fn draws(frames: usize) -> anyhow::Result<Vec<DrawRow>> {
    let mut rows = Vec::new();
    for scene in scenes()? {
        for (cols, rows_) in SIZES {
            let area = Rect::new(0, 0, cols, rows_ + 1);
            let mut apps: Vec<(App, Buffer, Vec<f64>)> = CellMode::ALL
                .iter()
                .map(|&mode| {
                    let app = app_at(&scene, mode, cols, rows_);
                    (app, Buffer::empty(area), Vec::with_capacity(frames))
                })
                .collect();
            for _ in 0..frames.max(1) {
                for (app, buf, times) in &mut apps {
                    let start = Instant::now();
                    app.draw(area, buf);
                    times.push(start.elapsed().as_secs_f64() * 1e3);
                }
            }
            let medians: Vec<f64> = apps.iter_mut().map(|(_, _, t)| median(t)).collect();
            for (&mode, &draw_ms) in CellMode::ALL.iter().zip(&medians) {
                rows.push(DrawRow {
                    scene: scene.name.clone(),
                    cols,
                    rows: rows_,
                    cells: mode,
                    draw_ms,
                    ratio_to_half: draw_ms / medians[0],
                });
            }
        }
    }
    Ok(rows)
}

/// Bytes written over 30 frame slots (30 fps, through the app's own tick) by the default scene at
/// 200 × 50 in `cells` once it has come to rest, after its first frame.
pub fn idle_bytes(cells: CellMode) -> anyhow::Result<u64> {
    let config = AppConfig {
        cells,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load("default")?, config);
    let area = Rect::new(0, 0, 200, 50);
    let mut screen = Screen::fixed(io::sink(), area)?;
    app.resize(area);
    for _ in 0..1200 {
        if app.world().awake_count() == 0 {
            break;
        }
        app.step_physics();
    }
    screen.present(&mut app)?;
    let mut bytes = 0;
    for _ in 0..30 {
        bytes += tick(&mut app, &mut screen, FRAME_SLOT)?.bytes();
    }
    Ok(bytes)
}

/// Byte rows: the pyramid collapsing at 200 × 50 in every mode, truecolor and 256 colours.
pub fn bytes(frames: usize) -> anyhow::Result<Vec<BytesRow>> {
    let mut rows = Vec::new();
    for depth in [
        (ColorDepth::TrueColor, Dither::None),
        (ColorDepth::Ansi256, Dither::Ordered),
    ] {
        for cells in CellMode::ALL {
            super::progress!("bench cells: bytes {} {}   \r", cells, depth.0.name());
            let frames =
                measure_frames_in(cases::pyramid(20), depth, cells, 200, 50, frames, true)?;
            rows.push(BytesRow {
                cells,
                frames,
                idle_bytes: idle_bytes(cells)?,
            });
        }
    }
    Ok(rows)
}

/// The whole benchmark (`quick`: fewer repetitions).
pub fn run(quick: bool) -> anyhow::Result<CellsReport> {
    let repeats = if quick { 3 } else { 15 };
    let (errors, bounds) = errors(repeats)?;
    Ok(CellsReport {
        errors,
        bounds,
        draws: draws(if quick { 10 } else { 60 })?,
        bytes: bytes(if quick { 30 } else { 180 })?,
    })
}

/// The report as tables, with the summary line the README quotes.
pub fn write_tables(report: &CellsReport, out: &mut dyn Write) -> anyhow::Result<()> {
    writeln!(
        out,
        "cells: each mode against the frame at 4x8 pixels a cell (truecolor), textured, {STEPS} steps in; OKLab distance x100 per pixel, and over edge pixels (silhouettes); pixels alone: the mode's frame without the two-colour limit"
    )?;
    let mut table = Table::new(&[
        "scene",
        "size",
        "cells",
        "fit",
        "supersampled",
        "mean error",
        "on edges",
        "vs half",
        "pixels alone",
        "map ms",
    ]);
    for r in &report.errors {
        table.push(vec![
            r.scene.clone(),
            format!("{}x{}", r.cols, r.rows),
            r.cells.name().to_string(),
            r.fit.to_string(),
            if r.supersampled { "yes" } else { "no" }.to_string(),
            format!("{:.3}", r.mean_de),
            format!("{:.2}", r.edge_de),
            format!("{:.2}x", r.ratio_to_half),
            format!("{:.3}", r.resolution_de),
            format!("{:.3}", r.map_ms),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    writeln!(
        out,
        "cells: the least error any two-colour octant picture can have (per cell the best split of its 8 pixels, each side the geometric median of the reference pixels it covers)"
    )?;
    let mut table = Table::new(&["scene", "size", "least octant error", "vs half"]);
    for r in &report.bounds {
        table.push(vec![
            r.scene.clone(),
            format!("{}x{}", r.cols, r.rows),
            format!("{:.3}", r.bound_de),
            format!("{:.2}x", r.ratio_to_half),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    writeln!(
        out,
        "cells: the app's draw of a still frame (rasterize + map to cells), median ms (the issue asks at most 1.5x half's at 200x50)"
    )?;
    let mut table = Table::new(&["scene", "size", "cells", "draw ms", "vs half"]);
    for r in &report.draws {
        table.push(vec![
            r.scene.clone(),
            format!("{}x{}", r.cols, r.rows),
            r.cells.name().to_string(),
            format!("{:.3}", r.draw_ms),
            format!("{:.2}x", r.ratio_to_half),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    writeln!(
        out,
        "cells: the pyramid collapsing at 200x50 through the default byte budget (1 MB/s), and the default scene at rest"
    )?;
    let mut table = Table::new(&[
        "cells",
        "colours",
        "frame ms",
        "bytes/frame",
        "worst second",
        "held",
        "idle bytes",
    ]);
    for r in &report.bytes {
        table.push(vec![
            r.cells.name().to_string(),
            r.frames.colors.name().to_string(),
            format!("{:.2}", r.frames.frame_ms),
            format!("{:.0}", r.frames.bytes_per_frame),
            r.frames.peak_bytes_per_second.to_string(),
            format!("{}/{}", r.frames.held_frames, r.frames.frames),
            r.idle_bytes.to_string(),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    let ratio = |scene: &str| {
        report
            .errors
            .iter()
            .find(|r| {
                r.scene == scene
                    && (r.cols, r.rows) == SIZES[0]
                    && r.cells == CellMode::Octant
                    && r.fit == FitMethod::for_mode(CellMode::Octant).name()
                    && !r.supersampled
            })
            .map_or(f64::NAN, |r| r.ratio_to_half)
    };
    let draw = report
        .draws
        .iter()
        .filter(|r| (r.cols, r.rows) == SIZES[1] && r.cells == CellMode::Octant)
        .map(|r| r.ratio_to_half)
        .fold(f64::NAN, f64::max);
    let floor = |scene: &str| {
        report
            .bounds
            .iter()
            .find(|r| r.scene == scene && (r.cols, r.rows) == SIZES[0])
            .map_or(f64::NAN, |r| r.ratio_to_half)
    };
    let pyramid = cases::pyramid(20).name;
    writeln!(
        out,
        "summary: octant's error {:.2}x half's (default), {:.2}x (pyramid) at 120x40, where no two-colour octant picture can do better than {:.2}x and {:.2}x; its draw at 200x50 at most {:.2}x half's",
        ratio("default"),
        ratio(&pyramid),
        floor("default"),
        floor(&pyramid),
        draw
    )?;
    writeln!(out)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_distance_is_that_of_the_geometric_median() {
        let lab = |l: f32, a: f32| Oklab { l, a, b: 0.0 };
        // A square's corners: the median is its centre, √½ from each (×100).
        let square = [lab(0.0, 0.0), lab(1.0, 0.0), lab(1.0, 1.0), lab(0.0, 1.0)];
        let expected = 4.0 * 0.5f64.sqrt() * 100.0;
        assert!((median_distance(&square) - expected).abs() < 1e-3);
        // Three points on a line, one far: the median is the middle one, not the mean.
        let line = [lab(0.0, 0.0), lab(1.0, 0.0), lab(10.0, 0.0)];
        assert!(
            (median_distance(&line) - 1000.0).abs() < 1.0,
            "{}",
            median_distance(&line)
        );
        assert_eq!(median_distance(&[]), 0.0);
    }

    #[test]
    fn octant_shows_the_default_scene_and_the_pyramid_closer_to_the_fine_frame_than_half_blocks() {
        for scene in [scene::load("default").unwrap(), cases::pyramid(20)] {
            let reference = reference(&scene, 60, 20);
            let de = |mode| {
                let app = app_at(&scene, mode, 60, 20);
                let (buf, _) = map(&app, mode, FitMethod::for_mode(mode), 1);
                error(&buf, mode, &reference)
            };
            let (half, half_edges) = de(CellMode::Half);
            let (octant, octant_edges) = de(CellMode::Octant);
            // Measured at 60 × 20: octant 0.70× half's on the default scene, 0.71× on the pyramid
            // (0.60× and 0.71× at 120 × 40, where the issue asks 0.6×). Allowed: a third of the gap
            // to parity given back.
            assert!(
                octant < 0.9 * half && octant_edges < half_edges,
                "{}: {octant} vs {half}",
                scene.name
            );
            // Half blocks have a sixteenth of the reference's pixels: the measure is not blind to that.
            assert!(half > 0.5, "{half}");
        }
    }
}
