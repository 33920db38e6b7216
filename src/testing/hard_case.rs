//! The hard cases: run one scene of [`crate::scene::cases`] with given solver knobs and measure its error
//! from the bodies' poses and velocities (never from the engine's own statistics). The tests in
//! `tests/physics/hard_cases.rs` hold each case to its tolerance; `nudge bench physics` sweeps the knobs.
//!
//! Every runner times each `World::step` call alone (measurement is outside the timed region) and reports
//! the median in milliseconds.

use std::time::Instant;

use glam::{Mat3, Quat, Vec3};

use super::penetration::max_penetration;
use crate::geometry::{Pose, Shape};
use crate::physics::{Body, BodyDesc, BodyId, Settings, World};
use crate::scene::{Scene, cases};

/// The solver knobs a benchmark sweeps; gravity and dt always come from the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Knobs {
    /// Sub-steps per step, ≥ 1.
    pub substeps: u32,
    /// Solver iterations per sub-step, ≥ 1.
    pub iterations: u32,
    /// Whether bodies at rest may fall asleep.
    pub sleep: bool,
    /// Which of the convergence fixes on top of the soft step are on.
    pub fixes: Fixes,
}

/// The convergence fixes on top of the soft step, each on unless a test switches it off to show the
/// case it exists for (see `contact_solver`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fixes {
    /// `Settings::spread_row`.
    pub spread_row: bool,
    /// `Settings::alternate_point_order`.
    pub alternate_point_order: bool,
    /// `Settings::alternate_sub_steps`.
    pub alternate_sub_steps: bool,
    /// `Settings::alternate_layer_order`.
    pub alternate_layer_order: bool,
    /// `Settings::symmetric_relax`.
    pub symmetric_relax: bool,
    /// `Settings::symmetric_biased_pass`.
    pub symmetric_biased_pass: bool,
    /// `Settings::preload`.
    pub preload: bool,
    /// `Settings::touching_spring`.
    pub touching_spring: bool,
    /// `Settings::shock_propagation`.
    pub shock_propagation: bool,
    /// The extra sweeps around mass ratios and heavy loads (off: `Settings::mass_ratio_iterations` = 0).
    pub mass_ratio_sweeps: bool,
    /// `Settings::friction_anchors`.
    pub friction_anchors: bool,
    /// `Settings::anchor_frequency_cap`.
    pub anchor_frequency_cap: bool,
    /// `Settings::thin_soft_range`.
    pub thin_soft_range: bool,
    /// `Settings::sleep_waits_for_springs`.
    pub sleep_waits_for_springs: bool,
    /// `Settings::sleep_waits_while_speeding_up`.
    pub sleep_waits_while_speeding_up: bool,
    /// `Settings::feed_load_changes`.
    pub feed_load_changes: bool,
    /// `Settings::feed_moment_changes`.
    pub feed_moment_changes: bool,
    /// `Settings::balance_new_supports`.
    pub balance_new_supports: bool,
    /// `Settings::piles_carry_blows`.
    pub piles_carry_blows: bool,
    /// `Settings::statics_skip_jointed`.
    pub statics_skip_jointed: bool,
    /// `Settings::rolling_held_mass_alone`.
    pub rolling_held_mass_alone: bool,
    /// `Settings::joint_geometric_stiffness`.
    pub joint_geometric_stiffness: bool,
    /// `Settings::joint_scalar_rows_last`.
    pub joint_scalar_rows_last: bool,
    /// `Settings::joint_pull_from_load`.
    pub joint_pull_from_load: bool,
    /// The touching tolerance (off: `Settings::touching_tolerance` = 0).
    pub touching_tolerance: bool,
}

impl Fixes {
    /// Every fix on, as in `Settings::default()`.
    pub const ALL: Fixes = Fixes::every(true);

    /// Every fix off: the soft step alone (Box2D v3's solver, with nudge's narrow phase).
    pub const NONE: Fixes = Fixes::every(false);

