//! Stage 3b, the feed-forward load (`Settings::preload`, on by default): the contact forces statics
//! give each support when a step begins, so that the solver starts from them instead of finding them
//! again, sub-step by sub-step, from last step's. An island that stays still keeps them from step
//! to step instead of having them found again ([`reuse`]).
//!
//! **Normal.** The soft step's row is Δλ = −m_eff·s_m·(v_n + b) − s_i·λ (Catto, "Solver2D: soft
//! step", 2024): the leak −s_i·λ relaxes λ towards the spring force k·(depth − slop), so a contact
//! carrying the load L at rest sits at depth − slop = L/(m_eff·ω²·h) — 0.55 mm per box above it at
//! the defaults, 16.5 mm at the bottom of a column of 30. With a preload λ₀ the leak acts on λ − λ₀
//! instead: the rest point is λ = λ₀ at depth = slop, so a contact whose preload is its true static
//! load does not sink at all, and the spring only answers the residual. λ₀ is found feed-forward,
//! top down over the contact graph's layers: each body hands its weight (and applied forces) plus
//! what rests on it to its supports, the vertical part scaled by the normal's cosine, shared among
//! them by statics ([`split_by_statics`]: the least shares that carry the load and balance its
//! moment about where it acts, its own weight at its centre and what rests on it at those
//! contacts). The warm start is rescaled to λ₀. The spring itself is preloaded with λ₀ less the top
//! body's own weight, shared evenly among the points, where the load is indeterminate (see
//! "Determinate loads"): preloaded with all of λ₀, it rested at the slop, where the row's law
//! changes, and a box whose side unloaded as it was pushed lost its stiffness there (a pushed stack
//! of ten pitched and swayed). A determinate support is preloaded with all of λ₀, and its spring is
//! centred where it touches, not at the band's edge (`wide_contacts::velocity`,
//! `Settings::touching_spring`), so its rest is where it touches and a contact knocked into the band
//! or past it comes back to it (short of the top body's weight, a knocked contact rested at the slop
//! plus that weight's spring depth: ten woken 2 cm plates ended 9 mm lower; pushed back only inside
//! the band, by a law that vanished at its edge, they came to rest tilted on it, 2.4 mm lower;
//! `tests/physics/rest.rs`).
//!
//! **Friction.** Gauss–Seidel finds a new friction slowly: pushed at its centre, a box's friction
//! row stops the contact point by turning the box (a unit box's friction at its base sees 0.4 of
//! its mass), the normal rows then take the turn back and the slip with it, and the floor under a
//! pushed stack of ten gave 61 % of its Coulomb limit in the first sub-step of the push: the stack
//! ran 4 % ahead of ½·a·t² for good, and the bottom box 10 to 13 %. So the statics go on, bottom up
//! over the layers: each support's top body (with what rests on it) follows its bottom body's
//! predicted motion, which takes a friction of its mass times that motion's change less the
//! along-surface part of its load, within the Coulomb limit under λ₀; where it slides, last step's
//! kinetic friction acts instead; what that leaves of the load moves the top body. A push on the
//! bottom of a column that overcomes the floor's friction is carried up the column at once, as a
//! rigid column would take it. A support that was sticking takes the change in that friction since
//! last step (kept in the contact, `fed_tangent`) as a change of its warm start: a push begun or
//! ended, a load set down on it. And since friction acts at a patch's centroid, the moment of what
//! the patch holds up (loads and applied torques, less the forces of their predicted motion) is
//! the points' pressure's to carry: a body on one determinate support starts every step with its
//! preload spread over that patch's points to balance it (a mass-ratio contact, which is not
//! preloaded, only when its friction was fed; elsewhere last step's spread, which the solver
//! balanced, is kept). Fed the friction without the moment, the stack's boxes were kicked
//! into a turn and the column leaned further than before. With both, the pushed stack moves as one
//! body, within 0.4 % of ½·a·t² at every box (measured 2026-11-27).
//!
//! Not preloaded (they keep the plain leak): a contact that carried nothing last step and may close
//! faster than the restitution threshold by the step's end (an impact: restitution owns it; judged
//! on the approach at the step's start alone, a ball that would arrive at 1.11 m/s, 0.95 m/s a step
//! before, was preloaded as if resting and did not bounce); a support whose chain of supports does
//! not reach a static body (a pile falling together carries nothing: preloaded, the light box of
//! Galileo's cannon rode down on its load and rose 11 % too high); overlaps deeper than the soft
//! range (rigid rows, the position pass owns them); and determinate contacts of mass-ratio-marked
//! bodies (the shock pass and extra sweeps own them: "Mass ratios" below) — which still hand their
//! top body's weight down, or the supports below would be preloaded short of their load and have
//! their warm start cut every step:
//! a stack under a light ball sank 3.5 mm. (Their friction is fed all the same: a light box pinned
//! under a heavy one holds its hand on it alone.) Nor is a support whose top body a joint holds a
//! support at all: the joint may hang that body's weight elsewhere or hang another's on it (a
//! ragdoll's shin on a stair's edge carrying three times its weight), loads that statics of
//! contacts alone cannot know. Preloaded with its own weight as a determinate support, such a body
//! rested on a spring that could not hold what the joint pressed on it: a 10 kg box welded above a
//! 1 kg foot never slept and jumped its foot 4 mm off the floor, and that ragdoll (a pose the
//! built-in scene reached with the touching tolerance's law changed, saved and reloaded) buzzed for
//! the whole minute and crept 104 mm. Left to the solver, the two sleep after half a second (the
//! weld's foot 1.75 mm deep, the soft row's give under eleven times its weight; the ragdoll within
//! 0.9 mm of where it lay), and piles of four ragdolls sleep where half of them were awake after a
//! minute (`Settings::statics_skip_jointed`; `tests/physics/joints.rs`,
//! `a_box_welded_above_a_light_foot_rests_on_it_and_sleeps_only_when_statics_skip_it`;
//! `tests/physics/ragdoll.rs`, `piles_of_ragdolls_sleep_only_when_statics_skip_their_parts`).
//! Bodies resting on a jointed body are supported as ever. A held body
//! (`World::hold_point`) is taken to pull as it did last step, at its held point: a hand holding a
//! box up takes its weight off the floor.
//!
//! **Determinate loads.** The statics find *a* set of contact forces that holds each body up; only
//! where the pile is statically determinate is it *the* set. A body that rests on one support,
//! touches nothing else and carries only such bodies (a column, a stack of plates, a box on a
//! ramp) has exactly one equilibrium: its support's warm start is set to λ₀ every step and its
//! friction fed. Where a body rests on several supports or is flush against neighbours (a
//! pyramid, bricks over joints, a crossed tower) equilibrium leaves the split open: the lever rule
//! picks one, the solver settles on another, and resetting the warm start to the lever rule's
//! every step kicked the pile every step, so that awake piles crept and fell (a touching 20-row
//! pyramid 71 mm in a minute at 4 sub-steps; a running-bond wall fell). There the lever rule's λ₀
//! is only the first guess of a new contact (one that carried nothing: starting from nothing, a
//! crossed tower of twenty layers fell through itself in its first steps); once the contact
//! carries a load the warm start is the solver's own, the spring still rests preloaded with λ₀
//! (so the pile does not sink under its load), and no friction is fed. Only touching contacts
//! support (a speculative one, apart by more than the slop, carries nothing: each of ten stacked
//! 2 cm plates took a share of its load on the plate two below and the stack squeezed out). And
//! only a pressed neighbour leaves a load open: a side contact counts where its bodies touch (a
//! point at zero separation or past it) or it pushed last step, not where they are apart inside
//! the slop. In the heap of boxes and balls a ball 0.8 mm beside the bottom box of a column made
//! the column's supports indeterminate, without the spring that brings a determinate support back
//! to touching; a 20 g ball dropped on its top dented the floor contact unevenly (1.1 mm at one
//! corner, 0.06 mm at the next) and it stayed so, the column leaning 1.5 mm at its top (the heap
//! woken at 4 sub-steps, `nudge bench rest`: 3 of 8 copies over 1 mm, now all within 0.004 mm;
//! `a_column_beside_a_ball_it_does_not_touch_comes_back_from_a_knock`). Kept awake a minute, the
//! pyramids and walls built resting now stand within micrometres at 2, 4 and 8 sub-steps, with
//! "New supports" below (`pyramids_and_walls_kept_awake_do_not_creep_or_fall`). A
//! determinate support's spring also acts inside the slop band, where no other row does
//! (`wide_contacts::velocity`), so a column knocked deeper into it settles back.
//!
//! **Load changes** (`Settings::feed_load_changes`). The solver's own warm start on an
//! indeterminate support knows nothing of a load set down on the pile since last step: a 20 g
//! ball landing on a crossed tower reached its lower layers one Gauss–Seidel sweep at a time, the
//! tower sagged into its springs and bounced, and woken so at 4 sub-steps it came to rest 0.9 to
//! 1.8 mm from where it slept. The lever rule is wrong about how such a pile shares its load, but
//! right enough about how the shares change when a load is set down or lifted off: so on a step
//! in which what rests on a support's top body changed, the support's warm start moves towards
//! its new λ₀ by at most the change in λ₀ since last step (kept in the contact, `fed_load`), in
//! the shares its points had, and the new load reaches every support under it at once, as on a
//! determinate one. At most the change, and only towards λ₀: added whole, whatever the support
//! already carried, the change made an 8 kg box on four balls, woken by the ball at 8 sub-steps,
//! roll 44 mm off them in one copy (four more rolled 46 to 68 mm); moved only towards λ₀, every
//! copy rests within 0.2 mm. Whether the load changed is judged on what the top body hands down with each body's load
//! split evenly among its supports, which moves only when a body comes to rest or leaves, a
//! support comes or goes, or a hand's pull changes; the lever rule's shares move with every
//! micrometre a pile stirs, and fed on every step they were noise: a wall kept awake as built
//! drifted 1.5 mm in a minute at 4 sub-steps, 0.7 mm without. On every other step nothing is fed,
//! and a pile at rest runs as it did without the rule. Not across a change of rule (a support that
//! was determinate last step, or carried nothing): there the two λ₀ answer different questions,
//! and ten 2 cm plates whose supports flicker between the two at 2 sub-steps, fed the difference,
//! sank 5 cm through each other when knocked. Woken, the crossed tower now rests 0.70 to 0.88 mm
//! from where it slept at 4 sub-steps (`nudge bench rest`'s eight copies, 2026-11-30;
//! `a_sleeping_crossed_tower_woken_by_a_small_ball_stands` and
//! `load_changes_are_fed_towards_the_statics_and_not_across_a_change_of_rule` in
//! `tests/physics/rest.rs`).
//!
//! **Moment changes** (`Settings::feed_moment_changes`). Where statics do not determine a support's
//! load, the spread of its warm start over its points is the solver's own, and nothing tells the
//! supports under a pile that leans that the moment they carry has changed: Gauss–Seidel carries
//! that news down one layer a pass. A wall leans out of its plane by micrometres, its lower joints'
//! pressure follows late, and the lean grows: kept awake at 4 sub-steps a wall of real bricks (12
//! courses, 78 cm high and 10 cm thick) fell within seconds, as did the bench's wall at 14 courses
//! and two flush columns of fourteen of its bricks (at 2 sub-steps, the bench's wall at 12, and the
//! touching pyramid drifted 91 mm). One column stands because its moments are set every step (a
//! body on one determinate support, above). The lever rule cannot say how such a pile shares its
//! moments, but it is right about how they change: a lean moves the moment every joint must carry
//! at once. So a support that is a level face (a patch of three points or more within
//! [`LEVEL_MIN_COS`] of level) takes, in its warm start, the change since last step in the moment
//! its patch must carry to hold up the loads that rest on it (kept in the contact, `fed_offset`),
//! added to the spread the solver left (`wide_contacts::build`). The loads alone: weights, applied
//! forces and torques, not the friction statics' predicted motion, which is a guess the solver
//! corrects and which a knock changes from step to step (fed with it, the bench's wall, woken by a
//! ball heavier than its bricks, passed the knock down its courses and shed bricks off its end: 5.2
//! to 246 mm from where it slept at 4 sub-steps over eight copies, against 3.5 to 12.4 mm without).
//! Not on a body resting off level: on a heap, whose boxes and balls rest at any angle, those
//! moments move with every micrometre it stirs, and fed as changes they rocked a heap of sixty
//! 8.5 mm (7 mm/s). Nor under a body resting off level on several supports: the lever rule's split
//! of its load among tilted supports moves as it stirs. One resting off level on a single support
//! (a ball on a wall) hands all its load down there, and the supports under it are fed with it:
//! while every body resting off level stopped the feed under it, the 20 g ball resting on one point
//! of a wall of real bricks took the whole wall under it off the feed, and woken so the wall leaned
//! as an unfed one does (2.4 mm from where it slept at 4 sub-steps, 11 mm in the worst of eight
//! copies; now 0.18 to 0.42 mm). The heap woken at 8 sub-steps rests within 1 mm in 14 of 20
//! copies, 17 before, and awake at 2 sub-steps in 5 of 16, 8 before (a heap at rest is chaotic, and
//! no rule tried holds it in every copy). Pinned by
//! `a_wall_of_real_bricks_kept_awake_stands_only_with_moment_changes_fed` and
//! `a_sleeping_wall_of_real_bricks_woken_by_a_small_ball_stands` (`tests/physics/rest.rs`).
//!
//! **New supports** (`Settings::balance_new_supports`). A support that carried nothing yet (a
//! pile as built, a box set down) has no spread of its own: its first warm start is the statics'
//! load, shared by its points, and on a level face it takes the whole moment its patch must carry,
//! as a change from an even spread (`offset_change`, the "Moment changes" path). Shared evenly,
//! every eccentrically loaded patch was kicked in the first step: the end brick of a wall of real
//! bricks, half under the one above, turned 7 mrad and sank 1.6 mm at one corner in its first
//! step at 2 sub-steps, the wall's other bricks rocked with it, and the wall kept awake fell within
//! two seconds (both walls, every copy of `nudge bench rest`; at 4 and 8 sub-steps they settled
//! leaning, 0.1 to 0.4 mm). Balanced, a pile built resting does not move when its first step
//! begins (`a_wall_built_at_two_sub_steps_stands_only_with_balanced_new_supports`, in
//! `tests/physics/rest.rs`). Its points then rest at zero separation, where rounding would flip
//! them between a speculative row and a resting one every step, did the rows not count a point
//! within rounding of touching as touching (`Settings::touching_tolerance`,
//! `wide_contacts::velocity`).
//!
//! **Blows** (`Settings::piles_carry_blows`, in [`blows`]). A body landing from above on a resting
//! pile, where the pile can carry the blow as it carries its weight (over the struck body's
//! supports, on level faces, within friction), is stopped by the pile as by the ground: for the step
//! it lands in, its contact's rows see the struck body as immovable. Passed down a layer a pass,
//! the blow of a 20 g ball sank the bench's running-bond wall into its slop band, 6 to 12 mm.
//!
//! **Mass ratios.** A support around a mass ratio (a contact of a mass-ratio-marked body, see
//! `solve::mass_ratio`) is preloaded only where statics do not determine its load. On a
//! determinate one (a heavy box on a light one) the shock pass and the extra sweeps own the load:
//! the spring, at the light body's effective mass, cannot carry it, and preloaded as well as
//! shocked, a 1000:1 box fell off its light one. Tried again (2026-12-02, the shock pass kept):
//! preloaded, a box up to 1000 times its light one's mass rests on it to the micrometre at 1 to 8
//! sub-steps (2 to 134 µm down as it is, `nudge bench corpus`'s heavy on light), but from 2000:1 at
//! 2 and 4 sub-steps (7000:1 at 8) the light box's tilt grows 2.2-fold a step once a point of its
//! face crosses the touching tolerance, and the heavy box falls off; so too with every other fix
//! off, with the points' shares even, and at 2 sub-steps with the tolerance ten or a hundred times
//! wider. The 10⁴:1 member, the family's only failure (0.15 mm), stays out of reach of both. On an
//! indeterminate one (a heavy box on four light
//! balls) the shock pass, pushing the upper body at each support in turn as if that one alone held
//! it, rocked the box and walked its balls out (0.3 m in a minute, still 0.65 m/s at its end);
//! there the springs, preloaded with the lever rule's split, hold it within a micrometre at 2, 4
//! and 8 sub-steps, and the shock pass skips them (`MassRatio::prepare_rows`).
//!
//! Columns kept awake leaned over (30 boxes 235 mm in a minute at 4 sub-steps) while the moment
//! balance below was applied only on the steps their friction's demand changed: on the others the
//! spring alone held the tilt, and a column whose rotational stiffness Σ m_eff·ω²·d² is below its
//! weight times its height buckles. Balanced on every step, columns of 10 to 50 stand within
//! 0.15 mm at 2, 4 and 8 sub-steps. The crossed tower, which still fell, and the wall, which
//! stirred at 3 mm/s, stand with friction held at anchors (`contact_solver`, "Friction anchors"),
//! which relax towards the friction these statics ask of determinate supports.
//!
//! An earlier version gave preloaded face patches a stiff tilt spring (a "plate law") to keep awake
//! columns from buckling; with the moments fed forward they stand without it, and it set an awake
//! pyramid rocking (0.24 m/s after 5 s).

