//! The velocity kernels of one lane group: warm start and one Gauss–Seidel sweep.
//!
//! They are arithmetic bound (callgrind on the touching pyramid: about 1,250 instructions per group
//! and pass, an eighth of them spills), so where a per-lane select would keep in every lane the
//! value it is given (no rigid row, no touching spring, every lane anchored or visited again, no
//! anchor past its reach or sliding) the kernel tests the whole group once and skips it. Such a
//! skip changes no bit of any result: it is a speed-up only if it keeps every trace as it was,
//! which the hashes of `tests/physics/determinism.rs` pin.
//!
//! # A normal row's law, by its point's separation s
//!
//! | where the point is                          | biased pass                  | leak | relax pass   |
//! |---------------------------------------------|------------------------------|------|--------------|
//! | apart, s > touching tolerance (speculative) | rigid, approach ≤ s/h        | no   | the same     |
//! | in the slop band, −slop ≤ s ≤ tolerance     | soft, no push                | no   | rigid, v ≥ 0 |
//! | … on a touching spring (determinate)        | soft, pushed out at rate·s   | no   | rigid, v ≥ 0 |
//! | past the band, within the soft range        | soft, pushed out past slop   | yes  | rigid, v ≥ 0 |
//! | … on a touching spring                      | soft, pushed out at rate·s   | yes  | rigid, v ≥ 0 |
//! | deeper than the soft range                  | rigid, no push               | no   | rigid, v ≥ 0 |
//!
//! - *Touching tolerance.* A point apart by no more than the rounding of the poses rests touching:
//!   a pile at rest where it was built has its points at zero separation, and flipping between the
//!   speculative row and the band's every step rocked it (`Settings::touching_tolerance`). The
//!   law still jumps there: just past the tolerance a row may close at tolerance/h, just inside it
//!   not at all. Made continuous (approach ≤ (s − tolerance)/h, tried 2026-12-02 over `nudge bench
//!   rest`), the crossed tower kept awake at 2 sub-steps held in 24 copies of 24 (22 as it is),
//!   but on single points the box on balls woken at 2 and 8 sub-steps rolled 70 mm off in five
//!   copies of eight, and on faces alone the heap's copies reshuffled (kept awake at 2, 9 of 16
//!   held, one slumping 274 mm; 10 as it is) and one woken at 4 moved 2.4 mm
//!   (`a_column_beside_a_ball_it_does_not_touch_comes_back_from_a_knock`), so it was not kept.
//! - *No leak inside the band.* The leak −impulse_scale·λ relaxes λ towards the spring force
//!   k·(depth − slop), zero there. With the shock pass removing the approach before positions
//!   integrate, a leaking row never sinks to where its spring holds the load, and λ rests short of
//!   it (half the load of 10 kg on 1 kg), the rest carried by the shock pass, which the friction
//!   bound μ·Σλn does not see: a 1 kg box under 10 kg slid at 40 N, not 54 N
//!   (`a_box_pushed_below_the_friction_limit_of_its_load_holds`).
//! - *No push inside the band*, so any depth in it is a rest, except on a determinate support
//!   (`prepare::preload`, "Determinate loads"), whose spring is centred where it touches, through
//!   the band and past it at one rate, so a knocked column or stack of plates comes back to where
//!   it was built (`columns_woken_by_a_small_ball_settle_back_where_they_slept`,
//!   `thin_plates_woken_by_a_small_ball_settle_back_only_on_touching_springs`). Where the load is
//!   indeterminate the band is what holds a pile's shape. Tried there and not kept (`nudge bench
//!   rest`, 2026-12-01): a push out
//!   everywhere (a pyramid's contacts fought and it came apart; at a tenth of the rate, by each
//!   patch's mean depth, the crossed tower kept awake at 2 sub-steps fell); each patch's mean depth
//!   taken a fifth of the way out in position space after every sub-step (the crossed tower woken
//!   at 2 sub-steps held to 0.75 mm, but the pyramids and walls kept awake moved: 69 mm at 8
//!   sub-steps; stopped 20 µm short of touching, the walls still moved); each point pushed back to
//!   a remembered rest depth (the running-bond wall kept awake at 4 sub-steps moved 16.6 mm); a
//!   push that vanished at both edges of the band (a second rest at its edge: knocked plates
//!   stayed 2.4 mm low).
//! - *Deeper than the soft range* the spring has bottomed out: the row stops approach and carries
//!   any load, pushing nothing, and the position pass removes the depth (`push_out`). Left soft
//!   and leaking, it let go of loads that need more spring than the range: with a 2 cm range a
//!   column of 40 boxes gave way.
//! - *The relax pass* takes back the velocity the biased pass's push added. A speculative row
//!   still catches there, against the separation the positions now have, which is what lands a
//!   dropped box or a sliding one; it also catches a rocking block's landing edge a pass early and
//!   moves that sub-step's weight to it (`testing::corpus::rocking`, where the measured
//!   alternatives are), and two balls sliding past each other a step early
//!   (`testing::corpus::collisions::off_centre_family`).

