//! `nudge bench kernels`: the physics kernels one call at a time, so the per-call figures quoted in
//! `collide/box_box.rs`, `broad_phase.rs` and the README can be rerun by anyone.
//!
//! - **collide**: [`collide`] on fixed shape pairs (the cases of `box_box`'s table, and a box–sphere and
//!   a sphere–sphere pair), ns per call.
//! - **broad phase**: [`BroadPhase::find_pairs`] on snapshots of the raining pit (sleeping off) after
//!   10, 40, 80 and 150 steps, µs per call; the boxes are the bodies' exact boxes grown by half the
//!   speculative distance (what the step gives it, less the sweep over v·dt).
//! - **solver**: a step of the settled 210-box pyramid with sleeping off, where the broad phase's
//!   pairs and every manifold are reused, so the step is preparing and solving the contacts; reported
//!   per step and per contact per sub-step.
//!
//! Each figure is the median over batches of calls (a batch long enough for the clock), on one core.

use std::hint::black_box;
use std::time::Instant;

use glam::{Quat, Vec3};
use serde::Serialize;

use crate::geometry::{Aabb, Pose, Shape};
use crate::physics::World;
use crate::physics::broad::broad_phase::{BodyKind, BroadPhase};
use crate::physics::narrow::collide::collide;
use crate::scene::cases;
use crate::util::median;

/// One kernel on one input.
#[derive(Clone, Debug, Serialize)]
pub struct KernelRow {
    /// "collide", "broad phase" or "solver".
    pub kernel: &'static str,
    /// The input.
    pub case: String,
    /// Median wall time per call, ns.
    pub ns_per_call: f64,
    /// What one call produced: contact points, pairs, or contacts solved.
    pub output: usize,
    /// What `output` counts.
    pub output_unit: &'static str,
}

/// Runs every kernel; `quick` takes fewer batches.
pub fn run(quick: bool) -> Vec<KernelRow> {
    let batches = if quick { 5 } else { 31 };
    let mut rows = collide_rows(batches);
    rows.extend(broad_phase_rows(batches, quick));
    rows.push(solver_row(batches, quick));
    rows
}

/// Median ns per call of `f` over `batches` batches of `calls` calls, after one call to warm up (also
/// what `mechanisms` times with).
pub(super) fn time_per_call(batches: usize, calls: usize, mut f: impl FnMut()) -> f64 {
    f();
    let mut samples: Vec<f64> = (0..batches)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..calls {
                f();
            }
            start.elapsed().as_secs_f64() * 1e9 / calls as f64
        })
        .collect();
    median(&mut samples)
}

fn collide_rows(batches: usize) -> Vec<KernelRow> {
    let unit = Shape::cuboid(Vec3::splat(0.5));
    let floor = Shape::cuboid(Vec3::new(10.0, 0.5, 10.0));
    let ball = Shape::sphere(0.5);
    let at = |x: f32, y: f32, z: f32| Pose::from_position(Vec3::new(x, y, z));
    let turned = |angle: f32, axis: Vec3, position: Vec3| Pose {
        position,
        rotation: Quat::from_axis_angle(axis, angle),
    };
    let cases: [(&str, Shape, Pose, Shape, Pose); 7] = [
        (
            "box-box separated (early out on a face axis)",
            unit,
            at(0.0, 0.0, 0.0),
            unit,
            at(3.0, 0.2, 0.1),
        ),
        (
            "box-box unit box resting on a floor (no clip)",
            floor,
            at(0.0, -0.5, 0.0),
            unit,
            at(0.0, 0.499, 0.0),
        ),
        (
            "box-box unit box on a unit box, offset (clip)",
            unit,
            at(0.0, 0.0, 0.0),
            unit,
            at(0.4, 0.999, 0.3),
        ),
        (
            "box-box 45°-turned box on a box (8 -> 4 points)",
            unit,
            at(0.0, 0.0, 0.0),
            unit,
            turned(
                std::f32::consts::FRAC_PI_4,
                Vec3::Y,
                Vec3::new(0.0, 0.999, 0.0),
            ),
        ),
        (
            "box-box crossed edges",
            unit,
            at(0.0, 0.0, 0.0),
            unit,
            Pose {
                position: Vec3::new(0.0, 1.2, 0.0),
                rotation: Quat::from_rotation_x(std::f32::consts::FRAC_PI_4)
                    * Quat::from_rotation_z(std::f32::consts::FRAC_PI_4),
            },
        ),
        (
            "box-sphere ball resting on a box",
            unit,
            at(0.0, 0.0, 0.0),
            ball,
            at(0.1, 0.999, -0.1),
        ),
        (
            "sphere-sphere touching balls",
            ball,
            at(0.0, 0.0, 0.0),
            ball,
            at(0.6, 0.8, 0.0),
        ),
    ];
    let margin = 0.02;
    cases
        .into_iter()
        .map(|(case, shape_a, pose_a, shape_b, pose_b)| {
            let points = collide(&shape_a, &pose_a, &shape_b, &pose_b, margin).len;
            let ns = time_per_call(batches, 20_000, || {
                black_box(collide(
                    black_box(&shape_a),
                    black_box(&pose_a),
                    black_box(&shape_b),
                    black_box(&pose_b),
                    black_box(margin),
                ));
            });
            KernelRow {
                kernel: "collide",
                case: case.to_string(),
                ns_per_call: ns,
                output: points,
                output_unit: "points",
            }
        })
        .collect()
}

