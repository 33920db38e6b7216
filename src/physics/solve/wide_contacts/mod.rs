//! The contact solver's velocity kernels, four manifolds at a time.
//!
//! Constraints of one graph colour share no dynamic body, so solving them one after the other or all at
//! once gives the same result (Gauss–Seidel between colours, Jacobi within one). Box2D v3 uses that to
//! solve 4 or 8 constraints in SIMD lanes; here each lane holds one *manifold* of up to four points, and
//! the points of a manifold are visited in turn, as derived in [`crate::physics::solve::contact_solver`]: the spread
//! row, then the point rows through their couplings (in the relax pass forward and back: "The
//! symmetric relax"), then friction at the centroid and twist. Every
//! formula is the scalar row's, written lane-wise. (The solver used to run one manifold at a time; the
//! lanes changed only the order of a few floating-point sums, and 0.317 → 0.19 ms per pyramid step.)
//!
//! Manifolds are grouped by colour and by point count into [`ManifoldLanes<P, M>`] with P = 1
//! (spheres), 2 (edges) or 4 (faces; a three-point manifold gets an inert fourth point), so a ball's
//! contact does not pay for four points and a face's point chain is unrolled; by whether body A is
//! static, so a group of bodies resting on a floor reads and writes only its B side; and by softness
//! (one per kind of contact), kept once in a small table instead of in every group. A group is padded
//! with inert lanes (both bodies the static dummy, zero masses and impulses): they compute zeros and
//! write zeros back to the dummy. The per-pass cost of a lane group is one gather of its bodies into
//! [`Vec3x4`]s and one scatter back, against four times fewer arithmetic instructions than four
//! manifolds one by one.
//!
//! # Layout: what a pass streams
//!
//! A big pile's groups do not fit in the cache, and each sub-step passes over them three times (warm
//! start, biased solve, relax), so a group is split by reader, each part in its own vector, the parts
//! of group i at index i of each (one set of vectors per kind and per static/dynamic side A, so each
//! pass streams every vector it reads front to back):
//!
//! - [`ManifoldLanes`]: what every pass reads: side B, the normal and friction rows, the points' B-side
//!   rows and, for P > 1 only, the spread row, the couplings K_ij (i < j only) and the twist row
//!   ([`ManifoldLanes::multi`]); and the mean biases of the last biased pass, for the shock pass. The
//!   fields the warm start reads come first, so it touches fewer cache lines.
//! - [`SideLanes`]: side A's rows. Read by the passes only when body A is dynamic; a static-A group's
//!   side A (the dummy, its anchors and zero inverse masses) is read only once a step.
//! - [`ColdLanes`]: what only preparation, restitution and storing read: contact indices, restitution,
//!   point count, pre-solve approach speeds and the largest impulse increments (the latter tracked by
//!   the passes only in groups with restitution).
//!
//! Bytes a solve pass streams per group (A static / dynamic): one point 704 / 1072, two points
//! 1024 / 1488, four points 1520 / 2176, of which 16 per point are its current separation
//! ([`PointLanes::separation_now`], which spares the biased passes the bodies' position deltas). (All
//! in one struct, with side A and the cold fields, and without the current separations, they were
//! 1312, 1680 and 2416 whatever side A.) The warm start reads half to two thirds of them. Measured on
//! rain(4000) (~2300 groups, 2 MB L2): the warm start took ~20% less time, the solve passes ~3% less
//! (they are bound by their arithmetic more than by these bytes), the step ~2% less.
//!
//! The lanes are the only copy of a step's constraints: they are prepared four at a time too
//! ([`WideContacts::build`]), and restitution and storing the impulses for next step's warm start run on
//! them. Only the shock pass, which visits a few constraints in layer order, uses a scalar row
//! (`contact_solver::ShockRow`).

mod body_lanes;
mod build;
mod end_of_step;
mod impacts;
mod multi_rows;
mod rolling;
mod velocity;

use glam::{Vec3A, Vec4};

use crate::physics::Body;
use crate::physics::narrow::contact::Contact;
use crate::physics::solve::contact_solver::{FrictionRows, PassParams};
use crate::physics::solve::lanes::Vec3x4;
use crate::physics::solve::softness::ContactSoftness;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use build::prepare;
use end_of_step::store;
pub(crate) use impacts::ImpactParams;
pub(crate) use multi_rows::{MultiRow, MultiRows, multi_row_count};
use rolling::{FrictionCoupling, RollingLanes, prepare_rolling, store_rolling};
use velocity::{solve, warm_start};

/// Manifolds per lane group.
pub(crate) const LANES: usize = 4;

/// Point i of the four manifolds of a lane group: its impulse and what applying it to side B takes,
/// all the warm start reads of it (zero in lanes whose manifold has fewer points).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub(crate) struct ImpulseLanes {
    /// Accumulated normal impulse, N·s.
    pub normal_impulse: Vec4,
    /// I_B⁻¹(r_B × n), 1/(kg·m).
    pub irn_b: Vec3x4,
}

/// Point i of the four manifolds of a lane group: the rest of its row on side B (zero in lanes whose
/// manifold has fewer points).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub(crate) struct PointLanes {
    /// r_B × n, m.
    pub rn_b: Vec3x4,
    /// Separation at the start of the step, m.
    pub separation: Vec4,
    /// Separation at the bodies' positions in the current sub-step, m: `separation` moved with the
    /// bodies' deltas by the last relax pass (or prepared equal to it: the deltas start at zero). The
    /// positions move only between a sub-step's biased and relax passes, so the biased passes (and
    /// the impulse store after the last sub-step) read it instead of gathering the deltas to
    /// recompute the same number.
    pub separation_now: Vec4,
    /// Effective mass, kg.
    pub normal_mass: Vec4,
    /// 1/len (0 in the padding): the point's weight in the spread row and in the mean bias.
    pub mean_weight: Vec4,
    /// The normal impulse the step was warm-started with, N·s: the spring's preload.
    pub load: Vec4,
}

/// Four manifolds of one colour with at most `P` points each, in lanes: the part every velocity pass
/// reads (side A is in [`SideLanes`], the rest in [`ColdLanes`]).
///
/// `M` is the number of [`MultiRows`]: [`multi_row_count`]`(P)`.
///
/// In memory order, the fields up to `in_b` are all the warm start reads (it touches the fewest
/// cache lines that way); the solve reads them and the rest.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct ManifoldLanes<const P: usize, const M: usize> {
    /// Solver body index of side B per lane (0, the static dummy, in padding lanes).
    pub b: [u32; LANES],
    pub tangent_impulse: [Vec4; 2],
    pub twist_impulse: Vec4,
    /// Mean of the points' biases in the last biased pass, m/s (for the shock pass; written beside
    /// the impulses the passes write anyway).
    pub bias_mean: Vec4,
    pub impulses: [ImpulseLanes; P],
    pub normal: Vec3x4,
    pub tangents: [Vec3x4; 2],
    pub inv_mass_b: Vec4,
    /// I_B⁻¹(c_B × t) of both tangents at the centroid c, and I_B⁻¹n.
    pub irt_b: [Vec3x4; 2],
    pub in_b: Vec3x4,
    pub points: [PointLanes; P],
    pub friction: Vec4,
    /// c_B × t of both tangents.
    pub rt_b: [Vec3x4; 2],
    pub tangent_mass: [Vec4; 2],
    /// Friction's anchor (see `contact_solver`, "Friction anchors"): 1 in the lanes whose friction
    /// is anchored, else 0; the patch's offset from its anchor along both tangents at the step's
    /// start and at the bodies' positions in the current sub-step (moved by the relax pass), m; and
    /// the friction the statics expect of the patch, which the row relaxes towards, N·s per sub-step.
    pub anchored: Vec4,
    /// 1 in the lanes whose normal rows are springs centred where they touch, else 0: the supports
    /// whose load the statics determine (`prepare::preload`, `Settings::touching_spring`; see
    /// `velocity`).
    pub touching_spring: Vec4,
    /// How far apart a point may be and still rest touching, m: `Settings::touching_tolerance` in
    /// the lanes of preloaded supports, else 0 (see `velocity`).
    pub touching_tolerance: Vec4,
    /// Penetration past the slop the soft rows push out, m (`Contact::soft_depth`): deeper, a row
    /// is rigid and the position pass pushes the pair apart; also how far a friction anchor may
    /// trail its patch.
    pub soft_depth: Vec4,
    /// 1 in the lanes whose points the relax pass visits twice (see `velocity`), else 0: the
    /// manifolds of two or more points whose bodies are neither marked for a mass ratio nor
    /// jointed.
    pub symmetric: Vec4,
    pub anchor_start: [Vec4; 2],
    pub anchor_now: [Vec4; 2],
    pub tangent_load: [Vec4; 2],
    /// The twist row's anchor: B's turn about the normal from it, at the step's start and now, rad.
    pub twist_anchor_start: Vec4,
    pub twist_anchor_now: Vec4,
    /// The rows only a manifold of two or more points has: the spread row, the twist row and the
    /// couplings between the points (none for P = 1).
    pub multi: MultiRows<P, M>,
}

