//! The command line: parse flags once, validate them into the objects the program uses, dispatch.
//!
//! Exit status: 0 success, 1 runtime failure, 2 bad input (arguments, scene files, no terminal),
//! 128 + N when the sandbox was ended by signal N.

use std::io::{self, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

use crate::app::{self, AppConfig, snapshot::SnapshotOptions};
use crate::bench;
use crate::render::RenderMode;
use crate::scene::{self, SceneError};
use crate::sim::{self, SimOptions};
use crate::term::{self, ColorDepth};

/// A 3D rigid-body physics sandbox in your terminal.
#[derive(Debug, Parser)]
#[command(name = "nudge", version, about, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    #[command(flatten)]
    pub run: RunArgs,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Open the interactive sandbox (the default).
    Run(RunArgs),
    /// Render one frame and print it as ANSI text (no raw mode, works in pipes and CI).
    Snapshot(SnapshotArgs),
    /// Run the physics headless and report timing; optionally write a CSV trace.
    Sim(SimArgs),
    /// Play a session recorded with `nudge run --record FILE` (in the terminal, or headless with --trace).
    Replay(ReplayArgs),
    /// List the built-in scenes.
    Scenes,
    /// Measure speed against error.
    Bench(BenchArgs),
}

/// Flags of the interactive sandbox.
#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long, default_value = "default")]
    pub scene: String,
    /// Maximum frames per second.
    #[arg(long, default_value_t = 30)]
    pub fps: u32,
    /// Colour depth: truecolor, 256 or 16 (default: detected from COLORTERM, TERM_PROGRAM and TERM).
    #[arg(long)]
    pub colors: Option<String>,
    /// Highlight the body under the pointer while it moves (asks the terminal for all-motion events).
    #[arg(long)]
    pub hover: bool,
    /// Terminal cell height / width (default: from the terminal's pixel size, else 2.0).
    #[arg(long)]
    pub cell_aspect: Option<f32>,
    /// Most bytes per second sent to the terminal; frames over it are skipped (0 = no limit).
    #[arg(long, default_value_t = crate::app::DEFAULT_MAX_BYTES_PER_SECOND)]
    pub max_bytes_per_second: u64,
    /// Record the session into FILE, for `nudge replay FILE`.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Directory Ctrl+S saves the world into (default: the working directory).
    #[arg(long, value_name = "DIR")]
    pub save_dir: Option<PathBuf>,
}

/// Flags of `nudge replay`.
#[derive(Debug, Args)]
pub struct ReplayArgs {
    /// The recording.
    pub file: String,
    /// Run headless and write every body's state after every step to this CSV file (the `sim` format).
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Maximum frames per second.
    #[arg(long, default_value_t = 30)]
    pub fps: u32,
    /// Colour depth: truecolor, 256 or 16 (default: detected).
    #[arg(long)]
    pub colors: Option<String>,
}

/// Flags of `nudge snapshot`.
#[derive(Debug, Args)]
pub struct SnapshotArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long, default_value = "default")]
    pub scene: String,
    /// Size in terminal cells, COLSxROWS.
    #[arg(long, default_value = "80x24")]
    pub size: String,
    /// Render mode: wireframe, flat, smooth, textured, depth, normals.
    #[arg(long, default_value = "textured")]
    pub mode: String,
    /// perspective or orthographic (default: the scene's).
    #[arg(long)]
    pub projection: Option<String>,
    /// Colour depth: truecolor, 256 or 16 (default: detected).
    #[arg(long)]
    pub colors: Option<String>,
    /// Characters only (a density ramp), for diffing.
    #[arg(long)]
    pub plain: bool,
    /// Simulate this many physics steps before drawing.
    #[arg(long, default_value_t = 0)]
    pub steps: u64,
    /// Terminal cell height / width.
    #[arg(long, default_value_t = 2.0)]
    pub cell_aspect: f32,
}

/// Flags of `nudge sim`.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long)]
    pub scene: String,
    /// Number of physics steps.
    #[arg(long, allow_negative_numbers = true)]
    pub steps: u64,
    /// Write every body's state after every step to this CSV file.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Sub-steps per step (default 4).
    #[arg(long, allow_negative_numbers = true)]
    pub substeps: Option<u32>,
    /// Solver iterations per sub-step (default 1).
    #[arg(long, allow_negative_numbers = true)]
    pub iterations: Option<u32>,
    /// Keep every body awake.
    #[arg(long)]
    pub no_sleep: bool,
}

