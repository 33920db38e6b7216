//! A slender block tipped onto one bottom edge and let go (Housner, "The behavior of inverted
//! pendulum structures during earthquakes", Bull. Seismol. Soc. Am. 53, 1963): it rocks about that
//! edge back to upright, strikes the floor with the other and rocks about it, each impact keeping
//! a fixed fraction of its angular velocity.
//!
//! For a block of half-width b and half-height h on a rough floor, R = √(b² + h²) from its centre
//! to an edge and α = atan(b/h) its critical angle, a lean θ (0 < θ < α) about the edge obeys
//!
//! ```text
//!   (4/3)·m·R²·θ̈ = −m·g·R·sin(α − θ)
//! ```
//!
//! (the moment of inertia about the edge is (4/3)·m·R²). Released from rest at θ₀, it reaches
//! upright at the time this equation gives, integrated here by fourth-order Runge–Kutta at a step
//! far finer than the engine's; slender blocks obey it nearly as the linear θ(t) = α − (α −
//! θ₀)·cosh(p·t), p² = 3g/4R. At the impact the new edge holds without bouncing or slipping and
//! the angular momentum about it is kept: the block leaves it at r = 1 − (3/2)·sin²α of its
//! angular speed, and the energy left, r² of it, sets how far it rocks the other way:
//! cos(α − θ₁) = cos α + r²·(cos(α − θ₀) − cos α).
//!
//! Two families: when the first impact comes (the rocking's dynamics, whatever the impact does),
//! and how far the block rocks back after it (what the impact keeps). A contact that lets the
//! pivot edge sink, or acts only at the points it found, shifts the first; an impact that
//! bounces, slips or loses more than the rigid answer moves the second.
//!
//! Measured 2026-12-01 (`nudge bench corpus`): the first impact comes within 0.38 % of the rigid
//! block's time at the defaults, 0.53 % at 8 sub-steps, 0.98 % at 2 and 2 % at 1 (pinned at the
//! defaults by `tests/physics/corpus.rs`). The rebound
//! falls short at every count, 23 % at the defaults (17 % at 8 sub-steps, 47 % at 1), worst for the
//! stocky block tipped furthest: the impact loses 2.5 to 5.5 times the energy the rigid one does
//! (20 % of it against 8 % for the stocky block tipped to 0.9 α, 12 % against 2 % for the slender
//! one tipped to 0.5 α). That family fails and has no test yet. Not the solver's convergence: at
//! 4 or 16 iterations the rebound is as short; more sub-steps help slowly (16: 7 to 14 % short,
//! 32: 6 to 12 %); without the spread row it is shorter (up to 26 %), without the symmetric relax
//! a little longer (up to 21 %), and the other fixes change it by under a point (measured
//! 2026-12-01). Both halves of a swing lose: at the defaults the block sheds about 2 % of its
//! energy pivoting to upright, where the rigid block keeps all of it, and 8.6 % (h/b = 12 tipped to
//! 0.5 α) to 15 % (h/b = 6 tipped to 0.9 α) of its kinetic energy at the impact, where Housner's
//! keeps all but 2.1 and 7.9 %; at 1 sub-step the slender block sheds 19 % pivoting and 24 % at
//! the impact.
//!
//! Where the impact's extra loss goes (traced pass by pass, h/b = 12 tipped to 0.5 α at one
//! sub-step of 1/240 s, 2026-12-01): the landing edge is caught one pass early, by its
//! speculative row in the relax pass of the sub-step before it lands, still 24 to 31 µm up; and
//! the relax pass, re-solving the manifold's totals, unloads the pivot that now lifts, so that
//! sub-step's whole weight moves from the old edge to the new one, a moment m·g·2b·h the rigid
//! block never feels. The block leaves at 0.977 of its angular speed where Housner's keeps 0.990:
//! one sub-step's gravity, an error of order h, as the slow gain with sub-steps says. Not the
//! manifold's solve, although at that catch its four coupled normal rows are far from converged
//! (the landing edge still approaches at 17 mm/s where its rows allow 7): converged by eight
//! extra sweeps of its points, the rebound is no longer (0.0337 rad against 0.0349 at the
//! defaults). Two changes to the relax pass that were measured and not kept: leaving speculative
//! rows out of it (the landing caught by the next biased pass) brings the slender block within
//! 5 % at the defaults and 0.5 % at 8 sub-steps, but the family to 19 % and 50 % (the stocky
//! blocks go wrong), and a box dropped flat fails at 2 to 8 sub-steps and one sliding to a stop
//! by 5 to 12 %, since that catch is what lands them; keeping every row's biased total through
//! the relax pass (no unloading) leaves the family 14 % short at the defaults and 13 % at 8, but
//! head-on balls, heavy-on-light and a ball on a stack at 8 sub-steps fail; kept only up to the
//! statics' preload (the weight the support held up, not the bias's push) and the spread row
//! taking none of it back, no corpus family gets worse and the rebound is 18.6 % short at the
//! defaults, 15 % at 8, but kept awake the crossed tower falls at 2 sub-steps and the heap of
//! boxes and balls holds in 1 of 8 copies at 4 (`nudge bench rest`; with the spread row allowed
//! back down to what is kept, the tower stands and the heap holds in 4 of 8); kept only on
//! manifolds where a point lands, the slender block rocks back 1.7 % further, no more. Nor is
//! it the statics spreading a block's pressure over the landing edge's points while they are
//! still in the air (the one sweep leaves some of that warm start on them): spread over the
//! touching points alone, the rebound moves by under 0.3 % at 2 to 8 sub-steps.

