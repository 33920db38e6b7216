//! `nudge sim`: run a scene's physics with no terminal, time the steps, optionally trace every body.
//!
//! Output contract (tests/cli/sim_cli.rs holds it):
//! - the last line of stdout is exactly `steps=N bodies=M mean_ms=X median_ms=Y` (X, Y with 4 decimals):
//!   wall-clock time of `World::step` alone, the trace writing is not timed;
//! - with `--profile`, the table of the step's stages (mean ms per step and share, see
//!   `bench::stages`) comes before it;
//! - the trace CSV has the header `step,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz`, then one row per body
//!   per step in scene order (statics included), step 0 being the initial state: (steps + 1) × bodies rows.
//!   Floats are written in Rust's shortest round-trip form, so each parses back to the identical f32
//!   (`NaN`, `inf` and `-inf` included);
//! - when bodies pile up beyond the contact caps (`physics::contact_cap`), the first step that
//!   ignored pairs is reported once on stderr;
//! - a body whose state stops being finite is reported once on stderr; the run goes on, the summary
//!   line is printed, and then `sim` fails (status 1): a non-finite state is an engine failure.
//!
//! Exit status (set by `cli`): bad arguments — `--steps` over [`MAX_STEPS`], `--substeps` or
//! `--iterations` outside 1..=64, a trace path that is a directory or whose directory does not
//! exist — are caught by [`SimOptions::validate`] before anything runs: status 2. A trace file the
//! operating system refuses to create or write (permissions, full disk) is a runtime failure: status
//! 1, with the path and the OS's reason.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;

use crate::bench::stages::StageTotals;
use crate::physics::World;
use crate::physics::broad::contact_cap::{MAX_PAIRS, MAX_PAIRS_PER_BODY};
use crate::physics::limits::{MAX_ITERATIONS, MAX_SUBSTEPS};
use crate::scene::Scene;
use crate::util::{SplitMix64, median};

/// Most steps `sim` and `snapshot` run: 10 million, 46 hours at 60 Hz.
pub const MAX_STEPS: u64 = 10_000_000;

/// What `nudge sim` was asked to do.
#[derive(Clone, Debug, Default)]
pub struct SimOptions {
    /// Steps to run; 0 only prints the summary (and the initial state to the trace).
    pub steps: u64,
    /// CSV file to write every body's state to, after every step.
    pub trace: Option<PathBuf>,
    /// Sub-steps per step (≥ 1); `None` keeps the scene's.
    pub substeps: Option<u32>,
    /// Solver iterations per sub-step (≥ 1); `None` keeps the scene's.
    pub iterations: Option<u32>,
    /// Whether bodies at rest may fall asleep.
    pub sleep: bool,
    /// Time the step's stages and print their table after the run (before the summary line).
    pub profile: bool,
}

impl SimOptions {
    /// Rejects values the solver cannot use and trace paths that cannot be a file to write; the message
    /// names the flag.
    pub fn validate(&self) -> Result<(), String> {
        if self.steps > MAX_STEPS {
            return Err(format!(
                "--steps must be at most {MAX_STEPS} (46 hours of simulated time), got {}",
                self.steps
            ));
        }
        if let Some(n) = self.substeps
            && !(1..=MAX_SUBSTEPS).contains(&n)
        {
            return Err(format!(
                "--substeps must be at least 1 and at most {MAX_SUBSTEPS}, got {n}"
            ));
        }
        if let Some(n) = self.iterations
            && !(1..=MAX_ITERATIONS).contains(&n)
        {
            return Err(format!(
                "--iterations must be at least 1 and at most {MAX_ITERATIONS}, got {n}"
            ));
        }
        if let Some(path) = &self.trace {
            validate_trace_path(path)?;
        }
        Ok(())
    }
}

