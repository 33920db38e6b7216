//! Rewind and replay in the sandbox: `[` steps back through the timeline, `]` forward again, and a
//! recording plays through the same timeline (see [`crate::app::time::timeline`]).

use crate::app::App;
use crate::app::input::action::Action;
use crate::app::input::hand::Hand;
use crate::app::panels::look::BodyLook;
use crate::color::PALETTE;
use crate::geometry::Camera;
use crate::recording::Recording;

/// Steps one press of `[` or `]` moves: a quarter of a second at 60 Hz, so holding the key (at a
/// terminal's usual 30 repeats a second) scrubs at about 7 s a second.
pub const REWIND_STEP: u64 = 15;

/// What a replay shows besides the world: the recorded camera.
#[derive(Clone, Debug, Default)]
pub struct ReplayView {
    /// Camera changes, each with the step from which it was shown, in order.
    pub cameras: Vec<(u64, Camera)>,
}

impl App {
    /// The inputs and keyframes of this session (see [`crate::app::time::timeline`]).
    pub fn timeline(&self) -> &crate::app::time::timeline::Timeline {
        &self.timeline
    }

    /// The same, to change its memory bound.
    pub fn timeline_mut(&mut self) -> &mut crate::app::time::timeline::Timeline {
        &mut self.timeline
    }

    /// An app that plays `recording` from its start: the recorded inputs are the timeline's future,
    /// input that would change the world is ignored, the view follows the recorded camera.
    pub fn replaying(recording: &Recording, config: crate::app::AppConfig) -> App {
        let mut scene = recording.scene.clone();
        scene.settings = recording.settings.clone();
        let mut app = App::new(scene, config);
        app.timeline = crate::app::time::timeline::Timeline::with_future(
            app.scene.bodies.iter().map(|b| b.desc).collect(),
            &mut app.world,
            recording
                .inputs
                .iter()
                .map(|(step, input, _)| (*step, input.clone())),
            recording.end,
        );
        app.replay = Some(ReplayView {
            cameras: recording.cameras.clone(),
        });
        app.before_step_view();
        app.say(format!(
            "replaying {} steps · space pauses, . steps, [ ] rewind, q quits",
            recording.end
        ));
        app
    }

    /// Whether a key is let through while replaying: Ctrl keys, and pause, step, rewind, view and
    /// quit (see [`Action::replays`]).
    pub(crate) fn replay_allows(&self, ctrl: bool, action: Option<Action>) -> bool {
        self.replay.is_none() || ctrl || action.is_some_and(Action::replays)
    }

    /// Before each step: looks for bodies a timeline added, the replayed camera, the recorded one.
    pub(crate) fn before_step_view(&mut self) {
        while self.looks.len() < self.world.len() {
            // The colour `spawn` gives the body with this index.
            let color = PALETTE[self.looks.len() % PALETTE.len()];
            self.looks.push(BodyLook {
                color,
                scenery: false,
            });
        }
        let now = self.world.step_count();
        if let Some(replay) = &self.replay
            && let Some((_, camera)) = replay.cameras.iter().rev().find(|(s, _)| *s <= now)
        {
            self.camera.follow(*camera);
        }
        self.timeline.record_camera(now, self.camera.get());
        // Playing a rewound timeline forward: the status bar counts down to the present.
        let behind = self.timeline.rewound_steps(&self.world);
        if self.replay.is_none() && behind > 0 && !self.ui.paused() {
            let seconds = behind as f32 * self.world.settings().dt;
            self.say(format!(
                "rewound {seconds:.1} s (playing the inputs made then)"
            ));
        } else if behind == 0 && self.message.starts_with("rewound") {
            self.say("back at the present");
        }
        if self.replay.is_some() && now >= self.timeline.end() && !self.ui.paused() {
            self.ui.pause();
            self.say("end of the recording (q quits, [ rewinds)");
        }
        if let Some(err) = self.timeline.take_record_error() {
            self.say(err);
        }
    }

    /// `[`: back one rewind step (pausing), no further than the oldest keyframe.
    pub(crate) fn rewind_back(&mut self) {
        // What the keys did since the last step is an input of this timeline, not of the past.
        self.absorb_inputs();
        let now = self.world.step_count();
        let oldest = self.timeline.oldest();
        let target = now.saturating_sub(REWIND_STEP).max(oldest);
        self.timeline.rewind_to(&mut self.world, target);
        self.after_jump();
        if target == now {
            // From the timeline's end, not from now: at the oldest moment "now − oldest" is 0.
            let back = (self.timeline.end() - oldest) as f32 * self.world.settings().dt;
            self.say(format!(
                "can't rewind further: the oldest moment kept, {} s back",
                quarter_seconds(back)
            ));
        }
    }

    /// `]`: forward one rewind step along the timeline, re-simulating; no further than its end.
    pub(crate) fn rewind_forward(&mut self) {
        let end = self.timeline.end();
        let target = (self.world.step_count() + REWIND_STEP).min(end);
        while self.world.step_count() < target {
            self.step_physics();
        }
        self.after_jump();
    }

    /// The app follows a jump in time: paused, the hand let go, gravity's flag from the world.
    fn after_jump(&mut self) {
        self.ui.pause();
        self.hand = Hand::default();
        self.growth = None;
        // A body spawned after the point rewound to is gone: forget it (found by tests/app/fuzz.rs,
        // `<` on a spawned body after `[` indexed past the world).
        let len = self.world.len();
        self.selection.forget_from(len);
        self.clock.reset();
        self.ui
            .set_gravity_on(self.world.settings().gravity != glam::Vec3::ZERO);
        self.before_step_view();
        let behind = self.timeline.rewound_steps(&self.world);
        let seconds = behind as f32 * self.world.settings().dt;
        if self.replay.is_some() {
            // A replay's "present" is the recording's end: "rewound 41.3 s" a second into it read
            // as nonsense, so say where in the recording the picture is.
            let dt = self.world.settings().dt;
            let now = self.world.step_count() as f32 * dt;
            let end = self.timeline.end() as f32 * dt;
            self.say(format!(
                "at {now:.1} s of {end:.1} s ([ back, ] forward, space plays)"
            ));
            return;
        }
        self.say(if behind == 0 {
            "at the present (space runs)".to_string()
        } else {
            format!(
                "rewound {} s ([ back, ] forward, space plays)",
                quarter_seconds(seconds)
            )
        });
    }
}

/// Seconds to the hundredth, with one decimal when that says it all: the ring keeps a snapshot every
/// quarter second, and `{:.1}` showed the first one as "rewound 0.2 s" (0.25 rounded to even).
fn quarter_seconds(seconds: f32) -> String {
    let mut text = format!("{seconds:.2}");
    if text.ends_with('0') {
        text.pop();
    }
    text
}

#[cfg(test)]
mod tests {
    use super::quarter_seconds;

    #[test]
    fn quarter_seconds_keep_their_hundredths_and_whole_ones_one_decimal() {
        assert_eq!(quarter_seconds(0.25), "0.25");
        assert_eq!(quarter_seconds(2.5), "2.5");
        assert_eq!(quarter_seconds(2.0), "2.0");
        assert_eq!(quarter_seconds(1.75), "1.75");
    }
}
