//! The contact solver's velocity kernels, four manifolds at a time.
//!
//! Constraints of one graph colour share no dynamic body, so solving them one after the other or all at
//! once gives the same result (Gauss–Seidel between colours, Jacobi within one). Box2D v3 uses that to
//! solve 4 or 8 constraints in SIMD lanes; here each lane holds one *manifold* of up to four points, and
//! the points of a manifold are visited in turn, as derived in [`super::contact_solver`]: the spread
//! row, then the point rows through their couplings, then friction at the centroid and twist. Every
//! formula is the scalar row's, written lane-wise. (The solver used to run one manifold at a time; the
//! lanes changed only the order of a few floating-point sums, and 0.317 → 0.19 ms per pyramid step.)
//!
//! Manifolds are grouped by colour and by point count into [`ManifoldLanes<P>`] with P = 1 (spheres),
//! 2 (edges) or 4 (faces; a three-point manifold gets an inert fourth point), so a ball's contact does not
//! pay for four points and a face's point chain is unrolled; and by whether body A is static, so a
//! group of bodies resting on a floor reads and writes only its B side. A group is padded with inert
//! lanes (both bodies the static dummy, zero masses and impulses): they compute zeros and write zeros
//! back to the dummy. The per-pass cost of a lane group is one gather of its bodies into [`Vec3x4`]s and
//! one scatter back, against four times fewer arithmetic instructions than four manifolds one by one.
//!
//! The lanes are the only copy of a step's constraints: they are prepared four at a time too
//! ([`WideContacts::build`]), and restitution and storing the impulses for next step's warm start run on
//! them. Only the shock pass, which visits a few constraints in layer order, uses a scalar row
//! (`contact_solver::ShockRow`).

use glam::{Mat3A, Vec3, Vec3A, Vec4};

use super::contact::Contact;
use super::contact_solver::PassParams;
use super::lanes::{Mat3x4, Vec3x4, inverse_or_zero, sqrt};
use super::softness::Softness;
use super::solver_body::{SolverBody, SolverMotion};

/// Manifolds per lane group.
pub(crate) const LANES: usize = 4;

/// Point i of the four manifolds of a lane group (zero in lanes whose manifold has fewer points).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PointLanes {
    /// r × n and I⁻¹(r × n) for each body, m and 1/(kg·m).
    pub rn_a: Vec3x4,
    pub rn_b: Vec3x4,
    pub irn_a: Vec3x4,
    pub irn_b: Vec3x4,
    /// Separation at the start of the step, m.
    pub separation: Vec4,
    /// Effective mass, kg.
    pub normal_mass: Vec4,
    /// Accumulated normal impulse, N·s.
    pub normal_impulse: Vec4,
    /// Largest increment this step, N·s.
    pub max_normal_impulse: Vec4,
    /// Relative normal velocity before the solve, m/s (restitution's reference; left zero in groups
    /// where no lane has restitution).
    pub relative_velocity: Vec4,
    /// 1/len (0 in the padding), K_ii/len and Σ_j K_ij/len: the spread row's weights (see "The spread
    /// row" in `contact_solver`).
    pub mean_weight: Vec4,
    pub spread_weight: Vec4,
    pub mean_response: Vec4,
    /// `coupling[k]`: K between this point i and point j = i + 1 + k, 1/kg.
    pub coupling: [Vec4; 3],
}

/// Four manifolds of one colour with at most `P` points each, in lanes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ManifoldLanes<const P: usize> {
    /// Solver body indices per lane (0, the static dummy, in padding lanes).
    pub a: [u32; LANES],
    pub b: [u32; LANES],
    /// Index of each lane's persistent contact, `u32::MAX` in padding lanes.
    pub contact: [u32; LANES],
    pub normal: Vec3x4,
    pub tangents: [Vec3x4; 2],
    pub inv_mass_a: Vec4,
    pub inv_mass_b: Vec4,
    pub friction: Vec4,
    pub restitution: Vec4,
    /// The lanes' `Softness`.
    pub bias_rate: Vec4,
    pub mass_scale: Vec4,
    pub impulse_scale: Vec4,
    pub rt_a: [Vec3x4; 2],
    pub rt_b: [Vec3x4; 2],
    pub irt_a: [Vec3x4; 2],
    pub irt_b: [Vec3x4; 2],
    pub in_a: Vec3x4,
    pub in_b: Vec3x4,
    pub tangent_mass: [Vec4; 2],
    pub twist_mass: Vec4,
    pub tangent_impulse: [Vec4; 2],
    pub twist_impulse: Vec4,
    pub twist_radius: Vec4,
    /// Mean of the points' biases in the last biased pass, m/s (for the shock pass).
    pub bias_mean: Vec4,
    /// Effective mass of the spread row, kg, and the number of points (0 in padding lanes).
    pub mean_mass: Vec4,
    pub count: Vec4,
    pub points: [PointLanes; P],
}