impl<const P: usize, const M: usize> ManifoldLanes<P, M> {
    /// The axes of the rolling rows (see `rolling`): both tangents, then the normal.
    #[inline(always)]
    pub fn rolling_axes(&self) -> [Vec3x4; 3] {
        [self.tangents[0], self.tangents[1], self.normal]
    }
}

impl<const P: usize, const M: usize> Default for ManifoldLanes<P, M> {
    fn default() -> Self {
        Self {
            b: [0; LANES],
            tangent_impulse: [Vec4::ZERO; 2],
            twist_impulse: Vec4::ZERO,
            bias_mean: Vec4::ZERO,
            impulses: [ImpulseLanes::default(); P],
            normal: Vec3x4::ZERO,
            tangents: [Vec3x4::ZERO; 2],
            inv_mass_b: Vec4::ZERO,
            irt_b: [Vec3x4::ZERO; 2],
            in_b: Vec3x4::ZERO,
            points: [PointLanes::default(); P],
            friction: Vec4::ZERO,
            rt_b: [Vec3x4::ZERO; 2],
            tangent_mass: [Vec4::ZERO; 2],
            anchored: Vec4::ZERO,
            touching_spring: Vec4::ZERO,
            touching_tolerance: Vec4::ZERO,
            soft_depth: Vec4::ZERO,
            symmetric: Vec4::ZERO,
            anchor_start: [Vec4::ZERO; 2],
            anchor_now: [Vec4::ZERO; 2],
            tangent_load: [Vec4::ZERO; 2],
            twist_anchor_start: Vec4::ZERO,
            twist_anchor_now: Vec4::ZERO,
            multi: MultiRows::ZERO,
        }
    }
}

/// Side A of a lane group: the A-side counterparts of [`ManifoldLanes`]' B-side rows (in memory order,
/// those the warm start reads first).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct SideLanes<const P: usize> {
    /// Solver body index of side A per lane (0 in padding lanes and static sides).
    pub a: [u32; LANES],
    pub inv_mass_a: Vec4,
    /// Per point I_A⁻¹(r_A × n); I_A⁻¹(c_A × t) of both tangents, and I_A⁻¹n.
    pub irn_a: [Vec3x4; P],
    pub irt_a: [Vec3x4; 2],
    pub in_a: Vec3x4,
    /// Per point r_A × n; c_A × t of both tangents.
    pub rn_a: [Vec3x4; P],
    pub rt_a: [Vec3x4; 2],
}

impl<const P: usize> Default for SideLanes<P> {
    fn default() -> Self {
        Self {
            a: [0; LANES],
            inv_mass_a: Vec4::ZERO,
            irn_a: [Vec3x4::ZERO; P],
            irt_a: [Vec3x4::ZERO; 2],
            in_a: Vec3x4::ZERO,
            rn_a: [Vec3x4::ZERO; P],
            rt_a: [Vec3x4::ZERO; 2],
        }
    }
}

/// What only preparation, restitution and storing the impulses read of a lane group.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ColdLanes<const P: usize> {
    /// Index of each lane's persistent contact, `u32::MAX` in padding lanes.
    pub contact: [u32; LANES],
    pub restitution: Vec4,
    /// Number of points (0 in padding lanes).
    pub count: Vec4,
    /// Per point: relative normal velocity before the solve, m/s (restitution's reference; left zero
    /// in groups where no lane has restitution), and the largest impulse increment this step, N·s
    /// (tracked only in groups with restitution, the only reader).
    pub relative_velocity: [Vec4; P],
    pub max_normal_impulse: [Vec4; P],
    /// Per point: the normal impulse delivered over the step so far, the sum of every sub-step's
    /// accumulated impulse, N·s (tracked only in groups with restitution: the impacts may take back
    /// at most this, see `impacts`).
    pub step_impulse: [Vec4; P],
}

impl<const P: usize> Default for ColdLanes<P> {
    fn default() -> Self {
        Self {
            contact: [u32::MAX; LANES],
            restitution: Vec4::ZERO,
            count: Vec4::ZERO,
            relative_velocity: [Vec4::ZERO; P],
            max_normal_impulse: [Vec4::ZERO; P],
            step_impulse: [Vec4::ZERO; P],
        }
    }
}

/// The lane groups of one kind and side A (static or not), the parts of group i at index i of each.
#[derive(Debug, Default)]
struct Groups<const P: usize, const M: usize> {
    hot: Vec<ManifoldLanes<P, M>>,
    side_a: Vec<SideLanes<P>>,
    cold: Vec<ColdLanes<P>>,
    /// One-point groups only: their rolling-resistance rows (`rolling`; empty for P > 1).
    rolling: Vec<RollingLanes>,
}

impl<const P: usize, const M: usize> Groups<P, M> {
    /// Holds `len` groups (their contents are overwritten by `prepare`).
    fn resize(&mut self, len: usize) {
        self.hot.resize_with(len, Default::default);
        self.side_a.resize_with(len, Default::default);
        self.cold.resize_with(len, Default::default);
        if P == 1 {
            self.rolling.resize_with(len, Default::default);
        }
    }

    /// Prepares group `i` from `sources`; returns whether any lane has restitution, and whether any
    /// resists rolling.
    fn prepare<const STATIC_A: bool>(
        &mut self,
        i: usize,
        sources: &[LaneSource],
        contacts: &[Contact],
        poses: &[Body],
        bodies: &[SolverBody],
        motions: &[SolverMotion],
    ) -> (bool, bool) {
        let bouncy = prepare::<P, M, STATIC_A>(
            &mut self.hot[i],
            &mut self.side_a[i],
            &mut self.cold[i],
            sources,
            contacts,
            poses,
            bodies,
            motions,
        );
        let rolling = P == 1
            && prepare_rolling(
                &mut self.rolling[i],
                &self.hot[i].rolling_axes(),
                FrictionCoupling {
                    irt_a: &self.side_a[i].irt_a,
                    irt_b: &self.hot[i].irt_b,
                    mass: &self.hot[i].tangent_mass,
                },
                sources,
                contacts,
                motions,
            );
        (bouncy, rolling)
    }

    /// Lane `k` of group `i`'s friction rows as scalars.
    fn friction_rows(&self, i: usize, k: usize) -> FrictionRows {
        let (g, a) = (&self.hot[i], &self.side_a[i]);
        FrictionRows {
            normal: g.normal.lane(k),
            tangents: g.tangents.map(|t| t.lane(k)),
            inv_mass_a: a.inv_mass_a[k],
            inv_mass_b: g.inv_mass_b[k],
            friction: g.friction[k],
            rt_a: a.rt_a.map(|v| v.lane(k)),
            rt_b: g.rt_b.map(|v| v.lane(k)),
            irt_a: a.irt_a.map(|v| v.lane(k)),
            irt_b: g.irt_b.map(|v| v.lane(k)),
            tangent_mass: g.tangent_mass.map(|m| m[k]),
        }
    }

