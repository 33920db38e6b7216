//! Joints: ball, hinge, slider, fixed and distance constraints between two bodies, or a body and the
//! world, solved inside the same sub-stepped soft solver as the contacts.
//!
//! # What a joint holds
//! A joint is described in the bodies' own frames ([`JointDesc`]): an anchor in each body, an axis
//! in each (hinge, slider) and the relative rotation at creation (hinge angle, slider and weld
//! reference), so that it follows the bodies wherever they go. [`JointDesc::at`] makes one from
//! world coordinates in the bodies' current poses, as a scene file gives it. A joint whose side A is
//! the world (`a: None`) keeps its anchor and axis in world coordinates.
//!
//! # The rows (see `rows` for the solver)
//! With anchors r_a = R_a·ℓ_a, r_b = R_b·ℓ_b and points p = x + r:
//! - **point** (ball, hinge, fixed): C = p_b − p_a ∈ ℝ³, solved as one 3×3 block with
//!   K = (1/m_a + 1/m_b)·1 − \[r_a\]× I_a⁻¹ \[r_a\]× − \[r_b\]× I_b⁻¹ \[r_b\]×;
//! - **weld** (fixed, slider): the rotation error E = q_b·q_ref⁻¹·q_a⁻¹ as a rotation vector 2·vec(E),
//!   one 3×3 block with K = I_a⁻¹ + I_b⁻¹;
//! - **hinge axes**: the two directions t₁, t₂ normal to A's axis, C_i = t_i·(a_a × a_b), a 2×2 block;
//! - **axial** rows (hinge angle about a_a, slider travel along a_a, distance along p_b − p_a): one
//!   scalar row each for the motor (a target speed, its impulse bounded by the maximum torque or
//!   force times h), the lower and the upper limit (one-sided, speculative while apart: the bias is
//!   C/h, so a limit is reached exactly, never overshot) and the distance spring;
//! - **slider lines**: t_i·d = 0 for d = p_b − p_a, with A's arm taken at p_b (r_a + d) as Box2D's
//!   prismatic joint does, so the rows stay exact however far the slider has travelled.
//!
//! # Friction
//! A ball joint, a hinge or a slider may have dry friction ([`JointDesc::friction`]): rows along its
//! free axes (a ball joint's three turns as one block, a hinge's turn about its axis, a slider's
//! travel) that stop the relative motion with at most the friction torque or force over the
//! sub-step. They are solved in both passes, first among the joint's rows, and warm-started as a
//! world vector (a hinge's and a slider's taken along the axis now), so a held limb carries its
//! load from sub-step to sub-step as a contact's friction does. Their mass is the two bodies' alone,
//! even in the tree, and they are applied to the two bodies: a friction row only takes motion out
//! and is bounded, so a mass lighter than what the tree holds together makes it take hold over a
//! few sub-steps instead of one, never overshoot; weighed through the tree as a motor is, every
//! joint of a ragdoll would walk its whole tree in every pass. Its kinetic torque is exact, and it
//! takes hold a sub-step late when a joint starts from rest (`tests/physics/joints.rs`,
//! `joint_friction_holds_an_arm_under_its_torque_and_slows_it_over_it`,
//! `a_pendulum_with_joint_friction_loses_a_fixed_angle_a_swing_and_stops`).
//!
//! # Order
//! Each sub-step warm-starts the joints; in both passes (biased, then the relax pass rigid) the
//! joints outside the tree are solved before the contacts, as Box2D v3 solves its joints, and the
//! tree (`tree`: the exact solve, with the scalar rows through it) after them. Whatever a pass solves
//! last holds at its end. Solved first, the tree was undone by every contact after it: each pass
//! left the joints open where a contact pushed a part (a ragdoll's hand stopped by the floor while
//! its arm went on), the next sub-step's biased pass closed the whole gap at once, and that closing
//! velocity went into whatever rested on the parts. A rope bridge gained up to 0.5 J a step under a
//! 4 kg box and never slept, with its hinges 11 mm open; a ragdoll dropped from 100 random poses
//! opened a joint by 76 mm. Solved last: 0.6 mm and 2.9 mm (`tests/physics/mechanisms.rs`,
//! `tests/physics/ragdoll.rs`). What the contacts give up for it is the overlap the tree pushes a
//! part into at a landing, which the next sub-step's contact rows push out (the deepest over the
//! hundred drops 46 → 63 mm for a moment; the deepest at rest 19 → 14 mm). Joints outside the tree
//! stay first: the loose rows are soft and would only be undone in turn, and a cradle's strings
//! solved after its balls' impacts gained 0.02 J in a step.
//!
//! Within the tree's turn, its joints' scalar rows (friction, motors, limits) come after its
//! equality rows (`Settings::joint_scalar_rows_last`), for the same reason: the biased pass closes
//! a joint's whole point error within the sub-step, and solved after a limit it undid it, so a
//! 10 kg arm on 1 m fell 78° past its 30° limit at one sub-step (0.2° at two). A limit or a motor
//! is applied through the tree, so the tree's rows still hold after it; a friction row moves its
//! two bodies alone, and the next pass closes what that opens. Solved last, every arm of the
//! corpus stays within 0.11° of its limit at one sub-step, a held arm's friction sags 0.025°, not
//! 0.044°, and a hundred ragdoll drops open a joint 2.6 mm, not 3.0 (`tests/physics/joints.rs`,
//! `a_hinge_limit_holds_a_loaded_arm_at_one_sub_step_only_with_scalar_rows_last`).
//!
//! # Geometric stiffness
//! A link between two pulls has a stiff turn: tilted by θ about its centre, the tension T at its
//! two anchors (arm d each) turns it back with 2·T·d·θ, a frequency ω = √(2·T·d / I) that a light
//! link under a heavy load makes high (4 cm balls 0.1 m apart holding 10 kg: 390 rad/s). The
//! sub-steps solve the joints' rows exactly at the poses a sub-step begins with and move the
//! bodies explicitly, so that turn is amplified once ω·h passes 2: the loaded chain of the corpus
//! (20 links, 100 times a link) stretched 3.6 m at 2 sub-steps and flew apart at 1, a 40-link one
//! stretched 3.2 % at the default 4, and 2 cm links came apart there too. The geometric stiffness
//! of a joint's rows (∂(Jᵀλ)/∂x, the change of the arms' torque as the body turns) taken
//! implicitly makes a turn against it heavier by about h²·T·d (Andrews, Teichmann and Kry,
//! "Geometric Stiffness for Real-time Constrained Multibody Dynamics", Eurographics 2017). So for
//! the step each body weighs in every row (the tree, the loose joints, the friction rows, the
//! contacts, a hand's hold) with its principal moments at least h·Σ|λ|·|r| over its joint ends
//! but the stiffest, λ each joint's pull a sub-step (`Settings::joint_geometric_stiffness`,
//! `stiffness`): then ω·h stays under √2 whatever the load. One metric for every row: with the tree
//! alone weighing the floor, a rubbing hinge's friction (two bodies' own inertia) and the tree's
//! projection traded energy and a double pendulum flew apart at 1 sub-step. Not the stiffest end,
//! because a body turns about that one by swinging, its mass in the turn (a pendulum's bob, a
//! chain's load, a hand; with every end counted, a double pendulum's upper bob was floored by its
//! pivot's pull and its energy wandered 1.7 % in 20 s, against 0.5 %). The moments themselves stay
//! for the integration, and a floor only raises a moment under it, so at the defaults the
//! pendulums, the cradle, the hinged chain and the ragdolls move as before where their bodies' own
//! moments are above it. The pull is held in quarter octaves (`Joint::pull`), so a swinging chain's
//! floors, and the tree's factorisation with them, do not change every step (the chain of 100
//! links: 1.8 % more instructions a step, not 11 %).
//!
//! Last step's pull lags its load by a step, and a light link must be stiff from the step its
//! load comes: a new joint has carried nothing, and unfloored in its first step a chain of 1 cm
//! balls under 100 times a link spun up its links at once and flew apart even at the default 4
//! sub-steps, however stiff the floors that came a step later; a chain of 4 cm balls whose light
//! end was suddenly pulled with 100 times a link's weight opened a joint 36 cm at 2. So the floors
//! take a joint's pull as at least the load its articulation can hang on it, the weight and
//! applied forces of every body joints join to its ends (`Settings::joint_pull_from_load`): no
//! joint carries more where those alone load it, and a pull guessed high only makes a body turn
//! heavier. A load the articulation does not carry itself (a heavy body dropped into a hanging
//! basket, a hand's pull) still comes a step before its floors. Measured in
//! `tests/physics/joints.rs`,
//! `a_light_chain_under_a_heavy_load_holds_at_low_sub_steps_only_with_geometric_stiffness`,
//! `light_links_stiffen_with_their_load_from_its_first_step_only_when_floors_take_it`, and the
//! corpus's loaded chains (`nudge bench corpus`).
//!
//! # Softness
//! Joint rows are soft like the contacts (`softness.rs`) at twice the contact frequency (capped by
//! the sub-step as the contacts are) and a damping ratio of [`JOINT_DAMPING_RATIO`]; a distance
//! spring at its own frequency and damping ratio. Bodies joined by a joint do not collide with each
//! other unless the joint says `collide`.