impl<const P: usize> Default for ManifoldLanes<P> {
    fn default() -> Self {
        Self {
            a: [0; LANES],
            b: [0; LANES],
            contact: [u32::MAX; LANES],
            normal: Vec3x4::ZERO,
            tangents: [Vec3x4::ZERO; 2],
            inv_mass_a: Vec4::ZERO,
            inv_mass_b: Vec4::ZERO,
            friction: Vec4::ZERO,
            restitution: Vec4::ZERO,
            bias_rate: Vec4::ZERO,
            mass_scale: Vec4::ZERO,
            impulse_scale: Vec4::ZERO,
            rt_a: [Vec3x4::ZERO; 2],
            rt_b: [Vec3x4::ZERO; 2],
            irt_a: [Vec3x4::ZERO; 2],
            irt_b: [Vec3x4::ZERO; 2],
            in_a: Vec3x4::ZERO,
            in_b: Vec3x4::ZERO,
            tangent_mass: [Vec4::ZERO; 2],
            twist_mass: Vec4::ZERO,
            tangent_impulse: [Vec4::ZERO; 2],
            twist_impulse: Vec4::ZERO,
            twist_radius: Vec4::ZERO,
            bias_mean: Vec4::ZERO,
            mean_mass: Vec4::ZERO,
            count: Vec4::ZERO,
            points: [PointLanes::default(); P],
        }
    }
}

/// A lane group by kind and index: which `ManifoldLanes` vector and where in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct GroupRef {
    /// 0: one point, 1: two points, 2: four points.
    pub kind: u8,
    /// Every lane's body A is the static dummy (a pile on a floor): the kernels skip side A.
    pub static_a: bool,
    pub index: u32,
}

/// Where a constraint lives: its group and lane.
#[derive(Clone, Copy, Debug, Default)]
struct Slot {
    group: u32,
    lane: u8,
}

/// What preparing one manifold needs besides its contact and the solver bodies.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LaneSource {
    /// Index of the persistent contact.
    pub contact: u32,
    /// Solver body indices (0 = static dummy).
    pub a: u32,
    pub b: u32,
    /// Centres of mass at the start of the step, world, m.
    pub x_a: Vec3,
    pub x_b: Vec3,
    /// How far each body moved since the contact's manifold was computed, as a translation (m) and a
    /// rotation vector (rad); zero for a manifold computed this step. A reused manifold's separations
    /// are brought up to date with them (see [`prepare`]).
    pub moved_a: (Vec3, Vec3),
    pub moved_b: (Vec3, Vec3),
    pub softness: Softness,
}

/// Every constraint of a step in lane groups, with the order the groups are solved in.
#[derive(Debug, Default)]
pub(crate) struct WideContacts {
    ones: Vec<ManifoldLanes<1>>,
    twos: Vec<ManifoldLanes<2>>,
    fours: Vec<ManifoldLanes<4>>,
    /// All groups in solve order (colour by colour).
    schedule: Vec<GroupRef>,
    /// The pushed manifolds in push order; group g holds `sources[starts[g]..starts[g + 1]]`.
    sources: Vec<LaneSource>,
    starts: Vec<u32>,
    /// Groups opened so far of each kind.
    opened: [u32; 3],
    /// Per constraint: its position in `schedule` and its lane.
    slots: Vec<Slot>,
    /// The key of the group being filled (see `push`) and how many lanes it has.
    open_key: u32,
    open_len: usize,
}

/// The group kind of a manifold with `len` points: 0 (one), 1 (two) or 2 (three or four).
#[inline]
pub(crate) fn kind_of(len: usize) -> u8 {
    match len {
        0 | 1 => 0,
        2 => 1,
        _ => 2,
    }
}

impl WideContacts {
    /// Empties the set for a new step.
    pub(crate) fn clear(&mut self) {
        self.schedule.clear();
        self.sources.clear();
        self.starts.clear();
        self.opened = [0; 3];
        self.slots.clear();
        self.open_len = LANES;
    }

    /// Adds the next constraint in solve order, a manifold of `len` points. `color` is its graph
    /// colour; constraints are packed four to a group while colour, kind and whether body A is static
    /// stay the same, except in colour `serial_color`, whose constraints may share bodies and each get
    /// a group of their own.
    /// [`Self::build`] prepares them.
    pub(crate) fn push(
        &mut self,
        index: u32,
        color: u32,
        serial_color: u32,
        len: usize,
        source: LaneSource,
    ) {
        let kind = kind_of(len);
        let static_a = source.a == 0;
        let key = color << 3 | u32::from(kind) << 1 | u32::from(static_a);
        if key != self.open_key || self.open_len == LANES || color == serial_color {
            let opened = &mut self.opened[kind as usize];
            self.schedule.push(GroupRef {
                kind,
                static_a,
                index: *opened,
            });
            *opened += 1;
            self.starts.push(self.sources.len() as u32);
            (self.open_key, self.open_len) = (key, 0);
        }
        debug_assert_eq!(
            self.slots.len(),
            index as usize,
            "constraints come in order"
        );
        self.slots.push(Slot {
            group: self.schedule.len() as u32 - 1,
            lane: self.open_len as u8,
        });
        self.sources.push(source);
        self.open_len += 1;
    }

