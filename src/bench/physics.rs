//! `nudge bench physics`: speed against error for every hard case, and raw speed for many bodies.
//!
//! For each hard case of [`crate::testing::hard_case`] and each sub-step count in {1, 2, 4, 8} (and, for the cases
//! where the solver's convergence matters — the stack, the pyramid and the 1000:1 mass ratio — each
//! iteration count in {1, 2, 4}), the median wall-clock ms per step beside the case's error metric, so a
//! user can pick a point on the curve. The tolerances the tests demand are in
//! `tests/physics/hard_cases.rs`. The sweep runs with sleeping **off**, so both columns measure the
//! solver rather than the sleep system (a settled, sleeping stack costs almost nothing and cannot drift);
//! the tests run with the defaults (sleeping on).
//!
//! Throughput rows:
//! - `rain(n)` for n = 100, 1,000, 4,000, sleeping off, timing the first [`RAIN_WINDOW_S`] seconds after
//!   release (the bodies start 2–5 m up, so this window covers the fall, the first impacts and the pile-up),
//!   and `spread rain(4000)`, the 4,000 in a pit four times the area, falling in one layer as rain(1000)'s
//!   do: how the step scales with the bodies, without the pile's own growth;
//! - the 210-box pyramid, sleeping off, timing [`TIMED_STEPS`] steps from the start, and the same
//!   pyramid with its boxes flush side by side over [`RESTING_STEPS`];
//! - "settled" rows, sleeping on: the pyramid and the built-in default scene after [`SETTLE_S`] seconds
//!   untimed, then [`TIMED_STEPS`] steps timed (what a scene at rest costs).
//!
//! `--quick` sweeps one iteration count only and rains 100 and 1,000 bodies for 1 s.

use std::io::{self, Write};

use glam::Vec3;

use crate::testing::hard_case::{self, Knobs, Timed};
use serde::{Serialize, Serializer};

use super::table::Table;
use crate::scene::{Scene, cases};

/// Simulated seconds of the rain window that is timed, s.
pub const RAIN_WINDOW_S: f32 = 2.5;
/// Simulated seconds a scene gets to settle before a "settled" row is timed, s.
pub const SETTLE_S: f32 = 10.0;
/// Steps timed for the pyramid and settled rows.
pub const TIMED_STEPS: usize = 120;
/// Steps timed for the touching pyramid kept awake: ten seconds, long enough for a pile that
/// stirs once it has stood a while to show it.
pub const RESTING_STEPS: usize = 600;

/// One measured error of a case. In JSON: a number, a boolean, or null (missing, or not finite).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Value {
    /// A quantity in `unit`.
    Number(f64),
    /// A yes/no outcome.
    Flag(bool),
    /// Nothing to measure (e.g. the ball never rebounded).
    Missing,
}

/// A named error metric of one run.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metric {
    /// What is measured, e.g. "drift".
    pub name: &'static str,
    /// The measured value.
    pub value: Value,
    /// Unit of a `Number`: "m", "m/s", "N", "%" (relative, in percent), "" for counts.
    pub unit: &'static str,
}

fn number(name: &'static str, value: f32, unit: &'static str) -> Metric {
    // Through the f32's shortest decimal, so reports show 0.98674977 rather than 0.9867497682571411.
    let widened = value.to_string().parse::<f64>().unwrap_or(f64::NAN);
    Metric {
        name,
        value: Value::Number(widened),
        unit,
    }
}

/// One hard case at one setting of the knobs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseRow {
    /// The case's report name ([`Case::name`]).
    pub case: String,
    /// Sub-steps per step of this run.
    pub substeps: u32,
    /// Solver iterations per sub-step of this run.
    pub iterations: u32,
    /// Median wall-clock ms per `World::step`.
    #[serde(serialize_with = "rounded_ms")]
    pub ms_per_step: f64,
    /// The case's error metrics.
    pub metrics: Vec<Metric>,
}

