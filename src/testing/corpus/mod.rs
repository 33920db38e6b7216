//! The corpus: families of hard cases generated from parameters, each member with an analytic or
//! conservation answer, so the physics is judged on cases nobody tuned it to. A family is a list of
//! members (one scene and one way to measure its error each); `nudge bench physics` reports each
//! family's worst error against ms/step for sub-steps 1–8, and `tests/physics/corpus.rs` holds every
//! member to its tolerance at the default knobs.
//!
//! Adding a family: a file here with a `pub fn family() -> Family` (members built from parameters,
//! most simply by [`Family::of`] from a list of cases and one outcome function;
//! each with its tolerance at the default knobs), one line in [`families`], and a test in
//! `tests/physics/corpus.rs` (`holds(family("its name"), regression)`, `regression` about 3–5× its
//! worst error at the defaults) once it passes there.
//! `nudge bench physics` reports every family, passing or not, with its failing members counted.
//! Errors are measured from the bodies' poses and velocities only, never from the engine's own
//! statistics, and are relative (a fraction of the analytic answer's scale) unless the family says
//! otherwise.

pub mod apex;
pub mod cannon;
pub mod collisions;
pub mod cradle;
pub mod far;
pub mod free_spin;
pub mod heavy_on_light;
pub mod joints;
pub mod melee;
pub mod oblique;
pub mod overlap;
pub mod push_to_tip;
pub mod ramp;
pub mod resting;
pub mod restitution;
pub mod rocking;
pub mod rolling_ramp;
pub mod rolling_resistance;
pub mod skid;
pub mod slide;
pub mod slope_bounce;
pub mod spin_down;
pub mod tipping;
pub mod tower;
pub mod wall_hop;
pub mod wall_squeeze;

use crate::testing::hard_case::Knobs;

/// What one member's run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The member's error (relative unless its family says otherwise); NaN when the run failed to
    /// produce the quantity measured (counted as a failure).
    pub error: f32,
    /// Median wall-clock ms per step.
    pub ms_per_step: f64,
    /// What was measured, for a failing test's message.
    pub detail: String,
}

/// One member of a family: a label naming its parameters, the tolerance its error must stay under
/// at the default knobs, and its runner.
pub struct Member {
    /// Its parameters, e.g. "e=0.5 h=2m".
    pub label: String,
    /// Largest error allowed at the default knobs.
    pub tolerance: f32,
    /// Builds the scene, runs it with the knobs, measures the error.
    pub run: Box<dyn Fn(Knobs) -> Outcome + Send + Sync>,
}

/// A family of members sharing one answer.
pub struct Family {
    /// Short name, the bench row's label.
    pub name: &'static str,
    /// The answer every member is measured against, in a phrase.
    pub answer: &'static str,
    /// What its errors are measured in.
    pub unit: Unit,
    /// Its members.
    pub members: Vec<Member>,
}

impl Family {
    /// A family of one member per case: labelled by `label`, held to `tolerance` at the default
    /// knobs, measured by `outcome` (the shape of most families: a parameter set, one error, one
    /// tolerance).
    pub fn of<C: Copy + Send + Sync + 'static>(
        name: &'static str,
        answer: &'static str,
        unit: Unit,
        tolerance: f32,
        cases: impl IntoIterator<Item = C>,
        label: impl Fn(&C) -> String,
        outcome: fn(C, Knobs) -> Outcome,
    ) -> Self {
        Self {
            name,
            answer,
            unit,
            members: cases
                .into_iter()
                .map(|case| Member {
                    label: label(&case),
                    tolerance,
                    run: Box::new(move |knobs| outcome(case, knobs)),
                })
                .collect(),
        }
    }
}

/// What a family's errors are measured in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Unit {
    /// A fraction of the answer's scale (or of the limit, as the family says).
    Relative,
    /// Metres.
    Metres,
}

impl Unit {
    /// `error` for a table: a percentage, or millimetres.
    pub fn format(self, error: f32) -> String {
        match self {
            Unit::Relative => format!("{:.3}%", 100.0 * error),
            Unit::Metres => format!("{:.4} mm", 1e3 * error),
        }
    }
}

/// Every family of the corpus, in the bench's order.
pub fn families() -> Vec<Family> {
    vec![
        restitution::family(),
        collisions::head_on_family(),
        collisions::moving_target_family(),
        collisions::off_centre_family(),
        restitution::corner_family(),
        restitution::ball_on_box_family(),
        restitution::ball_on_stack_family(),
        restitution::box_drop_family(),
        resting::family(),
        cradle::family(),
        cannon::family(),
        ramp::family(),
        spin_down::family(),
        slide::family(),
        tower::drift_family(),
        tower::penetration_family(),
        overlap::family(),
        heavy_on_light::family(),
        rolling_ramp::family(),
        rolling_resistance::family(),
        skid::family(),
        tipping::family(),
        push_to_tip::family(),
        rocking::impact_family(),
        rocking::rebound_family(),
        oblique::family(),
        slope_bounce::family(),
        wall_squeeze::family(),
        wall_hop::family(),
        melee::momentum_family(),
        melee::angular_family(),
        free_spin::family(),
        far::family(),
        joints::period_family(),
        joints::double_family(),
        joints::chain_family(),
        joints::limit_family(),
    ]
}

/// Whether `error` is within `tolerance` (a NaN error, a failed measurement, never is).
pub fn within(error: f32, tolerance: f32) -> bool {
    error <= tolerance
}

/// Whether error `a` is worse than `b`: larger, or NaN where `b` is not.
pub fn worse(a: f32, b: f32) -> bool {
    (a.is_nan() && !b.is_nan()) || a > b
}

/// How a family did at some knobs.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// The worst member's error (NaN if some member failed to measure).
    pub error: f32,
    /// The worst member's label.
    pub label: String,
    /// Mean over the members of their median ms per step.
    pub ms_per_step: f64,
    /// Members over their tolerance.
    pub failing: usize,
}

/// Runs every member of `family` with `knobs`.
pub fn worst(family: &Family, knobs: Knobs) -> Summary {
    let mut summary = Summary {
        error: 0.0,
        label: String::new(),
        ms_per_step: 0.0,
        failing: 0,
    };
    for member in &family.members {
        let out = (member.run)(knobs);
        summary.ms_per_step += out.ms_per_step / family.members.len() as f64;
        summary.failing += usize::from(!within(out.error, member.tolerance));
        if worse(out.error, summary.error) {
            (summary.error, summary.label) = (out.error, member.label.clone());
        }
    }
    summary
}