    /// Every fix `on`, or every one off.
    const fn every(on: bool) -> Fixes {
        Fixes {
            spread_row: on,
            alternate_point_order: on,
            alternate_sub_steps: on,
            alternate_layer_order: on,
            symmetric_relax: on,
            symmetric_biased_pass: on,
            preload: on,
            touching_spring: on,
            shock_propagation: on,
            mass_ratio_sweeps: on,
            friction_anchors: on,
            anchor_frequency_cap: on,
            thin_soft_range: on,
            sleep_waits_for_springs: on,
            sleep_waits_while_speeding_up: on,
            feed_load_changes: on,
            feed_moment_changes: on,
            balance_new_supports: on,
            piles_carry_blows: on,
            statics_skip_jointed: on,
            rolling_held_mass_alone: on,
            joint_geometric_stiffness: on,
            joint_scalar_rows_last: on,
            joint_pull_from_load: on,
            touching_tolerance: on,
        }
    }
}

impl Default for Knobs {
    /// The knobs of `Settings::default()`.
    fn default() -> Self {
        let settings = Settings::default();
        Self {
            substeps: settings.substeps,
            iterations: settings.iterations,
            sleep: settings.sleep,
            fixes: Fixes::ALL,
        }
    }
}

impl Knobs {
    /// A world holding `scene` with these knobs.
    pub fn world(&self, scene: &Scene) -> World {
        scene.build_world_with(self.settings(&scene.settings))
    }

    /// `settings` with these knobs: their sub-steps, iterations and sleeping, and each fix they
    /// switch off switched off.
    pub fn settings(&self, settings: &Settings) -> Settings {
        let fixes = self.fixes;
        Settings {
            substeps: self.substeps,
            iterations: self.iterations,
            sleep: self.sleep,
            spread_row: settings.spread_row && fixes.spread_row,
            alternate_point_order: settings.alternate_point_order && fixes.alternate_point_order,
            alternate_sub_steps: settings.alternate_sub_steps && fixes.alternate_sub_steps,
            alternate_layer_order: settings.alternate_layer_order && fixes.alternate_layer_order,
            symmetric_relax: settings.symmetric_relax && fixes.symmetric_relax,
            symmetric_biased_pass: settings.symmetric_biased_pass && fixes.symmetric_biased_pass,
            preload: settings.preload && fixes.preload,
            touching_spring: settings.touching_spring && fixes.touching_spring,
            shock_propagation: settings.shock_propagation && fixes.shock_propagation,
            friction_anchors: settings.friction_anchors && fixes.friction_anchors,
            anchor_frequency_cap: settings.anchor_frequency_cap && fixes.anchor_frequency_cap,
            thin_soft_range: settings.thin_soft_range && fixes.thin_soft_range,
            sleep_waits_for_springs: settings.sleep_waits_for_springs
                && fixes.sleep_waits_for_springs,
            sleep_waits_while_speeding_up: settings.sleep_waits_while_speeding_up
                && fixes.sleep_waits_while_speeding_up,
            feed_load_changes: settings.feed_load_changes && fixes.feed_load_changes,
            feed_moment_changes: settings.feed_moment_changes && fixes.feed_moment_changes,
            balance_new_supports: settings.balance_new_supports && fixes.balance_new_supports,
            piles_carry_blows: settings.piles_carry_blows && fixes.piles_carry_blows,
            statics_skip_jointed: settings.statics_skip_jointed && fixes.statics_skip_jointed,
            rolling_held_mass_alone: settings.rolling_held_mass_alone
                && fixes.rolling_held_mass_alone,
            joint_geometric_stiffness: settings.joint_geometric_stiffness
                && fixes.joint_geometric_stiffness,
            joint_scalar_rows_last: settings.joint_scalar_rows_last && fixes.joint_scalar_rows_last,
            joint_pull_from_load: settings.joint_pull_from_load && fixes.joint_pull_from_load,
            touching_tolerance: if fixes.touching_tolerance {
                settings.touching_tolerance
            } else {
                0.0
            },
            mass_ratio_iterations: if fixes.mass_ratio_sweeps {
                settings.mass_ratio_iterations
            } else {
                0
            },
            ..settings.clone()
        }
    }
}

/// A world plus the wall-clock time of each of its steps.
pub struct Timed {
    /// The world being run.
    pub world: World,
    step_ms: Vec<f64>,
}

impl Timed {
    /// Wraps `world` with no steps timed yet.
    pub fn new(world: World) -> Self {
        Self {
            world,
            step_ms: Vec::new(),
        }
    }

