//! Seeing inside the physics: the state of the debug overlays and their menu, and the keys that
//! drive them. (`o` opens the overlay menu, where 1–8 toggle overlays.)

use crossterm::event::{KeyCode, KeyEvent};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

use super::App;
use super::overlays::{self, OverlayKind, OverlaySet};
use crate::render::{Overlay, draw_overlay};
use crate::term::{ColorDepth, quantize};

/// What the app shows of the physics beyond the scene itself.
#[derive(Debug, Default)]
pub struct Inspection {
    /// The overlays drawn.
    pub overlays: OverlaySet,
    /// The overlay menu is open: digits toggle overlays.
    pub menu_open: bool,
    /// This frame's overlay marks (scratch, reused).
    marks: Overlay,
    /// Island labels (scratch, reused).
    labels: Vec<u32>,
}

impl App {
    /// The overlays drawn.
    pub fn overlays(&self) -> OverlaySet {
        self.inspect.overlays
    }

    /// Replaces the overlays drawn.
    pub fn set_overlays(&mut self, overlays: OverlaySet) {
        self.inspect.overlays = overlays;
        self.dirty = true;
    }

    /// Handles the inspection keys (and every key while one of their menus is open); returns whether
    /// the key was used. Looking changes nothing in the world, so this works while replaying too.
    pub(crate) fn handle_inspection_key(&mut self, key: &KeyEvent) -> bool {
        if self.show_help {
            return false;
        }
        if self.inspect.menu_open {
            match key.code {
                KeyCode::Char(c) if OverlayKind::from_key(c).is_some() => {
                    if let Some(kind) = OverlayKind::from_key(c) {
                        let on = self.inspect.overlays.toggle(kind);
                        let state = if on { "on" } else { "off" };
                        self.say(format!("overlay {}: {state}", kind.name()));
                    }
                    return true;
                }
                KeyCode::Char('o') | KeyCode::Esc | KeyCode::Enter => {
                    self.inspect.menu_open = false;
                    return true;
                }
                // Any other key closes the menu and does what it always does.
                _ => self.inspect.menu_open = false,
            }
            return false;
        }
        match key.code {
            KeyCode::Char('o') => {
                self.inspect.menu_open = true;
                self.say("overlays: 1-8 toggle, o closes");
                true
            }
            _ => false,
        }
    }

    /// Tints the drawables for the island and sleep overlays (before the scene is rasterized).
    pub(crate) fn tint_for_overlays(&mut self) {
        overlays::tint(
            &self.world,
            &self.looks,
            self.inspect.overlays,
            &mut self.inspect.labels,
            &mut self.drawables,
        );
    }

    /// Draws the overlays' marks over the rasterized scene, through the scene's camera and viewport.
    pub(crate) fn draw_overlay_marks(&mut self) {
        overlays::marks(&self.world, self.inspect.overlays, &mut self.inspect.marks);
        let viewport = self.viewport();
        draw_overlay(
            &mut self.frame,
            &viewport,
            &self.camera,
            &self.inspect.marks,
        );
    }

    /// Draws the open menus over the 3D view's cells.
    pub(crate) fn draw_inspection_menus(&self, view: Rect, buf: &mut Buffer) {
        if self.inspect.menu_open {
            OverlayMenu(self.inspect.overlays, self.config.color_depth).render(view, buf);
        }
    }
}

/// The overlay menu: a box in the view's top-left corner, one line per overlay.
struct OverlayMenu(OverlaySet, ColorDepth);

impl Widget for OverlayMenu {
    fn render(self, view: Rect, buf: &mut Buffer) {
        let lines: Vec<Line> = OverlayKind::ALL
            .iter()
            .map(|&kind| {
                let on = self.0.contains(kind);
                let name_style = Style::default().fg(quantize(kind.color(), self.1));
                let name_style = if on {
                    name_style.add_modifier(Modifier::BOLD)
                } else {
                    name_style
                };
                Line::from(vec![
                    Span::raw(format!(" {} {} ", kind.key(), if on { "■" } else { "·" })),
                    Span::styled(format!("{:<9}", kind.name()), name_style),
                    Span::styled(kind.describe(), Style::default().fg(Color::Gray)),
                ])
            })
            .collect();
        let width = lines.iter().map(Line::width).max().unwrap_or(0) as u16 + 3;
        let area = Rect {
            width: width.min(view.width),
            height: (lines.len() as u16 + 2).min(view.height),
            ..view
        };
        Clear.render(area, buf);
        Paragraph::new(lines)
            .block(Block::bordered().title(" overlays · 1-8 toggle · o closes "))
            .style(Style::default().fg(Color::White).bg(Color::Black))
            .render(area, buf);
    }
}
