//! Contact constraints: their mathematics (this page), the shock-propagation pass, and what both
//! share. The kernels that prepare and solve the rows, four manifolds at a time, are in
//! `wide_contacts`.
//!
//! # The contact row
//! For a point with anchors r_a = p − x_a, r_b = p − x_b (world, relative to the centres of mass — never
//! absolute positions, so a stack at x = 5000 m solves like one at the origin) and normal n (A → B), the
//! relative normal velocity is
//!
//!   v_n = n · (v_b + ω_b × r_b − v_a − ω_a × r_a) = n·(v_b − v_a) + ω_b·(r_b × n) − ω_a·(r_a × n),
//!
//! so the Jacobian is J = [−nᵀ, −(r_a × n)ᵀ, nᵀ, (r_b × n)ᵀ] and the effective mass m = 1 / (J M⁻¹ Jᵀ) with
//!
//!   J M⁻¹ Jᵀ = 1/m_a + 1/m_b + (r_a × n)·I_a⁻¹(r_a × n) + (r_b × n)·I_b⁻¹(r_b × n).
//!
//! Friction acts on the manifold as a whole (as in Bepu and PhysX "patch friction"), not per point: two
//! tangent rows t₁, t₂ at the centroid c of the points (the same formulas with c for r and t for n) and a
//! twist row about n with J = [0, −nᵀ, 0, nᵀ], J M⁻¹ Jᵀ = n·I_a⁻¹n + n·I_b⁻¹n. Three friction rows instead
//! of eight for a face contact, and the friction force is exactly Coulomb for a sliding face (the
//! 30° ramp slides within 0.5 % of ½g(sin30° − μcos30°)t²); a one-point manifold (a ball) gets plain point
//! friction, so rolling is exact.
//!
//! # Sequential impulses (Catto, GDC 2006/2014; Box2D v3 `contact_solver.c`)
//! Each row keeps its accumulated impulse λ and clamps the *total*, not the increment: λ_n ≥ 0 per point;
//! the friction pair (λ₁, λ₂) inside the circle of radius μ·Σλ_n (a round friction cone, no pyramid
//! bias); the twist impulse within ±μ·Σλ_n·ρ, ρ the mean distance from the centre of the contact patch
//! to its points (`collide::patch`: 0.3826·a for a square face of side a, not the corners' 0.7071·a).
//! Normal impulses are warm-started from last step by feature id, friction and twist by manifold.
//!
//! # The spread row (why a symmetric stack does not walk)
//! The normal rows of a face contact are redundant: four coplanar points constrain three degrees of
//! freedom (approach along n and tilt about two axes), so J M⁻¹ Jᵀ has rank 3 and one sweep of
//! point-by-point Gauss–Seidel leaves an order-dependent residual. In the first sub-step of a stack
//! released in exact contact every point approaches at g·h; point 0 takes nearly all of it, the others
//! what is left, and the net impulse tilts the box. Friction at the centroid (correctly) turns the tilt
//! into a horizontal impulse, the rocking never fully dies under warm starting, and a load that changes
//! between the rocking phases ratchets it into a walk: a ten-box stack moved 15.4 mm sideways in its
//! first half second (alternating the point order per step halved that; order alone is not the fix).
//! So each manifold's sweep starts with one scalar *spread row*: an increment d of the total normal
//! impulse shared equally by the points (λ_i += d/len), against the mean residual of the point rows
//! (m_eff = 1 / mean_j(Σ_i K_ji / len)), clamped so no λ_i turns negative. Its fixed point is the point
//! rows' (it uses their soft residual), it carries the uniform part of the load without tilting
//! anything, and the point rows that follow correct only the (small) non-uniform rest. It is a two-level
//! (coarse + fine) Gauss–Seidel step, in lane arithmetic: one more multiply-add and two horizontal
//! reductions per manifold. What it buys (a ten-box stack's drift with it and without) is printed by
//! `nudge bench physics` in its table of the fixes;
//! `tests/physics/convergence_fixes.rs` pins it (`Settings::spread_row` switches it off).
//!
//! # Soft step (Catto, "Solver2D" 2024 / Box2D v3)
//! The current separation is s = s₀ + n·(Δp_b − Δp_a) + Δθ_b·(r_b × n) − Δθ_a·(r_a × n), updated from the
//! bodies' position deltas each sub-step (first order in rotation) instead of re-running collision. Then
//!   s > 0 (speculative):  bias = s / h, rigid — the bodies may close the gap exactly, never more;
//!   s ≤ 0, solve pass:    bias = β·min(s + slop, 0), soft (see `softness.rs`), while s + slop ≥ −d_soft
//!                         (5 cm); deeper the spring has bottomed out: bias = 0, rigid, and the overlap
//!                         is pushed out in position space at a bounded speed per body (`push_out`);
//!   s ≤ 0, relax pass:    bias = 0, rigid — removes the velocity the bias added, so push-out adds no
//!                         energy.
//! and Δλ = −m·mass_scale·(v_n + bias) − impulse_scale·λ.
//! Restitution runs once per step after the sub-steps, on points whose pre-solve approach speed exceeded
//! the threshold: target v_n = −e·v_n(pre-solve).
//!
//! # Friction anchors (why an awake pile stays where it stands)
//! A rigid friction row warm-started from last step is an integrator: λ_t keeps whatever it has
//! summed, and one Gauss–Seidel sweep a sub-step corrects it late. Where friction couples the layers
//! of a pile (a crossed "jenga" tower, whose blocks cross two below near their ends, so a sideways
//! friction at one end turns the block about the vertical) that lag feeds a sway that grows: kept
//! awake, a crossed tower of eleven layers or more doubled its sway every 0.15 s and fell within
//! seconds, at any contact stiffness, while the same tower without friction, or with ten sweeps a
//! sub-step, or without friction's warm start, stood. (Without the warm start, pyramids and walls
//! lost the friction that holds them and slid apart.) Friction's load must survive the step; its
//! integrator must not.
//!
//! So static friction holds a patch at an *anchor*, as the normal rows hold a contact at its
//! surface: the pair of tangent rows at the centroid is a soft spring (the contact's frequency and
//! damping ratio, `softness.rs`) on the patch's offset c from where it began to stick,
//!
//!   Δλ_t = −m_t·mass_scale·(v_t + bias_rate·c) − impulse_scale·(λ_t − λ_s),
//!
//! whose leak relaxes λ_t towards λ_s, the friction the preload's statics ask of a support whose
//! load they determine (`prepare::preload`: a box on a ramp, a column, a light box pinned under a
//! heavy one, whose friction a spring of the light box's stiffness could not carry), and towards
//! nothing elsewhere, where what friction carries is internal and the spring holds it. The twist
//! row is anchored the same way, on the turn about the normal (anchoring the pair alone, the apex of
//! a touching pyramid walked off along its twist-coupled axis). The offsets move with the bodies'
//! deltas (first order, as the separations do), are kept in the contact across steps
//! (`CachedImpulses::anchor`, `twist_anchor`), and an anchor moves to the patch whenever the pair
//! leaves the friction cone (it slides) or the offset passes the soft range (`push_out`), as the
//! normal spring bottoms out there. The relax pass keeps the rigid rows, so the springs' correction
//! adds no energy. Measured over a minute awake (`nudge bench rest`, 2026-11-28): the crossed tower
//! of twenty layers, which fell at 4 and 8 sub-steps (and, with its contacts no longer flickering,
//! still creeps 12 mm at 4), stands within 0.014 mm; the wall 3.1 → 0.16 mm at 4 and 0.47 → 0.09 mm
//! at 8; the touching pyramid 0.24 → 0.007 mm at 8 (at 4 its apex still rocks, 1.7 mm). Pinned by
//! `an_awake_crossed_tower_holds_still_only_with_friction_anchors` (`tests/physics/rest.rs`).
//!
//! Not anchored, each because the spring's stiffness, set by the contact's own effective mass, is
//! not what holds the pair there: a body a joint holds (its rows do not see the joint, whose tree
//! is solved before them: anchored, boxes riding a rope bridge kept it swinging); a body marked for
//! a mass ratio (the 10⁴:1 heavy box sank 35 cm: the shock pass and the extra sweeps own it); a
//! one-point contact (a rolling ball's contact point is a new material point every instant; the
//! rolling-resistance family lost a factor of ten); a patch deeper than the soft range (the position
//! pass pushes it apart, and an anchor held crowds of coincident boxes together). Nothing is
//! anchored with the preload off (`Settings::friction_anchors` needs it: the load the leak relaxes
//! towards).
//!
//! **How fast an anchor may be.** At the contacts' 30 Hz, a quarter of the sub-step rate at 2
//! sub-steps, the anchors between blocks made a crossed tower kept awake fall: its sway doubled
//! about every 0.5 s from 3 s on (87 mm at 10 s), and unanchored it stood a few seconds longer.
//! The rows' leak, a fraction 1/(1 + hω(2ζ + hω)) of λ a sub-step, gives the anchored friction a
//! memory of 0.29 s at 2 sub-steps against 0.07 s at 4, and a spring coupling the layers with
//! that lag feeds the sway. More biased iterations a sub-step do the same at 4 sub-steps: at 2
//! iterations, anchors at 30 Hz rock the spaced pyramid at 1.4–3.2 mm/s in three copies of eight.
//! Both fall where hω·√iterations passes about 1 (at 2 sub-steps 22.5 Hz fell in every copy, 18 Hz
//! held; at 4 × 2, 30 Hz is 1.1). So an anchor between two dynamic bodies is a spring of at most an
//! eighth of the sub-step rate over the square root of the iterations
//! ([`ANCHOR_MAX_STEP_FRACTION`]; the normal rows may have a quarter): 15 Hz at 2 sub-steps and at
//! 4 × 4, 21 Hz at 4 × 2, the contact's own at 4 and 8 sub-steps of one iteration. (At 4 × 4 the
//! law is loose: the pyramid's rocking measured there at 30 Hz, six copies of eight, was the
//! sub-steps' handedness, `Settings::alternate_sub_steps`; with sub-steps alternating, 30 Hz holds
//! all eight, and so does the cap's 15 Hz.) Measured on `nudge bench
//! rest`'s eight copies of each pile (`bench::rest::perturbed`, 2026-11-30), kept awake at 2
//! sub-steps the tower now stands a minute within 0.15 mm in all eight (it fell 11–13 m in all
//! eight) and the spaced pyramid holds in eight (seven); woken there the tower rests 1.7–7 mm from
//! where it slept (0.18–1.2 m). At 4 × 4 the spaced pyramid holds in all eight awake (two), within
//! 0.16 mm. What the slower anchors cost falls on piles that failed there before and still do: at
//! 2 sub-steps the touching pyramid drifts up to 91 mm awake (52), though five of eight copies now
//! hold woken (two), and the heap of boxes and balls holds 3 of 8 awake and 3 woken (5 and 2); at
//! 4 × 4 the heap woken holds 1 (4; its worst 62 → 5.6 mm), the touching pyramid 2 awake and 3
//! woken (3 and 2). The floor's anchors keep the normal rows' frequency: capped as well, the heap
//! lost more (2 and 2 at 2 sub-steps) and no pile gained. Pinned by
//! `an_awake_crossed_tower_stands_at_two_sub_steps_only_with_slower_anchors` and
//! `an_awake_pyramid_at_two_iterations_rests_only_with_slower_anchors` (`tests/physics/rest.rs`),
//! and 4 sub-steps and more stepping as before by
//! `anchors_are_slower_than_the_contacts_only_below_four_sub_steps_of_one_iteration` (`prepare`).
//!
//! What they cost: a spring that pulls a patch back to where it began to stick moves bodies, and
//! where a pile's rest is indeterminate (its contacts resting inside the slop band, where no normal
//! row restores a tilt) the pile moves with it. The mixed pile of `nudge bench rest`, settled for
//! 5 s at 4 sub-steps, creeps 3.7 mm over the next 25 s (at up to 2 mm/s) before it stops; with
//! the anchors switched off in the same settled state (`Settings::friction_anchors`) it gives
//! 0.6 mm at once, 0.7 mm by the minute's end, and moves under 0.01 mm/s. The springs are soft
//! because the tangent rows act at the patch's centroid and their effective mass includes the turn
//! about the tilt axis that the normal rows resist: 25 g for a 125 g box on another
//! (1/m = 8 + 8 + 12 + 12 kg⁻¹), about 0.9 N/mm at 30 Hz; in that pile a 0.6 N friction between
//! two such boxes held its anchor 0.8–1.1 mm out (measured 2026-11-29).
//!
//! # The symmetric relax (why an awake pile does not rock)
//! The relax pass ends every sub-step: its velocities are what the next sub-step integrates and
//! warm-starts from. One Gauss–Seidel sweep leaves them short of rigid, and what it leaves most is
//! the tilt of a face contact: a pile's contacts carry its moments as differences between their
//! points' impulses, and a change in those differences (a pile leaning a little further) reaches the
//! points of each manifold one at a time, in the order the pass visits them. Kept awake at the
//! default 4 sub-steps, the top two thirds of a touching 20-row pyramid rocked out of its plane on
//! the middle rows' contacts, with a period of about 3 s, and never settled (1.7 mm from where it
//! stood after a minute, 1.6 mm/s); a second whole relax sweep held it to 0.13 mm but cost a fifth
//! of the step, and a second *biased* sweep made it worse (6.6 mm): the relax pass's convergence is
//! what rest depends on.
//!
//! So the relax pass visits each manifold's points twice, in its order and then back (symmetric
//! Gauss–Seidel within the manifold; the normal rows only, which are what carries the tilt). The
//! second visit reads no body: a point's row from where the others now stand is its row against the
//! velocities before the manifold acted plus their changes through the couplings K_ij, which the
//! first visit already holds. It has no handedness of its own either (the stack that the alternating
//! order was added for stood in one order with it). Not around
//! a mass ratio: the shock pass and the extra sweeps own those contacts, and the squeezed light box
//! of the 3000:1 pile at 8 sub-steps, whose rocking is already near its stability limit, was set
//! rocking by it. Nor on a body a joint holds, whose velocities the tree's exact solve sets after
//! the contacts (with it, the pile of 20 ragdolls, which never comes to rest, cost 6 % more).
//!
//! What it buys at 4 sub-steps, over `nudge bench rest`'s four copies of each pile (2026-11-29):
//! kept awake a minute, the touching pyramid's median drift 1.53 → 0.15 mm (copies holding 2 → 3
//! of 4), the wall's copies holding 1 → 2; woken by the 20 g ball, the crossed tower 7.8 → 0.93 mm
//! (0 → 4). Worse: ten plates knocked by the ball end 2.4 mm from where they lay, not 1.6 (2 → 0),
//! and the heap of boxes and balls holds in fewer copies (awake 2 → 1 at 4 sub-steps, 3 → 2 at 8).
//! It costs the pyramid about 5 % of its step. Pinned by
//! `the_symmetric_relax_keeps_an_awake_touching_pyramid_from_rocking` and
//! `a_sleeping_crossed_tower_woken_by_a_small_ball_stands` (`tests/physics/rest.rs`).
//!
//! # The symmetric biased pass
//! The biased pass visits a manifold's points in one order, and at one iteration (the relax pass
//! being the symmetric one) every sub-step's biased pass visits backward: its residual sits on the
//! same side of every face, sub-step after sub-step. From 4 sub-steps up the biased passes go up
//! and down the pile's layers in turn (`wide_contacts::LayerOrder`), and a pile rests; below, each
//! sub-step's one biased pass must carry the load up from the ground, and a pile kept the lean.
//! So below 4 sub-steps, where the statics preload a manifold's supports (its load is known: the
//! biased pass only has to hold it), the biased pass visits its points twice, forward and back, as
//! the relax pass does: the same second visit, which reads no body, on the soft rows, whose own
//! change drops out through their leak as a rigid row's does.
//!
//! What it buys at 2 sub-steps, over `nudge bench rest`'s eight copies (2026-12-02): the
//! running-bond wall woken by the 20 g ball comes back within 0.6 mm in all eight (two held; median
//! 18 mm), the crossed tower kept awake holds in all eight (seven), and over 32 copies of the heap
//! of boxes and balls woken, 30 hold (24). What it costs: the rocking block rebounds 33 % short at
//! 2 sub-steps (32 %) and 61 % at 1 (47 %; `testing::corpus::rocking`). From 4 sub-steps up it
//! was not kept (tried 2026-12-01 and 2026-12-02): with the layers alternating it bought nothing
//! there, and over 32 heap copies kept awake at 4 sub-steps seven landed with a box wedged by
//! friction against the pit's wall that rocked its column at 3.6 mm/s (none without); the rocking
//! block rebounded 23.7 % short at 4 (22.7 %) and a sliding box crept 21 µm after it stopped (9).
//! Not on manifolds the statics leave alone: on every symmetric lane, the wall squeezed between
//! two boxes (`testing::corpus`) missed by 7 % at 4 sub-steps, not 0.2 %. Pinned by
//! `a_wall_woken_at_two_sub_steps_stands_only_with_a_symmetric_biased_pass`
//! (`tests/physics/rest.rs`).
//!
//! # The heavy-on-light problem and shock propagation
//! A soft contact is a spring of stiffness k = m_eff·ω² (see `softness.rs`), and the effective mass of a
//! contact between a 1000 kg box and a 1 kg box is ≈ 1 kg. Holding 9810 N then needs ≈ 0.28 m of
//! penetration, and Gauss–Seidel iterations barely move the heavy body anyway: this is why Rapier sinks.
//! Options considered:
//! - more iterations for islands with a large mass ratio: convergence of Gauss–Seidel is governed by the
//!   ratio, so 1000:1 needs thousands of iterations; the spring stiffness problem stays. (Used, capped,
//!   for moderate ratios: see "Mass-ratio sweeps" below.)
//! - an exact (direct, LCP/Cholesky) solve for small islands: exact, but a second solver with its own
//!   friction model and a cliff in cost and behaviour at the island-size cutoff.
//! - **shock propagation** (Guendelman, Bridson & Fedkiw 2003; Erleben 2005), chosen: each step the
//!   contact graph is layered by breadth-first distance from static bodies, constraints are solved in
//!   that order, and after the biased solve of every sub-step one extra pass visits the manifolds bottom
//!   up treating the lower body as infinitely heavy: if the points of a manifold still approach (on
//!   average) faster than the bias allows, the upper body alone is pushed along n by the missing amount,
//!   with a matching friction impulse so the push cannot make it slide. It is a one-sided velocity
//!   projection: where Gauss–Seidel converged it does nothing; where it did not (mass ratios, tall
//!   stacks) the stack becomes rigid from the ground up, so positions never integrate a sinking velocity.
//!   Cost: one cheap pass over the manifolds per sub-step, a BFS and a sort per step. Trade-offs: the
//!   shock impulses get no reaction, so momentum is not conserved by that residual (a heavy body dropped
//!   on a light one is stopped "by the ground"); layering follows the contact graph, not gravity, so a
//!   body hit from the side by a body deeper in the graph is treated as the lighter one; the push is
//!   translational (an angular push per corner made stacks lean and walk), so tilt is left to the
//!   regular rows; its friction on a moving lower body acts on linear velocity only (an angular
//!   response there fed the lower body's jitter into the upper one and tipped the 1000 kg box off).
//!
//! # Mass-ratio sweeps (moderate ratios: the shock pass's hidden load)
//! The shock pass gives the upper body what the rows did not, without recording it, so friction — bounded
//! by μ·Σλn of the rows — does not see that part of the load, here and at every support below (which
//! never feels its reaction). At rest the rows converge and the shock pass idles; the trouble is a
//! *changing* load on a light body under a heavy one. Push a 1 kg box with a 10 kg box on it: its floor
//! friction acts at its bottom face, tips it, the tipping drags the top box and shifts both contacts'
//! loads, and one Gauss–Seidel sweep corrects a light body squeezed by a heavy one only by a factor
//! ≈ m/(M + m) of the error (a row's effective mass is ≈ m, so it moves the heavy body m/M of the way
//! and the lower row undoes the push on the light one). For the first steps the regular λn at both
//! contacts fall up to a third short, the shock pass carries the rest, friction is too weak, and the pair
//! gains momentum it should not (pushed with 60 N: 0.344 m in 1 s where Coulomb says 0.275 m; with
//! 100 N the top box slid off). Measured options (default 4 sub-steps, 1 iteration, 60 N, distance in
//! 1 s):
//! - record the shock impulse in the contact's friction bound and propagate it down the layers to the
//!   supports' bounds: 0.306 m. The shock pass fires only in some sub-steps while the rows' deficit
//!   persists, and the dominant loss is the unconverged tipping, not the bound.
//! - record the shock impulse in λn so that it is warm-started (with its reaction) next sub-step: the top
//!   box was thrown up (the warm start replays an impulse that one row of effective mass m cannot take
//!   back from a body of mass M).
//! - a direct solve of small islands: exact, but a second solver and friction model (not tried here).
//! - more sweeps where the ratio is (chosen): every contact touching a body that has a contact with mass
//!   ratio ≥ `mass_ratio_threshold` gets `mass_ratio_iterations` extra biased sweeps after the regular
//!   ones and as many extra relax sweeps, in the usual order. PhysX does the same by hand (per-body
//!   minimum iteration counts, `PxRigidDynamic::setSolverIterationCounts`); here it is automatic and
//!   costs nothing in scenes of similar masses. With `contact::Contact::inherit_impulses` keeping the
//!   load across feature-id changes: 0 + 0 extra sweeps 0.308 m (and at 100 N the top box slides off),
//!   2 + 2: 0.303 m, 4 + 4: 0.287 m, 8 + 8 (default): 0.281 m, 16 + 16: 0.279 m; at 100 N 8 + 8 gives
//!   2.105 m for Coulomb's 2.093 m. The 1000:1 case also gains (`nudge bench physics`, its table
//!   of the fixes). The shock pass stays for the extreme ratios, where no affordable sweep count
//!   converges: on the soft step alone a 1 kg box under 1000 kg holds sideways pushes up to about
//!   400 N at 4 sub-steps (`testing::hard_case::pinned_push`), far below the floor's friction limit
//!   of 4,910 N; harder pushes tip it a little every sub-step until it pops out. Capping the shock
//!   pass so it never lifts the upper body, and solving friction before the normal rows, were tried:
//!   neither raised the threshold. The feed-forward statics (`prepare/preload.rs`, on by default)
//!   feed the pinned box its friction and lift that threshold close to Coulomb's: `nudge bench
//!   physics`, its `1 kg pinned, pushed` rows.
//!
//! # What the fixes cost
//! Every fix above and the statics together, on the awake touching pyramid of 20 rows: 1.98 G
//! instructions over 600 steps, against 1.77 G for the soft step alone (`Fixes::NONE`) and 2.8 G
//! for Rapier 0.36 (callgrind, 2026-12-03). In time, `rapier-bench --versus` times both against
//! Rapier in one run, on that pyramid and on rain(1000): 0.63 × and 0.51 × on the pyramid, the
//! median of 9 rounds (2026-12-03). The soft step alone is the floor of this solver's cost; the fixes add 12 %
//! to it on a resting pile, and they are what keeps such a pile at rest (`nudge bench physics`,
//! its table of the fixes).

