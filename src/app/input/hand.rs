//! The mouse as a hand. While the left button is held on a body, a motor pushes the point under the
//! pointer along the ray, up to a walking pace; the right button pulls it back toward the camera the
//! same way. In grab mode (`h`) the left button instead holds the clicked point on a spring to the
//! pointer (see [`crate::app::input::grab`]). Key nudges push a body for a few steps. All of it reaches the world
//! as inputs at step boundaries (forces at points, and the grab's held point), so a recording replays
//! it exactly.

use glam::Vec3;
use ratatui::layout::Rect;

use crate::app::input::grab::Grab;
use crate::app::input::picking::ScreenView;
use crate::physics::{BodyId, World};

/// The speed a push (or pull) drives the point under the pointer toward, along the ray, m/s: a
/// brisk walk. A hand that pushed with a force growing while held (1 g, up to 3 g) launched the
/// default scene's boxes off the floor within a second and a half; a motor that only leans in until
/// the point moves this fast shoves them along steadily however long it is held, and lets go of
/// itself once the box slides out from under the pointer.
pub const PUSH_SPEED: f32 = 2.5;
/// The most a push accelerates the body it pushes, m/s²: its force limit is this times the body's
/// mass, so heavy bodies answer like light ones. 1.5 g is three times what floor friction at
/// μ = 0.5 takes back, so a push gets going at once (even pressing down a little, along a ray from
/// above) and tips a tall box, but cannot throw anything.
pub const PUSH_ACCEL_MAX: f32 = 15.0;
/// The strong hand (`x`, Shift) pushes with 4× the force...
pub const STRONG_FACTOR: f32 = 4.0;
/// ...up to twice the speed.
pub const STRONG_SPEED_FACTOR: f32 = 2.0;
/// How far a push reaches, m: it drives the point under the pointer while that point is at most this
/// much farther along the ray than where the hand first touched the body (for a pull, nearer). A
/// person's arm has a reach; without one, a hold on a box shoved it along the ray for as long as the
/// ray still met it, nearly 2 m across the default scene's 5 m deep floor, and at a walking pace it
/// then slid off the far edge. Press again, or drag after the body, to push on.
pub const REACH_M: f32 = 1.0;
/// A click pushes at least this long, s, even if the button comes up before the next step: a tap
/// nudges, whichever frame the release arrives in (0.1 s of 1.5 g: a box slides a hand's width).
pub const TAP_S: f32 = 0.1;

/// The speed (m/s) a push drives toward and its force limit (N) for a body of `mass` (kg).
pub fn push_limits(mass: f32, strong: bool) -> (f32, f32) {
    if strong {
        (
            PUSH_SPEED * STRONG_SPEED_FACTOR,
            PUSH_ACCEL_MAX * STRONG_FACTOR * mass,
        )
    } else {
        (PUSH_SPEED, PUSH_ACCEL_MAX * mass)
    }
}

/// Steps a WASD/E key nudge acts for (its force: `nudge::nudge_force`).
pub const KEY_NUDGE_STEPS: u32 = 6;

/// Push away from the camera or pull toward it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandMode {
    Push,
    Pull,
}

/// A held push or pull button: its mode and the cell under the pointer (absolute terminal
/// coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grip {
    pub mode: HandMode,
    pub cell: (u16, u16),
    /// Shift was held when the button went down (where the terminal reports it).
    pub strong: bool,
    /// How long the button has been held, s (counted in physics steps).
    pub held: f32,
    /// The button is up; the push goes on until [`TAP_S`] have passed.
    pub released: bool,
    /// The body first touched and how far along the ray, m: the push reaches [`REACH_M`] from there.
    pub touched: Option<(BodyId, f32)>,
}

impl Grip {
    /// It has pushed for [`TAP_S`] (up to the rounding of summed step lengths).
    fn tap_done(&self) -> bool {
        self.held >= TAP_S - 1e-4
    }
}

/// What the hand did this step, for the status bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HandReport {
    pub action: HandAction,
    pub body: BodyId,
    /// Magnitude of the force applied, N.
    pub force_n: f32,
    /// Push/pull: the held point's speed along the push, m/s. Grab: its distance from the pointer's
    /// point, m.
    pub measure: f32,
    /// Push/pull: the speed the hand leans in up to, m/s ([`push_limits`]); 0 for a grab.
    pub target_speed: f32,
    /// Push/pull: the body has gone beyond [`REACH_M`], so nothing pushes it.
    pub out_of_reach: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandAction {
    Push,
    Pull,
    Grab,
}

