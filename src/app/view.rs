//! Drawing the app: the 3D view in the configured cell mode above a status bar, and the help overlay.

use std::time::Instant;

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::{Color, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Clear, Paragraph, Widget, Wrap};

use super::App;
use super::input::CONTROLS;
use super::look;
use super::status::StatusLine;
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
        // The cell mode beside the colours, when it is not the default half blocks.
        let colors = match self.config.cells {
            CellMode::Half => self.config.color_depth.name().to_string(),
            cells => format!("{} {cells}", self.config.color_depth.name()),
        };
        StatusLine {
            stats: &self.stats,
            awake: self.world.awake_count(),
            total: self.world.len(),
            mode: self.render_options.mode.name(),
            projection,
            colors: &colors,
            paused: self.ui.paused,
            strong: self.ui.strong,
            grab: self.ui.grab_mode,
            gravity_off: !self.ui.gravity_on,
            freeze_armed: self.ui.freeze_armed,
            pointing_at: pointing_at.as_deref(),
            message: &self.message,
        }
        .render(status, buf);

        self.draw_inspection(view, buf);
        if self.ui.show_help {
            // Over the whole screen but the status bar: beside the inspector, the view alone is too
            // narrow for it at 80 columns.
            draw_help(viewport_area(area), buf);
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
        let options = self.view_render_options();
        self.renderer.render(
            &mut self.frame,
            &viewport,
            &self.camera,
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
    /// tenth on the pyramid and none on the default scene (`nudge bench cells`).
    pub(crate) fn view_render_options(&self) -> crate::render::RenderOptions {
        crate::render::RenderOptions {
            supersample: self.render_options.supersample && self.config.cells == CellMode::Half,
            ..self.render_options
        }
    }
}

fn draw_help(view: Rect, buf: &mut Buffer) {
    let keys_width = CONTROLS
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(0);
    let action_width = CONTROLS
        .iter()
        .map(|(_, a)| a.chars().count())
        .max()
        .unwrap_or(0);
    let width = ((keys_width + action_width + 6) as u16).min(view.width);
    let height = (CONTROLS.len() as u16 + 2).min(view.height);
    let [_, middle, _] = Layout::horizontal([
        Constraint::Fill(1),
        Constraint::Length(width),
        Constraint::Fill(1),
    ])
    .areas(view);
    let [_, popup, _] = Layout::vertical([
        Constraint::Fill(1),
        Constraint::Length(height),
        Constraint::Fill(1),
    ])
    .areas(middle);
    Clear.render(popup, buf);
    let lines: Vec<Line> = CONTROLS
        .iter()
        .map(|(keys, action)| Line::from(format!("{keys:>keys_width$}  {action}")))
        .collect();
    let scenes: Vec<&str> = crate::scene::builtin_scenes()
        .iter()
        .map(|(name, _)| *name)
        .collect();
    let scenes = format!(" scenes (n, N): {} ", scenes.join(" · "));
    Paragraph::new(lines)
        .block(
            Block::bordered()
                .title(" nudge · any key closes ")
                .title_bottom(scenes),
        )
        .style(Style::default().fg(Color::White).bg(Color::Black))
        .render(popup, buf);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_help_overlay_fits_an_80_column_terminal_uncut_and_lists_the_scenes() {
        let view = Rect::new(0, 0, 80, 23);
        let mut buf = Buffer::empty(view);
        draw_help(view, &mut buf);
        let text: String = (0..view.height)
            .map(|y| {
                (0..view.width)
                    .map(|x| buf[(x, y)].symbol().to_string())
                    .collect::<String>()
                    + "\n"
            })
            .collect();
        for (name, _) in crate::scene::builtin_scenes() {
            assert!(
                text.contains(&format!(" {name} ")),
                "{name} missing:\n{text}"
            );
        }
        // Every key the sandbox answers, the later additions too.
        for key in [
            " h ",
            " o then 1-8",
            " i, t ",
            "[ / ]",
            "< / >",
            "Ctrl+S",
            "Ctrl+Z",
            "F1",
            "Ctrl+L",
            "c, Home",
            "n / N",
            " x ",
            " g ",
            " r ",
            " p ",
        ] {
            assert!(text.contains(key), "{key} missing:\n{text}");
        }
        for (keys, action) in CONTROLS {
            assert!(text.contains(keys), "{keys} missing:\n{text}");
            assert!(
                text.contains(&format!("{action} ")),
                "{action} cut:\n{text}"
            );
        }
    }
}
