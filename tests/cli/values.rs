//! The command line's closed sets of values (render modes, colour depths, dithers, projections,
//! benchmarks)
//! and `--size`, parsed by clap: every spelling the README documents is accepted, in any case, and
//! nothing else.

use clap::Parser;
use nudge::bench::Which;
use nudge::cli::{CellCount, Cli, Command, ProjectionFlag, SnapshotArgs};
use nudge::render::RenderMode;
use nudge::term::{ColorDepth, Dither};

fn snapshot(args: &[&str]) -> Result<SnapshotArgs, clap::Error> {
    let cli = Cli::try_parse_from(["nudge", "snapshot"].iter().chain(args))?;
    match cli.command {
        Some(Command::Snapshot(args)) => Ok(args),
        other => panic!("not a snapshot: {other:?}"),
    }
}

#[test]
fn every_render_mode_is_accepted_by_its_status_bar_name_in_any_case() {
    for mode in RenderMode::ALL {
        assert_eq!(snapshot(&["--mode", mode.name()]).unwrap().mode, mode);
        let upper = mode.name().to_uppercase();
        assert_eq!(snapshot(&["--mode", &upper]).unwrap().mode, mode);
    }
    assert_eq!(snapshot(&[]).unwrap().mode, RenderMode::Textured);
    assert!(snapshot(&["--mode", "phong"]).is_err());
}

#[test]
fn dither_modes_are_accepted_by_name_in_any_case_and_default_to_ordered() {
    for dither in Dither::ALL {
        assert_eq!(
            snapshot(&["--dither", dither.name()]).unwrap().dither,
            dither
        );
        let upper = dither.name().to_uppercase();
        assert_eq!(snapshot(&["--dither", &upper]).unwrap().dither, dither);
    }
    assert_eq!(snapshot(&[]).unwrap().dither, Dither::Ordered);
    for bad in ["", "bayer", "floyd-steinberg"] {
        assert!(snapshot(&["--dither", bad]).is_err(), "{bad:?}");
    }
}

#[test]
fn colour_depths_accept_their_names_and_24bit() {
    for depth in ColorDepth::ALL {
        assert_eq!(
            snapshot(&["--colors", depth.name()]).unwrap().colors,
            Some(depth)
        );
    }
    for truecolor in ["TrueColor", "24bit", "24BIT"] {
        assert_eq!(
            snapshot(&["--colors", truecolor]).unwrap().colors,
            Some(ColorDepth::TrueColor)
        );
    }
    assert_eq!(snapshot(&[]).unwrap().colors, None);
    for bad in ["", "8", "255", "true", "ansi", "256color"] {
        assert!(snapshot(&["--colors", bad]).is_err(), "{bad:?}");
    }
}

#[test]
fn projections_and_sizes_parse() {
    let args = snapshot(&["--projection", "orthographic", "--size", "120X40"]).unwrap();
    assert_eq!(args.projection, Some(ProjectionFlag::Orthographic));
    assert_eq!(
        args.size,
        CellCount {
            cols: 120,
            rows: 40
        }
    );
    let args = snapshot(&["--projection", "Perspective"]).unwrap();
    assert_eq!(args.projection, Some(ProjectionFlag::Perspective));
    assert_eq!(
        snapshot(&[]).unwrap().size,
        CellCount { cols: 80, rows: 24 }
    );
    for bad in ["0x10", "80", "1001x10", "80x", "x24", "-1x5"] {
        assert!(snapshot(&["--size", bad]).is_err(), "{bad:?}");
    }
}

#[test]
fn bench_takes_one_of_its_sections() {
    let parse = |args: &[&str]| match Cli::try_parse_from(["nudge", "bench"].iter().chain(args)) {
        Ok(Cli {
            command: Some(Command::Bench(args)),
            ..
        }) => Some(args.what),
        _ => None,
    };
    assert_eq!(parse(&[]), Some(Which::All));
    for (name, which) in [
        ("all", Which::All),
        ("render", Which::Render),
        ("physics", Which::Physics),
        ("app", Which::App),
        ("rewind", Which::Rewind),
        ("kernels", Which::Kernels),
        ("corpus", Which::Corpus),
    ] {
        assert_eq!(parse(&[name]), Some(which));
    }
    assert_eq!(parse(&["everything"]), None);
}