mod blows;
pub(crate) mod reuse;

use crate::physics::narrow::contact::{Contact, FedLoad};
use crate::physics::prepare::constraint_order::NOT_IN_GRAPH;
use crate::physics::scratch::refill;
use crate::physics::settings::Settings;
use crate::physics::solve::point_drive::PointHold;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::solve::wide_contacts::StruckPile;
use crate::physics::world::Scratch;
use crate::physics::{Body, BodyId};
use blows::Blow;
use glam::{Mat3, Vec2, Vec3};

/// Cosine of the steepest contact normal (from vertical) through which a body counts as resting on
/// another: 45°.
///
/// A cut, and a body wedged across it rests on one side only as far as the statics know. Copy 15
/// of the heap (`bench::rest::perturbed`, measured 2026-12-01), kept awake at 2 sub-steps: a
/// 125 g box on two 65 g balls, through normals 42° and 47° from vertical, hands its weight down
/// the first ball alone; the second ball's floor contact carries 0.6 N it was not preloaded with
/// and rests at the slop's edge (0.8 to 1.1 mm deep), where the row's leak starts. The box buzzes
/// at about 17 Hz (2.5 mm/s) and creeps 0.5 mm/s for the whole minute (33 mm). Switching any
/// feed off changes nothing; switched to 4 sub-steps it stops within a second. Taken at 53° or
/// 60° instead, the heap at 2 sub-steps held in 10 and 13 of 16 copies (10 as it is): other
/// copies fail instead, so the cut stays where a body alone on such a slope would slide at any
/// usual friction.
pub(in crate::physics) const RESTING_MIN_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// Cosine of the steepest normal (from vertical) of a level face, on which the moment changes are
/// fed (see the module docs, "Moment changes"): about 5.7°. A pile built level stays within
/// milliradians of it; a heap's boxes lie at any angle.
const LEVEL_MIN_COS: f32 = 0.995;