use super::{Family, Outcome, Unit};
use crate::physics::Settings;
use crate::scene::cases::{TIPPED_BLOCK_HALF_WIDTH, critical_angle, tipped_block};
use crate::testing::hard_case::{self, Knobs, Timed};

/// The gravity the rigid answer falls under, m/s²: the scene's (`Settings::default()`, which
/// `scene::cases::tipped_block` builds with), so the answer cannot drift from the run.
fn gravity() -> f64 {
    f64::from(Settings::default().gravity.length())
}
/// Half-width of every block across its rocking, m.
const HALF_WIDTH: f32 = TIPPED_BLOCK_HALF_WIDTH;
/// The blocks' slenderness h/b (`scene::cases::tipped_block`), and the fractions of the critical
/// angle they are tipped to.
const ASPECTS: [f32; 2] = [6.0, 12.0];
const TIPS: [f32; 2] = [0.5, 0.9];
/// Simulated time of a run, s: past the first rebound's peak of every member.
const SECONDS: f32 = 5.0;
/// Runge–Kutta steps per second for the rigid answer.
const RK_RATE: f64 = 100_000.0;
/// Largest error of the first impact's time at the default knobs, relative (measured: the module
/// docs).
pub const MAX_IMPACT_TIME_ERROR: f32 = 0.01;
/// Largest error of the first rebound's amplitude at the default knobs, relative.
pub const MAX_REBOUND_ERROR: f32 = 0.05;

/// One block: slenderness h/b, and its tip as a fraction of its critical angle.
#[derive(Clone, Copy, Debug)]
pub struct Rocking {
    pub aspect: f32,
    pub tip: f32,
}

impl Rocking {
    fn half_height(&self) -> f32 {
        self.aspect * HALF_WIDTH
    }

    /// The critical angle α = atan(b/h), rad.
    pub fn critical(&self) -> f32 {
        critical_angle(self.aspect)
    }

    /// The rigid answer: the time the block released at rest from θ₀ = tip·α takes to reach
    /// upright, s (Runge–Kutta on the equation of the module docs, in f64).
    pub fn first_impact_s(&self) -> f64 {
        let (b, h) = (f64::from(HALF_WIDTH), f64::from(self.half_height()));
        let (alpha, radius) = (b.atan2(h), b.hypot(h));
        let k = 3.0 * gravity() / (4.0 * radius);
        let accel = |theta: f64| -k * (alpha - theta).sin();
        let dt = 1.0 / RK_RATE;
        let (mut theta, mut omega, mut t) = (f64::from(self.tip) * alpha, 0.0f64, 0.0f64);
        while theta > 0.0 {
            let (th0, om0) = (theta, omega);
            let k1 = (om0, accel(th0));
            let k2 = (om0 + 0.5 * dt * k1.1, accel(th0 + 0.5 * dt * k1.0));
            let k3 = (om0 + 0.5 * dt * k2.1, accel(th0 + 0.5 * dt * k2.0));
            let k4 = (om0 + dt * k3.1, accel(th0 + dt * k3.0));
            theta = th0 + dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            omega = om0 + dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
            // Crossing within this step: the part of it before θ = 0, linearly.
            t += if theta > 0.0 {
                dt
            } else {
                dt * th0 / (th0 - theta)
            };
        }
        t
    }

    /// The rigid answer: how far the block rocks the other way after the first impact, rad.
    pub fn rebound_rad(&self) -> f32 {
        let alpha = f64::from(self.critical());
        let theta0 = f64::from(self.tip) * alpha;
        let r = 1.0 - 1.5 * alpha.sin().powi(2);
        let cos1 = alpha.cos() + r * r * ((alpha - theta0).cos() - alpha.cos());
        (alpha - cos1.acos()) as f32
    }
}

/// What a run measured: when the lean first reached zero (s, interpolated between steps; NaN if
/// it never did) and the largest lean the other way before it came back (rad).
struct Rocked {
    first_impact_s: f32,
    rebound_rad: f32,
    ms_per_step: f64,
}