    /// Prepares every pushed constraint, four at a time.
    pub(crate) fn build(
        &mut self,
        contacts: &[Contact],
        bodies: &[SolverBody],
        motions: &[SolverMotion],
    ) {
        // Filled in place, over last step's groups (a group is a few kilobytes: returning it by value or
        // zeroing it first costs a copy).
        let [ones, twos, fours] = self.opened.map(|count| count as usize);
        self.ones.resize_with(ones, Default::default);
        self.twos.resize_with(twos, Default::default);
        self.fours.resize_with(fours, Default::default);
        let end = self.sources.len() as u32;
        for (g, group) in self.schedule.iter().enumerate() {
            let start = self.starts[g] as usize;
            let stop = self.starts.get(g + 1).copied().unwrap_or(end) as usize;
            let sources = &self.sources[start..stop];
            let i = group.index as usize;
            match group.kind {
                0 => prepare(&mut self.ones[i], sources, contacts, bodies, motions),
                1 => prepare(&mut self.twos[i], sources, contacts, bodies, motions),
                _ => prepare(&mut self.fours[i], sources, contacts, bodies, motions),
            }
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
        let slot = self.slots[i as usize];
        let group = self.schedule[slot.group as usize];
        let lane = slot.lane as usize;
        match group.kind {
            0 => self.ones[group.index as usize].bias_mean[lane],
            1 => self.twos[group.index as usize].bias_mean[lane],
            _ => self.fours[group.index as usize].bias_mean[lane],
        }
    }

    /// Restitution, once per step after the sub-steps: points that approached faster than `threshold`
    /// (m/s) before the solve and pushed during it leave at e times that speed.
    pub(crate) fn apply_restitution(&mut self, bodies: &mut [SolverBody], threshold: f32) {
        for &g in &self.schedule {
            match g.kind {
                0 => restitution(&mut self.ones[g.index as usize], bodies, threshold),
                1 => restitution(&mut self.twos[g.index as usize], bodies, threshold),
                _ => restitution(&mut self.fours[g.index as usize], bodies, threshold),
            }
        }
    }

    /// Copies the accumulated impulses back to the persistent contacts and returns the deepest
    /// penetration at the end of the step, m (≥ 0).
    pub(crate) fn store_impulses(&self, bodies: &[SolverBody], contacts: &mut [Contact]) -> f32 {
        let deepest = store(&self.ones, bodies, contacts)
            .max(store(&self.twos, bodies, contacts))
            .max(store(&self.fours, bodies, contacts));
        deepest.max_element()
    }

    /// Applies last step's impulses (every group).
    pub(crate) fn warm_start(&self, bodies: &mut [SolverBody]) {
        for &g in &self.schedule {
            let i = g.index as usize;
            match (g.kind, g.static_a) {
                (0, false) => warm_start::<1, false>(&self.ones[i], bodies),
                (0, true) => warm_start::<1, true>(&self.ones[i], bodies),
                (1, false) => warm_start::<2, false>(&self.twos[i], bodies),
                (1, true) => warm_start::<2, true>(&self.twos[i], bodies),
                (_, false) => warm_start::<4, false>(&self.fours[i], bodies),
                (_, true) => warm_start::<4, true>(&self.fours[i], bodies),
            }
        }
    }

    /// One Gauss–Seidel sweep over every group in solve order (soft and biased when `BIAS`, else the
    /// rigid relax pass).
    pub(crate) fn solve<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        params: &PassParams,
    ) {
        let schedule = std::mem::take(&mut self.schedule);
        self.solve_groups::<BIAS>(&schedule, bodies, params);
        self.schedule = schedule;
    }

    /// One sweep over `groups`, in the order given.
    pub(crate) fn solve_groups<const BIAS: bool>(
        &mut self,
        groups: &[GroupRef],
        bodies: &mut [SolverBody],
        params: &PassParams,
    ) {
        for &g in groups {
            let i = g.index as usize;
            match (g.kind, g.static_a) {
                (0, false) => solve::<1, BIAS, false>(&mut self.ones[i], bodies, params),
                (0, true) => solve::<1, BIAS, true>(&mut self.ones[i], bodies, params),
                (1, false) => solve::<2, BIAS, false>(&mut self.twos[i], bodies, params),
                (1, true) => solve::<2, BIAS, true>(&mut self.twos[i], bodies, params),
                (_, false) => solve::<4, BIAS, false>(&mut self.fours[i], bodies, params),
                (_, true) => solve::<4, BIAS, true>(&mut self.fours[i], bodies, params),
            }
        }
    }
}

