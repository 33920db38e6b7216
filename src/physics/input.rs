//! Inputs: every change the world's API makes between steps, as data, so a session can be
//! recorded and replayed exactly.
//!
//! While journaling (`World::start_journal`), each call that changes the world from outside —
//! a force, an impulse, a held point, a freeze, gravity, a wake, a new body, a resize, a reset, a
//! settings change — is appended to the journal as a [`WorldInput`] tagged with the number of steps
//! taken before it. Applying the same inputs at the same step counts to a world built from the same
//! bodies (with [`World::apply_input`], which calls the same functions with the same arguments)
//! gives a bit-identical world: this is what recording, replay and rewind rest on.
//!
//! Why journal at the world's API rather than the app's commands: whatever a hand computes each step
//! (a ramped push, a speed-limited motor, a spring toward the pointer), what reaches the physics is
//! these calls, so the journal stays exact however the app derives them.
//!
//! A `settings_mut` borrow cannot say what it changed: the whole settings are journaled at the next
//! step, which is where they take effect (nothing between steps reads them).

use glam::Vec3;

use crate::geometry::Shape;
use crate::physics::solve::point_drive::PointHold;
use crate::physics::{BodyDesc, BodyId, JointDesc, Settings, World};

/// One change applied to the world between steps.
#[derive(Clone, Debug, PartialEq)]
pub enum WorldInput {
    /// [`World::apply_force_at_point`]: N and m, world frame.
    Force {
        body: BodyId,
        force: Vec3,
        point: Vec3,
    },
    /// [`World::apply_impulse_at_point`]: N·s and m, world frame.
    Impulse {
        body: BodyId,
        impulse: Vec3,
        point: Vec3,
    },
    /// [`World::hold_point`].
    Hold(PointHold),
    /// [`World::set_static`]: freeze (`true`) or unfreeze.
    SetStatic { body: BodyId, is_static: bool },
    /// [`World::set_gravity`], m/s².
    Gravity(Vec3),
    /// [`World::wake`].
    Wake(BodyId),
    /// [`World::add_body`].
    AddBody(BodyDesc),
    /// [`World::add_joint`].
    AddJoint(JointDesc),
    /// [`World::set_shape`].
    Resize { body: BodyId, shape: Shape },
    /// [`World::reset_bodies`]: the bodies are those the world was first built with, which the
    /// journal's reader keeps (a scene), so they are not repeated here.
    Reset,
    /// The settings after a `settings_mut` borrow, as the next step used them.
    Settings(Box<Settings>),
}

/// Why an input could not be applied (it names a body the world does not have).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoSuchBody(pub BodyId);

impl World {
    /// Steps taken since the world was built (a reset does not restart it).
    pub fn step_count(&self) -> u64 {
        self.steps
    }

    /// Starts (or restarts, emptied) journaling every input.
    pub fn start_journal(&mut self) {
        self.journal = Some(Vec::new());
    }

    /// Whether inputs are being journaled.
    pub fn is_journaling(&self) -> bool {
        self.journal.is_some()
    }

    /// The inputs journaled since the last call, each with the step count it was applied at, oldest
    /// first. Settings changed through `settings_mut` and not yet stepped are journaled now.
    pub fn take_journal(&mut self) -> Vec<(u64, WorldInput)> {
        if self.journal.is_some() && std::mem::take(&mut self.settings_touched) {
            self.log(WorldInput::Settings(Box::new(self.settings.clone())));
        }
        self.journal
            .as_mut()
            .map(std::mem::take)
            .unwrap_or_default()
    }

    pub(super) fn log(&mut self, input: WorldInput) {
        if let Some(journal) = &mut self.journal {
            journal.push((self.steps, input));
        }
    }

