//! Every knob of the simulation in one place, with units.
//!
//! The defaults are what every test and benchmark uses unless it says otherwise. Changing a default is a
//! behaviour change for the whole crate: the hard-case tests in `tests/physics/` pin them.

use glam::Vec3;

/// World and solver parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Gravitational acceleration, m/s², world frame.
    pub gravity: Vec3,
    /// Fixed step, s; finite and > 0.
    pub dt: f32,
    /// Sub-steps per step; ≥ 1 (0 is treated as 1). Each sub-step integrates velocities, warm starts,
    /// solves, integrates positions and relaxes (Box2D v3 "soft step").
    pub substeps: u32,
    /// Biased solver iterations per sub-step; ≥ 1 (0 is treated as 1).
    pub iterations: u32,
    /// Whether bodies at rest fall asleep.
    pub sleep: bool,
    /// Linear damping, 1/s: v decays as e^(−c·t) (implicit, v /= 1 + c·h per sub-step). 0 = none (the
    /// default: no hidden damping).
    pub linear_damping: f32,
    /// Angular damping, 1/s: ω decays as e^(−c·t). 0 = none (the default).
    pub angular_damping: f32,
    /// Stiffness of contacts as a natural frequency, Hz; > 0. Capped at a quarter of the sub-step rate.
    /// Contacts against static bodies use twice this (they have only one body to move).
    pub contact_hertz: f32,
    /// Damping ratio of contacts, dimensionless; ≥ 0 (10 = heavily over-damped: no bounce from push-out).
    pub contact_damping_ratio: f32,
    /// Fastest speed at which a body is pushed out of overlap, m/s; > 0. It holds per body, however
    /// many contacts push it: overlap deeper than the soft contact's range is pushed out in position
    /// space, each body moving at most this far per second (see `push_out`).
    pub max_push_out_velocity: f32,
    /// Approach speed below which restitution is ignored, m/s; ≥ 0 (resting contacts must not bounce).
    pub restitution_threshold: f32,
    /// Penetration tolerated without correction, m; ≥ 0. Keeps resting contacts from flickering. Every
    /// contact of a stack may rest this deep, so it is 1 mm rather than Box2D's 5 mm: ten boxes sink
    /// 1 cm at most.
    pub linear_slop: f32,
    /// Speculative distance added to every pair's contact margin, m; ≥ 0. The margin of a pair is
    /// `(|v_rel| + |ω_a|·R_a + |ω_b|·R_b)·dt + speculative_distance` (R = bounding radius), so fast bodies
    /// find their contacts before they touch.
    pub speculative_distance: f32,
    /// A manifold is reused instead of re-running the narrow phase while B has moved none of its
    /// points farther than this relative to A since the manifold was computed, m; ≥ 0 (0 = always
    /// collide), and neither body has moved five times as far in all (only as far, for a pair
    /// with a ball). Resting bodies, and piles swaying as one, then cost no narrow phase; a reused
    /// manifold is followed to where its bodies are (`narrow::contact::Contact::follow`), its
    /// separations off by at most this to first order. Keep it well under `linear_slop`. A face
    /// contact between bodies whose masses differ by `mass_ratio_threshold` is never reused (see
    /// `narrow::PairStep::reuse`).
    pub manifold_reuse_distance: f32,
    /// Linear speed under which a body counts as resting, m/s.
    pub sleep_linear_threshold: f32,
    /// Angular speed under which a body counts as resting, rad/s.
    pub sleep_angular_threshold: f32,
    /// Time every body of an island must rest before the island sleeps, s.
    pub time_to_sleep: f32,
    /// Largest linear speed a body may reach, m/s; a guard against blow-ups from absurd forces.
    pub max_linear_speed: f32,
    /// Largest angular speed a body may reach, rad/s (keeps one sub-step's rotation well below π).
    pub max_angular_speed: f32,
    /// Final depth-ordered pass per sub-step that treats the supporting body as infinitely heavy
    /// (shock propagation); see `contact_solver` for why. Off = plain soft-step Gauss–Seidel.
    pub shock_propagation: bool,
    /// A contact between two dynamic bodies whose masses differ by at least this factor (≥ 1) marks both
    /// bodies as "mass-ratio" bodies; every contact touching one gets the extra sweeps below. (A body
    /// carrying 16 times its mass or more in bodies resting on it is marked too, with them: a light
    /// plank under a crowd, where no single contact has a ratio.) Bodies that joints hold together
    /// count with the mass of all of them against any other body (`MassRatio::weigh_articulations`).
    pub mass_ratio_threshold: f32,
    /// Extra biased sweeps and extra relax sweeps per sub-step over the contacts touching a mass-ratio
    /// body (0 = off). Gauss–Seidel contracts the error of a light body squeezed by a heavy one by only
    /// ≈ M/(M + m) per sweep; see `contact_solver` for why they are spent there and only there.
    pub mass_ratio_iterations: u32,
    /// Each manifold of two or more points starts its sweep with the spread row, which carries the
    /// uniform part of the load without tilting anything (see `contact_solver`, "The spread row").
    /// Always on in use; switchable so that a test can show the case it exists for failing without it.
    pub spread_row: bool,
    /// Successive passes visit a manifold's points in opposite directions, so Gauss–Seidel has no
    /// handedness to whirl a stack with (see `wide_contacts::PointOrder`). Always on in use;
    /// switchable so that a test can show the case it exists for failing without it.
    pub alternate_point_order: bool,
    /// With an odd number of passes a sub-step (two or four iterations and the relax pass),
    /// successive sub-steps start in opposite directions, so that the alternating passes stay
    /// balanced (see `wide_contacts::PointOrder::before_substep`). Always on in use; switchable so
    /// that a test can show the case it exists for failing without it: off, every sub-step starts
    /// backward and visits backward once more than forward, and an awake heap of boxes and balls
    /// keeps stirring at 2 iterations and leans at 4
    /// (`even_iterations_stir_an_awake_heap_unless_sub_steps_alternate`, in `tests/physics/rest.rs`).
    pub alternate_sub_steps: bool,
    /// From 4 sub-steps up, the biased passes visit the contact graph's layers bottom-up and
    /// top-down in turn (the contacts around a mass ratio, of a jointed body or too deep for their
    /// soft range always bottom-up), so that Gauss–Seidel leaves its residual at neither end of a
    /// pile (see `wide_contacts::LayerOrder`). Always on in use; switchable so that a test can show
    /// the case it exists for failing without it: off, every pass goes bottom-up, and a heap of
    /// boxes and balls kept awake creeps (`alternating_layers_keep_an_awake_heap_still`, in
    /// `tests/physics/rest.rs`).
    pub alternate_layer_order: bool,
    /// The relax pass visits each manifold's points twice, forward and then back (symmetric
    /// Gauss–Seidel within the manifold), except around a mass ratio or a joint: one sweep
    /// converges the tilts a pile's contacts carry, whose lag kept awake piles rocking (see
    /// `contact_solver`, "The symmetric relax"). Always on in use; switchable so that a test can
    /// show the case it exists for failing without it.
    pub symmetric_relax: bool,
    /// Below 4 sub-steps, where the biased passes cannot alternate over the layers, the biased
    /// pass too visits twice, forward and back, the points of a manifold the relax pass visits so
    /// and whose supports the statics preload (see `contact_solver`, "The symmetric biased pass").
    /// Visited one way, its residual sat on one side of every face, and a running-bond wall woken
    /// by a small ball at 2 sub-steps crept 18 mm (`tests/physics/rest.rs`,
    /// `a_wall_woken_at_two_sub_steps_stands_only_with_a_symmetric_biased_pass`). Absent from
    /// recordings made before it existed: off, as it was.
    pub symmetric_biased_pass: bool,
    /// Each resting contact starts its step with the load statics give it (see `prepare::preload`):
    /// its normal impulse is the weight and applied forces of everything on it, so its soft spring
    /// rests at the slop instead of sinking by load/(m_eff·ω²) (pinned for a column of 30 boxes by
    /// `the_preload_keeps_a_thirty_box_column_from_sinking_into_itself`, in
    /// `tests/physics/convergence_fixes.rs`); its friction, where it sticks, takes a change in what
    /// rests on it at once (a push on the bottom of a column moves the whole column, not first the
    /// bottom box); and a body on one support spreads that support's pressure to balance the
    /// moment. On by default; off, the warm start is last step's impulses alone.
    pub preload: bool,
    /// A support whose load the statics determine (`prepare::preload`, "Determinate loads") is a
    /// spring centred where it touches, through the slop band and past it, so a knocked column or
    /// stack of plates comes back to where it stood (see `wide_contacts::velocity`). Always on in
    /// use; switchable so that a test can show the case it exists for failing without it: off,
    /// such a support is a row like any other, and any depth inside the band is a rest.
    pub touching_spring: bool,
    /// The preload sets a support's warm start to its load, and feeds its friction, only where
    /// statics determine that load (a body on one support, touching nothing else, carrying only
    /// such bodies); elsewhere only a new contact's warm start, and the spring rests preloaded
    /// (see `prepare::preload`, "Determinate loads"). Always on in use; switchable so that a test can show the case it
    /// exists for failing without it: off, every support is reset to the lever rule's share.
    pub determinate_preload: bool,
    /// Where statics do not determine a support's load, on a step in which what rests on it
    /// changed (a body set down or lifted off) its warm start moves towards the load they now ask
    /// of it by at most the change: the new load reaches every support under it at once, as on a
    /// determinate one (see `prepare::preload`, "Load changes"). Always on in use; switchable so that a test
    /// can show the case it exists for failing without it: off, such a support finds a new load by
    /// its sweeps alone.
    pub feed_load_changes: bool,
    /// Where statics do not determine a support's load, on a pile of level faces, each step its
    /// points' pressure takes the change since last step in the moment the statics ask its patch
    /// to carry (see `prepare::preload`, "Moment changes"): a lean shifts the moment at every joint
    /// of a wall at once, as it does on a column. Always on in use; switchable so that a test can
    /// show the case it exists for failing without it: off, a wall of real bricks kept awake leans
    /// out of its plane and falls once its landing has stirred it (as it did before
    /// `balance_new_supports`; `tests/physics/rest.rs`,
    /// `a_wall_of_real_bricks_kept_awake_stands_only_with_moment_changes_fed`).
    pub feed_moment_changes: bool,
    /// A support that carried nothing yet starts with its patch's points pressed to carry the
    /// moment the statics ask of it, not its load shared evenly (see `prepare::preload`, "New
    /// supports"): a pile built resting does not move when its first step begins. Always on in
    /// use; switchable so that a test can show the case it exists for failing without it: off, the
    /// end bricks of a wall built at 2 sub-steps are kicked over in its first step and the wall
    /// falls (`tests/physics/rest.rs`,
    /// `a_wall_built_at_two_sub_steps_stands_only_with_balanced_new_supports`).
    pub balance_new_supports: bool,
    /// A body landing on a resting pile from above, where the pile can carry the blow as it
    /// carries its weight (a level face, over the struck body's supports, within friction), is
    /// stopped by the pile as by the ground: its rows see the struck body as immovable for the step
    /// it lands in (see `prepare::preload::blows`). Always on in use; switchable so that a test can
    /// show the case it exists for failing without it: off, the blow is passed down the pile a
    /// layer a pass while its joints sink into their slop band, and the bench's running-bond wall,
    /// woken by a 20 g ball, settles 10 mm from where it slept at 4 sub-steps (`tests/physics/
    /// rest.rs`, `a_sleeping_running_bond_wall_woken_by_a_ball_stands_only_when_piles_carry_blows`).
    pub piles_carry_blows: bool,
    /// The statics give a body a joint holds no supports (see `prepare::preload`, "Not
    /// preloaded"): what it presses on them is the joint's to say, and the solver finds it. Always
    /// on in use; switchable so that a test can show the case it exists for failing without it:
    /// off, such a body's support is preloaded with its own weight, and a 10 kg box welded above a
    /// 1 kg foot never sleeps (`tests/physics/joints.rs`,
    /// `a_box_welded_above_a_light_foot_rests_on_it_and_sleeps_only_when_statics_skip_it`).
    pub statics_skip_jointed: bool,
    /// The rolling rows take the mass they have with the contact's friction held (see
    /// `wide_contacts::rolling`) only on a contact that is each of its dynamic bodies' only one: a
    /// ball's inertia about its contact point is its mass for rolling only while it can pivot
    /// there. Wedged between two contacts, that mass over-relaxed the rolling rows three and a half
    /// times, and a ball under a plank's end buzzed for good once the plank weighed five times the
    /// ball (`tests/physics/rolling.rs`,
    /// `a_ball_wedged_under_a_plank_sleeps_only_when_a_lone_contact_takes_the_held_mass`). Off:
    /// every contact takes it, as before.
    pub rolling_held_mass_alone: bool,
    /// A body joints pull on weighs in the step's rows with principal moments of inertia at least
    /// their geometric stiffness: h·Σ|λ|·|r| over its joint ends but the stiffest (λ a joint's
    /// pull a sub-step, r the end's arm; see `joint`, "Geometric stiffness"). A light link between
    /// two heavy pulls has a stiff turn whose frequency grows as √(tension/inertia); past two over
    /// the sub-step, the sub-steps amplify it, and a chain of 4 cm balls holding 100 times a link
    /// stretched 3.6 m at 2 sub-steps (2 cm balls came apart at the default 4). Off: the bodies'
    /// own inertia, as before (`tests/physics/joints.rs`,
    /// `a_light_chain_under_a_heavy_load_holds_at_low_sub_steps_only_with_geometric_stiffness`).
    pub joint_geometric_stiffness: bool,
    /// A tree's joints have their scalar rows (friction, motor, limits) solved after the tree's
    /// rows in each pass, not before: whatever a pass solves last holds at its end, and the tree
    /// closes its joints' whole error within the sub-step, so solved after the limits it drove a
    /// loaded arm past its limit every sub-step (see `joint`, "Order"). Off: before, as it was
    /// (`tests/physics/joints.rs`,
    /// `a_hinge_limit_holds_a_loaded_arm_at_one_sub_step_only_with_scalar_rows_last`).
    pub joint_scalar_rows_last: bool,
    /// The inertia floors take a joint's pull as at least the load its articulation can hang on
    /// it: the weight and applied forces of every body joints join to its ends
    /// (`joint::stiffness::ArticulationLoads`). Floored by last step's pull alone, light links
    /// stiffened a step after their load: a new chain of 1 cm balls under 100 times a link flew
    /// apart at the default 4 sub-steps from the turn its links took in its first step, and one of
    /// 4 cm balls whose end was suddenly pulled with 100 times a link's weight opened a joint 36 cm
    /// at 2. Off: last step's pull alone, as before (`tests/physics/joints.rs`,
    /// `light_links_stiffen_with_their_load_from_its_first_step_only_when_floors_take_it`).
    pub joint_pull_from_load: bool,
    /// Joints whose equality rows form trees (a chain, a ragdoll, a bridge between two anchors) are
    /// solved exactly, by Baraff's linear-time elimination (see `joint::tree`): a row's mass is
    /// the whole articulation's, so a chain holding a load a hundred times a link carries it
    /// without stretching. Off: every joint by Gauss–Seidel, with the soft rows of the joints
    /// outside a tree, as Box2D's joints and Rapier's impulse joints are solved; what that costs
    /// and saves is measured by `nudge bench mechanisms` (`tests/physics/joints.rs`,
    /// `a_chain_holds_a_load_a_hundred_times_a_link_only_with_the_exact_tree`).
    pub joint_tree: bool,
    /// The statics of an island that stays still are kept, not found again every step: its bodies
    /// within 10 nm of where the statics last saw them, nothing but gravity and contacts acting on
    /// them, its contacts and manifolds unchanged (see `prepare::preload::reuse`). What the
    /// statics feed is a change, so a still step feeds nothing and the next found step feeds what
    /// changed over both. A resting pyramid kept awake finds them on 7 of its first 120 steps. It
    /// stands as still either way. Off: found every step, as before (`tests/physics/rest.rs`,
    /// `a_still_pile_keeps_its_statics_and_stands_as_when_they_are_found_every_step`).
    pub statics_reuse: bool,
    /// A resting contact's point apart by at most this counts as touching, m: its row is the slop
    /// band's, not a speculative one's (see `wide_contacts::velocity`). A pile that rests where it
    /// was built has its points at zero separation, where the rounding of its poses (about a
    /// micrometre ten metres from the origin) flipped them between the two rows every step, and the
    /// flicker rocked a touching pyramid kept awake out of its plane (`tests/physics/rest.rs`,
    /// `a_touching_pyramid_built_and_kept_awake_stands_only_with_a_touching_tolerance`). Only
    /// supports the statics preload (an impact's rows are untouched); 0 switches it off.
    pub touching_tolerance: f32,
    /// Static friction holds a patch at an anchor: the friction row is a soft spring (the contact's
    /// stiffness and damping) pulling the patch back to where it began to stick, relaxing towards
    /// the preload's friction instead of keeping last step's (see `contact_solver`, "Friction
    /// anchors"). Off, friction is a rigid velocity row warm-started from last step, and awake piles
    /// whose friction couples their layers sway (a crossed tower of twenty layers creeps 12 mm in a
    /// minute: `an_awake_crossed_tower_holds_still_only_with_friction_anchors`, in
    /// `tests/physics/rest.rs`). Acts only with `preload` on (the friction it relaxes towards).
    pub friction_anchors: bool,
    /// A friction anchor between two dynamic bodies is a spring of at most an eighth of the
    /// sub-step rate over the square root of the iterations (`contact_solver::
    /// ANCHOR_MAX_STEP_FRACTION`, half the normal rows' cap), which at 4 sub-steps of one
    /// iteration and more is the contact's own frequency. Always on in use; switchable so that a
    /// test can show the case it exists for failing without it: off, anchors take the contact's
    /// frequency, and at 2 sub-steps a crossed tower of twenty layers kept awake and stirred by its
    /// landing (as before `balance_new_supports`) sways further every second until it falls, at 2
    /// iterations a pyramid rocks (`tests/physics/rest.rs`,
    /// `..._only_with_slower_anchors`).
    pub anchor_frequency_cap: bool,
    /// A contact's soft range (how deep its spring reaches before the position pass takes over,
    /// `push_out`) is at most a quarter of the depth at which its bodies' centres would cross, so
    /// thin bodies (2 cm plates) hit hard are pushed apart before the separating axis flips and
    /// drives them through each other (`push_out::soft_depth`). Always on in use; switchable so that
    /// a test can show the case it exists for failing without it: off, every contact's range is
    /// 5 cm.
    pub thin_soft_range: bool,
    /// A body held by a touching spring (`touching_spring`) pressed past where it touches, over its
    /// whole patch, is not resting, however slowly it moves: the spring is still pushing it back,
    /// and an island put to sleep then would keep the dent (see `sleep`, "Pressed springs"). Always
    /// on in use; switchable so that a test can show the case it exists for failing without it:
    /// off, a body rests on its speed alone.
    pub sleep_waits_for_springs: bool,
    /// A body whose speed has grown by a quarter of the linear sleep threshold from the slowest it
    /// moved since its rest began is not resting, however slowly it moves (see `sleep`, "Speeding up").
    /// Always on in use; switchable so that a test can show the case it exists for failing without
    /// it: off, a slender block let go leaning near its critical angle falls asleep leaning
    /// (`a_slender_block_let_go_leaning_rocks_back_instead_of_sleeping`, in
    /// `tests/physics/hard_cases.rs`).
    pub sleep_waits_while_speeding_up: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            dt: 1.0 / 60.0,
            substeps: 4,
            iterations: 1,
            sleep: true,
            linear_damping: 0.0,
            angular_damping: 0.0,
            contact_hertz: 30.0,
            contact_damping_ratio: 10.0,
            max_push_out_velocity: 3.0,
            restitution_threshold: 1.0,
            linear_slop: 0.001,
            speculative_distance: 0.02,
            manifold_reuse_distance: 0.0002,
            sleep_linear_threshold: 0.05,
            sleep_angular_threshold: 0.05,
            time_to_sleep: 0.5,
            max_linear_speed: 400.0,
            max_angular_speed: 200.0,
            shock_propagation: true,
            mass_ratio_threshold: 4.0,
            mass_ratio_iterations: 8,
            spread_row: true,
            alternate_point_order: true,
            alternate_sub_steps: true,
            alternate_layer_order: true,
            symmetric_relax: true,
            symmetric_biased_pass: true,
            preload: true,
            touching_spring: true,
            determinate_preload: true,
            feed_load_changes: true,
            feed_moment_changes: true,
            balance_new_supports: true,
            piles_carry_blows: true,
            statics_skip_jointed: true,
            rolling_held_mass_alone: true,
            joint_geometric_stiffness: true,
            joint_scalar_rows_last: true,
            joint_pull_from_load: true,
            joint_tree: true,
            statics_reuse: true,
            touching_tolerance: 5e-7,
            friction_anchors: true,
            anchor_frequency_cap: true,
            thin_soft_range: true,
            sleep_waits_for_springs: true,
            sleep_waits_while_speeding_up: true,
        }
    }
}

impl Settings {
    /// Sub-step count, at least 1.
    pub fn substep_count(&self) -> u32 {
        self.substeps.max(1)
    }

    /// Biased iteration count, at least 1.
    pub fn iteration_count(&self) -> u32 {
        self.iterations.max(1)
    }

    /// Whether two bodies of inverse masses `inv_a` and `inv_b` meet at a mass ratio: their masses
    /// differ by `mass_ratio_threshold` (at least 1) or more.
    pub(crate) fn is_mass_ratio(&self, inv_a: f32, inv_b: f32) -> bool {
        inv_a.max(inv_b) >= self.mass_ratio_threshold.max(1.0) * inv_a.min(inv_b)
    }
}