/// Prepares up to four manifolds (`sources`, at most [`LANES`]) of at most `P` points each into `g`,
/// overwriting every field: lanes past `sources.len()` and points past a manifold's length are inert
/// (zero masses, anchors and impulses). The quantities are those of `contact_solver`'s
/// module docs: anchors from the centres of mass, r × n and I⁻¹(r × n), effective masses, the couplings
/// K_ij and the spread row's weights, the friction rows at the centroid and the twist row. (Written to
/// reproduce the former one-manifold-at-a-time preparation bit for bit: traces did not change.)
#[allow(clippy::needless_range_loop)] // point and tangent indices read as the math does
fn prepare<const P: usize>(
    g: &mut ManifoldLanes<P>,
    sources: &[LaneSource],
    contacts: &[Contact],
    bodies: &[SolverBody],
    motions: &[SolverMotion],
) {
    let mut normal = [Vec3A::ZERO; LANES];
    let (mut x_a, mut x_b) = ([Vec3A::ZERO; LANES], [Vec3A::ZERO; LANES]);
    let (mut v_a, mut w_a) = ([Vec3A::ZERO; LANES], [Vec3A::ZERO; LANES]);
    let (mut v_b, mut w_b) = ([Vec3A::ZERO; LANES], [Vec3A::ZERO; LANES]);
    let (mut inertia_a, mut inertia_b) = ([Mat3A::ZERO; LANES], [Mat3A::ZERO; LANES]);
    let mut cached_tangent = [Vec3A::ZERO; LANES];
    let mut point = [[Vec3A::ZERO; LANES]; P];
    // Scalars per lane, whole vectors assigned below (every field of `g` is written: it may hold a
    // group of an earlier step).
    let (mut a, mut b, mut contact_index) = ([0; LANES], [0; LANES], [u32::MAX; LANES]);
    let [
        mut inv_mass_a,
        mut inv_mass_b,
        mut friction,
        mut restitution,
    ] = [[0.0; LANES]; 4];
    let [mut bias_rate, mut mass_scale, mut impulse_scale] = [[0.0; LANES]; 3];
    let [mut twist_impulse, mut count] = [[0.0; LANES]; 2];
    let (mut separation, mut normal_impulse) = ([[0.0; LANES]; P], [[0.0; LANES]; P]);
    let mut moved = [[Vec3A::ZERO; LANES]; 4];
    let mut reused = false;
    for (k, source) in sources.iter().enumerate() {
        let contact = &contacts[source.contact as usize];
        let (ma, mb) = (&motions[source.a as usize], &motions[source.b as usize]);
        let (ba, bb) = (&bodies[source.a as usize], &bodies[source.b as usize]);
        (a[k], b[k], contact_index[k]) = (source.a, source.b, source.contact);
        if source.moved_a != (Vec3::ZERO, Vec3::ZERO) || source.moved_b != (Vec3::ZERO, Vec3::ZERO)
        {
            reused = true;
            moved[0][k] = source.moved_a.0.into();
            moved[1][k] = source.moved_a.1.into();
            moved[2][k] = source.moved_b.0.into();
            moved[3][k] = source.moved_b.1.into();
        }
        normal[k] = contact.manifold.normal.into();
        (x_a[k], x_b[k]) = (source.x_a.into(), source.x_b.into());
        if contact.restitution > 0.0 {
            (v_a[k], w_a[k], v_b[k], w_b[k]) = (ba.v, ba.w, bb.v, bb.w);
        }
        (inertia_a[k], inertia_b[k]) = (ma.inv_inertia, mb.inv_inertia);
        (inv_mass_a[k], inv_mass_b[k]) = (ma.inv_mass, mb.inv_mass);
        (friction[k], restitution[k]) = (contact.friction, contact.restitution);
        bias_rate[k] = source.softness.bias_rate;
        mass_scale[k] = source.softness.mass_scale;
        impulse_scale[k] = source.softness.impulse_scale;
        twist_impulse[k] = contact.impulses.twist;
        cached_tangent[k] = contact.impulses.tangent.into();
        count[k] = contact.manifold.len as f32;
        for (i, mp) in contact.manifold.points().iter().enumerate().take(P) {
            point[i][k] = mp.point.into();
            separation[i][k] = mp.separation;
            normal_impulse[i][k] = contact.impulses.normal[i].max(0.0);
        }
    }
    (g.a, g.b, g.contact) = (a, b, contact_index);
    g.inv_mass_a = Vec4::from_array(inv_mass_a);
    g.inv_mass_b = Vec4::from_array(inv_mass_b);
    g.friction = Vec4::from_array(friction);
    g.restitution = Vec4::from_array(restitution);
    g.bias_rate = Vec4::from_array(bias_rate);
    g.mass_scale = Vec4::from_array(mass_scale);
    g.impulse_scale = Vec4::from_array(impulse_scale);
    g.twist_impulse = Vec4::from_array(twist_impulse);
    g.count = Vec4::from_array(count);
    g.bias_mean = Vec4::ZERO;
    let moved = reused.then(|| moved.map(Vec3x4::from_lanes));
    for (i, row) in g.points.iter_mut().enumerate() {
        row.separation = Vec4::from_array(separation[i]);
        row.normal_impulse = Vec4::from_array(normal_impulse[i]);
        row.max_normal_impulse = Vec4::ZERO;
        row.relative_velocity = Vec4::ZERO;
        row.coupling = [Vec4::ZERO; 3];
    }
    let n = Vec3x4::from_lanes(normal);
    let (x_a, x_b) = (Vec3x4::from_lanes(x_a), Vec3x4::from_lanes(x_b));
    // The pre-solve approach speed is restitution's reference; without restitution it is not needed.
    let bouncy = g.restitution.cmpgt(Vec4::ZERO).any();
    let (v_a, w_a) = (Vec3x4::from_lanes(v_a), Vec3x4::from_lanes(w_a));
    let (v_b, w_b) = (Vec3x4::from_lanes(v_b), Vec3x4::from_lanes(w_b));
    // Side A all static (the dummy's inverse inertia is zero): its angular terms are zero, skip them.
    let static_a = sources.iter().all(|source| source.a == 0);
    let inv_i_a = (!static_a).then(|| Mat3x4::from_lanes(inertia_a));
    let inv_i_b = Mat3x4::from_lanes(inertia_b);
    let times_inv_i_a = |v: Vec3x4| inv_i_a.map_or(Vec3x4::ZERO, |m| m * v);
    let zero = Vec4::ZERO;
    let m_sum = g.inv_mass_a + g.inv_mass_b;
    let inv_len = inverse_or_zero(g.count);

    // Tangent basis (Duff et al. 2017), lane-wise.
    let sign = Vec4::ONE.copysign(n.z);
    let basis_a = -Vec4::ONE / (sign + n.z);
    let basis_b = n.x * n.y * basis_a;
    let tangents = [
        Vec3x4 {
            x: Vec4::ONE + sign * n.x * n.x * basis_a,
            y: sign * basis_b,
            z: -sign * n.x,
        },
        Vec3x4 {
            x: basis_b,
            y: sign + n.y * n.y * basis_a,
            z: -n.y,
        },
    ];

    // Normal rows.
    let mut anchors_a = [Vec3x4::ZERO; P];
    let mut centroid = Vec3x4::ZERO;
    let mut k_ii = [zero; P];
    for i in 0..P {
        let real = g.count.cmpgt(Vec4::splat(i as f32));
        let p = Vec3x4::from_lanes(point[i]);
        let r_a = (p - x_a).masked(real);
        let r_b = (p - x_b).masked(real);
        anchors_a[i] = r_a;
        centroid += r_a;
        let rn_a = r_a.cross(n);
        let rn_b = r_b.cross(n);
        let irn_a = times_inv_i_a(rn_a);
        let irn_b = inv_i_b * rn_b;
        let k = m_sum + rn_a.dot(irn_a) + rn_b.dot(irn_b);
        let row = &mut g.points[i];
        if let Some([dp_a, dtheta_a, dp_b, dtheta_b]) = moved {
            // A reused manifold was computed up to `manifold_reuse_distance` ago: move its separations
            // with the bodies, to first order as the sub-steps do. Left stale, they lag the bodies, and
            // that lag fed a growing sway into tall stacks (a ten-box stack drifted 49 mm in 10 s at
            // 4 iterations, 2.8 mm at the default 1, against 4.9 and 0.3 mm without reuse).
            let shift = n.dot(dp_b - dp_a) + (dtheta_b.dot(rn_b) - dtheta_a.dot(rn_a));
            row.separation += Vec4::select(real, shift, zero);
        }
        (row.rn_a, row.rn_b, row.irn_a, row.irn_b) = (rn_a, rn_b, irn_a, irn_b);
        row.normal_mass = Vec4::select(real, inverse_or_zero(k), zero);
        if bouncy {
            let dv = v_b + w_b.cross(r_b) - v_a - w_a.cross(r_a);
            row.relative_velocity = Vec4::select(real, n.dot(dv), zero);
        }
        row.mean_weight = Vec4::select(real, inv_len, zero);
        k_ii[i] = Vec4::select(real, k, zero);
    }
    // Couplings K_ij (i < j; zero where point j is padding) and the spread row's row sums.
    let mut row_sum = [zero; P];
    for i in 0..P {
        row_sum[i] += k_ii[i];
        g.points[i].spread_weight = k_ii[i] * inv_len;
        for j in i + 1..P {
            let real = g.count.cmpgt(Vec4::splat(j as f32));
            let (pi, pj) = (&g.points[i], &g.points[j]);
            let k_ij = Vec4::select(
                real,
                m_sum + pj.rn_a.dot(pi.irn_a) + pj.rn_b.dot(pi.irn_b),
                zero,
            );
            g.points[i].coupling[j - i - 1] = k_ij;
            row_sum[i] += k_ij;
            row_sum[j] += k_ij;
        }
    }
    let mut mean = [zero; LANES];
    for i in 0..P {
        let p = &mut g.points[i];
        p.mean_response = row_sum[i] * inv_len;
        mean[i] = p.mean_response * p.mean_weight;
    }
    // Summed as `Vec4::element_sum` sums the points of the scalar rows.
    g.mean_mass = inverse_or_zero((mean[0] + mean[1]) + (mean[2] + mean[3]));

    // Friction at the centroid and twist.
    let c_a = centroid * inv_len;
    let c_b = c_a + (x_a - x_b);
    let mut radius = zero;
    for (i, r_a) in anchors_a.iter().enumerate() {
        let real = g.count.cmpgt(Vec4::splat(i as f32));
        radius += Vec4::select(real, (*r_a - c_a).length(), zero);
    }
    g.twist_radius = radius * inv_len;
    for j in 0..2 {
        let t = tangents[j];
        let ra_t = c_a.cross(t);
        let rb_t = c_b.cross(t);
        let ia_t = times_inv_i_a(ra_t);
        let ib_t = inv_i_b * rb_t;
        g.tangent_mass[j] = inverse_or_zero(m_sum + ra_t.dot(ia_t) + rb_t.dot(ib_t));
        (g.rt_a[j], g.rt_b[j], g.irt_a[j], g.irt_b[j]) = (ra_t, rb_t, ia_t, ib_t);
        g.tangent_impulse[j] = Vec3x4::from_lanes(cached_tangent).dot(t);
    }
    g.in_a = times_inv_i_a(n);
    g.in_b = inv_i_b * n;
    g.twist_mass = inverse_or_zero(n.dot(g.in_a) + n.dot(g.in_b));
    g.normal = n;
    g.tangents = tangents;
}

