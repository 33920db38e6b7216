//! The bodies of a lane group's side, gathered into lanes and scattered back.

use crate::physics::solve::lanes::Vec3x4;
use crate::physics::solve::solver_body::SolverBody;
use crate::physics::solve::wide_contacts::LANES;

/// One side of a lane group: four bodies' velocities and rotations since the step began.
#[derive(Clone, Copy)]
pub(super) struct BodyLanes {
    /// Where the bodies are in the solver's slice: the same values for the scatter as for the gather,
    /// so the compiler drops the scatter's bounds checks, the gather's having passed.
    index: [usize; LANES],
    /// Linear and angular velocities, m/s and rad/s.
    pub v: Vec3x4,
    pub w: Vec3x4,
    /// Rotation since the start of the step (zero unless gathered with deltas; the translations are
    /// read only relative to side A, see [`relative_dp`]).
    pub dtheta: Vec3x4,
}

impl BodyLanes {
    const ZERO: BodyLanes = BodyLanes {
        index: [0; LANES],
        v: Vec3x4::ZERO,
        w: Vec3x4::ZERO,
        dtheta: Vec3x4::ZERO,
    };
}

/// Side A of a group: the gathered bodies, or zeros (unread) when they are all the static dummy.
#[inline(always)]
pub(super) fn gather_a<const DELTAS: bool, const STATIC_A: bool>(
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
pub(super) fn minus_a<const STATIC_A: bool, T: std::ops::Sub<Output = T>>(
    b: T,
    a: impl FnOnce() -> T,
) -> T {
    if STATIC_A { b } else { b - a() }
}

/// Reads the bodies `index` into lanes (velocities only unless `DELTAS`, then their rotations too).
#[inline(always)]
pub(super) fn gather<const DELTAS: bool>(bodies: &[SolverBody], index: &[u32; LANES]) -> BodyLanes {
    let index = index.map(|i| i as usize);
    let b = index.map(|i| bodies[i]);
    BodyLanes {
        index,
        v: Vec3x4::from_lanes([b[0].v, b[1].v, b[2].v, b[3].v]),
        w: Vec3x4::from_lanes([b[0].w, b[1].w, b[2].w, b[3].w]),
        dtheta: if DELTAS {
            Vec3x4::from_lanes([b[0].dtheta, b[1].dtheta, b[2].dtheta, b[3].dtheta])
        } else {
            Vec3x4::ZERO
        },
    }
}

/// B's translation since the step began relative to A's, `b.dp − a.dp` lane by lane (B's own when
/// side A is static): the only way the kernels read the translations. Subtracted before the transpose,
/// one transpose instead of one per side: the same differences, element by element.
#[inline(always)]
pub(super) fn relative_dp<const STATIC_A: bool>(
    bodies: &[SolverBody],
    a: &[u32; LANES],
    b: &[u32; LANES],
) -> Vec3x4 {
    let dp =
        |k: usize| minus_a::<STATIC_A, _>(bodies[b[k] as usize].dp, || bodies[a[k] as usize].dp);
    Vec3x4::from_lanes([dp(0), dp(1), dp(2), dp(3)])
}

/// Writes the lanes' velocities back to the bodies they were gathered from (the only state the
/// velocity passes change). Padding lanes and static sides write the dummy's zeros back to it.
#[inline(always)]
pub(super) fn scatter(bodies: &mut [SolverBody], side: &BodyLanes) {
    for (k, &i) in side.index.iter().enumerate() {
        let body = &mut bodies[i];
        body.v = side.v.lane(k);
        body.w = side.w.lane(k);
    }
}
