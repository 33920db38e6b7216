//! Restitution: a ball dropped on a floor, on a box resting on the floor, and a box landing on a
//! corner. The answers come from Newton's law of restitution (the rebound speed is e times the
//! approach speed at the moment of impact) and energy in free flight.

use glam::{Quat, Vec3};

use super::apex::apexes;
use super::{Family, Member, Outcome, Unit, worse};
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, BodyId, Settings};
use crate::scene::cases::floor;
use crate::scene::{Scene, SceneBody, framing};
use crate::testing::hard_case::{Knobs, Timed};

/// Coefficients of restitution the sweeps try.
pub const RESTITUTIONS: [f32; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];
/// Drop heights (gap under the body at release), m.
pub const DROPS_M: [f32; 4] = [0.5, 2.0, 5.0, 20.0];
/// Simulated time of every run, s.
pub const SECONDS: f32 = 10.0;
/// Radius of the dropped ball, m.
pub const BALL_RADIUS: f32 = 0.25;
/// Allowed relative error of every apex against e²ⁿ·h.
pub const APEX_TOLERANCE: f32 = 0.01;
/// A hop whose neighbouring samples are within this of the rest height is not an apex, m.
pub(super) const AIRBORNE_M: f32 = 1e-3;
/// Impacts within this fraction of the restitution threshold are ambiguous (either answer is
/// right) and end the comparison.
const THRESHOLD_MARGIN: f32 = 0.05;

/// A scene of `bodies` with default settings and a framing camera.
pub(super) fn scene(name: String, bodies: Vec<SceneBody>) -> Scene {
    Scene {
        name,
        settings: Settings::default(),
        camera: framing::auto_camera(&bodies, framing::DEFAULT_FOV_DEG.to_radians()),
        bodies,
        joints: Vec::new(),
    }
}

/// A floor of restitution `e` (top at y = 0).
pub(super) fn bouncy_floor(e: f32) -> SceneBody {
    let mut ground = floor(10.0);
    ground.desc.restitution = e;
    ground
}

/// A dynamic body of density 1, restitution `e`, no friction, at `pose`.
pub(super) fn body(shape: Shape, pose: Pose, e: f32, color: usize) -> SceneBody {
    let mut desc = BodyDesc::dynamic(shape, pose, shape.volume());
    desc.restitution = e;
    desc.friction = 0.0;
    SceneBody {
        name: None,
        frozen: false,
        desc,
        color: PALETTE[color % PALETTE.len()],
    }
}

/// The apexes a body dropped from rest `h` above where it rests should reach within `seconds`:
/// e²ⁿ·h for every impact n faster than the threshold (by a margin), under gravity `g`.
pub fn expected_apexes(e: f32, h: f32, g: f32, threshold: f32, seconds: f32) -> Vec<f32> {
    let mut out = Vec::new();
    let (mut height, mut t) = (h, (2.0 * h / g).sqrt());
    loop {
        let impact = (2.0 * g * height).sqrt();
        if impact <= threshold * (1.0 + THRESHOLD_MARGIN) || e == 0.0 {
            return out;
        }
        let next = e * e * height;
        let rise = (2.0 * next / g).sqrt();
        // Apexes in the last tenth of a second may not be sampled on both sides.
        if t + rise > seconds - 0.1 || next < 2.0 * AIRBORNE_M {
            return out;
        }
        out.push(next);
        height = next;
        t += 2.0 * rise;
    }
}

/// Compares measured apexes with expected ones: the worst relative error, and a description. A
/// missing apex counts as an error of 1; an apex after the last expected one (a bounce that should
/// not have been) counts as its height over the last expected height (over h when none was).
pub fn compare_apexes(measured: &[f32], expected: &[f32], h: f32) -> (f32, String) {
    let mut worst = (0.0f32, String::from("no apex expected, none measured"));
    for (n, want) in expected.iter().enumerate() {
        let (error, detail) = match measured.get(n) {
            Some(got) => (
                (got - want).abs() / want,
                format!("apex {} at {got:.5} m, expected {want:.5} m", n + 1),
            ),
            None => (1.0, format!("apex {} missing, expected {want:.5} m", n + 1)),
        };
        if worse(error, worst.0) || n == 0 {
            worst = (error.max(worst.0), detail);
        }
    }
    let scale = expected.last().copied().unwrap_or(h);
    for (n, got) in measured.iter().enumerate().skip(expected.len()) {
        let error = got / scale;
        if worse(error, worst.0) {
            worst = (error, format!("apex {} at {got:.5} m not expected", n + 1));
        }
    }
    worst
}