/// One side of a lane group: four bodies' velocities and step deltas.
#[derive(Clone, Copy)]
struct BodyLanes {
    v: Vec3x4,
    w: Vec3x4,
    dp: Vec3x4,
    dtheta: Vec3x4,
}

impl BodyLanes {
    const ZERO: BodyLanes = BodyLanes {
        v: Vec3x4::ZERO,
        w: Vec3x4::ZERO,
        dp: Vec3x4::ZERO,
        dtheta: Vec3x4::ZERO,
    };
}

/// Side A of a group: the gathered bodies, or zeros (unread) when they are all the static dummy.
#[inline(always)]
fn gather_a<const DELTAS: bool, const STATIC_A: bool>(
    bodies: &[SolverBody],
    index: &[u32; LANES],
) -> BodyLanes {
    if STATIC_A {
        BodyLanes::ZERO
    } else {
        gather::<DELTAS>(bodies, index)
    }
}

/// `b − a()`, or `b` when side A is static (its terms are exactly zero; skipping them keeps the
/// arithmetic of the general kernel).
#[inline(always)]
fn minus_a<const STATIC_A: bool, T: std::ops::Sub<Output = T>>(b: T, a: impl FnOnce() -> T) -> T {
    if STATIC_A { b } else { b - a() }
}

