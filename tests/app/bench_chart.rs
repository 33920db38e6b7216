//! `nudge bench physics --chart`, as a user runs it: a quick sweep drawn as one chart per hard case,
//! in a pipe, with colours or characters only.

use crate::common;

use common::cli::nudge;

#[test]
fn the_chart_prints_for_a_quick_bench() {
    let out = nudge(&["bench", "physics", "--quick", "--chart", "--plain"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("utf-8");
    assert!(!text.contains('\x1b'), "no escapes with --plain");
    // One chart per case with a numeric error (the bullet's is a yes/no), each with its default.
    let cases = [
        "stack(10)",
        "pyramid(20)",
        "mass ratio 1000:1",
        "1 kg pinned, pushed",
        "bounce e=0.5",
        "ramp mu=0.7",
        "ramp mu=0.3",
        "rolling ball",
        "projectile",
        "deep overlap",
        "stack(5) at origin",
        "stack(5) at 5000 m",
        "intermediate axis",
    ];
    for case in cases {
        assert!(
            text.contains(&format!("┌ {case} ")),
            "{case} missing:\n{text}"
        );
    }
    assert_eq!(text.matches('█').count(), cases.len() + 1, "{text}");
    assert!(text.matches("ms/step").count() >= cases.len());

    let colour = nudge(&["bench", "physics", "--quick", "--chart", "--colors", "256"]);
    assert!(colour.status.success());
    let colour = String::from_utf8(colour.stdout).expect("utf-8");
    assert!(colour.contains("\x1b["), "colour escapes without --plain");
    assert!(!colour.contains("38;2;"), "no truecolor at 256 colours");
}

#[test]
fn chart_is_for_the_physics_bench_only_and_not_with_json() {
    for args in [
        &["bench", "render", "--chart"][..],
        &["bench", "physics", "--chart", "--json"][..],
        &["bench", "physics", "--plain"][..],
    ] {
        let out = nudge(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
    }
}
