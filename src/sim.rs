//! `nudge sim`: run a scene's physics with no terminal, time the steps, optionally trace every body.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;

use crate::physics::World;
use crate::scene::Scene;

/// What `nudge sim` was asked to do.
#[derive(Clone, Debug, Default)]
pub struct SimOptions {
    pub steps: u64,
    pub trace: Option<PathBuf>,
    pub substeps: Option<u32>,
    pub iterations: Option<u32>,
    pub sleep: bool,
}

impl SimOptions {
    /// Rejects values the solver cannot use.
    pub fn validate(&self) -> Result<(), String> {
        if self.substeps == Some(0) {
            return Err("--substeps must be at least 1".into());
        }
        if self.iterations == Some(0) {
            return Err("--iterations must be at least 1".into());
        }
        Ok(())
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
            let mut writer = BufWriter::new(file);
            writeln!(writer, "step,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz")?;
            write_trace_rows(&mut writer, 0, &world)?;
            Some(writer)
        }
        None => None,
    };

    let mut step_ms = Vec::with_capacity(options.steps.min(1 << 24) as usize);
    for step in 1..=options.steps {
        let start = Instant::now();
        world.step();
        step_ms.push(start.elapsed().as_secs_f64() * 1e3);
        if let Some(writer) = trace.as_mut() {
            write_trace_rows(writer, step, &world)?;
        }
    }
    if let Some(mut writer) = trace {
        writer.flush().context("cannot write trace file")?;
    }

    let mean = if step_ms.is_empty() {
        0.0
    } else {
        step_ms.iter().sum::<f64>() / step_ms.len() as f64
    };
    let median = median(&mut step_ms);
    writeln!(
        out,
        "steps={} bodies={} mean_ms={mean:.4} median_ms={median:.4}",
        options.steps,
        world.len()
    )?;
    Ok(())
}

/// One row per body, scene order, f32 shortest round-trip formatting (Rust's `Display` for floats).
fn write_trace_rows(out: &mut impl Write, step: u64, world: &World) -> std::io::Result<()> {
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

/// Median of the samples (sorts them); 0 for none.
pub fn median(samples: &mut [f64]) -> f64 {
    if samples.is_empty() {
        return 0.0;
    }
    samples.sort_by(f64::total_cmp);
    let mid = samples.len() / 2;
    if samples.len() % 2 == 0 {
        0.5 * (samples[mid - 1] + samples[mid])
    } else {
        samples[mid]
    }
}
