//! `nudge bench rest --scene FILE`: a pile a user built is measured as the built-in piles are, and
//! `--pile` picks among those by name.

use std::process::Output;

use crate::common::cli::{nudge, stderr};
use crate::common::temp::TempPath;

/// The rows of `nudge bench rest ... --json`.
fn rest_rows(out: &Output) -> Vec<serde_json::Value> {
    assert_eq!(out.status.code(), Some(0), "{}", stderr(out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("a JSON report");
    report["rest"].as_array().expect("a rest section").clone()
}

/// Two boxes on a floor, as Ctrl+S would save a small pile: it rests, awake and woken.
const TWO_BOXES: &str = r#"
[[body]]
shape = "box"
half_extents = [4.0, 0.5, 4.0]
position = [0.0, -0.5, 0.0]
static = true

[[body]]
shape = "box"
half_extents = [0.5, 0.5, 0.5]
position = [0.0, 0.5, 0.0]

[[body]]
shape = "box"
half_extents = [0.25, 0.25, 0.25]
position = [0.1, 1.25, 0.0]
"#;

#[test]
fn a_pile_from_a_scene_file_is_measured_as_the_built_in_piles_are() {
    let file = TempPath::with_text("two-boxes.toml", TWO_BOXES);
    let rows = rest_rows(&nudge(&[
        "bench",
        "rest",
        "--scene",
        file.as_str(),
        "--settle",
        "0.5",
        "--quick",
        "--json",
    ]));
    assert_eq!(rows.len(), 1, "{rows:?}");
    let row = &rows[0];
    assert_eq!(row["pile"], file.as_str());
    assert_eq!(row["substeps"], 4);
    // A small box on a bigger one stays within the target awake and woken (it measures 0 mm).
    assert_eq!(row["awake_holding"], 1, "{row}");
    assert_eq!(row["woken_holding"], 1, "{row}");
    assert!(row["awake_drift_m"][1].as_f64().unwrap() < 1e-4, "{row}");
    assert_eq!(row["slept"], true, "{row}");
}

#[test]
fn pile_picks_the_built_in_piles_by_a_part_of_their_name() {
    let rows = rest_rows(&nudge(&[
        "bench", "rest", "--pile", "BOX ON", "--quick", "--json",
    ]));
    let names: Vec<&str> = rows.iter().map(|r| r["pile"].as_str().unwrap()).collect();
    assert_eq!(names, ["box on balls", "box on a 30° ramp"]);
    let rows = rest_rows(&nudge(&[
        "bench", "rest", "--pile", "wall", "--quick", "--json",
    ]));
    let names: Vec<&str> = rows.iter().map(|r| r["pile"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "running bond wall(12)",
            "brick wall(12), 215 × 102.5 × 65 mm"
        ]
    );
}

#[test]
fn choosing_piles_is_refused_where_it_means_nothing() {
    let out = nudge(&["bench", "rest", "--pile", "nope"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("no pile's name contains it"), "{err}");
    assert!(err.contains("running bond wall(12)"), "{err}");

    let out = nudge(&["bench", "physics", "--scene", "stack"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("`nudge bench rest`"),
        "{}",
        stderr(&out)
    );

    for args in [
        &["bench", "rest", "--settle", "2"][..],
        &["bench", "rest", "--scene", "stack", "--pile", "wall"],
        &["bench", "rest", "--scene", "stack", "--settle", "-1"],
    ] {
        assert_eq!(nudge(args).status.code(), Some(2), "{args:?}");
    }

    let out = nudge(&["bench", "rest", "--scene", "no-such-pile.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("no such file"), "{}", stderr(&out));
}