    /// One step, timed.
    pub fn step(&mut self) {
        let start = Instant::now();
        self.world.step();
        self.step_ms.push(start.elapsed().as_secs_f64() * 1e3);
    }

    /// Steps taken so far.
    pub fn step_count(&self) -> usize {
        self.step_ms.len()
    }

    /// Simulated time so far, seconds.
    pub fn time(&self) -> f32 {
        self.step_ms.len() as f32 * self.world.settings().dt
    }

    /// Median wall-clock time of the steps so far, ms (0 before the first).
    pub fn median_ms(&self) -> f64 {
        crate::util::median(&mut self.step_ms.clone())
    }

    /// Mean wall-clock time of the steps so far, ms (0 before the first).
    pub fn mean_ms(&self) -> f64 {
        if self.step_ms.is_empty() {
            return 0.0;
        }
        self.step_ms.iter().sum::<f64>() / self.step_ms.len() as f64
    }
}

/// Number of steps of `seconds` at the world's dt (rounded to nearest).
fn steps_for(world: &World, seconds: f32) -> usize {
    (seconds / world.settings().dt).round() as usize
}

fn horizontal(v: Vec3) -> f32 {
    Vec3::new(v.x, 0.0, v.z).length()
}

/// Result of [`stack`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StackOutcome {
    /// Largest horizontal distance of any box from where it started, at any step, metres.
    pub max_drift_m: f32,
    /// Deepest overlap between any two bodies (floor included) at any step, metres.
    pub max_penetration_m: f32,
    /// Widest vertical gap between neighbouring boxes, or between the bottom box and the floor, at any
    /// step, metres: (y_above − y_below) − 1 and y_bottom − 0.5. Catches a stack floating apart.
    pub max_hover_m: f32,
    /// Median ms per step.
    pub ms_per_step: f64,
}

/// The lean of body 1 of `world` towards +z, rad: the angle of its up axis from vertical in the
/// y–z plane (the block of `cases::tipped_block`).
pub fn lean_about_x(world: &World) -> f32 {
    let up = world.body(BodyId(1)).pose().rotation * Vec3::Y;
    up.z.atan2(up.y)
}

/// A pile of four ragdolls (`scene::ragdoll::pile`, `seed`) dropped and watched for a minute: the
/// farthest any part moved over the minute's second half, m.
pub fn ragdoll_pile_creep(seed: u64, knobs: Knobs) -> f32 {
    let mut world = knobs.world(&crate::scene::ragdoll::pile(4, seed));
    for _ in 0..steps_for(&world, 30.0) {
        world.step();
    }
    let halfway: Vec<Vec3> = world.bodies().iter().map(|b| b.pose().position).collect();
    for _ in 0..steps_for(&world, 30.0) {
        world.step();
    }
    world
        .bodies()
        .iter()
        .zip(&halfway)
        .map(|(b, p)| b.pose().position.distance(*p))
        .fold(0.0, f32::max)
}

/// The block of `cases::tipped_block` (`aspect`, `tip`) let go and run for `seconds`: how far its
/// top ended from where it stands upright, m, and whether it was asleep then.
pub fn let_go_leaning(aspect: f32, tip: f32, seconds: f32, knobs: Knobs) -> (f32, bool) {
    let mut world = knobs.world(&cases::tipped_block(aspect, tip));
    for _ in 0..steps_for(&world, seconds) {
        world.step();
    }
    let height = 2.0 * aspect * cases::TIPPED_BLOCK_HALF_WIDTH;
    let off = height * lean_about_x(&world).sin().abs();
    (off, world.awake_count() == 0)
}

/// Runs [`cases::stack`]`(count, base)` for `seconds`.
pub fn stack(count: usize, base: Vec3, seconds: f32, knobs: Knobs) -> StackOutcome {
    let mut run = Timed::new(knobs.world(&cases::stack(count, base)));
    let start: Vec<Vec3> = run
        .world
        .bodies()
        .iter()
        .map(|b| b.pose().position)
        .collect();
    let (mut max_drift_m, mut max_penetration_m, mut max_hover_m) = (0.0f32, 0.0f32, 0.0f32);
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        let mut y_below = 0.0 - cases::UNIT_HALF; // a unit box's centre resting on the floor is at 0.5
        for (body, p0) in run.world.bodies().iter().zip(&start).skip(1) {
            let p = body.pose().position;
            max_drift_m = max_drift_m.max(horizontal(p - *p0));
            max_hover_m = max_hover_m.max(p.y - y_below - 2.0 * cases::UNIT_HALF);
            y_below = p.y;
        }
        max_penetration_m = max_penetration_m.max(max_penetration(&run.world, true).0);
    }
    StackOutcome {
        max_drift_m,
        max_penetration_m,
        max_hover_m,
        ms_per_step: run.median_ms(),
    }
}

