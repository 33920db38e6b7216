//! Colour fidelity at 256 and 16 colours: every built-in scene as `nudge snapshot` draws it (120×40
//! cells, textured, 90 steps in), measured against its truecolor frame with
//! [`term::fidelity`](crate::term::fidelity), dithered and not.

use crossterm::event::{KeyCode, MouseButton, MouseEventKind};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::hands;
use crate::app::panels::overlays::{OverlayKind, OverlaySet};
use crate::app::snapshot::{SnapshotOptions, render_buffer};
use crate::color::Rgb;
use crate::physics::BodyId;
use crate::render::RenderMode;
use crate::scene::{self, Scene};
use crate::term::fidelity::{Fidelity, MarkFidelity, fidelity, mark_fidelity};
use crate::term::{ColorDepth, Dither, HalfBlocks};

/// Terminal size of the fidelity frames, cells.
pub const FIDELITY_SIZE: (u16, u16) = (120, 40);
/// Physics steps before the frame is drawn.
pub const FIDELITY_STEPS: u64 = 90;

/// The error of one scene at one depth and dither mode.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FidelityRow {
    pub scene: String,
    #[serde(serialize_with = "super::app::depth_name")]
    pub colors: ColorDepth,
    #[serde(serialize_with = "super::app::dither_name")]
    pub dither: Dither,
    #[serde(flatten)]
    pub fidelity: Fidelity,
}

/// The snapshot options of the fidelity frames at `colors` and `dither`.
pub fn fidelity_options(colors: ColorDepth, dither: Dither) -> SnapshotOptions {
    let (cols, rows) = FIDELITY_SIZE;
    SnapshotOptions {
        cols,
        rows,
        mode: RenderMode::Textured,
        orthographic: None,
        color_depth: colors,
        dither,
        plain: false,
        steps: FIDELITY_STEPS,
        cell_aspect: 2.0,
        overlays: Default::default(),
        cells: Default::default(),
    }
}

/// `scene` at `colors` with and without dithering, each against its truecolor frame.
pub fn scene_fidelity(scene: &Scene, colors: ColorDepth) -> [(Dither, Fidelity); 2] {
    scene_fidelity_with(scene, colors, OverlaySet::default())
}

/// [`scene_fidelity`] with `overlays` drawn over the scene (in every frame, the reference too).
pub fn scene_fidelity_with(
    scene: &Scene,
    colors: ColorDepth,
    overlays: OverlaySet,
) -> [(Dither, Fidelity); 2] {
    let options = |colors, dither| SnapshotOptions {
        overlays,
        ..fidelity_options(colors, dither)
    };
    let (_, reference) =
        render_buffer(scene.clone(), &options(ColorDepth::TrueColor, Dither::None));
    Dither::ALL.map(|dither| {
        let (_, frame) = render_buffer(scene.clone(), &options(colors, dither));
        (dither, fidelity(&reference, &frame))
    })
}

/// Every built-in scene at 256 and 16 colours, dithered (the default) and not; then the default
/// scene with every overlay on (marks and the island and sleep tints).
pub fn run() -> anyhow::Result<Vec<FidelityRow>> {
    let mut frames: Vec<(String, Scene, OverlaySet)> = Vec::new();
    for (name, _) in scene::builtin_scenes() {
        frames.push((
            (*name).to_string(),
            scene::load(name)?,
            OverlaySet::default(),
        ));
    }
    frames.push((
        "default --overlay all".to_string(),
        scene::load("default")?,
        OverlaySet::ALL,
    ));
    let mut rows = Vec::new();
    for (name, scene, overlays) in &frames {
        for colors in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            for (dither, fidelity) in scene_fidelity_with(scene, colors, *overlays) {
                rows.push(FidelityRow {
                    scene: name.clone(),
                    colors,
                    dither,
                    fidelity,
                });
            }
        }
    }
    Ok(rows)
}

/// The marks a frame carries beside the scene: the debug overlays that draw lines and dots (the
/// tints are measured as pictures, in [`run`]), or the tether of a grab.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marks {
    Overlays,
    Tether,
}

impl Marks {
    pub const ALL: [Marks; 2] = [Marks::Overlays, Marks::Tether];

    pub fn name(self) -> &'static str {
        match self {
            Marks::Overlays => "overlay marks",
            Marks::Tether => "grab tether",
        }
    }
}

