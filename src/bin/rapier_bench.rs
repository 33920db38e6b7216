//! The peer on our own scenes: times Rapier 3D on exactly the bodies `nudge bench physics` times, so
//! the README's comparison can be rerun rather than quoted.
//!
//! `cargo run --release --features rapier --bin rapier-bench` prints, for the 210-box pyramid
//! (spaced, and with its boxes flush side by side), the raining pits of 1,000 and 4,000 bodies and
//! the 4,000 in a pit four times the area (`scene::cases::spread_rain`),
//! the median and mean ms per step over the same windows as `nudge bench physics`, and for the
//! chain of 100 links and the pile of 20 ragdolls of `nudge bench mechanisms` (ball joints and
//! hinges with limits and friction, built as Rapier's impulse joints), beside the contact pairs
//! Rapier solved in the last step.
//! `--scene NAME|FILE [--steps N]` times any nudge scene instead (repeat `--scene` for several).
//!
//! `--versus ROUNDS` times nudge and Rapier in turn on each of those scenes, ROUNDS times each, in
//! this one process: on a shared machine whose speed drifts by a third from minute to minute, a ratio
//! of two runs minutes apart measures the drift as much as the engines. Each round times nudge's
//! world (built as `nudge bench physics` builds it, sleeping off) and then Rapier's over the same
//! window; the report gives each round's ratio, their median, and the ratio of the two engines'
//! fastest rounds (the least disturbed run of each). Three rows time nudge again with some of its
//! mechanisms off, against the same Rapier world: the touching pyramid and rain(1000) with every
//! convergence fix off (the soft step alone, `Fixes::NONE`: what the statics, spread rows, anchors
//! and symmetric passes cost), and the ragdoll pile with its joints by Gauss–Seidel alone, as
//! Rapier's are (`Settings::joint_tree` off: what the exact tree costs). `--only NAME` keeps the
//! scenes whose name contains NAME (`--only chain`, `--only ragdoll`); `--scene NAME|FILE [--steps N]` (repeatable)
//! compares on those scenes instead, over their first N steps ([`TIMED_STEPS`] by default), so a
//! scene file of one's own is measured the way the built-in ones are.
//!
//! `--rest SECONDS` keeps each pile of `nudge bench rest` awake in Rapier and in nudge for SECONDS
//! after it settles, and prints how far each drifted and how fast it still moves.
//!
//! Each scene is built from nudge's `Scene`: the same shapes, poses, masses, friction and restitution,
//! with nudge's combine rules (friction √(a·b), restitution max) and gravity; Rapier's
//! `IntegrationParameters::default()` (4 sub-steps, like nudge), one thread, and no body may sleep.
//! Rolling resistance has no Rapier counterpart and is left out.

use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, bail};
use nudge::bench::mechanisms::{self, JOINT_STEPS, PILE_RAGDOLLS, PILE_SEED};
use nudge::bench::physics::{RAIN_WINDOW_S, RESTING_STEPS, TIMED_STEPS};
use nudge::bench::rest as rest_bench;
use nudge::geometry::Shape;
use nudge::scene::{self, Scene, cases, piles, ragdoll};
use nudge::testing::hard_case::{Fixes, Knobs, Timed};
use nudge::util::median;
use rapier3d::prelude::*;

/// A Rapier world holding one nudge scene.
struct RapierWorld {
    gravity: Vector,
    pipeline: PhysicsPipeline,
    params: IntegrationParameters,
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    soft_bodies: SoftBodySet,
    ccd: CCDSolver,
    /// The scene's bodies, in the scene's order.
    handles: Vec<RigidBodyHandle>,
}

