//! `nudge snapshot`: one frame of a scene, printed as ANSI text or plain characters.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::Widget;

use super::{App, AppConfig};
use crate::render::RenderMode;
use crate::scene::Scene;
use crate::term::{CellMode, CellView, ColorDepth, Dither};

/// What to draw.
#[derive(Clone, Debug)]
pub struct SnapshotOptions {
    pub cols: u16,
    pub rows: u16,
    pub mode: RenderMode,
    /// `Some(true)` forces orthographic, `Some(false)` perspective, `None` keeps the scene's.
    pub orthographic: Option<bool>,
    pub color_depth: ColorDepth,
    /// How colours the palette lacks are shown (ignored in truecolor).
    pub dither: Dither,
    pub plain: bool,
    /// Physics steps to run before drawing.
    pub steps: u64,
    pub cell_aspect: f32,
    /// Debug overlays drawn over the scene.
    pub overlays: super::panels::overlays::OverlaySet,
    /// How many pixels a cell shows, and with which glyphs.
    pub cells: CellMode,
}

/// Renders the scene's view (no status bar) into a `cols × rows` buffer.
pub fn render_buffer(scene: Scene, options: &SnapshotOptions) -> (App, Buffer) {
    let config = AppConfig {
        color_depth: options.color_depth,
        dither: options.dither,
        cell_aspect: options.cell_aspect,
        // `--plain` prints one character per half-block cell of the frame.
        cells: if options.plain {
            CellMode::Half
        } else {
            options.cells
        },
        ..AppConfig::default()
    };
    let mut app = App::new(scene, config);
    app.render_options.mode = options.mode;
    app.set_overlays(options.overlays);
    if options.plain {
        // The density ramp reads best when empty space is blank.
        app.render_options.background = crate::color::Rgb::BLACK;
    }
    if let Some(orthographic) = options.orthographic {
        app.camera.set_orthographic(orthographic);
    }
    for _ in 0..options.steps {
        app.world.step();
    }
    // The snapshot is all view: lay out one extra row for the status bar we do not print.
    let area = Rect::new(0, 0, options.cols, options.rows);
    app.resize(Rect::new(
        0,
        0,
        options.cols,
        options.rows.saturating_add(1),
    ));
    app.render_scene();
    let mut buffer = Buffer::empty(area);
    CellView {
        pixels: app.frame.pixels(),
        width: app.frame.width(),
        height: app.frame.height(),
        mode: app.config.cells,
        depth: options.color_depth,
        dither: options.dither,
    }
    .render(area, &mut buffer);
    app.draw_joint_labels(area, &mut buffer);
    (app, buffer)
}

/// The frame as text: ANSI colours, or plain characters when `options.plain`.
pub fn snapshot_text(scene: Scene, options: &SnapshotOptions) -> String {
    let (app, buffer) = render_buffer(scene, options);
    if options.plain {
        let mut text = String::new();
        for line in
            crate::term::plain_lines(app.frame.pixels(), app.frame.width(), app.frame.height())
        {
            text.push_str(line.trim_end());
            text.push('\n');
        }
        text
    } else {
        crate::term::buffer_to_ansi(&buffer, options.color_depth)
    }
}