/// Flags of `nudge bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// What to measure: all, render, physics, app or rewind.
    #[arg(default_value = "all")]
    pub what: String,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Fewer repetitions (a smoke run, numbers are rough).
    #[arg(long)]
    pub quick: bool,
}

/// Bad input from the user: printed once, exit status 2.
#[derive(Debug)]
pub struct InputError(pub String);

impl std::fmt::Display for InputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

/// Entry point of the binary.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => {
            // clap prints help/version to stdout with status 0 and usage errors to stderr with 2.
            let _ = err.print();
            return ExitCode::from(err.exit_code().clamp(0, 255) as u8);
        }
    };
    match dispatch(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) if is_broken_pipe(&err) => ExitCode::SUCCESS,
        // Ended by a signal the user sent: the shell's status for it, and nothing to explain.
        Err(err) if err.is::<term::EndedBySignal>() => {
            let signal = err.downcast_ref::<term::EndedBySignal>().map_or(0, |e| e.0);
            ExitCode::from(term::signals::exit_status(signal).clamp(0, 255) as u8)
        }
        Err(err) => {
            eprintln!("nudge: {err:#}");
            if is_input_error(&err) {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

fn dispatch(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        None => run_interactive(cli.run),
        Some(Command::Run(args)) => run_interactive(args),
        Some(Command::Snapshot(args)) => snapshot(args),
        Some(Command::Sim(args)) => simulate(args),
        Some(Command::Replay(args)) => replay(args),
        Some(Command::Scenes) => list_scenes(),
        Some(Command::Bench(args)) => bench(args),
    }
}

fn run_interactive(args: RunArgs) -> anyhow::Result<()> {
    if !io::stdout().is_terminal() {
        return Err(InputError(
            "stdout is not a terminal; the sandbox needs one (to print a frame instead, use `nudge snapshot`)".into(),
        )
        .into());
    }
    term::refuse_dumb(std::env::var("TERM").ok().as_deref()).map_err(InputError)?;
    validate_fps(args.fps)?;
    let cell_aspect = validate_cell_aspect(args.cell_aspect)?;
    let scene = scene::load(&args.scene)?;
    let (color_depth, color_depth_certain) = color_depth(args.colors.as_deref())?;
    let config = AppConfig {
        color_depth,
        color_depth_certain,
        cell_aspect: term::cell_aspect(crossterm::terminal::window_size().ok(), cell_aspect),
        hover: args.hover,
        supersample: true,
        max_bytes_per_second: args.max_bytes_per_second,
        save_dir: args.save_dir.clone(),
    };
    if let Some(dir) = &args.save_dir
        && !dir.is_dir()
    {
        return Err(InputError(format!("--save-dir {}: not a directory", dir.display())).into());
    }
    let mut app = app::App::new(scene, config);
    if let Some(path) = &args.record {
        app.start_recording(path)
            .map_err(|err| InputError(format!("{err:#}")))?;
    }
    app::run::run_app(app, args.fps)
}

/// `nudge replay`: a located message and status 2 for a bad recording, before any terminal setup.
fn replay(args: ReplayArgs) -> anyhow::Result<()> {
    let recording =
        crate::recording::load(&args.file).map_err(|err| InputError(err.to_string()))?;
    if let Some(path) = &args.trace {
        let file = std::fs::File::create(path)
            .map_err(|err| InputError(format!("--trace {}: {err}", path.display())))?;
        let mut out = io::BufWriter::new(file);
        crate::replay::write_trace(&recording, &mut out)?;
        out.flush()?;
        return Ok(());
    }
    if !io::stdout().is_terminal() {
        return Err(InputError(
            "stdout is not a terminal; to replay headless, give --trace OUT.csv".into(),
        )
        .into());
    }
    term::refuse_dumb(std::env::var("TERM").ok().as_deref()).map_err(InputError)?;
    validate_fps(args.fps)?;
    let (color_depth, color_depth_certain) = color_depth(args.colors.as_deref())?;
    let config = AppConfig {
        color_depth,
        color_depth_certain,
        cell_aspect: term::cell_aspect(crossterm::terminal::window_size().ok(), None),
        ..AppConfig::default()
    };
    app::run::run_app(app::App::replaying(&recording, config), args.fps)
}

fn snapshot(args: SnapshotArgs) -> anyhow::Result<()> {
    let (cols, rows) = parse_size(&args.size)?;
    let mode: RenderMode = args.mode.parse().map_err(|_| {
        InputError(format!(
            "unknown render mode '{}' (one of: {})",
            args.mode,
            mode_names()
        ))
    })?;
    let orthographic = match args.projection.as_deref() {
        None => None,
        Some("perspective") => Some(false),
        Some("orthographic") => Some(true),
        Some(other) => {
            return Err(InputError(format!(
                "unknown projection '{other}' (perspective or orthographic)"
            ))
            .into());
        }
    };
    if args.steps > sim::MAX_STEPS {
        return Err(InputError(format!(
            "--steps must be at most {}, got {}",
            sim::MAX_STEPS,
            args.steps
        ))
        .into());
    }
    let cell_aspect = validate_cell_aspect(Some(args.cell_aspect))?.unwrap_or(2.0);
    let (color_depth, _) = color_depth(args.colors.as_deref())?;
    let scene = scene::load(&args.scene)?;
    let options = SnapshotOptions {
        cols,
        rows,
        mode,
        orthographic,
        color_depth,
        plain: args.plain,
        steps: args.steps,
        cell_aspect,
    };
    let text = app::snapshot::snapshot_text(scene, &options);
    let stdout = io::stdout();
    let mut out = stdout.lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

fn mode_names() -> String {
    RenderMode::ALL
        .iter()
        .map(|m| m.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `--colors` if given, else what the environment says; the flag is `certain` by definition.
fn color_depth(flag: Option<&str>) -> anyhow::Result<(ColorDepth, bool)> {
    match flag {
        Some(text) => text
            .parse::<ColorDepth>()
            .map(|depth| (depth, true))
            .map_err(|_| {
                InputError(format!(
                    "unknown colour depth '{text}' (truecolor, 256 or 16)"
                ))
                .into()
            }),
        None => {
            let detected = term::detect_from_env();
            Ok((detected.depth, detected.certain))
        }
    }
}

/// `--fps` in 1..=240 (the event loop cannot draw faster than that usefully).
fn validate_fps(fps: u32) -> anyhow::Result<()> {
    if (1..=240).contains(&fps) {
        Ok(())
    } else {
        Err(InputError(format!("--fps must be between 1 and 240, got {fps}")).into())
    }
}

fn validate_cell_aspect(value: Option<f32>) -> anyhow::Result<Option<f32>> {
    match value {
        Some(v) if !(v.is_finite() && (0.25..=8.0).contains(&v)) => {
            Err(InputError(format!("--cell-aspect must be between 0.25 and 8, got {v}")).into())
        }
        other => Ok(other),
    }
}

/// Parses `COLSxROWS`, each 1..=1000.
fn parse_size(text: &str) -> anyhow::Result<(u16, u16)> {
    let bad = || {
        InputError(format!(
            "--size must look like 80x24 (COLSxROWS, 1 to 1000 each), got '{text}'"
        ))
    };
    let (cols, rows) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u16>()
            .ok()
            .filter(|n| (1..=1000).contains(n))
    };
    Ok((parse(cols).ok_or_else(bad)?, parse(rows).ok_or_else(bad)?))
}

fn bench(args: BenchArgs) -> anyhow::Result<()> {
    let which: bench::Which = args.what.parse().map_err(InputError)?;
    let stdout = io::stdout();
    bench::run(which, args.json, args.quick, &mut stdout.lock())
}

fn simulate(args: SimArgs) -> anyhow::Result<()> {
    let scene = scene::load(&args.scene)?;
    let options = SimOptions {
        steps: args.steps,
        trace: args.trace,
        substeps: args.substeps,
        iterations: args.iterations,
        sleep: !args.no_sleep,
    };
    options.validate().map_err(InputError)?;
    let stdout = io::stdout();
    sim::run(&scene, &options, &mut stdout.lock())
}

fn list_scenes() -> anyhow::Result<()> {
    let stdout = io::stdout();
    let mut out = stdout.lock();
    for (name, description) in scene::builtin_scenes() {
        writeln!(out, "{name:<10} {description}")?;
    }
    Ok(())
}

fn is_input_error(err: &anyhow::Error) -> bool {
    err.chain()
        .any(|cause| cause.is::<InputError>() || cause.is::<SceneError>())
}

fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<io::Error>()
            .is_some_and(|e| e.kind() == io::ErrorKind::BrokenPipe)
    })
}
