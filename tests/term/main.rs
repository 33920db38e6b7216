//! The terminal layer: cells, colours, escape sequences, probes, and the real binary on a pseudo-terminal (signals, hang-ups, silence).
//!
//! One test crate per area (each integration-test file used to link the whole library on its own).

#[cfg(target_os = "linux")]
#[path = "../pty/mod.rs"]
mod pty;

mod ansi;
mod cells;
mod colour;
mod guard;
mod half_block;
mod hangup;
mod probe;
mod probe_pty;
mod signals;
mod silent;