/// `preload` of a constraint that supports nothing (not resting, or no gravity): the spring leaks to
/// zero as before.
pub(crate) const NO_PRELOAD: f32 = -1.0;

/// One constraint as the preload sees it: `top` rests on `bottom` (solver indices; `top == 0` when
/// it is not a support), through a normal at `cos` from vertical.
#[derive(Clone, Copy, Debug, Default)]
struct Support {
    bottom: u32,
    top: u32,
    cos: f32,
    /// Whether the contact takes its load as a preload. A support that does not (a mass-ratio
    /// contact, whose extra sweeps and shock pass own it) still hands its top body's weight down:
    /// the contacts below carry it either way, and a preload that left it out would be rescaling
    /// their warm start below their load every step, so the pile would sink step after step.
    preloaded: bool,
    /// The middle of the contact's points, where it carries its share.
    centroid: Vec3,
    /// The contact's normal (from A to B), and whether B is the top body.
    normal: Vec3,
    top_is_b: bool,
    /// Whether it is a face patch (three points or more) within [`LEVEL_MIN_COS`] of level: what
    /// the moment changes are fed on (see the module docs, "Moment changes").
    level_face: bool,
    /// From the contact, for the friction statics: the normal impulse it carried last step, its
    /// friction coefficient, its friction last step and the friction the statics asked of it then
    /// (both on B), so that pass reads the supports in order instead of the contacts at random.
    carried: f32,
    friction: f32,
    last_friction: Vec3,
    fed_friction: Vec3,
    /// From the contact, for the change feeds: the pressure offset and the load the statics gave
    /// it last step (see the module docs, "Moment changes" and "Load changes").
    last_offset: Option<Vec3>,
    last_load: Option<FedLoad>,
}