/// Result of [`pyramid`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PyramidOutcome {
    /// Largest horizontal distance of the top box from where it started, at any step, metres.
    pub top_drift_m: f32,
    /// How far the top box sank below where it started, at the end, metres (penetration summed over rows).
    pub top_sag_m: f32,
    /// Deepest overlap between any two bodies at any step, metres.
    pub max_penetration_m: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::pyramid`]`(base)` for `seconds`.
pub fn pyramid(base: usize, seconds: f32, knobs: Knobs) -> PyramidOutcome {
    let mut run = Timed::new(knobs.world(&cases::pyramid(base)));
    let top = BodyId(run.world.len() as u32 - 1);
    let p0 = run.world.body(top).pose().position;
    let (mut top_drift_m, mut max_penetration_m) = (0.0f32, 0.0f32);
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        top_drift_m = top_drift_m.max(horizontal(run.world.body(top).pose().position - p0));
        max_penetration_m = max_penetration_m.max(max_penetration(&run.world, true).0);
    }
    PyramidOutcome {
        top_drift_m,
        top_sag_m: p0.y - run.world.body(top).pose().position.y,
        max_penetration_m,
        ms_per_step: run.median_ms(),
    }
}

/// Result of [`mass_ratio`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassRatioOutcome {
    /// Deepest overlap (box–box or box–floor) at any step, metres.
    pub max_penetration_m: f32,
    /// Largest |y − y₀| of the heavy box at any step, metres.
    pub max_height_error_m: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::mass_ratio`] for `seconds`.
pub fn mass_ratio(seconds: f32, knobs: Knobs) -> MassRatioOutcome {
    heavy_on_light(cases::MASS_RATIO_HEAVY_KG, seconds, knobs)
}

/// Runs [`cases::heavy_on_light`]`(heavy_kg)` for `seconds`.
pub fn heavy_on_light(heavy_kg: f32, seconds: f32, knobs: Knobs) -> MassRatioOutcome {
    let mut run = Timed::new(knobs.world(&cases::heavy_on_light(heavy_kg)));
    let heavy = BodyId(2);
    let y0 = run.world.body(heavy).pose().position.y;
    let (mut max_penetration_m, mut max_height_error_m) = (0.0f32, 0.0f32);
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        max_penetration_m = max_penetration_m.max(max_penetration(&run.world, true).0);
        max_height_error_m =
            max_height_error_m.max((run.world.body(heavy).pose().position.y - y0).abs());
    }
    MassRatioOutcome {
        max_penetration_m,
        max_height_error_m,
        ms_per_step: run.median_ms(),
    }
}

/// Forces [`pinned_push`] tries, N: 25 · √2^k up to 6,400 (half an octave apart), so the last held
/// force is within a factor √2 of the true threshold.
fn pinned_push_forces() -> impl Iterator<Item = f32> {
    (0..=16).map(|k| 25.0 * 2f32.powf(0.5 * k as f32))
}

/// Simulated seconds [`pinned_push_slide`] lets the stack settle before pushing, s.
const PINNED_SETTLE_S: f32 = 1.0;
/// Simulated seconds the ladder of [`pinned_push`] pushes, s.
const PINNED_PUSH_S: f32 = 2.0;
/// Simulated seconds [`pinned_push_slide`] keeps watching after the push ends, s: letting go of a
/// push the solver only just held can kick the box back.
const PINNED_AFTER_S: f32 = 1.0;
/// A push is held while the light box moves less than this, metres.
pub const PINNED_HELD_M: f32 = 0.05;

