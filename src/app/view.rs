//! Drawing the app: the 3D view as half-block cells above a status bar, and the help overlay.

use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::widgets::{Paragraph, Widget, Wrap};

use super::App;
use super::help::HelpOverlay;
use super::look;
use super::status::StatusLine;
use crate::geometry::Projection;
use crate::term::HalfBlocks;

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
        HalfBlocks {
            pixels: self.frame.pixels(),
            width: self.frame.width(),
            height: self.frame.height(),
            depth: self.config.color_depth,
            dither: self.config.dither,
        }
        .render(view, buf);
        let map_ms = map_start.elapsed().as_secs_f64() * 1e3;
        self.inspect.frame_profile.map.record(map_ms);
        self.stats
            .record_render(start.elapsed().as_secs_f64() * 1e3);

        let status = Rect {
            y: area.bottom() - 1,
            height: 1,
            ..area
        };
        let projection = match self.camera.projection {
            Projection::Perspective { .. } => "persp",
            Projection::Orthographic { .. } => "ortho",
        };
        let pointing_at = self.pointing_at();
        let byte_limit = super::byte_budget::limit_note(
            self.config.max_bytes_per_second,
            self.config.byte_limit_origin,
        );
        StatusLine {
            stats: &self.stats,
            awake: self.world.awake_count(),
            total: self.world.len(),
            mode: self.render_options.mode.name(),
            projection,
            colors: self.config.color_depth.name(),
            paused: self.ui.paused,
            strong: self.ui.strong,
            grab: self.ui.grab_mode,
            gravity_off: !self.ui.gravity_on,
            freeze_armed: self.ui.freeze_armed,
            pointing_at: pointing_at.as_deref(),
            byte_limit: &byte_limit,
            message: &self.message,
        }
        .render(status, buf);

        self.draw_inspection(view, buf);
        if self.ui.show_help {
            // Over the whole screen but the status bar: beside the inspector, the view alone is too
            // narrow for it at 80 columns.
            HelpOverlay {
                scroll: self.ui.help_scroll,
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
            self.highlighted,
            &mut self.drawables,
        );
        self.tint_for_overlays();
        self.renderer.render(
            &mut self.frame,
            &viewport,
            &self.camera,
            &self.drawables,
            &self.render_options,
        );
        self.draw_grab_tether();
        self.draw_overlay_marks();
    }
}
