//! End-to-end frame cost: physics + render + half-block mapping + ratatui diff + bytes to the terminal,
//! and the cost of one pick.

use std::io;
use std::time::Instant;

use glam::Vec2;
use ratatui::layout::Rect;

use crate::app::input::picking;
use crate::app::run::{Screen, Turn};
use crate::app::{App, AppConfig};
use crate::physics::BodyId;
use crate::scene::{self, Scene, cases};
use crate::term::{CellMode, ColorDepth, Dither};
use crate::util::median;

/// One row of the end-to-end table.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FrameRow {
    pub scene: String,
    /// In JSON by its name (`ColorDepth::name`).
    #[serde(serialize_with = "depth_name")]
    pub colors: ColorDepth,
    /// How the picture was dithered (meaningless in truecolor, which never is).
    #[serde(serialize_with = "dither_name")]
    pub dither: Dither,
    pub cols: u16,
    pub rows: u16,
    /// Median wall time of a whole drawn frame (2 physics steps at 60 Hz + draw), ms.
    pub frame_ms: f64,
    /// Mean bytes written per drawn frame (after the first frame).
    pub bytes_per_frame: f64,
    /// Bytes written over the run (after the first frame) per second at 30 frame slots a second:
    /// the average rate.
    pub bytes_per_second_at_30fps: f64,
    /// The most bytes written in any 30 consecutive frame slots: the worst second at 30 fps.
    pub peak_bytes_per_second: u64,
    /// Frame slots the default byte budget held back (see `app::byte_budget`), of `frames`.
    pub held_frames: usize,
    pub frames: usize,
}

pub(crate) fn dither_name<S: serde::Serializer>(
    dither: &Dither,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(dither.name())
}

pub(crate) fn depth_name<S: serde::Serializer>(
    depth: &ColorDepth,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.serialize_str(depth.name())
}

/// Picking cost over a scene of many bodies.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PickRow {
    pub bodies: usize,
    /// Mean time of one cell → ray → nearest-hit query, µs.
    pub us_per_pick: f64,
    pub hit_fraction: f64,
}

/// One frame slot at 30 fps.
pub(crate) const FRAME_SLOT: std::time::Duration =
    std::time::Duration::from_nanos(1_000_000_000 / 30);

/// Frames measured per configuration.
fn frame_count(quick: bool) -> usize {
    if quick { 30 } else { 180 }
}

/// Measures a scene at a terminal size, `frames` frame slots at 30 fps, through the app's default
/// byte budget as the sandbox runs (a held slot draws nothing; the physics goes on). For the pyramid,
/// the bottom row is shoved on the first frames so the measurement covers the collapse (the worst
/// case for bytes on the wire).
pub fn measure_frames(
    scene: Scene,
    depth: (ColorDepth, Dither),
    cols: u16,
    rows: u16,
    frames: usize,
    collapse: bool,
) -> io::Result<FrameRow> {
    measure_frames_in(scene, depth, CellMode::Half, cols, rows, frames, collapse)
}

/// [`measure_frames`] with the view in `cells`.
pub fn measure_frames_in(
    scene: Scene,
    (colors, dither): (ColorDepth, Dither),
    cells: CellMode,
    cols: u16,
    rows: u16,
    frames: usize,
    collapse: bool,
) -> io::Result<FrameRow> {
    let name = scene.name.clone();
    let config = AppConfig {
        color_depth: colors,
        dither,
        cells,
        ..AppConfig::default()
    };
    let mut app = App::new(scene, config);
    let mut screen = Screen::fixed(io::sink(), Rect::new(0, 0, cols, rows))?;
    app.resize(Rect::new(0, 0, cols, rows));
    screen.present(&mut app)?;
    let mut frame_ms = Vec::with_capacity(frames);
    let mut frame_bytes = Vec::with_capacity(frames);
    let mut held_frames = 0;
    for frame in 0..frames {
        if collapse && frame < 10 {
            shove_bottom_row(&mut app);
        }
        let start = Instant::now();
        app.step_physics();
        app.step_physics();
        app.byte_budget.refill(FRAME_SLOT);
        let turn = screen.present_within_budget(&mut app)?;
        if turn == Turn::Held {
            held_frames += 1;
        } else {
            frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
        }
        frame_bytes.push(turn.bytes());
    }
    let bytes: u64 = frame_bytes.iter().sum();
    let bytes_per_frame = bytes as f64 / (frames - held_frames).max(1) as f64;
    let peak_bytes_per_second = frame_bytes
        .windows(30.min(frame_bytes.len()).max(1))
        .map(|second| second.iter().sum())
        .max()
        .unwrap_or(0);
    Ok(FrameRow {
        scene: name,
        colors,
        dither,
        cols,
        rows,
        frame_ms: median(&mut frame_ms),
        bytes_per_frame,
        bytes_per_second_at_30fps: bytes as f64 * 30.0 / frames.max(1) as f64,
        peak_bytes_per_second,
        held_frames,
        frames,
    })
}

