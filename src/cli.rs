//! The command line: parse flags once, validate them into the objects the program uses, dispatch.
//!
//! Exit status: 0 success, 1 runtime failure, 2 bad input (arguments, scene files, no terminal),
//! 128 + N when the sandbox was ended by signal N.

use std::io::{self, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::builder::PossibleValue;
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::app::byte_budget::LimitOrigin;
use crate::app::panels::overlays::{OverlaySet, UnknownOverlay};
use crate::app::{self, AppConfig, snapshot::SnapshotOptions};
use crate::bench;
use crate::render::RenderMode;
use crate::scene::piles::{self, Pile};
use crate::scene::{self, SceneError};
use crate::sim::{self, SimOptions};
use crate::term::{self, CellMode, ColorDepth, Dither};

/// A 3D rigid-body physics sandbox in your terminal.
#[derive(Debug, Parser)]
#[command(
    name = "nudge",
    version,
    about,
    args_conflicts_with_subcommands = true,
    disable_help_subcommand = true
)]
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
    /// Print a test card: each cell mode's glyphs and a ball drawn in it, to see which your terminal
    /// draws (for `--cells`).
    Cells(CellsArgs),
    /// Measure speed against error.
    Bench(BenchArgs),
    /// Print this message or the help of the given subcommand.
    Help {
        /// The subcommand to explain.
        command: Option<String>,
    },
}

/// Flags of the interactive sandbox.
#[derive(Debug, Args, Default)]
pub struct RunArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long, default_value = "default")]
    pub scene: String,
    /// Maximum frames per second.
    #[arg(long, default_value_t = 30, allow_negative_numbers = true, value_parser = frames_per_second)]
    pub fps: u32,
    /// Colour depth: truecolor (or 24bit), 256 or 16 (default: detected from COLORTERM, TERM_PROGRAM
    /// and TERM).
    #[arg(long, ignore_case = true)]
    pub colors: Option<ColorDepth>,
    /// At 256 and 16 colours: none (nearest colour) or ordered (a still 2×2 pattern).
    #[arg(long, default_value = "ordered", ignore_case = true)]
    pub dither: Dither,
    /// Pixels a cell shows: half (1x2, every terminal), quadrant (2x2, nearly every one), sextant
    /// (2x3) or octant (2x4, Unicode 16 glyphs); `nudge cells` shows which your terminal draws.
    #[arg(long, default_value = "half", ignore_case = true)]
    pub cells: CellMode,
    /// Highlight the body under the pointer while it moves (asks the terminal for all-motion events).
    #[arg(long)]
    pub hover: bool,
    /// Terminal cell height / width (default: from the terminal's pixel size, else 2.0).
    #[arg(long, allow_negative_numbers = true)]
    pub cell_aspect: Option<f32>,
    /// Most bytes per second sent to the terminal; frames over it are skipped (0 = no limit;
    /// default: 1000000 over SSH, no limit in a local terminal).
    #[arg(long, allow_negative_numbers = true, value_parser = count::<u64>)]
    pub max_bytes_per_second: Option<u64>,
    /// Record the session into FILE, for `nudge replay FILE`.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Directory Ctrl+S saves the world into (default: the working directory).
    #[arg(long, value_name = "DIR")]
    pub save_dir: Option<PathBuf>,
    /// Debug overlays to start with, comma-separated: contacts, normals, friction, aabbs, axes,
    /// velocity, islands, sleep, joints (or all).
    #[arg(long, value_name = "LIST", value_parser = overlay_list)]
    pub overlay: Option<OverlaySet>,
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
    #[arg(long, default_value_t = 30, allow_negative_numbers = true, value_parser = frames_per_second)]
    pub fps: u32,
    /// Colour depth: truecolor (or 24bit), 256 or 16 (default: detected).
    #[arg(long, ignore_case = true)]
    pub colors: Option<ColorDepth>,
    /// Pixels a cell shows: half (1x2, every terminal), quadrant (2x2, nearly every one), sextant
    /// (2x3) or octant (2x4, Unicode 16 glyphs); `nudge cells` shows which your terminal draws.
    #[arg(long, default_value = "half", ignore_case = true)]
    pub cells: CellMode,
}