/// One body as the preload sees it (by solver index; the dummy's is all zero): what it hands down
/// and what the passes over its supports gather in it. One struct, not a vector per quantity, so
/// that a support's visit reads its two bodies' fields together.
#[derive(Clone, Copy, Debug, Default)]
struct BodyLoad {
    /// Its own weight (the vertical impulse it hands down), then with what rests on it, and the
    /// same with each body's weight shared evenly among its supports instead of by the lever rule.
    own_weight: f32,
    weight_above: f32,
    even_weight_above: f32,
    /// Its mass, then with what rests on it, kg.
    mass: f32,
    mass_above: f32,
    /// Its own load (gravity, applied forces and its hold's pull), then with what rests on it, N·s
    /// per sub-step.
    own_load: Vec3,
    load_above: Vec3,
    /// Its centre, its applied moment about it (torque and hold, N·m·s per sub-step), the moment
    /// of its loads (its own weight at its centre, what rests on it at the contacts it rests
    /// through; divided out when the body is reached) and where its supports carry it, relative
    /// to its centre.
    centre: Vec3,
    own_moment: Vec3,
    load_moment: Vec3,
    load_point: Vec3,
    /// The change of velocity per sub-step the friction statics predict for it, m/s; the force and
    /// moment (about its centre) its supports must supply to it and what rests on it; and the same
    /// for the loads alone, their predicted accelerations left out (see the module docs, "Moment
    /// changes").
    drift: Vec3,
    wrench_force: Vec3,
    wrench_moment: Vec3,
    load_wrench_force: Vec3,
    load_wrench_moment: Vec3,
    /// Its contacts that are not supports and can carry a load (neighbours pressed side by side,
    /// walls), and how many supports carry it, listed in `Statics::supports_list` from
    /// `first_support`.
    side_contacts: u32,
    supports: u32,
    first_support: u32,
    /// Whether a chain of supports carries it to a static body, and whether its load has been
    /// split among its supports this step.
    grounded: bool,
    split_done: bool,
    /// Whether its load, or that of something resting on it, includes a hold's pull, which is only
    /// known from last step; whether anything resting on it carries a load that statics do not
    /// determine.
    held_above: bool,
    indeterminate_above: bool,
    /// Whether it rests on other than level faces, and whether a body above it rests so on several
    /// supports (see the module docs, "Moment changes").
    off_level: bool,
    under_heap: bool,
}

impl BodyLoad {
    /// Its own weight, load and the moment of its weight, from what it was read with (and a
    /// hold's pull), before anything rests on it.
    fn settle(&mut self) {
        self.weight_above = self.weight_above.max(0.0);
        self.own_weight = self.weight_above;
        self.even_weight_above = self.weight_above;
        self.own_load = self.load_above;
        self.load_moment = self.centre * self.own_weight;
    }
}

/// The statics' results for one step, per constraint in solve order, and the buffers they are
/// worked out in (kept between steps so that a step allocates nothing).
#[derive(Debug, Default)]
pub(in crate::physics) struct Statics {
    /// Its feed-forward load, N·s per sub-step, or [`NO_PRELOAD`]: its normal warm start.
    pub(in crate::physics) preload: Vec<f32>,
    /// The part of that load its spring rests preloaded with: all of it where it is determinate,
    /// else the load less its top body's own weight.
    pub(in crate::physics) spring_preload: Vec<f32>,
    /// Its friction warm start on B, when it sticks and what the statics ask of it changed
    /// (`None`: last step's).
    pub(in crate::physics) tangent_warm: Vec<Option<Vec3>>,
    /// The static friction asked of it, on B (zero when it is not a support): kept in the contact
    /// for the next step's comparison.
    pub(in crate::physics) tangent_demand: Vec<Vec3>,
    /// Σ δᵢ·dᵢ its points' pressure must have to balance the moment it carries (see
    /// `wide_contacts::build`), for a body on one determinate support.
    pub(in crate::physics) pressure_offset: Vec<Option<Vec3>>,
    /// The change in that offset since last step, for the other supports of a pile of level faces
    /// (see the module docs, "Moment changes").
    pub(in crate::physics) offset_change: Vec<Option<Vec3>>,
    /// That offset as the next step will compare it, for those supports (kept in the contact).
    pub(in crate::physics) fed_offset: Vec<Option<Vec3>>,
    /// The change in its load since last step, N·s per sub-step, on a step in which what it
    /// carries changed and statics determine neither load (zero elsewhere): see the module docs,
    /// "Load changes".
    pub(in crate::physics) load_change: Vec<f32>,
    /// Its load as the next step will compare it, where statics do not determine it (kept in the
    /// contact).
    pub(in crate::physics) fed_load: Vec<Option<FedLoad>>,
    /// Whether statics determine its load: its top body rests on it alone, touches nothing else
    /// and carries only such bodies (see the module docs, "Determinate loads"). Only then is its
    /// warm start set to its preload and its friction fed.
    pub(in crate::physics) determinate: Vec<bool>,
    /// Which side, if any, is a pile that takes a body's landing as the ground would (see
    /// [`blows`]): its rows see that side as immovable this step.
    pub(in crate::physics) struck_pile: Vec<StruckPile>,
    /// The level faces' impacts on dynamic bodies this step, which [`blows`] judges, and the
    /// points it finds the struck body's support hull in.
    blows: Vec<Blow>,
    hull_points: Vec<Vec2>,
    hull: Vec<Vec2>,
    /// The walk down a pile under a blow: (body, the constraint it is loaded through) to visit,
    /// and the bodies whose supports it has followed.
    walk: Vec<(u32, u32)>,
    walked: Vec<bool>,
    walked_list: Vec<u32>,
    /// Per constraint: whether it is pressed (touching, and a point at zero separation or past it,
    /// or it pushed last step), who rests on whom through it, and its share of its top body's load.
    pressed: Vec<bool>,
    support: Vec<Support>,
    share: Vec<f32>,
    /// The supports whose chain reaches a static body, in layer order: the passes top down and
    /// bottom up walk these alone, not every constraint.
    layered: Vec<u32>,
    /// The supports whose bottom body was not known to be carried where the layers reached them.
    late: Vec<u32>,
    /// Per body (solver index).
    body: Vec<BodyLoad>,
    /// The bodies' supports, each body's in constraint order from its `first_support`, and a fill
    /// cursor per body.
    supports_list: Vec<u32>,
    supports_fill: Vec<u32>,
    /// Per constraint, whether its statics are found this step, not kept ([`reuse`]); per solver
    /// body, whether its island's are, whether it is quiet and slow enough to be still at the next
    /// step, its contacts, and its island.
    fresh: Vec<bool>,
    body_fresh: Vec<bool>,
    quiet: Vec<bool>,
    slow: Vec<bool>,
    contacts_of: Vec<u32>,
    island: Vec<u32>,
    island_fresh: Vec<bool>,
}