pub(crate) mod rows;
pub(crate) mod stiffness;
pub(crate) mod tree;

use glam::{Quat, Vec3};

use crate::geometry::Pose;
use crate::physics::input::WorldInput;
use crate::physics::{BodyId, World};

/// Damping ratio of the joints' soft rows. Above critical: a joint error closes without ringing.
pub const JOINT_DAMPING_RATIO: f32 = 2.0;

/// A joint's handle, in the order joints were added, from 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct JointId(pub u32);

impl JointId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A motor on a hinge (rad/s and N·m) or a slider (m/s and N): it drives the joint's relative
/// speed towards `speed` with at most `max` torque or force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motor {
    pub speed: f32,
    pub max: f32,
}

/// A distance joint's spring: natural frequency (Hz) and damping ratio.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spring {
    pub hertz: f32,
    pub damping_ratio: f32,
}

/// What a joint constrains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointKind {
    /// The anchors stay together; the bodies turn freely about them.
    Ball,
    /// The anchors stay together and the bodies turn only about the axis; `limits` (radians, lower ≤
    /// upper) bound the angle from the pose at creation.
    Hinge {
        limits: Option<[f32; 2]>,
        motor: Option<Motor>,
    },
    /// No relative rotation; B's anchor moves only along A's axis; `limits` (m) bound the travel
    /// from the pose at creation.
    Slider {
        limits: Option<[f32; 2]>,
        motor: Option<Motor>,
    },
    /// No relative motion at all (a weld).
    Fixed,
    /// The anchors' distance stays within `[min, max]` (m): a rod when they are equal, a rope when
    /// `min` is 0; with a `spring`, it pulls the distance towards `length` inside those bounds.
    Distance {
        length: f32,
        min: f32,
        max: f32,
        spring: Option<Spring>,
    },
}