fn validate_trace_path(path: &Path) -> Result<(), String> {
    let shown = path.display();
    if path.as_os_str().is_empty() {
        return Err("--trace needs a file path".into());
    }
    if path.is_dir() {
        return Err(format!("--trace {shown}: is a directory, not a file"));
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(format!(
            "--trace {shown}: directory {} does not exist",
            parent.display()
        ));
    }
    Ok(())
}

/// Step times kept for the median: all of them up to this many, a uniform sample of this many beyond.
pub const MAX_TIMING_SAMPLES: usize = 1 << 20;

/// Wall-clock step times: the exact mean, and the median of all samples or (past
/// [`MAX_TIMING_SAMPLES`]) of a uniform reservoir sample (Vitter's algorithm R), so memory stays bounded
/// however many steps are asked for.
struct StepTimes {
    count: u64,
    sum_ms: f64,
    samples: Vec<f64>,
    rng: SplitMix64,
}

impl StepTimes {
    fn new(expected: u64) -> Self {
        Self {
            count: 0,
            sum_ms: 0.0,
            samples: Vec::with_capacity(expected.min(MAX_TIMING_SAMPLES as u64) as usize),
            rng: SplitMix64(0x5eed),
        }
    }

    fn push(&mut self, ms: f64) {
        self.count += 1;
        self.sum_ms += ms;
        if self.samples.len() < MAX_TIMING_SAMPLES {
            self.samples.push(ms);
        } else {
            let slot = self.rng.next_u64() % self.count;
            if let Some(sample) = self.samples.get_mut(slot as usize) {
                *sample = ms;
            }
        }
    }

    fn mean(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.sum_ms / self.count as f64
        }
    }
}

/// Runs the simulation and prints `steps=N bodies=M mean_ms=X median_ms=Y` as the last line.
pub fn run(scene: &Scene, options: &SimOptions, out: &mut dyn Write) -> anyhow::Result<()> {
    let mut settings = scene.settings.clone();
    if let Some(substeps) = options.substeps {
        settings.substeps = substeps;
    }
    if let Some(iterations) = options.iterations {
        settings.iterations = iterations;
    }
    settings.sleep = options.sleep;
    let mut world = scene.build_world_with(settings);

    let mut trace = match &options.trace {
        Some(path) => {
            let file = File::create(path)
                .with_context(|| format!("cannot create trace file {}", path.display()))?;
            let mut writer = BufWriter::with_capacity(1 << 16, file);
            writeln!(writer, "{TRACE_HEADER}")
                .and_then(|()| write_trace_rows(&mut writer, 0, &world))
                .with_context(|| format!("cannot write trace file {}", path.display()))?;
            Some((writer, path))
        }
        None => None,
    };

    world.set_profiling(options.profile);
    let mut stages = StageTotals::default();
    let mut times = StepTimes::new(options.steps);
    let mut non_finite = first_non_finite(&world).map(|body| (body, 0));
    let mut warned_over_cap = false;
    for step in 1..=options.steps {
        let start = Instant::now();
        world.step();
        times.push(start.elapsed().as_secs_f64() * 1e3);
        stages.record(&world);
        if let Some((writer, path)) = trace.as_mut() {
            write_trace_rows(writer, step, &world)
                .with_context(|| format!("cannot write trace file {}", path.display()))?;
        }
        let over = world.pairs_over_cap();
        if over > 0 && !warned_over_cap {
            eprintln!(
                "nudge: warning: step {step}: {over} touching pairs over the contact caps \
                 ({MAX_PAIRS_PER_BODY} per body, {MAX_PAIRS} in all) were ignored; those bodies pass through each other"
            );
            warned_over_cap = true;
        }
        if non_finite.is_none()
            && let Some(body) = first_non_finite(&world)
        {
            eprintln!("nudge: warning: body {body} has a non-finite state after step {step}");
            non_finite = Some((body, step));
        }
    }
    if let Some((mut writer, path)) = trace {
        writer
            .flush()
            .with_context(|| format!("cannot write trace file {}", path.display()))?;
    }

    if options.profile {
        stages.write(out)?;
    }
    let mean = times.mean();
    let median = median(&mut times.samples);
    writeln!(
        out,
        "steps={} bodies={} mean_ms={mean:.4} median_ms={median:.4}",
        options.steps,
        world.len()
    )?;
    match non_finite {
        Some((body, step)) => Err(anyhow::anyhow!(
            "body {body} had a non-finite state after step {step}: the simulation failed"
        )),
        None => Ok(()),
    }
}