/// Raw speed of one scene.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThroughputRow {
    /// Scene name, with " settled" for rows timed after settling.
    pub scene: String,
    /// Bodies in the world, statics included.
    pub bodies: usize,
    /// Whether sleeping was on.
    pub sleep: bool,
    /// Steps timed.
    pub steps: usize,
    /// Median wall-clock ms per step over those steps.
    #[serde(serialize_with = "rounded_ms")]
    pub ms_per_step: f64,
    /// Mean wall-clock ms per step over those steps (the median hides the costliest steps, the mean
    /// shows them, and the machine's hiccups too).
    #[serde(serialize_with = "rounded_ms")]
    pub mean_ms_per_step: f64,
    /// Contacts the solver handled per step, mean over the timed steps: the work a step scales with
    /// (a pile has more per body than a scattered layer).
    #[serde(serialize_with = "rounded")]
    pub mean_contacts: f64,
    /// The share of those contacts whose statics were found afresh, not kept for an island that
    /// stayed still (`World::statics_found`), %.
    #[serde(serialize_with = "rounded")]
    pub statics_found_percent: f64,
    /// Awake dynamic bodies after the last timed step.
    pub awake_at_end: usize,
    /// What window was timed.
    pub window: String,
}

/// Everything `nudge bench physics` measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PhysicsReport {
    /// Whether this was a `--quick` run.
    pub quick: bool,
    /// Hard cases, in [`Case::ALL`] order, then by sub-steps and iterations.
    pub cases: Vec<CaseRow>,
    /// Raw-speed rows.
    pub throughput: Vec<ThroughputRow>,
    /// The step by stage per scene, and what profiling costs (see `super::stages`).
    pub stages: Vec<super::stages::StageRow>,
    /// The corpus's families against sub-steps (see `super::corpus`).
    pub corpus: Vec<super::corpus::CorpusRow>,
}

/// Runs the whole benchmark; progress goes to stderr, one line per case.
pub fn run(quick: bool) -> PhysicsReport {
    let cases = run_cases(quick);
    let throughput = run_throughput(quick);
    let stages = super::stages::run(quick);
    let corpus = super::corpus::run();
    super::progress!("bench physics: done{}\n", " ".repeat(40));
    PhysicsReport {
        quick,
        cases,
        throughput,
        stages,
        corpus,
    }
}

/// The hard cases at every setting of the sweep, in [`Case::ALL`] order, then by sub-steps and
/// iterations.
pub fn run_cases(quick: bool) -> Vec<CaseRow> {
    let substeps: &[u32] = &[1, 2, 4, 8];
    let iterations: &[u32] = if quick { &[1] } else { &[1, 2, 4] };
    let mut cases = Vec::new();
    for &sub in substeps {
        for case in Case::ALL {
            let its: &[u32] = if case.sweeps_iterations() {
                iterations
            } else {
                &[1]
            };
            for &it in its {
                let knobs = Knobs {
                    substeps: sub,
                    iterations: it,
                    sleep: false,
                    ..Knobs::default()
                };
                super::progress!(
                    "bench physics: {} substeps={sub} iterations={it}          \r",
                    case.name()
                );
                let (ms_per_step, metrics) = run_case(case, knobs);
                cases.push(CaseRow {
                    case: case.name().to_string(),
                    substeps: sub,
                    iterations: it,
                    ms_per_step,
                    metrics,
                });
            }
        }
    }
    cases.sort_by(|a, b| {
        let rank = |name: &str| Case::ALL.iter().position(|c| c.name() == name);
        (rank(&a.case), a.substeps, a.iterations).cmp(&(rank(&b.case), b.substeps, b.iterations))
    });
    cases
}