/// Knocks the pyramid's whole bottom row out, alternate boxes forward and back, so that everything
/// above comes down: the worst case for bytes on the wire (the byte-budget test shoves it too).
pub fn shove_bottom_row(app: &mut App) {
    let world = app.world_mut();
    for i in 0..world.len() {
        let id = BodyId(i as u32);
        let body = world.body(id);
        if !body.is_static() && body.pose().position.y < 1.0 {
            let center = body.pose().position;
            let side = if i % 2 == 0 { 1.0 } else { -1.0 };
            world.apply_force_at_point(id, glam::Vec3::new(0.0, 0.0, 3000.0 * side), center);
        }
    }
}

/// Casts `count` rays through pseudo-random pixels of a 200×100 view of `scene`.
pub fn measure_picking(scene: Scene, count: usize) -> PickRow {
    let bodies = scene.bodies.len();
    let mut app = App::new(scene, AppConfig::default());
    app.resize(Rect::new(0, 0, 200, 51));
    let viewport = app.viewport();
    let mut rng = crate::util::SplitMix64(7);
    let pixels: Vec<Vec2> = (0..count)
        .map(|_| Vec2::new(rng.next_unit() * 200.0, rng.next_unit() * 100.0))
        .collect();
    let start = Instant::now();
    let mut hits = 0usize;
    for pixel in &pixels {
        if picking::pick_pixel(app.world(), app.camera(), &viewport, *pixel).is_some() {
            hits += 1;
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    PickRow {
        bodies,
        us_per_pick: elapsed * 1e6 / count.max(1) as f64,
        hit_fraction: hits as f64 / count.max(1) as f64,
    }
}

/// The whole end-to-end benchmark.
pub fn run(quick: bool) -> anyhow::Result<(Vec<FrameRow>, PickRow)> {
    let frames = frame_count(quick);
    let mut rows = Vec::new();
    // 256 colours is what an SSH session gets by default; truecolor is the worst case on the wire.
    let ssh = (ColorDepth::Ansi256, Dither::Ordered);
    for (cols, rows_) in [(120, 40), (200, 50)] {
        let default_scene = scene::load("default")?;
        rows.push(measure_frames(
            default_scene,
            ssh,
            cols,
            rows_,
            frames,
            false,
        )?);
        rows.push(measure_frames(
            cases::pyramid(20),
            ssh,
            cols,
            rows_,
            frames,
            true,
        )?);
    }
    // The collapse at every depth, dithered (the default) and not (the cost of dithering).
    for depth in [
        (ColorDepth::Ansi256, Dither::None),
        (ColorDepth::Ansi16, Dither::Ordered),
        (ColorDepth::Ansi16, Dither::None),
        (ColorDepth::TrueColor, Dither::None),
    ] {
        rows.push(measure_frames(
            cases::pyramid(20),
            depth,
            200,
            50,
            frames,
            true,
        )?);
    }
    let picks = measure_picking(cases::rain(1000), if quick { 200 } else { 2000 });
    Ok((rows, picks))
}

/// The section's tables (frames, then picking), as `nudge bench` prints them.
pub(super) fn print_table(
    rows: &[FrameRow],
    pick: &PickRow,
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
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
    for r in rows {
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
        "picking: {:.2} us per ray cast over {} bodies ({:.0}% of rays hit)",
        pick.us_per_pick,
        pick.bodies,
        pick.hit_fraction * 100.0
    )?;
    Ok(())
}