impl RapierWorld {
    fn of(scene: &Scene) -> Self {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let mut handles = Vec::with_capacity(scene.bodies.len());
        for body in &scene.bodies {
            let d = &body.desc;
            let pose = Pose::from_parts(
                Vector::from_array(d.pose.position.to_array()),
                Rotation::from_array(d.pose.rotation.to_array()),
            );
            let builder = if d.is_static {
                RigidBodyBuilder::fixed()
            } else {
                RigidBodyBuilder::dynamic()
            };
            let handle = bodies.insert(
                builder
                    .pose(pose)
                    .linvel(Vector::from_array(d.linear_velocity.to_array()))
                    .angvel(Vector::from_array(d.angular_velocity.to_array()))
                    .can_sleep(false)
                    .build(),
            );
            let shape = match d.shape {
                Shape::Cuboid { half_extents: h } => ColliderBuilder::cuboid(h.x, h.y, h.z),
                Shape::Sphere { radius } => ColliderBuilder::ball(radius),
            };
            let collider = shape
                .mass(d.mass)
                .friction(d.friction)
                .restitution(d.restitution)
                .friction_combine_rule(CoefficientCombineRule::GeometricMean)
                .restitution_combine_rule(CoefficientCombineRule::Max)
                .build();
            colliders.insert_with_parent(collider, handle, &mut bodies);
            handles.push(handle);
        }
        let mut impulse_joints = ImpulseJointSet::new();
        // A joint to the world hangs from a fixed body at the origin, without a collider.
        let world = bodies.insert(RigidBodyBuilder::fixed().build());
        for desc in &scene.joints {
            let a = desc.a.map_or(world, |a| handles[a.index()]);
            impulse_joints.insert(a, handles[desc.b.index()], rapier_joint(desc), true);
        }
        let params = IntegrationParameters {
            dt: scene.settings.dt,
            ..IntegrationParameters::default()
        };
        Self {
            gravity: Vector::from_array(scene.settings.gravity.to_array()),
            pipeline: PhysicsPipeline::new(),
            params,
            islands: IslandManager::new(),
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            bodies,
            colliders,
            impulse_joints,
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            handles,
        }
    }

    fn step(&mut self) {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            &(),
            &(),
        );
    }

    /// Each scene body's position.
    fn positions(&self) -> Vec<glam::Vec3> {
        self.handles
            .iter()
            .map(|&h| glam::Vec3::from_array(self.bodies[h].translation().to_array()))
            .collect()
    }

    /// The fastest any body moves, m/s.
    fn fastest(&self) -> f32 {
        self.handles
            .iter()
            .map(|&h| self.bodies[h].linvel().length())
            .fold(0.0, f32::max)
    }

    /// Contact pairs the solver saw in the last step.
    fn active_pairs(&self) -> usize {
        self.narrow_phase
            .contact_pairs()
            .filter(|pair| pair.has_any_active_contact())
            .count()
    }
}

/// A joint's friction in Rapier: a motor driving the joint's speed to zero with at most the
/// friction's torque. Its damping (an acceleration gain, 1/s) is high enough that the motor holds
/// the joint still rigidly until that torque is reached, as nudge's friction rows do.
const FRICTION_DAMPING: f32 = 1.0e4;

/// Rapier's impulse joint for one of nudge's ball joints or hinges (the joint scenes have no
/// other kind). A hinge's frames are set whole, X along its axis: on A the shortest turn of X
/// onto A's axis, on B the same frame carried by the bodies' turn at creation (`reference`), so
/// that Rapier's angle is zero where nudge's is and its limits are the same.
fn rapier_joint(desc: &nudge::physics::JointDesc) -> GenericJoint {
    use nudge::physics::JointKind;
    let v = |v: glam::Vec3| Vector::from_array(v.to_array());
    let (anchor_a, anchor_b) = (v(desc.local_anchor_a), v(desc.local_anchor_b));
    match desc.kind {
        JointKind::Ball => {
            let mut joint = SphericalJointBuilder::new()
                .local_anchor1(anchor_a)
                .local_anchor2(anchor_b)
                .contacts_enabled(desc.collide);
            if desc.friction > 0.0 {
                for axis in [JointAxis::AngX, JointAxis::AngY, JointAxis::AngZ] {
                    joint = joint
                        .motor_velocity(axis, 0.0, FRICTION_DAMPING)
                        .motor_max_force(axis, desc.friction);
                }
            }
            joint.build().into()
        }
        JointKind::Hinge {
            limits,
            motor: None,
        } => {
            let frame_a = glam::Quat::from_rotation_arc(glam::Vec3::X, desc.local_axis_a);
            let frame_b = desc.reference.inverse() * frame_a;
            let rotation = |q: glam::Quat| Rotation::from_array(q.normalize().to_array());
            let mut joint = RevoluteJointBuilder::new(v(desc.local_axis_a))
                .contacts_enabled(desc.collide)
                .build();
            if desc.friction > 0.0 {
                joint
                    .set_motor_velocity(0.0, FRICTION_DAMPING)
                    .set_motor_max_force(desc.friction);
            }
            if let Some(limits) = limits {
                joint.set_limits(limits);
            }
            let mut joint: GenericJoint = joint.into();
            joint.set_local_frame1(Pose::from_parts(anchor_a, rotation(frame_a)));
            joint.set_local_frame2(Pose::from_parts(anchor_b, rotation(frame_b)));
            joint
        }
        kind => panic!("rapier-bench mirrors ball joints and hinges without motors, not {kind:?}"),
    }
}