/// A joint between bodies `a` (or the world, `None`) and `b`, in the bodies' frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointDesc {
    pub kind: JointKind,
    pub a: Option<BodyId>,
    pub b: BodyId,
    /// The anchors in A's and B's frames (A's in world coordinates when A is the world), m.
    pub local_anchor_a: Vec3,
    pub local_anchor_b: Vec3,
    /// The axis in A's and B's frames, unit (hinge, slider; +y for the others).
    pub local_axis_a: Vec3,
    pub local_axis_b: Vec3,
    /// B's rotation relative to A's at creation, q_a⁻¹·q_b: where the hinge angle is 0 and what a
    /// weld holds.
    pub reference: Quat,
    /// Whether the two bodies still collide with each other.
    pub collide: bool,
    /// The torque (ball, hinge; N·m) or force (slider; N) it takes to turn or slide the joint along
    /// its free axes: dry friction in the joint, 0 for none (fixed and distance joints have none).
    pub friction: f32,
}

impl JointDesc {
    /// A joint from world coordinates in the poses the bodies have now (`pose_a` is `None` for the
    /// world): the anchors (the same point for every kind but distance) and the axis (normalised;
    /// ignored by ball, fixed and distance joints).
    #[allow(clippy::too_many_arguments)] // the joint's parts, each once, as a scene file lists them
    pub fn at(
        kind: JointKind,
        a: Option<(BodyId, Pose)>,
        b: (BodyId, Pose),
        anchor_a: Vec3,
        anchor_b: Vec3,
        axis: Vec3,
        collide: bool,
    ) -> Self {
        let axis = axis.try_normalize().unwrap_or(Vec3::Y);
        let pose_a = a.map_or(Pose::IDENTITY, |(_, pose)| pose);
        let (id_b, pose_b) = b;
        let inv_a = pose_a.rotation.inverse();
        let inv_b = pose_b.rotation.inverse();
        Self {
            kind,
            a: a.map(|(id, _)| id),
            b: id_b,
            local_anchor_a: inv_a * (anchor_a - pose_a.position),
            local_anchor_b: inv_b * (anchor_b - pose_b.position),
            local_axis_a: inv_a * axis,
            local_axis_b: inv_b * axis,
            reference: (inv_a * pose_b.rotation).normalize(),
            collide,
            friction: 0.0,
        }
    }

    /// The same joint with `friction` (see [`JointDesc::friction`]).
    pub fn with_friction(self, friction: f32) -> Self {
        Self { friction, ..self }
    }
}