    /// [`WideContacts::mark_pressed_springs`] for group `i`.
    fn mark_pressed_springs(&self, i: usize, tolerance: f32, unsettled: &mut [bool]) {
        let (g, a) = (&self.hot[i], &self.side_a[i]);
        // The whole patch pressed: a patch at rest tilted (two faces that are not flush, as
        // dominoes lean) has points pressed and points apart.
        let mut shallowest = Vec4::splat(f32::MIN);
        for p in &g.points {
            let real = p.mean_weight.cmpgt(Vec4::ZERO);
            shallowest =
                shallowest.max(Vec4::select(real, p.separation_now, Vec4::splat(f32::MIN)));
        }
        let pressed =
            shallowest.cmplt(Vec4::splat(-tolerance)) & g.touching_spring.cmpgt(Vec4::ZERO);
        let pressed = pressed.bitmask();
        for k in 0..LANES {
            if pressed & (1 << k) != 0 {
                unsettled[a.a[k] as usize] = true;
                unsettled[g.b[k] as usize] = true;
            }
        }
    }

    /// Stores every group's impulses; returns the deepest penetration per lane, m.
    fn store(&self, contacts: &mut [Contact]) -> Vec4 {
        store(&self.hot, &self.cold, contacts)
    }

    /// Stores group `i`'s rolling impulses (a one-point group that resists rolling).
    fn store_rolling(&self, i: usize, contacts: &mut [Contact]) {
        store_rolling(
            &self.rolling[i],
            &self.hot[i].rolling_axes(),
            &self.cold[i].contact,
            contacts,
        );
    }

    /// Warm start of group `g`.
    #[inline(always)]
    fn warm_start<const STATIC_A: bool>(&self, g: GroupRef, bodies: &mut [SolverBody]) {
        let i = g.index as usize;
        let (hot, side_a) = (&self.hot[i], &self.side_a[i]);
        if P == 1 && g.rolling {
            warm_start::<P, M, STATIC_A>(hot, side_a, Some(&self.rolling[i]), bodies);
        } else {
            warm_start::<P, M, STATIC_A>(hot, side_a, None, bodies);
        }
    }

    /// One sweep over group `i`, visiting each manifold's points backwards when `REVERSE`.
    #[inline(always)]
    fn solve<const BIAS: bool, const STATIC_A: bool, const REVERSE: bool>(
        &mut self,
        g: GroupRef,
        softness: &SoftnessLanes,
        bodies: &mut [SolverBody],
        params: &PassParams,
    ) {
        let i = g.index as usize;
        let (hot, side_a) = (&mut self.hot[i], &self.side_a[i]);
        // A call site per combination: without restitution or rolling resistance the kernel is built
        // with no trace of them.
        let max = &mut self.cold[i].max_normal_impulse;
        match (g.bouncy, P == 1 && g.rolling) {
            (false, false) => solve::<P, M, BIAS, STATIC_A, REVERSE>(
                hot, side_a, softness, None, None, bodies, params,
            ),
            (true, false) => solve::<P, M, BIAS, STATIC_A, REVERSE>(
                hot,
                side_a,
                softness,
                Some(max),
                None,
                bodies,
                params,
            ),
            (bouncy, true) => solve::<P, M, BIAS, STATIC_A, REVERSE>(
                hot,
                side_a,
                softness,
                bouncy.then_some(max),
                Some(&mut self.rolling[i]),
                bodies,
                params,
            ),
        }
    }
}

/// A [`ContactSoftness`] splat across the lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SoftnessLanes {
    pub bias_rate: Vec4,
    pub mass_scale: Vec4,
    pub impulse_scale: Vec4,
    /// The friction anchors' spring (`contact_solver`, "Friction anchors").
    pub anchor_bias_rate: Vec4,
    pub anchor_mass_scale: Vec4,
    pub anchor_impulse_scale: Vec4,
}

impl SoftnessLanes {
    fn splat(s: ContactSoftness) -> Self {
        let (normal, anchor) = (s.normal, s.anchor);
        Self {
            bias_rate: Vec4::splat(normal.bias_rate),
            mass_scale: Vec4::splat(normal.mass_scale),
            impulse_scale: Vec4::splat(normal.impulse_scale),
            anchor_bias_rate: Vec4::splat(anchor.bias_rate),
            anchor_mass_scale: Vec4::splat(anchor.mass_scale),
            anchor_impulse_scale: Vec4::splat(anchor.impulse_scale),
        }
    }
}

/// The order a biased pass visits the contact graph's layers in: up, the solve order (colour by
/// colour, each bottom-up, `prepare::constraint_order`), or down, against it. A fixed order is a
/// bias of its own: Gauss–Seidel leaves its residual where it visits last, at the top of every
/// pile, sub-step after sub-step, and piles kept awake crept on it (a heap of boxes and balls 8 to
/// 10 mm in a minute at 4 sub-steps in five copies of eight, a running-bond wall 1.2 mm, a touching
/// pyramid at 8 sub-steps 1.3 mm). So from [`DOWN_MIN_SUBSTEPS`] sub-steps up the biased passes go
/// up and down in turn (`Settings::alternate_layer_order`), symmetric Gauss–Seidel over the layers;
/// the relax pass, which ends each sub-step and leaves the velocities it integrates, always goes up
/// (turned against the biased pass, it brought the running-bond wall woken at 4 sub-steps from 10.8
/// to 3.7 mm, still not within 1 mm, and the heap woken at 4 from 0.004 to 16 mm in its worst copy;
/// 2026-12-01). Over `nudge bench rest`'s eight copies, kept awake a minute at 4 and 8 sub-steps,
/// every pile now stays within 0.7 mm (the heap's worst copy; its median 8.3 → 0.003 mm at 4), the
/// touching pyramid within 0.05 mm at 4 (0.19), and at 4 × 4 every pile holds.
///
/// A downward pass leaves some contacts bottom-up, after the others (`GroupRef::always_up`), each
/// where turning them cost more than it bought: around a mass ratio (the light box pinned under a
/// heavy one held 3,200 N of push instead of 4,525; Coulomb: 4,910 N), on a jointed body (a
/// Newton's cradle out of step gained 0.027 J in a step), and deeper than the soft range, where the
/// position pass pushes the pair apart (100 coincident boxes ended 10.3 mm overlapped after 5 s,
/// not 7.9).
///
/// Below 4 sub-steps a downward pass costs more than its symmetry buys: each sub-step's one biased
/// pass must carry the load up from the ground, and a 20-row pyramid kept awake at 2 sub-steps
/// drifted 7 to 112 mm with it (0.14 to 0.38 mm without), at 3 sub-steps 0.18 mm (0.05) (measured
/// 2026-11-30; `nudge bench rest`; `alternating_layers_keep_an_awake_heap_still`,
/// `tests/physics/rest.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LayerOrder {
    Up,
    Down,
}

/// The fewest sub-steps at which the biased passes alternate their direction (see [`LayerOrder`]).
pub(crate) const DOWN_MIN_SUBSTEPS: u32 = 4;

impl LayerOrder {
    /// The direction of biased pass `pass` (from 0) of the sub-step numbered `substep` over the
    /// world's life with `substeps` a step: up and down in turn, from up on even sub-steps and
    /// down on odd ones, when `alternate` and there are at least [`DOWN_MIN_SUBSTEPS`]; else up.
    pub(crate) fn of_pass(substep: u64, pass: u32, substeps: u32, alternate: bool) -> LayerOrder {
        if alternate && substeps >= DOWN_MIN_SUBSTEPS && (substep + u64::from(pass)) % 2 == 1 {
            LayerOrder::Down
        } else {
            LayerOrder::Up
        }
    }
}