/// Flags of `nudge snapshot`.
#[derive(Debug, Args)]
pub struct SnapshotArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long, default_value = "default")]
    pub scene: String,
    /// Size in terminal cells, COLSxROWS (1 to 1000 each).
    #[arg(long, default_value = "80x24", value_parser = parse_size)]
    pub size: CellCount,
    /// Render mode.
    #[arg(long, default_value = "textured", ignore_case = true)]
    pub mode: RenderMode,
    /// Projection (default: the scene's).
    #[arg(long, ignore_case = true)]
    pub projection: Option<ProjectionFlag>,
    /// Colour depth: truecolor (or 24bit), 256 or 16 (default: detected).
    #[arg(long, ignore_case = true)]
    pub colors: Option<ColorDepth>,
    /// At 256 and 16 colours: none (nearest colour) or ordered (a still 2×2 pattern).
    #[arg(long, default_value = "ordered", ignore_case = true)]
    pub dither: Dither,
    /// Pixels a cell shows: half (1x2, every terminal), quadrant (2x2, nearly every one), sextant
    /// (2x3) or octant (2x4, Unicode 16 glyphs); `nudge cells` shows which your terminal draws.
    #[arg(long, default_value = "half", ignore_case = true)]
    pub cells: CellMode,
    /// Characters only (a density ramp), for diffing.
    #[arg(long)]
    pub plain: bool,
    /// Simulate this many physics steps before drawing.
    #[arg(long, default_value_t = 0, allow_negative_numbers = true, value_parser = count::<u64>)]
    pub steps: u64,
    /// Terminal cell height / width.
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub cell_aspect: f32,
    /// Debug overlays, comma-separated: contacts, normals, friction, aabbs, axes, velocity, islands,
    /// sleep, joints (or all).
    #[arg(long, value_name = "LIST", value_parser = overlay_list)]
    pub overlay: Option<OverlaySet>,
}

/// Flags of `nudge cells`.
#[derive(Debug, Args)]
pub struct CellsArgs {
    /// Colour depth: truecolor (or 24bit), 256 or 16 (default: detected).
    #[arg(long, ignore_case = true)]
    pub colors: Option<ColorDepth>,
}

/// Flags of `nudge sim`.
#[derive(Debug, Args)]
pub struct SimArgs {
    /// Built-in scene name or path to a scene file.
    #[arg(long)]
    pub scene: String,
    /// Number of physics steps.
    #[arg(long, allow_negative_numbers = true, value_parser = count::<u64>)]
    pub steps: u64,
    /// Write every body's state after every step to this CSV file.
    #[arg(long)]
    pub trace: Option<PathBuf>,
    /// Sub-steps per step (default 4).
    #[arg(long, allow_negative_numbers = true, value_parser = count::<u32>)]
    pub substeps: Option<u32>,
    /// Solver iterations per sub-step (default 1).
    #[arg(long, allow_negative_numbers = true, value_parser = count::<u32>)]
    pub iterations: Option<u32>,
    /// Keep every body awake.
    #[arg(long)]
    pub no_sleep: bool,
    /// Time each stage of the step and print the table after the run.
    #[arg(long)]
    pub profile: bool,
}

/// Flags of `nudge bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// What to measure.
    #[arg(value_enum, default_value_t = bench::Which::All)]
    pub what: bench::Which,
    /// Print JSON instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Fewer repetitions (a smoke run, numbers are rough).
    #[arg(long)]
    pub quick: bool,
    /// physics only: draw error against ms per step for each hard case, instead of tables.
    #[arg(long, conflicts_with = "json")]
    pub chart: bool,
    /// With --chart: characters only, no colour escapes.
    #[arg(long, requires = "chart")]
    pub plain: bool,
    /// With --chart: colour depth (default: detected).
    #[arg(long, requires = "chart", ignore_case = true)]
    pub colors: Option<ColorDepth>,
    /// rest only: measure this scene, a built-in name or a scene file (one saved with Ctrl+S, say),
    /// instead of the built-in piles.
    #[arg(long, value_name = "NAME|FILE")]
    pub scene: Option<String>,
    /// rest only: the built-in piles whose name contains this (any case), e.g. "wall".
    #[arg(long, value_name = "NAME", conflicts_with = "scene")]
    pub pile: Option<String>,
    /// rest with --scene: seconds it settles, awake, before where it rests is taken (default 1; give
    /// a pile dropped into place the time it takes to land).
    #[arg(long, value_name = "SECONDS", requires = "scene", allow_negative_numbers = true, value_parser = settle_seconds)]
    pub settle: Option<f32>,
}

