//! Keyboard nudges: `w` `a` `d` and Shift+`s` push the selected body along the camera's horizontal
//! forward, left, right and back; `e` lifts it.
//!
//! A nudge is a force of the body's mass × [`NUDGE_ACCEL`] for [`KEY_NUDGE_STEPS`] steps (0.1 s),
//! like the hand's, so every body answers a tap alike: a 1 kg ball and the default scene's 5 kg box
//! each gain about 1 m/s. A fixed 40 N threw the ball off the world with one press and barely moved
//! the box. Every direction is equal (Shift is only how the back key is typed; it used to make `S`
//! 4× the others); the strong hand (`x`) makes every nudge 4× as it does the mouse. A lift adds the
//! body's weight, so it rises at the same rate. Like a held push, a nudge leans in only until the
//! body moves at the hand's walking pace (`hand::PUSH_SPEED`), and a new press on the same body
//! takes over from the one in flight: a key held down (repeated by the terminal) moves a body
//! steadily instead of stacking pushes until it flies.

use glam::Vec3;

use crate::app::App;
use crate::app::input::hand::KEY_NUDGE_STEPS;

/// Acceleration a key nudge gives the selected body while it acts, m/s²: 1.5 g, about twice what
/// floor friction at μ = 0.5 takes back, so a box slides some 15 cm per tap and a ball rolls on.
pub const NUDGE_ACCEL: f32 = 15.0;

/// Standard gravity the lift adds, m/s² (a nudge is a push, not a gravity switch).
const G: f32 = 9.81;

/// The force of one nudge on a body of `mass` kg along unit `direction` (before the strong hand's
/// factor), N; a lift (`direction` = +y) also carries the body's weight.
pub fn nudge_force(mass: f32, direction: Vec3, lift: bool) -> Vec3 {
    let accel = if lift { NUDGE_ACCEL + G } else { NUDGE_ACCEL };
    direction * mass * accel
}

/// Which way a nudge pushes, relative to the camera's horizontal view.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NudgeDir {
    /// `w`.
    Away,
    /// Shift+`s`.
    Back,
    /// `a`.
    Left,
    /// `d`.
    Right,
    /// `e`: a lift.
    Up,
}

impl App {
    /// Nudges the selected body `dir`.
    pub(crate) fn nudge_selected(&mut self, dir: NudgeDir) {
        let Some(id) = self
            .selection
            .selected()
            .filter(|id| id.index() < self.world.len())
        else {
            self.say("click a body first to select it");
            return;
        };
        let name = self.body_name(id);
        if self.world.body(id).is_static() {
            self.say(format!(
                "{name} is fixed (freeze/unfreeze: middle-click or f)"
            ));
            return;
        }
        let basis = self.camera.get().basis();
        let forward = Vec3::new(basis.forward.x, 0.0, basis.forward.z).normalize_or(Vec3::Z);
        let right = Vec3::new(basis.right.x, 0.0, basis.right.z).normalize_or(Vec3::X);
        let (direction, word) = match dir {
            NudgeDir::Away => (forward, "away"),
            NudgeDir::Back => (-forward, "back"),
            NudgeDir::Left => (-right, "left"),
            NudgeDir::Right => (right, "right"),
            NudgeDir::Up => (Vec3::Y, "up"),
        };
        let mass = self.world.body(id).mass();
        let force = nudge_force(mass, direction, word == "up");
        self.hand.nudge(id, force);
        let factor = if self.ui.strong() {
            crate::app::input::hand::STRONG_FACTOR
        } else {
            1.0
        };
        let newtons = force.length() * factor;
        let seconds = KEY_NUDGE_STEPS as f32 * self.world.settings().dt;
        self.say(format!(
            "nudged {name} {word} ({newtons:.0} N for {seconds:.1} s)"
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nudge_scales_with_mass_and_a_lift_carries_the_weight() {
        assert_eq!(nudge_force(1.0, Vec3::X, false), Vec3::X * NUDGE_ACCEL);
        assert_eq!(
            nudge_force(5.0, -Vec3::Z, false),
            -Vec3::Z * 5.0 * NUDGE_ACCEL
        );
        assert_eq!(
            nudge_force(2.0, Vec3::Y, true),
            Vec3::Y * 2.0 * (NUDGE_ACCEL + G)
        );
    }
}
