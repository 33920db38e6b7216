//! Live settings (`t`): sub-steps, iterations, sleeping, the time scale, gravity, the restitution
//! threshold and the terminal's cell aspect, changed while the world runs.
//!
//! Physics settings reach the world through its API between steps (`World::settings_mut`,
//! `World::set_gravity`), so they are journaled like every other input: a recording replays them and
//! a rewind restores them. The time scale is the app's alone (how much simulated time a second of
//! real time runs), so it changes no trace; so is the cell aspect (how tall a terminal cell is against
//! its width, which the picture is drawn for: a terminal that reports no pixel size gets a guess,
//! and bodies drawn too tall or too flat are corrected here by eye). A reset (`r`) rebuilds the bodies and keeps all of them.

use glam::Vec3;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph, Widget};

use crate::app::App;
use crate::term::cell_aspect::{MAX_CELL_ASPECT, MIN_CELL_ASPECT};

/// Sub-steps the panel offers.
pub const SUBSTEPS: std::ops::RangeInclusive<u32> = 1..=8;
/// Solver iterations per sub-step the panel offers.
pub const ITERATIONS: std::ops::RangeInclusive<u32> = 1..=4;
/// Time scales, slowest first (1 = real time).
pub const TIME_SCALES: [f32; 7] = [0.1, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0];
/// Gravity strengths, m/s²: the Moon, Mars, a few between, the Earth, Jupiter.
pub const GRAVITY_STRENGTHS: [f32; 8] = [1.62, 3.71, 5.0, 7.5, 9.81, 15.0, 20.0, 24.79];
/// Restitution thresholds, m/s: approach speeds below which contacts do not bounce.
pub const RESTITUTION_THRESHOLDS: [f32; 7] = [0.0, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0];

/// A notch of the cell aspect: 1 px in 20 of a cell's height, finer than the eye needs.
pub const CELL_ASPECT_STEP: f32 = 0.05;

/// One row of the panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    Substeps,
    Iterations,
    Sleep,
    TimeScale,
    Gravity,
    GravityStrength,
    RestitutionThreshold,
    CellAspect,
}

impl Setting {
    pub const ALL: [Setting; 8] = [
        Setting::Substeps,
        Setting::Iterations,
        Setting::Sleep,
        Setting::TimeScale,
        Setting::Gravity,
        Setting::GravityStrength,
        Setting::RestitutionThreshold,
        Setting::CellAspect,
    ];

    fn label(self) -> &'static str {
        match self {
            Setting::Substeps => "sub-steps",
            Setting::Iterations => "iterations",
            Setting::Sleep => "sleeping",
            Setting::TimeScale => "time scale",
            Setting::Gravity => "gravity",
            Setting::GravityStrength => "strength",
            Setting::RestitutionThreshold => "bounce above",
            Setting::CellAspect => "cell h / w",
        }
    }
}

/// The panel's state.
#[derive(Clone, Debug)]
pub struct LiveSettings {
    open: bool,
    /// Index in [`Setting::ALL`] of the highlighted row.
    row: usize,
    /// Simulated seconds per real second, one of [`TIME_SCALES`].
    time_scale: f32,
}

impl LiveSettings {
    pub fn is_open(&self) -> bool {
        self.open
    }

    pub fn open(&mut self) {
        self.open = true;
    }

    pub fn close(&mut self) {
        self.open = false;
    }

    /// ↑ ↓: the row above or below, wrapping round.
    pub fn move_row(&mut self, down: bool) {
        let rows = Setting::ALL.len();
        self.row = if down {
            (self.row + 1) % rows
        } else {
            (self.row + rows - 1) % rows
        };
    }
}

impl Default for LiveSettings {
    fn default() -> Self {
        Self {
            open: false,
            row: 0,
            time_scale: 1.0,
        }
    }
}

/// The entry after (`up`) or before `current` in `values` (sorted ascending), stopping at the ends;
/// a value between entries moves to the nearest one on that side.
fn next_in(values: &[f32], current: f32, up: bool) -> f32 {
    if up {
        values.iter().copied().find(|&v| v > current * 1.0001)
    } else {
        values.iter().rev().copied().find(|&v| v < current * 0.9999)
    }
    .unwrap_or(current)
}

impl App {
    /// Simulated seconds per real second (1 = real time).
    pub fn time_scale(&self) -> f32 {
        self.inspect.settings.time_scale
    }

    /// Gravity as the app applies it when on: the scene's direction (down if it has none) at the
    /// chosen strength (the scene's own until one is chosen).
    pub(crate) fn gravity_vector(&self) -> Vec3 {
        // A scene without gravity gets the standard one when `g` turns it on: saved while gravity
        // was off, a world wrote [0, 0, 0], and loaded back, `g` could never bring gravity back.
        let scene = match self.scene.settings.gravity {
            Vec3::ZERO => crate::physics::Settings::default().gravity,
            gravity => gravity,
        };
        match self.inspect.gravity_strength {
            Some(strength) => scene.try_normalize().unwrap_or(Vec3::NEG_Y) * strength,
            None => scene,
        }
    }

    /// The strength gravity has when on, m/s².
    fn gravity_strength(&self) -> f32 {
        self.gravity_vector().length()
    }

    /// `t` or Esc while the settings are open (their keys are in
    /// [`crate::app::input::menu_keys`]).
    pub(crate) fn close_settings(&mut self) {
        self.inspect.settings.close();
        self.say("settings closed");
    }

