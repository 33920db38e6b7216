//! The step's time by stage (the physics' [`StepProfile`]): the table `nudge sim --profile` prints
//! after its run, and `nudge bench physics`'s per-scene rows with what profiling itself costs.
//!
//! The cost is measured on two copies of one world stepped in turn, one profiled and one not: they
//! hold the same state at every step (profiling changes nothing in the physics), so each pair of
//! steps does the same work and the machine's drift hits both alike.

use std::io::{self, Write};
use std::time::Instant;

use serde::Serialize;

use super::table::Table;
use crate::physics::{Stage, StepProfile, World};
use crate::scene::{Scene, cases};
use crate::util::median;

/// A run's stage times, summed over its steps.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StageTotals {
    pub profile: StepProfile,
    pub steps: u64,
}

impl StageTotals {
    /// Adds the world's last step (a no-op unless it is profiling).
    pub fn record(&mut self, world: &World) {
        if let Some(profile) = world.step_profile() {
            self.profile.add(profile);
            self.steps += 1;
        }
    }

    /// Mean ms per step of each stage, in step order.
    pub fn per_step_ms(&self) -> [(&'static str, f64); 7] {
        self.profile.per_step_ms(self.steps)
    }

    /// The table: each stage's mean ms per step and its share of the step, then the total.
    pub fn write(&self, out: &mut dyn Write) -> io::Result<()> {
        let stages = self.per_step_ms();
        let total: f64 = stages.iter().map(|(_, ms)| ms).sum();
        writeln!(
            out,
            "profile: mean wall-clock ms per step by stage, over {} steps",
            self.steps
        )?;
        let mut table = Table::new(&["stage", "ms/step", "share"]);
        for (name, ms) in stages {
            table.push(vec![name.to_string(), format!("{ms:.4}"), share(ms, total)]);
        }
        table.push(vec![
            "total".into(),
            format!("{total:.4}"),
            share(total, total),
        ]);
        table.write(out)
    }
}

fn share(ms: f64, total: f64) -> String {
    if total > 0.0 {
        format!("{:.1}%", 100.0 * ms / total)
    } else {
        "-".into()
    }
}

/// One scene's row: its stages' mean ms per step, and the step's median with profiling off and on.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StageRow {
    pub scene: String,
    pub steps: usize,
    /// Mean ms per step of each stage, in step order, keyed by the stage's name.
    #[serde(serialize_with = "stage_map")]
    pub stages: [(&'static str, f64); 7],
    #[serde(serialize_with = "super::physics::rounded_ms")]
    pub off_ms: f64,
    #[serde(serialize_with = "super::physics::rounded_ms")]
    pub on_ms: f64,
}

impl StageRow {
    /// What profiling adds to a step, in percent of the unprofiled step (noise makes it negative
    /// at times).
    pub fn overhead_percent(&self) -> f64 {
        100.0 * (self.on_ms / self.off_ms - 1.0)
    }
}

fn stage_map<S: serde::Serializer>(
    stages: &[(&'static str, f64); 7],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeMap;
    let mut map = serializer.serialize_map(Some(stages.len()))?;
    for (name, ms) in stages {
        map.serialize_entry(name, &((ms * 1e4).round() / 1e4))?;
    }
    map.end()
}

/// The scenes: a rain falling awake, the pyramid settling awake, the pyramid asleep after settling.
pub fn run(quick: bool) -> Vec<StageRow> {
    let steps = if quick { 60 } else { 300 };
    let mut awake_rain = cases::rain(1000);
    awake_rain.settings.sleep = false;
    let mut awake_pyramid = cases::pyramid(20);
    awake_pyramid.settings.sleep = false;
    [
        (awake_rain, 0, "rain(1000), first steps, sleeping off"),
        (awake_pyramid, 0, "pyramid(20), first steps, sleeping off"),
        (cases::pyramid(20), 600, "pyramid(20) settled"),
    ]
    .into_iter()
    .map(|(scene, settle, name)| {
        super::progress!("bench physics: stages of {name}          \r");
        time_stages(&scene, settle, steps, name)
    })
    .collect()
}

/// Steps a profiled and an unprofiled copy of `scene` in turn, `steps` times after `settle` untimed.
fn time_stages(scene: &Scene, settle: usize, steps: usize, name: &str) -> StageRow {
    let mut plain = scene.build_world();
    for _ in 0..settle {
        plain.step();
    }
    let mut profiled = scene.build_world();
    for _ in 0..settle {
        profiled.step();
    }
    profiled.set_profiling(true);
    let mut totals = StageTotals::default();
    let (mut off, mut on) = (Vec::with_capacity(steps), Vec::with_capacity(steps));
    for i in 0..steps {
        // Alternate which goes first, so neither always runs on a cache the other warmed.
        let order: [bool; 2] = if i % 2 == 0 {
            [false, true]
        } else {
            [true, false]
        };
        for profiling in order {
            let world = if profiling { &mut profiled } else { &mut plain };
            let start = Instant::now();
            world.step();
            let ms = start.elapsed().as_secs_f64() * 1e3;
            if profiling {
                on.push(ms);
                totals.record(world);
            } else {
                off.push(ms);
            }
        }
    }
    StageRow {
        scene: name.to_string(),
        steps,
        stages: totals.per_step_ms(),
        off_ms: median(&mut off),
        on_ms: median(&mut on),
    }
}

/// The per-scene table.
pub fn print_table(rows: &[StageRow], out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "physics: the step by stage (mean ms per step), and the median step with the profile off and on (noisy)"
    )?;
    let mut headers = vec!["scene"];
    headers.extend(Stage::ALL.iter().map(|s| s.name()));
    headers.extend(["off ms", "on ms", "cost"]);
    let mut table = Table::new(&headers);
    for row in rows {
        let mut cells = vec![row.scene.clone()];
        cells.extend(row.stages.iter().map(|(_, ms)| format!("{ms:.4}")));
        cells.push(format!("{:.4}", row.off_ms));
        cells.push(format!("{:.4}", row.on_ms));
        cells.push(format!("{:+.1}%", row.overhead_percent()));
        table.push(cells);
    }
    table.write(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_falling_pyramid_is_timed_in_every_busy_stage_and_the_table_sums_them() {
        let row = time_stages(&cases::pyramid(4), 0, 20, "pyramid(4)");
        for (name, ms) in &row.stages[..6] {
            assert!(*ms > 0.0, "{name} never timed");
        }
        assert!(row.off_ms > 0.0 && row.on_ms > 0.0);
        let mut text = Vec::new();
        print_table(&[row], &mut text).unwrap();
        let text = String::from_utf8(text).unwrap();
        for stage in Stage::ALL {
            assert!(text.contains(stage.name()), "{text}");
        }
        assert!(text.contains("| pyramid(4) "), "{text}");
    }

    #[test]
    fn totals_count_only_profiled_steps_and_print_every_stage_with_its_share() {
        let scene = cases::pyramid(3);
        let mut world = scene.build_world();
        let mut totals = StageTotals::default();
        world.step();
        totals.record(&world);
        assert_eq!(totals.steps, 0, "an unprofiled step adds nothing");
        world.set_profiling(true);
        for _ in 0..5 {
            world.step();
            totals.record(&world);
        }
        assert_eq!(totals.steps, 5);
        let mut text = Vec::new();
        totals.write(&mut text).unwrap();
        let text = String::from_utf8(text).unwrap();
        assert!(text.contains("over 5 steps"), "{text}");
        for stage in Stage::ALL {
            assert!(text.contains(stage.name()), "{text}");
        }
        assert!(
            text.contains("| total ") && text.contains("100.0%"),
            "{text}"
        );
    }
}