/// One timed scene: median and mean ms per step, and the pairs solved in the last step.
struct Row {
    name: String,
    bodies: usize,
    steps: usize,
    median_ms: f64,
    mean_ms: f64,
    pairs: usize,
}

fn time(name: &str, scene: &Scene, steps: usize) -> Row {
    // Progress only on a terminal: redirected, the carriage returns pile up into one long line.
    if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        eprint!("rapier-bench: {name}                    \r");
    }
    let mut world = RapierWorld::of(scene);
    let mut ms = Vec::with_capacity(steps);
    for _ in 0..steps {
        let start = Instant::now();
        world.step();
        ms.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let mean_ms = ms.iter().sum::<f64>() / ms.len().max(1) as f64;
    Row {
        name: name.to_owned(),
        bodies: scene.bodies.len(),
        steps,
        median_ms: median(&mut ms),
        mean_ms,
        pairs: world.active_pairs(),
    }
}

/// nudge's median ms per step on `scene` over `steps` steps from the start, sleeping off: the world
/// and the window of `nudge bench physics`'s throughput rows.
fn time_nudge(scene: &Scene, steps: usize) -> f64 {
    let knobs = Knobs {
        sleep: false,
        ..Knobs::default()
    };
    let mut run = Timed::new(knobs.world(scene));
    for _ in 0..steps {
        run.step();
    }
    run.median_ms()
}

/// Times nudge and then Rapier on `scene`, `rounds` times, and prints one table row: each round's
/// ratio, their median, and the fastest rounds' ratio.
fn versus(name: &str, scene: &Scene, steps: usize, rounds: usize) {
    let (mut ours, mut theirs) = (Vec::with_capacity(rounds), Vec::with_capacity(rounds));
    for round in 0..rounds {
        if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
            eprint!(
                "rapier-bench: {name}, round {}/{rounds}          \r",
                round + 1
            );
        }
        ours.push(time_nudge(scene, steps));
        theirs.push(time(name, scene, steps).median_ms);
    }
    let mut ratios: Vec<f64> = ours.iter().zip(&theirs).map(|(a, b)| a / b).collect();
    let per_round = ratios
        .iter()
        .map(|r| format!("{r:.2}"))
        .collect::<Vec<_>>()
        .join(", ");
    let fastest = |xs: &[f64]| xs.iter().copied().fold(f64::INFINITY, f64::min);
    let (best_ours, best_theirs) = (fastest(&ours), fastest(&theirs));
    println!(
        "| {name} | {:.4}–{:.4} | {:.4}–{:.4} | {per_round} | {:.2} | {:.2} |",
        best_ours,
        ours.iter().copied().fold(0.0, f64::max),
        best_theirs,
        theirs.iter().copied().fold(0.0, f64::max),
        median(&mut ratios),
        best_ours / best_theirs,
    );
}

