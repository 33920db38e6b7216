//! What a key or the mouse can ask the sandbox for, and the one place that does it. Input is read in
//! [`crate::app::input`] and looked up in the key table ([`crate::app::input::keys`]); the answer is an [`Action`],
//! so a key's meaning is written once and the same request reads the same wherever it comes from.

use glam::Vec3;

use crate::app::App;
use crate::app::input::leaving::Leave;
use crate::app::input::mouse::Press;
use crate::app::input::nudge::NudgeDir;
use crate::app::panels::overlays::OverlayKind;
use crate::geometry::Shape;

/// Orbit step per arrow key, radians.
const ORBIT_STEP: f32 = 0.08;
/// Zoom factor per key or wheel notch.
const ZOOM_STEP: f32 = 0.9;

/// What the status bar says while `f` waits for a click; a user without a middle button freezes
/// this way.
pub const FREEZE_PROMPT: &str = "click a body to freeze or unfreeze it (Esc cancels)";

/// Which way an arrow key turns the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turn {
    Left,
    Right,
    Up,
    Down,
}

/// One thing a key or the mouse asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// `h`: the left button grabs instead of pushing, or pushes again.
    ToggleGrabMode,
    /// `x`: the strong hand on or off.
    ToggleStrong,
    /// `f`: the next click freezes or unfreezes.
    ArmFreeze,
    /// `w` `a` `d`, Shift+`s`, `e`: nudges the selected body.
    Nudge(NudgeDir),
    /// `+` / `-`, the wheel: zooms, or moves a held body nearer or farther (the keys' `+` / `-`
    /// are caught for that before the menus, in [`crate::app::input`], as the hand comes first).
    Zoom { closer: bool },
    /// Arrows: orbits the camera.
    Orbit(Turn),
    /// `c`, Home.
    ResetCamera,
    /// `p`: perspective ↔ orthographic.
    ToggleProjection,
    /// `m`, Tab / Shift+Tab.
    CycleMode { forward: bool },
    /// `v`: the next cell mode.
    CycleCells,
    /// Space.
    TogglePause,
    /// `.`: pauses and steps once.
    SingleStep,
    /// `g`.
    ToggleGravity,
    /// `r`: the bodies back where the scene put them.
    ResetBodies,
    /// `b`.
    SpawnBox,
    /// `s`.
    SpawnSphere,
    /// `<` / `>`: the selected body 10 % smaller or larger.
    Grow { larger: bool },
    /// `[` / `]`.
    Rewind { forward: bool },
    /// Ctrl+S.
    Save,
    /// `?`, F1.
    OpenHelp,
    /// `o`: the overlay menu.
    OverlayMenu,
    /// `i`: the inspector panel.
    ToggleInspector,
    /// `t`: the live settings.
    OpenSettings,
    /// ↑↓, PageUp/PageDown, Space, the wheel in the help: scrolls it, or closes it where it fits.
    ScrollHelp { rows: i32 },
    /// Any other key, or a click, in the help.
    CloseHelp,
    /// A digit in the overlay menu (see [`crate::app::input::menu_keys`]).
    ToggleOverlay(OverlayKind),
    /// `o`, Esc, Enter in the overlay menu.
    CloseOverlayMenu,
    /// ↑ ↓ in the live settings: the row above or below (wrapping).
    SettingsRow { down: bool },
    /// ← → (- +, Enter) in the live settings: the highlighted setting one notch down or up.
    ChangeSetting { up: bool },
    /// `t`, Esc in the live settings.
    CloseSettings,
    /// A mouse button pressed over `cell` (see [`crate::app::input::mouse`]); `strong`: Shift held.
    Click {
        cell: (u16, u16),
        press: Press,
        strong: bool,
    },
    /// The pointer moved to `cell` with a button held.
    Drag { cell: (u16, u16) },
    /// The button came up: the hand lets go.
    Release,
    /// The pointer moved to `cell` with no button held.
    Hover { cell: (u16, u16) },
    /// Ctrl+L.
    Repaint,
    /// Esc: closes the topmost thing open, else leaves as `q` does.
    Escape,
    /// `q`: leaves (asking first if the world changed).
    Quit,
    /// `n` / `N`: the next or previous built-in scene (asking first if the world changed).
    SwitchScene { forward: bool },
    /// Ctrl+C: leaves at once, whatever is open.
    Interrupt,
    /// Ctrl+Z: the event loop (`run`) suspends before the app sees the press; only a held key's
    /// repeats reach `App::apply`.
    Suspend,
}

