//! `nudge bench mechanisms`: what the contact mechanisms cost, each measured on its own.
//!
//! - **Patch friction** (`physics::collide::patch`): the contact patch's area and mean radius, computed
//!   in the box–box narrow phase for every face contact: ns per patch alone (a square face, an
//!   octagon: two faces turned 45°) beside ns per whole box–box call that includes it.
//! - **Per-body push-out** (`physics::push_out`): the position pass runs only while some contact is
//!   deeper than the soft range, so it is timed where it works: N coincident unit boxes above a floor,
//!   ms per step over their first second (the crowd coming apart), beside the fastest body.
//!   Elsewhere it costs one scan of the step's contacts for a deep one (inside the pyramid and rain
//!   rows of `nudge bench physics`).
//!
//! - **Feed-forward statics** (`physics::prepare::preload`, `Settings::preload`): three passes over a
//!   step's supports (load, friction, moments) and the warm start they rescale. Timed as the whole
//!   step with them on and off, in alternating rounds, on the pyramid (at rest: the statics' cost,
//!   less what its stillness saves in the narrow phase) and on rain(1000) (a pile landing), sleeping
//!   off, over `nudge bench physics`' windows.
//!
//! - **Joints** (`physics::joint`): ms per step over the first five seconds of a chain of
//!   ball-jointed links hung from the world and released 30° from the vertical (100 links, and 20
//!   links holding a load a hundred times a link: its equality rows solved exactly by the tree,
//!   `joint::tree`) and of a pile of 20 ragdolls (`scene::ragdoll`: ball joints, hinges with limits)
//!   dropped on a floor, beside the widest any joint opened; then the same three with every joint
//!   solved by Gauss–Seidel (`Settings::joint_tree` off), what the exact tree costs and holds.
//!   `rapier-bench --versus` times the same chain of 100 and the same pile with Rapier's impulse
//!   joints. A world without joints prepares no joint rows and skips their passes: the other rows
//!   here and every scene of `nudge bench physics` have none.
//!
//! Timings are medians of repeated runs on a machine that may be shared: noisy.

use std::hint::black_box;

use glam::{Quat, Vec2, Vec3};

use super::kernels::time_per_call;
use crate::color::PALETTE;
use crate::geometry::{Camera, Pose, Shape};
use crate::physics::narrow::collide::{collide, patch_of};
use crate::physics::{BodyDesc, Settings, World};
use crate::scene::framing::DEFAULT_FOV_DEG;
use crate::scene::{Scene, SceneBody, cases, ragdoll};
use crate::testing::hard_case::Timed;

/// One measured cost.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MechanismRow {
    /// Which mechanism.
    pub mechanism: &'static str,
    /// What it was measured on.
    pub case: String,
    /// The cost.
    pub value: f64,
    /// Its unit ("ns/call", "ms/step").
    pub unit: &'static str,
    /// What else the run showed.
    pub note: String,
}