/// Runs `scene` for [`SECONDS`], sampling the height of `id`'s lowest point above the top of
/// `under` (what it bounces on: where that surface is, sagging on soft supports included) each
/// step.
fn heights(scene: &Scene, knobs: Knobs, id: BodyId, under: BodyId) -> (Vec<f32>, f64) {
    let mut run = Timed::new(knobs.world(scene));
    let steps = (SECONDS / run.world.settings().dt).round() as usize;
    let mut out = Vec::with_capacity(steps + 1);
    let low = |world: &crate::physics::World| {
        let (body, below) = (world.body(id), world.body(under));
        let top = below.shape().aabb(below.pose()).max.y;
        body.shape().aabb(body.pose()).min.y - top
    };
    out.push(low(&run.world));
    for _ in 0..steps {
        run.step();
        out.push(low(&run.world));
    }
    (out, run.median_ms())
}

/// The apex outcome of dropping body `id` of `scene` from `h` above `under`.
fn apex_outcome(scene: &Scene, knobs: Knobs, id: BodyId, under: BodyId, e: f32, h: f32) -> Outcome {
    let (heights, ms_per_step) = heights(scene, knobs, id, under);
    let g = -scene.settings.gravity.y;
    let expected = expected_apexes(e, h, g, scene.settings.restitution_threshold, SECONDS);
    let measured = apexes(&heights, 0.0, AIRBORNE_M);
    let (error, detail) = compare_apexes(&measured, &expected, h);
    Outcome {
        error,
        ms_per_step,
        detail: format!(
            "{detail}; {} apexes measured, {} expected",
            measured.len(),
            expected.len()
        ),
    }
}

/// A ball of restitution `e` dropped from `h` onto a floor of restitution `e`.
pub fn ball_drop(e: f32, h: f32) -> Scene {
    let ball = body(
        Shape::sphere(BALL_RADIUS),
        Pose::from_position(Vec3::new(0.0, h + BALL_RADIUS, 0.0)),
        e,
        3,
    );
    scene(format!("drop e={e} h={h}"), vec![bouncy_floor(e), ball])
}

/// Balls dropped on a floor: e ∈ [`RESTITUTIONS`], h ∈ [`DROPS_M`].
pub fn family() -> Family {
    let mut members = Vec::new();
    for e in RESTITUTIONS {
        for h in DROPS_M {
            members.push(Member {
                label: format!("e={e} h={h}m"),
                tolerance: APEX_TOLERANCE,
                run: Box::new(move |knobs| {
                    apex_outcome(&ball_drop(e, h), knobs, BodyId(1), BodyId(0), e, h)
                }),
            });
        }
    }
    Family {
        name: "ball drop",
        answer: "every apex after an impact above the threshold within 1 % of e^2n h",
        unit: Unit::Relative,
        members,
    }
}

/// Half-extent of the box of [`ball_on_box`], m.
pub const BOX_HALF: f32 = 0.5;

/// A ball of restitution `e` dropped from `h` onto a stack of `boxes` unit boxes of restitution
/// `box_e` resting on a floor of the same: the floor holds the stack, so the ball rebounds as from
/// the floor itself. Bodies: floor, boxes from the bottom, ball.
pub fn ball_on_box(e: f32, h: f32, boxes: usize, box_e: f32) -> Scene {
    let mut bodies = vec![bouncy_floor(box_e)];
    for i in 0..boxes {
        let mut block = body(
            Shape::cuboid(Vec3::splat(BOX_HALF)),
            Pose::from_position(Vec3::new(0.0, BOX_HALF * (2 * i + 1) as f32, 0.0)),
            box_e,
            i,
        );
        block.desc.friction = 0.5;
        bodies.push(block);
    }
    let top = 2.0 * BOX_HALF * boxes as f32;
    bodies.push(body(
        Shape::sphere(BALL_RADIUS),
        Pose::from_position(Vec3::new(0.0, top + h + BALL_RADIUS, 0.0)),
        e,
        3,
    ));
    scene(format!("ball on {boxes} boxes e={e} h={h}"), bodies)
}