/// The order a pass visits each manifold's points in. Gauss–Seidel around the points of a face has a
/// handedness: each point's correction leans on the next one around, so a tilt error is handed on a
/// quarter turn at every visit. In a stack that could not sleep this fed a slow whirl (the top of an
/// 8-box stack at 8 sub-steps circled with a growing radius, while reused manifolds kept stale
/// points); today it rocks a copy of the awake spaced pyramid at 8 sub-steps. Passes alternate
/// directions (symmetric Gauss–Seidel), which has no handedness, and so do the sub-steps when their
/// passes are odd in number ([`PointOrder::before_substep`]). Measured with and without by
/// `nudge bench physics` (its table of the fixes) and pinned by
/// `tests/physics/convergence_fixes.rs`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PointOrder {
    Forward,
    Backward,
}

impl PointOrder {
    /// The other direction.
    pub(crate) fn flipped(self) -> PointOrder {
        match self {
            PointOrder::Forward => PointOrder::Backward,
            PointOrder::Backward => PointOrder::Forward,
        }
    }

    /// The order "before" the first pass of the sub-step numbered `substep` (counted over the
    /// world's life) with `iterations` biased passes: its first pass visits the points the other
    /// way. A sub-step's passes are its iterations and the relax pass. An even count of them is
    /// balanced within the sub-step, and every sub-step starts backward. An odd count (two or four
    /// iterations) is not: started alike, each sub-step visits backward once more than forward,
    /// and that handedness leaned an awake touching pyramid at 4 × 4 by 2.3 mm within its first
    /// seconds (0.05 mm at 4 × 1, whose two passes balance) and kept a heap of boxes and balls
    /// stirring at 4 × 2. So with `alternate` (`Settings::alternate_sub_steps`) those sub-steps
    /// start in turn backward and forward, balanced over each pair
    /// (`even_iterations_stir_an_awake_heap_unless_sub_steps_alternate`, `tests/physics/rest.rs`).
    ///
    /// "Balanced" holds pass for pass, not kind for kind: the relax pass visits a symmetric
    /// manifold's points both ways (`velocity`, "The symmetric relax"), so at one iteration every
    /// biased pass visits backward; below 4 sub-steps a preloaded manifold's biased pass visits both
    /// ways too (`contact_solver`, "The symmetric biased pass", where what it cost from 4 up is).
    /// Tried and not kept (measured 2026-12-01, the tower over 24 copies, the heap over 16): the
    /// biased passes alternating from sub-step to sub-step, the relax pass forward. The crossed
    /// tower kept awake at 2 sub-steps, where 2 copies of 24 swayed up from noise over seconds, held
    /// in all 24; but the heap of boxes and balls kept awake at 2 sub-steps was stirred, all 16
    /// copies 4.9 to 15.6 mm off (10 of 16 held without).
    pub(crate) fn before_substep(substep: u64, iterations: u32, alternate: bool) -> PointOrder {
        let passes = u64::from(iterations) + 1;
        if alternate && passes % 2 == 1 && substep % 2 == 1 {
            PointOrder::Backward
        } else {
            PointOrder::Forward
        }
    }

    /// The order of the pass after one in `self`: the other direction when `alternate`, else forward
    /// every time (`Settings::alternate_point_order`).
    #[inline]
    pub(crate) fn next(self, alternate: bool) -> PointOrder {
        if alternate {
            self.flipped()
        } else {
            PointOrder::Forward
        }
    }
}

/// A lane group by kind and index: which `Groups` and where in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct GroupRef {
    pub kind: GroupKind,
    /// Every lane's body A is the static dummy (a pile on a floor): the kernels skip side A.
    pub static_a: bool,
    /// Some lane has restitution: the passes track the largest impulse increments (set by `build`).
    pub bouncy: bool,
    /// Some lane resists rolling (one-point groups only; set by `build`): see `rolling`.
    pub rolling: bool,
    /// Some lane is a touching spring (set by `build`): see `sleep`, "Pressed springs".
    pub touching: bool,
    /// The lanes' softness, an index into `WideContacts::softness` (set by `build`).
    pub softness: u32,
    /// Index among the groups of the same kind and side A.
    pub index: u32,
    /// Visited bottom-up by every pass (see [`LayerOrder`], set by `build`): one of its constraints
    /// is around a mass ratio or holds a jointed body (not symmetric, which covers every constraint
    /// the mass-ratio sweeps visit), or is deeper than its soft range.
    pub always_up: bool,
}

/// Where a constraint lives: its group and lane.
#[derive(Clone, Copy, Debug, Default)]
struct Slot {
    group: u32,
    lane: u8,
}

/// Which side of a contact is a resting pile that takes the other's blow as the ground would (see
/// `prepare::preload::blows`): that side's rows see it as immovable for the step.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum StruckPile {
    #[default]
    Neither,
    A,
    B,
}

/// What preparing one manifold needs besides its contact, the bodies and the solver bodies. (The
/// bodies' poses are read where the lanes are prepared, not copied here: this is written once per
/// constraint and read back once, and the poses and motions since the manifold was computed were
/// two thirds of its bytes.)
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneSource {
    /// Index of the persistent contact.
    pub contact: u32,
    /// Solver body indices (0 = static dummy).
    pub a: u32,
    pub b: u32,
    pub softness: ContactSoftness,
    /// The contact's feed-forward load, N·s per sub-step (`NO_PRELOAD`: none): its warm start.
    pub preload: f32,
    /// The part of it the soft spring rests preloaded with, N·s per sub-step.
    pub spring_preload: f32,
    /// The friction warm start on B, N·s per sub-step, when the preload's statics give one (a
    /// sticking support whose load changed); else the contact's own from last step.
    pub tangent_warm: Option<glam::Vec3>,
    /// Σ δᵢ·dᵢ the preload's points must have (dᵢ a point's offset from the patch's centroid, δᵢ its
    /// load less an even share) for their pressure to balance the moment the patch carries.
    pub pressure_offset: Option<glam::Vec3>,
    /// The change to add to the moment its warm start's pressure carries (see
    /// `prepare::preload`, "Moment changes").
    pub offset_change: Option<glam::Vec3>,
    /// The change in its preload since last step, where statics do not determine it, on a step in
    /// which what it carries changed (see `prepare::preload`, "Load changes"): the solver's own
    /// warm start moves towards the new preload by at most this much.
    pub load_change: f32,
    /// Whether statics determine the preload (see `prepare::preload`): then the warm start is
    /// rescaled to it every step; otherwise only while the contact carries nothing yet, and after
    /// that the spring alone rests preloaded and the warm start is the solver's own.
    pub determinate: bool,
    /// Which side, if any, is a pile taking this contact's landing as the ground would: its rows
    /// see that side as immovable (`prepare::preload::blows`).
    pub struck_pile: StruckPile,
    /// Whether its normal rows are springs centred where they touch (a determinate support, with
    /// `Settings::touching_spring` on; see `velocity`).
    pub touching_spring: bool,
    /// How far apart its points may be and still rest touching where it is preloaded, m
    /// (`Settings::touching_tolerance`; an impact's rows keep 0).
    pub touching_tolerance: f32,
    /// Whether the patch's friction is anchored (see `contact_solver`, "Friction anchors").
    pub anchored: bool,
    /// Whether the relax pass visits the points twice (see `contact_solver`, "The symmetric
    /// relax"): neither body is marked for a mass ratio or held by a joint.
    pub symmetric: bool,
    /// A point is deeper than the soft range (`push_out`).
    pub deep: bool,
    /// Whether the rolling rows may take the mass they have with friction held (see `rolling`):
    /// the contact is each of its dynamic bodies' only one.
    pub rolling_held: bool,
}

