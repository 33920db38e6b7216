//! `nudge sim` as a user runs it: the binary, its last line, its trace file and its exit status.

use std::path::PathBuf;
use std::process::Output;

use nudge::scene::cases;

use crate::common;

use common::cli::{nudge, stderr, stdout};

/// A trace path unique to this test process and test.
fn temp_trace(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("nudge-sim-cli-{}-{name}.csv", std::process::id()))
}

/// Checks `line` against `^steps=\d+ bodies=\d+ mean_ms=\d+\.\d{4} median_ms=\d+\.\d{4}$` (no regex crate)
/// and returns (steps, bodies).
fn parse_summary(line: &str) -> (u64, usize) {
    let fields: Vec<&str> = line.split(' ').collect();
    assert_eq!(fields.len(), 4, "summary line {line:?}");
    let value = |field: &str, key: &str| -> String {
        field
            .strip_prefix(key)
            .and_then(|rest| rest.strip_prefix('='))
            .unwrap_or_else(|| panic!("expected {key}=… in {line:?}"))
            .to_string()
    };
    let integer = |text: &str| {
        assert!(
            !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit()),
            "{line:?}"
        );
        text.parse::<u64>().expect("digits")
    };
    let milliseconds = |text: &str| {
        let (whole, frac) = text.split_once('.').unwrap_or_else(|| panic!("{line:?}"));
        integer(whole);
        assert!(
            frac.len() == 4 && frac.bytes().all(|b| b.is_ascii_digit()),
            "{line:?}"
        );
    };
    let steps = integer(&value(fields[0], "steps"));
    let bodies = integer(&value(fields[1], "bodies")) as usize;
    milliseconds(&value(fields[2], "mean_ms"));
    milliseconds(&value(fields[3], "median_ms"));
    (steps, bodies)
}

fn last_line(output: &Output) -> String {
    stdout(output)
        .lines()
        .last()
        .expect("sim prints a summary line")
        .to_string()
}

