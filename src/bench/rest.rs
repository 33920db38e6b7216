//! `nudge bench rest`: whether a pile at rest stays at rest, awake as asleep.
//!
//! Every click in the sandbox wakes the island it lands on, so a pile a user built must stand as
//! still awake as asleep. For each pile of [`crate::scene::piles`] and each sub-step count in
//! {2, 4, 8}:
//! - **awake**: sleeping off; the pile settles for its `settle_s`, its positions are taken, then it
//!   runs [`AWAKE_S`] more seconds. Reported: the farthest any body moved from where it settled
//!   (drift), the fastest any body moved over the last second, and ms per step;
//! - **woken**: sleeping on; once the pile sleeps (or after [`SLEEP_WAIT_S`]), a 20 g ball of
//!   2 cm radius is dropped from 0.5 m onto its highest body, and the drift is read
//!   [`WOKEN_S`] seconds later (the ball itself left out).
//!
//! A pile passes when its drift is within [`MAX_DRIFT_M`] and (awake) its speed under
//! [`MAX_SPEED_M_S`].

use std::io::{self, Write};
use std::time::Instant;

use glam::Vec3;
use serde::Serialize;

use super::physics::rounded_ms;
use super::table::Table;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, World};
use crate::scene::piles::{self, Pile};

/// Seconds an awake pile is watched after it settled.
pub const AWAKE_S: f32 = 60.0;
/// Seconds a pile gets to fall asleep before the ball is dropped anyway.
pub const SLEEP_WAIT_S: f32 = 10.0;
/// Seconds after the drop at which a woken pile's drift is read.
pub const WOKEN_S: f32 = 10.0;
/// The target: within 1 mm of where it settled ...
pub const MAX_DRIFT_M: f32 = 0.001;
/// ... and under 1 mm/s.
pub const MAX_SPEED_M_S: f32 = 0.001;
/// The sub-step counts every pile is run at.
pub const SUBSTEPS: [u32; 3] = [2, 4, 8];

/// One pile at one sub-step count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RestRow {
    pub pile: String,
    pub substeps: u32,
    /// Awake: the farthest any body moved from where it settled, m.
    pub awake_drift_m: f32,
    /// Awake: the fastest any body moved over the last second, m/s.
    pub awake_speed_m_s: f32,
    /// Awake: the deepest overlap over the watch, m.
    pub awake_penetration_m: f32,
    /// Mean wall-clock ms per step over the awake watch.
    #[serde(serialize_with = "rounded_ms")]
    pub awake_ms_per_step: f64,
    /// Woken: the farthest any of the pile's bodies moved from where it slept, m.
    pub woken_drift_m: f32,
    /// Whether the pile was asleep when the ball was dropped.
    pub slept: bool,
}

impl RestRow {
    /// Whether both runs met the targets.
    pub fn holds(&self) -> bool {
        self.awake_drift_m <= MAX_DRIFT_M
            && self.awake_speed_m_s <= MAX_SPEED_M_S
            && self.woken_drift_m <= MAX_DRIFT_M
    }
}

/// Runs every pile at every sub-step count (`quick`: 4 sub-steps only, watched 10 s).
pub fn run(quick: bool) -> Vec<RestRow> {
    let substeps: &[u32] = if quick { &[4] } else { &SUBSTEPS };
    let awake_s = if quick { 10.0 } else { AWAKE_S };
    let mut rows = Vec::new();
    for pile in piles::all() {
        for &n in substeps {
            super::progress!(
                "bench rest: {} at {n} sub-steps{}\r",
                pile.scene.name,
                " ".repeat(20)
            );
            rows.push(measure(&pile, n, awake_s));
        }
    }
    rows
}

fn world(pile: &Pile, substeps: u32, sleep: bool) -> World {
    let mut settings = pile.scene.settings.clone();
    settings.substeps = substeps;
    settings.sleep = sleep;
    pile.scene.build_world_with(settings)
}

fn steps_in(world: &World, seconds: f32) -> usize {
    (seconds / world.settings().dt).round() as usize
}

fn positions(world: &World) -> Vec<Vec3> {
    world.bodies().iter().map(|b| b.pose().position).collect()
}

/// The farthest any of the first `rest.len()` bodies is from its position in `rest`, m.
fn drift(world: &World, rest: &[Vec3]) -> f32 {
    world
        .bodies()
        .iter()
        .zip(rest)
        .map(|(b, r)| b.pose().position.distance(*r))
        .fold(0.0, f32::max)
}

