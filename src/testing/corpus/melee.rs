//! A melee in zero gravity: boxes of several aspect ratios and balls, thrown spinning at one another,
//! collide with friction and restitution, in clusters that touch many at once. Whatever happens
//! between them, contact impulses come in equal and opposite pairs through one point, so the total
//! linear momentum P = Σ m·v and angular momentum L = Σ (x × m·v + I·ω) about the origin are kept, and
//! with restitution at most 1 the kinetic energy can only fall. An engine breaks these where its
//! impulses are not applied at the same point on both bodies, where a position correction leaves
//! velocity behind, or where a speed cap or damping acts unseen.
//!
//! **Where nudge fails it** (the "melee L and energy" family, which has no test until it passes;
//! `nudge bench corpus` reports it): P is kept, but L drifts by a few per cent of its scale over the
//! run and the elastic frictionless crowd ends with more kinetic energy than it began. The L drift
//! is first order in the step, not the sub-step (halving dt halves it; more sub-steps do not): a
//! manifold's anchors and the bodies' world inertias are prepared once per step and held through
//! its sub-steps (as Box2D v3 holds its anchors), so an impulse late in a step turns the bodies
//! about where they were at its start. The energy gain comes from the same place (a spinning flat
//! box gains a little at each impact; a pair of cubes, or of spheres, keeps it exactly).

use glam::{Quat, Vec3};

use super::restitution::scene;
use super::{Family, Member, Outcome, Unit};
use crate::color::PALETTE;
use crate::geometry::{Pose, Shape};
use crate::physics::{BodyDesc, World};
use crate::scene::{Scene, SceneBody};
use crate::testing::hard_case::{Knobs, Timed, world_inertia};

/// Simulated time of a run: the clusters meet within the first second, s.
const SECONDS: f32 = 3.0;
/// Allowed drift of L over its scale (Σ (|x × m·v| + |I·ω|) at the start), and allowed rise of the
/// kinetic energy over its start.
pub const TOLERANCE: f32 = 1e-3;
/// Allowed drift of P over its scale (Σ m·|v| at the start): f32 rounding's.
pub const MOMENTUM_TOLERANCE: f32 = 1e-5;

/// One melee: how many bodies, their restitution and friction.
#[derive(Clone, Copy, Debug)]
pub struct Melee {
    pub bodies: usize,
    pub e: f32,
    pub mu: f32,
}

/// A deterministic stream of numbers in [−1, 1) (a linear congruential generator: the members must
/// not depend on a library's random numbers).
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 40) as f32 / (1u64 << 24) as f32) * 2.0 - 1.0
    }

    fn vec3(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next())
    }
}

impl Melee {
    /// The bodies on a loose grid around the origin, each thrown towards the origin at 2–4 m/s with a
    /// random part and a spin of up to 3 rad/s about a random axis, turned at random.
    pub fn scene(&self) -> Scene {
        let mut random = Stream(0x5eed ^ self.bodies as u64);
        let side = (self.bodies as f32).cbrt().ceil() as usize;
        let spacing = 1.6;
        let shapes = [
            Shape::cuboid(Vec3::splat(0.4)),
            Shape::sphere(0.35),
            Shape::cuboid(Vec3::new(0.7, 0.2, 0.3)),
            Shape::sphere(0.5),
            Shape::cuboid(Vec3::new(0.15, 0.6, 0.15)),
        ];
        let bodies = (0..self.bodies)
            .map(|i| {
                let cell = Vec3::new(
                    (i % side) as f32,
                    (i / side % side) as f32,
                    (i / (side * side)) as f32,
                ) - Vec3::splat(0.5 * (side as f32 - 1.0));
                let position = cell * spacing + random.vec3() * 0.2;
                let rotation = Quat::from_scaled_axis(random.vec3() * 3.0);
                let shape = shapes[i % shapes.len()];
                let mut desc =
                    BodyDesc::dynamic(shape, Pose::new(position, rotation), shape.volume());
                let inward = -position.normalize_or(Vec3::X);
                desc.linear_velocity = inward * (3.0 + random.next()) + random.vec3();
                desc.angular_velocity = random.vec3().normalize_or(Vec3::Y) * 3.0 * random.next();
                desc.restitution = self.e;
                desc.friction = self.mu;
                SceneBody::new(desc, PALETTE[i % PALETTE.len()])
            })
            .collect();
        let mut scene = scene(format!("melee {self:?}"), bodies);
        scene.settings.gravity = Vec3::ZERO;
        scene
    }
}