/// The raw-speed rows.
fn run_throughput(quick: bool) -> Vec<ThroughputRow> {
    let mut throughput = Vec::new();
    let rain_sizes: &[usize] = if quick {
        &[100, 1000]
    } else {
        &[100, 1000, 4000]
    };
    let rain_seconds = if quick { 1.0 } else { RAIN_WINDOW_S };
    let awake = Knobs {
        sleep: false,
        ..Knobs::default()
    };
    // Every rain is timed over the same first seconds of its fall.
    let time_rain = |scene: &Scene| {
        let steps = (rain_seconds / scene.settings.dt).round() as usize;
        time_scene(
            scene,
            awake,
            0.0,
            steps,
            format!("first {rain_seconds} s of the fall"),
        )
    };
    for &n in rain_sizes {
        super::progress!("bench physics: rain({n})                          \r");
        throughput.push(time_rain(&cases::rain(n)));
    }
    if !quick {
        // How the step scales with the bodies alone: 4,000 as far apart as rain(1000)'s.
        super::progress!("bench physics: spread rain(4000)                  \r");
        throughput.push(time_rain(&cases::spread_rain(4000)));
    }
    // What the impact pass costs: the same rain with every body bouncy (e = 0.5).
    super::progress!("bench physics: rain(1000) e=0.5                   \r");
    let mut bouncy = cases::rain(1000);
    bouncy.name = "rain(1000) e=0.5".into();
    for body in &mut bouncy.bodies {
        body.desc.restitution = 0.5;
    }
    throughput.push(time_rain(&bouncy));
    super::progress!("bench physics: pyramid, sleeping off              \r");
    throughput.push(time_scene(
        &cases::pyramid(20),
        awake,
        0.0,
        TIMED_STEPS,
        format!("first {TIMED_STEPS} steps"),
    ));
    super::progress!("bench physics: touching pyramid, sleeping off     \r");
    throughput.push(time_scene(
        &crate::scene::piles::touching_pyramid(20),
        awake,
        0.0,
        RESTING_STEPS,
        format!("first {RESTING_STEPS} steps"),
    ));
    let default_scene = crate::scene::load("default").ok();
    for scene in [Some(cases::pyramid(20)), default_scene]
        .into_iter()
        .flatten()
    {
        super::progress!(
            "bench physics: {} settled                          \r",
            scene.name
        );
        throughput.push(time_scene(
            &scene,
            Knobs::default(),
            SETTLE_S,
            TIMED_STEPS,
            format!("{TIMED_STEPS} steps after {SETTLE_S} s settling"),
        ));
    }
    throughput
}

/// The hard cases of the sweep, in report order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Case {
    Stack10,
    Pyramid20,
    MassRatio,
    PinnedPush,
    Bounce,
    RampHolds,
    RampSlides,
    RollingBall,
    Projectile,
    DeepOverlap,
    Stack5Origin,
    Stack5Far,
    IntermediateAxis,
    Bullet,
}

impl Case {
    /// Every case, in report order.
    pub const ALL: [Case; 14] = [
        Case::Stack10,
        Case::Pyramid20,
        Case::MassRatio,
        Case::PinnedPush,
        Case::Bounce,
        Case::RampHolds,
        Case::RampSlides,
        Case::RollingBall,
        Case::Projectile,
        Case::DeepOverlap,
        Case::Stack5Origin,
        Case::Stack5Far,
        Case::IntermediateAxis,
        Case::Bullet,
    ];

    /// The name shown in reports.
    pub fn name(self) -> &'static str {
        match self {
            Case::Stack10 => "stack(10)",
            Case::Pyramid20 => "pyramid(20)",
            Case::MassRatio => "mass ratio 1000:1",
            Case::PinnedPush => "1 kg pinned, pushed",
            Case::Bounce => "bounce e=0.5",
            Case::RampHolds => "ramp mu=0.7",
            Case::RampSlides => "ramp mu=0.3",
            Case::RollingBall => "rolling ball",
            Case::Projectile => "projectile",
            Case::DeepOverlap => "deep overlap",
            Case::Stack5Origin => "stack(5) at origin",
            Case::Stack5Far => "stack(5) at 5000 m",
            Case::IntermediateAxis => "intermediate axis",
            Case::Bullet => "bullet 200 m/s",
        }
    }

    /// Whether the solver's iteration count is swept too (where convergence matters).
    pub fn sweeps_iterations(self) -> bool {
        matches!(
            self,
            Case::Stack10 | Case::Pyramid20 | Case::MassRatio | Case::PinnedPush
        )
    }
}