/// Reads the bodies `index` into lanes (velocities only unless `DELTAS`).
#[inline(always)]
fn gather<const DELTAS: bool>(bodies: &[SolverBody], index: &[u32; LANES]) -> BodyLanes {
    let b = index.map(|i| bodies[i as usize]);
    BodyLanes {
        v: Vec3x4::from_lanes([b[0].v, b[1].v, b[2].v, b[3].v]),
        w: Vec3x4::from_lanes([b[0].w, b[1].w, b[2].w, b[3].w]),
        dp: if DELTAS {
            Vec3x4::from_lanes([b[0].dp, b[1].dp, b[2].dp, b[3].dp])
        } else {
            Vec3x4::ZERO
        },
        dtheta: if DELTAS {
            Vec3x4::from_lanes([b[0].dtheta, b[1].dtheta, b[2].dtheta, b[3].dtheta])
        } else {
            Vec3x4::ZERO
        },
    }
}

/// Writes the lanes' velocities back (the only state the velocity passes change). Padding lanes and
/// static sides write the dummy's zeros back to it.
#[inline(always)]
fn scatter(bodies: &mut [SolverBody], index: &[u32; LANES], side: &BodyLanes) {
    for (k, &i) in index.iter().enumerate() {
        let body = &mut bodies[i as usize];
        body.v = side.v.lane(k);
        body.w = side.w.lane(k);
    }
}

/// Applies last step's impulses of one group.
#[inline(always)]
fn warm_start<const P: usize, const STATIC_A: bool>(
    g: &ManifoldLanes<P>,
    bodies: &mut [SolverBody],
) {
    // Nothing to apply (fresh or speculative contacts that never pushed): skip the gather and scatter.
    let [l1, l2] = g.tangent_impulse;
    let zero = Vec4::ZERO;
    let mut pushed = l1.cmpne(zero) | l2.cmpne(zero) | g.twist_impulse.cmpne(zero);
    for p in &g.points {
        pushed |= p.normal_impulse.cmpne(zero);
    }
    if !pushed.any() {
        return;
    }
    let mut sa = gather_a::<false, STATIC_A>(bodies, &g.a);
    let mut sb = gather::<false>(bodies, &g.b);
    let mut total = Vec4::ZERO;
    let mut angular_a = g.irt_a[0] * l1 + g.irt_a[1] * l2 + g.in_a * g.twist_impulse;
    let mut angular_b = g.irt_b[0] * l1 + g.irt_b[1] * l2 + g.in_b * g.twist_impulse;
    for p in &g.points {
        total += p.normal_impulse;
        angular_a += p.irn_a * p.normal_impulse;
        angular_b += p.irn_b * p.normal_impulse;
    }
    let linear = g.tangents[0] * l1 + g.tangents[1] * l2 + g.normal * total;
    if !STATIC_A {
        sa.v -= linear * g.inv_mass_a;
        sa.w -= angular_a;
        scatter(bodies, &g.a, &sa);
    }
    sb.v += linear * g.inv_mass_b;
    sb.w += angular_b;
    scatter(bodies, &g.b, &sb);
}