use glam::{BVec4A, Vec4};

use crate::physics::solve::contact_solver::PassParams;
use crate::physics::solve::lanes::{Vec3x4, sqrt};
use crate::physics::solve::solver_body::SolverBody;
use crate::physics::solve::wide_contacts::body_lanes::{
    gather, gather_a, minus_a, relative_dp, scatter,
};
use crate::physics::solve::wide_contacts::{
    ManifoldLanes, MultiRow, MultiRows, RollingLanes, SideLanes, SoftnessLanes,
};

/// Applies last step's impulses of one group.
#[inline(always)]
pub(super) fn warm_start<const P: usize, const M: usize, const STATIC_A: bool>(
    g: &ManifoldLanes<P, M>,
    side_a: &SideLanes<P>,
    rolling: Option<&RollingLanes>,
    bodies: &mut [SolverBody],
) {
    // Nothing to apply (fresh or speculative contacts that never pushed): skip the gather and scatter.
    let [l1, l2] = g.tangent_impulse;
    let zero = Vec4::ZERO;
    let mut pushed = l1.cmpne(zero) | l2.cmpne(zero) | g.twist_impulse.cmpne(zero);
    for p in &g.impulses {
        pushed |= p.normal_impulse.cmpne(zero);
    }
    if let Some(r) = rolling {
        pushed |= r.impulse[0].cmpne(zero) | r.impulse[1].cmpne(zero) | r.impulse[2].cmpne(zero);
    }
    if !pushed.any() {
        return;
    }
    let a = side_a;
    let mut sa = gather_a::<false, STATIC_A>(bodies, &a.a);
    let mut sb = gather::<false>(bodies, &g.b);
    let mut total = Vec4::ZERO;
    // Side A's sums only when it is dynamic (static: its rows are not read; the sums were unused).
    let mut angular_a = if STATIC_A {
        Vec3x4::ZERO
    } else {
        a.irt_a[0] * l1 + a.irt_a[1] * l2 + a.in_a * g.twist_impulse
    };
    let mut angular_b = g.irt_b[0] * l1 + g.irt_b[1] * l2 + g.in_b * g.twist_impulse;
    if let Some(r) = rolling {
        let [r1, r2, r3] = r.impulse;
        if !STATIC_A {
            angular_a += r.it_a[0] * r1 + r.it_a[1] * r2 + r.it_a[2] * r3;
        }
        angular_b += r.it_b[0] * r1 + r.it_b[1] * r2 + r.it_b[2] * r3;
    }
    for (i, p) in g.impulses.iter().enumerate() {
        total += p.normal_impulse;
        if !STATIC_A {
            angular_a += a.irn_a[i] * p.normal_impulse;
        }
        angular_b += p.irn_b * p.normal_impulse;
    }
    let linear = g.tangents[0] * l1 + g.tangents[1] * l2 + g.normal * total;
    if !STATIC_A {
        sa.v -= linear * a.inv_mass_a;
        sa.w -= angular_a;
        scatter(bodies, &sa);
    }
    sb.v += linear * g.inv_mass_b;
    sb.w += angular_b;
    scatter(bodies, &sb);
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
pub(super) fn solve<
    const P: usize,
    const M: usize,
    const BIAS: bool,
    const STATIC_A: bool,
    const REVERSE: bool,
>(
    g: &mut ManifoldLanes<P, M>,
    side_a: &SideLanes<P>,
    softness: &SoftnessLanes,
    max_normal_impulse: Option<&mut [Vec4; P]>,
    rolling: Option<&mut RollingLanes>,
    bodies: &mut [SolverBody],
    params: &PassParams,
) {
    let a = side_a;
    // The biased passes read the current separations the last relax pass left (see
    // `PointLanes::separation_now`): only the relax pass needs the position deltas.
    let (mut sa, mut sb) = if BIAS {
        (
            gather_a::<false, STATIC_A>(bodies, &a.a),
            gather::<false>(bodies, &g.b),
        )
    } else {
        (
            gather_a::<true, STATIC_A>(bodies, &a.a),
            gather::<true>(bodies, &g.b),
        )
    };
    let n = g.normal;
    let [t1, t2] = g.tangents;
    let anchored = g.anchored.cmpgt(Vec4::ZERO);
    // Everything the relax pass needs of the bodies' position deltas, taken up front so the deltas
    // need not stay live (spilled) through the rows: the separations move with them, and anchored
    // friction and twist read the patch's displacement and turn since the step began.
    let dp = (!BIAS).then(|| relative_dp::<STATIC_A>(bodies, &a.a, &g.b));
    let d_p = dp.map(|dp| n.dot(dp));
    let (moved, turned) = match dp {
        Some(dp) if anchored.any() => {
            let turn = |j: usize| {
                minus_a::<STATIC_A, _>(sb.dtheta.dot(g.rt_b[j]), || sa.dtheta.dot(a.rt_a[j]))
            };
            let moved = [t1.dot(dp) + turn(0), t2.dot(dp) + turn(1)];
            let turned = (P > 1).then(|| n.dot(minus_a::<STATIC_A, _>(sb.dtheta, || sa.dtheta)));
            (Some(moved), turned)
        }
        _ => (None, None),
    };
    let n_dv = n.dot(minus_a::<STATIC_A, _>(sb.v, || sa.v));
    let zero = Vec4::ZERO;

    let touching_tolerance = g.touching_tolerance;
    // The lanes whose supports are springs centred where they touch (see the module docs).
    let springs = g.touching_spring.cmpgt(zero);
    // Per point: current separation, bias, and the row's Δλ = gain·vn + offset.
    let mut gain = [zero; P];
    let mut jacobi = [zero; P];
    let mut old = [zero; P];
    let mut bias_mean = zero;
    for i in 0..P {
        let s = match d_p {
            None => g.points[i].separation_now,
            Some(d_p) => {
                let p = &g.points[i];
                let s = p.separation
                    + d_p
                    + minus_a::<STATIC_A, _>(sb.dtheta.dot(p.rn_b), || sa.dtheta.dot(a.rn_a[i]));
                g.points[i].separation_now = s;
                s
            }
        };
        let p = &g.points[i];
        // The row's law by where the point is: see the module docs' table.
        let speculative = s.cmpgt(touching_tolerance);
        let rigid_bias = s * params.inv_h;
        let (bias, mass_scale, impulse_scale) = if BIAS {
            let depth_past_slop = s + Vec4::splat(params.linear_slop);
            let deep = depth_past_slop.cmplt(-g.soft_depth);
            let rigid = speculative | deep;
            let pushed_past_slop = softness.bias_rate * depth_past_slop.min(zero);
            // Usually no lane of the group has a touching spring: the select would keep the push.
            let soft_bias = if springs.any() {
                let touching_spring = springs & s.cmplt(zero);
                Vec4::select(touching_spring, softness.bias_rate * s, pushed_past_slop)
            } else {
                pushed_past_slop
            };
            let leaks = depth_past_slop.cmplt(zero);
            // Usually every lane's row is soft (touching, not past the soft range): the selects of
            // the rigid rows would keep the soft values, so they go.
            if !rigid.any() {
                (
                    soft_bias,
                    softness.mass_scale,
                    Vec4::select(leaks, softness.impulse_scale, zero),
                )
            } else {
                (
                    Vec4::select(speculative, rigid_bias, Vec4::select(deep, zero, soft_bias)),
                    Vec4::select(rigid, Vec4::ONE, softness.mass_scale),
                    Vec4::select(leaks & !rigid, softness.impulse_scale, zero),
                )
            }
        } else {
            (Vec4::select(speculative, rigid_bias, zero), Vec4::ONE, zero)
        };
        bias_mean += bias * p.mean_weight;
        let vn = n_dv + minus_a::<STATIC_A, _>(sb.w.dot(p.rn_b), || sa.w.dot(a.rn_a[i]));
        old[i] = g.impulses[i].normal_impulse;
        gain[i] = -p.normal_mass * mass_scale;
        // The soft step's leak pulls λ towards the spring's preload, not towards 0 (see
        // `prepare::preload`); without one the load is 0.
        jacobi[i] = gain[i] * (vn + bias) - impulse_scale * (old[i] - p.load);
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
        let multi = &g.multi;
        let mut residual = zero;
        let mut min_old = Vec4::splat(f32::MAX);
        for i in 0..P {
            let p = &g.points[i];
            residual += multi[MultiRow::SpreadWeight(i)] * jacobi[i];
            min_old = min_old.min(Vec4::select(p.mean_weight.cmpgt(zero), old[i], min_old));
        }
        let count = multi[MultiRow::Count];
        let d = if params.spread_row {
            (multi[MultiRow::MeanMass] * residual).max(-min_old * count)
        } else {
            zero
        };
        // Unclamped new totals u_j = start_j + Δλ_j(after the spread and the earlier points), with the
        // earlier points' starts taken out up front so the chain per point is a clamp and multiply-adds.
        let mut start = [zero; P];
        let mut u = [zero; P];
        for j in 0..P {
            let p = &g.points[j];
            start[j] = old[j] + p.mean_weight * d;
            u[j] = start[j] + jacobi[j] + gain[j] * multi[MultiRow::MeanResponse(j)] * d;
        }
        // The k-th point visited, and K_ij = K_ji (stored for i < j). `first` and `later` count visits;
        // i and j are the points visited then.
        let at = |k: usize| if REVERSE { P - 1 - k } else { k };
        let k_ij = |i: usize, j: usize| multi[MultiRow::Coupling(i.min(j), i.max(j))];
        for first in 0..P {
            for later in first + 1..P {
                let (i, j) = (at(first), at(later));
                u[j] -= gain[j] * k_ij(i, j) * start[i];
            }
        }
        for first in 0..P {
            let i = at(first);
            total[i] = u[i].max(zero);
            for later in first + 1..P {
                let j = at(later);
                u[j] += gain[j] * k_ij(i, j) * total[i];
            }
        }
        // The relax pass visits the points again, the other way round (see `contact_solver`, "The
        // symmetric relax"). A point's rigid row from where the others now stand is its row
        // against the velocities before this manifold acted (`jacobi`, from `old`) plus their
        // changes through the couplings: its own change drops out (its gain times K_jj is −1).
        // So it does for a soft row, through its leak: gain·K_jj is −mass_scale, the leak takes
        // impulse_scale of the change, and the two sum to 1 (`softness`). So the biased pass visits
        // back the same way where it is symmetric below 4 sub-steps (see `contact_solver`, "The
        // symmetric biased pass").
        let visit_twice = if BIAS {
            params.symmetric_bias
        } else {
            params.symmetric_relax
        };
        let symmetric = if !visit_twice {
            BVec4A::FALSE
        } else if BIAS {
            // The biased pass only where the statics preload the supports.
            let mut preloaded = g.points[0].load.cmpgt(zero);
            for i in 1..P {
                preloaded |= g.points[i].load.cmpgt(zero);
            }
            g.symmetric.cmpgt(zero) & preloaded
        } else {
            g.symmetric.cmpgt(zero)
        };
        if symmetric.any() {
            let rows = [&old, &jacobi, &gain];
            // Usually every lane is visited again: there the selects would keep nothing, so they go.
            if symmetric.all() {
                visit_back::<P, M, REVERSE>(multi, rows, &mut total, |again, _| again);
            } else {
                let pick = |again, before| Vec4::select(symmetric, again, before);
                visit_back::<P, M, REVERSE>(multi, rows, &mut total, pick);
            }
        }
    }
    let mut pushed = zero;
    let mut total_normal = zero;
    let mut max_normal_impulse = max_normal_impulse;
    for i in 0..P {
        let p = &mut g.impulses[i];
        let delta = total[i] - old[i];
        p.normal_impulse = total[i];
        if let Some(max) = &mut max_normal_impulse {
            max[i] = max[i].max(delta);
        }
        pushed += delta;
        total_normal += total[i];
        if !STATIC_A {
            sa.w -= a.irn_a[i] * delta;
        }
        sb.w += p.irn_b * delta;
    }
    if !STATIC_A {
        sa.v -= n * (a.inv_mass_a * pushed);
    }
    sb.v += n * (g.inv_mass_b * pushed);

    // Friction at the centroid, both tangents from the same velocities, clamped as a pair.
    let max_friction = g.friction * total_normal;
    let dv = minus_a::<STATIC_A, _>(sb.v, || sa.v);
    let vt1 = minus_a::<STATIC_A, _>(t1.dot(dv) + sb.w.dot(g.rt_b[0]), || sa.w.dot(a.rt_a[0]));
    let vt2 = minus_a::<STATIC_A, _>(t2.dot(dv) + sb.w.dot(g.rt_b[1]), || sa.w.dot(a.rt_a[1]));
    let [o1, o2] = g.tangent_impulse;
    let mut u = [o1 - g.tangent_mass[0] * vt1, o2 - g.tangent_mass[1] * vt2];
    if anchored.any() {
        u = anchor_friction::<P, M, BIAS>(g, softness, [vt1, vt2], u, moved, max_friction);
    }
    let [l1, l2] = clamp_to_circle(u[0], u[1], max_friction);
    let max2 = max_friction * max_friction;
    g.tangent_impulse = [l1, l2];
    let (d1, d2) = (l1 - o1, l2 - o2);
    let impulse = t1 * d1 + t2 * d2;
    if !STATIC_A {
        sa.v -= impulse * a.inv_mass_a;
        sa.w -= a.irt_a[0] * d1 + a.irt_a[1] * d2;
    }
    sb.v += impulse * g.inv_mass_b;
    sb.w += g.irt_b[0] * d1 + g.irt_b[1] * d2;

    // Twist about the normal inside the elliptic limit surface (zero radius: a single point, none).
    if P > 1 {
        let twist_radius = g.multi[MultiRow::TwistRadius];
        let twist_mass = g.multi[MultiRow::TwistMass];
        let twisting = twist_radius.cmpgt(zero);
        let used = Vec4::select(
            max_friction.cmpgt(zero),
            ((l1 * l1 + l2 * l2) / max2).min(Vec4::ONE),
            Vec4::ONE,
        );
        let max_twist = max_friction * twist_radius * sqrt(Vec4::ONE - used);
        let w_rel = n.dot(minus_a::<STATIC_A, _>(sb.w, || sa.w));
        let old = g.twist_impulse;
        let mut unclamped = old - twist_mass * w_rel;
        if anchored.any() {
            unclamped = anchor_twist::<P, M, BIAS>(
                g,
                softness,
                [w_rel, twist_mass, twist_radius, max_twist],
                unclamped,
                turned,
            );
        }
        let total = unclamped.max(-max_twist).min(max_twist);
        let total = Vec4::select(twisting, total, old);
        g.twist_impulse = total;
        let delta = total - old;
        if !STATIC_A {
            sa.w -= a.in_a * delta;
        }
        sb.w += g.in_b * delta;
    }
    // Rolling and spinning resistance (one-point groups that have it; see `rolling`).
    if let Some(r) = rolling {
        let w_rel = minus_a::<STATIC_A, _>(sb.w, || sa.w);
        let [o1, o2, o3] = r.impulse;
        let max = r.limit * total_normal;
        let (c1, c2) = (g.tangents[0].dot(w_rel), g.tangents[1].dot(w_rel));
        // While friction holds (its pair stayed inside its circle), the pair's mass with friction
        // held (see `rolling`).
        let [f1, f2] = g.tangent_impulse;
        let friction_holds = (f1 * f1 + f2 * f2).cmplt(max2);
        let [h11, h12, h22] = r.held_mass;
        let (m11, m12, m22) = (
            Vec4::select(friction_holds, h11, r.mass[0]),
            Vec4::select(friction_holds, h12, zero),
            Vec4::select(friction_holds, h22, r.mass[1]),
        );
        let [l1, l2] = clamp_to_circle(o1 - (m11 * c1 + m12 * c2), o2 - (m12 * c1 + m22 * c2), max);
        let l3 = (o3 - r.mass[2] * g.normal.dot(w_rel)).max(-max).min(max);
        r.impulse = [l1, l2, l3];
        let (d1, d2, d3) = (l1 - o1, l2 - o2, l3 - o3);
        if !STATIC_A {
            sa.w -= r.it_a[0] * d1 + r.it_a[1] * d2 + r.it_a[2] * d3;
        }
        sb.w += r.it_b[0] * d1 + r.it_b[1] * d2 + r.it_b[2] * d3;
    }
    if !STATIC_A {
        scatter(bodies, &sa);
    }
    scatter(bodies, &sb);
}

/// The relax pass's second visit of a group's points, the other way round (see [`solve`]), from the
/// totals `total` of the first: `rows` are the points' impulses before the pass, rigid rows' Δλ
/// against the velocities before it and gains; `pick(again, before)` is, lane by lane, the value
/// after the second visit where the lane is visited again, else the value before it.
#[inline(always)]
#[allow(clippy::needless_range_loop)] // i ≠ j index pairs over the points read as the math does
fn visit_back<const P: usize, const M: usize, const REVERSE: bool>(
    multi: &MultiRows<P, M>,
    [old, jacobi, gain]: [&[Vec4; P]; 3],
    total: &mut [Vec4; P],
    pick: impl Fn(Vec4, Vec4) -> Vec4,
) {
    let at = |k: usize| if REVERSE { P - 1 - k } else { k };
    let k_ij = |i: usize, j: usize| multi[MultiRow::Coupling(i.min(j), i.max(j))];
    let mut change: [Vec4; P] = std::array::from_fn(|i| total[i] - old[i]);
    for visit in (0..P).rev() {
        let j = at(visit);
        let mut coupled = Vec4::ZERO;
        for i in (0..P).filter(|&i| i != j) {
            coupled += k_ij(i, j) * change[i];
        }
        let again = (old[j] + jacobi[j] + gain[j] * coupled).max(Vec4::ZERO);
        change[j] = pick(again - old[j], change[j]);
    }
    for i in 0..P {
        total[i] = pick(old[i] + change[i], total[i]);
    }
}

/// The anchored friction pair of one group (see `contact_solver`, "Friction anchors"): given the
/// plain rigid rows' unclamped totals `rigid`, returns the totals in the anchored lanes' law. The
/// relax pass (`moved`: the patch's tangential displacement since the step began, to first order in
/// the bodies' deltas) moves the anchor offsets with the bodies and drags an anchor along where the
/// patch has gone farther than the soft range (`push_out`) from it; the biased pass solves the soft row
/// Δλ = −m·mass_scale·(v_t + bias_rate·offset) − impulse_scale·(λ − λ_statics). Either pass re-anchors
/// a patch whose friction leaves the cone (it slides): the anchor is where the patch is.
#[inline(always)]
fn anchor_friction<const P: usize, const M: usize, const BIAS: bool>(
    g: &mut ManifoldLanes<P, M>,
    softness: &SoftnessLanes,
    vt: [Vec4; 2],
    rigid: [Vec4; 2],
    moved: Option<[Vec4; 2]>,
    max_friction: Vec4,
) -> [Vec4; 2] {
    // The offsets are kept as `now = start + moved`, `moved` the displacement since the step began
    // (which the relax pass measures): moving an anchor moves `start` with it.
    let anchored = g.anchored.cmpgt(Vec4::ZERO);
    if let Some(moved) = moved {
        let [s1, s2] = g.anchor_start;
        let [c1, c2] = [s1 + moved[0], s2 + moved[1]];
        let reach = g.soft_depth;
        let len2 = c1 * c1 + c2 * c2;
        let beyond = len2.cmpgt(reach * reach);
        // Usually no anchor trails beyond reach: the scale would be one in every lane (x·1 = x), so
        // its root and division are skipped.
        g.anchor_now = if beyond.any() {
            let scale = Vec4::select(beyond, reach / sqrt(len2), Vec4::ONE);
            [c1 * scale, c2 * scale]
        } else {
            [c1, c2]
        };
        g.anchor_start = [g.anchor_now[0] - moved[0], g.anchor_now[1] - moved[1]];
    }
    let (start, now) = (g.anchor_start, g.anchor_now);
    let u = if BIAS {
        let [o1, o2] = g.tangent_impulse;
        let [f1, f2] = g.tangent_load;
        let gain = softness.anchor_mass_scale * softness.anchor_bias_rate;
        let soft = |j: usize, o: Vec4, f: Vec4| {
            o - g.tangent_mass[j] * (softness.anchor_mass_scale * vt[j] + gain * now[j])
                - softness.anchor_impulse_scale * (o - f)
        };
        let soft = [soft(0, o1, f1), soft(1, o2, f2)];
        // Usually every lane is anchored: the selects would keep the soft rows.
        if anchored.all() {
            soft
        } else {
            [
                Vec4::select(anchored, soft[0], rigid[0]),
                Vec4::select(anchored, soft[1], rigid[1]),
            ]
        }
    } else {
        rigid
    };
    let slides = (u[0] * u[0] + u[1] * u[1]).cmpgt(max_friction * max_friction) & anchored;
    // Usually nothing slides, and the anchors stay as they are.
    if slides.any() {
        g.anchor_start = [
            Vec4::select(slides, start[0] - now[0], start[0]),
            Vec4::select(slides, start[1] - now[1], start[1]),
        ];
        g.anchor_now = [
            Vec4::select(slides, Vec4::ZERO, now[0]),
            Vec4::select(slides, Vec4::ZERO, now[1]),
        ];
    }
    u
}

/// The anchored twist row of one group, as [`anchor_friction`] for the friction pair: the offset is
/// the turn of B relative to A about the normal since the patch began to stick, its reach the turn
/// that moves the patch's mean radius by the soft range. `row` is (ω_rel, the row's mass, the patch's mean
/// radius, the twist limit); `rigid` the plain row's unclamped total; `turned` (relax pass) the turn
/// since the step began.
#[inline(always)]
fn anchor_twist<const P: usize, const M: usize, const BIAS: bool>(
    g: &mut ManifoldLanes<P, M>,
    softness: &SoftnessLanes,
    row: [Vec4; 4],
    rigid: Vec4,
    turned: Option<Vec4>,
) -> Vec4 {
    let [w_rel, mass, radius, max_twist] = row;
    let anchored = g.anchored.cmpgt(Vec4::ZERO) & radius.cmpgt(Vec4::ZERO);
    if let Some(turned) = turned {
        let reach = g.soft_depth / radius.max(Vec4::splat(f32::MIN_POSITIVE));
        let now = (g.twist_anchor_start + turned).max(-reach).min(reach);
        g.twist_anchor_now = now;
        g.twist_anchor_start = now - turned;
    }
    let now = g.twist_anchor_now;
    let u = if BIAS {
        let old = g.twist_impulse;
        let soft = old
            - mass * softness.anchor_mass_scale * (w_rel + softness.anchor_bias_rate * now)
            - softness.anchor_impulse_scale * old;
        Vec4::select(anchored, soft, rigid)
    } else {
        rigid
    };
    let slides = u.abs().cmpgt(max_twist) & anchored;
    // Usually nothing slides, and the anchor stays as it is.
    if slides.any() {
        let start = g.twist_anchor_start;
        g.twist_anchor_start = Vec4::select(slides, start - now, start);
        g.twist_anchor_now = Vec4::select(slides, Vec4::ZERO, now);
    }
    u
}

/// `(l1, l2)`, lane by lane, scaled back onto the circle of radius `max` where they lie outside it:
/// friction's pair of tangent impulses against Coulomb's bound, and rolling resistance's against its
/// own, are clamped as a vector, not one axis at a time.
#[inline(always)]
fn clamp_to_circle(l1: Vec4, l2: Vec4, max: Vec4) -> [Vec4; 2] {
    let len2 = l1 * l1 + l2 * l2;
    let clamped = len2.cmpgt(max * max);
    if clamped.any() {
        let scale = Vec4::select(clamped, max / sqrt(len2), Vec4::ONE);
        [l1 * scale, l2 * scale]
    } else {
        [l1, l2]
    }
}