impl Scratch {
    /// Fills `statics` for this step's constraints (see [`Statics`]; every preload [`NO_PRELOAD`]
    /// when `Settings::preload` is off): the normal load top down through the contact graph's
    /// layers, a body's weight plus what rests on it shared by its supports by statics
    /// ([`split_by_statics`]); then the friction bottom up and the moments top down. `bodies` are
    /// the world's (for their centres and torques), `seen` where the statics last saw them, `holds`
    /// the step's holds (see `World::hold_point`), `h` the sub-step; found only for the islands
    /// that did not stay still, the others given what they kept ([`reuse`]). Kept out of line
    /// (once per step) so that profiles show its cost: 16.7 % of the spaced pyramid's instructions
    /// found every step, 8.4 % with reuse, 2.1 % of it telling the still islands (callgrind, 300
    /// steps, 2026-12-02).
    #[inline(never)]
    pub(in crate::physics) fn compute_preloads(
        &mut self,
        (contacts, bodies, seen): (&[Contact], &[Body], &[Option<reuse::SeenAt>]),
        holds: &[PointHold],
        settings: &Settings,
        h: f32,
    ) {
        let Scratch {
            statics: s,
            graph,
            solver,
            mass_ratio,
            holds: step_holds,
            jointed,
            ..
        } = self;
        let n_constraints = graph.links.len();
        s.clear_results(n_constraints);
        s.mark_fresh(reuse::StillInputs {
            contacts,
            constraint_of: &graph.constraint_of,
            links: &graph.links,
            solver_bodies: &solver.bodies,
            motions: &solver.motions,
            solver_index: &solver.index,
            bodies,
            seen,
            holds,
            jointed,
            marked: &mass_ratio.marked,
            settings,
        });
        if !s.any_fresh() {
            // Every island still: all kept (`reuse`).
            s.fill_kept(contacts, &graph.constraint_of);
            return;
        }
        // With no contact there is nothing to find (a chain swinging in the air): the per-body
        // passes below would only fill what no constraint reads.
        let Some(up) = (-settings.gravity)
            .try_normalize()
            .filter(|_| settings.preload && n_constraints > 0)
        else {
            return;
        };
        // Each body is settled as it is read, unless a hold adds to its load first.
        let held = !step_holds.impulses.is_empty();
        s.read_bodies(&solver.motions, bodies, h, up, !held);
        if held {
            s.add_holds(
                &step_holds.impulses,
                holds,
                &solver.index,
                &solver.motions,
                settings,
                up,
            );
        }
        s.read_contacts(
            contacts,
            &graph.constraint_of,
            &graph.links,
            &solver.bodies,
            &mass_ratio.marked,
            jointed,
            settings,
            up,
        );
        s.find_supports(&graph.layer_order, &graph.links);
        s.find_struck_piles(contacts, graph, up, settings.linear_slop);
        s.hand_down_loads(up, settings);
        s.feed_friction();
        s.balance_moments(settings.feed_moment_changes, settings.balance_new_supports);
        s.fill_kept(contacts, &graph.constraint_of);
    }
}

impl Statics {
    /// Every constraint's results as if it supported nothing: no preload, nothing fed.
    fn clear_results(&mut self, n_constraints: usize) {
        refill(&mut self.preload, n_constraints, NO_PRELOAD);
        refill(&mut self.spring_preload, n_constraints, NO_PRELOAD);
        refill(&mut self.tangent_warm, n_constraints, None);
        refill(&mut self.tangent_demand, n_constraints, Vec3::ZERO);
        refill(&mut self.pressure_offset, n_constraints, None);
        refill(&mut self.offset_change, n_constraints, None);
        refill(&mut self.fed_offset, n_constraints, None);
        refill(&mut self.load_change, n_constraints, 0.0);
        refill(&mut self.fed_load, n_constraints, None);
        refill(&mut self.determinate, n_constraints, false);
        refill(&mut self.struck_pile, n_constraints, StruckPile::Neither);
        self.blows.clear();
    }

    /// Per body: its weight (the vertical impulse it hands down), its mass, its whole load
    /// (gravity and the applied forces: a hand pressing a box down presses on its supports too),
    /// its centre and its applied moment about it, read from the world once (the dummy's are
    /// zero); what rests on it is added to the weight, mass and load top down.
    fn read_bodies(
        &mut self,
        motions: &[SolverMotion],
        bodies: &[Body],
        h: f32,
        up: Vec3,
        settle: bool,
    ) {
        self.body.clear();
        self.body.extend(motions.iter().map(|m| {
            let (weight, mass, load) = if m.inv_mass > 0.0 {
                (
                    -m.linear_accel.dot(up.into()) * h / m.inv_mass,
                    1.0 / m.inv_mass,
                    Vec3::from(m.linear_accel) * (h / m.inv_mass),
                )
            } else {
                (0.0, 0.0, Vec3::ZERO)
            };
            let (centre, torque) = bodies
                .get(m.body as usize)
                .map_or((Vec3::ZERO, Vec3::ZERO), |body| {
                    (body.pose.position, body.torque)
                });
            let mut body = BodyLoad {
                weight_above: weight,
                mass,
                mass_above: mass,
                load_above: load,
                centre,
                own_moment: torque * h,
                ..BodyLoad::default()
            };
            if settle {
                body.settle();
            }
            body
        }));
    }

    /// A hold's pull is solved in the sub-steps, so it is not known yet: a body held again this
    /// step is taken to pull as it did over the last one, at its held point (a hand that holds a
    /// box up takes its weight off the floor, one dragging it into the floor adds to it). Then
    /// every body is settled ([`BodyLoad::settle`]).
    fn add_holds(
        &mut self,
        hold_impulses: &[(BodyId, Vec3)],
        holds: &[PointHold],
        solver_index: &[u32],
        motions: &[SolverMotion],
        settings: &Settings,
        up: Vec3,
    ) {
        for &(body, impulse) in hold_impulses {
            let i = solver_index[body.index()] as usize;
            if let Some(hold) = holds
                .iter()
                .find(|hold| hold.body == body)
                .filter(|_| i != 0)
            {
                let per_substep = impulse / settings.substep_count() as f32;
                let held = &mut self.body[i];
                held.weight_above -= per_substep.dot(up);
                held.load_above += per_substep;
                let lever = motions[i].rotation * hold.anchor;
                held.own_moment += lever.cross(per_substep);
                held.held_above = true;
            }
        }
        self.body.iter_mut().for_each(BodyLoad::settle);
    }