/// What a pile did while kept awake (see [`watch_awake`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AwakeRun {
    /// The farthest any body moved from where it settled, m.
    pub drift_m: f32,
    /// The fastest any body moved over the last second, m/s.
    pub speed_m_s: f32,
    /// The deepest overlap over the watch, m.
    pub penetration_m: f32,
    /// Mean wall-clock ms per step over the watch.
    pub ms_per_step: f64,
}

/// Keeps `pile` awake at `substeps` sub-steps: it settles for its `settle_s`, then is watched for
/// `seconds`.
pub fn watch_awake(pile: &Pile, substeps: u32, seconds: f32) -> AwakeRun {
    let mut world = world(pile, substeps, false);
    for _ in 0..steps_in(&world, pile.settle_s) {
        world.step();
    }
    let rest = positions(&world);
    let steps = steps_in(&world, seconds);
    let last_second = steps.saturating_sub(steps_in(&world, 1.0));
    let (mut speed, mut penetration, mut elapsed) = (0.0f32, 0.0f32, 0.0f64);
    for step in 0..steps {
        let start = Instant::now();
        world.step();
        elapsed += start.elapsed().as_secs_f64();
        penetration = penetration.max(world.max_penetration());
        if step >= last_second {
            let fastest = world
                .bodies()
                .iter()
                .map(|b| b.linear_velocity().length())
                .fold(0.0, f32::max);
            speed = speed.max(fastest);
        }
    }
    AwakeRun {
        drift_m: drift(&world, &rest),
        speed_m_s: speed,
        penetration_m: penetration,
        ms_per_step: elapsed * 1000.0 / steps.max(1) as f64,
    }
}

fn measure(pile: &Pile, substeps: u32, awake_s: f32) -> RestRow {
    let awake = watch_awake(pile, substeps, awake_s);
    let (woken_drift_m, slept) = woken(pile, substeps);
    RestRow {
        pile: pile.scene.name.clone(),
        substeps,
        awake_drift_m: awake.drift_m,
        awake_speed_m_s: awake.speed_m_s,
        awake_penetration_m: awake.penetration_m,
        awake_ms_per_step: awake.ms_per_step,
        woken_drift_m,
        slept,
    }
}

/// The pile left to sleep, then hit by a small ball: (its drift [`WOKEN_S`] after, whether it slept).
pub fn woken(pile: &Pile, substeps: u32) -> (f32, bool) {
    let mut world = world(pile, substeps, true);
    for _ in 0..steps_in(&world, pile.settle_s) {
        world.step();
    }
    let mut waited = 0;
    while world.awake_count() > 0 && waited < steps_in(&world, SLEEP_WAIT_S) {
        world.step();
        waited += 1;
    }
    let slept = world.awake_count() == 0;
    let rest = positions(&world);
    let top = world
        .bodies()
        .iter()
        .filter(|b| !b.is_static())
        .map(|b| b.shape().aabb(b.pose()))
        .max_by(|a, b| a.max.y.total_cmp(&b.max.y));
    if let Some(top) = top {
        let above = Vec3::new(
            0.5 * (top.min.x + top.max.x),
            top.max.y + 0.5,
            0.5 * (top.min.z + top.max.z),
        );
        world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.02),
            Pose::from_position(above),
            0.02,
        ));
    }
    for _ in 0..steps_in(&world, WOKEN_S) {
        world.step();
    }
    (drift(&world, &rest), slept)
}

/// Prints the rows as a table.
pub fn print_table(rows: &[RestRow], out: &mut dyn Write) -> io::Result<()> {
    writeln!(
        out,
        "rest: piles kept awake {AWAKE_S} s after settling (sleeping off), and asleep then hit by a 20 g ball (drift {WOKEN_S} s after); target: within {} mm and under {} mm/s",
        MAX_DRIFT_M * 1000.0,
        MAX_SPEED_M_S * 1000.0
    )?;
    let mut table = Table::new(&[
        "pile",
        "sub-steps",
        "awake drift mm",
        "awake speed mm/s",
        "awake overlap mm",
        "ms/step",
        "woken drift mm",
        "holds",
    ]);
    for r in rows {
        table.push(vec![
            r.pile.clone(),
            r.substeps.to_string(),
            format!("{:.3}", r.awake_drift_m * 1000.0),
            format!("{:.3}", r.awake_speed_m_s * 1000.0),
            format!("{:.3}", r.awake_penetration_m * 1000.0),
            format!("{:.4}", r.awake_ms_per_step),
            format!(
                "{:.3}{}",
                r.woken_drift_m * 1000.0,
                if r.slept { "" } else { " (never slept)" }
            ),
            if r.holds() { "yes" } else { "no" }.to_string(),
        ]);
    }
    table.write(out)
}