/// Result of [`pinned_push`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PinnedPushOutcome {
    /// Largest force of the half-octave ladder held before the first one that was not, N (0 when even
    /// the first was not). Coulomb: the floor holds up to μ·(1 kg + 1000 kg)·g ≈ 4,910 N.
    pub held_n: f32,
    /// Median wall-clock ms per step of that push's run (of the first push when none was held).
    pub ms_per_step: f64,
}

/// The 1 kg box of [`cases::mass_ratio`] pinned under the 1000 kg box and pushed sideways: settles for
/// 1 s, then `force_n` (N, along +x, through the centre of its −x face, so it exerts no torque about the
/// centre) for `push_steps` steps, then nothing for 1 s. Returns the light box's largest distance from
/// where the push began, metres (during the push or after it), and the run.
///
/// Coulomb friction holds every push below μ·(m + M)·g: the floor's friction stops the light box and
/// the heavy box on it never feels the push. The solver must turn the floor's friction, which acts a
/// half-box below the push, into a shift of the normal loads of both faces that keeps the light box
/// from tipping; one sweep a sub-step gets there only approximately, and a push large against the
/// light box's own mass tips it enough to pop it out.
pub fn pinned_push_slide(force_n: f32, push_steps: usize, knobs: Knobs) -> (f32, Timed) {
    let mut run = Timed::new(knobs.world(&cases::mass_ratio()));
    let light = BodyId(1);
    for _ in 0..steps_for(&run.world, PINNED_SETTLE_S) {
        run.world.step();
    }
    let start = run.world.body(light).pose().position;
    let half_x = run.world.body(light).shape().reach(Quat::IDENTITY, Vec3::X);
    let mut moved = 0.0f32;
    for step in 0..push_steps + steps_for(&run.world, PINNED_AFTER_S) {
        if step < push_steps {
            let centre = run.world.body(light).pose().position;
            run.world.apply_force_at_point(
                light,
                Vec3::new(force_n, 0.0, 0.0),
                centre - Vec3::new(half_x, 0.0, 0.0),
            );
        }
        run.step();
        // Once NaN (a blown-up run), always NaN: `max` would drop it.
        let d = (run.world.body(light).pose().position - start).length();
        moved = if moved.is_nan() || d.is_nan() {
            f32::NAN
        } else {
            moved.max(d)
        };
    }
    (moved, run)
}

/// The largest push [`pinned_push_slide`] holds for 2 s (moves less than [`PINNED_HELD_M`], during
/// the push or after it), climbing the half-octave ladder from 25 N and stopping at the first push
/// that is not held.
pub fn pinned_push(knobs: Knobs) -> PinnedPushOutcome {
    let mut held_n = 0.0;
    let mut ms_per_step = None;
    let push_steps = (PINNED_PUSH_S / cases::mass_ratio().settings.dt).round() as usize;
    for force in pinned_push_forces() {
        let (moved, run) = pinned_push_slide(force, push_steps, knobs);
        // A NaN distance (a blown-up run) is not held either.
        let held = moved < PINNED_HELD_M;
        if held || ms_per_step.is_none() {
            ms_per_step = Some(run.median_ms());
        }
        if !held {
            break;
        }
        held_n = force;
    }
    PinnedPushOutcome {
        held_n,
        ms_per_step: ms_per_step.unwrap_or(0.0),
    }
}

