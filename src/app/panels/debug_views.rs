//! Seeing inside the physics: the state of the debug overlays and their menu, the inspector panel
//! and the live settings ([`DebugViews`], `App::inspect`), and the methods that open, close and
//! draw them: `o` opens the overlay menu, where 1–9 toggle overlays; `i` opens the inspector panel;
//! `t` the live settings (see [`crate::app::panels::live_settings`]). Input asks for these through
//! the methods here; a scene switch carries the overlays and the panel over (`DebugViews::carry_to`).

use crossterm::event::KeyEvent;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

use std::time::Instant;

use crate::app::App;
use crate::app::input::menu_keys;
use crate::app::panels::charts::{History, Sample};
use crate::app::panels::inspector::{self, BodyReport, InspectorPanel, WorldReport};
use crate::app::panels::joint_view::{self, JointReport};
use crate::app::panels::live_settings::LiveSettings;
use crate::app::panels::overlays::{self, OverlayKind, OverlaySet};
use crate::app::panels::profile::{self, FrameProfile, StepStages};
use crate::render::{Overlay, draw_overlay};
use crate::term::{ColorDepth, quantize};

/// What the app shows of the physics beyond the scene itself.
#[derive(Debug, Default)]
pub struct DebugViews {
    /// The overlays drawn.
    overlays: OverlaySet,
    /// The overlay menu is open: digits toggle overlays.
    menu_open: bool,
    /// This frame's overlay marks (scratch, reused).
    marks: Overlay,
    /// Island labels (scratch, reused).
    labels: Vec<u32>,
    /// The inspector panel is open (on the right, when the terminal has room for it).
    panel_open: bool,
    /// The live settings panel.
    pub(in crate::app) settings: LiveSettings,
    /// Gravity's strength when on, m/s², once chosen in the settings (else the scene's).
    pub(in crate::app) gravity_strength: Option<f32>,
    /// The last 10 s of energy, momentum, penetration and step time, for the charts.
    history: History,
    /// Where frames spend their time.
    pub(in crate::app) frame_profile: FrameProfile,
    /// Where steps spend their time (the world times its stages while the panel is open).
    step_profile: StepStages,
}

impl DebugViews {
    /// A scene switch: what the user chose to see of the physics (the overlays, the inspector)
    /// goes over to the new scene's views; menus close, and the charts start afresh with its world.
    pub(crate) fn carry_to(&self, next: &mut DebugViews) {
        next.overlays = self.overlays;
        next.panel_open = self.panel_open;
    }
}

impl App {
    /// The overlays drawn.
    pub fn overlays(&self) -> OverlaySet {
        self.inspect.overlays
    }

    /// The selected body (the last clicked), which the inspector shows.
    pub fn selected(&self) -> Option<crate::physics::BodyId> {
        self.selection.selected()
    }

    /// Replaces the overlays drawn.
    pub fn set_overlays(&mut self, overlays: OverlaySet) {
        self.inspect.overlays = overlays;
        self.dirty = true;
    }

    /// Keys while the live settings or the overlay menu is open (not under the help); returns
    /// whether the key was used. The menu's own layer of the key table first
    /// ([`crate::app::input::menu_keys`]); any other key closes it and does what it always does, so
    /// `o` from the settings (or `t` from the overlay menu) switches to the other panel. Looking
    /// changes nothing in the world, so this works while replaying too.
    pub(crate) fn handle_menu_key(&mut self, key: &KeyEvent, key_name: &str) -> bool {
        if self.help.is_open() {
            return false;
        }
        let settings_open = self.inspect.settings.is_open();
        let action = if settings_open {
            menu_keys::settings_action(key.code)
        } else if self.inspect.menu_open {
            menu_keys::overlay_menu_action(key.code)
        } else {
            return false;
        };
        let Some(action) = action else {
            // Closed quietly: the key's own action says what it did.
            if settings_open {
                self.inspect.settings.close();
            } else {
                self.inspect.menu_open = false;
            }
            return false;
        };
        self.apply(action, key_name, None);
        true
    }

    /// A digit in the overlay menu: that overlay on or off.
    pub(crate) fn toggle_overlay(&mut self, kind: OverlayKind) {
        let on = self.inspect.overlays.toggle(kind);
        let state = if on { "on" } else { "off" };
        self.say(format!("overlay {}: {state}", kind.name()));
    }