    /// Each constraint's [`Support`] (or none) and whether it is pressed, from its contact.
    fn read_contacts(
        &mut self,
        contacts: &[Contact],
        constraint_of: &[u32],
        links: &[(u32, u32)],
        solver_bodies: &[SolverBody],
        marked: &[bool],
        jointed: &[bool],
        settings: &Settings,
        up: Vec3,
    ) {
        let jointed = |body: u32| super::held_by_joint(jointed, body);
        let impact_speed = settings.restitution_threshold;
        // A contact whose points are all apart by more than the slop (a speculative one, found
        // before its bodies meet) carries nothing: it is neither a support nor a side contact.
        let touching = |c: &Contact| {
            c.manifold
                .points()
                .iter()
                .any(|p| p.separation <= settings.linear_slop)
        };
        let carried = |c: &Contact| -> f32 {
            c.impulses.normal[..c.manifold.len]
                .iter()
                .map(|l| l.max(0.0))
                .sum()
        };
        // A contact that carried nothing (`warm`, its normal impulse last step) and may close
        // faster than restitution's threshold by the end of the step (gravity adds g·dt along the
        // normal).
        let impact = |c: &Contact, (a, b): (u32, u32), warm: f32| {
            warm == 0.0 && {
                let n = glam::Vec3A::from(c.manifold.normal);
                let closing = -n.dot(solver_bodies[b as usize].v - solver_bodies[a as usize].v);
                closing + settings.gravity.dot(n.into()).abs() * settings.dt > impact_speed
            }
        };
        // Deeper than the soft range (the deepest point, or zero, below its limit): rigid rows and
        // the position pass own it.
        let deep = |c: &Contact| {
            let deep_limit = c.deep_limit(settings.linear_slop);
            0.0 < deep_limit
                || c.manifold
                    .points()
                    .iter()
                    .any(|p| p.separation < deep_limit)
        };
        // A pile carries a blow as statics do its weight only while it rests (see `blows`).
        let at_rest = |body: &SolverBody| {
            body.v.length_squared() < settings.sleep_linear_threshold.powi(2)
                && body.w.length_squared() < settings.sleep_angular_threshold.powi(2)
        };
        let support_of = |c: &Contact, (a, b): (u32, u32)| -> Option<Support> {
            let tilt = c.manifold.normal.dot(up);
            // The normal points from A to B: B rests on A when it points up.
            let (bottom, top) = if tilt >= RESTING_MIN_COS && b != 0 {
                (a, b)
            } else if tilt <= -RESTING_MIN_COS && a != 0 {
                (b, a)
            } else {
                return None;
            };
            // What a body a joint holds presses on its supports is the joint's to say, not the
            // statics' (the module docs, "Not preloaded").
            let top_body = if top == b { c.b } else { c.a };
            if settings.statics_skip_jointed && jointed(top_body) {
                return None;
            }
            let cos = tilt.abs();
            // An impact is not a support: restitution owns it (and a blow may land on a pile:
            // `blows`).
            let warm = carried(c);
            if impact(c, (a, b), warm) || deep(c) {
                return None;
            }
            let marked = marked[a as usize] || marked[b as usize];
            let points = c.manifold.points();
            let centroid = points.iter().map(|p| p.point).sum::<Vec3>() / points.len() as f32;
            Some(Support {
                bottom,
                top,
                cos,
                preloaded: !marked,
                centroid,
                normal: c.manifold.normal,
                top_is_b: top == b,
                level_face: points.len() >= 3 && cos >= LEVEL_MIN_COS,
                carried: warm,
                friction: c.friction,
                last_friction: c.impulses.tangent,
                fed_friction: c.impulses.fed_tangent,
                last_offset: c.impulses.fed_offset,
                last_load: c.impulses.fed_load,
            })
        };
        // The contacts in the order they are stored (visited in solve order, each a cache miss in
        // a large pile: a third of the statics' time in a raining pit of 4,000 bodies), and all the
        // statics read of them, so that no pass below goes back to them.
        let n_constraints = links.len();
        refill(&mut self.support, n_constraints, Support::default());
        refill(&mut self.pressed, n_constraints, false);
        for (c, &i) in contacts.iter().zip(constraint_of) {
            // A still island's are kept (`reuse`): none of its contacts is read.
            if i == NOT_IN_GRAPH || !self.fresh[i as usize] {
                continue;
            }
            let i = i as usize;
            let touches = touching(c);
            self.pressed[i] = touches
                && (c.manifold.points().iter().any(|p| p.separation <= 0.0)
                    || c.impulses.normal[..c.manifold.len]
                        .iter()
                        .any(|&impulse| impulse > 0.0));
            if touches && let Some(support) = support_of(c, links[i]) {
                self.support[i] = support;
            } else if settings.piles_carry_blows
                && let Some(blow) = Blow::of(i as u32, c, links[i], up)
                && impact(c, links[i], carried(c))
                && !deep(c)
                && at_rest(&solver_bodies[blow.struck as usize])
            {
                self.blows.push(blow);
            }
        }
    }

    /// Which supports carry a load (listed in `layered`; the others are supports no longer), and
    /// per body its supports (in `supports_list`), its side contacts and whether it rests off
    /// level.
    fn find_supports(&mut self, layer_order: &[u32], links: &[(u32, u32)]) {
        let Statics {
            support,
            pressed,
            layered,
            late,
            body,
            supports_list,
            supports_fill,
            ..
        } = self;
        let (support, pressed, body) = (&mut support[..], &pressed[..], &mut body[..]);
        // A support that carries its load is counted for its top body's list (filled below in
        // constraint order).
        let count_support = |support: &Support, body: &mut [BodyLoad]| {
            let top = &mut body[support.top as usize];
            top.supports += 1;
            top.off_level |= !support.level_face;
        };
        // Only a pressed side contact leaves its bodies' loads open ("Determinate loads" above):
        // apart, even inside the slop, its rows only stop an approach (`wide_contacts::velocity`).
        let count_side = |i: usize, body: &mut [BodyLoad]| {
            if pressed[i] {
                let (a, b) = links[i];
                body[a as usize].side_contacts += 1;
                body[b as usize].side_contacts += 1;
            }
        };
        // Only a support whose chain reaches a static body carries its load (a pile in free fall
        // carries nothing): bottom up over the layers. One whose bottom body is not carried yet
        // where the layers reach it is judged once they are all walked (`late`).
        layered.clear();
        late.clear();
        for &i in layer_order {
            let s = &support[i as usize];
            let (bottom, top) = (s.bottom as usize, s.top as usize);
            if top == 0 {
                count_side(i as usize, body);
            } else if bottom == 0 || body[bottom].grounded {
                body[top].grounded = true;
                layered.push(i);
                count_support(s, body);
            } else {
                late.push(i);
            }
        }
        // A late support whose bottom body a support later in the layer order carried carries its
        // load too, in its place in the layer order, so the list is built again (rare: the layers
        // mostly go bottom up); the others support nothing.
        let mut missed = false;
        for &i in late.iter() {
            let s = &mut support[i as usize];
            if body[s.bottom as usize].grounded {
                count_support(s, body);
                missed = true;
            } else {
                *s = Support::default();
                count_side(i as usize, body);
            }
        }
        if missed {
            layered.clear();
            layered.extend(
                layer_order
                    .iter()
                    .copied()
                    .filter(|&i| support[i as usize].top != 0),
            );
        }
        let mut listed = 0;
        for body in &mut *body {
            body.first_support = listed;
            listed += body.supports;
        }
        refill(supports_list, listed as usize, 0);
        supports_fill.clear();
        supports_fill.extend(body.iter().map(|body| body.first_support));
        let (list, fill) = (&mut supports_list[..], &mut supports_fill[..]);
        for (i, support) in support.iter().enumerate() {
            if support.top != 0 {
                let slot = &mut fill[support.top as usize];
                list[*slot as usize] = i as u32;
                *slot += 1;
            }
        }
    }