/// Momentum, angular momentum about the origin, kinetic energy, and the scales of the first two.
fn totals(world: &World) -> (Vec3, Vec3, f32, f32, f32) {
    let (mut p, mut l, mut energy, mut p_scale, mut l_scale) =
        (Vec3::ZERO, Vec3::ZERO, 0.0, 0.0, 0.0);
    for body in world.bodies() {
        let (m, v, w) = (body.mass(), body.linear_velocity(), body.angular_velocity());
        let iw = world_inertia(body) * w;
        let orbit = body.pose().position.cross(m * v);
        p += m * v;
        l += orbit + iw;
        energy += 0.5 * m * v.length_squared() + 0.5 * w.dot(iw);
        p_scale += m * v.length();
        l_scale += orbit.length() + iw.length();
    }
    (p, l, energy, p_scale, l_scale)
}

/// What a melee keeps: momentum (exact by construction) or angular momentum and energy.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kept {
    /// P: every impulse is applied equal and opposite.
    Momentum,
    /// L about the origin, and no rise in kinetic energy.
    AngularMomentumAndEnergy,
}

/// Runs the melee for `SECONDS`; the error is, at any step, P's drift over its scale, or the
/// larger of L's drift over its scale and the kinetic energy's rise over its start.
pub fn outcome(melee: Melee, kept: Kept, knobs: Knobs) -> Outcome {
    let mut run = Timed::new(knobs.world(&melee.scene()));
    let (p0, l0, e0, p_scale, l_scale) = totals(&run.world);
    let (mut p_drift, mut l_drift, mut rise, mut e_end) = (0.0f32, 0.0f32, 0.0f32, e0);
    // NaN (a blown-up run) must fail: folded in as infinity.
    let worst = |old: f32, x: f32| {
        if x.is_nan() {
            f32::INFINITY
        } else {
            old.max(x)
        }
    };
    for _ in 0..(SECONDS / run.world.settings().dt).round() as usize {
        run.step();
        let (p, l, energy, _, _) = totals(&run.world);
        p_drift = worst(p_drift, (p - p0).length() / p_scale);
        l_drift = worst(l_drift, (l - l0).length() / l_scale);
        rise = worst(rise, (energy - e0) / e0);
        e_end = energy;
    }
    Outcome {
        error: match kept {
            Kept::Momentum => p_drift,
            Kept::AngularMomentumAndEnergy => l_drift.max(rise),
        },
        ms_per_step: run.median_ms(),
        detail: format!(
            "P drift {p_drift:.2e}, L drift {l_drift:.2e}, energy rise {rise:.2e} (ends at {:.1} % \
             of its start)",
            100.0 * e_end / e0
        ),
    }
}

/// 2, 8 and 27 bodies, inelastic to elastic, frictionless and rough.
const MELEES: [Melee; 6] = [
    Melee {
        bodies: 2,
        e: 1.0,
        mu: 0.5,
    },
    Melee {
        bodies: 8,
        e: 0.0,
        mu: 0.5,
    },
    Melee {
        bodies: 8,
        e: 1.0,
        mu: 0.0,
    },
    Melee {
        bodies: 8,
        e: 0.5,
        mu: 1.0,
    },
    Melee {
        bodies: 27,
        e: 0.5,
        mu: 0.5,
    },
    Melee {
        bodies: 27,
        e: 1.0,
        mu: 0.5,
    },
];

/// The melees judged on what they keep: `name`, the answer in a phrase, the tolerance.
fn family_of(kept: Kept, name: &'static str, answer: &'static str, tolerance: f32) -> Family {
    Family {
        name,
        answer,
        unit: Unit::Relative,
        members: MELEES
            .into_iter()
            .map(|melee| Member {
                label: format!("{} bodies e={} μ={}", melee.bodies, melee.e, melee.mu),
                tolerance,
                run: Box::new(move |knobs| outcome(melee, kept, knobs)),
            })
            .collect(),
    }
}

/// Momentum kept: it holds by construction, so its tolerance is f32 rounding's scale.
pub fn momentum_family() -> Family {
    family_of(
        Kept::Momentum,
        "melee momentum",
        "P kept in a zero-g melee (10⁻⁵)",
        MOMENTUM_TOLERANCE,
    )
}

/// Angular momentum about the origin kept and no energy gained.
pub fn angular_family() -> Family {
    family_of(
        Kept::AngularMomentumAndEnergy,
        "melee L and energy",
        "L about the origin kept, kinetic energy never rises, in a zero-g melee (0.1 %)",
        TOLERANCE,
    )
}
