//! The timeline: every input the world has been given, and a ring of snapshots to rewind through.
//!
//! The world journals each input it is given (see `physics::input`). The app absorbs the journal at
//! every step boundary into this timeline, which keeps
//! - the inputs, each with the step it was applied at, oldest first, and a cursor: the inputs
//!   before it have been applied to the world, those after it are the future of a rewound world;
//! - keyframes: a world snapshot every [`KEYFRAME_STEPS`] steps, covering at least the last
//!   [`REWIND_SECONDS`] and at most [`MAX_REWIND_BYTES`] (the oldest are dropped first);
//! - `end`: the furthest step this timeline reached.
//!
//! Rewinding to step t restores the last keyframe at or before t and re-simulates to t, applying the
//! timeline's inputs at their steps: the world is bit for bit what it was at t (restores are exact,
//! stepping is deterministic). Stepping on from there applies the inputs still ahead, so forward after
//! back gives the same world as before. A new input while rewound cuts the future off: the timeline
//! goes on from there (and a recording says so, keeping the timeline actually played).
//!
//! Keyframes plus re-simulation keep memory low: a snapshot holds every body and contact (a few
//! hundred bytes each), one every half second instead of every step.

use std::collections::VecDeque;

use crate::physics::{BodyDesc, World, WorldInput, WorldSnapshot};
use crate::recording::Recorder;

/// Steps between keyframes: at 60 Hz, half a second; a rewind re-simulates at most this many steps.
pub const KEYFRAME_STEPS: u64 = 30;
/// The span kept for rewinding, s (at least; one keyframe more than it is kept).
pub const REWIND_SECONDS: f32 = 30.0;
/// Most bytes of keyframes and inputs kept: a scene so large that 30 s of keyframes would need more
/// keeps less time (rain(4000)'s keyframes are over 2 MB each).
pub const MAX_REWIND_BYTES: usize = 128 << 20;

pub struct Timeline {
    /// The scene's bodies: what a `Reset` input rebuilds.
    scene_bodies: Vec<BodyDesc>,
    inputs: VecDeque<(u64, WorldInput)>,
    /// Index in `inputs` of the first input not yet applied to the world.
    next: usize,
    keyframes: VecDeque<WorldSnapshot>,
    keyframe_bytes: usize,
    end: u64,
    /// Most bytes of keyframes and inputs kept (default [`MAX_REWIND_BYTES`]).
    max_bytes: usize,
    /// Where inputs are recorded, if anywhere; cleared by the first write error.
    recorder: Option<Recorder>,
    /// A write error the app has not shown yet.
    record_error: Option<String>,
}

impl Timeline {
    /// Writes every input from now on to `recorder` (see `record`).
    pub(crate) fn start_recording(&mut self, recorder: Recorder) {
        self.recorder = Some(recorder);
    }

    /// Whether inputs are being recorded (a recording holds one scene).
    pub(crate) fn is_recording(&self) -> bool {
        self.recorder.is_some()
    }

    /// The write error that stopped the recording, once: the app shows it and forgets it.
    pub(crate) fn take_record_error(&mut self) -> Option<String> {
        self.record_error.take()
    }

    /// A timeline starting from `world` as it is now, which starts journaling.
    pub fn new(scene_bodies: Vec<BodyDesc>, world: &mut World) -> Self {
        world.start_journal();
        let start = world.snapshot();
        let mut timeline = Self {
            scene_bodies,
            inputs: VecDeque::new(),
            next: 0,
            keyframe_bytes: start.bytes(),
            end: world.step_count(),
            max_bytes: MAX_REWIND_BYTES,
            keyframes: VecDeque::from([start]),
            recorder: None,
            record_error: None,
        };
        timeline.keyframes.shrink_to_fit();
        timeline
    }

    /// A timeline whose future is given: `inputs` (with their steps) up to step `end`, as a
    /// recording holds them. `world` is at its start.
    pub fn with_future(
        scene_bodies: Vec<BodyDesc>,
        world: &mut World,
        inputs: impl IntoIterator<Item = (u64, WorldInput)>,
        end: u64,
    ) -> Self {
        let mut timeline = Self::new(scene_bodies, world);
        timeline.inputs.extend(inputs);
        timeline.end = end;
        timeline
    }

    /// Steps the world is behind the furthest this timeline reached.
    pub fn rewound_steps(&self, world: &World) -> u64 {
        self.end.saturating_sub(world.step_count())
    }

    /// The furthest step reached.
    pub fn end(&self) -> u64 {
        self.end
    }

    /// The oldest step the world can be rewound to.
    pub fn oldest(&self) -> u64 {
        self.keyframes.front().map_or(0, WorldSnapshot::step)
    }

    /// Bytes held: keyframes and inputs.
    pub fn bytes(&self) -> usize {
        self.keyframe_bytes + self.inputs.len() * std::mem::size_of::<(u64, WorldInput)>()
    }