/// Every constraint of a step in lane groups, with the order the groups are solved in.
#[derive(Debug, Default)]
pub(crate) struct WideContacts {
    /// Groups by kind, each indexed by `static_a as usize`.
    ones: [Groups<1, { multi_row_count(1) }>; 2],
    twos: [Groups<2, { multi_row_count(2) }>; 2],
    fours: [Groups<4, { multi_row_count(4) }>; 2],
    /// The distinct softnesses of this step's groups (one per kind of contact), splat.
    softness: Vec<SoftnessLanes>,
    /// The same as pushed (their bits), to find them again.
    softness_keys: Vec<[u32; 6]>,
    /// All groups in solve order (colour by colour).
    schedule: Vec<GroupRef>,
    /// The pushed manifolds in push order; group g holds `sources[starts[g]..starts[g + 1]]`.
    sources: Vec<LaneSource>,
    starts: Vec<u32>,
    /// Groups opened so far of each kind and side A (index `2·kind + static_a`).
    opened: [u32; 6],
    /// Per constraint: its position in `schedule` and its lane.
    slots: Vec<Slot>,
    /// The constraints of the open colour that get the mass-ratio sweeps, held back to be packed
    /// after the colour's others (see `push`): constraint index, point count and source.
    held_back: Vec<(u32, usize, LaneSource)>,
    /// The colour whose constraints may share bodies, each in a group of its own (see `clear`), and
    /// the colour being pushed.
    serial_color: u32,
    open_color: u32,
    /// The key of the group being filled (see `push`), its softness' bits and how many lanes it has.
    open_key: u32,
    open_softness: [u32; 6],
    open_len: usize,
    /// Restitution's scratch (see `impacts`): the bodies' velocities at the start of the step and
    /// after the first sub-step's kick and warm start (both empty when no group has restitution),
    /// and the rows.
    start_velocities: Vec<(Vec3A, Vec3A)>,
    kicked_velocities: Vec<(Vec3A, Vec3A)>,
    post_velocities: Vec<(Vec3A, Vec3A)>,
    impact_rows: Vec<impacts::ImpactRow>,
    /// Restitution's union–find forest over bodies (reused by lift-off for each body's supports)
    /// and its islands' marks (see `impacts`).
    impact_islands: Vec<u32>,
    impact_hit: Vec<bool>,
    /// Restitution's friction rows, one per manifold that rebounds (see `impacts`).
    impact_friction: Vec<impacts::ReboundFriction>,
}

/// What a lane group holds, by the point count of its manifolds: one (spheres), two (edges) or four
/// (faces; three-point manifolds get an inert fourth point). The discriminant orders groups within a
/// colour (see `constraint_order`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(crate) enum GroupKind {
    One = 0,
    Two = 1,
    Four = 2,
}

/// The group kind of a manifold with `len` points.
#[inline]
pub(crate) fn kind_of(len: usize) -> GroupKind {
    match len {
        0 | 1 => GroupKind::One,
        2 => GroupKind::Two,
        _ => GroupKind::Four,
    }
}

/// The one place that maps a group to its storage: evaluates `$body` with `$groups` bound to the
/// [`Groups`] of `$group`'s kind and side A in `$wide` (borrowed as written, `&` or `&mut`) and
/// `$static_a` a `const bool` of its side A, so the body can hand it to a kernel as a const generic.
/// With `each` instead of a group, evaluates `$body` for every storage in turn (dynamic side A first,
/// kinds in order), `$kind` a `const GroupKind` of it.
macro_rules! with_groups {
    (each &mut $wide:ident, |$groups:ident, $static_a:ident, $kind:ident| $body:expr) => {
        with_groups!(@each [&mut] $wide, |$groups, $static_a, $kind| $body)
    };
    (each &$wide:ident, |$groups:ident, $static_a:ident, $kind:ident| $body:expr) => {
        with_groups!(@each [&] $wide, |$groups, $static_a, $kind| $body)
    };
    (@each [$($borrow:tt)+] $wide:ident, |$groups:ident, $static_a:ident, $kind:ident| $body:expr) => {{
        with_groups!(@one [$($borrow)+] $wide.ones[0], false, GroupKind::One, |$groups, $static_a, $kind| $body);
        with_groups!(@one [$($borrow)+] $wide.twos[0], false, GroupKind::Two, |$groups, $static_a, $kind| $body);
        with_groups!(@one [$($borrow)+] $wide.fours[0], false, GroupKind::Four, |$groups, $static_a, $kind| $body);
        with_groups!(@one [$($borrow)+] $wide.ones[1], true, GroupKind::One, |$groups, $static_a, $kind| $body);
        with_groups!(@one [$($borrow)+] $wide.twos[1], true, GroupKind::Two, |$groups, $static_a, $kind| $body);
        with_groups!(@one [$($borrow)+] $wide.fours[1], true, GroupKind::Four, |$groups, $static_a, $kind| $body);
    }};
    (@one [$($borrow:tt)+] $storage:expr, $side:expr, $which:expr, |$groups:ident, $static_a:ident, $kind:ident| $body:expr) => {{
        #[allow(dead_code)]
        const $static_a: bool = $side;
        #[allow(dead_code)]
        const $kind: GroupKind = $which;
        let $groups = $($borrow)+ $storage;
        $body;
    }};
    (&mut $wide:ident, $group:expr, |$groups:ident, $static_a:ident| $body:expr) => {
        with_groups!(@arms [&mut] $wide, $group, |$groups, $static_a| $body)
    };
    (&$wide:ident, $group:expr, |$groups:ident, $static_a:ident| $body:expr) => {
        with_groups!(@arms [&] $wide, $group, |$groups, $static_a| $body)
    };
    (@arms [$($borrow:tt)+] $wide:ident, $group:expr, |$groups:ident, $static_a:ident| $body:expr) => {{
        let group: GroupRef = $group;
        match (group.kind, group.static_a) {
            (GroupKind::One, false) => {
                const $static_a: bool = false;
                let $groups = $($borrow)+ $wide.ones[0];
                $body
            }
            (GroupKind::One, true) => {
                const $static_a: bool = true;
                let $groups = $($borrow)+ $wide.ones[1];
                $body
            }
            (GroupKind::Two, false) => {
                const $static_a: bool = false;
                let $groups = $($borrow)+ $wide.twos[0];
                $body
            }
            (GroupKind::Two, true) => {
                const $static_a: bool = true;
                let $groups = $($borrow)+ $wide.twos[1];
                $body
            }
            (GroupKind::Four, false) => {
                const $static_a: bool = false;
                let $groups = $($borrow)+ $wide.fours[0];
                $body
            }
            (GroupKind::Four, true) => {
                const $static_a: bool = true;
                let $groups = $($borrow)+ $wide.fours[1];
                $body
            }
        }
    }};
}
pub(super) use with_groups;

impl WideContacts {
    /// Empties the set for a new step whose constraints of colour `serial_color` may share bodies
    /// (each then gets a group of its own).
    pub(crate) fn clear(&mut self, serial_color: u32) {
        self.serial_color = serial_color;
        self.schedule.clear();
        self.sources.clear();
        self.starts.clear();
        self.opened = [0; 6];
        self.slots.clear();
        self.held_back.clear();
        self.open_color = u32::MAX;
        self.softness.clear();
        self.softness_keys.clear();
        self.open_len = LANES;
    }