#[test]
fn sim_prints_the_summary_as_its_last_line() {
    let output = nudge(&["sim", "--scene", "pyramid", "--steps", "5"]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(parse_summary(&last_line(&output)), (5, 211));
}

#[test]
fn sim_with_zero_steps_reports_zero_times() {
    let output = nudge(&["sim", "--scene", "pyramid", "--steps", "0"]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(
        last_line(&output),
        "steps=0 bodies=211 mean_ms=0.0000 median_ms=0.0000"
    );
}

#[test]
fn sim_accepts_every_solver_flag() {
    let output = nudge(&[
        "sim",
        "--scene",
        "rain",
        "--steps",
        "2",
        "--substeps",
        "2",
        "--iterations",
        "3",
        "--no-sleep",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert_eq!(parse_summary(&last_line(&output)), (2, 1005));
}

#[test]
fn the_trace_holds_every_body_at_every_step_in_round_trip_floats() {
    const STEPS: usize = 3;
    let path = temp_trace("round-trip");
    let output = nudge(&[
        "sim",
        "--scene",
        "pyramid",
        "--steps",
        &STEPS.to_string(),
        "--trace",
        path.to_str().expect("UTF-8 temp path"),
    ]);
    let text = std::fs::read_to_string(&path);
    let _ = std::fs::remove_file(&path);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = text.expect("the trace file was written");
    let scene = cases::pyramid(20);
    let bodies = scene.bodies.len();

    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("step,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), (STEPS + 1) * bodies);
    for (n, row) in rows.iter().enumerate() {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields.len(), 15, "row {n}: {row}");
        assert_eq!(fields[0], (n / bodies).to_string(), "row {n}: {row}");
        assert_eq!(fields[1], (n % bodies).to_string(), "row {n}: {row}");
        let values: Vec<f32> = fields[2..]
            .iter()
            .map(|f| {
                f.parse::<f32>()
                    .unwrap_or_else(|_| panic!("row {n}: {f:?}"))
            })
            .collect();
        for (field, value) in fields[2..].iter().zip(&values) {
            // Shortest round-trip: printing the parsed value gives the same text back.
            assert_eq!(value.to_string(), *field, "row {n}: {row}");
        }
        if n < bodies {
            // Step 0 is the scene as declared.
            let desc = &scene.bodies[n].desc;
            let p = desc.pose.position;
            let q = desc.pose.rotation;
            assert_eq!(
                &values[..7],
                &[p.x, p.y, p.z, q.x, q.y, q.z, q.w],
                "row {n}"
            );
        }
    }
}

#[test]
fn two_runs_of_the_same_scene_write_identical_traces() {
    let (a, b) = (temp_trace("determinism-a"), temp_trace("determinism-b"));
    for path in [&a, &b] {
        let output = nudge(&[
            "sim",
            "--scene",
            "rain",
            "--steps",
            "20",
            "--trace",
            path.to_str().expect("UTF-8 temp path"),
        ]);
        assert!(output.status.success(), "{}", stderr(&output));
    }
    let (text_a, text_b) = (std::fs::read(&a), std::fs::read(&b));
    let _ = (std::fs::remove_file(&a), std::fs::remove_file(&b));
    assert!(text_a.expect("trace a") == text_b.expect("trace b"));
}

/// Runs `args`, expects exit status 2 and a message on stderr containing every one of `needles`.
fn assert_bad_input(args: &[&str], needles: &[&str]) {
    let output = nudge(args);
    let message = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {message}");
    assert!(stdout(&output).is_empty(), "{args:?} printed to stdout");
    for needle in needles {
        assert!(
            message.contains(needle),
            "{args:?}: {message:?} lacks {needle:?}"
        );
    }
}

/// clap reads `-1` as an unknown flag ("unexpected argument '-1' found") unless the `--steps` argument
/// has `allow_negative_numbers = true`; with it the message names the flag and the bad value.
#[test]
fn negative_steps_are_rejected_naming_the_flag() {
    assert_bad_input(
        &["sim", "--scene", "pyramid", "--steps", "-1"],
        &["invalid value '-1' for '--steps"],
    );
}

#[test]
fn zero_substeps_are_rejected_naming_the_flag() {
    assert_bad_input(
        &[
            "sim",
            "--scene",
            "pyramid",
            "--steps",
            "1",
            "--substeps",
            "0",
        ],
        &["--substeps must be at least 1"],
    );
}

#[test]
fn an_unknown_scene_is_rejected_naming_it() {
    assert_bad_input(
        &["sim", "--scene", "no-such-scene", "--steps", "1"],
        &["no-such-scene"],
    );
}

#[test]
fn a_trace_path_in_a_missing_directory_is_rejected_before_running() {
    let path = std::env::temp_dir()
        .join(format!("nudge-no-such-dir-{}", std::process::id()))
        .join("trace.csv");
    let shown = path.to_str().expect("UTF-8 temp path");
    assert_bad_input(
        &[
            "sim", "--scene", "pyramid", "--steps", "1", "--trace", shown,
        ],
        &["--trace", shown, "does not exist"],
    );
}

#[test]
fn a_trace_path_naming_a_directory_is_rejected_before_running() {
    let dir = std::env::temp_dir();
    let shown = dir.to_str().expect("UTF-8 temp path");
    assert_bad_input(
        &[
            "sim", "--scene", "pyramid", "--steps", "1", "--trace", shown,
        ],
        &["--trace", "is a directory"],
    );
}

#[test]
fn sim_profile_prints_the_stage_table_before_the_summary() {
    let output = nudge(&["sim", "--scene", "pyramid", "--steps", "20", "--profile"]);
    assert!(output.status.success(), "{}", stderr(&output));
    let text = stdout(&output);
    assert!(text.contains("over 20 steps"), "{text}");
    for stage in [
        "broad phase",
        "narrow phase",
        "prepare",
        "solve",
        "integrate",
        "restitution+store",
        "sleep",
        "total",
    ] {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| {stage} ")))
            .unwrap_or_else(|| panic!("no {stage} row:\n{text}"));
        // ms/step and share are numbers.
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert!(cells[2].parse::<f64>().is_ok(), "{row}");
        assert!(cells[3].ends_with('%'), "{row}");
    }
    assert_eq!(parse_summary(&last_line(&output)), (20, 211));
    // Without the flag, no table.
    let plain = nudge(&["sim", "--scene", "pyramid", "--steps", "2"]);
    assert!(!stdout(&plain).contains("broad phase"));
}
