//! Drawing the app: the 3D view in the configured cell mode above a status bar, and the help overlay.

use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Paragraph, Widget, Wrap};

use crate::app::App;
use crate::app::panels::help::HelpOverlay;
use crate::app::panels::look;
use crate::app::panels::status::StatusLine;
use crate::geometry::Projection;
use crate::term::{CellMode, CellView};

/// Below this size the app shows a notice instead of a scene.
pub const MIN_COLS: u16 = 16;
pub const MIN_ROWS: u16 = 4;

/// The 3D view's cells: everything but the bottom row (the status bar).
pub fn viewport_area(area: Rect) -> Rect {
    Rect {
        height: area.height.saturating_sub(1),
        ..area
    }
}

impl App {
    /// Draws the whole app into `buf` over `area` (the terminal), re-laying out if it changed.
    pub fn draw(&mut self, area: Rect, buf: &mut Buffer) {
        self.resize(area);
        self.dirty = false;
        if area.width < MIN_COLS || area.height < MIN_ROWS {
            Paragraph::new("terminal too small for nudge")
                .wrap(Wrap { trim: true })
                .render(area, buf);
            return;
        }
        let start = Instant::now();
        self.render_scene();
        let view = self.viewport_area();
        let map_start = Instant::now();
        CellView {
            pixels: self.frame.pixels(),
            width: self.frame.width(),
            height: self.frame.height(),
            mode: self.config.cells,
            depth: self.config.color_depth,
            dither: self.config.dither,
        }
        .render(view, buf);
        let map_ms = map_start.elapsed().as_secs_f64() * 1e3;
        self.inspect.frame_profile.map.record(map_ms);
        self.draw_joint_labels(view, buf);
        self.stats
            .record_render(start.elapsed().as_secs_f64() * 1e3);

        let status = Rect {
            y: area.bottom() - 1,
            height: 1,
            ..area
        };
        let projection = match self.camera.get().projection {
            Projection::Perspective { .. } => "persp",
            Projection::Orthographic { .. } => "ortho",
        };
        let pointing_at = self.pointing_at();
        // The cell mode beside the colours, when it is not the default half blocks.
        let colors = match self.config.cells {
            CellMode::Half => self.config.color_depth.name().to_string(),
            cells => format!("{} {cells}", self.config.color_depth.name()),
        };
        let byte_limit = crate::app::byte_budget::limit_note(
            self.config.max_bytes_per_second,
            self.config.byte_limit_origin,
        );
        StatusLine {
            stats: &self.stats,
            awake: self.world.awake_count(),
            total: self.world.len(),
            mode: self.render_options.mode.name(),
            projection,
            colors: &colors,
            paused: self.ui.paused(),
            strong: self.ui.strong(),
            grab: self.ui.grab_mode(),
            gravity_off: !self.ui.gravity_on(),
            freeze_armed: self.ui.freeze_armed(),
            pointing_at: pointing_at.as_deref(),
            byte_limit: &byte_limit,
            message: &self.message,
        }
        .render(status, buf);

        self.draw_inspection(view, buf);
        if self.help.is_open() {
            // Over the whole screen but the status bar: beside the inspector, the view alone is too
            // narrow for it at 80 columns.
            HelpOverlay {
                scroll: self.help.scroll(),
            }
            .render(viewport_area(area), buf);
        }
    }

    /// Rasterizes the world into `self.frame` for the current viewport.
    pub fn render_scene(&mut self) {
        let viewport = self.viewport();
        look::drawables(
            &self.world,
            &self.looks,
            self.selection.highlighted(),
            &mut self.drawables,
        );
        self.tint_for_overlays();
        let options = self.view_render_options();
        self.renderer.render(
            &mut self.frame,
            &viewport,
            self.camera.get(),
            &self.drawables,
            &options,
        );
        self.draw_grab_tether();
        self.draw_overlay_marks();
    }
}

impl App {
    /// The render options the view is drawn with: supersampled in half-block cells only. A finer
    /// cell already samples 4 to 8 points, as a supersampled half-block cell does (2 × 4); sampling
    /// those 4 times over again cost 3 to 5 times half blocks' draw time for an error lower by a
    /// tenth on the pyramid and none on the default scene (`nudge bench cells`). Supersampling only
    /// the pixels on a silhouette (a second 2× pass shading just those, resolved to the samples'
    /// OKLab median) was tried too: octant's error stayed 0.60× half's on the default scene and
    /// 0.72× on the pyramid, at 2 to 3 times half's draw time. What the pyramid's octant picture
    /// misses is the wood grain finer than its pixels, not its edges: untextured, it is 0.55× half's.
    pub(crate) fn view_render_options(&self) -> crate::render::RenderOptions {
        crate::render::RenderOptions {
            supersample: self.render_options.supersample && self.config.cells == CellMode::Half,
            ..self.render_options
        }
    }
}