    /// The normal load, top down over the layers: each body's weight plus what rests on it shared
    /// among its supports by statics ([`split_by_statics`]), each support's `preload`,
    /// `spring_preload` and whether it is `determinate`, and the load changes (`fed_load`,
    /// `load_change`).
    fn hand_down_loads(&mut self, up: Vec3, settings: &Settings) {
        let Statics {
            preload,
            spring_preload,
            load_change,
            fed_load,
            determinate: is_determinate,
            support,
            share: shares,
            layered,
            body,
            supports_list,
            ..
        } = self;
        let n = support.len();
        refill(shares, n, 0.0);
        // Slices, not the vectors, and the constraints' all of one length: a store into one vector
        // could be a store into another's length, as far as the compiler knows, and every index
        // would load it and check it again.
        let (support, shares, body) = (&support[..], &mut shares[..n], &mut body[..]);
        let (preload, spring_preload) = (&mut preload[..n], &mut spring_preload[..n]);
        let (load_change, fed_load) = (&mut load_change[..n], &mut fed_load[..n]);
        let is_determinate = &mut is_determinate[..n];
        let supports_list = &supports_list[..];
        let (u, w) = up.any_orthonormal_pair();
        for &i in layered.iter().rev() {
            let i = i as usize;
            let Support {
                bottom,
                top,
                cos,
                preloaded,
                centroid,
                last_load,
                ..
            } = support[i];
            let (t, b) = (top as usize, bottom as usize);
            let weight = body[t].weight_above;
            if !body[t].split_done {
                body[t].split_done = true;
                let first = body[t].first_support as usize;
                let list = &supports_list[first..first + body[t].supports as usize];
                let at = if weight > 0.0 {
                    body[t].load_moment / weight
                } else {
                    body[t].load_moment
                };
                split_by_statics(support, list, at, u, w, shares);
                // Where its supports carry it, relative to its centre: the mean of their centroids
                // by share (for the moments, `balance_moments`).
                let centre = body[t].centre;
                body[t].load_point = list
                    .iter()
                    .map(|&j| (support[j as usize].centroid - centre) * shares[j as usize])
                    .sum();
            }
            // This support's share of the weight: friction carries its part along the surface, the
            // normal impulse the rest (a box on a 30° ramp: W·cos 30°).
            let share = shares[i];
            // Top down, so everything resting on `t` has been judged already.
            let above = body[t];
            let determinate = !settings.determinate_preload
                || (above.supports == 1 && above.side_contacts == 0 && !above.indeterminate_above);
            is_determinate[i] = determinate;
            // Around a mass ratio only an indeterminate support is preloaded (see the module docs,
            // "Mass ratios").
            if preloaded || !determinate {
                let load = weight * share * cos;
                preload[i] = load;
                // The spring's share (see the module docs): all of the load where it is
                // determinate, less the top body's own weight elsewhere.
                let on_spring = if determinate {
                    weight
                } else {
                    weight - above.own_weight
                };
                spring_preload[i] = on_spring * share * cos;
                let now = (load >= 0.0 && !determinate).then_some(FedLoad {
                    preload: load,
                    carried: above.even_weight_above,
                });
                if let Some(change) = load_change_of(now, last_load, settings.feed_load_changes) {
                    load_change[i] = change;
                }
                fed_load[i] = now;
            }
            if b != 0 {
                let below = &mut body[b];
                below.indeterminate_above |= !determinate;
                below.held_above |= above.held_above;
                below.even_weight_above += above.even_weight_above / above.supports as f32;
                below.weight_above += weight * share;
                below.load_moment += centroid * (weight * share);
                below.load_above += above.load_above * share;
                below.mass_above += above.mass_above * share;
            }
        }
    }

    /// The friction statics, bottom up over the layers (see the module docs, "Friction"): fills
    /// `drift`, `tangent_demand` and, for the sticking supports whose demand changed, `tangent_warm`.
    fn feed_friction(&mut self) {
        let Statics {
            preload,
            tangent_warm,
            tangent_demand,
            determinate,
            support,
            share: shares,
            layered,
            body,
            ..
        } = self;
        // Slices of one length, as in `hand_down_loads`.
        let n = support.len();
        let (support, shares, body) = (&support[..], &shares[..n], &mut body[..]);
        let (preload, determinate) = (&preload[..n], &determinate[..n]);
        let (tangent_warm, tangent_demand) = (&mut tangent_warm[..n], &mut tangent_demand[..n]);
        // Each support's top body (and what rests on it) follows its bottom body's predicted motion
        // where it sticks, which takes a friction of its mass times that acceleration less the
        // along-surface part of its load, within the Coulomb limit under this step's load; where it
        // slides, last step's kinetic friction. What that leaves of the load accelerates the top
        // body: a push on the bottom of a column that overcomes the floor's friction is carried up
        // the column at once, as a rigid column would take it. A support that was sticking takes
        // the change in that friction since last step as a change of its warm start (a push begun
        // or ended, a load set down on it); a sliding one keeps its own.
        for &i in layered.iter() {
            let i = i as usize;
            let Support {
                bottom,
                top,
                normal,
                top_is_b,
                carried,
                friction: mu,
                last_friction: last,
                fed_friction: fed,
                ..
            } = support[i];
            let (t, b) = (top as usize, bottom as usize);
            let share = shares[i];
            let along = |v: Vec3| v - normal * v.dot(normal);
            let push = along(body[t].load_above * share);
            let mass = body[t].mass_above * share;
            let on_b = |on_top: Vec3| if top_is_b { on_top } else { -on_top };
            let sliding = carried > 0.0 && last.length() >= SLIDING_FRICTION * mu * carried;
            let load = if preload[i] >= 0.0 {
                preload[i]
            } else {
                carried
            };
            let holding = (along(body[b].drift) * mass - push).clamp_length_max(mu * load);
            let friction = if sliding { on_b(last) } else { holding };
            let above = &mut body[t];
            if above.mass_above > 0.0 {
                above.drift += (friction + push) / above.mass_above;
            }
            // The demand is what holding would take, sliding or not: a contact that comes to rest
            // then takes only what changed since, not the step from kinetic friction to none.
            let demand = on_b(holding);
            tangent_demand[i] = demand;
            if !sliding && demand != fed && determinate[i] {
                // Within the Coulomb limit: the warm start is applied before any row clamps it.
                let warm = last + demand - fed;
                tangent_warm[i] = Some(warm.clamp_length_max(mu * load));
            }
        }
    }

    /// The moments, top down over the layers (see the module docs, "Friction", "Moment changes"
    /// and "New supports"): fills `pressure_offset` for a body on one determinate support and, for
    /// the other supports on a pile of level faces, `offset_change` and `fed_offset` where
    /// `feed_changes`, and `offset_change` of the new ones where `balance_new`.
    fn balance_moments(&mut self, feed_changes: bool, balance_new: bool) {
        let Statics {
            tangent_warm,
            pressure_offset,
            offset_change,
            fed_offset,
            determinate,
            support,
            share: shares,
            layered,
            body,
            ..
        } = self;
        // Slices of one length, as in `hand_down_loads`.
        let n = support.len();
        let (support, shares, body) = (&support[..], &shares[..n], &mut body[..]);
        let (tangent_warm, determinate) = (&tangent_warm[..n], &determinate[..n]);
        let (pressure_offset, offset_change) = (&mut pressure_offset[..n], &mut offset_change[..n]);
        let fed_offset = &mut fed_offset[..n];
        // Each support's patch must carry, about its centroid, the moment of what it holds up
        // (their loads and applied moments, less their predicted accelerations' forces); friction
        // acts at the centroid, so the points' pressure carries all of it. A body on one
        // determinate support spreads that patch's warm start over its points to balance it every
        // step (elsewhere last step's spread, which the solver balanced, is kept). Moments are
        // taken about each body's own centre: about the world's origin they would be differences of
        // large numbers far from it. The moments fed as changes are those of the loads alone (see
        // the module docs, "Moment changes"): the same sums without the predicted accelerations'
        // forces.
        for body in &mut *body {
            body.wrench_force = body.drift * body.mass - body.own_load;
            body.wrench_moment = -body.own_moment;
            body.load_wrench_force = -body.own_load;
            body.load_wrench_moment = body.wrench_moment;
        }
        // Not fed: the supports of a body resting on anything but level faces (`off_level`,
        // marked with the supports), and those under a body that rests so on several supports (a
        // heap's; marked top down below). One resting off level on a single support (a ball on a
        // wall) hands all its load down there, and the supports under it are fed.
        for &i in layered.iter().rev() {
            let i = i as usize;
            let Support {
                bottom,
                top,
                preloaded,
                centroid,
                normal,
                top_is_b,
                carried,
                last_offset,
                ..
            } = support[i];
            let (t, b) = (top as usize, bottom as usize);
            let share = shares[i];
            // The top's supports carry its force where they are (at `load_point`, the mean of their
            // centroids by share) and the rest of its moment by the same shares.
            let above = body[t];
            let single_support = above.supports == 1;
            let load_point = above.load_point;
            let (whole_force, whole_moment) = (above.wrench_force, above.wrench_moment);
            let force = whole_force * share;
            let about_centroid = (whole_moment - load_point.cross(whole_force)) * share;
            let (load_force, load_moment) = (above.load_wrench_force, above.load_wrench_moment);
            let loads_about_centroid = (load_moment - load_point.cross(load_force)) * share;
            // A hold's pull is a guess from last step: balanced on it every step, a box grabbed
            // into the floor sank (`tests/physics/point_drive.rs`).
            let known = preloaded && !above.held_above;
            let into_top = if top_is_b { normal } else { -normal };
            if single_support && determinate[i] && (known || tangent_warm[i].is_some()) {
                pressure_offset[i] = Some(into_top.cross(about_centroid));
            } else if known && !above.off_level && !above.under_heap {
                let now = into_top.cross(loads_about_centroid);
                // A support that carried nothing yet starts from the whole of it (see the module
                // docs, "New supports"): the even spread it gets is changed by all of `now`.
                let new = balance_new && carried == 0.0;
                offset_change[i] = match last_offset {
                    Some(last) if feed_changes => Some(now - last),
                    None if new => Some(now),
                    _ => None,
                };
                if feed_changes {
                    fed_offset[i] = Some(now);
                }
            }
            if b != 0 {
                let below = &mut body[b];
                let lever = centroid - below.centre;
                below.wrench_force += force;
                below.wrench_moment += about_centroid + lever.cross(force);
                below.under_heap |= above.under_heap || (above.off_level && !single_support);
                let force = load_force * share;
                below.load_wrench_force += force;
                below.load_wrench_moment += loads_about_centroid + lever.cross(force);
            }
        }
    }
}