use glam::{Vec3, Vec3A};

/// The highest frequency of a friction anchor between two dynamic bodies, as a fraction of the
/// sub-step rate, at one iteration a sub-step (divided by the square root of the iterations): see
/// the module docs, "How fast an anchor may be". Half the cap on every other spring
/// ([`MAX_STEP_FRACTION`]); at the default 4 sub-steps it is the contacts' 30 Hz.
pub(crate) const ANCHOR_MAX_STEP_FRACTION: f32 = MAX_STEP_FRACTION / 2.0;

use crate::physics::narrow::contact::Contact;
use crate::physics::solve::softness::MAX_STEP_FRACTION;
use crate::physics::solve::solver_body::SolverBody;

/// The friction rows of one manifold at the centroid of its points, as the lanes prepared them
/// (`WideContacts::friction_rows`): read back for the shock pass, never computed twice.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrictionRows {
    /// Unit normal A → B and two unit tangents, world.
    pub normal: Vec3A,
    pub tangents: [Vec3A; 2],
    /// Inverse masses, 1/kg (0 for the dummy).
    pub inv_mass_a: f32,
    pub inv_mass_b: f32,
    pub friction: f32,
    /// c × t and I⁻¹(c × t) for the two tangents at the centroid c, and their effective masses, kg.
    pub rt_a: [Vec3A; 2],
    pub rt_b: [Vec3A; 2],
    pub irt_a: [Vec3A; 2],
    pub irt_b: [Vec3A; 2],
    pub tangent_mass: [f32; 2],
}

