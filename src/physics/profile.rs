//! Where a step's time goes, by stage: a read-only view for the inspector, `nudge sim --profile` and
//! `nudge bench physics`. Off by default; off, each stage boundary costs one predictable branch and
//! no clock read, so the step is not slower (measured in `nudge bench physics`).
//!
//! The stages are those of the step (see [`crate::physics::world`]): the broad phase (with waking sleepers
//! it touches), the narrow phase (collide, manifold reuse), prepare (solver bodies, the contact
//! graph's order, constraints and lanes), solve (warm start, the soft passes, the shock pass and the
//! relax passes, every sub-step), integrate (velocities and positions every sub-step, and writing
//! the results back), restitution and storing impulses, and sleep (islands).

use std::time::{Duration, Instant};

/// One stage of the step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    BroadPhase,
    NarrowPhase,
    Prepare,
    Solve,
    Integrate,
    RestitutionStore,
    Sleep,
}

impl Stage {
    /// Every stage, in step order.
    pub const ALL: [Stage; 7] = [
        Stage::BroadPhase,
        Stage::NarrowPhase,
        Stage::Prepare,
        Stage::Solve,
        Stage::Integrate,
        Stage::RestitutionStore,
        Stage::Sleep,
    ];

    /// A short name for tables.
    pub fn name(self) -> &'static str {
        match self {
            Stage::BroadPhase => "broad phase",
            Stage::NarrowPhase => "narrow phase",
            Stage::Prepare => "prepare",
            Stage::Solve => "solve",
            Stage::Integrate => "integrate",
            Stage::RestitutionStore => "restitution+store",
            Stage::Sleep => "sleep",
        }
    }
}

/// Wall time per stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepProfile {
    /// Indexed like [`Stage::ALL`].
    pub stages: [Duration; 7],
}

impl StepProfile {
    pub fn get(&self, stage: Stage) -> Duration {
        self.stages[stage as usize]
    }

    /// The sum over the stages.
    pub fn total(&self) -> Duration {
        self.stages.iter().sum()
    }

    /// Adds `other`'s times to these (to total a run).
    pub fn add(&mut self, other: &StepProfile) {
        for (mine, theirs) in self.stages.iter_mut().zip(&other.stages) {
            *mine += *theirs;
        }
    }

    /// (name, ms) per stage, each divided by `steps` (≥ 1): a mean per step.
    pub fn per_step_ms(&self, steps: u64) -> [(&'static str, f64); 7] {
        let n = steps.max(1) as f64;
        Stage::ALL.map(|s| (s.name(), self.get(s).as_secs_f64() * 1e3 / n))
    }
}

impl crate::physics::World {
    /// Turns the per-stage profile of each step on or off (off by default; a reset keeps it).
    pub fn set_profiling(&mut self, on: bool) {
        self.stopwatch.on = on;
        self.stopwatch.profile = StepProfile::default();
    }

    pub fn is_profiling(&self) -> bool {
        self.stopwatch.on
    }

    /// The last step's time per stage, while profiling is on.
    pub fn step_profile(&self) -> Option<&StepProfile> {
        self.stopwatch.on.then_some(&self.stopwatch.profile)
    }
}

/// Times the stages of one step when on: `start` at the top of the step, `lap(stage)` at the end of
/// each stage charges the time since the last mark to it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Stopwatch {
    pub(crate) on: bool,
    /// The last mark of this step (`None` while off).
    last: Option<Instant>,
    /// The last step's (or, mid-step, this step's so far) times.
    pub(crate) profile: StepProfile,
}

impl Stopwatch {
    #[inline]
    pub(crate) fn start(&mut self) {
        if self.on {
            self.profile = StepProfile::default();
            self.last = Some(Instant::now());
        }
    }

    #[inline]
    pub(crate) fn lap(&mut self, stage: Stage) {
        if let Some(last) = self.last {
            let now = Instant::now();
            self.profile.stages[stage as usize] += now - last;
            self.last = Some(now);
        }
    }

    /// Ends the step's timing (the next `start` begins afresh).
    #[inline]
    pub(crate) fn stop(&mut self) {
        self.last = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` unit boxes stacked 5 cm apart on a floor (the physics layer builds its own worlds: it
    /// must not import the scene layer).
    fn stack(n: usize) -> crate::physics::World {
        use crate::geometry::{Pose, Shape};
        use crate::physics::{BodyDesc, Settings};
        use glam::Vec3;
        let mut world = crate::physics::World::new(Settings::default());
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ));
        for i in 0..n {
            world.add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::splat(0.5)),
                Pose::from_position(Vec3::new(0.0, 0.55 + 1.05 * i as f32, 0.0)),
                1.0,
            ));
        }
        world
    }

    #[test]
    fn a_profiled_world_times_every_busy_stage_and_steps_exactly_as_an_unprofiled_one() {
        let (mut plain, mut profiled) = (stack(6), stack(6));
        profiled.set_profiling(true);
        assert!(plain.step_profile().is_none());
        let mut total = StepProfile::default();
        for _ in 0..60 {
            plain.step();
            profiled.step();
            total.add(profiled.step_profile().unwrap());
        }
        for stage in [
            Stage::BroadPhase,
            Stage::NarrowPhase,
            Stage::Prepare,
            Stage::Solve,
            Stage::Integrate,
            Stage::RestitutionStore,
        ] {
            assert!(total.get(stage) > Duration::ZERO, "{stage:?} never timed");
        }
        for (a, b) in plain.bodies().iter().zip(profiled.bodies()) {
            assert_eq!(a.pose(), b.pose());
            assert_eq!(a.linear_velocity(), b.linear_velocity());
        }
        // A reset keeps the profile on.
        profiled.reset_bodies(&[]);
        assert!(profiled.is_profiling());
    }

    #[test]
    fn laps_charge_the_time_since_the_last_mark_and_nothing_while_off() {
        let mut watch = Stopwatch::default();
        watch.start();
        watch.lap(Stage::Solve);
        assert_eq!(watch.profile, StepProfile::default(), "off: nothing timed");
        watch.on = true;
        watch.start();
        std::thread::sleep(Duration::from_millis(2));
        watch.lap(Stage::Solve);
        watch.lap(Stage::Sleep);
        watch.stop();
        watch.lap(Stage::Solve);
        let solve = watch.profile.get(Stage::Solve);
        assert!(solve >= Duration::from_millis(2), "{solve:?}");
        assert_eq!(
            watch.profile.total(),
            solve + watch.profile.get(Stage::Sleep)
        );
    }
}