/// Tips the block onto its edge and lets it rock for `SECONDS`, never asleep: released at rest
/// near its critical angle, a block starts slowly, and one judged asleep by its speed alone would
/// stop there (see `sleep`, "Speeding up"); the families measure the rocking, not the sleeping.
fn rock(case: Rocking, knobs: Knobs) -> Rocked {
    let knobs = Knobs {
        sleep: false,
        ..knobs
    };
    let mut run = Timed::new(knobs.world(&tipped_block(case.aspect, case.tip)));
    let dt = run.world.settings().dt;
    let lean = |run: &Timed| hard_case::lean_about_x(&run.world);
    let (mut before, mut first_impact_s, mut rebound_rad) = (lean(&run), f32::NAN, 0.0f32);
    for step in 1..=(SECONDS / dt).round() as usize {
        run.step();
        let now = lean(&run);
        if first_impact_s.is_nan() {
            if now <= 0.0 {
                first_impact_s = (step as f32 - now / (now - before)) * dt;
            }
        } else if now > 0.0 {
            break;
        }
        if !first_impact_s.is_nan() {
            rebound_rad = rebound_rad.max(-now);
        }
        before = now;
    }
    Rocked {
        first_impact_s,
        rebound_rad,
        ms_per_step: run.median_ms(),
    }
}

fn members() -> impl Iterator<Item = Rocking> {
    ASPECTS
        .into_iter()
        .flat_map(|aspect| TIPS.map(|tip| Rocking { aspect, tip }))
}

fn label(case: &Rocking) -> String {
    format!("h/b={} tipped {}α", case.aspect, case.tip)
}

/// When the first impact comes, against the rigid block's equation of motion.
pub fn impact_family() -> Family {
    Family::of(
        "rocking: 1st impact",
        "a block tipped on its edge reaches upright when (4/3)mR²θ̈ = −mgR sin(α − θ) says",
        Unit::Relative,
        MAX_IMPACT_TIME_ERROR,
        members(),
        label,
        |case, knobs| {
            let rocked = rock(case, knobs);
            let answer = case.first_impact_s() as f32;
            Outcome {
                error: (rocked.first_impact_s / answer - 1.0).abs(),
                ms_per_step: rocked.ms_per_step,
                detail: format!(
                    "upright at {:.4} s, the rigid block at {answer:.4} s",
                    rocked.first_impact_s
                ),
            }
        },
    )
}

/// How far the block rocks back after the first impact, against Housner's rigid impact.
pub fn rebound_family() -> Family {
    Family::of(
        "rocking: rebound",
        "after the impact it rocks back as far as Housner's r = 1 − 1.5 sin²α leaves it energy for",
        Unit::Relative,
        MAX_REBOUND_ERROR,
        members(),
        label,
        |case, knobs| {
            let rocked = rock(case, knobs);
            let answer = case.rebound_rad();
            Outcome {
                error: (rocked.rebound_rad / answer - 1.0).abs(),
                ms_per_step: rocked.ms_per_step,
                detail: format!(
                    "rocked back {:.4} rad, the rigid block {answer:.4} rad (tipped {:.4})",
                    rocked.rebound_rad,
                    case.tip * case.critical()
                ),
            }
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Runge–Kutta answer of a slender block agrees with the linear solution's
    /// acosh(1/(1 − θ₀/α))/p, which it should approach as α → 0 (h/b = 12: within 0.2 %).
    #[test]
    fn the_rigid_answer_of_a_slender_block_is_nearly_the_linear_one() {
        let case = Rocking {
            aspect: 12.0,
            tip: 0.5,
        };
        let radius = f64::from(HALF_WIDTH).hypot(f64::from(case.half_height()));
        let p = (3.0 * gravity() / (4.0 * radius)).sqrt();
        let linear = (1.0 / (1.0 - 0.5f64)).acosh() / p;
        let exact = case.first_impact_s();
        assert!(
            (exact / linear - 1.0).abs() < 0.002,
            "{exact} against {linear}"
        );
    }

    /// The rebound keeps r² of the energy: r = 1 − 1.5·sin²α is just under 1 for a slender block,
    /// so it rocks back nearly as far as it was tipped, and less for a stocky one.
    #[test]
    fn a_stocky_block_keeps_less_of_its_rocking_than_a_slender_one() {
        let [stocky, slender] = [6.0, 12.0].map(|aspect| {
            let case = Rocking { aspect, tip: 0.5 };
            case.rebound_rad() / (case.tip * case.critical())
        });
        assert!(stocky < slender && slender < 1.0, "{stocky} {slender}");
        assert!(slender > 0.95, "{slender}");
    }
}