/// Rapier on each pile of `nudge bench rest`, kept awake as that bench keeps nudge's (it settles
/// for the pile's `settle_s`, then is watched `seconds`): one table row per pile with the farthest
/// any body moved from where it settled and the fastest any moved over the last second, in mm and
/// mm/s, beside nudge's at the same 4 sub-steps.
fn rest(seconds: f32) {
    println!(
        "Piles kept awake {seconds} s after settling (4 sub-steps, sleeping off): drift mm / speed mm/s"
    );
    println!("| pile | Rapier drift | Rapier speed | nudge drift | nudge speed |");
    println!("|---|---:|---:|---:|---:|");
    for pile in piles::all() {
        let mut world = RapierWorld::of(&pile.scene);
        let steps = |s: f32| (s / pile.scene.settings.dt).round() as usize;
        for _ in 0..steps(pile.settle_s) {
            world.step();
        }
        let settled = world.positions();
        let (watched, last_second) = (steps(seconds), steps(seconds.min(1.0)));
        let mut speed = 0.0f32;
        for step in 0..watched {
            world.step();
            if step + last_second >= watched {
                speed = speed.max(world.fastest());
            }
        }
        let drift = world
            .positions()
            .iter()
            .zip(&settled)
            .map(|(p, q)| p.distance(*q))
            .fold(0.0, f32::max);
        let ours = rest_bench::watch_awake(&pile, 4, seconds);
        println!(
            "| {} | {:.3} | {:.3} | {:.3} | {:.3} |",
            pile.scene.name,
            drift * 1e3,
            speed * 1e3,
            ours.drift_m * 1e3,
            ours.speed_m_s * 1e3
        );
    }
}

/// One scene of the comparison: its name, the scene, the steps timed, and whether it is a
/// variant of the row before it with some of nudge's mechanisms off (Rapier's world is the same,
/// so Rapier alone times it once, in that row).
struct Compared {
    name: &'static str,
    scene: Scene,
    steps: usize,
    variant: bool,
}

/// `scene` with every convergence fix of nudge's off ([`Fixes::NONE`]: the soft step alone, no
/// statics, spread rows, anchors, symmetric or alternating passes): what those cost beside Rapier.
/// Such a pile does not stay at rest (`tests/physics/rest.rs`,
/// `a_touching_pyramid_kept_awake_stands_only_with_the_convergence_fixes`).
fn soft_step_alone(mut scene: Scene) -> Scene {
    let knobs = Knobs {
        fixes: Fixes::NONE,
        ..Knobs::default()
    };
    scene.settings = knobs.settings(&scene.settings);
    scene
}

/// The scenes of the comparison and their windows (steps). The touching pyramid is timed over
/// [`RESTING_STEPS`]: a pile that stirs once it has stood a while shows it only there.
fn compared_scenes() -> Vec<Compared> {
    let rain_steps = (RAIN_WINDOW_S / cases::rain(0).settings.dt).round() as usize;
    let row = |name, scene, steps| Compared {
        name,
        scene,
        steps,
        variant: false,
    };
    let variant = |name, scene, steps| Compared {
        name,
        scene,
        steps,
        variant: true,
    };
    let mut gauss_seidel_pile = ragdoll::pile(PILE_RAGDOLLS, PILE_SEED);
    gauss_seidel_pile.settings.joint_tree = false;
    vec![
        row("pyramid(20)", cases::pyramid(20), TIMED_STEPS),
        row(
            "touching pyramid(20)",
            piles::touching_pyramid(20),
            RESTING_STEPS,
        ),
        variant(
            "touching pyramid(20), nudge's soft step alone",
            soft_step_alone(piles::touching_pyramid(20)),
            RESTING_STEPS,
        ),
        row("rain(1000)", cases::rain(1000), rain_steps),
        variant(
            "rain(1000), nudge's soft step alone",
            soft_step_alone(cases::rain(1000)),
            rain_steps,
        ),
        row("rain(4000)", cases::rain(4000), rain_steps),
        row("spread rain(4000)", cases::spread_rain(4000), rain_steps),
        row(
            "chain of 100 links",
            mechanisms::chain(100, 1.0),
            JOINT_STEPS,
        ),
        row(
            "pile of 20 ragdolls",
            ragdoll::pile(PILE_RAGDOLLS, PILE_SEED),
            JOINT_STEPS,
        ),
        // Nudge's joints solved as Rapier's are, by Gauss–Seidel alone (`Settings::joint_tree`
        // off): how much of the difference is the exact tree.
        variant(
            "pile of 20 ragdolls, nudge's joints by Gauss–Seidel",
            gauss_seidel_pile,
            JOINT_STEPS,
        ),
    ]
}