impl HandReport {
    /// "pushing box #2 · 41 N · point at 2.4 m/s (hand: 2.5)", "grabbing box #2 · 30 N · 3 cm off".
    /// The speed is the pointed-at point's, the one the hand's cap applies to: a rolling ball's
    /// point passes the cap while its centre lags (the bar read "2.9 m/s" at "0 N" with no cap
    /// shown, issue 28).
    pub fn describe(&self, name: &str) -> String {
        if self.out_of_reach {
            return format!("{name} is out of reach (press again or drag to push on)");
        }
        let (verb, measure) = match self.action {
            HandAction::Push | HandAction::Pull => (
                if self.action == HandAction::Push {
                    "pushing"
                } else {
                    "pulling"
                },
                format!(
                    "point at {:.1} m/s (hand: {:.1})",
                    self.measure, self.target_speed
                ),
            ),
            HandAction::Grab => ("grabbing", format!("{:.0} cm off", self.measure * 100.0)),
        };
        format!("{verb} {name} · {:.0} N · {measure}", self.force_n)
    }
}

/// A key nudge in flight: a push on one body's centre for a few more steps, a force of at most
/// `force` (before the strong hand's factor) driving the centre along it toward [`PUSH_SPEED`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Nudge {
    body: BodyId,
    force: Vec3,
    steps_left: u32,
}

#[derive(Clone, Debug, Default)]
pub struct Hand {
    grip: Option<Grip>,
    grab: Option<Grab>,
    nudges: Vec<Nudge>,
    /// The push or pull that just ended, until the app has said so.
    ended: Option<Grip>,
}

impl Hand {
    pub fn grip(&self) -> Option<Grip> {
        self.grip
    }

    pub fn grab(&self) -> Option<&Grab> {
        self.grab.as_ref()
    }

    pub fn grab_mut(&mut self) -> Option<&mut Grab> {
        self.grab.as_mut()
    }

    pub fn press(&mut self, mode: HandMode, cell: (u16, u16), strong: bool) {
        self.grab = None;
        self.grip = Some(Grip {
            mode,
            cell,
            strong,
            held: 0.0,
            released: false,
            touched: None,
        });
    }

    /// Starts holding a body's point on the spring (left button in grab mode).
    pub fn hold(&mut self, grab: Grab) {
        self.grip = None;
        self.grab = Some(grab);
    }

    /// The pointer moved with the button down: the push, or the grab's target, follows it. A push
    /// dragged after its body reaches on from where it touches next (the hand followed it).
    pub fn drag(&mut self, cell: (u16, u16)) {
        if let Some(grip) = &mut self.grip
            && grip.cell != cell
        {
            grip.cell = cell;
            grip.touched = None;
        }
        if let Some(grab) = &mut self.grab {
            grab.report(cell);
        }
    }

    /// The button came up: a grab lets go at once; a push goes on until it has lasted [`TAP_S`].
    /// Returns the grab, if any (see [`Grab::let_go`] for the throw).
    pub fn release(&mut self) -> Option<Grab> {
        if let Some(grip) = &mut self.grip {
            grip.released = true;
            if grip.tap_done() {
                self.ended = self.grip.take();
            }
        }
        self.grab.take()
    }

    /// Pushes `body` with at most `force` (world, N) at its centre for the next few steps. A nudge
    /// already pushing `body` gives way to the new one: a held key (the terminal repeats it about 30
    /// times a second) pushes steadily instead of stacking three pushes at once.
    pub fn nudge(&mut self, body: BodyId, force: Vec3) {
        self.nudges.retain(|n| n.body != body);
        self.nudges.push(Nudge {
            body,
            force,
            steps_left: KEY_NUDGE_STEPS,
        });
    }

    pub fn is_active(&self) -> bool {
        self.grip.is_some() || self.grab.is_some() || !self.nudges.is_empty()
    }

    /// Applies this step's forces in the view `view`. Returns what the push, pull or grab did, if it
    /// touched a body.
    pub fn apply(
        &mut self,
        world: &mut World,
        view: &ScreenView,
        strong: bool,
    ) -> Option<HandReport> {
        let mut report = None;
        if let Some(grip) = &mut self.grip
            && let Some(pick) = view.pick(world, grip.cell)
            && !world.body(pick.body).is_static()
        {
            let (direction, action) = match grip.mode {
                HandMode::Push => (pick.ray.dir, HandAction::Push),
                HandMode::Pull => (-pick.ray.dir, HandAction::Pull),
            };
            let first_t = match grip.touched {
                Some((body, t)) if body == pick.body => t,
                _ => pick.hit.t,
            };
            grip.touched = Some((pick.body, first_t));
            let reached = match grip.mode {
                HandMode::Push => pick.hit.t - first_t,
                HandMode::Pull => first_t - pick.hit.t,
            };
            let out_of_reach = reached > REACH_M;
            let point = pick.hit.point;
            let (speed, max_force) =
                push_limits(world.body(pick.body).mass(), strong || grip.strong);
            let force = if out_of_reach {
                0.0
            } else {
                world.motor_force(pick.body, point, direction, speed, max_force)
            };
            if force > 0.0 {
                world.apply_force_at_point(pick.body, direction * force, point);
            }
            report = Some(HandReport {
                action,
                body: pick.body,
                force_n: force,
                measure: direction.dot(world.point_velocity(pick.body, point)),
                target_speed: speed,
                out_of_reach,
            });
        }
        if let Some(grip) = &mut self.grip {
            grip.held += world.settings().dt;
            if grip.released && grip.tap_done() {
                self.ended = self.grip.take();
            }
        }
        if let Some(grab) = &mut self.grab {
            // A body frozen (or lost) while held is let go: the hand cannot move it.
            if grab.body.index() >= world.len() || world.body(grab.body).is_static() {
                self.grab = None;
            } else {
                report = Some(grab.apply(world, view, strong));
            }
        }
        // A nudge is the push's motor at the body's centre: it leans in up to its force until the
        // centre moves at the push's speed, so a key held down moves a body steadily, as a held
        // button does. Stacked fixed forces launched the default scene's 5 kg box at 120 m/s after
        // a second of a held `d` (400 m/s with the strong hand).
        let (speed, scale) = if strong {
            (PUSH_SPEED * STRONG_SPEED_FACTOR, STRONG_FACTOR)
        } else {
            (PUSH_SPEED, 1.0)
        };
        for nudge in &mut self.nudges {
            if nudge.body.index() < world.len()
                && !world.body(nudge.body).is_static()
                && let Some(direction) = nudge.force.try_normalize()
            {
                let center = world.body(nudge.body).pose().position;
                let max_force = nudge.force.length() * scale;
                let force = world.motor_force(nudge.body, center, direction, speed, max_force);
                if force > 0.0 {
                    world.apply_force_at_point(nudge.body, direction * force, center);
                }
            }
            nudge.steps_left -= 1;
        }
        self.nudges.retain(|n| n.steps_left > 0);
        report
    }
}