/// One Gauss–Seidel sweep over one group: normal rows (soft and biased when `BIAS`, else rigid), then
/// the centroid friction pair clamped to the circle of radius μ·Σλn, then twist inside the elliptic
/// limit of radius μ·Σλn·twist_radius.
///
/// The normal rows of a manifold are solved point after point, but in the velocity space of the rows
/// (Catto's block solver idea without the block): the impulse increment Δλ_i at point i changes point
/// j's normal velocity by K_ji·Δλ_i (the precomputed couplings), so
///
/// ```text
/// vn = normal velocities of all points, bias, mass and impulse scales
/// spread row: d = max(m_mean · mean_j(K_jj·Δ_j), −len·min λ);  λ += d/len;  vn += mean_response·d
/// for i in points: λ_i' = max(λ_i + gain_i·vn_i + offset_i, 0);  vn += coupling_i · (λ_i' − λ_i)
/// apply Σ(λ' − λ_start) to the bodies once
/// ```
/// (with gain = −m·mass_scale, offset = gain·bias − impulse_scale·λ_start, Δ_j = gain_j·vn_j +
/// offset_j; see `contact_solver` for the spread row). After the spread row this is exactly sequential
/// Gauss–Seidel over the points (the velocity is linear in the impulses), with a dependency chain per
/// point of a few operations instead of a full body update. A one-point manifold has no spread row.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // i < j index pairs over the points read as the math does
fn solve<const P: usize, const BIAS: bool, const STATIC_A: bool>(
    g: &mut ManifoldLanes<P>,
    bodies: &mut [SolverBody],
    params: &PassParams,
) {
    let mut sa = gather_a::<true, STATIC_A>(bodies, &g.a);
    let mut sb = gather::<true>(bodies, &g.b);
    let n = g.normal;
    let d_p = n.dot(minus_a::<STATIC_A, _>(sb.dp, || sa.dp));
    let n_dv = n.dot(minus_a::<STATIC_A, _>(sb.v, || sa.v));
    let zero = Vec4::ZERO;

    // Per point: current separation, bias, and the row's Δλ = gain·vn + offset.
    let mut gain = [zero; P];
    let mut jacobi = [zero; P];
    let mut old = [zero; P];
    let mut bias_mean = zero;
    for i in 0..P {
        let p = &g.points[i];
        let s = p.separation
            + d_p
            + minus_a::<STATIC_A, _>(sb.dtheta.dot(p.rn_b), || sa.dtheta.dot(p.rn_a));
        let speculative = s.cmpgt(zero);
        let rigid_bias = s * params.inv_h;
        let (bias, mass_scale, impulse_scale) = if BIAS {
            // No leak inside the slop band. The leak −impulse_scale·λ relaxes λ towards the spring
            // force k·(depth − slop), which is zero there. Without the shock pass a resting contact
            // sinks past the slop until the spring holds the load. With it, the shock pass removes
            // the approach (unrecorded) before positions integrate, so the contact never sinks: the
            // leak drains λ every sub-step and a heavy-on-light row refills only r = mass_scale ·
            // m_eff / m_upper of the deficit, so λ rests at r/(r + impulse_scale) of the load (0.5 for
            // 10 kg on 1 kg, 0.85 for equal boxes). The shock pass carried the rest, with no reaction
            // on the lower body and invisible to the friction bound μ·Σλn: friction at that contact
            // and at every support below it was too weak (a 1 kg box under 10 kg slid at 40 N, not
            // 54 N). Kept, λ converges to the full load and the shock pass idles at rest.
            let depth_past_slop = s + Vec4::splat(params.linear_slop);
            let soft_bias =
                (g.bias_rate * depth_past_slop.min(zero)).max(Vec4::splat(-params.max_push_out));
            let leaks = depth_past_slop.cmplt(zero) & !speculative;
            (
                Vec4::select(speculative, rigid_bias, soft_bias),
                Vec4::select(speculative, Vec4::ONE, g.mass_scale),
                Vec4::select(leaks, g.impulse_scale, zero),
            )
        } else {
            (Vec4::select(speculative, rigid_bias, zero), Vec4::ONE, zero)
        };
        bias_mean += bias * p.mean_weight;
        let vn = n_dv + minus_a::<STATIC_A, _>(sb.w.dot(p.rn_b), || sa.w.dot(p.rn_a));
        old[i] = p.normal_impulse;
        gain[i] = -p.normal_mass * mass_scale;
        jacobi[i] = gain[i] * (vn + bias) - impulse_scale * old[i];
    }
    if BIAS {
        g.bias_mean = bias_mean;
    }

    let mut total = [zero; P];
    if P == 1 {
        total[0] = (old[0] + jacobi[0]).max(zero);
    } else {
        // The spread row: one increment d of the total against the rows' mean residual, shared
        // equally, clamped so no λ turns negative (padding points weigh nothing).
        let mut residual = zero;
        let mut min_old = Vec4::splat(f32::MAX);
        for i in 0..P {
            let p = &g.points[i];
            residual += p.spread_weight * jacobi[i];
            min_old = min_old.min(Vec4::select(p.mean_weight.cmpgt(zero), old[i], min_old));
        }
        let d = (g.mean_mass * residual).max(-min_old * g.count);
        // Unclamped new totals u_j = start_j + Δλ_j(after the spread and the earlier points), with the
        // earlier points' starts taken out up front so the chain per point is a clamp and multiply-adds.
        let mut start = [zero; P];
        let mut u = [zero; P];
        for j in 0..P {
            let p = &g.points[j];
            start[j] = old[j] + p.mean_weight * d;
            u[j] = start[j] + jacobi[j] + gain[j] * p.mean_response * d;
        }
        for i in 0..P {
            for j in i + 1..P {
                u[j] -= gain[j] * g.points[i].coupling[j - i - 1] * start[i];
            }
        }
        for i in 0..P {
            total[i] = u[i].max(zero);
            for j in i + 1..P {
                u[j] += gain[j] * g.points[i].coupling[j - i - 1] * total[i];
            }
        }
    }
    let mut pushed = zero;
    let mut total_normal = zero;
    for i in 0..P {
        let p = &mut g.points[i];
        let delta = total[i] - old[i];
        p.normal_impulse = total[i];
        p.max_normal_impulse = p.max_normal_impulse.max(delta);
        pushed += delta;
        total_normal += total[i];
        if !STATIC_A {
            sa.w -= p.irn_a * delta;
        }
        sb.w += p.irn_b * delta;
    }
    if !STATIC_A {
        sa.v -= n * (g.inv_mass_a * pushed);
    }
    sb.v += n * (g.inv_mass_b * pushed);

    // Friction at the centroid, both tangents from the same velocities, clamped as a pair.
    let max_friction = g.friction * total_normal;
    let [t1, t2] = g.tangents;
    let dv = minus_a::<STATIC_A, _>(sb.v, || sa.v);
    let vt1 = minus_a::<STATIC_A, _>(t1.dot(dv) + sb.w.dot(g.rt_b[0]), || sa.w.dot(g.rt_a[0]));
    let vt2 = minus_a::<STATIC_A, _>(t2.dot(dv) + sb.w.dot(g.rt_b[1]), || sa.w.dot(g.rt_a[1]));
    let [o1, o2] = g.tangent_impulse;
    let mut l1 = o1 - g.tangent_mass[0] * vt1;
    let mut l2 = o2 - g.tangent_mass[1] * vt2;
    let len2 = l1 * l1 + l2 * l2;
    let max2 = max_friction * max_friction;
    let clamped = len2.cmpgt(max2);
    if clamped.any() {
        let scale = Vec4::select(clamped, max_friction / sqrt(len2), Vec4::ONE);
        l1 *= scale;
        l2 *= scale;
    }
    g.tangent_impulse = [l1, l2];
    let (d1, d2) = (l1 - o1, l2 - o2);
    let impulse = t1 * d1 + t2 * d2;
    if !STATIC_A {
        sa.v -= impulse * g.inv_mass_a;
        sa.w -= g.irt_a[0] * d1 + g.irt_a[1] * d2;
    }
    sb.v += impulse * g.inv_mass_b;
    sb.w += g.irt_b[0] * d1 + g.irt_b[1] * d2;

    // Twist about the normal inside the elliptic limit surface (zero radius: a single point, none).
    if P > 1 {
        let twisting = g.twist_radius.cmpgt(zero);
        let used = Vec4::select(
            max_friction.cmpgt(zero),
            ((l1 * l1 + l2 * l2) / max2).min(Vec4::ONE),
            Vec4::ONE,
        );
        let max_twist = max_friction * g.twist_radius * sqrt(Vec4::ONE - used);
        let w_rel = n.dot(minus_a::<STATIC_A, _>(sb.w, || sa.w));
        let old = g.twist_impulse;
        let total = (old - g.twist_mass * w_rel).max(-max_twist).min(max_twist);
        let total = Vec4::select(twisting, total, old);
        g.twist_impulse = total;
        let delta = total - old;
        if !STATIC_A {
            sa.w -= g.in_a * delta;
        }
        sb.w += g.in_b * delta;
    }
    if !STATIC_A {
        scatter(bodies, &g.a, &sa);
    }
    scatter(bodies, &g.b, &sb);
}

