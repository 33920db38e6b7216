//! Two free bodies colliding in zero gravity: head-on, one chasing another, and off-centre. The
//! answer is the frictionless impact law: along the normal n at the contact, the impulse is
//! j = (1 + e)·c / (1/m₁ + 1/m₂), c = (v₁ − v₂)·n the approach speed; momentum is kept exactly.
//! Spheres and centred face hits turn nothing, so the bodies' velocities after are all there is.

use glam::Vec3;

use super::restitution::{body, scene};
use super::{Family, Member, Outcome, Unit};
use crate::geometry::{Pose, Shape};
use crate::physics::BodyId;
use crate::scene::Scene;
use crate::testing::hard_case::{Knobs, Timed};

/// Simulated time of a collision run: long enough for any pair to meet and part, s.
const SECONDS: f32 = 2.0;
/// Allowed error of the velocities after, as a fraction of the approach speed.
pub const VELOCITY_TOLERANCE: f32 = 0.01;
/// Radius of the balls, m.
const RADIUS: f32 = 0.25;

/// One collision: two bodies, where they start, how they move, and the normal they meet along.
#[derive(Clone, Copy, Debug)]
pub struct Collision {
    /// Shapes of the two bodies.
    pub shapes: [Shape; 2],
    /// Their densities (masses are density × volume).
    pub densities: [f32; 2],
    /// Their starting centres, m.
    pub positions: [Vec3; 2],
    /// Their velocities, m/s.
    pub velocities: [Vec3; 2],
    /// Restitution of both.
    pub e: f32,
    /// Unit normal from body 1 to body 2 at the moment of impact.
    pub normal: Vec3,
}

impl Collision {
    /// Zero gravity and the two bodies (ids 0 and 1).
    pub fn scene(&self, name: String) -> Scene {
        let bodies = (0..2)
            .map(|i| {
                let mut b = body(
                    self.shapes[i],
                    Pose::from_position(self.positions[i]),
                    self.e,
                    i + 1,
                );
                b.desc.mass *= self.densities[i];
                b.desc.linear_velocity = self.velocities[i];
                b
            })
            .collect();
        let mut scene = scene(name, bodies);
        scene.settings.gravity = Vec3::ZERO;
        scene
    }

    /// The velocities after the impact.
    pub fn expected(&self) -> [Vec3; 2] {
        let m = [0, 1].map(|i| self.densities[i] * self.shapes[i].volume());
        let c = (self.velocities[0] - self.velocities[1]).dot(self.normal);
        let j = (1.0 + self.e) * c.max(0.0) / (1.0 / m[0] + 1.0 / m[1]);
        [
            self.velocities[0] - self.normal * (j / m[0]),
            self.velocities[1] + self.normal * (j / m[1]),
        ]
    }

    /// Runs it; the error is the largest velocity error after `SECONDS` over the approach speed.
    pub fn outcome(&self, knobs: Knobs) -> Outcome {
        let mut run = Timed::new(knobs.world(&self.scene("collision".into())));
        let steps = (SECONDS / run.world.settings().dt).round() as usize;
        for _ in 0..steps {
            run.step();
        }
        let want = self.expected();
        let c = (self.velocities[0] - self.velocities[1]).dot(self.normal);
        let got = [0, 1].map(|i| run.world.body(BodyId(i)).linear_velocity());
        let error = (0..2)
            .map(|i| (got[i] - want[i]).length() / c)
            .fold(0.0f32, |a, b| if b.is_nan() { b } else { a.max(b) });
        Outcome {
            error,
            ms_per_step: run.median_ms(),
            detail: format!(
                "after: {:.4?} and {:.4?} m/s, expected {:.4?} and {:.4?}",
                got[0], got[1], want[0], want[1]
            ),
        }
    }
}

fn member(label: String, collision: Collision) -> Member {
    Member {
        label,
        tolerance: VELOCITY_TOLERANCE,
        run: Box::new(move |knobs| collision.outcome(knobs)),
    }
}

fn ball() -> Shape {
    Shape::sphere(RADIUS)
}

/// Two equal balls meeting head-on along x, and one striking another at rest; `gap` between them
/// at the start, so the impact falls at a different point within a step.
fn head_on(e: f32, v1: f32, v2: f32, gap: f32) -> Collision {
    let x = RADIUS + 0.5 * gap;
    Collision {
        shapes: [ball(); 2],
        densities: [1.0; 2],
        positions: [Vec3::new(-x, 1.0, 0.0), Vec3::new(x, 1.0, 0.0)],
        velocities: [Vec3::new(v1, 0.0, 0.0), Vec3::new(v2, 0.0, 0.0)],
        e,
        normal: Vec3::X,
    }
}