    /// Sets the most bytes kept (the oldest keyframes go first; one is always kept).
    pub fn set_max_bytes(&mut self, bytes: usize) {
        self.max_bytes = bytes;
    }

    /// Keyframes held.
    pub fn keyframe_count(&self) -> usize {
        self.keyframes.len()
    }

    /// Takes the inputs the world journaled since the last call (new ones, from the app) into the
    /// timeline, and returns how many there were. While rewound, a new input cuts off the future it
    /// would change.
    pub fn absorb(&mut self, world: &mut World) -> usize {
        let new = world.take_journal();
        if new.is_empty() {
            return 0;
        }
        let count = new.len();
        let now = world.step_count();
        if self.next < self.inputs.len() || now < self.end {
            self.inputs.truncate(self.next);
            self.keyframes.retain(|k| k.step() <= now);
            self.keyframe_bytes = self.keyframes.iter().map(WorldSnapshot::bytes).sum();
            self.end = now;
            // A recording drops what it wrote from `now` on, then repeats the inputs at `now` that
            // were applied before this one.
            let applied_now: Vec<(u64, WorldInput)> = self
                .inputs
                .iter()
                .filter(|(s, _)| *s == now)
                .cloned()
                .collect();
            self.record(|r| {
                r.truncate(now)?;
                r.inputs(&applied_now)
            });
        }
        self.record(|r| r.inputs(&new));
        self.inputs.extend(new);
        self.next = self.inputs.len();
        count
    }

    /// Applies the timeline's inputs due at the world's current step (a rewound world's future).
    pub fn apply_due(&mut self, world: &mut World) {
        let now = world.step_count();
        let mut applied = false;
        while let Some((step, input)) = self.inputs.get(self.next) {
            if *step != now {
                break;
            }
            // Inputs were checked when made or read; one that no longer applies is skipped.
            let _ = world.apply_input(input, &self.scene_bodies);
            self.next += 1;
            applied = true;
        }
        if applied {
            // They are in the timeline already.
            world.take_journal();
        }
    }

    /// After a step: the end moves on, a keyframe is taken on the keyframe grid, and the oldest are
    /// dropped beyond the span and the memory bound.
    pub fn after_step(&mut self, world: &World) {
        let now = world.step_count();
        self.end = self.end.max(now);
        let newest = self.keyframes.back().map_or(0, WorldSnapshot::step);
        if now % KEYFRAME_STEPS == 0 && now > newest {
            let keyframe = world.snapshot();
            self.keyframe_bytes += keyframe.bytes();
            self.keyframes.push_back(keyframe);
        }
        let span = (REWIND_SECONDS / world.settings().dt).ceil() as u64;
        while self.keyframes.len() > 1
            && (self.keyframes[1].step() + span <= self.end || self.bytes() > self.max_bytes)
        {
            let dropped = self.keyframes.pop_front().expect("more than one");
            self.keyframe_bytes -= dropped.bytes();
            let oldest = self.oldest();
            while self.inputs.front().is_some_and(|(s, _)| *s < oldest) && self.next > 0 {
                self.inputs.pop_front();
                self.next -= 1;
            }
        }
    }

    /// Rewinds the world to `step` (no earlier than the oldest keyframe, no later than now) and
    /// returns the step reached.
    pub fn rewind_to(&mut self, world: &mut World, step: u64) -> u64 {
        let target = step.max(self.oldest()).min(world.step_count());
        let Some(keyframe) = self.keyframes.iter().rev().find(|k| k.step() <= target) else {
            return world.step_count();
        };
        world.restore(keyframe);
        self.next = self.inputs.partition_point(|(s, _)| *s < keyframe.step());
        while world.step_count() < target {
            self.apply_due(world);
            world.step();
        }
        world.take_journal();
        target
    }

    fn record(&mut self, write: impl FnOnce(&mut Recorder) -> std::io::Result<()>) {
        if let Some(recorder) = &mut self.recorder
            && let Err(err) = write(recorder)
        {
            self.record_error = Some(format!("recording stopped: {err}"));
            self.recorder = None;
        }
    }

    /// Records the camera shown from the current step on (a no-op if unchanged or not recording).
    pub fn record_camera(&mut self, step: u64, camera: &crate::geometry::Camera) {
        self.record(|r| r.camera(step, camera));
    }

    /// Flushes the recording (once a frame, so a crash loses little).
    pub fn flush_recording(&mut self) {
        self.record(Recorder::flush);
    }

    /// Ends the recording: the session ran to the end of this timeline.
    pub fn finish_recording(&mut self) -> std::io::Result<()> {
        match self.recorder.take() {
            Some(recorder) => recorder.finish(self.end),
            None => Ok(()),
        }
    }
}
