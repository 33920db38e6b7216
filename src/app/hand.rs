//! The mouse as a hand: while a button is held, push (or pull) whatever is under the pointer, at the
//! point the ray enters it, every physics step.

use glam::Vec3;
use ratatui::layout::Rect;

use super::picking;
use crate::geometry::{Camera, Viewport};
use crate::physics::{BodyId, World};

/// Acceleration a push or pull gives the body under the pointer, m/s²: the force is this times the
/// body's mass, so every body answers the hand alike, and it grows while the button is held, from
/// about 1 g (twice what floor friction at μ = 0.5 takes back) by `HAND_ACCEL_RAMP` per second up to
/// `HAND_ACCEL_MAX`, as a person leans in: a tap nudges, a hold shoves (and shifts a box under a
/// load). A fixed force did neither: 20 N, plenty for a 1 kg ball, could not overcome the floor's
/// friction under the default scene's 5 kg box (μ·m·g = 24.5 N), so a click on it did nothing,
/// while any force that did sent the light bodies off the floor at a touch. The strong hand pushes
/// 4× harder, enough to throw.
pub const HAND_ACCEL: f32 = 10.0;
pub const HAND_ACCEL_RAMP: f32 = 20.0;
pub const HAND_ACCEL_MAX: f32 = 30.0;
pub const STRONG_FACTOR: f32 = 4.0;

/// The force (N) the hand pushes or pulls a body of `mass` (kg) with after holding it `held`
/// seconds.
pub fn hand_force(mass: f32, held: f32, strong: bool) -> f32 {
    let accel = (HAND_ACCEL + HAND_ACCEL_RAMP * held.max(0.0)).min(HAND_ACCEL_MAX);
    accel * mass * if strong { STRONG_FACTOR } else { 1.0 }
}

/// Steps a WASD/E key nudge acts for (its force: `nudge::nudge_force`).
pub const KEY_NUDGE_STEPS: u32 = 6;

/// Push away from the camera or pull toward it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HandMode {
    Push,
    Pull,
}

/// A held button: its mode and the cell under the pointer (absolute terminal coordinates).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grip {
    pub mode: HandMode,
    pub cell: (u16, u16),
    /// Shift was held when the button went down (where the terminal reports it).
    pub strong: bool,
    /// How long the button has been held, s (counted in physics steps).
    pub held: f32,
}

/// A key nudge in flight: a force on one body for a few more steps.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Nudge {
    body: BodyId,
    force: Vec3,
    steps_left: u32,
}

#[derive(Clone, Debug, Default)]
pub struct Hand {
    grip: Option<Grip>,
    nudges: Vec<Nudge>,
}

impl Hand {
    pub fn grip(&self) -> Option<Grip> {
        self.grip
    }

    pub fn press(&mut self, mode: HandMode, cell: (u16, u16), strong: bool) {
        self.grip = Some(Grip {
            mode,
            cell,
            strong,
            held: 0.0,
        });
    }

    /// The pointer moved with the button down: the force follows it.
    pub fn drag(&mut self, cell: (u16, u16)) {
        if let Some(grip) = &mut self.grip {
            grip.cell = cell;
        }
    }

    pub fn release(&mut self) {
        self.grip = None;
    }

    /// Pushes `body` with `force` (world, N) at its centre for the next few steps.
    pub fn nudge(&mut self, body: BodyId, force: Vec3) {
        self.nudges.push(Nudge {
            body,
            force,
            steps_left: KEY_NUDGE_STEPS,
        });
    }

    pub fn is_active(&self) -> bool {
        self.grip.is_some() || !self.nudges.is_empty()
    }

    /// Applies this step's forces. `viewport_cells` is where the 3D view sits in the terminal.
    pub fn apply(
        &mut self,
        world: &mut World,
        camera: &Camera,
        viewport: &Viewport,
        viewport_cells: Rect,
        strong: bool,
    ) {
        let scale = if strong { STRONG_FACTOR } else { 1.0 };
        if let Some(grip) = self.grip
            && let Some((col, row)) = cell_in(viewport_cells, grip.cell)
            && let Some(pick) = picking::pick_cell(world, camera, viewport, col, row)
            && !world.body(pick.body).is_static()
        {
            let direction = match grip.mode {
                HandMode::Push => pick.ray.dir,
                HandMode::Pull => -pick.ray.dir,
            };
            let force = hand_force(
                world.body(pick.body).mass(),
                grip.held,
                strong || grip.strong,
            );
            world.apply_force_at_point(pick.body, direction * force, pick.hit.point);
        }
        if let Some(grip) = &mut self.grip {
            grip.held += world.settings().dt;
        }
        for nudge in &mut self.nudges {
            if nudge.body.index() < world.len() {
                let center = world.body(nudge.body).pose().position;
                world.apply_force_at_point(nudge.body, nudge.force * scale, center);
            }
            nudge.steps_left -= 1;
        }
        self.nudges.retain(|n| n.steps_left > 0);
    }
}

/// `cell` (absolute) relative to `area`, if inside it.
pub fn cell_in(area: Rect, cell: (u16, u16)) -> Option<(u16, u16)> {
    let (col, row) = cell;
    (col >= area.x && col < area.right() && row >= area.y && row < area.bottom())
        .then(|| (col - area.x, row - area.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hand_pushes_in_proportion_to_mass_and_leans_in_while_held() {
        // 1 g at the touch, +2 g per second held, at most 3 g; 4× when strong.
        assert_eq!(hand_force(1.0, 0.0, false), 10.0);
        assert_eq!(hand_force(5.0, 0.0, false), 50.0);
        assert_eq!(hand_force(2.0, 0.5, false), 40.0);
        assert_eq!(hand_force(2.0, 1.0, false), 60.0);
        assert_eq!(hand_force(2.0, 60.0, false), 60.0);
        assert_eq!(hand_force(2.0, 0.0, true), 80.0);
        // Whatever the clock says, never less than the touch.
        assert_eq!(hand_force(1.0, -3.0, false), 10.0);
    }

    #[test]
    fn a_grip_counts_the_time_it_is_held_and_a_new_press_starts_over() {
        let mut hand = Hand::default();
        hand.press(HandMode::Push, (3, 4), false);
        let mut world = World::new(crate::physics::Settings::default());
        let camera = Camera::perspective(glam::Vec3::new(0.0, 0.0, -5.0), glam::Vec3::ZERO, 1.0);
        let viewport = Viewport::new(10, 10, 1.0);
        for _ in 0..30 {
            hand.apply(
                &mut world,
                &camera,
                &viewport,
                Rect::new(0, 0, 10, 5),
                false,
            );
        }
        let held = hand.grip().unwrap().held;
        assert!((held - 0.5).abs() < 1e-5, "{held}");
        hand.press(HandMode::Pull, (3, 4), false);
        assert_eq!(hand.grip().unwrap().held, 0.0);
    }
}