impl Action {
    /// Whether a replay takes it: looking, time and leaving, never a change to the world (Ctrl
    /// keys are let through by the caller; the panels' keys come before the check).
    pub fn replays(self) -> bool {
        matches!(
            self,
            Action::TogglePause
                | Action::SingleStep
                | Action::Quit
                | Action::Rewind { .. }
                | Action::OpenHelp
                | Action::CycleMode { .. }
                | Action::ToggleProjection
                | Action::ResetCamera
                | Action::Escape
        )
    }

    /// The panels' own keys, which work while replaying (looking changes nothing).
    pub fn is_panel(self) -> bool {
        matches!(
            self,
            Action::OverlayMenu | Action::ToggleInspector | Action::OpenSettings
        )
    }
}

impl App {
    /// Does what `action` asks. `key` names the key that asked (for the messages that quote it);
    /// `leave_asked` is the request to leave the previous key made, if any.
    pub(crate) fn apply(&mut self, action: Action, key: &str, leave_asked: Option<Leave>) {
        match action {
            Action::ToggleGrabMode => self.toggle_grab_mode(),
            Action::ToggleStrong => {
                let strong = self.ui.toggle_strong();
                self.say(if strong { "strong hand" } else { "gentle hand" });
            }
            Action::ArmFreeze => {
                self.ui.arm_freeze();
                self.say(FREEZE_PROMPT);
            }
            Action::Nudge(dir) => self.nudge_selected(dir),
            Action::Zoom { closer } => {
                // The hand is what the user is busy with: a held body goes nearer or farther.
                if !self.move_grab(closer) {
                    self.zoom(if closer { ZOOM_STEP } else { 1.0 / ZOOM_STEP });
                }
            }
            Action::Orbit(turn) => {
                let (yaw, pitch) = match turn {
                    Turn::Left => (-ORBIT_STEP, 0.0),
                    Turn::Right => (ORBIT_STEP, 0.0),
                    Turn::Up => (0.0, ORBIT_STEP),
                    Turn::Down => (0.0, -ORBIT_STEP),
                };
                self.orbit(yaw, pitch);
            }
            Action::ResetCamera => self.reset_camera(),
            Action::ToggleProjection => self.toggle_projection(),
            Action::CycleMode { forward } => self.cycle_mode(forward),
            Action::CycleCells => self.cycle_cells(),
            Action::TogglePause => {
                let paused = self.ui.toggle_pause();
                self.say(if paused {
                    "paused (. steps)"
                } else {
                    "running"
                });
            }
            Action::SingleStep => {
                self.ui.step_once();
                self.say("single step");
            }
            Action::ToggleGravity => self.toggle_gravity(),
            Action::ResetBodies => self.reset(),
            Action::SpawnBox => self.spawn(Shape::cuboid(Vec3::splat(0.5))),
            Action::SpawnSphere => self.spawn(Shape::sphere(0.5)),
            Action::Grow { larger } => self.grow_selected(larger),
            Action::Rewind { forward: false } => self.rewind_back(),
            Action::Rewind { forward: true } => self.rewind_forward(),
            Action::Save => self.save_world(),
            Action::OpenHelp => self.open_help(),
            Action::OverlayMenu => self.open_overlay_menu(),
            Action::ToggleInspector => self.toggle_inspector(),
            Action::OpenSettings => self.open_settings(),
            Action::ScrollHelp { rows } => self.scroll_or_close_help(rows),
            Action::CloseHelp => self.close_help(),
            Action::ToggleOverlay(kind) => self.toggle_overlay(kind),
            Action::CloseOverlayMenu => self.close_overlay_menu(),
            Action::SettingsRow { down } => self.inspect.settings.move_row(down),
            Action::ChangeSetting { up } => self.change_setting(up),
            Action::CloseSettings => self.close_settings(),
            Action::Click {
                cell,
                press,
                strong,
            } => self.click(cell, press, strong),
            Action::Drag { cell } => self.drag_hand(cell),
            Action::Release => self.release_hand(),
            Action::Hover { cell } => self.hover(cell),
            Action::Repaint => {
                self.request_repaint();
                self.say("screen redrawn");
            }
            Action::Escape => {
                if !self.close_topmost() {
                    self.leave(Leave::Quit, leave_asked, key);
                }
            }
            Action::Quit => self.leave(Leave::Quit, leave_asked, key),
            Action::SwitchScene { forward } => {
                self.leave(Leave::Scene { forward }, leave_asked, key)
            }
            Action::Interrupt => self.quit = true,
            // Headless, or a held Ctrl+Z's repeats: as any other Ctrl key the app has no use for.
            Action::Suspend => self.say(format!("Ctrl+{key}: no such key (? for help)")),
        }
    }
}