/// What the shock pass needs of one manifold (see the module docs): built by [`prepare_shock`] for the
/// few constraints it visits.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShockRow {
    /// Solver body indices; 0 is the static dummy.
    pub a: u32,
    pub b: u32,
    /// The manifold's friction rows, from the lanes.
    pub rows: FrictionRows,
    /// Centroid of the points relative to each centre of mass, world, m.
    pub centroid_a: Vec3A,
    pub centroid_b: Vec3A,
    /// 1 or 0: whether the shock pass may move A (0 when A is the lower, "infinitely heavy" body).
    pub shock_scale_a: f32,
    pub shock_scale_b: f32,
    /// 1 / (scale_a / m_a + scale_b / m_b): translational mass of the shock pass, kg.
    pub shock_mass: f32,
    /// Mean of r × n over the points, per body, m: the mean normal velocity is
    /// n·(v_b − v_a) + ω_b·mean(r_b × n) − ω_a·mean(r_a × n) without visiting the points.
    pub rn_mean_a: Vec3A,
    pub rn_mean_b: Vec3A,
    /// Mean of the points' biases in the sub-step's last biased pass, m/s (copied from the lanes before
    /// each shock pass: positions do not move in between).
    pub bias_mean: f32,
}

/// What [`prepare_shock`] needs to know about one side of a contact.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Side {
    /// Solver index (0 = static dummy).
    pub index: u32,
    /// Centre of mass, world, m.
    pub position: Vec3,
    /// Shock-propagation layer: 0 for static bodies, BFS depth from them otherwise.
    pub level: u32,
}

