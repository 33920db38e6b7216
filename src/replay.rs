//! `nudge replay FILE`: a recorded session played again, in the terminal or headless.
//!
//! Headless (`--trace OUT.csv`), the recording's world is stepped `end` times with each input
//! applied at its step, exactly as the sandbox applied it, and every body's state is written after
//! every step in the `nudge sim` trace format: two replays give the same bytes, and the same as the
//! live session's trace. In the terminal it is the sandbox's own timeline playing the recording's
//! inputs (see `app::time::rewind`).

use std::io::Write;

use crate::physics::BodyDesc;
use crate::recording::{Recording, RecordingError};
use crate::sim::{TRACE_HEADER, write_trace_rows};

/// Writes the trace of the recorded session: the initial state as step 0, then every step.
pub fn write_trace(recording: &Recording, out: &mut impl Write) -> anyhow::Result<()> {
    let mut world = recording.scene.build_world_with(recording.settings.clone());
    let bodies: Vec<BodyDesc> = recording.scene.bodies.iter().map(|b| b.desc).collect();
    writeln!(out, "{TRACE_HEADER}")?;
    write_trace_rows(out, 0, &world)?;
    let mut inputs = recording.inputs.iter().peekable();
    for _ in 0..recording.end {
        let now = world.step_count();
        while let Some((step, input, location)) = inputs.next_if(|(step, ..)| *step == now) {
            world
                .apply_input(input, &bodies)
                .map_err(|missing| RecordingError {
                    source_name: recording.scene.name.clone(),
                    location: Some(*location),
                    message: format!("step {step}: body {} does not exist", missing.0.0),
                })?;
        }
        world.step();
        write_trace_rows(out, world.step_count(), &world)?;
    }
    Ok(())
}