/// Index of the first body whose pose or velocity holds a NaN or an infinity.
fn first_non_finite(world: &World) -> Option<usize> {
    world.bodies().iter().position(|body| {
        !(body.pose().is_finite()
            && body.linear_velocity().is_finite()
            && body.angular_velocity().is_finite())
    })
}

/// One row per body, scene order, f32 shortest round-trip formatting (Rust's `Display` for floats).
/// The trace CSV's header line.
pub const TRACE_HEADER: &str = "step,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz";

/// One trace row per body of `world`, tagged `step` (shared with `nudge replay --trace`).
pub fn write_trace_rows(out: &mut impl Write, step: u64, world: &World) -> std::io::Result<()> {
    for (i, body) in world.bodies().iter().enumerate() {
        let p = body.pose().position;
        let q = body.pose().rotation;
        let v = body.linear_velocity();
        let w = body.angular_velocity();
        writeln!(
            out,
            "{step},{i},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, w.x, w.y, w.z
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_times_keep_a_bounded_sample_and_an_exact_mean() {
        let mut times = StepTimes::new(u64::MAX);
        let n = MAX_TIMING_SAMPLES as u64 + 1000;
        for i in 0..n {
            times.push((i % 2) as f64);
        }
        assert_eq!(times.samples.len(), MAX_TIMING_SAMPLES);
        assert!((times.mean() - 0.5).abs() < 1e-9);
    }

    #[test]
    fn trace_paths_in_missing_directories_or_naming_directories_are_rejected() {
        let missing = SimOptions {
            trace: Some(PathBuf::from("/no/such/dir/trace.csv")),
            ..SimOptions::default()
        };
        assert!(missing.validate().unwrap_err().contains("does not exist"));
        let dir = SimOptions {
            trace: Some(std::env::temp_dir()),
            ..SimOptions::default()
        };
        assert!(dir.validate().unwrap_err().contains("directory"));
        let bare = SimOptions {
            trace: Some(PathBuf::from("trace.csv")),
            ..SimOptions::default()
        };
        assert_eq!(bare.validate(), Ok(()));
    }

    #[test]
    fn zero_substeps_or_iterations_are_rejected_by_name() {
        let options = SimOptions {
            substeps: Some(0),
            ..SimOptions::default()
        };
        assert!(options.validate().unwrap_err().contains("--substeps"));
        let options = SimOptions {
            iterations: Some(0),
            ..SimOptions::default()
        };
        assert!(options.validate().unwrap_err().contains("--iterations"));
    }

    #[test]
    fn steps_substeps_and_iterations_have_upper_bounds() {
        let too_many = |options: SimOptions, flag: &str| {
            let message = options.validate().unwrap_err();
            assert!(
                message.contains(flag) && message.contains("at"),
                "{message}"
            );
        };
        too_many(
            SimOptions {
                steps: MAX_STEPS + 1,
                ..SimOptions::default()
            },
            "--steps",
        );
        too_many(
            SimOptions {
                substeps: Some(65),
                ..SimOptions::default()
            },
            "--substeps",
        );
        too_many(
            SimOptions {
                iterations: Some(u32::MAX),
                ..SimOptions::default()
            },
            "--iterations",
        );
        let most = SimOptions {
            steps: MAX_STEPS,
            substeps: Some(MAX_SUBSTEPS),
            iterations: Some(MAX_ITERATIONS),
            ..SimOptions::default()
        };
        assert_eq!(most.validate(), Ok(()));
    }
}