/// Balls dropped on a stack of `boxes` resting on the floor, the boxes plastic or as bouncy as the
/// ball.
fn ball_on_stack_members(boxes: usize) -> Vec<Member> {
    let mut members = Vec::new();
    for box_bouncy in [false, true] {
        for e in [0.5, 1.0] {
            for h in [0.5, 2.0, 5.0] {
                let box_e = if box_bouncy { e } else { 0.0 };
                members.push(Member {
                    label: format!("e={e} h={h}m, boxes e={box_e}"),
                    tolerance: APEX_TOLERANCE,
                    run: Box::new(move |knobs| {
                        let scene = ball_on_box(e, h, boxes, box_e);
                        let (ball, top) = (BodyId(boxes as u32 + 1), BodyId(boxes as u32));
                        apex_outcome(&scene, knobs, ball, top, e, h)
                    }),
                });
            }
        }
    }
    members
}

/// Balls dropped on a box resting on the floor.
pub fn ball_on_box_family() -> Family {
    Family {
        name: "ball on box",
        answer: "as the ball drop: the floor holds the box",
        unit: Unit::Relative,
        members: ball_on_stack_members(1),
    }
}

/// Balls dropped on a stack of three boxes resting on the floor.
pub fn ball_on_stack_family() -> Family {
    Family {
        name: "ball on a stack",
        answer: "as the ball drop: the floor holds the stack",
        unit: Unit::Relative,
        members: ball_on_stack_members(3),
    }
}

/// Half-extent of the box of [`box_drop`], m.
pub const FLAT_HALF: f32 = 0.25;

/// A box of restitution `e` released at rest face down, `h` above a floor of restitution `e`.
pub fn box_drop(e: f32, h: f32) -> Scene {
    let block = body(
        Shape::cuboid(Vec3::new(2.0 * FLAT_HALF, FLAT_HALF, FLAT_HALF)),
        Pose::from_position(Vec3::new(0.0, h + FLAT_HALF, 0.0)),
        e,
        0,
    );
    scene(
        format!("box drop e={e} h={h}"),
        vec![bouncy_floor(e), block],
    )
}

/// Boxes landing flat: four corners hit at once, so the impact is simultaneous and must not tip
/// the box (a point-by-point rebound would).
pub fn box_drop_family() -> Family {
    let mut members = Vec::new();
    for e in [0.25, 0.5, 1.0] {
        for h in [0.5, 2.0, 5.0] {
            members.push(Member {
                label: format!("e={e} h={h}m"),
                tolerance: APEX_TOLERANCE,
                run: Box::new(move |knobs| {
                    apex_outcome(&box_drop(e, h), knobs, BodyId(1), BodyId(0), e, h)
                }),
            });
        }
    }
    Family {
        name: "box drop flat",
        answer: "every apex of the lowest point within 1 % of e^2n h",
        unit: Unit::Relative,
        members,
    }
}

/// Half-extent of the cube of [`corner_drop`], m.
pub const CUBE_HALF: f32 = 0.25;

/// A frictionless cube of restitution `e`, tilted so one corner points down, released at rest with
/// that corner `h` above a floor of restitution `e`.
pub fn corner_drop(e: f32, h: f32) -> Scene {
    let tilt = corner_tilt();
    let shape = Shape::cuboid(Vec3::splat(CUBE_HALF));
    let lowest = lowest_corner(tilt);
    let pose = Pose::new(Vec3::new(0.0, h - lowest.y, 0.0), tilt);
    let mut ground = bouncy_floor(e);
    ground.desc.friction = 0.0;
    ground.color = FLOOR_COLOR;
    scene(
        format!("corner e={e} h={h}"),
        vec![ground, body(shape, pose, e, 1)],
    )
}

/// The cube's tilt: not symmetric, so the corner's lever arm is off the vertical and the impact
/// also spins it.
fn corner_tilt() -> Quat {
    Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.3)
}

/// The lowest corner of the tilted cube, relative to its centre, world frame.
fn lowest_corner(tilt: Quat) -> Vec3 {
    let mut low = Vec3::splat(f32::INFINITY);
    for k in 0..8 {
        let sign = |bit: u32| if k & bit == 0 { -1.0 } else { 1.0 };
        let c = tilt * (CUBE_HALF * Vec3::new(sign(1), sign(2), sign(4)));
        if c.y < low.y {
            low = c;
        }
    }
    low
}

/// The energy the corner drop keeps through its first impact, J: the release energy less
/// ½·m_eff·(1 − e²)·c², c the corner's approach speed and m_eff the cube's mass seen at the corner
/// along the normal (1/m + |r × n|²/I for a cube).
/// Returns (energy at release, energy expected after the impact, kinetic energy at impact), J.
pub fn corner_expected_energy(e: f32, h: f32, g: f32) -> (f32, f32, f32) {
    let shape = Shape::cuboid(Vec3::splat(CUBE_HALF));
    let m = shape.volume();
    let inertia = m * (2.0 * CUBE_HALF).powi(2) / 6.0;
    let r = lowest_corner(corner_tilt());
    let lever = r.cross(Vec3::Y).length_squared();
    let m_eff = 1.0 / (1.0 / m + lever / inertia);
    let c2 = 2.0 * g * h;
    let released = m * g * (h - r.y);
    (
        released,
        released - 0.5 * m_eff * (1.0 - e * e) * c2,
        0.5 * m * c2,
    )
}