    /// Adds constraint `i`, the next in solve order, a manifold of `len` points. `color` is its
    /// graph colour; constraints are packed four to a group while colour, kind, softness, whether
    /// body A is static and whether it gets the mass-ratio sweeps (`swept`) stay the same, except in
    /// the serial colour (see [`Self::clear`]). [`Self::build`] prepares them.
    ///
    /// A swept constraint is held back and packed after the other constraints of its colour, with
    /// the colour's other swept ones: the extra sweeps visit whole groups, and packed among the
    /// others each swept constraint took up to three lane-mates through them (in a settled pile of
    /// twenty ragdolls 30 to 50 swept constraints filled 27 to 43 groups, and the extra sweeps were
    /// a sixth of the step; packed apart, 1,500 steps of that pile take 9 % less time). A colour's
    /// constraints share no dynamic body, so the order they are solved in within it changes no
    /// result: only the lane-mates' extra sweeps are gone, and a scene without mass ratios steps bit
    /// for bit as before (the scripted pyramid's and default scene's hashes in
    /// `tests/physics/determinism.rs` did not move). The packing itself is pinned by
    /// `swept_constraints_are_packed_apart_after_their_colour`.
    pub(crate) fn push(
        &mut self,
        i: usize,
        color: u32,
        len: usize,
        source: LaneSource,
        swept: bool,
    ) {
        if color != self.open_color {
            self.release_held_back();
            self.open_color = color;
        }
        if swept && color != self.serial_color {
            self.held_back.push((i as u32, len, source));
            return;
        }
        self.pack(i, color, len, source, swept);
    }

    /// Packs the open colour's held-back constraints (see [`Self::push`]).
    fn release_held_back(&mut self) {
        let color = self.open_color;
        let mut held_back = std::mem::take(&mut self.held_back);
        for (i, len, source) in held_back.drain(..) {
            self.pack(i as usize, color, len, source, true);
        }
        self.held_back = held_back;
    }

    /// Puts constraint `i` in the open group if it fits there, else in a new one.
    fn pack(&mut self, i: usize, color: u32, len: usize, source: LaneSource, swept: bool) {
        let kind = kind_of(len);
        let static_a = source.a == 0;
        let key = color << 4 | (kind as u32) << 2 | u32::from(swept) << 1 | u32::from(static_a);
        // Field by field, each read only if the one before matched: one wide read of the argument
        // straddled the caller's narrower writes and stalled on store forwarding.
        let (open, normal, anchor) = (
            &self.open_softness,
            &source.softness.normal,
            &source.softness.anchor,
        );
        let same_softness = normal.bias_rate.to_bits() == open[0]
            && normal.mass_scale.to_bits() == open[1]
            && normal.impulse_scale.to_bits() == open[2]
            && anchor.bias_rate.to_bits() == open[3]
            && anchor.mass_scale.to_bits() == open[4]
            && anchor.impulse_scale.to_bits() == open[5];
        if key != self.open_key
            || !same_softness
            || self.open_len == LANES
            || color == self.serial_color
        {
            let opened = &mut self.opened[2 * kind as usize + usize::from(static_a)];
            self.schedule.push(GroupRef {
                kind,
                static_a,
                bouncy: false,
                rolling: false,
                touching: false,
                softness: 0,
                index: *opened,
                always_up: false,
            });
            *opened += 1;
            self.starts.push(self.sources.len() as u32);
            let softness = source.softness.bits();
            (self.open_key, self.open_softness, self.open_len) = (key, softness, 0);
        }
        let slot = Slot {
            group: self.schedule.len() as u32 - 1,
            lane: self.open_len as u8,
        };
        // Pushed in solve order, a constraint is most often the next slot (a held-back one comes
        // after later ones).
        match self.slots.get_mut(i) {
            Some(held_back) => *held_back = slot,
            None => {
                self.slots.resize(i, Slot::default());
                self.slots.push(slot);
            }
        }
        self.sources.push(source);
        self.open_len += 1;
    }

    /// The index of `softness` in the table, added if new (compared bit for bit).
    fn softness_index(&mut self, softness: ContactSoftness) -> u32 {
        let bits = softness.bits();
        if let Some(i) = self.softness_keys.iter().position(|s| *s == bits) {
            return i as u32;
        }
        self.softness_keys.push(bits);
        self.softness.push(SoftnessLanes::splat(softness));
        self.softness_keys.len() as u32 - 1
    }

    /// Prepares every pushed constraint, four at a time.
    pub(crate) fn build(
        &mut self,
        contacts: &[Contact],
        poses: &[Body],
        bodies: &[SolverBody],
        motions: &[SolverMotion],
    ) {
        self.release_held_back();
        // Filled in place, over last step's groups (a group is a few kilobytes: returning it by value or
        // zeroing it first costs a copy).
        let opened = self.opened.map(|count| count as usize);
        with_groups!(each &mut self, |storage, STATIC_A, KIND| {
            storage.resize(opened[2 * KIND as usize + usize::from(STATIC_A)])
        });
        let end = self.sources.len() as u32;
        for g in 0..self.schedule.len() {
            let start = self.starts[g] as usize;
            let stop = self.starts.get(g + 1).copied().unwrap_or(end) as usize;
            // Every lane of a group has the first one's softness (see `push`).
            let softness = self.softness_index(self.sources[start].softness);
            let sources = &self.sources[start..stop];
            let group = &mut self.schedule[g];
            let i = group.index as usize;
            group.softness = softness;
            let (mut touching, mut always_up) = (false, false);
            for source in sources {
                touching |= source.touching_spring;
                // Around a mass ratio or a joint, or deeper than the soft range (see `LayerOrder`).
                always_up |= !source.symmetric || source.deep;
            }
            (group.touching, group.always_up) = (touching, always_up);
            (group.bouncy, group.rolling) = with_groups!(&mut self, *group, |storage, STATIC_A| {
                storage.prepare::<STATIC_A>(i, sources, contacts, poses, bodies, motions)
            });
        }
    }

    /// The groups holding the constraints `subset` (ascending constraint indices), in solve order,
    /// each once, into `out`.
    pub(crate) fn groups_of(&self, subset: &[u32], out: &mut Vec<GroupRef>) {
        out.clear();
        let mut last = u32::MAX;
        for &i in subset {
            let group = self.slots[i as usize].group;
            if group != last {
                out.push(self.schedule[group as usize]);
                last = group;
            }
        }
    }

    /// The mean bias of constraint `i`'s points in the last biased pass, m/s.
    pub(crate) fn bias_mean(&self, i: u32) -> f32 {
        let (g, lane) = self.locate(i);
        let i = g.index as usize;
        with_groups!(&self, g, |storage, _STATIC_A| storage.hot[i].bias_mean
            [lane])
    }

    /// Constraint `i`'s friction rows, read out of its lane (after [`Self::build`]).
    pub(crate) fn friction_rows(&self, i: u32) -> FrictionRows {
        let (g, lane) = self.locate(i);
        let i = g.index as usize;
        with_groups!(&self, g, |storage, _STATIC_A| storage
            .friction_rows(i, lane))
    }

    /// Constraint `i`'s group and lane.
    fn locate(&self, i: u32) -> (GroupRef, usize) {
        let slot = self.slots[i as usize];
        (self.schedule[slot.group as usize], slot.lane as usize)
    }

    /// Copies the accumulated impulses back to the persistent contacts and returns the deepest
    /// penetration at the end of the step, m (≥ 0).
    pub(crate) fn store_impulses(&self, contacts: &mut [Contact]) -> f32 {
        let mut deepest = Vec4::ZERO;
        with_groups!(each & self, |storage, _STATIC_A, _KIND| {
            deepest = deepest.max(storage.store(contacts))
        });
        for g in self.schedule.iter().filter(|g| g.rolling) {
            debug_assert_eq!(
                g.kind,
                GroupKind::One,
                "only one-point groups resist rolling"
            );
            with_groups!(&self, *g, |storage, _STATIC_A| {
                storage.store_rolling(g.index as usize, contacts)
            });
        }
        deepest.max_element()
    }

    /// Marks in `unsettled` (by solver index; index 0, the static dummy, may be marked too) both
    /// bodies of every contact whose touching spring is pressed deeper than `tolerance` (m) at every
    /// point at the step's end (the separations the last relax pass left): not yet where they rest.
    pub(crate) fn mark_pressed_springs(&self, tolerance: f32, unsettled: &mut [bool]) {
        for &g in self.schedule.iter().filter(|g| g.touching) {
            with_groups!(&self, g, |storage, _STATIC_A| {
                storage.mark_pressed_springs(g.index as usize, tolerance, unsettled)
            });
        }
    }