/// Per-pass constants.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PassParams {
    /// 1 / sub-step, 1/s.
    pub inv_h: f32,
    /// Penetration left uncorrected, m.
    pub linear_slop: f32,
    /// Whether manifolds of two or more points start with the spread row (`Settings::spread_row`).
    pub spread_row: bool,
    /// Whether the relax pass visits a manifold's points twice, forward and back
    /// (`Settings::symmetric_relax`).
    pub symmetric_relax: bool,
    /// Whether the biased pass visits a preloaded manifold's points twice too: below
    /// `DOWN_MIN_SUBSTEPS`, with `Settings::symmetric_biased_pass`.
    pub symmetric_bias: bool,
}

#[inline]
fn inverse_or_zero(k: f32) -> f32 {
    if k > 0.0 { 1.0 / k } else { 0.0 }
}

/// Builds the shock row of `contact` between sides `sa` and `sb`, whose friction rows the lanes
/// prepared (`rows`).
pub(crate) fn prepare_shock(
    contact: &Contact,
    sa: &Side,
    sb: &Side,
    rows: FrictionRows,
) -> ShockRow {
    let n = rows.normal;
    let (shock_scale_a, shock_scale_b) = match sa.level.cmp(&sb.level) {
        std::cmp::Ordering::Less => (0.0, 1.0),
        std::cmp::Ordering::Greater => (1.0, 0.0),
        std::cmp::Ordering::Equal => (1.0, 1.0),
    };
    let x_a = Vec3A::from(sa.position);
    // B's anchors at the moment of impact relative to A (see `Manifold::approach`).
    let x_b = Vec3A::from(sb.position + contact.manifold.approach);
    let mut centroid = Vec3A::ZERO;
    let (mut rn_sum_a, mut rn_sum_b) = (Vec3A::ZERO, Vec3A::ZERO);
    for mp in contact.manifold.points() {
        let p = Vec3A::from(mp.point);
        centroid += p - x_a;
        rn_sum_a += (p - x_a).cross(n);
        rn_sum_b += (p - x_b).cross(n);
    }
    let inv_len = inverse_or_zero(contact.manifold.len as f32);
    let c_a = centroid * inv_len;
    ShockRow {
        a: sa.index,
        b: sb.index,
        rows,
        centroid_a: c_a,
        centroid_b: c_a + (x_a - x_b),
        shock_scale_a,
        shock_scale_b,
        shock_mass: inverse_or_zero(
            shock_scale_a * rows.inv_mass_a + shock_scale_b * rows.inv_mass_b,
        ),
        rn_mean_a: rn_sum_a * inv_len,
        rn_mean_b: rn_sum_b * inv_len,
        bias_mean: 0.0,
    }
}