/// Equal balls head-on and striking one at rest, e ∈ {0, 0.5, 1}.
pub fn head_on_family() -> Family {
    let mut members = Vec::new();
    for e in [0.0, 0.5, 1.0] {
        for (v1, v2, gap) in [(2.0, -2.0, 0.31), (2.0, 0.0, 0.173), (5.0, -1.0, 0.77)] {
            members.push(member(
                format!("e={e} {v1} vs {v2} m/s"),
                head_on(e, v1, v2, gap),
            ));
        }
    }
    Family {
        name: "balls head-on",
        answer: "velocities after = the impact law (e = 1: equal balls exchange them)",
        unit: Unit::Relative,
        members,
    }
}

/// A ball chasing a unit box that moves away along x, the box `density` times as dense.
fn chase(e: f32, density: f32) -> Collision {
    Collision {
        shapes: [ball(), Shape::cuboid(Vec3::splat(0.5))],
        densities: [1.0, density],
        positions: [Vec3::new(-1.2, 1.0, 0.0), Vec3::new(0.5, 1.0, 0.0)],
        velocities: [Vec3::new(4.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0)],
        e,
        normal: Vec3::X,
    }
}

/// A ball hitting a moving box face-on, e ∈ {0.5, 1}, the box 0.2 to 5 times as dense.
pub fn moving_target_family() -> Family {
    let mut members = Vec::new();
    for e in [0.5, 1.0] {
        for density in [0.2, 1.0, 5.0] {
            members.push(member(
                format!("e={e} box density {density}"),
                chase(e, density),
            ));
        }
    }
    Family {
        name: "ball hits moving box",
        answer: "velocities after = the impact law",
        unit: Unit::Relative,
        members,
    }
}

/// A ball striking a resting ball with its centre `offset` (m) off the line of motion.
fn off_centre(e: f32, offset: f32) -> Collision {
    let d = 2.0 * RADIUS;
    let normal = Vec3::new((d * d - offset * offset).sqrt(), -offset, 0.0) / d;
    Collision {
        shapes: [ball(); 2],
        densities: [1.0; 2],
        positions: [Vec3::new(-1.0, 1.0 + offset, 0.0), Vec3::new(0.0, 1.0, 0.0)],
        velocities: [Vec3::new(3.0, 0.0, 0.0), Vec3::ZERO],
        e,
        normal,
    }
}

/// Off-centre (oblique) impacts of equal frictionless balls, e ∈ {0.5, 1}.
///
/// Within 0.4 % at the defaults; at 1 and 2 sub-steps up to 12.5 % and 1.9 % off (`nudge bench
/// corpus`, 2026-12-01), for a reason traced at 1 sub-step, offset 0.4 m: the pair's manifold
/// gives their separation along one normal, moved to first order with the bodies, which for two
/// balls sliding past each other is short of the true gap. After the step's positions the balls
/// are 31 mm apart, but along that normal the relax pass's speculative row sees them closing by
/// 33 mm in the next step, catches the difference, and the impact events
/// (`wide_contacts::impacts`) bounce them there, along a normal 3.8° off the one they meet along. Leaving rows
/// more than the slop apart out of the relax pass puts every member within 0.001 %, but a light
/// block squeezed against a wall (`wall_squeeze`) and a ball bouncing on a slope at 8 sub-steps
/// (`slope_bounce`) lose collisions that the relax pass's catch brings into the step's events.
pub fn off_centre_family() -> Family {
    let mut members = Vec::new();
    for e in [0.5, 1.0] {
        for offset in [0.1, 0.25, 0.4] {
            members.push(member(
                format!("e={e} offset {offset} m"),
                off_centre(e, offset),
            ));
        }
    }
    Family {
        name: "balls off-centre",
        answer: "velocities after = the impact law along the contact normal",
        unit: Unit::Relative,
        members,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_elastic_balls_are_expected_to_exchange_velocities() {
        let [a, b] = head_on(1.0, 2.0, -1.0, 0.1).expected();
        assert!(
            (a.x + 1.0).abs() < 1e-6 && (b.x - 2.0).abs() < 1e-6,
            "{a} {b}"
        );
    }

    #[test]
    fn an_impact_keeps_momentum() {
        let c = chase(0.5, 5.0);
        let m = [c.shapes[0].volume(), 5.0 * c.shapes[1].volume()];
        let [a, b] = c.expected();
        let before = c.velocities[0] * m[0] + c.velocities[1] * m[1];
        assert!((a * m[0] + b * m[1] - before).length() < 1e-4);
    }
}