/// Runs one case and returns its median ms per step and its error metrics.
fn run_case(case: Case, knobs: Knobs) -> (f64, Vec<Metric>) {
    let percent = |relative: f32| 100.0 * relative;
    match case {
        Case::Stack10 | Case::Stack5Origin | Case::Stack5Far => {
            let (count, base) = match case {
                Case::Stack10 => (10, Vec3::ZERO),
                Case::Stack5Origin => (5, Vec3::ZERO),
                _ => (5, Vec3::new(5000.0, 0.0, 5000.0)),
            };
            let out = hard_case::stack(count, base, 10.0, knobs);
            (
                out.ms_per_step,
                vec![
                    number("drift", out.max_drift_m, "m"),
                    number("penetration", out.max_penetration_m, "m"),
                    number("hover", out.max_hover_m, "m"),
                ],
            )
        }
        Case::Pyramid20 => {
            let out = hard_case::pyramid(20, 10.0, knobs);
            (
                out.ms_per_step,
                vec![
                    number("top drift", out.top_drift_m, "m"),
                    number("penetration", out.max_penetration_m, "m"),
                    number("top sag", out.top_sag_m, "m"),
                ],
            )
        }
        Case::MassRatio => {
            let out = hard_case::mass_ratio(10.0, knobs);
            (
                out.ms_per_step,
                vec![
                    number("penetration", out.max_penetration_m, "m"),
                    number("height error", out.max_height_error_m, "m"),
                ],
            )
        }
        Case::PinnedPush => {
            let out = hard_case::pinned_push(knobs);
            (out.ms_per_step, vec![number("push held", out.held_n, "N")])
        }
        Case::Bounce => {
            let out = hard_case::bounce(5.0, knobs);
            let expected = cases::BOUNCE_RESTITUTION.powi(2) * cases::BOUNCE_GAP;
            let error = match out.apex_gap_m {
                Some(apex) => Value::Number(percent((apex - expected).abs() / expected) as f64),
                None => Value::Missing,
            };
            (
                out.ms_per_step,
                vec![Metric {
                    name: "rebound error",
                    value: error,
                    unit: "%",
                }],
            )
        }
        Case::RampHolds => {
            let out = hard_case::ramp(0.7, 2.0, knobs);
            (
                out.ms_per_step,
                vec![number("creep in 2 s", out.max_displacement_m, "m")],
            )
        }
        Case::RampSlides => {
            let out = hard_case::ramp(0.3, 1.0, knobs);
            let error = (out.slide_m - out.expected_slide_m).abs() / out.expected_slide_m;
            (
                out.ms_per_step,
                vec![number("slide error at 1 s", percent(error), "%")],
            )
        }
        Case::RollingBall => {
            let out = hard_case::rolling_ball(2.0, knobs);
            let expected = 5.0 / 7.0 * cases::ROLL_SPEED;
            (
                out.ms_per_step,
                vec![
                    number(
                        "rolling speed error",
                        percent((out.speed_mps - expected).abs() / expected),
                        "%",
                    ),
                    number("slip", out.slip_mps, "m/s"),
                ],
            )
        }
        Case::Projectile => {
            let out = hard_case::projectile(2.0, knobs);
            (
                out.ms_per_step,
                vec![number(
                    "parabola error at 2 s",
                    percent(out.error_m / out.displacement_m),
                    "%",
                )],
            )
        }
        Case::DeepOverlap => {
            let out = hard_case::deep_overlap(2.0, knobs);
            (
                out.ms_per_step,
                vec![
                    number("overlap at 2 s", out.final_penetration_m, "m"),
                    number("max speed", out.max_speed_mps, "m/s"),
                ],
            )
        }
        Case::IntermediateAxis => {
            let out = hard_case::intermediate_axis(10.0, knobs);
            (
                out.ms_per_step,
                vec![
                    number("energy drift", percent(out.max_energy_drift), "%"),
                    number("|L| drift", percent(out.max_momentum_drift), "%"),
                    number("flips", out.flips as f32, ""),
                ],
            )
        }
        Case::Bullet => {
            let out = hard_case::bullet(1.0, knobs);
            (
                out.ms_per_step,
                vec![
                    Metric {
                        name: "crossed wall",
                        value: Value::Flag(out.crossed),
                        unit: "",
                    },
                    number("max x", out.max_x_m, "m"),
                ],
            )
        }
    }
}

