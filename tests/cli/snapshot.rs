//! The binary as a user meets it: snapshots in pipes, the sandbox refusing a non-terminal, bad flags.

use crate::common;

use common::cli::{nudge, stderr};

#[test]
fn plain_snapshot_prints_one_line_per_row_of_characters_only() {
    let out = nudge(&["snapshot", "--size", "40x12", "--plain"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 12);
    assert!(lines.iter().all(|l| l.chars().count() <= 40));
    assert!(!text.contains('\x1b'), "no escape codes in --plain");
    assert!(
        text.chars().any(|c| c != ' ' && c != '\n'),
        "something is drawn"
    );
}

#[test]
fn colour_snapshot_uses_half_blocks_and_the_requested_palette() {
    let out = nudge(&["snapshot", "--size", "30x10", "--colors", "256"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(text.contains('▀'));
    assert!(text.contains("\x1b[38;5;") || text.contains("\x1b[48;5;"));
    assert!(
        !text.contains("38;2;"),
        "no truecolor escapes at 256 colours"
    );
    assert_eq!(text.lines().count(), 10);
}

#[test]
fn every_mode_and_projection_snapshots() {
    for mode in [
        "wireframe",
        "flat",
        "smooth",
        "textured",
        "depth",
        "normals",
    ] {
        for projection in ["perspective", "orthographic"] {
            let out = nudge(&[
                "snapshot",
                "--size",
                "20x8",
                "--mode",
                mode,
                "--projection",
                projection,
                "--plain",
            ]);
            assert!(
                out.status.success(),
                "{mode} {projection}: {}",
                stderr(&out)
            );
        }
    }
}

#[test]
fn bad_snapshot_flags_exit_2_with_a_message() {
    for (args, phrase) in [
        (&["snapshot", "--size", "0x10"][..], "--size"),
        (&["snapshot", "--size", "80"][..], "--size"),
        (
            &["snapshot", "--mode", "glossy"][..],
            "possible values: wireframe, flat, smooth, textured, depth, normals",
        ),
        (
            &["snapshot", "--projection", "fisheye"][..],
            "possible values: perspective, orthographic",
        ),
        (
            &["snapshot", "--colors", "12"][..],
            "possible values: truecolor, 256, 16",
        ),
        (
            &["snapshot", "--scene", "no-such-scene"][..],
            "no-such-scene",
        ),
        (
            &["bench", "everything"][..],
            "possible values: all, render, physics, app, rewind, kernels",
        ),
    ] {
        let out = nudge(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(phrase), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
    }
}

#[test]
fn the_sandbox_refuses_a_non_terminal_and_points_at_snapshot() {
    for args in [&[][..], &["run"][..]] {
        let out = nudge(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(stderr(&out).contains("nudge snapshot"), "{}", stderr(&out));
        assert!(out.stdout.is_empty(), "nothing written to a non-terminal");
    }
}

#[test]
fn scenes_lists_every_built_in_scene() {
    let out = nudge(&["scenes"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).expect("utf-8");
    for name in [
        "default", "stack", "pyramid", "ramp", "dominoes", "pendulum", "cradle", "chain", "bridge",
        "door", "rain", "wrecking",
    ] {
        assert!(text.lines().any(|l| l.starts_with(name)), "{name} listed");
    }
}

#[test]
fn an_octant_snapshot_prints_octant_glyphs_in_the_same_rows() {
    let out = nudge(&[
        "snapshot",
        "--size",
        "40x12",
        "--colors",
        "truecolor",
        "--cells",
        "octant",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert_eq!(text.lines().count(), 12);
    assert!(
        text.chars()
            .any(|c| ('\u{1CD00}'..='\u{1CDE5}').contains(&c)),
        "octant glyphs"
    );
    assert!(
        !text
            .chars()
            .any(|c| ('\u{1FB00}'..='\u{1FB3B}').contains(&c)),
        "no sextants in octant mode"
    );
}

#[test]
fn the_cells_test_card_names_every_mode() {
    let out = nudge(&["cells", "--colors", "256"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).expect("utf-8");
    for name in ["half", "quadrant", "sextant", "octant"] {
        assert!(
            text.lines().any(|l| l.contains(name)),
            "{name} missing:\n{text}"
        );
    }
    assert!(text.contains('\u{1CD00}') && text.contains('\u{1FB00}') && text.contains('▚'));
    assert!(!text.contains("38;2;"), "256 colours asked for");
}

#[test]
fn an_unknown_cell_mode_is_a_usage_error_that_lists_the_modes() {
    let out = nudge(&["snapshot", "--cells", "braille"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("octant") && err.contains("quadrant"), "{err}");
}
