//! The app driven headless: synthetic keys and mouse events into `App`, assertions on its `Buffer` and status line (hands, panels, help, time control, the inspector).
//!
//! One test crate per area (each integration-test file used to link the whole library on its own).

#[path = "../common/mod.rs"]
mod common;
#[cfg(target_os = "linux")]
#[path = "../pty/mod.rs"]
mod pty;

mod backgrounds;
mod bench_chart;
mod bytes;
mod cells;
mod controls_readme;
mod first_minutes;
mod framing;
mod fuzz;
mod hands;
mod hands_alongside;
mod hands_suspend;
mod help;
mod inspect_overlay_colours;
mod inspect_overlays;
mod inspect_panel;
mod inspect_settings;
mod interaction;
mod jointed;
mod nothing_lost;
mod picking;
mod spawn;
mod status_truth;
mod time_control;