/// Parses a count (steps, frames per second, bytes): a whole number, 0 or more, with a message that
/// says what is wrong with the value (clap's own read "unexpected argument '-1'" for a negative one).
fn count<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    let text = text.trim();
    text.parse::<T>().map_err(|_| {
        if text.starts_with('-') {
            "must be 0 or more (a count cannot be negative)".to_string()
        } else if text.parse::<f64>().is_ok() {
            "must be a whole number".to_string()
        } else {
            "must be a whole number, 0 or more".to_string()
        }
    })
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
    let cli = match Cli::try_parse_from(help_as_flag(std::env::args_os().collect())) {
        Ok(cli) => cli,
        Err(err) => {
            // clap prints help/version to stdout with status 0 and usage errors to stderr with 2.
            // A usage error quotes the value it refused: a 100 kB argument must not become a
            // 100 kB message, so it is made readable like the scene files' errors.
            if err.use_stderr() {
                eprint!(
                    "{}",
                    crate::scene::readable::readable(&err.render().to_string())
                );
            } else {
                let _ = err.print();
            }
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
        Some(Command::Cells(args)) => cells_card(args),
        Some(Command::Bench(args)) => bench(args),
        Some(Command::Help { command }) => help(command.as_deref()),
    }
}

/// `nudge help [COMMAND]`: what `nudge --help` or `nudge COMMAND --help` prints (clap's own help
/// subcommand refused `nudge help --help`).
fn help(command: Option<&str>) -> anyhow::Result<()> {
    use clap::CommandFactory;
    let mut cli = Cli::command();
    // Built, so a subcommand's usage reads "nudge sim …".
    cli.build();
    let text = match command {
        None => cli.render_long_help(),
        Some(name) => match cli.find_subcommand_mut(name) {
            Some(sub) => sub.render_long_help(),
            None => {
                return Err(InputError(format!(
                    "no subcommand '{name}' (run, snapshot, sim, replay, scenes, bench, help)"
                ))
                .into());
            }
        },
    };
    let stdout = io::stdout();
    let mut out = stdout.lock();
    write!(out, "{text}")?;
    out.flush()?;
    Ok(())
}

fn run_interactive(args: RunArgs) -> anyhow::Result<()> {
    // The arguments first: a missing scene is the error to report, whatever stdout is.
    let cell_aspect = validate_cell_aspect(args.cell_aspect)?;
    let scene = scene::load(&args.scene)?;
    let (color_depth, color_depth_certain) = color_depth(args.colors);
    if let Some(dir) = &args.save_dir
        && !dir.is_dir()
    {
        return Err(InputError(format!("--save-dir {}: not a directory", dir.display())).into());
    }
    term::check_term_env().map_err(InputError)?;
    if !io::stdout().is_terminal() {
        return Err(InputError(
            "stdout is not a terminal; the sandbox needs one (to print a frame instead, use `nudge snapshot`)".into(),
        )
        .into());
    }
    let window_size = crossterm::terminal::window_size().ok();
    // A pty that reports no pixel size (xterm.js's) leaves the cell aspect to the terminal's answer.
    let pty_says_cell_aspect = window_size
        .as_ref()
        .and_then(term::cell_aspect::reported_cell_aspect)
        .is_some();
    let (max_bytes_per_second, byte_limit_origin) = match args.max_bytes_per_second {
        Some(limit) => (limit, LimitOrigin::Flag),
        None => {
            let link = LimitOrigin::of_env(|name| std::env::var_os(name));
            (link.default_limit(), link)
        }
    };
    let config = AppConfig {
        color_depth,
        color_depth_certain,
        dither: args.dither,
        // A guess (no --colors, an uncertain environment): ask the terminal, if it is safe to.
        probe_truecolor: !color_depth_certain
            && term::probe::safe_to_ask(std::env::var("TERM").ok().as_deref()),
        cell_aspect: term::cell_aspect(window_size, cell_aspect),
        ask_cell_size: cell_aspect.is_none() && !pty_says_cell_aspect,
        hover: args.hover,
        supersample: true,
        cells: args.cells,
        max_bytes_per_second,
        byte_limit_origin,
        save_dir: args.save_dir.clone(),
    };
    let mut app = app::App::new(scene, config);
    app.set_overlays(args.overlay.unwrap_or_default());
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
    term::check_term_env().map_err(InputError)?;
    let (color_depth, color_depth_certain) = color_depth(args.colors);
    let link = LimitOrigin::of_env(|name| std::env::var_os(name));
    let window_size = crossterm::terminal::window_size().ok();
    let pty_says_cell_aspect = window_size
        .as_ref()
        .and_then(term::cell_aspect::reported_cell_aspect);
    let config = AppConfig {
        color_depth,
        color_depth_certain,
        ask_cell_size: pty_says_cell_aspect.is_none(),
        cell_aspect: term::cell_aspect(window_size, None),
        cells: args.cells,
        max_bytes_per_second: link.default_limit(),
        byte_limit_origin: link,
        ..AppConfig::default()
    };
    app::run::run_app(app::App::replaying(&recording, config), args.fps)
}