/// Result of [`bounce`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BounceOutcome {
    /// Gap between the floor top (y = 0) and the ball's bottom at the apex of the first rebound, metres;
    /// `None` when the ball never came back up within the time given.
    pub apex_gap_m: Option<f32>,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::bounce`] until the first rebound's apex (at most `seconds`).
///
/// The rebound starts at the first step where the ball moves up after having moved down; its apex is the
/// highest centre seen until the ball moves down again (sampled once per step: the error is below
/// ½·g·dt² ≈ 1.4 mm).
pub fn bounce(seconds: f32, knobs: Knobs) -> BounceOutcome {
    let mut run = Timed::new(knobs.world(&cases::bounce()));
    let ball = BodyId(1);
    let radius = cases::UNIT_HALF;
    let mut fell = false;
    let mut apex: Option<f32> = None;
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        let body = run.world.body(ball);
        let vy = body.linear_velocity().y;
        let y = body.pose().position.y;
        if vy < 0.0 && apex.is_none() {
            fell = true;
        } else if vy > 0.0 && fell {
            apex = Some(apex.map_or(y, |a| a.max(y)));
        }
        if let Some(top) = apex
            && vy <= 0.0
        {
            apex = Some(top.max(y));
            break;
        }
    }
    BounceOutcome {
        apex_gap_m: apex.map(|y| y - radius),
        ms_per_step: run.median_ms(),
    }
}

/// Expected slide of a box released at rest on [`cases::ramp`] after `t` seconds, metres:
/// ½·g·(sin θ − μ cos θ)·t², or 0 when friction holds it (μ ≥ tan θ).
pub fn ramp_expected_slide_m(friction: f32, t: f32, gravity: f32) -> f32 {
    ramp_expected_slide_at(cases::RAMP_ANGLE, friction, t, gravity)
}

/// [`ramp_expected_slide_m`] on a ramp tilted by `theta` (radians).
pub fn ramp_expected_slide_at(theta: f32, friction: f32, t: f32, gravity: f32) -> f32 {
    let a = gravity * (theta.sin() - friction * theta.cos());
    (0.5 * a * t * t).max(0.0)
}

/// Result of [`ramp`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RampOutcome {
    /// Distance the box moved down the slope by the end, metres.
    pub slide_m: f32,
    /// Largest distance (any direction) of the box from its start at any step, metres.
    pub max_displacement_m: f32,
    /// [`ramp_expected_slide_m`] for this run, metres.
    pub expected_slide_m: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::ramp`]`(friction)` for `seconds`.
pub fn ramp(friction: f32, seconds: f32, knobs: Knobs) -> RampOutcome {
    ramp_at(cases::RAMP_ANGLE, friction, seconds, knobs)
}

/// Runs [`cases::ramp_at`]`(angle, friction)` for `seconds`.
pub fn ramp_at(angle: f32, friction: f32, seconds: f32, knobs: Knobs) -> RampOutcome {
    let mut run = Timed::new(knobs.world(&cases::ramp_at(angle, friction)));
    let block = BodyId(1);
    let p0 = run.world.body(block).pose().position;
    let down = cases::ramp_downhill_at(angle);
    let mut max_displacement_m = 0.0f32;
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        max_displacement_m =
            max_displacement_m.max((run.world.body(block).pose().position - p0).length());
    }
    let g = run.world.settings().gravity.length();
    RampOutcome {
        slide_m: (run.world.body(block).pose().position - p0).dot(down),
        max_displacement_m,
        expected_slide_m: ramp_expected_slide_at(angle, friction, run.time(), g),
        ms_per_step: run.median_ms(),
    }
}

/// Result of [`rolling_ball`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RollingOutcome {
    /// Horizontal speed of the ball's centre at the end, m/s.
    pub speed_mps: f32,
    /// Speed of the ball's material point at the contact (v + ω × (−r ŷ)) at the end, m/s; 0 = rolling.
    pub slip_mps: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::rolling_ball`] for `seconds`.
pub fn rolling_ball(seconds: f32, knobs: Knobs) -> RollingOutcome {
    let mut run = Timed::new(knobs.world(&cases::rolling_ball()));
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
    }
    let ball = run.world.body(BodyId(1));
    let v = ball.linear_velocity();
    let contact_arm = Vec3::new(0.0, -cases::UNIT_HALF, 0.0);
    RollingOutcome {
        speed_mps: horizontal(v),
        slip_mps: (v + ball.angular_velocity().cross(contact_arm)).length(),
        ms_per_step: run.median_ms(),
    }
}

/// Result of [`projectile`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectileOutcome {
    /// Distance between the ball and the analytic parabola p₀ + v₀t + ½gt² at the end, metres.
    pub error_m: f32,
    /// Length of the analytic displacement v₀t + ½gt² at the end, metres.
    pub displacement_m: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::projectile`] for `seconds`.
pub fn projectile(seconds: f32, knobs: Knobs) -> ProjectileOutcome {
    let mut run = Timed::new(knobs.world(&cases::projectile()));
    let p0 = run.world.body(BodyId(0)).pose().position;
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
    }
    let t = run.time();
    let g = run.world.settings().gravity;
    let displacement = cases::PROJECTILE_VELOCITY * t + 0.5 * g * t * t;
    ProjectileOutcome {
        error_m: (run.world.body(BodyId(0)).pose().position - (p0 + displacement)).length(),
        displacement_m: displacement.length(),
        ms_per_step: run.median_ms(),
    }
}