    pub(crate) fn close_overlay_menu(&mut self) {
        self.inspect.menu_open = false;
        self.say("overlay menu closed");
    }

    /// After each physics step (`step_ms` of wall time): samples the world for the charts.
    pub(crate) fn after_step_inspection(&mut self, step_ms: f64) {
        if let Some(profile) = self.world.step_profile() {
            self.inspect.step_profile.record(profile);
        }
        let sample = Sample::of(&self.world, step_ms as f32);
        self.inspect
            .history
            .record(sample, self.world.settings().dt);
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

    /// Draws the overlays' marks over the rasterized scene, through the scene's camera and viewport
    /// (and notes what the renderer and the overlays took, for the profile).
    pub(crate) fn draw_overlay_marks(&mut self) {
        let start = Instant::now();
        let timings = self.renderer.timings();
        let profile = &mut self.inspect.frame_profile;
        profile.raster.record(timings.raster_ms);
        profile.shadow.record(timings.shadow_ms);
        overlays::marks(&self.world, self.inspect.overlays, &mut self.inspect.marks);
        let viewport = self.viewport();
        draw_overlay(
            &mut self.frame,
            &viewport,
            self.camera.get(),
            &self.inspect.marks,
        );
        self.inspect
            .frame_profile
            .overlay
            .record(start.elapsed().as_secs_f64() * 1e3);
    }

    /// The joints overlay's force labels over the view's cells (see [`joint_view::force_labels`]),
    /// magenta on black as the force arrows are drawn.
    pub(crate) fn draw_joint_labels(&self, view: Rect, buf: &mut Buffer) {
        if !self.inspect.overlays.contains(OverlayKind::Joints) {
            return;
        }
        let viewport = self.viewport();
        let clip_from_world = self.camera.get().clip_from_world(viewport.aspect());
        let cell_of = |p: glam::Vec3| {
            let clip = clip_from_world * p.extend(1.0);
            if clip.w <= 1e-6 {
                return None;
            }
            let ndc = glam::Vec2::new(clip.x / clip.w, clip.y / clip.w);
            let cell = viewport.cell_from_pixel(viewport.pixel_from_ndc(ndc));
            Some((cell.x.floor() as i32, cell.y.floor() as i32))
        };
        let style = Style::default()
            .fg(quantize(
                joint_view::JOINT_FORCE_COLOR,
                self.config.color_depth,
            ))
            .bg(Color::Black);
        for label in joint_view::force_labels(&self.world, cell_of, view.width, view.height) {
            buf.set_string(
                view.x + label.cell.0,
                view.y + label.cell.1,
                &label.text,
                style,
            );
        }
    }

    /// `o`: the overlay menu, where digits toggle overlays.
    pub(crate) fn open_overlay_menu(&mut self) {
        self.inspect.menu_open = true;
        self.say("overlays: 1-9 toggle, o closes");
    }

    /// `t`: the live settings, except in a replay, whose physics the recording sets.
    pub(crate) fn open_settings(&mut self) {
        if self.replay.is_some() {
            self.say("replaying: the recording sets the physics");
            return;
        }
        self.inspect.settings.open();
        self.say("settings: ↑↓ choose, ←→ change, t closes");
    }

    pub(crate) fn inspector_open(&self) -> bool {
        self.inspect.panel_open
    }

    pub(crate) fn toggle_inspector(&mut self) {
        self.inspect.panel_open = !self.inspect.panel_open;
        // Only timed while shown: closed, the step does not read the clock at all.
        self.world.set_profiling(self.inspect.panel_open);
        let room = inspector::panel_cols(self.area.width) > 0;
        self.say(match (self.inspect.panel_open, room) {
            (false, _) => "inspector closed",
            (true, true) => "inspector (i closes)",
            (true, false) => "inspector: the terminal is too narrow for it",
        });
    }

    /// The selected body's joints as the inspector lists them (none when nothing is selected).
    fn selected_joints(&self) -> Vec<JointReport> {
        let Some(id) = self.selection.selected() else {
            return Vec::new();
        };
        if id.index() >= self.world.len() {
            return Vec::new();
        }
        joint_view::joints_of(&self.world, id)
            .map(|(joint, other)| {
                let other = other.map_or_else(|| "world".to_string(), |b| self.body_name(b));
                JointReport::of(&self.world, joint, id, other)
            })
            .collect()
    }

    /// The inspector panel's cells (right of the scene, above the status bar), when it is shown.
    pub fn inspector_area(&self) -> Option<Rect> {
        if !self.inspect.panel_open {
            return None;
        }
        let rows = crate::app::panels::view::viewport_area(self.area);
        let cols = inspector::panel_cols(rows.width);
        (cols > 0).then(|| Rect {
            x: rows.right() - cols,
            width: cols,
            ..rows
        })
    }

    /// What to say to a click on the live settings or the overlay menu, which are drawn over the
    /// view: a click there must not push or grab a body the user cannot see. `None` elsewhere.
    pub(crate) fn popup_under(&self, cell: (u16, u16)) -> Option<&'static str> {
        let view = self.viewport_area();
        let contains = |area: Rect| crate::app::input::hand::cell_in(area, cell).is_some();
        if self.inspect.settings.is_open() && contains(self.settings_area(view)) {
            return Some("settings: ↑↓ choose, ←→ change, t closes");
        }
        let menu = OverlayMenu(self.inspect.overlays, self.config.color_depth);
        if self.inspect.menu_open && contains(OverlayMenu::area(&menu.lines(), view)) {
            return Some("overlays: 1-9 toggle, o closes");
        }
        None
    }

