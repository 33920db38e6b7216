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

mod body_lanes;
mod end_of_step;
mod prepare;
mod velocity;

use glam::{Vec3, Vec4};

use super::contact::Contact;
use super::contact_solver::{FrictionRows, PassParams};
use super::lanes::Vec3x4;
use super::softness::Softness;
use super::solver_body::{SolverBody, SolverMotion};
use end_of_step::{restitution, store};
use prepare::prepare;
use velocity::{solve, warm_start};

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

impl<const P: usize> ManifoldLanes<P> {
    /// Lane `k`'s friction rows as scalars.
    fn friction_rows(&self, k: usize) -> FrictionRows {
        FrictionRows {
            normal: self.normal.lane(k),
            tangents: self.tangents.map(|t| t.lane(k)),
            inv_mass_a: self.inv_mass_a[k],
            inv_mass_b: self.inv_mass_b[k],
            friction: self.friction[k],
            rt_a: self.rt_a.map(|v| v.lane(k)),
            rt_b: self.rt_b.map(|v| v.lane(k)),
            irt_a: self.irt_a.map(|v| v.lane(k)),
            irt_b: self.irt_b.map(|v| v.lane(k)),
            tangent_mass: self.tangent_mass.map(|m| m[k]),
        }
    }
}

/// A lane group by kind and index: which `ManifoldLanes` vector and where in it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

    /// Adds the next constraint in solve order (constraint `i` is the i-th pushed), a manifold of `len`
    /// points. `color` is its graph
    /// colour; constraints are packed four to a group while colour, kind and whether body A is static
    /// stay the same, except in colour `serial_color`, whose constraints may share bodies and each get
    /// a group of their own.
    /// [`Self::build`] prepares them.
    pub(crate) fn push(&mut self, color: u32, serial_color: u32, len: usize, source: LaneSource) {
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
            let a_static = group.static_a;
            match group.kind {
                0 => prepare(
                    &mut self.ones[i],
                    a_static,
                    sources,
                    contacts,
                    bodies,
                    motions,
                ),
                1 => prepare(
                    &mut self.twos[i],
                    a_static,
                    sources,
                    contacts,
                    bodies,
                    motions,
                ),
                _ => prepare(
                    &mut self.fours[i],
                    a_static,
                    sources,
                    contacts,
                    bodies,
                    motions,
                ),
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
        let (group, lane) = self.locate(i);
        match group.kind {
            0 => self.ones[group.index as usize].bias_mean[lane],
            1 => self.twos[group.index as usize].bias_mean[lane],
            _ => self.fours[group.index as usize].bias_mean[lane],
        }
    }

    /// Constraint `i`'s friction rows, read out of its lane (after [`Self::build`]).
    pub(crate) fn friction_rows(&self, i: u32) -> FrictionRows {
        let (group, lane) = self.locate(i);
        match group.kind {
            0 => self.ones[group.index as usize].friction_rows(lane),
            1 => self.twos[group.index as usize].friction_rows(lane),
            _ => self.fours[group.index as usize].friction_rows(lane),
        }
    }

    /// Constraint `i`'s group and lane.
    fn locate(&self, i: u32) -> (GroupRef, usize) {
        let slot = self.slots[i as usize];
        (self.schedule[slot.group as usize], slot.lane as usize)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::physics::ContactPoint;
    use crate::physics::contact::CachedImpulses;
    use crate::physics::manifold::Manifold;
    use glam::{Mat3, Mat3A, Quat, Vec3A};

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
            wide.push(0, 63, len, source);
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