/// The load changes (see the module docs, "Load changes"): given an indeterminate support's load
/// as the next step will compare it (`now`, none where statics determine it) and as the contact
/// kept it from last step, its change since then on a step in which what it carries changed, where
/// `feed`.
fn load_change_of(now: Option<FedLoad>, last: Option<FedLoad>, feed: bool) -> Option<f32> {
    // Compared exactly: a pile whose supports and loads are unchanged hands down the same bits
    // (the same sums in the same order).
    match (now, last) {
        (Some(now), Some(last)) if feed && now.carried != last.carried => {
            Some(now.preload - last.preload)
        }
        _ => None,
    }
}

/// The fraction of its Coulomb limit, μ·Σλn, from which a contact's last friction counts as sliding.
/// The solver clamps a sliding contact's friction to the limit itself; one that sticks stays below
/// it (unless it was exactly at the verge of slipping, where either reading is right).
const SLIDING_FRICTION: f32 = 0.99;

/// Shares a body's vertical load, acting at `at`, among its supports `list` (indices into
/// `supports`), written into `share`: the smallest shares (in the least-squares sense) that carry
/// the whole load and balance its moment about both horizontal axes `u` and `w`, the lever rule
/// of statics. One support takes everything; two on a line balance the moment along it (the
/// moment across it, which they cannot take, is left as small as it can be); three or more, a
/// statically indeterminate body, share by the minimum-norm solution. A load outside what the
/// supports span would need a negative share: those are clamped to zero and the rest rescaled.
/// (Shared instead in proportion to last step's loads, the shares fed on themselves: a box pushed
/// in a pyramid drained the load off itself step after step until friction let go, 34 mm in 1 s.)
fn split_by_statics(
    supports: &[Support],
    list: &[u32],
    at: Vec3,
    u: Vec3,
    w: Vec3,
    share: &mut [f32],
) {
    if let [only] = list {
        share[*only as usize] = 1.0;
        return;
    }
    // Rows [1, x, z] per support, x and z its centroid's offset from `at` along u and w; the shares
    // are f = Aᵀ·y with (A·Aᵀ + εD)·y = e₁, D = diag(0, 1, 1): Σf = 1 exactly, the moments to ε.
    let offset = |i: u32| {
        let d = supports[i as usize].centroid - at;
        (d.dot(u), d.dot(w))
    };
    // A·Aᵀ is symmetric, [Σ1, Σx, Σz; Σx, Σx², Σxz; Σz, Σxz, Σz²]: its six sums, each in list order.
    let (mut n, mut sx, mut sz, mut sxx, mut sxz, mut szz) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for &i in list {
        let (x, z) = offset(i);
        n += 1.0;
        sx += x;
        sz += z;
        sxx += x * x;
        sxz += x * z;
        szz += z * z;
    }
    let epsilon = 1e-6 * (1.0 + sxx + szz);
    let m = Mat3::from_cols(
        Vec3::new(n, sx, sz),
        Vec3::new(sx, sxx + epsilon, sxz),
        Vec3::new(sz, sxz, szz + epsilon),
    );
    let y = m.inverse() * Vec3::X;
    let mut total = 0.0;
    for &i in list {
        let (x, z) = offset(i);
        let f = Vec3::new(1.0, x, z).dot(y);
        let f = if f.is_finite() { f.max(0.0) } else { 0.0 };
        share[i as usize] = f;
        total += f;
    }
    for i in list {
        share[*i as usize] = if total > 0.0 {
            share[*i as usize] / total
        } else {
            1.0 / list.len() as f32
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn support_at(x: f32, z: f32) -> Support {
        Support {
            top: 1,
            centroid: Vec3::new(x, 0.0, z),
            ..Support::default()
        }
    }

    fn shares(supports: &[Support], at: Vec3) -> Vec<f32> {
        let list: Vec<u32> = (0..supports.len() as u32).collect();
        let mut share = vec![0.0; supports.len()];
        split_by_statics(supports, &list, at, Vec3::X, Vec3::Z, &mut share);
        share
    }

    #[test]
    fn two_supports_share_a_load_by_the_lever_rule() {
        // A plank on supports 1 m left and 2 m right of its load: 2/3 and 1/3.
        let s = shares(&[support_at(-1.0, 0.0), support_at(2.0, 0.0)], Vec3::ZERO);
        assert!(
            (s[0] - 2.0 / 3.0).abs() < 1e-4 && (s[1] - 1.0 / 3.0).abs() < 1e-4,
            "{s:?}"
        );
    }

    #[test]
    fn a_load_over_the_middle_of_four_supports_is_shared_evenly_and_one_support_takes_it_all() {
        let square =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, z)| support_at(x, z));
        for s in shares(&square, Vec3::new(0.0, 3.0, 0.0)) {
            assert!((s - 0.25).abs() < 1e-4, "{s}");
        }
        assert_eq!(shares(&[support_at(5.0, 5.0)], Vec3::ZERO), vec![1.0]);
    }

    #[test]
    fn a_load_beyond_its_supports_rests_on_the_nearer_one() {
        // Past the right support the lever rule asks the left one to pull: it takes nothing.
        let s = shares(
            &[support_at(-1.0, 0.0), support_at(1.0, 0.0)],
            Vec3::new(3.0, 0.0, 0.0),
        );
        assert_eq!(s, vec![0.0, 1.0]);
    }
}