/// A joint in the world: its description and what it carried last step (the warm start).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint {
    pub desc: JointDesc,
    pub(crate) impulses: JointImpulses,
    /// The impulse a sub-step its point, line or rod rows carried, as the inertia floors of its
    /// bodies take it (see "Geometric stiffness"): raised to a quarter octave above it when it
    /// grows, lowered only when it falls under a quarter.
    pub(crate) pull: f32,
}

/// Accumulated impulses of a joint's rows over the last step, on B (A gets the opposite).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct JointImpulses {
    /// Point or slider-line rows, N·s (slider: only the two across the axis are used).
    pub linear: Vec3,
    /// Weld or hinge-axis rows, N·m·s.
    pub angular: Vec3,
    /// The axial rows: motor, lower limit, upper limit, spring (distance: the rod's row is `lower`).
    pub motor: f32,
    pub lower: f32,
    pub upper: f32,
    pub spring: f32,
    /// The friction rows, as a world vector: N·m·s about the free axes (ball, hinge) or N·s along
    /// the slider's axis.
    pub friction: Vec3,
}

/// What a joint applied to its body B over the last step (A felt the opposite), as forces.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointLoad {
    /// Its point, line or (distance joint) rod rows, N.
    pub force: Vec3,
    /// Its weld or hinge-axis rows, N·m.
    pub torque: Vec3,
    /// Its axial rows along the hinge or slider axis or the distance joint's line (motor, limits,
    /// spring, rod), N·m or N; positive turns B forward about the axis or pushes it away from A.
    pub axial: f32,
}

/// Why a joint was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointError {
    /// It names a body the world does not have.
    NoSuchBody(BodyId),
    /// Both ends are the same body.
    SameBody,
    /// A number is not finite, an axis is zero, limits are in the wrong order or a length negative.
    Invalid,
}

impl std::fmt::Display for JointError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            JointError::NoSuchBody(id) => write!(f, "there is no body {}", id.0),
            JointError::SameBody => write!(f, "a joint needs two different bodies"),
            JointError::Invalid => write!(
                f,
                "a joint needs finite numbers, a non-zero axis, limits in order, lengths ≥ 0 and \
                 friction ≥ 0 (on a ball, hinge or slider only)"
            ),
        }
    }
}

impl std::error::Error for JointError {}

impl JointDesc {
    /// Whether it can join two bodies of some world: two different ends and numbers that make a
    /// joint (see [`JointError`]); whether its bodies exist is the world's to say.
    pub fn check(&self) -> Result<(), JointError> {
        if self.a == Some(self.b) {
            Err(JointError::SameBody)
        } else if !self.is_valid() {
            Err(JointError::Invalid)
        } else {
            Ok(())
        }
    }

    /// Whether its numbers make a joint (see [`JointError::Invalid`]).
    fn is_valid(&self) -> bool {
        let finite = self.local_anchor_a.is_finite()
            && self.local_anchor_b.is_finite()
            && self.local_axis_a.is_finite()
            && self.local_axis_b.is_finite()
            && self.reference.is_finite();
        let unit = |v: Vec3| (v.length() - 1.0).abs() < 1e-3;
        let in_order = |l: Option<[f32; 2]>| {
            l.is_none_or(|[lo, hi]| lo.is_finite() && hi.is_finite() && lo <= hi)
        };
        let motor_ok = |m: Option<Motor>| {
            m.is_none_or(|m| m.speed.is_finite() && m.max.is_finite() && m.max >= 0.0)
        };
        let friction_ok = self.friction.is_finite()
            && self.friction >= 0.0
            && (self.friction == 0.0
                || matches!(
                    self.kind,
                    JointKind::Ball | JointKind::Hinge { .. } | JointKind::Slider { .. }
                ));
        let kind_ok = match self.kind {
            JointKind::Ball | JointKind::Fixed => true,
            JointKind::Hinge { limits, motor } | JointKind::Slider { limits, motor } => {
                in_order(limits) && motor_ok(motor)
            }
            JointKind::Distance {
                length,
                min,
                max,
                spring,
            } => {
                [length, min, max]
                    .iter()
                    .all(|x| x.is_finite() && *x >= 0.0)
                    && min <= max
                    && spring.is_none_or(|s| {
                        s.hertz.is_finite()
                            && s.hertz >= 0.0
                            && s.damping_ratio.is_finite()
                            && s.damping_ratio >= 0.0
                    })
            }
        };
        finite && unit(self.local_axis_a) && unit(self.local_axis_b) && kind_ok && friction_ok
    }
}