/// The bodies' boxes and kinds as the step hands them to the broad phase, less the sweep.
fn broad_phase_input(world: &World) -> (Vec<Aabb>, Vec<BodyKind>) {
    let half_margin = 0.5 * world.settings().speculative_distance;
    world
        .bodies()
        .iter()
        .map(|body| {
            let aabb = body.shape.aabb(&body.pose);
            if body.is_static {
                (aabb, BodyKind::Static)
            } else {
                (aabb.expanded(half_margin), BodyKind::Dynamic)
            }
        })
        .unzip()
}

fn broad_phase_rows(batches: usize, quick: bool) -> Vec<KernelRow> {
    let counts: &[usize] = if quick { &[1000] } else { &[1000, 4000] };
    let mut rows = Vec::new();
    for &count in counts {
        let scene = cases::rain(count);
        let mut settings = scene.settings.clone();
        settings.sleep = false;
        let mut world = scene.build_world_with(settings);
        let mut steps = 0;
        for snapshot in [10, 40, 80, 150] {
            while steps < snapshot {
                world.step();
                steps += 1;
            }
            let (aabbs, kinds) = broad_phase_input(&world);
            let mut broad_phase = BroadPhase::new();
            let mut pairs = Vec::new();
            let calls = if count > 1000 { 20 } else { 100 };
            let ns = time_per_call(batches, calls, || {
                broad_phase.find_pairs(black_box(&aabbs), black_box(&kinds), &mut pairs);
            });
            rows.push(KernelRow {
                kernel: "broad phase",
                case: format!("rain({count}) after {snapshot} steps"),
                ns_per_call: ns,
                output: pairs.len(),
                output_unit: "pairs",
            });
        }
    }
    rows
}

fn solver_row(batches: usize, quick: bool) -> KernelRow {
    let scene = cases::pyramid(20);
    let mut settings = scene.settings.clone();
    settings.sleep = false;
    let mut world = scene.build_world_with(settings);
    let settle_steps = if quick { 300 } else { 600 };
    for _ in 0..settle_steps {
        world.step();
    }
    let ns = time_per_call(batches, 20, || world.step());
    KernelRow {
        kernel: "solver",
        case: format!(
            "pyramid(20) settled, sleeping off, {} sub-steps (pairs and manifolds reused)",
            world.settings().substep_count()
        ),
        ns_per_call: ns,
        output: world.contact_count(),
        output_unit: "contacts",
    }
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(rows: &[KernelRow], out: &mut dyn std::io::Write) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "kernels: one call at a time, median over batches (see bench/kernels.rs for the inputs)"
    )?;
    let mut table = Table::new(&["kernel", "input", "ns/call", "output"]);
    for r in rows {
        table.push(vec![
            r.kernel.to_string(),
            r.case.clone(),
            format!("{:.0}", r.ns_per_call),
            format!("{} {}", r.output, r.output_unit),
        ]);
    }
    table.write(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The inputs are what their names say: the collide cases make the points their names promise, the
    /// raining pit has pairs, the pyramid has its contacts.
    #[test]
    fn each_kernel_measures_the_input_it_names() {
        let rows = run(true);
        let output = |case: &str| {
            rows.iter()
                .find(|r| r.case.starts_with(case))
                .unwrap_or_else(|| panic!("no row {case}"))
                .output
        };
        assert_eq!(output("box-box separated"), 0);
        assert_eq!(output("box-box unit box resting on a floor"), 4);
        assert_eq!(output("box-box unit box on a unit box"), 4);
        assert_eq!(output("box-box 45°-turned"), 4);
        assert!((1..=2).contains(&output("box-box crossed edges")));
        assert_eq!(output("box-sphere"), 1);
        assert_eq!(output("sphere-sphere"), 1);
        assert!(output("rain(1000) after 150 steps") > 100);
        // 210 boxes: each on the floor or on two below it, and its row neighbours within the margin.
        assert!(output("pyramid(20)") >= 210);
        assert!(rows.iter().all(|r| r.ns_per_call > 0.0));
    }
}