/// Runs every measurement (`quick`: fewer calls and the crowds of 5 and 20 only).
pub fn run(quick: bool) -> Vec<MechanismRow> {
    let (rounds, calls) = if quick { (5, 2_000) } else { (15, 20_000) };
    let mut rows = Vec::new();

    let square = [
        Vec2::new(0.5, 0.5),
        Vec2::new(-0.5, 0.5),
        Vec2::new(-0.5, -0.5),
        Vec2::new(0.5, -0.5),
    ];
    let octagon: Vec<Vec2> = (0..8)
        .map(|k| {
            let angle = std::f32::consts::TAU * (k as f32 + 0.5) / 8.0;
            0.6 * Vec2::new(angle.cos(), angle.sin())
        })
        .collect();
    for (case, points) in [("square face", &square[..]), ("octagon", &octagon[..])] {
        let depths = vec![-0.001; points.len()];
        let ns = time_per_call(rounds, calls, || {
            black_box(patch_of(black_box(points), black_box(&depths)));
        });
        rows.push(MechanismRow {
            mechanism: "patch friction",
            case: format!("patch of a {case} ({} vertices)", points.len()),
            value: ns,
            unit: "ns/call",
            note: String::new(),
        });
    }
    let cube = Shape::cuboid(Vec3::splat(0.5));
    let floor = Shape::cuboid(Vec3::new(10.0, 0.5, 10.0));
    let pairs = [
        (
            "box resting on a floor",
            floor,
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
            Pose::from_position(Vec3::new(0.1, 0.499, 0.2)),
        ),
        (
            "box on a box, offset",
            cube,
            Pose::IDENTITY,
            Pose::from_position(Vec3::new(0.3, 0.999, -0.2)),
        ),
        (
            "box on a box, turned 45°",
            cube,
            Pose::IDENTITY,
            Pose::new(Vec3::new(0.0, 0.999, 0.0), Quat::from_rotation_y(0.785)),
        ),
    ];
    for (case, shape_a, pose_a, pose_b) in pairs {
        let ns = time_per_call(rounds, calls, || {
            black_box(collide(
                black_box(&shape_a),
                black_box(&pose_a),
                black_box(&cube),
                black_box(&pose_b),
                0.02,
            ));
        });
        let manifold = collide(&shape_a, &pose_a, &cube, &pose_b, 0.02);
        rows.push(MechanismRow {
            mechanism: "patch friction",
            case: format!("box-box narrow phase with the patch: {case}"),
            value: ns,
            unit: "ns/call",
            note: format!(
                "{} points, patch {:.3} m², mean radius {:.4} m",
                manifold.len, manifold.patch.area, manifold.patch.mean_radius
            ),
        });
    }

    let crowds: &[usize] = if quick { &[5, 20] } else { &[5, 20, 50] };
    for &n in crowds {
        let mut world = World::new(Settings::default());
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(40.0, 0.5, 40.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ));
        for _ in 0..n {
            world.add_body(BodyDesc::dynamic(
                cube,
                Pose::from_position(Vec3::new(0.0, 1.0, 0.0)),
                1.0,
            ));
        }
        let mut run = Timed::new(world);
        let mut fastest = 0.0f32;
        for _ in 0..60 {
            run.step();
            for body in run.world.bodies() {
                fastest = fastest.max(body.linear_velocity().length());
            }
        }
        rows.push(MechanismRow {
            mechanism: "per-body push-out",
            case: format!("{n} coincident unit boxes, first second"),
            value: run.median_ms(),
            unit: "ms/step",
            note: format!("fastest body {fastest:.2} m/s"),
        });
    }
    let rounds = if quick { 1 } else { 5 };
    for (name, scene, steps) in [
        ("pyramid(20), first 120 steps", cases::pyramid(20), 120),
        ("rain(1000), first 150 steps", cases::rain(1000), 150),
    ] {
        let mut medians = [Vec::new(), Vec::new()];
        for _ in 0..rounds {
            for (preload, times) in [true, false].into_iter().zip(&mut medians) {
                let mut world = scene.build_world();
                let settings = world.settings_mut();
                settings.sleep = false;
                settings.preload = preload;
                let mut run = Timed::new(world);
                for _ in 0..steps {
                    run.step();
                }
                times.push(run.median_ms());
            }
        }
        let [on, off] = medians.map(|mut times| {
            times.sort_by(f64::total_cmp);
            times[times.len() / 2]
        });
        rows.push(MechanismRow {
            mechanism: "feed-forward statics",
            case: name.to_string(),
            value: on,
            unit: "ms/step",
            note: format!("off: {off:.4} ms/step ({:+.0} %)", 100.0 * (on / off - 1.0)),
        });
    }
    let joint_scenes = [
        (chain(100, 1.0), "chain of 100 links, swinging"),
        (
            chain(20, 100.0),
            "chain of 20 links, load 100× a link, swinging",
        ),
        (
            ragdoll::pile(PILE_RAGDOLLS, PILE_SEED),
            "pile of 20 ragdolls, falling and settling",
        ),
    ];
    // Each scene as the defaults solve it, then with every joint by Gauss–Seidel: what the exact
    // tree costs and what it holds.
    for tree in [true, false] {
        for (scene, case) in &joint_scenes {
            let mut scene = scene.clone();
            scene.settings.joint_tree = tree;
            let mut run = Timed::new(scene.build_world());
            let mut widest = 0.0f32;
            for _ in 0..JOINT_STEPS {
                run.step();
                for joint in run.world.joints() {
                    let (a, b) = run.world.joint_anchors(joint);
                    widest = widest.max(a.distance(b));
                }
            }
            rows.push(MechanismRow {
                mechanism: if tree {
                    "joints"
                } else {
                    "joints, Gauss–Seidel alone"
                },
                case: case.to_string(),
                value: run.median_ms(),
                unit: "ms/step",
                note: format!("widest joint {:.1} µm", widest * 1e6),
            });
        }
    }
    rows
}

/// Steps the joint rows time (5 s), from the start; `rapier-bench --versus` times the same window.
pub const JOINT_STEPS: usize = 300;

/// Ragdolls in the joint rows' pile, and the seed of their postures.
pub const PILE_RAGDOLLS: usize = 20;
pub const PILE_SEED: u64 = 20;

/// `links` balls of 0.1 kg, 10 cm apart, ball-jointed end to end from a point of the world and
/// released 30° from the vertical, the last holding a ball of `load` times a link's mass; sleeping
/// off, as the benchmarks run.
pub fn chain(links: usize, load: f32) -> Scene {
    use crate::physics::{BodyId, JointDesc, JointKind};
    let top = Vec3::new(0.0, 12.0, 0.0);
    let angle = 30f32.to_radians();
    let down = Vec3::new(angle.sin(), -angle.cos(), 0.0);
    let mut bodies: Vec<SceneBody> = Vec::new();
    let mut joints = Vec::new();
    for i in 0..=links {
        let (radius, mass) = if i == links {
            (0.2, 0.1 * load)
        } else {
            (0.04, 0.1)
        };
        let centre = top + down * (0.1 * i as f32 + if i == links { 0.2 } else { 0.05 });
        let desc = BodyDesc::dynamic(Shape::sphere(radius), Pose::from_position(centre), mass);
        let anchor = top + down * (0.1 * i as f32);
        let previous = (i > 0).then(|| (BodyId(i as u32 - 1), bodies[i - 1].desc.pose));
        joints.push(JointDesc::at(
            JointKind::Ball,
            previous,
            (BodyId(i as u32), desc.pose),
            anchor,
            anchor,
            Vec3::Y,
            false,
        ));
        bodies.push(SceneBody::new(desc, PALETTE[i % PALETTE.len()]));
    }
    Scene {
        name: format!("chain({links}, load {load})"),
        settings: Settings {
            sleep: false,
            ..Settings::default()
        },
        camera: Camera::perspective(
            Vec3::new(0.0, 8.0, 16.0),
            Vec3::new(0.0, 6.0, 0.0),
            DEFAULT_FOV_DEG.to_radians(),
        ),
        bodies,
        joints,
    }
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(
    rows: &[MechanismRow],
    out: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "mechanisms: what the contact mechanisms cost, each on its own (noisy)"
    )?;
    let mut table = Table::new(&["mechanism", "measured on", "cost", "unit", "note"]);
    for r in rows {
        table.push(vec![
            r.mechanism.to_string(),
            r.case.clone(),
            format!("{:.4}", r.value),
            r.unit.to_string(),
            r.note.clone(),
        ]);
    }
    table.write(out)
}
