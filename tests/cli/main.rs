//! The command line and scene files: arguments and values, `nudge sim` and `nudge snapshot`, scene-file errors, files and orientation.
//!
//! One test crate per area (each integration-test file used to link the whole library on its own).

#[path = "../common/mod.rs"]
mod common;

mod arguments;
mod bench_rest;
mod joint_files;
mod scene_errors;
mod scene_files;
mod scene_orientation;
mod schema;
mod sim_cli;
mod snapshot;
mod values;