fn snapshot(args: SnapshotArgs) -> anyhow::Result<()> {
    let CellCount { cols, rows } = args.size;
    let mode = args.mode;
    let orthographic = args
        .projection
        .map(|projection| projection == ProjectionFlag::Orthographic);
    if args.steps > sim::MAX_STEPS {
        return Err(InputError(format!(
            "--steps must be at most {}, got {}",
            sim::MAX_STEPS,
            args.steps
        ))
        .into());
    }
    let cell_aspect = validate_cell_aspect(Some(args.cell_aspect))?.unwrap_or(2.0);
    let (color_depth, _) = color_depth(args.colors);
    let scene = scene::load(&args.scene)?;
    let options = SnapshotOptions {
        cols,
        rows,
        mode,
        orthographic,
        color_depth,
        dither: args.dither,
        plain: args.plain,
        steps: args.steps,
        cell_aspect,
        overlays: args.overlay.unwrap_or_default(),
        cells: args.cells,
    };
    let text = app::snapshot::snapshot_text(scene, &options);
    let stdout = io::stdout();
    let mut out = stdout.lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

fn cells_card(args: CellsArgs) -> anyhow::Result<()> {
    let (depth, _) = color_depth(args.colors);
    let text = term::buffer_to_ansi(&term::test_card::test_card(depth), depth);
    let stdout = io::stdout();
    let mut out = stdout.lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// Parses `--overlay LIST` (clap's value parser for it: an unknown name is a usage error that lists
/// the valid ones).
fn overlay_list(text: &str) -> Result<OverlaySet, UnknownOverlay> {
    text.parse()
}

/// `--colors` if given, else what the environment says; the flag is `certain` by definition.
fn color_depth(flag: Option<ColorDepth>) -> (ColorDepth, bool) {
    match flag {
        Some(depth) => (depth, true),
        None => {
            let detected = term::detect_from_env();
            (detected.depth, detected.certain)
        }
    }
}

/// `nudge help COMMAND ...` as `nudge COMMAND ... --help`: clap's help subcommand prints the long
/// layout (a blank line between options) where `--help` prints the compact one, and the README
/// promises they are the same.
fn help_as_flag(mut args: Vec<std::ffi::OsString>) -> Vec<std::ffi::OsString> {
    let names_a_command = args.get(1).is_some_and(|a| a == "help")
        && args
            .get(2)
            .is_some_and(|a| !a.to_string_lossy().starts_with('-'));
    if names_a_command {
        args.remove(1);
        args.push("--help".into());
    }
    args
}

/// `--mode` takes the names the status bar shows ([`RenderMode::name`]), and `--help` lists them.
/// (The trait is clap's; implemented here so that the render layer knows nothing of the command line.)
impl ValueEnum for RenderMode {
    fn value_variants<'a>() -> &'a [Self] {
        &RenderMode::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.name()))
    }
}

/// `--colors` takes [`ColorDepth::name`], or `24bit` for truecolor (`COLORTERM`'s other spelling).
impl ValueEnum for ColorDepth {
    fn value_variants<'a>() -> &'a [Self] {
        &ColorDepth::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let value = PossibleValue::new(self.name());
        Some(match self {
            ColorDepth::TrueColor => value.alias("24bit"),
            _ => value,
        })
    }
}

/// `--dither` takes [`Dither::name`].
impl ValueEnum for Dither {
    fn value_variants<'a>() -> &'a [Self] {
        &Dither::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.name()))
    }
}

