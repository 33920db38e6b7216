//! `nudge run --record FILE`: the session written as it is played (format in `recording`).

use std::path::Path;

use anyhow::Context;

use crate::app::App;
use crate::recording::Recorder;
use crate::scene::write::to_toml;

impl App {
    /// Starts recording into `path`: the world as it is now (as scene text, bit for bit), every
    /// setting, then every input as it is applied.
    pub fn start_recording(&mut self, path: &Path) -> anyhow::Result<()> {
        // Inputs made before now belong to no recording.
        self.absorb_inputs();
        let scene = self.scene_now();
        let text = to_toml(&scene, &[&format!("recorded from {}", self.scene.name)]);
        let recorder = Recorder::create(path, &text, self.world.settings())
            .with_context(|| format!("cannot write recording {}", path.display()))?;
        self.timeline.start_recording(recorder);
        self.timeline
            .record_camera(self.world.step_count(), self.camera.get());
        Ok(())
    }

    /// Writes the recording's end (the furthest step played); nothing if not recording.
    pub fn finish_recording(&mut self) -> anyhow::Result<()> {
        self.absorb_inputs();
        self.timeline
            .finish_recording()
            .context("cannot finish the recording")
    }
}
