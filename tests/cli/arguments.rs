//! The command line checks its arguments first and says what is wrong with a value.

use std::process::{Command, Output, Stdio};

fn nudge(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_nudge"));
    command.args(args).stdin(Stdio::null());
    for (key, value) in env {
        command.env(key, value);
    }
    command.output().expect("nudge runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `nudge --scene nope > file` said "stdout is not a terminal".
#[test]
fn a_missing_scene_is_reported_before_the_missing_terminal() {
    let out = nudge(&["--scene", "nope"], &[]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("nope: no built-in scene"), "{err}");
    assert!(!err.contains("not a terminal"), "{err}");
}

/// clap said "unexpected argument '-1' found".
#[test]
fn negative_counts_and_aspects_say_what_is_wrong_with_the_value() {
    for args in [
        &["snapshot", "--steps", "-1"][..],
        &["sim", "--scene", "default", "--steps", "-1"],
        &["run", "--max-bytes-per-second", "-5"],
    ] {
        let out = nudge(args, &[]);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains("cannot be negative"), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    for args in [
        &["snapshot", "--cell-aspect", "-1"][..],
        &["--cell-aspect", "-1", "--scene", "default"],
    ] {
        let out = nudge(args, &[]);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains("--cell-aspect must be between"),
            "{args:?}: {err}"
        );
    }
    let err = stderr(&nudge(
        &["sim", "--scene", "default", "--steps", "1.5"],
        &[],
    ));
    assert!(err.contains("must be a whole number"), "{err}");
}

/// `--fps -5` said "must be 0 or more", and then `--fps 0` said "between 1 and 240": one message
/// for every value outside the range sends nobody round twice.
#[test]
fn every_frame_rate_outside_its_range_gets_the_range() {
    for value in ["-5", "0", "241", "2.5", "fast"] {
        for command in [
            &["--fps", value][..],
            &["replay", "x.jsonl", "--fps", value],
        ] {
            let out = nudge(command, &[]);
            assert_eq!(out.status.code(), Some(2), "{command:?}");
            let err = stderr(&out);
            assert!(
                err.contains("must be a whole number between 1 and 240"),
                "{command:?}: {err}"
            );
        }
    }
}

#[test]
fn help_help_works_and_help_names_a_subcommand() {
    let out = nudge(&["help", "--help"], &[]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: nudge help"));
    let out = nudge(&["help", "sim"], &[]);
    assert_eq!(out.status.code(), Some(0));
    assert!(String::from_utf8_lossy(&out.stdout).contains("Usage: nudge sim"));
    // The same page, in the same layout, as `COMMAND --help` (the long layout differed: issue 28).
    for command in [
        "run", "sim", "snapshot", "scenes", "replay", "bench", "help",
    ] {
        let (a, b) = (
            nudge(&["help", command], &[]),
            nudge(&[command, "--help"], &[]),
        );
        assert_eq!(a.status.code(), Some(0), "{command}: {}", stderr(&a));
        assert_eq!(
            String::from_utf8_lossy(&a.stdout),
            String::from_utf8_lossy(&b.stdout),
            "{command}"
        );
    }
    let out = nudge(&["help"], &[]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("snapshot"));
    assert_eq!(nudge(&["help", "nope"], &[]).status.code(), Some(2));
}

#[test]
fn colors_24bit_is_a_synonym_of_truecolor_everywhere() {
    let snapshot = |colors: &str| nudge(&["snapshot", "--size", "20x6", "--colors", colors], &[]);
    let (a, b) = (snapshot("24bit"), snapshot("truecolor"));
    assert_eq!(a.status.code(), Some(0), "{}", stderr(&a));
    assert_eq!(a.stdout, b.stdout);
    // The sandbox and the replay accept it too: they get as far as needing a terminal.
    for args in [&["--colors", "24bit"][..], &["run", "--colors", "24bit"]] {
        let err = stderr(&nudge(args, &[]));
        assert!(err.contains("not a terminal"), "{args:?}: {err}");
    }
    let err = stderr(&nudge(&["snapshot", "--colors", "8"], &[]));
    assert!(
        err.contains("[possible values: truecolor, 256, 16]"),
        "{err}"
    );
}

/// Progress lines end in a carriage return: redirected, they became one long line.
#[test]
fn bench_progress_is_written_only_to_a_terminal() {
    let out = nudge(&["bench", "physics", "--quick"], &[]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(!stderr(&out).contains('\r'), "{:?}", stderr(&out));
}

/// A dumb terminal got full-screen escape codes.
#[test]
fn term_dumb_is_pointed_at_plain_snapshots() {
    let out = nudge(&[], &[("TERM", "dumb")]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("nudge snapshot --plain"), "{err}");
    assert!(out.stdout.is_empty());
}