    /// `view` less the inspector panel: the scene shrinks beside it rather than hiding under it.
    pub(crate) fn beside_panel(&self, view: Rect) -> Rect {
        match self.inspector_area() {
            Some(panel) => Rect {
                width: view.width.saturating_sub(panel.width),
                ..view
            },
            None => view,
        }
    }

    /// Draws the inspector panel beside the 3D view and the open menus over it.
    pub(crate) fn draw_inspection(&self, view: Rect, buf: &mut Buffer) {
        if let Some(panel) = self.inspector_area() {
            let body = self.selection.selected().and_then(|id| {
                let scenery = self.looks.get(id.index()).is_some_and(|l| l.scenery);
                let name = self.scene_name_of(id).map(str::to_owned);
                BodyReport::of(&self.world, id, scenery).map(|r| BodyReport { name, ..r })
            });
            let inner = panel.width.saturating_sub(1);
            let n = inspector::number_cols(inner);
            let bar_cols = usize::from(inner.saturating_sub(16));
            let mut sections = vec![inspector::body_section(body.as_ref(), n)];
            let joints = self.selected_joints();
            if !joints.is_empty() {
                sections.push(inspector::joints_section(&joints, usize::from(inner)));
            }
            sections.extend([
                inspector::world_section(&WorldReport::of(&self.world), n),
                profile::stage_section("step", &self.inspect.step_profile.stages(), bar_cols),
                profile::stage_section("frame", &self.inspect.frame_profile.stages(), bar_cols),
            ]);
            InspectorPanel {
                sections: &sections,
                history: Some(&self.inspect.history),
            }
            .render(panel, buf);
        }
        if self.inspect.settings.is_open() {
            self.draw_settings(view, buf);
        }
        if self.inspect.menu_open {
            OverlayMenu(self.inspect.overlays, self.config.color_depth).render(view, buf);
        }
    }
}

/// The overlay menu: a box in the view's top-left corner, one line per overlay.
struct OverlayMenu(OverlaySet, ColorDepth);

impl OverlayMenu {
    fn lines(&self) -> Vec<Line<'static>> {
        OverlayKind::ALL
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
            .collect()
    }

    /// The menu's cells: the view's top-left corner, as wide as its lines.
    fn area(lines: &[Line], view: Rect) -> Rect {
        let width = lines.iter().map(Line::width).max().unwrap_or(0) as u16 + 3;
        Rect {
            width: width.min(view.width),
            height: (lines.len() as u16 + 2).min(view.height),
            ..view
        }
    }
}

impl Widget for OverlayMenu {
    fn render(self, view: Rect, buf: &mut Buffer) {
        let lines = self.lines();
        let area = Self::area(&lines, view);
        Clear.render(area, buf);
        Paragraph::new(lines)
            .block(Block::bordered().title(" overlays · 1-9 toggle · o closes "))
            .style(Style::default().fg(Color::White).bg(Color::Black))
            .render(area, buf);
    }
}
