//! The joints' geometric stiffness as inertia floors (see "Geometric stiffness" in `joint`): how
//! heavy each body a joint pulls on must turn for the step, and the held pull it is reckoned from.

use glam::Vec3;

use crate::physics::joint::Joint;
use crate::physics::settings::Settings;
use crate::physics::{Body, BodyId, union_find};

/// Fills `ends` (per body) with the stiffness of the joint ends on it, summed and the stiffest
/// (`[sum, stiffest]`, kg·m²; [`inertia_floor`] makes the floor of them): h·|λ|·|r| for each end,
/// λ the joint's pull (`Joint::pull`, the impulse a sub-step its rows carried, held in steps) or,
/// where it is more, the load its articulation can hang on it ([`ArticulationLoads`]), and r the
/// end's arm. Left empty without joints or with `Settings::joint_geometric_stiffness` off.
pub(in crate::physics) fn stiffness_of_ends(
    (ends, loads): (&mut Vec<[f32; 2]>, &mut ArticulationLoads),
    joints: &[Joint],
    bodies: &[Body],
    settings: &Settings,
) {
    ends.clear();
    loads.clear();
    if !settings.joint_geometric_stiffness || joints.is_empty() {
        return;
    }
    let h = settings.dt / settings.substep_count() as f32;
    if settings.joint_pull_from_load {
        loads.fill(joints, bodies, settings.gravity.length(), h);
    }
    ends.resize(bodies.len(), [0.0; 2]);
    for joint in joints {
        let pull = joint.pull.max(loads.on(joint));
        if pull.is_nan() || pull <= 0.0 {
            continue;
        }
        let arms = [
            (joint.desc.a, joint.desc.local_anchor_a),
            (Some(joint.desc.b), joint.desc.local_anchor_b),
        ];
        for (id, arm) in arms {
            if let Some(id) = id {
                let stiffness = h * pull * arm.length();
                let [sum, stiffest] = &mut ends[id.index()];
                *sum += stiffness;
                *stiffest = stiffest.max(stiffness);
            }
        }
    }
}

/// The load each articulation can hang on a joint of it, N·s a sub-step: the weight and applied
/// forces over a sub-step of every body joints join together (a chain and its load, a ragdoll). No
/// joint carries more where gravity and those forces alone load it, and a floor above the pull
/// only makes a body turn heavier. Floored by the pull its joints carried the step before alone, a
/// light link stiffened a step after its load: a new chain of 20 balls of 1 cm under 100 times a
/// link spun up its links in its first step, which had no pull at all, and flew apart, as did 4 cm
/// balls at 2 sub-steps when their chain's end was suddenly pulled with 100 times a link's weight
/// (`Settings::joint_pull_from_load`). A joint to the world or a static body joins nothing.
#[derive(Debug, Default)]
pub(in crate::physics) struct ArticulationLoads {
    /// Per body, its articulation's root (empty: no loads this step).
    roots: Vec<u32>,
    /// Per root, its articulation's load, N·s a sub-step.
    loads: Vec<f32>,
}

impl ArticulationLoads {
    fn clear(&mut self) {
        self.roots.clear();
        self.loads.clear();
    }

    /// The loads of the articulations `joints` make of `bodies`, under gravity `g` (m/s²) over
    /// sub-steps of `h` (s).
    fn fill(&mut self, joints: &[Joint], bodies: &[Body], g: f32, h: f32) {
        let dynamic = |id: Option<BodyId>| id.filter(|id| !bodies[id.index()].is_static);
        union_find::reset(&mut self.roots, bodies.len());
        for joint in joints {
            if let (Some(a), Some(b)) = (dynamic(joint.desc.a), dynamic(Some(joint.desc.b))) {
                union_find::union(&mut self.roots, a.0, b.0);
            }
        }
        self.loads.resize(bodies.len(), 0.0);
        for (i, body) in bodies.iter().enumerate() {
            let root = union_find::find(&mut self.roots, i as u32);
            self.roots[i] = root;
            if !body.is_static {
                self.loads[root as usize] += h * (g * body.mass() + body.force.length());
            }
        }
    }