    /// Applies a journaled input through the same call that made it. `Reset` rebuilds `bodies`
    /// (the world's first bodies, which the caller keeps).
    pub fn apply_input(
        &mut self,
        input: &WorldInput,
        bodies: &[BodyDesc],
    ) -> Result<(), NoSuchBody> {
        let check = |world: &World, id: BodyId| {
            if id.index() < world.len() {
                Ok(())
            } else {
                Err(NoSuchBody(id))
            }
        };
        match input {
            WorldInput::Force { body, force, point } => {
                check(self, *body)?;
                self.apply_force_at_point(*body, *force, *point);
            }
            WorldInput::Impulse {
                body,
                impulse,
                point,
            } => {
                check(self, *body)?;
                self.apply_impulse_at_point(*body, *impulse, *point);
            }
            WorldInput::Hold(hold) => {
                check(self, hold.body)?;
                self.hold_point(*hold);
            }
            WorldInput::SetStatic { body, is_static } => {
                check(self, *body)?;
                self.set_static(*body, *is_static);
            }
            WorldInput::Gravity(gravity) => self.set_gravity(*gravity),
            WorldInput::Wake(body) => {
                check(self, *body)?;
                self.wake(*body);
            }
            WorldInput::AddBody(desc) => {
                self.add_body(*desc);
            }
            WorldInput::AddJoint(desc) => {
                // What a reader parses is checked (`JointDesc::check`): only its bodies can be
                // missing here.
                for id in [desc.a, Some(desc.b)].into_iter().flatten() {
                    check(self, id)?;
                }
                let _ = self.add_joint(*desc);
            }
            WorldInput::Resize { body, shape } => {
                check(self, *body)?;
                self.set_shape(*body, *shape);
            }
            WorldInput::Reset => self.reset_bodies(bodies),
            WorldInput::Settings(settings) => {
                // Not through `settings_mut`: replaying must not journal it a second time at the step.
                self.settings = (**settings).clone();
                self.forget_kept_statics();
                self.log(input.clone());
            }
        }
        Ok(())
    }

    /// Removes every body and contact and adds `bodies` afresh, keeping the settings: the world as
    /// `World::new` and `add_body` would build it (a scene's reset). The step count goes on: it is the
    /// session's clock.
    pub fn reset_bodies(&mut self, bodies: &[BodyDesc]) {
        let journal = self.journal.take();
        let settings = std::mem::take(&mut self.settings);
        let steps = self.steps;
        let profiling = self.stopwatch.on;
        // A settings change not yet journaled still is after the reset (it was lost from
        // recordings, found by fuzzing: sub-steps changed, then `r`, and the replay diverged).
        let settings_touched = self.settings_touched;
        // The joints belong to the scene as its bodies do: they stay, with no warm start.
        let mut joints = std::mem::take(&mut self.joints);
        *self = World::new(settings);
        self.stopwatch.on = profiling;
        for desc in bodies {
            self.add_body(*desc);
        }
        let count = self.bodies.len();
        joints.retain(|j| j.desc.b.index() < count && j.desc.a.is_none_or(|a| a.index() < count));
        for joint in &mut joints {
            joint.impulses = Default::default();
        }
        self.joints = joints;
        self.journal = journal;
        self.steps = steps;
        self.settings_touched = settings_touched;
        // Tagged with the step count it ended: a reader replays the steps before it, then resets.
        self.log(WorldInput::Reset);
    }

    /// Gives a body a new shape of the same density: its mass scales with the volume and its inertia
    /// is recomputed. It and the bodies touching it wake, and its manifolds are recomputed at the next
    /// step (the old ones describe the old surface). An invalid shape, or one whose mass or inertia
    /// would not be finite and > 0, is ignored.
    pub fn set_shape(&mut self, id: BodyId, shape: Shape) {
        let Some(body) = self.bodies.get(id.index()) else {
            return;
        };
        if !shape.is_valid() {
            return;
        }
        let mass = body.mass * (shape.volume() / body.shape.volume());
        let inertia = shape.principal_inertia(mass);
        if !(mass.is_finite()
            && mass > 0.0
            && inertia.is_finite()
            && inertia.cmpgt(Vec3::ZERO).all())
        {
            return;
        }
        self.log(WorldInput::Resize { body: id, shape });
        self.wake_island(id.0);
        self.wake_neighbours(id.0);
        let body = &mut self.bodies[id.index()];
        body.shape = shape;
        body.mass = mass;
        body.inv_mass = 1.0 / mass;
        body.inertia_local = inertia;
        body.inv_inertia_local = inertia.recip();
        body.sleep_time = 0.0;
        for contact in &mut self.contacts {
            if contact.a == id.0 || contact.b == id.0 {
                // A NaN pose is never within the reuse tolerance: the pair is collided again.
                contact.pose_a.position = Vec3::NAN;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Pose, Shape};

    #[test]
    fn a_settings_change_before_a_reset_is_journaled() {
        let ball = BodyDesc::dynamic(Shape::sphere(0.5), Pose::from_position(Vec3::Y), 1.0);
        let mut world = World::new(Settings::default());
        world.add_body(ball);
        world.start_journal();
        world.settings_mut().substeps = 5;
        world.reset_bodies(&[ball]);
        world.step();
        let journal = world.take_journal();
        assert!(
            journal
                .iter()
                .any(|(_, input)| matches!(input, WorldInput::Settings(s) if s.substeps == 5)),
            "{journal:?}"
        );
    }
}