fn run() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .map(|i| {
                args.get(i + 1)
                    .with_context(|| format!("{flag} needs a value"))
            })
            .transpose()
    };
    // Every value of a flag given more than once (`--scene A --scene B`).
    let values = |flag: &str| {
        args.iter()
            .enumerate()
            .filter(|(_, a)| *a == flag)
            .map(|(i, _)| {
                args.get(i + 1)
                    .with_context(|| format!("{flag} needs a value"))
            })
            .collect::<anyhow::Result<Vec<_>>>()
    };
    let steps_given = || -> anyhow::Result<usize> {
        Ok(match value("--steps")? {
            Some(text) => text
                .parse()
                .with_context(|| format!("bad --steps {text}"))?,
            None => TIMED_STEPS,
        })
    };
    if let Some(text) = value("--versus")? {
        let rounds: usize = text
            .parse()
            .ok()
            .filter(|&n| n > 0)
            .with_context(|| format!("bad --versus {text}: a number of rounds, at least 1"))?;
        println!(
            "nudge against Rapier 3D, alternated in one process, {rounds} rounds (ms/step = each \
             round's median; 4 sub-steps; one thread; sleeping off)"
        );
        println!(
            "| scene | nudge ms/step (fastest–slowest) | Rapier ms/step | nudge ÷ Rapier per round \
             | median ratio | fastest ÷ fastest |"
        );
        println!("|---|---:|---:|---|---:|---:|");
        let files = values("--scene")?;
        if !files.is_empty() {
            let steps = steps_given()?;
            for name in files {
                versus(name, &scene::load(name)?, steps, rounds);
            }
            return Ok(());
        }
        let only = value("--only")?;
        for c in compared_scenes() {
            if only.is_none_or(|only| c.name.contains(only.as_str())) {
                versus(c.name, &c.scene, c.steps, rounds);
            }
        }
        return Ok(());
    }
    if let Some(text) = value("--rest")? {
        let seconds: f32 = text
            .parse()
            .ok()
            .filter(|&s: &f32| s > 0.0)
            .with_context(|| format!("bad --rest {text}: seconds, more than 0"))?;
        rest(seconds);
        return Ok(());
    }
    let files = values("--scene")?;
    let rows = if !files.is_empty() {
        let steps = steps_given()?;
        files
            .into_iter()
            .map(|name| Ok(time(name, &scene::load(name)?, steps)))
            .collect::<anyhow::Result<Vec<_>>>()?
    } else if args.is_empty() {
        compared_scenes()
            .iter()
            .filter(|c| !c.variant)
            .map(|c| time(c.name, &c.scene, c.steps))
            .collect()
    } else {
        bail!(
            "usage: rapier-bench [--versus ROUNDS] [--scene NAME|FILE ... [--steps N]] \
             | --versus ROUNDS [--only NAME] | --rest SECONDS"
        );
    };
    println!("Rapier 3D on nudge's scenes (defaults: 4 sub-steps; one thread; sleeping off)");
    println!("| scene | bodies | steps | ms/step | mean | contact pairs (last step) |");
    println!("|---|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {:.4} | {:.4} | {} |",
            r.name, r.bodies, r.steps, r.median_ms, r.mean_ms, r.pairs
        );
    }
    let row = |name: &str| rows.iter().find(|r| r.name == name);
    if let (Some(small), Some(large)) = (row("rain(1000)"), row("rain(4000)")) {
        println!(
            "rain(4000) / rain(1000): {:.2}x by the median, {:.2}x by the mean",
            large.median_ms / small.median_ms,
            large.mean_ms / small.mean_ms
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("rapier-bench: {error:#}");
            ExitCode::from(2)
        }
    }
}