/// Result of [`deep_overlap`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverlapOutcome {
    /// Deepest box–box overlap at the end, metres.
    pub final_penetration_m: f32,
    /// Fastest any body moved at any step (linear speed of the centre), m/s.
    pub max_speed_mps: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::deep_overlap`] for `seconds`.
pub fn deep_overlap(seconds: f32, knobs: Knobs) -> OverlapOutcome {
    let mut run = Timed::new(knobs.world(&cases::deep_overlap()));
    let mut max_speed_mps = 0.0f32;
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        for body in run.world.bodies() {
            // A NaN speed must fail the check, so fold it in as infinity.
            let speed = body.linear_velocity().length();
            max_speed_mps = max_speed_mps.max(if speed.is_nan() { f32::INFINITY } else { speed });
        }
    }
    OverlapOutcome {
        final_penetration_m: max_penetration(&run.world, false).0,
        max_speed_mps,
        ms_per_step: run.median_ms(),
    }
}

/// World-space inertia tensor of a body, kg·m²: R · diag(I_body) · Rᵀ.
pub fn world_inertia(body: &Body) -> Mat3 {
    let r = body.pose().rotation_matrix();
    r * Mat3::from_diagonal(body.shape().principal_inertia(body.mass())) * r.transpose()
}

/// Result of [`intermediate_axis`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpinOutcome {
    /// Largest |E − E₀| / E₀ of the rotational kinetic energy at any step.
    pub max_energy_drift: f32,
    /// Largest ||L| − |L₀|| / |L₀| of the angular momentum about the centre at any step.
    pub max_momentum_drift: f32,
    /// Largest angle between L and L₀ at any step, radians (L is conserved in direction too).
    pub max_momentum_turn_rad: f32,
    /// How many times the intermediate axis reversed relative to L (its cosine to L went from > 0.5 to
    /// < −0.5 or back).
    pub flips: u32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::intermediate_axis`] for `seconds`.
pub fn intermediate_axis(seconds: f32, knobs: Knobs) -> SpinOutcome {
    free_spin(
        cases::SPIN_HALF_EXTENTS,
        cases::SPIN_ANGULAR_VELOCITY,
        seconds,
        knobs,
    )
}

/// Runs [`cases::free_spin`]`(half, angular_velocity)` for `seconds`; `flips` counts reversals of
/// the box's local y axis relative to L.
pub fn free_spin(half: Vec3, angular_velocity: Vec3, seconds: f32, knobs: Knobs) -> SpinOutcome {
    let mut run = Timed::new(knobs.world(&cases::free_spin(half, angular_velocity)));
    let measure = |body: &Body| {
        let w = body.angular_velocity();
        let l = world_inertia(body) * w;
        (0.5 * w.dot(l), l, body.pose().rotation * Vec3::Y)
    };
    let (e0, l0, axis0) = measure(run.world.body(BodyId(0)));
    let mut sign = axis0.dot(l0.normalize()).signum();
    let mut outcome = SpinOutcome {
        max_energy_drift: 0.0,
        max_momentum_drift: 0.0,
        max_momentum_turn_rad: 0.0,
        flips: 0,
        ms_per_step: 0.0,
    };
    let nan_to_inf = |x: f32| if x.is_nan() { f32::INFINITY } else { x };
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        let (e, l, axis) = measure(run.world.body(BodyId(0)));
        outcome.max_energy_drift = outcome
            .max_energy_drift
            .max(nan_to_inf((e - e0).abs() / e0));
        outcome.max_momentum_drift = outcome
            .max_momentum_drift
            .max(nan_to_inf((l.length() - l0.length()).abs() / l0.length()));
        outcome.max_momentum_turn_rad = outcome
            .max_momentum_turn_rad
            .max(nan_to_inf(l.angle_between(l0)));
        let cosine = axis.dot(l.normalize_or_zero());
        if cosine * sign < -0.5 {
            outcome.flips += 1;
            sign = -sign;
        }
    }
    outcome.ms_per_step = run.median_ms();
    outcome
}