    /// Moves the highlighted setting one notch up or down (booleans flip) and says so.
    pub(crate) fn change_setting(&mut self, up: bool) {
        let setting = Setting::ALL[self.inspect.settings.row];
        let message = match setting {
            Setting::Substeps => {
                let now = self.world.settings().substep_count();
                let new = if up { now + 1 } else { now.saturating_sub(1) }
                    .clamp(*SUBSTEPS.start(), *SUBSTEPS.end());
                self.world.settings_mut().substeps = new;
                format!("sub-steps {new}")
            }
            Setting::Iterations => {
                let now = self.world.settings().iteration_count();
                let new = if up { now + 1 } else { now.saturating_sub(1) }
                    .clamp(*ITERATIONS.start(), *ITERATIONS.end());
                self.world.settings_mut().iterations = new;
                format!("iterations {new}")
            }
            Setting::Sleep => {
                let on = !self.world.settings().sleep;
                self.world.settings_mut().sleep = on;
                format!("sleeping {}", if on { "on" } else { "off" })
            }
            Setting::TimeScale => {
                let scale = next_in(&TIME_SCALES, self.inspect.settings.time_scale, up);
                self.inspect.settings.time_scale = scale;
                format!("time scale {scale}×")
            }
            Setting::Gravity => {
                self.toggle_gravity();
                return;
            }
            Setting::GravityStrength => {
                let strength = next_in(&GRAVITY_STRENGTHS, self.gravity_strength(), up);
                self.inspect.gravity_strength = Some(strength);
                if self.ui.gravity_on() {
                    self.world.set_gravity(self.gravity_vector());
                    format!("gravity {strength} m/s²")
                } else {
                    format!("gravity {strength} m/s² when on (g)")
                }
            }
            Setting::RestitutionThreshold => {
                let now = self.world.settings().restitution_threshold;
                let new = next_in(&RESTITUTION_THRESHOLDS, now, up);
                self.world.settings_mut().restitution_threshold = new;
                format!("bounce above {new} m/s")
            }
            Setting::CellAspect => {
                let step = if up {
                    CELL_ASPECT_STEP
                } else {
                    -CELL_ASPECT_STEP
                };
                let new = ((self.config.cell_aspect + step) / CELL_ASPECT_STEP).round()
                    * CELL_ASPECT_STEP;
                let new = new.clamp(MIN_CELL_ASPECT, MAX_CELL_ASPECT);
                self.config.cell_aspect = new;
                format!("cell aspect {new:.2} (round bodies look round when it is right)")
            }
        };
        self.say(message);
    }

    /// The settings panel's lines: each row's label and value.
    fn settings_lines(&self) -> Vec<(Setting, String)> {
        let s = self.world.settings();
        Setting::ALL
            .iter()
            .map(|&setting| {
                let value = match setting {
                    Setting::Substeps => s.substep_count().to_string(),
                    Setting::Iterations => s.iteration_count().to_string(),
                    Setting::Sleep => if s.sleep { "on" } else { "off" }.to_string(),
                    Setting::TimeScale => format!("{}×", self.inspect.settings.time_scale),
                    Setting::Gravity => if self.ui.gravity_on() { "on" } else { "off" }.to_string(),
                    Setting::GravityStrength => format!("{:.2} m/s²", self.gravity_strength()),
                    Setting::RestitutionThreshold => format!("{} m/s", s.restitution_threshold),
                    Setting::CellAspect => format!("{:.2}", self.config.cell_aspect),
                };
                (setting, value)
            })
            .collect()
    }

    /// The settings panel's lines, the highlighted setting marked.
    fn settings_text(&self) -> Vec<Line<'static>> {
        let selected = self.inspect.settings.row;
        self.settings_lines()
            .into_iter()
            .enumerate()
            .map(|(i, (setting, value))| {
                let style = if i == selected {
                    Style::default()
                        .fg(Color::Black)
                        .bg(Color::Yellow)
                        .add_modifier(Modifier::BOLD)
                } else {
                    Style::default()
                };
                Line::from(vec![
                    Span::styled(format!(" {:<12}", setting.label()), style),
                    Span::styled(format!("{value:>11} "), style),
                ])
            })
            .collect()
    }

    /// The settings panel's cells: the view's top-right corner, as wide as its lines.
    pub(crate) fn settings_area(&self, view: Rect) -> Rect {
        area_of(&self.settings_text(), view)
    }

    /// Draws the settings panel in the view's top-right corner.
    pub(crate) fn draw_settings(&self, view: Rect, buf: &mut Buffer) {
        let lines = self.settings_text();
        let area = area_of(&lines, view);
        Clear.render(area, buf);
        Paragraph::new(lines)
            .block(Block::bordered().title(" settings ↑↓ ←→ · t "))
            .style(Style::default().fg(Color::White).bg(Color::Black))
            .render(area, buf);
    }
}

/// The bordered box `lines` fill in `view`'s top-right corner.
fn area_of(lines: &[Line], view: Rect) -> Rect {
    let width = (lines.iter().map(Line::width).max().unwrap_or(0) as u16 + 2).min(view.width);
    let height = (lines.len() as u16 + 2).min(view.height);
    Rect {
        x: view.right().saturating_sub(width),
        width,
        height,
        ..view
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_notch_moves_to_the_neighbouring_value_and_stops_at_the_ends() {
        assert_eq!(next_in(&TIME_SCALES, 1.0, true), 1.5);
        assert_eq!(next_in(&TIME_SCALES, 1.0, false), 0.75);
        assert_eq!(next_in(&TIME_SCALES, 2.0, true), 2.0);
        assert_eq!(next_in(&TIME_SCALES, 0.1, false), 0.1);
        // The scene's gravity need not be on the list.
        assert_eq!(next_in(&GRAVITY_STRENGTHS, 9.0, true), 9.81);
        assert_eq!(next_in(&GRAVITY_STRENGTHS, 9.0, false), 7.5);
    }
}