    /// Whether some group has restitution (known once [`Self::remember_start_velocities`] ran).
    pub(crate) fn any_bouncy(&self) -> bool {
        !self.start_velocities.is_empty()
    }

    /// Adds each point's accumulated normal impulse to what it delivered over the step (groups
    /// with restitution only; call once at the end of every sub-step).
    pub(crate) fn add_step_impulses(&mut self) {
        for &g in self.schedule.iter().filter(|g| g.bouncy) {
            let i = g.index as usize;
            with_groups!(&mut self, g, |storage, _STATIC_A| {
                let (hot, cold) = (&storage.hot[i], &mut storage.cold[i]);
                for (sum, point) in cold.step_impulse.iter_mut().zip(&hot.impulses) {
                    *sum += point.normal_impulse;
                }
            });
        }
    }

    /// Applies last step's impulses (every group).
    pub(crate) fn warm_start(&self, bodies: &mut [SolverBody]) {
        for &g in &self.schedule {
            with_groups!(&self, g, |storage, STATIC_A| {
                storage.warm_start::<STATIC_A>(g, bodies)
            });
        }
    }

    /// One Gauss–Seidel sweep over every group (soft and biased when `BIAS`, else the rigid relax
    /// pass), in solve order or against it (`layers`), visiting each manifold's points in `order`.
    pub(crate) fn solve<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        params: &PassParams,
        order: PointOrder,
        layers: LayerOrder,
    ) {
        let schedule = std::mem::take(&mut self.schedule);
        match layers {
            LayerOrder::Up => self.solve_groups::<BIAS>(&schedule, bodies, params, order),
            LayerOrder::Down => {
                let turned = schedule.iter().rev().filter(|g| !g.always_up);
                self.solve_groups::<BIAS>(turned, bodies, params, order);
                let kept = schedule.iter().filter(|g| g.always_up);
                self.solve_groups::<BIAS>(kept, bodies, params, order);
            }
        }
        self.schedule = schedule;
    }

    /// One sweep over `groups`, in the order given, visiting each manifold's points in `order`.
    pub(crate) fn solve_groups<'g, const BIAS: bool>(
        &mut self,
        groups: impl IntoIterator<Item = &'g GroupRef>,
        bodies: &mut [SolverBody],
        params: &PassParams,
        order: PointOrder,
    ) {
        match order {
            PointOrder::Forward => self.sweep::<BIAS, false>(groups, bodies, params),
            PointOrder::Backward => self.sweep::<BIAS, true>(groups, bodies, params),
        }
    }

    fn sweep<'g, const BIAS: bool, const REVERSE: bool>(
        &mut self,
        groups: impl IntoIterator<Item = &'g GroupRef>,
        bodies: &mut [SolverBody],
        params: &PassParams,
    ) {
        for &g in groups {
            let softness = &self.softness[g.softness as usize];
            with_groups!(&mut self, g, |storage, STATIC_A| {
                storage.solve::<BIAS, STATIC_A, REVERSE>(g, softness, bodies, params)
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::physics::ContactPoint;
    use crate::physics::narrow::contact::CachedImpulses;
    use crate::physics::narrow::manifold::Manifold;
    use crate::physics::solve::softness::Softness;
    use glam::{Mat3, Mat3A, Quat, Vec3, Vec3A};

    /// From 4 sub-steps the biased passes go down every other pass, starting down on odd
    /// sub-steps; below 4, or switched off, always up.
    #[test]
    fn biased_passes_go_up_and_down_in_turn_from_four_sub_steps() {
        use LayerOrder::{Down, Up};
        let passes = |substep: u64, substeps: u32, alternate: bool| -> Vec<LayerOrder> {
            (0..4)
                .map(|pass| LayerOrder::of_pass(substep, pass, substeps, alternate))
                .collect()
        };
        assert_eq!(passes(0, 4, true), [Up, Down, Up, Down]);
        assert_eq!(passes(1, 4, true), [Down, Up, Down, Up]);
        assert_eq!(passes(7, 8, true), [Down, Up, Down, Up]);
        assert_eq!(passes(1, 3, true), [Up; 4]);
        assert_eq!(passes(1, 8, false), [Up; 4]);
    }

    /// Counted over a pair of sub-steps, the passes visit the points as often backward as forward
    /// at every iteration count (each sub-step alone when its passes are even in number); with the
    /// sub-steps started alike, two or four iterations lean backward.
    #[test]
    fn a_pair_of_sub_steps_visits_the_points_as_often_backward_as_forward() {
        let lean = |iterations: u32, alternate: bool| {
            let mut lean = 0i32;
            for substep in 0..2u64 {
                let mut order = PointOrder::before_substep(substep, iterations, alternate);
                // The biased passes and the relax pass.
                for _ in 0..=iterations {
                    order = order.next(true);
                    lean += if order == PointOrder::Backward { 1 } else { -1 };
                }
            }
            lean
        };
        for iterations in 1..=4 {
            assert_eq!(lean(iterations, true), 0, "{iterations} iterations");
        }
        assert_eq!(lean(2, false), 2);
        assert_eq!(lean(4, false), 2);
    }

    /// A tilted box (B) touching a tumbling one (A) with the first `len` of four points, both moving.
    struct Case {
        bodies: Vec<SolverBody>,
        motions: Vec<SolverMotion>,
        contact: Contact,
        x_a: Vec3,
        x_b: Vec3,
    }

    fn case(len: usize) -> Case {
        let n = Vec3::new(0.1, 1.0, -0.2).normalize();
        let mut manifold = Manifold {
            normal: n,
            ..Default::default()
        };
        for (i, (x, z, depth)) in [
            (-0.5, -0.4, -0.004),
            (0.5, -0.45, 0.05),
            (0.45, 0.5, -0.001),
            (-0.5, 0.4, -0.006),
        ]
        .into_iter()
        .enumerate()
        .take(len)
        {
            manifold.push(ContactPoint {
                point: Vec3::new(x, 0.02 * x, z),
                separation: depth,
                id: i as u32,
            });
        }
        let impulses = CachedImpulses {
            normal: [0.3, 0.1, 1.2, 0.7],
            ..Default::default()
        };
        let contact = Contact {
            a: 0,
            b: 1,
            manifold,
            impulses,
            friction: 0.0,
            restitution: 0.0,
            rolling_resistance: 0.0,
            soft_depth: 0.02,
            computed: crate::physics::narrow::contact::Computed::of(&manifold),
            pose_a: Pose::IDENTITY,
            pose_b: Pose::IDENTITY,
            statics: None,
        };
        let inertia = |m: f32, q: Quat| {
            let r = Mat3::from_quat(q);
            Mat3A::from(r * Mat3::from_diagonal(Vec3::new(6.0, 4.0, 5.0) / m) * r.transpose())
        };
        let motion = |m: f32, q: Quat| SolverMotion {
            inv_mass: 1.0 / m,
            inv_inertia: inertia(m, q),
            ..SolverMotion::DUMMY
        };
        let body = |v: Vec3, w: Vec3| SolverBody {
            v: v.into(),
            w: w.into(),
            ..SolverBody::DUMMY
        };
        Case {
            bodies: vec![
                SolverBody::DUMMY,
                body(Vec3::new(0.2, 0.5, -0.1), Vec3::new(1.0, -0.5, 2.0)),
                body(Vec3::new(-0.3, -2.0, 0.4), Vec3::new(-0.7, 0.2, 0.9)),
            ],
            motions: vec![
                SolverMotion::DUMMY,
                motion(2.0, Quat::from_rotation_x(0.3)),
                motion(0.5, Quat::from_rotation_z(-0.2)),
            ],
            contact,
            x_a: Vec3::new(0.1, -0.5, 0.0),
            x_b: Vec3::new(-0.05, 0.5, 0.1),
        }
    }

    /// The lane kernel (prepare and one rigid, frictionless sweep) against Gauss–Seidel written out
    /// from the geometry: the spread row (the total shared equally, its effective mass measured by
    /// applying a unit spread to copies of the bodies), then point by point, each seeing the bodies as
    /// updated by the points before it. With four points, and with three (a padding point in the lane).
    #[test]
    fn coupled_normal_rows_in_lanes_match_sequential_gauss_seidel_over_the_points() {
        for len in [4, 3] {
            let Case {
                bodies,
                motions,
                mut contact,
                x_a,
                x_b,
            } = case(len);
            // The world's bodies A and B where the manifold was computed (it is not moved).
            let poses = [x_a, x_b].map(|x| {
                let shape = crate::geometry::Shape::cuboid(Vec3::splat(0.5));
                Body::from_desc(&crate::physics::BodyDesc::dynamic(
                    shape,
                    Pose::from_position(x),
                    1.0,
                ))
            });
            (contact.pose_a, contact.pose_b) = (poses[0].pose, poses[1].pose);
            let params = PassParams {
                inv_h: 240.0,
                linear_slop: 0.001,
                spread_row: true,
                symmetric_relax: true,
                symmetric_bias: true,
            };
            let mut fast_bodies = bodies.clone();
            let mut wide = WideContacts::default();
            wide.clear(63);
            let source = LaneSource {
                determinate: true,
                ..rigid_source(2)
            };
            wide.push(0, 0, len, source, false);
            wide.build(std::slice::from_ref(&contact), &poses, &bodies, &motions);
            wide.solve::<false>(
                &mut fast_bodies,
                &params,
                PointOrder::Forward,
                LayerOrder::Up,
            );
            let got: Vec<f32> = (0..len)
                .map(|i| wide.fours[0].hot[0].impulses[i].normal_impulse[0])
                .collect();

            let n = Vec3A::from(contact.manifold.normal);
            let (ma, mb) = (&motions[1], &motions[2]);
            let points = contact.manifold.points();
            let r = |i: usize, x: Vec3| Vec3A::from(points[i].point - x);
            let rn = |i: usize| (r(i, x_a).cross(n), r(i, x_b).cross(n));
            let irn = |i: usize| {
                let (rn_a, rn_b) = rn(i);
                (ma.inv_inertia * rn_a, mb.inv_inertia * rn_b)
            };
            let normal_mass = |i: usize| {
                let ((rn_a, rn_b), (irn_a, irn_b)) = (rn(i), irn(i));
                1.0 / (ma.inv_mass + mb.inv_mass + rn_a.dot(irn_a) + rn_b.dot(irn_b))
            };
            let vn = |ba: &SolverBody, bb: &SolverBody, i: usize| {
                let (rn_a, rn_b) = rn(i);
                n.dot(bb.v - ba.v) + bb.w.dot(rn_b) - ba.w.dot(rn_a)
            };
            let bias = |i: usize| {
                let s = points[i].separation;
                if s > 0.0 { s * params.inv_h } else { 0.0 }
            };
            let apply = |ba: &mut SolverBody, bb: &mut SolverBody, i: usize, delta: f32| {
                let (irn_a, irn_b) = irn(i);
                ba.v -= (ma.inv_mass * delta) * n;
                ba.w -= delta * irn_a;
                bb.v += (mb.inv_mass * delta) * n;
                bb.w += delta * irn_b;
            };
            let mean_vn = |ba: &SolverBody, bb: &SolverBody| {
                (0..len).map(|i| vn(ba, bb, i)).sum::<f32>() / len as f32
            };
            let (mut ba, mut bb) = (bodies[1], bodies[2]);
            let (mut ua, mut ub) = (ba, bb);
            for i in 0..len {
                apply(&mut ua, &mut ub, i, 1.0 / len as f32);
            }
            let response = mean_vn(&ua, &ub) - mean_vn(&ba, &bb);
            let mut lambda = contact.impulses.normal[..len].to_vec();
            let residual = (0..len).map(|i| vn(&ba, &bb, i) + bias(i)).sum::<f32>() / len as f32;
            let min_lambda = lambda.iter().copied().fold(f32::INFINITY, f32::min);
            let spread = (-residual / response).max(-min_lambda * len as f32);
            for (i, l) in lambda.iter_mut().enumerate() {
                *l += spread / len as f32;
                apply(&mut ba, &mut bb, i, spread / len as f32);
            }
            for (i, l) in lambda.iter_mut().enumerate() {
                let total = (*l - normal_mass(i) * (vn(&ba, &bb, i) + bias(i))).max(0.0);
                let delta = total - *l;
                *l = total;
                apply(&mut ba, &mut bb, i, delta);
            }
            // The spread row acted.
            assert!(spread != 0.0, "spread {spread}");
            for (i, (&got, &expected)) in got.iter().zip(&lambda).enumerate() {
                assert!(
                    (got - expected).abs() < 1e-5 * (1.0 + expected),
                    "{len} points, point {i}: {got} vs {expected}"
                );
            }
            // Both regimes: points that push and a speculative one clamped at zero.
            assert!(lambda.iter().any(|&l| l > 0.0) && lambda.contains(&0.0));
            let close = |x: Vec3A, y: Vec3A| (x - y).length() < 1e-5 * (1.0 + y.length());
            assert!(close(fast_bodies[1].v, ba.v) && close(fast_bodies[1].w, ba.w));
            assert!(close(fast_bodies[2].v, bb.v) && close(fast_bodies[2].w, bb.w));
            // The padding lanes wrote nothing but zeros to the static dummy.
            assert_eq!(fast_bodies[0].v, Vec3A::ZERO);
            assert_eq!(fast_bodies[0].w, Vec3A::ZERO);
        }
    }

    /// A rigid row between bodies 1 and `b`, with no preload, nothing anchored and one visit.
    fn rigid_source(b: u32) -> LaneSource {
        LaneSource {
            contact: 0,
            a: 1,
            b,
            softness: ContactSoftness::uniform(Softness::RIGID),
            preload: -1.0,
            spring_preload: -1.0,
            tangent_warm: None,
            pressure_offset: None,
            offset_change: None,
            load_change: 0.0,
            determinate: false,
            struck_pile: StruckPile::Neither,
            touching_spring: false,
            touching_tolerance: 0.0,
            anchored: false,
            symmetric: false,
            deep: false,
            rolling_held: true,
        }
    }

    /// The constraints that get the mass-ratio sweeps share groups only with each other, after
    /// their colour's other groups and before the next colour's, and each constraint's slot
    /// still finds it (`WideContacts::push`).
    #[test]
    fn swept_constraints_are_packed_apart_after_their_colour() {
        let mut wide = WideContacts::default();
        wide.clear(63);
        let swept = [false, true, false, true, false, false];
        for (i, &swept) in swept.iter().enumerate() {
            wide.push(i, 0, 4, rigid_source(i as u32 + 2), swept);
        }
        wide.push(6, 1, 4, rigid_source(8), false);
        let group = |i: usize| wide.slots[i].group;
        let lanes = |i: usize| (group(i), wide.slots[i].lane);
        // Colour 0's four others fill one group, its two swept ones the next, colour 1 the third.
        assert_eq!([0, 2, 4, 5].map(lanes), [(0, 0), (0, 1), (0, 2), (0, 3)]);
        assert_eq!([1, 3].map(lanes), [(1, 0), (1, 1)]);
        assert_eq!(group(6), 2);
        assert_eq!(wide.sources[wide.starts[1] as usize].b, 3);
        let mut groups = Vec::new();
        wide.groups_of(&[1, 3], &mut groups);
        assert_eq!(groups.len(), 1);
        assert_eq!(groups[0].index, wide.schedule[1].index);
    }
}