/// Mechanical energy of the cube: kinetic (the vertical velocity taken as the free-flight
/// parabola's, v − ½·g·h_sub, which the symplectic sub-steps keep constant in flight) plus
/// potential above the floor.
fn cube_energy(world: &crate::physics::World, id: BodyId, h_sub: f32) -> f32 {
    let body = world.body(id);
    let g = -world.settings().gravity.y;
    let mut v = body.linear_velocity();
    v.y -= 0.5 * g * h_sub;
    let w = body.angular_velocity();
    let m = body.mass();
    let inertia = m * (2.0 * CUBE_HALF).powi(2) / 6.0;
    0.5 * m * v.length_squared()
        + 0.5 * inertia * w.length_squared()
        + m * g * body.pose().position.y
}

/// Drops the cube on its corner; the error is the energy at the end of the step of the first
/// impact (the cube is then on its free flight after it: touching, or just above) against the
/// expected, over the kinetic energy at impact.
fn corner_outcome(e: f32, h: f32, knobs: Knobs) -> Outcome {
    let scene = corner_drop(e, h);
    let g = -scene.settings.gravity.y;
    let (_, want, impact_ke) = corner_expected_energy(e, h, g);
    let mut run = Timed::new(knobs.world(&scene));
    let id = BodyId(1);
    let dt = run.world.settings().dt;
    let h_sub = dt / knobs.substeps.max(1) as f32;
    let steps = (SECONDS / dt).round() as usize;
    let mut previous_vy = 0.0f32;
    let mut got: Option<f32> = None;
    for _ in 0..steps {
        run.step();
        let vy = run.world.body(id).linear_velocity().y;
        if (vy - (previous_vy - g * dt)).abs() > 1e-3 {
            got = Some(cube_energy(&run.world, id, h_sub));
            break;
        }
        previous_vy = vy;
    }
    let ms_per_step = run.median_ms();
    match got {
        Some(energy) => Outcome {
            error: (energy - want).abs() / impact_ke,
            ms_per_step,
            detail: format!("energy after the first impact {energy:.5} J, expected {want:.5} J"),
        },
        None => Outcome {
            error: f32::NAN,
            ms_per_step,
            detail: "never hit the floor".into(),
        },
    }
}

/// Cubes landing on a corner.
pub fn corner_family() -> Family {
    let mut members = Vec::new();
    // Plastic landings (e = 0) are the sub-steps' alone, and their last relax brakes a corner short
    // of the floor: the energy "after" is not read at an impact.
    for e in [0.25, 0.5, 1.0] {
        for h in [0.5, 2.0, 5.0] {
            members.push(Member {
                label: format!("e={e} h={h}m"),
                tolerance: APEX_TOLERANCE,
                run: Box::new(move |knobs| corner_outcome(e, h, knobs)),
            });
        }
    }
    Family {
        name: "cube on a corner",
        answer: "energy after the impact = before - m_eff (1 - e^2) c^2 / 2",
        unit: Unit::Relative,
        members,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_elastic_drop_is_expected_to_come_back_to_its_height_every_time() {
        let apexes = expected_apexes(1.0, 2.0, 9.81, 1.0, 10.0);
        assert!(
            apexes.len() >= 3 && apexes.iter().all(|&a| a == 2.0),
            "{apexes:?}"
        );
    }

    #[test]
    fn apexes_stop_where_the_impact_falls_under_the_threshold() {
        let apexes = expected_apexes(0.5, 5.0, 9.81, 1.0, 10.0);
        // Impacts at 9.9, 4.95, 2.48, 1.24 m/s bounce; 0.62 m/s does not.
        assert_eq!(apexes.len(), 4, "{apexes:?}");
    }

    #[test]
    fn a_missing_apex_is_a_whole_error_and_an_extra_one_is_measured() {
        assert_eq!(compare_apexes(&[1.0], &[1.0, 0.5], 2.0).0, 1.0);
        assert_eq!(compare_apexes(&[1.0, 0.1], &[1.0], 2.0).0, 0.1);
    }
}