impl World {
    /// Adds a joint; ids are handed out in order, from 0. Both bodies wake.
    pub fn add_joint(&mut self, desc: JointDesc) -> Result<JointId, JointError> {
        let exists = |id: BodyId| id.index() < self.bodies.len();
        if let Some(a) = desc.a
            && !exists(a)
        {
            return Err(JointError::NoSuchBody(a));
        }
        if !exists(desc.b) {
            return Err(JointError::NoSuchBody(desc.b));
        }
        desc.check()?;
        self.log(WorldInput::AddJoint(desc));
        for id in [desc.a, Some(desc.b)].into_iter().flatten() {
            self.wake_island(id.0);
        }
        self.joints.push(Joint {
            desc,
            impulses: JointImpulses::default(),
            pull: 0.0,
        });
        Ok(JointId(self.joints.len() as u32 - 1))
    }

    /// What `joint` applied over the last step. Its rows' impulses are per sub-step (the warm
    /// start replays them every sub-step), so a force is an impulse over the sub-step, not the step.
    pub fn joint_load(&self, joint: &Joint) -> JointLoad {
        let h = self.settings.dt / self.settings.substep_count() as f32;
        let per = if h > 0.0 { 1.0 / h } else { 0.0 };
        let i = &joint.impulses;
        // Friction along the free axes is the axial rows' (hinge, slider) or the torque's (ball).
        let (friction_axial, friction_torque) = match joint.desc.kind {
            JointKind::Hinge { .. } | JointKind::Slider { .. } => {
                let rotation_a = joint
                    .desc
                    .a
                    .map_or(Quat::IDENTITY, |a| self.bodies[a.index()].pose.rotation);
                let axis = rotation_a * joint.desc.local_axis_a;
                (axis.dot(i.friction), Vec3::ZERO)
            }
            _ => (0.0, i.friction),
        };
        JointLoad {
            force: i.linear * per,
            torque: (i.angular + friction_torque) * per,
            axial: (i.motor + i.lower - i.upper + i.spring + friction_axial) * per,
        }
    }

    /// Every joint, indexed by `JointId`.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// The joints' anchors in world coordinates now, (on A, on B) for each joint: where a view draws
    /// the links.
    pub fn joint_anchors(&self, joint: &Joint) -> (Vec3, Vec3) {
        let pose =
            |id: Option<BodyId>| id.map_or(Pose::IDENTITY, |id| self.bodies[id.index()].pose);
        let (pa, pb) = (pose(joint.desc.a), pose(Some(joint.desc.b)));
        (
            pa.position + pa.rotation * joint.desc.local_anchor_a,
            pb.position + pb.rotation * joint.desc.local_anchor_b,
        )
    }

    /// Wakes the sleeping end of every joint whose other end is awake (a joint holds its bodies in
    /// one island, as a contact does), until none is left. Returns whether any woke.
    pub(in crate::physics) fn wake_jointed_sleepers(&mut self) -> bool {
        let mut any = false;
        loop {
            let mut woke = false;
            for k in 0..self.joints.len() {
                let desc = self.joints[k].desc;
                let Some(a) = desc.a else { continue };
                let (ba, bb) = (&self.bodies[a.index()], &self.bodies[desc.b.index()]);
                if ba.is_awake_dynamic() && bb.sleeping {
                    self.wake_island(desc.b.0);
                    woke = true;
                } else if bb.is_awake_dynamic() && ba.sleeping {
                    self.wake_island(a.0);
                    woke = true;
                }
            }
            if !woke {
                return any;
            }
            any = true;
        }
    }

    /// Removes the pairs of bodies joined by a joint that does not let them collide from this
    /// step's candidate pairs (sorted `(a, b)`, `a < b`).
    pub(in crate::physics) fn drop_jointed_pairs(&mut self) {
        let s = &mut self.scratch;
        s.joint_rows.no_collide.clear();
        for joint in &self.joints {
            if let (Some(a), false) = (joint.desc.a, joint.desc.collide) {
                let (a, b) = (a.0.min(joint.desc.b.0), a.0.max(joint.desc.b.0));
                s.joint_rows.no_collide.push((a, b));
            }
        }
        if s.joint_rows.no_collide.is_empty() {
            return;
        }
        s.joint_rows.no_collide.sort_unstable();
        // Both lists are sorted and `retain` visits the pairs in order: one merge, not a search
        // per pair.
        let no_collide = &s.joint_rows.no_collide;
        let mut next = 0;
        s.pair_finder.pairs.retain(|pair| {
            while next < no_collide.len() && no_collide[next] < *pair {
                next += 1;
            }
            no_collide.get(next) != Some(pair)
        });
    }
}