/// Restitution of one group: the scalar rule of `WideContacts::apply_restitution` in lanes, point by
/// point.
fn restitution<const P: usize>(
    g: &mut ManifoldLanes<P>,
    bodies: &mut [SolverBody],
    threshold: f32,
) {
    let zero = Vec4::ZERO;
    if !g.restitution.cmpgt(zero).any() {
        return;
    }
    let mut sa = gather::<false>(bodies, &g.a);
    let mut sb = gather::<false>(bodies, &g.b);
    let n = g.normal;
    for p in &mut g.points {
        let bounces = p.relative_velocity.cmple(Vec4::splat(-threshold))
            & p.max_normal_impulse.cmpne(zero)
            & g.restitution.cmpgt(zero);
        if !bounces.any() {
            continue;
        }
        let vn = n.dot(sb.v - sa.v) + (sb.w.dot(p.rn_b) - sa.w.dot(p.rn_a));
        let delta = -p.normal_mass * (vn + g.restitution * p.relative_velocity);
        let total = Vec4::select(
            bounces,
            (p.normal_impulse + delta).max(zero),
            p.normal_impulse,
        );
        let delta = total - p.normal_impulse;
        p.normal_impulse = total;
        sa.v -= n * (g.inv_mass_a * delta);
        sa.w -= p.irn_a * delta;
        sb.v += n * (g.inv_mass_b * delta);
        sb.w += p.irn_b * delta;
    }
    scatter(bodies, &g.a, &sa);
    scatter(bodies, &g.b, &sb);
}

/// Stores the impulses of `groups` in their contacts; returns the deepest penetration per lane, m.
fn store<const P: usize>(
    groups: &[ManifoldLanes<P>],
    bodies: &[SolverBody],
    contacts: &mut [Contact],
) -> Vec4 {
    let mut deepest = Vec4::ZERO;
    for g in groups {
        let sa = gather::<true>(bodies, &g.a);
        let sb = gather::<true>(bodies, &g.b);
        let d_p = g.normal.dot(sb.dp - sa.dp);
        for p in &g.points {
            let s = p.separation + d_p + (sb.dtheta.dot(p.rn_b) - sa.dtheta.dot(p.rn_a));
            let real = p.mean_weight.cmpgt(Vec4::ZERO);
            deepest = deepest.max(Vec4::select(real, -s, Vec4::ZERO));
        }
        for (k, &contact) in g.contact.iter().enumerate() {
            if contact == u32::MAX {
                continue;
            }
            let cached = &mut contacts[contact as usize].impulses;
            let (l1, l2) = (g.tangent_impulse[0][k], g.tangent_impulse[1][k]);
            cached.tangent = (l1 * g.tangents[0].lane(k) + l2 * g.tangents[1].lane(k)).into();
            cached.twist = g.twist_impulse[k];
            for (i, p) in g.points.iter().enumerate().take(g.count[k] as usize) {
                cached.normal[i] = p.normal_impulse[k];
            }
        }
    }
    deepest
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::physics::ContactPoint;
    use crate::physics::contact::CachedImpulses;
    use crate::physics::manifold::Manifold;
    use glam::{Mat3, Quat};

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
            pose_a: Pose::IDENTITY,
            pose_b: Pose::IDENTITY,
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
                contact,
                x_a,
                x_b,
            } = case(len);
            let params = PassParams {
                inv_h: 240.0,
                max_push_out: 3.0,
                linear_slop: 0.001,
            };
            let mut fast_bodies = bodies.clone();
            let mut wide = WideContacts::default();
            wide.clear();
            let source = LaneSource {
                contact: 0,
                a: 1,
                b: 2,
                x_a,
                x_b,
                moved_a: (Vec3::ZERO, Vec3::ZERO),
                moved_b: (Vec3::ZERO, Vec3::ZERO),
                softness: Softness::RIGID,
            };
            wide.push(0, 0, 63, len, source);
            wide.build(std::slice::from_ref(&contact), &bodies, &motions);
            wide.solve::<false>(&mut fast_bodies, &params);
            let got: Vec<f32> = (0..len)
                .map(|i| wide.fours[0].points[i].normal_impulse[0])
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
}