/// `cell` (absolute) relative to `area`, if inside it.
pub fn cell_in(area: Rect, cell: (u16, u16)) -> Option<(u16, u16)> {
    let (col, row) = cell;
    (col >= area.x && col < area.right() && row >= area.y && row < area.bottom())
        .then(|| (col - area.x, row - area.y))
}

impl crate::app::App {
    /// The hand's forces for the next step; what it does shows in the status bar.
    pub(crate) fn apply_hand(&mut self) {
        let view = self.screen_view();
        let report = self.hand.apply(&mut self.world, &view, self.ui.strong());
        if let Some(report) = report {
            let name = self.body_name(report.body);
            self.say(report.describe(&name));
        }
        self.say_push_ended();
    }

    /// A push or pull ended (the button came up and any tap ran out): says so, with the speed the
    /// body's centre was left at, so the bar does not go on "pushing" a body drifting free.
    pub(crate) fn say_push_ended(&mut self) {
        let Some(grip) = self.hand.ended.take() else {
            return;
        };
        let Some((body, _)) = grip.touched else {
            return;
        };
        if body.index() >= self.world.len() {
            return;
        }
        let verb = match grip.mode {
            HandMode::Push => "pushing",
            HandMode::Pull => "pulling",
        };
        let name = self.body_name(body);
        let speed = self.world.body(body).linear_velocity().length();
        self.say(format!(
            "stopped {verb} {name} · its centre at {speed:.1} m/s"
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Camera, Viewport};

    #[test]
    fn the_push_limit_scales_with_mass_and_the_strong_hand() {
        assert_eq!(push_limits(1.0, false), (2.5, 15.0));
        assert_eq!(push_limits(5.0, false), (2.5, 75.0));
        assert_eq!(push_limits(2.0, true), (5.0, 120.0));
    }

    fn stepped(hand: &mut Hand, steps: usize) {
        let mut world = World::new(crate::physics::Settings::default());
        let view = ScreenView {
            camera: Camera::perspective(glam::Vec3::new(0.0, 0.0, -5.0), glam::Vec3::ZERO, 1.0),
            viewport: Viewport::new(10, 10, 1.0),
            cells: Rect::new(0, 0, 10, 5),
            samples: 1,
        };
        for _ in 0..steps {
            hand.apply(&mut world, &view, false);
        }
    }

    #[test]
    fn a_grip_counts_the_time_it_is_held_and_a_new_press_starts_over() {
        let mut hand = Hand::default();
        hand.press(HandMode::Push, (3, 4), false);
        stepped(&mut hand, 30);
        let held = hand.grip().unwrap().held;
        assert!((held - 0.5).abs() < 1e-5, "{held}");
        hand.press(HandMode::Pull, (3, 4), false);
        assert_eq!(hand.grip().unwrap().held, 0.0);
    }

    #[test]
    fn a_tap_pushes_for_a_tenth_of_a_second_and_a_hold_stops_at_once() {
        let mut hand = Hand::default();
        hand.press(HandMode::Push, (3, 4), false);
        hand.release();
        assert!(hand.grip().is_some(), "released before any step");
        stepped(&mut hand, 5);
        assert!(hand.grip().is_some(), "5 steps are under 0.1 s");
        stepped(&mut hand, 1);
        assert!(hand.grip().is_none(), "6 steps are 0.1 s");
        hand.press(HandMode::Push, (3, 4), false);
        stepped(&mut hand, 20);
        hand.release();
        assert!(hand.grip().is_none());
    }
}