/// Result of [`bullet`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BulletOutcome {
    /// Largest x the ball's centre reached at any step, metres (the wall's mid-plane is x = 0, its near face
    /// x = −0.05, so a ball stopped by it stays below −0.15).
    pub max_x_m: f32,
    /// Whether the centre ever got past the wall's mid-plane (or became NaN).
    pub crossed: bool,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
}

/// Runs [`cases::bullet`] for `seconds`.
pub fn bullet(seconds: f32, knobs: Knobs) -> BulletOutcome {
    let mut run = Timed::new(knobs.world(&cases::bullet()));
    let mut max_x_m = f32::NEG_INFINITY;
    let mut crossed = false;
    for _ in 0..steps_for(&run.world, seconds) {
        run.step();
        let x = run.world.body(BodyId(1)).pose().position.x;
        max_x_m = max_x_m.max(x);
        crossed |= x.is_nan() || x > 0.0;
    }
    BulletOutcome {
        max_x_m,
        crossed,
        ms_per_step: run.median_ms(),
    }
}

/// A 3 kg plank under a hundred 1 kg balls, sleeping off: the largest distance of a ball from resting
/// on the plank over the second second, m.
pub fn plank_ball_error(mass_ratio_iterations: u32) -> f32 {
    let mut world = World::new(Settings {
        sleep: false,
        mass_ratio_iterations,
        ..Settings::default()
    });
    world.add_body(BodyDesc::fixed(
        Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)),
        Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
    ));
    let plank = world.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(6.0, 0.1, 6.0)),
        Pose::from_position(Vec3::new(0.0, 0.1, 0.0)),
        3.0,
    ));
    let radius = 0.25;
    let balls: Vec<_> = (0..100)
        .map(|i| {
            let (x, z) = (-4.5 + (i / 10) as f32, -4.5 + (i % 10) as f32);
            world.add_body(BodyDesc::dynamic(
                Shape::sphere(radius),
                Pose::from_position(Vec3::new(x, 0.2 + radius, z)),
                1.0,
            ))
        })
        .collect();
    // The first second settles the load; the second is measured.
    for _ in 0..60 {
        world.step();
    }
    let mut worst: f32 = 0.0;
    for _ in 0..60 {
        world.step();
        let top = world.body(plank).pose().position.y + 0.1;
        for &ball in &balls {
            let y = world.body(ball).pose().position.y;
            worst = worst.max((y - (top + radius)).abs());
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coulomb_slide_on_a_thirty_degree_ramp_matches_the_hand_value() {
        // ½ · 9.81 · (0.5 − 0.3 · 0.8660) · 1² = 1.17814 m.
        assert!((ramp_expected_slide_m(0.3, 1.0, 9.81) - 1.17814).abs() < 1e-4);
        assert_eq!(ramp_expected_slide_m(0.7, 2.0, 9.81), 0.0);
    }

    #[test]
    fn knobs_default_to_the_default_settings_and_keep_the_scene_gravity() {
        let settings = Settings::default();
        let knobs = Knobs::default();
        assert_eq!(
            (knobs.substeps, knobs.iterations, knobs.sleep),
            (settings.substeps, settings.iterations, settings.sleep)
        );
        let world = knobs.world(&cases::intermediate_axis());
        assert_eq!(world.settings().gravity, Vec3::ZERO);
    }

    #[test]
    fn world_inertia_of_a_turned_box_swaps_its_principal_moments() {
        let mut world = World::new(Settings::default());
        let shape = crate::geometry::Shape::cuboid(Vec3::new(0.1, 0.4, 1.0));
        let pose = crate::geometry::Pose::new(
            Vec3::ZERO,
            glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_2),
        );
        let id = world.add_body(crate::physics::BodyDesc::dynamic(shape, pose, 3.0));
        let inertia = world_inertia(world.body(id));
        let local = shape.principal_inertia(3.0);
        // A quarter turn about z swaps the x and y moments.
        assert!((inertia.x_axis.x - local.y).abs() < 1e-5);
        assert!((inertia.y_axis.y - local.x).abs() < 1e-5);
        assert!((inertia.z_axis.z - local.z).abs() < 1e-5);
    }
}