    /// The load `joint`'s articulation can hang on it (0 without loads).
    fn on(&self, joint: &Joint) -> f32 {
        [Some(joint.desc.b), joint.desc.a]
            .into_iter()
            .flatten()
            .filter_map(|id| self.roots.get(id.index()))
            .map(|&root| self.loads[root as usize])
            .fold(0.0, f32::max)
    }
}

/// The least a body's moments of inertia may be for the step, from its ends' `[sum, stiffest]`
/// stiffness: all but the stiffest. A body turns about that end freely, by swinging (a pendulum's
/// bob, a chain's load, a limb's end), with its mass in the turn; only the others hold it to a stiff
/// turn about its centre (a link between two pulls).
pub(in crate::physics) fn inertia_floor([sum, stiffest]: [f32; 2]) -> f32 {
    sum - stiffest
}

/// Principal moments `moments` raised to `floor` where they are under it (exactly `moments` where
/// none is): how the step's rows weigh a body its joints floor.
pub(in crate::physics) fn floored(moments: Vec3, floor: f32) -> Vec3 {
    moments.max(Vec3::splat(floor))
}

/// The pull a joint's bodies' inertia floors take (`Joint::pull`): `kept` while the pull now,
/// `now`, is within a quarter of it and not above it, else the quarter octave at or above `now`.
/// Held so, the floors change only when a load does by a good part (see `quarter_octave_above`).
pub(in crate::physics) fn held_pull(kept: f32, now: f32) -> f32 {
    if !now.is_finite() {
        return kept;
    }
    if now > kept || now < 0.25 * kept {
        quarter_octave_above(now)
    } else {
        kept
    }
}

/// The least of 1, 1.25, 1.5 or 1.75 times a power of two that is at least `x` (`x` itself when it
/// is one, or zero, or not a positive normal number). A floor that follows the joints' loads to the
/// bit changes every step, and with it the tree's masses: a step's first pass could not take the
/// factorisation its last one left (`tree`, "Masses"), and a swinging chain of 100 links factored
/// five times a step instead of four (11 % more instructions a step).
fn quarter_octave_above(x: f32) -> f32 {
    if !(x > 0.0 && x.is_normal()) {
        return x.max(0.0);
    }
    // The exponent and the mantissa's top two bits are kept; any lower bit rounds them up.
    const LOW: u32 = (1 << 21) - 1;
    f32::from_bits((x.to_bits() + LOW) & !LOW)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_octave_is_at_least_the_value_and_under_a_quarter_more() {
        for x in [1e-9f32, 0.003, 0.1, 0.7, 1.0, 1.3, 2.0, 17.5, 3e5] {
            let q = quarter_octave_above(x);
            assert!(q >= x && q < 1.25 * x + f32::EPSILON, "{x} → {q}");
            assert_eq!(quarter_octave_above(q), q, "{x}: not a step");
        }
        assert_eq!(quarter_octave_above(1.5), 1.5);
        assert_eq!(quarter_octave_above(1.6), 1.75);
        for x in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(!(quarter_octave_above(x) > 0.0 && quarter_octave_above(x).is_finite()));
        }
    }

    #[test]
    fn a_held_pull_rises_with_the_load_and_falls_only_under_a_quarter() {
        let kept = held_pull(0.0, 3.0);
        assert_eq!(kept, 3.0);
        // Rises at once, to a step at or above the load.
        assert_eq!(held_pull(kept, 3.1), 3.5);
        // Held while the load stays between a quarter of it and it.
        assert_eq!(held_pull(kept, 2.0), kept);
        assert_eq!(held_pull(kept, 0.8), kept);
        // Lowered once under a quarter; a lost load keeps it.
        assert_eq!(held_pull(kept, 0.7), 0.75);
        assert_eq!(held_pull(kept, f32::NAN), kept);
    }

    #[test]
    fn only_a_body_held_from_two_sides_gets_a_floor() {
        // A link between two equal pulls: one of them. A bob on one joint, or a body whose other
        // joint holds it at its centre: none.
        assert_eq!(inertia_floor([2.0, 1.0]), 1.0);
        assert_eq!(inertia_floor([1.0, 1.0]), 0.0);
        assert_eq!(inertia_floor([0.0, 0.0]), 0.0);
        assert_eq!(inertia_floor([3.0, 2.0]), 1.0);
    }
}