/// Runs `scene` for `settle_s` seconds untimed, then times `steps` steps.
fn time_scene(
    scene: &Scene,
    knobs: Knobs,
    settle_s: f32,
    steps: usize,
    window: String,
) -> ThroughputRow {
    let mut world = knobs.world(scene);
    for _ in 0..(settle_s / world.settings().dt).round() as usize {
        world.step();
    }
    let mut run = Timed::new(world);
    let (mut contacts, mut found) = (0, 0);
    for _ in 0..steps {
        run.step();
        contacts += run.world.contact_count();
        found += run.world.statics_found();
    }
    ThroughputRow {
        scene: if settle_s > 0.0 {
            format!("{} settled", scene.name)
        } else {
            scene.name.clone()
        },
        bodies: run.world.len(),
        sleep: knobs.sleep,
        steps,
        ms_per_step: run.median_ms(),
        mean_ms_per_step: run.mean_ms(),
        mean_contacts: contacts as f64 / steps.max(1) as f64,
        statics_found_percent: 100.0 * found as f64 / contacts.max(1) as f64,
        awake_at_end: run.world.awake_count(),
        window,
    }
}

fn format_value(metric: &Metric) -> String {
    match metric.value {
        Value::Number(x) if metric.unit.is_empty() => format!("{x}"),
        Value::Number(x) if metric.unit == "%" => format!("{x:.3}%"),
        Value::Number(x) if metric.unit == "N" => format!("{x:.0} N"),
        Value::Number(x) => format!("{x:.5} {}", metric.unit),
        Value::Flag(yes) => if yes { "yes" } else { "no" }.into(),
        Value::Missing => "none".into(),
    }
}

/// Prints the report as two tables (hard cases, then throughput).
pub fn print_table(report: &PhysicsReport, out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "physics: hard cases (sleeping off; ms/step = median wall-clock per World::step; dt = 1/60 s){}",
        if report.quick { " [quick]" } else { "" }
    )?;
    let mut table = Table::new(&["case", "substeps", "iters", "ms/step", "error"]);
    for row in &report.cases {
        let error = row
            .metrics
            .iter()
            .map(|m| format!("{} {}", m.name, format_value(m)))
            .collect::<Vec<_>>()
            .join(", ");
        table.push(vec![
            row.case.clone(),
            row.substeps.to_string(),
            row.iterations.to_string(),
            format!("{:.4}", row.ms_per_step),
            error,
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    writeln!(
        out,
        "physics: throughput (default sub-steps and iterations; ms/step = median, mean beside it)"
    )?;
    let mut table = Table::new(&[
        "scene",
        "bodies",
        "contacts",
        "statics found",
        "sleep",
        "steps",
        "ms/step",
        "mean",
        "awake",
        "window",
    ]);
    for row in &report.throughput {
        table.push(vec![
            row.scene.clone(),
            row.bodies.to_string(),
            format!("{:.0}", row.mean_contacts),
            if row.mean_contacts > 0.0 {
                format!("{:.0}%", row.statics_found_percent)
            } else {
                "-".into()
            },
            if row.sleep { "on" } else { "off" }.into(),
            row.steps.to_string(),
            format!("{:.4}", row.ms_per_step),
            format!("{:.4}", row.mean_ms_per_step),
            row.awake_at_end.to_string(),
            row.window.clone(),
        ]);
    }
    table.write(out)?;
    writeln!(out)?;
    super::stages::print_table(&report.stages, out)?;
    writeln!(out)?;
    super::corpus::print_table(&report.corpus, out)
}

/// Writes the report as one JSON object:
/// `{"quick": bool, "cases": [{"case", "substeps", "iterations", "ms_per_step", "metrics": [{"name",
/// "value", "unit"}]}], "throughput": [{"scene", "bodies", "sleep", "steps", "ms_per_step",
/// "mean_ms_per_step", "mean_contacts", "statics_found_percent", "awake_at_end", "window"}], "corpus": [{"family", "members", "substeps", "ms_per_step",
/// "worst_error", "unit", "worst_member", "failing"}]}` (`ms_per_step` is the median).
/// A flag metric's value is a boolean; a missing or non-finite one is null.
pub fn write_json(report: &PhysicsReport, out: &mut dyn Write) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *out, report)?;
    writeln!(out)
}

/// Milliseconds rounded to the nanosecond, so JSON shows 0.001568 rather than 0.0015680000000000002.
fn round_ms(ms: f64) -> f64 {
    (ms * 1e6).round() / 1e6
}

/// Serializes milliseconds through [`round_ms`].
pub(crate) fn rounded_ms<S: Serializer>(ms: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_f64(round_ms(*ms))
}