/// How one kind of mark reads at one depth and dither mode.
#[derive(Clone, Debug, serde::Serialize)]
pub struct MarkRow {
    pub marks: &'static str,
    #[serde(serialize_with = "super::app::depth_name")]
    pub colors: ColorDepth,
    #[serde(serialize_with = "super::app::dither_name")]
    pub dither: Dither,
    #[serde(flatten)]
    pub fidelity: MarkFidelity,
}

/// The overlays that draw marks (every one but the tints).
pub fn mark_overlays() -> OverlaySet {
    let mut set = OverlaySet::default();
    for kind in OverlayKind::ALL {
        if !matches!(kind, OverlayKind::Islands | OverlayKind::Sleep) {
            set.insert(kind);
        }
    }
    set
}

/// The default scene's frame, as truecolor pixels, without and with `marks`, and its width:
/// the overlays as `nudge snapshot --overlay` draws them (120×40, 90 steps in), or a box held by
/// the grab hand and pulled up and to the side, as the sandbox draws it.
pub fn marked_frames(marks: Marks) -> (Vec<Rgb>, Vec<Rgb>, usize) {
    let scene = scene::load("default").expect("built in");
    match marks {
        Marks::Overlays => {
            let options = fidelity_options(ColorDepth::TrueColor, Dither::None);
            let (plain, _) = render_buffer(scene.clone(), &options);
            let marked_options = SnapshotOptions {
                overlays: mark_overlays(),
                ..options
            };
            let (marked, _) = render_buffer(scene, &marked_options);
            let width = marked.frame().width() as usize;
            (
                plain.frame().pixels().to_vec(),
                marked.frame().pixels().to_vec(),
                width,
            )
        }
        Marks::Tether => {
            let mut app = hands::app_for(scene, false);
            hands::settle(&mut app);
            app.handle_event(&hands::key(KeyCode::Char('h')));
            let held = BodyId(1);
            let cell = hands::cell_of(&app, app.world().body(held).pose().position);
            app.handle_event(&hands::mouse(MouseEventKind::Down(MouseButton::Left), cell));
            // Pulled up and to the side, one step later: the body has not caught up yet, so the
            // line shows beside the marker.
            let to = (cell.0 + 12, cell.1.saturating_sub(6));
            app.handle_event(&hands::mouse(MouseEventKind::Drag(MouseButton::Left), to));
            app.step_physics();
            app.render_scene();
            let marked = app.frame().pixels().to_vec();
            app.handle_event(&hands::mouse(MouseEventKind::Up(MouseButton::Left), to));
            app.render_scene();
            let width = app.frame().width() as usize;
            (app.frame().pixels().to_vec(), marked, width)
        }
    }
}

/// `marks` at `colors` with `dither`, pixel by pixel against the colours they were drawn in.
pub fn mark_fidelity_at(marks: Marks, colors: ColorDepth, dither: Dither) -> MarkFidelity {
    let (plain, marked, width) = marked_frames(marks);
    let height = marked.len() / width.max(1);
    let area = Rect::new(0, 0, width as u16, height.div_ceil(2) as u16);
    let show = |pixels: &[Rgb]| {
        let mut buf = Buffer::empty(area);
        HalfBlocks::new(pixels, width as u32, height as u32, colors)
            .with_dither(dither)
            .render(area, &mut buf);
        buf
    };
    mark_fidelity(&plain, &marked, width, &show(&marked), &show(&plain))
}

/// Both kinds of marks at 256 and 16 colours, dithered and not.
pub fn mark_rows() -> Vec<MarkRow> {
    let mut rows = Vec::new();
    for marks in Marks::ALL {
        for colors in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            for dither in Dither::ALL {
                rows.push(MarkRow {
                    marks: marks.name(),
                    colors,
                    dither,
                    fidelity: mark_fidelity_at(marks, colors, dither),
                });
            }
        }
    }
    rows
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(
    rows: &[FidelityRow],
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
    let (cols, rows_) = FIDELITY_SIZE;
    writeln!(
        out,
        "colour: built-in scenes at {cols}x{rows_}, textured, {} steps in, against their truecolor frame in 2x2-pixel blends (hue lost: coloured blocks shown grey; OKLab distance x100; added speckle: pixels' distance from their block's blend beyond the truecolor frame's; speckled: blocks where that exceeds 4)",
        FIDELITY_STEPS
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
    for r in rows {
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
    table.write(out)
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_marks(marks: &[MarkRow], out: &mut dyn std::io::Write) -> std::io::Result<()> {
    use super::table::Table;
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
    for r in marks {
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
    table.write(out)
}
