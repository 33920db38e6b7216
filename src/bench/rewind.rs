//! The rewind ring's cost: bytes held for the last 30 s and time per step spent on keyframes, on
//! the pyramid (settling, then asleep) and rain(1000) (falling into a pile).

use std::time::Instant;

use crate::app::time::timeline::{KEYFRAME_STEPS, REWIND_SECONDS, Timeline};
use crate::scene::{Scene, builtin, cases};

/// One scene's figures.
#[derive(serde::Serialize)]
pub struct RewindRow {
    pub scene: String,
    pub bodies: usize,
    pub steps: u64,
    /// Bytes the timeline held at the end.
    pub bytes: usize,
    pub keyframes: usize,
    /// Seconds of history it covered.
    pub seconds: f32,
    /// Mean wall time per step of keeping the timeline (keyframes, bounds), µs.
    pub us_per_step: f64,
    /// Mean wall time of one keyframe, µs.
    pub us_per_keyframe: f64,
    /// Wall time of rewinding 1 s (restore + re-simulation), ms.
    pub rewind_1s_ms: f64,
}

fn measure(name: &str, scene: &Scene, steps: u64) -> RewindRow {
    let mut world = scene.build_world();
    let mut timeline = Timeline::new(scene.bodies.iter().map(|b| b.desc).collect(), &mut world);
    let mut timeline_s = 0.0;
    for _ in 0..steps {
        timeline.absorb(&mut world);
        world.step();
        let start = Instant::now();
        timeline.after_step(&world);
        timeline_s += start.elapsed().as_secs_f64();
    }
    let keyframes_taken = steps / KEYFRAME_STEPS;
    let now = world.step_count();
    let back = (1.0 / world.settings().dt).round() as u64;
    let start = Instant::now();
    timeline.rewind_to(&mut world, now - back);
    let rewind_1s_ms = start.elapsed().as_secs_f64() * 1e3;
    RewindRow {
        scene: name.to_string(),
        bodies: world.len(),
        steps,
        bytes: timeline.bytes(),
        keyframes: timeline.keyframe_count(),
        seconds: (now - timeline.oldest()) as f32 * world.settings().dt,
        us_per_step: timeline_s * 1e6 / steps as f64,
        us_per_keyframe: timeline_s * 1e6 / keyframes_taken.max(1) as f64,
        rewind_1s_ms,
    }
}

/// Runs both scenes for 31 s of simulated time (a few seconds with `quick`, whose bytes then cover
/// less than the full span).
pub fn run(quick: bool) -> Vec<RewindRow> {
    let seconds = if quick { 3.0 } else { REWIND_SECONDS + 1.0 };
    let steps = (seconds * 60.0) as u64;
    vec![
        measure("pyramid(20)", &cases::pyramid(20), steps),
        measure(
            "rain(1000)",
            &builtin::by_name("rain").expect("built in"),
            steps,
        ),
    ]
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(rows: &[RewindRow], out: &mut dyn std::io::Write) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "rewind: the timeline's keyframes (one every {} steps) over the run; cost per step is the keyframes' time spread over every step",
        crate::app::time::timeline::KEYFRAME_STEPS
    )?;
    let mut table = Table::new(&[
        "scene",
        "bodies",
        "steps",
        "bytes held",
        "keyframes",
        "seconds kept",
        "us/step",
        "us/keyframe",
        "rewind 1 s, ms",
    ]);
    for r in rows {
        table.push(vec![
            r.scene.clone(),
            r.bodies.to_string(),
            r.steps.to_string(),
            r.bytes.to_string(),
            r.keyframes.to_string(),
            format!("{:.1}", r.seconds),
            format!("{:.2}", r.us_per_step),
            format!("{:.1}", r.us_per_keyframe),
            format!("{:.2}", r.rewind_1s_ms),
        ]);
    }
    table.write(out)
}