/// Serializes a mean count rounded to a whole number.
fn rounded<S: Serializer>(x: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    serializer.serialize_f64(x.round())
}

/// `nudge bench physics [--json] [--quick]`: runs [`run`] and prints the report to stdout.
pub fn main(json: bool, quick: bool) -> anyhow::Result<()> {
    let report = run(quick);
    let stdout = io::stdout();
    let mut out = stdout.lock();
    if json {
        write_json(&report, &mut out)?;
    } else {
        print_table(&report, &mut out)?;
    }
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> PhysicsReport {
        PhysicsReport {
            quick: true,
            cases: vec![CaseRow {
                case: "bullet \"fast\"".into(),
                substeps: 4,
                iterations: 1,
                ms_per_step: 0.5,
                metrics: vec![
                    Metric {
                        name: "crossed wall",
                        value: Value::Flag(false),
                        unit: "",
                    },
                    Metric {
                        name: "rebound error",
                        value: Value::Missing,
                        unit: "%",
                    },
                    number("max x", f32::NAN, "m"),
                ],
            }],
            throughput: vec![ThroughputRow {
                scene: "rain(100)".into(),
                bodies: 105,
                sleep: false,
                steps: 60,
                ms_per_step: 1.25,
                mean_ms_per_step: 1.5,
                mean_contacts: 42.0,
                statics_found_percent: 12.5,
                awake_at_end: 100,
                window: "first 1 s".into(),
            }],
            stages: vec![super::super::stages::StageRow {
                scene: "pyramid(20) settled".into(),
                steps: 60,
                stages: crate::physics::Stage::ALL.map(|s| (s.name(), 0.5)),
                off_ms: 3.5,
                on_ms: 3.6,
            }],
            corpus: vec![super::super::corpus::CorpusRow {
                family: "ball drop".into(),
                members: 20,
                substeps: 4,
                ms_per_step: 0.001,
                worst_error: 0.25,
                unit: crate::testing::corpus::Unit::Relative,
                worst_member: "e=0.5 h=2m".into(),
                failing: 1,
            }],
        }
    }

    #[test]
    fn json_report_escapes_names_and_writes_flags_and_gaps_as_json_values() {
        let mut out = Vec::new();
        write_json(&sample(), &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let json: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
        let case = &json["cases"][0];
        assert_eq!(case["case"], "bullet \"fast\"", "{text}");
        let metric = |i: usize| (&case["metrics"][i]["value"], &case["metrics"][i]["unit"]);
        assert_eq!(metric(0), (&false.into(), &"".into()), "{text}");
        assert_eq!(metric(1), (&serde_json::Value::Null, &"%".into()), "{text}");
        assert_eq!(metric(2), (&serde_json::Value::Null, &"m".into()), "{text}");
        let row = &json["throughput"][0];
        assert_eq!(row["ms_per_step"], 1.25, "{text}");
        assert_eq!(row["mean_ms_per_step"], 1.5, "{text}");
        assert_eq!(row["mean_contacts"], 42.0, "{text}");
        assert_eq!(row["statics_found_percent"], 13.0, "{text}");
        assert_eq!(json["quick"], true, "{text}");
        assert_eq!(json["corpus"][0]["worst_member"], "e=0.5 h=2m", "{text}");
        assert_eq!(json["corpus"][0]["ms_per_step"], 0.001, "{text}");
        assert_eq!(json["corpus"][0]["unit"], "relative", "{text}");
        let stages = &json["stages"][0];
        assert_eq!(stages["stages"]["narrow phase"], 0.5, "{text}");
        assert_eq!(stages["on_ms"], 3.6, "{text}");
    }

    #[test]
    fn table_report_shows_each_case_with_its_error() {
        let mut out = Vec::new();
        print_table(&sample(), &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(
            text.contains("crossed wall no, rebound error none"),
            "{text}"
        );
        assert!(text.contains("rain(100)"), "{text}");
        assert!(text.contains("| ball drop"), "{text}");
        assert!(text.contains("25.000%"), "{text}");
        assert!(text.contains("| pyramid(20) settled"), "{text}");
        assert!(text.contains("+2.9%"), "{text}");
    }
}