/// min(a, b), likewise.
#[inline(always)]
fn fmin(a: f32, b: f32) -> f32 {
    if a < b { a } else { b }
}

/// Sum of the three components: one horizontal add where three dot products would take three.
#[inline(always)]
fn hsum(v: Vec3A) -> f32 {
    v.x + v.y + v.z
}

/// Reads the two bodies of a constraint (the dummy reads as zero).
#[inline(always)]
fn load(bodies: &[SolverBody], c: &ShockRow) -> (SolverBody, SolverBody) {
    (bodies[c.a as usize], bodies[c.b as usize])
}

/// Writes their velocities back (the only state the velocity passes change: half the stores of the
/// whole bodies). Writing the dummy is harmless: every impulse applied to it was scaled by its zero
/// inverse mass and inertia.
#[inline(always)]
fn store(bodies: &mut [SolverBody], c: &ShockRow, ba: SolverBody, bb: SolverBody) {
    let a = &mut bodies[c.a as usize];
    (a.v, a.w) = (ba.v, ba.w);
    let b = &mut bodies[c.b as usize];
    (b.v, b.w) = (bb.v, bb.w);
}

/// The shock-propagation pass (see the module docs), visiting rows in layer order (`order` lists
/// indices into `rows`).
pub(crate) fn shock_pass(rows: &[ShockRow], order: &[u32], bodies: &mut [SolverBody]) {
    for &i in order {
        let c = &rows[i as usize];
        let f = &c.rows;
        let (mut ba, mut bb) = load(bodies, c);
        let n = f.normal;
        // Translation only, for the manifold as a whole: the average approach of its points (beyond what
        // the bias allows) is removed by moving the upper body (both, by mass, at equal levels) along n.
        // Per-point angular pushes would tilt bodies one corner at a time and make stacks walk; the
        // tilt is left to the regular rows. The biases are those of the biased pass just run (same
        // positions), and the mean vn comes from the precomputed mean r × n.
        let vn_mean = hsum(n * (bb.v - ba.v) + bb.w * c.rn_mean_b - ba.w * c.rn_mean_a);
        let need = -(vn_mean + c.bias_mean);
        if need <= 0.0 {
            continue;
        }
        // Friction for the push itself, with a budget of μ times the push: a push along a slightly
        // tilted normal would otherwise make the upper body slide, and a leaning stack would push
        // itself over.
        let (move_a, move_b) = (
            c.shock_scale_a * f.inv_mass_a,
            c.shock_scale_b * f.inv_mass_b,
        );
        let normal_impulse = need * c.shock_mass;
        ba.v -= (move_a * normal_impulse) * n;
        bb.v += (move_b * normal_impulse) * n;
        let max_friction = f.friction * normal_impulse;
        if c.a == 0 || c.b == 0 {
            // On a static body: an ordinary rigid friction row pair at the centroid (its effective
            // masses involve the moving body only), with the push's budget. Angular response
            // included, so a sliding ball spins up exactly as with the regular rows.
            let [t1, t2] = f.tangents;
            let dv = bb.v - ba.v;
            let vt1 = hsum(t1 * dv + bb.w * f.rt_b[0] - ba.w * f.rt_a[0]);
            let vt2 = hsum(t2 * dv + bb.w * f.rt_b[1] - ba.w * f.rt_a[1]);
            let mut l1 = -f.tangent_mass[0] * vt1;
            let mut l2 = -f.tangent_mass[1] * vt2;
            let len2 = l1 * l1 + l2 * l2;
            if len2 > max_friction * max_friction {
                let scale = max_friction / len2.sqrt();
                l1 *= scale;
                l2 *= scale;
            }
            let impulse = l1 * t1 + l2 * t2;
            ba.v -= f.inv_mass_a * impulse;
            ba.w -= l1 * f.irt_a[0] + l2 * f.irt_a[1];
            bb.v += f.inv_mass_b * impulse;
            bb.w += l1 * f.irt_b[0] + l2 * f.irt_b[1];
        } else {
            // On a moving body: linear only (an angular response here would feed the lower body's
            // jitter into the upper one), never more than the slip at the centroid.
            let dv_linear = bb.v - ba.v;
            let dv_point = dv_linear + bb.w.cross(c.centroid_b) - ba.w.cross(c.centroid_a);
            let slip_linear = dv_linear - n.dot(dv_linear) * n;
            let slip_point = (dv_point - n.dot(dv_point) * n).length();
            let wanted = slip_linear.length();
            if wanted > 1e-9 {
                let magnitude = fmin(c.shock_mass * fmin(wanted, slip_point), max_friction);
                let impulse = -(magnitude / wanted) * slip_linear;
                ba.v -= move_a * impulse;
                bb.v += move_b * impulse;
            }
        }
        store(bodies, c, ba, bb);
    }
}