/// `--cells` takes [`CellMode::name`].
impl ValueEnum for CellMode {
    fn value_variants<'a>() -> &'a [Self] {
        &CellMode::ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(PossibleValue::new(self.name()))
    }
}

/// `--projection`: overrides the scene's camera projection.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProjectionFlag {
    Perspective,
    Orthographic,
}

/// A frame's size in terminal cells (`--size COLSxROWS`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CellCount {
    pub cols: u16,
    pub rows: u16,
}

/// Parses `--fps`: a whole number in 1..=240 (the event loop cannot draw faster than that
/// usefully), with one message for every value outside it, negative or not ("must be 0 or more"
/// for −5 and then "between 1 and 240" for 0 sent a user round twice).
fn frames_per_second(text: &str) -> Result<u32, String> {
    const RANGE: std::ops::RangeInclusive<u32> = 1..=240;
    count::<u32>(text)
        .ok()
        .filter(|fps| RANGE.contains(fps))
        .ok_or_else(|| {
            format!(
                "must be a whole number between {} and {}",
                RANGE.start(),
                RANGE.end()
            )
        })
}

fn validate_cell_aspect(value: Option<f32>) -> anyhow::Result<Option<f32>> {
    match value {
        Some(v) if !(v.is_finite() && (0.25..=8.0).contains(&v)) => {
            Err(InputError(format!("--cell-aspect must be between 0.25 and 8, got {v}")).into())
        }
        other => Ok(other),
    }
}

/// Parses `COLSxROWS`, each 1..=1000 (clap's value parser for `--size`; it names the flag).
fn parse_size(text: &str) -> Result<CellCount, String> {
    let bad = || "expected COLSxROWS like 80x24, 1 to 1000 each".to_string();
    let (cols, rows) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let parse = |v: &str| {
        v.trim()
            .parse::<u16>()
            .ok()
            .filter(|n| (1..=1000).contains(n))
    };
    Ok(CellCount {
        cols: parse(cols).ok_or_else(bad)?,
        rows: parse(rows).ok_or_else(bad)?,
    })
}

/// Parses `--settle`: seconds, 0 to 600.
fn settle_seconds(text: &str) -> Result<f32, String> {
    text.trim()
        .parse::<f32>()
        .ok()
        .filter(|s| (0.0..=600.0).contains(s))
        .ok_or_else(|| "must be a number of seconds between 0 and 600".to_string())
}

fn bench(args: BenchArgs) -> anyhow::Result<()> {
    let stdout = io::stdout();
    if args.chart {
        if args.what != bench::Which::Physics {
            return Err(InputError("--chart draws `nudge bench physics` only".into()).into());
        }
        let (depth, _) = color_depth(args.colors);
        return bench::run_chart(args.quick, args.plain, depth, &mut stdout.lock());
    }
    let piles = rest_piles(&args)?;
    bench::run(args.what, args.json, args.quick, piles, &mut stdout.lock())
}

/// The piles `nudge bench rest` measures when `--scene` or `--pile` chooses them (`None`: all the
/// built-in piles).
fn rest_piles(args: &BenchArgs) -> anyhow::Result<Option<Vec<Pile>>> {
    if args.scene.is_none() && args.pile.is_none() {
        return Ok(None);
    }
    if args.what != bench::Which::Rest {
        return Err(InputError(
            "--scene and --pile choose what `nudge bench rest` measures".into(),
        )
        .into());
    }
    if let Some(name) = &args.scene {
        let scene = scene::load(name)?;
        let settle_s = args.settle.unwrap_or(piles::BUILT_SETTLE_S);
        return Ok(Some(vec![Pile {
            scene,
            settle_s,
            until_still: false,
        }]));
    }
    let part = args.pile.as_deref().unwrap_or_default();
    let chosen = piles::containing(part);
    if chosen.is_empty() {
        let names: Vec<String> = piles::all().into_iter().map(|p| p.scene.name).collect();
        return Err(InputError(format!(
            "--pile {part:?}: no pile's name contains it; the piles: {}",
            names.join(", ")
        ))
        .into());
    }
    Ok(Some(chosen))
}

fn simulate(args: SimArgs) -> anyhow::Result<()> {
    let scene = scene::load(&args.scene)?;
    let options = SimOptions {
        steps: args.steps,
        trace: args.trace,
        substeps: args.substeps,
        iterations: args.iterations,
        sleep: !args.no_sleep,
        profile: args.profile,
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
