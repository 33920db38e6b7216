//! Preparing four manifolds at a time: anchors, effective masses, couplings and friction rows in lanes.

use glam::{BVec4A, Mat3A, Vec3A, Vec4};

use crate::physics::Body;
use crate::physics::narrow::contact::Contact;
use crate::physics::solve::lanes::{Mat3x4, Vec3x4, inverse_or_zero};
use crate::physics::solve::push_out::SOFT_DEPTH;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::solve::wide_contacts::{
    ColdLanes, LANES, LaneSource, ManifoldLanes, MultiRow, SideLanes, StruckPile,
};

/// Prepares up to four manifolds (`sources`, at most [`LANES`]) of at most `P` points each into the
/// group's parts `g`, `side_a` and `cold` (`poses`: the world's bodies, for their centres and how far
/// they moved since each manifold was computed), overwriting every field: lanes past `sources.len()` and
/// points past a manifold's length are inert (zero masses, anchors and impulses). `STATIC_A`: every
/// lane's body A is the static dummy (a constant, as in the kernels: a version for each side A, without
/// the branches on it, took 3 % fewer instructions). The quantities are those of `contact_solver`'s
/// module docs: anchors from the centres of mass, r × n and I⁻¹(r × n), effective masses, the couplings
/// K_ij and the spread row's weights, the friction rows at the centroid and the twist row. (Written to
/// reproduce the former one-manifold-at-a-time preparation bit for bit: traces did not change.) The
/// softness is not here: it is the group's, kept in `WideContacts`. Returns whether any lane has
/// restitution.
#[allow(clippy::needless_range_loop)] // point and tangent indices read as the math does
#[allow(clippy::too_many_arguments)] // the three parts of a group, and what they are prepared from
pub(super) fn prepare<const P: usize, const M: usize, const STATIC_A: bool>(
    g: &mut ManifoldLanes<P, M>,
    side_a: &mut SideLanes<P>,
    cold: &mut ColdLanes<P>,
    sources: &[LaneSource],
    contacts: &[Contact],
    poses: &[Body],
    bodies: &[SolverBody],
    motions: &[SolverMotion],
) -> bool {
    let mut normal = [Vec3A::ZERO; LANES];
    let (mut x_a, mut x_b) = ([Vec3A::ZERO; LANES], [Vec3A::ZERO; LANES]);
    let mut cached_tangent = [Vec3A::ZERO; LANES];
    let [mut anchor, mut demand] = [[Vec3A::ZERO; LANES]; 2];
    let mut anchored = [0.0f32; LANES];
    let mut touching_spring = [0.0f32; LANES];
    let mut touching_tolerance = [0.0f32; LANES];
    // Padding lanes keep the widest range: their zero separations are never deep.
    let mut soft_depth = [SOFT_DEPTH; LANES];
    let mut symmetric = [0.0f32; LANES];
    let mut point = [[Vec3A::ZERO; LANES]; P];
    // Scalars per lane, whole vectors assigned below (every field of `g` is written: it may hold a
    // group of an earlier step).
    let (mut a, mut b, mut contact_index) = ([0; LANES], [0; LANES], [u32::MAX; LANES]);
    let [mut friction, mut restitution] = [[0.0; LANES]; 2];
    let [mut twist_impulse, mut twist_radius, mut twist_anchor] = [[0.0; LANES]; 3];
    let (mut separation, mut normal_impulse) = ([[0.0; LANES]; P], [[0.0; LANES]; P]);
    let mut load = [[0.0; LANES]; P];
    let mut approach = [Vec3A::ZERO; LANES];
    let mut moment = [Vec3A::ZERO; LANES];
    let ([mut spread, mut even], mut count) = ([[false; LANES]; 2], [0.0; LANES]);
    let mut struck_pile = [StruckPile::Neither; LANES];
    for (k, source) in sources.iter().enumerate() {
        let contact = &contacts[source.contact as usize];
        (a[k], b[k], contact_index[k]) = (source.a, source.b, source.contact);
        struck_pile[k] = source.struck_pile;
        let (pose_a, pose_b) = (
            &poses[contact.a as usize].pose,
            &poses[contact.b as usize].pose,
        );
        normal[k] = contact.manifold.normal.into();
        soft_depth[k] = contact.soft_depth;
        approach[k] = contact.manifold.approach.into();
        (x_a[k], x_b[k]) = (pose_a.position.into(), pose_b.position.into());
        (friction[k], restitution[k]) = (contact.friction, contact.restitution);
        twist_impulse[k] = contact.impulses.twist;
        if source.symmetric {
            symmetric[k] = 1.0;
        }
        if source.anchored {
            anchored[k] = 1.0;
            anchor[k] = contact.impulses.anchor.into();
            twist_anchor[k] = contact.impulses.twist_anchor;
            if source.determinate {
                demand[k] = contact.impulses.fed_tangent.into();
            }
        }
        twist_radius[k] = contact.manifold.patch.mean_radius;
        cached_tangent[k] = source
            .tangent_warm
            .unwrap_or(contact.impulses.tangent)
            .into();
        // The group's kind has room for every point (`kind_of`); bounded by `P`, the points need no
        // bounds checks.
        let len = contact.manifold.len.min(P);
        count[k] = len as f32;
        for (i, mp) in contact.manifold.points[..len].iter().enumerate() {
            point[i][k] = mp.point.into();
            separation[i][k] = mp.separation;
            normal_impulse[i][k] = contact.impulses.normal[i].max(0.0);
        }
        // Where statics determine the load, or the contact carried nothing yet, the warm start is
        // rescaled to the preload, shared by the points as last step's impulses were (the torque
        // balance the solver found), evenly if there were none; elsewhere it stays the solver's own
        // (see `prepare::preload`, "Determinate loads"), moved towards a changed preload in the
        // same shares ("Load changes"). The spring's rest
        // force is shared evenly: had it followed last step's shares, a point that carried more
        // would rest carrying more, and a box would have no stiffness against rocking.
        if source.preload >= 0.0 {
            touching_tolerance[k] = source.touching_tolerance;
            if source.touching_spring {
                touching_spring[k] = 1.0;
            }
            let warm: f32 = (0..len).map(|i| normal_impulse[i][k]).sum();
            let scale = if source.load_change != 0.0 && warm > 0.0 {
                fed_warm_start(warm, source.load_change, source.preload) / warm
            } else {
                1.0
            };
            for i in 0..len {
                load[i][k] = source.spring_preload / len as f32;
                if !source.determinate && warm > 0.0 {
                    normal_impulse[i][k] *= scale;
                    continue;
                }
                normal_impulse[i][k] = if warm > 0.0 {
                    normal_impulse[i][k] * (source.preload / warm)
                } else {
                    source.preload / len as f32
                };
            }
        }
        // The moment its pressure must carry, set (a body on one determinate support) or changed
        // by what the statics ask more than last step (elsewhere on a pile of level faces): spread
        // below, four lanes at a time.
        match (source.pressure_offset, source.offset_change) {
            (Some(offset), _) => (moment[k], spread[k], even[k]) = (offset.into(), true, true),
            (None, Some(change)) => (moment[k], spread[k]) = (change.into(), true),
            (None, None) => {}
        }
    }
    // The points in lanes, read by the spread and the normal rows alike.
    let point: [Vec3x4; P] = std::array::from_fn(|i| Vec3x4::from_lanes(point[i]));
    if spread.contains(&true) {
        spread_pressure(
            &mut normal_impulse,
            &point,
            Vec4::from_array(count),
            Vec3x4::from_lanes(moment),
            Vec3x4::from_lanes(normal),
            BVec4A::from_array(even),
            BVec4A::from_array(spread),
        );
    }
    (side_a.a, g.b, cold.contact) = (a, b, contact_index);
    // The mass properties by solver index: a padding lane's bodies are the dummy, whose inverse mass
    // and inertia are the zeros an inert lane needs, as are a struck pile's (`preload::blows`).
    let inv_mass = |side: &[u32; LANES], pile: StruckPile| {
        Vec4::from_array(std::array::from_fn(|k| {
            let immovable = struck_pile[k] == pile;
            if immovable {
                0.0
            } else {
                motions[side[k] as usize].inv_mass
            }
        }))
    };
    side_a.inv_mass_a = inv_mass(&a, StruckPile::A);
    g.inv_mass_b = inv_mass(&b, StruckPile::B);
    g.friction = Vec4::from_array(friction);
    cold.restitution = Vec4::from_array(restitution);
    g.twist_impulse = Vec4::from_array(twist_impulse);
    g.bias_mean = Vec4::ZERO;
    cold.count = Vec4::from_array(count);
    for i in 0..P {
        g.points[i].separation = Vec4::from_array(separation[i]);
        g.impulses[i].normal_impulse = Vec4::from_array(normal_impulse[i]);
        g.points[i].load = Vec4::from_array(load[i]);
    }
    cold.max_normal_impulse = [Vec4::ZERO; P];
    cold.step_impulse = [Vec4::ZERO; P];
    cold.relative_velocity = [Vec4::ZERO; P];
    let n = Vec3x4::from_lanes(normal);
    let (x_a, x_b) = (Vec3x4::from_lanes(x_a), Vec3x4::from_lanes(x_b));
    // B's anchors are taken where B was at the moment of impact relative to A (zero unless the
    // narrow phase found the contact at its time of impact): x_b shifted by the approach.
    let x_b = x_b + Vec3x4::from_lanes(approach);
    // The pre-solve approach speed is restitution's reference; without restitution it is not needed.
    let bouncy = cold.restitution.cmpgt(Vec4::ZERO).any();
    // The velocities of the lanes with restitution (zero in the others).
    let velocities = |side: &[u32; LANES], of: fn(&SolverBody) -> Vec3A| {
        Vec3x4::from_lanes(std::array::from_fn(|k| {
            if restitution[k] > 0.0 {
                of(&bodies[side[k] as usize])
            } else {
                Vec3A::ZERO
            }
        }))
    };
    let [v_a, w_a, v_b, w_b] = if bouncy {
        [
            velocities(&a, |body| body.v),
            velocities(&a, |body| body.w),
            velocities(&b, |body| body.v),
            velocities(&b, |body| body.w),
        ]
    } else {
        [Vec3x4::ZERO; 4]
    };
    // Side A all static (the dummy's inverse inertia is zero): its angular terms are zero, skip them.
    let inertia = |side: &[u32; LANES], pile: StruckPile| {
        Mat3x4::from_lanes(std::array::from_fn(|k| {
            let immovable = struck_pile[k] == pile;
            if immovable {
                Mat3A::ZERO
            } else {
                motions[side[k] as usize].inv_inertia
            }
        }))
    };
    let inv_i_a = (!STATIC_A).then(|| inertia(&a, StruckPile::A));
    let inv_i_b = inertia(&b, StruckPile::B);
    let times_inv_i_a = |v: Vec3x4| inv_i_a.map_or(Vec3x4::ZERO, |m| m * v);
    let zero = Vec4::ZERO;
    let m_sum = side_a.inv_mass_a + g.inv_mass_b;
    let inv_len = inverse_or_zero(cold.count);

    let tangents = tangent_basis(n);

    // Normal rows.
    let mut mean_weight = [zero; P];
    let mut centroid = Vec3x4::ZERO;
    let mut k_ii = [zero; P];
    for i in 0..P {
        let real = cold.count.cmpgt(Vec4::splat(i as f32));
        let p = point[i];
        let r_a = (p - x_a).masked(real);
        let r_b = (p - x_b).masked(real);
        centroid += r_a;
        let rn_a = r_a.cross(n);
        let rn_b = r_b.cross(n);
        let irn_a = times_inv_i_a(rn_a);
        let irn_b = inv_i_b * rn_b;
        let k = m_sum + rn_a.dot(irn_a) + rn_b.dot(irn_b);
        let row = &mut g.points[i];
        // The bodies have not moved yet this step (their deltas are zero).
        row.separation_now = row.separation;
        (side_a.rn_a[i], row.rn_b, side_a.irn_a[i]) = (rn_a, rn_b, irn_a);
        g.impulses[i].irn_b = irn_b;
        row.normal_mass = Vec4::select(real, inverse_or_zero(k), zero);
        if bouncy {
            let dv = v_b + w_b.cross(r_b) - v_a - w_a.cross(r_a);
            cold.relative_velocity[i] = Vec4::select(real, n.dot(dv), zero);
        }
        row.mean_weight = Vec4::select(real, inv_len, zero);
        mean_weight[i] = row.mean_weight;
        k_ii[i] = Vec4::select(real, k, zero);
    }
    // Couplings K_ij (i < j; zero where point j is padding) and the spread row's row sums (a
    // one-point manifold has neither, nor a spread row: its `multi` is empty).
    let mut row_sum = [zero; P];
    for i in 0..P {
        row_sum[i] += k_ii[i];
        if P > 1 {
            g.multi[MultiRow::SpreadWeight(i)] = k_ii[i] * inv_len;
        }
        for j in i + 1..P {
            let real = cold.count.cmpgt(Vec4::splat(j as f32));
            let (pi, pj) = (&g.impulses[i], &g.points[j]);
            let k_ij = Vec4::select(
                real,
                m_sum + side_a.rn_a[j].dot(side_a.irn_a[i]) + pj.rn_b.dot(pi.irn_b),
                zero,
            );
            g.multi[MultiRow::Coupling(i, j)] = k_ij;
            row_sum[i] += k_ij;
            row_sum[j] += k_ij;
        }
    }
    if P > 1 {
        let mut mean = [zero; LANES];
        for i in 0..P {
            let mean_response = row_sum[i] * inv_len;
            g.multi[MultiRow::MeanResponse(i)] = mean_response;
            mean[i] = mean_response * mean_weight[i];
        }
        // Summed as `Vec4::element_sum` sums the points of the scalar rows.
        g.multi[MultiRow::MeanMass] = inverse_or_zero((mean[0] + mean[1]) + (mean[2] + mean[3]));
        g.multi[MultiRow::Count] = cold.count;
    }

    // Friction at the centroid and twist.
    let c_a = centroid * inv_len;
    let c_b = c_a + (x_a - x_b);
    for j in 0..2 {
        let t = tangents[j];
        let ra_t = c_a.cross(t);
        let rb_t = c_b.cross(t);
        let ia_t = times_inv_i_a(ra_t);
        let ib_t = inv_i_b * rb_t;
        g.tangent_mass[j] = inverse_or_zero(m_sum + ra_t.dot(ia_t) + rb_t.dot(ib_t));
        (side_a.rt_a[j], g.rt_b[j], side_a.irt_a[j], g.irt_b[j]) = (ra_t, rb_t, ia_t, ib_t);
        g.tangent_impulse[j] = Vec3x4::from_lanes(cached_tangent).dot(t);
        g.anchor_start[j] = Vec3x4::from_lanes(anchor).dot(t);
        g.anchor_now[j] = g.anchor_start[j];
        g.tangent_load[j] = Vec3x4::from_lanes(demand).dot(t);
    }
    side_a.in_a = times_inv_i_a(n);
    g.in_b = inv_i_b * n;
    if P > 1 {
        // Twist friction acts over the patch the points stand for, not at them (see
        // `collide::patch`): its mean radius from the narrow phase.
        g.multi[MultiRow::TwistRadius] = Vec4::from_array(twist_radius);
        g.multi[MultiRow::TwistMass] = inverse_or_zero(n.dot(side_a.in_a) + n.dot(g.in_b));
    }
    g.normal = n;
    g.tangents = tangents;
    g.anchored = Vec4::from_array(anchored);
    g.touching_spring = Vec4::from_array(touching_spring);
    g.touching_tolerance = Vec4::from_array(touching_tolerance);
    g.soft_depth = Vec4::from_array(soft_depth);
    g.symmetric = Vec4::from_array(symmetric);
    g.twist_anchor_start = Vec4::from_array(twist_anchor);
    g.twist_anchor_now = g.twist_anchor_start;
    bouncy
}

/// An indeterminate support's warm start `warm` (its points' total) moved towards its new
/// `preload` by at most `change`, the change in that preload (see `prepare::preload`, "Load
/// changes"): a load set down raises it towards what the statics ask, never past it, one lifted off
/// lowers it as far, and it never goes below zero.
fn fed_warm_start(warm: f32, change: f32, preload: f32) -> f32 {
    let fed = if change > 0.0 {
        (warm + change).min(warm.max(preload))
    } else {
        (warm + change).max(warm.min(preload))
    };
    fed.max(0.0)
}

/// Spreads each lane's `impulses` (a patch's normal warm start, point by point; `count` points,
/// `points` where they are) by the least change that makes Σ δᵢ·dᵢ = `moment`, dᵢ each point's
/// offset from the points' centroid and δᵢ its impulse less its start, the total kept, in the lanes
/// of `spread`. Where `even`, each point starts from an even share of the total: the pressure that
/// gives the patch the moment it carries (see `prepare::preload`, "Friction"); elsewhere from its
/// own warm start, to which the moment is added ("Moment changes"). A single point carries no
/// moment and is left as it is.
///
/// No point pulls where none has to. Where the least change would pull a point (a load outside
/// the middle of its patch: a box resting across a corner of the one below), that point is let go
/// and the same change is found over the other three, which then carry its share and its moment.
/// Clamped to zero and rescaled instead, the spread carried less than the moment, the warm start
/// turned the body every step and the solver turned it back: a unit box resting 0.4 m off the centre of
/// another along both axes rocked for good, at 7.2 mm/s at 2 sub-steps, 3.1 at 4 and 0.9 at 8;
/// now it rests still (`tests/physics/rest.rs`, `a_box_across_the_corner_of_another_rests_
/// still`). Only from an even share, on a body's one determinate support, and only down to three
/// points, which carry a load inside their triangle exactly: let go on the "Moment changes" path
/// too, or down to two points (which carry no moment across their line, so a clamp-free answer
/// there was no answer), a dropped heap of boxes and balls held in fewer of 32 copies, awake and
/// woken (`nudge bench rest`'s heap, 2026-12-01). Where three points do not carry it either (the
/// load near or past the patch's edge) the least change is clamped and rescaled as before: such a
/// body tips.
#[allow(clippy::needless_range_loop)] // point indices read as the math does
fn spread_pressure<const P: usize>(
    impulses: &mut [[f32; LANES]; P],
    points: &[Vec3x4; P],
    count: Vec4,
    moment: Vec3x4,
    normal: Vec3x4,
    even: BVec4A,
    spread: BVec4A,
) {
    let zero = Vec4::ZERO;
    let real: [BVec4A; P] = std::array::from_fn(|i| count.cmpgt(Vec4::splat(i as f32)));
    let start: [Vec4; P] = std::array::from_fn(|i| Vec4::from_array(impulses[i]));
    // The sums below run over some points of each lane: a term is masked to +0 where its point
    // is left out, which leaves the sum exactly as it was, since a sum started at +0 is never -0
    // (the same bits as keeping the sum without the term, in half the instructions).
    let only = |mask: BVec4A, term: Vec4| Vec4::select(mask, term, zero);
    let mut total = zero;
    let mut centre = Vec3x4::ZERO;
    for i in 0..P {
        total += only(real[i], start[i]);
        centre += points[i].masked(real[i]);
    }
    let active = spread & count.cmpge(Vec4::splat(2.0)) & total.cmpgt(zero);
    if !active.any() {
        return;
    }
    let centre = Vec3x4 {
        x: centre.x / count,
        y: centre.y / count,
        z: centre.z / count,
    };
    let offset: [Vec3x4; P] = std::array::from_fn(|i| points[i] - centre);
    let gradient = least_spread(&offset, &real, moment);
    let even_share = total / count;
    let from: [Vec4; P] = std::array::from_fn(|i| Vec4::select(even, even_share, start[i]));
    let mut wanted: [Vec4; P] = std::array::from_fn(|i| from[i] + offset[i].dot(gradient));
    let least = wanted;
    // From an even share on four points, the point each lane would pull hardest.
    let mut carrying: [BVec4A; P] = std::array::from_fn(|i| active & real[i]);
    let mut hardest = [BVec4A::default(); P];
    let mut worst = zero;
    for i in 0..P {
        let harder = carrying[i] & wanted[i].cmplt(worst);
        for h in &mut hardest[..i] {
            *h &= !harder;
        }
        hardest[i] = harder;
        worst = Vec4::select(harder, wanted[i], worst);
    }
    let letting_go = even & count.cmpeq(Vec4::splat(4.0)) & worst.cmplt(zero);
    if letting_go.any() {
        for i in 0..P {
            carrying[i] &= !(hardest[i] & letting_go);
        }
        // Over the three points left, A: their start plus δᵢ = a + g·eᵢ (eᵢ from A's own
        // centroid c), with Σ δᵢ = what the fourth held and Σ δᵢ·dᵢ = the moment plus its.
        let (mut n, mut c) = (zero, Vec3x4::ZERO);
        let (mut released, mut released_moment) = (zero, moment);
        for i in 0..P {
            n += only(carrying[i], Vec4::ONE);
            c += offset[i].masked(carrying[i]);
            let gone = active & real[i] & !carrying[i];
            released += only(gone, from[i]);
            released_moment += (offset[i] * from[i]).masked(gone);
        }
        let c = Vec3x4 {
            x: c.x / n,
            y: c.y / n,
            z: c.z / n,
        };
        // In the patch's plane: the points' depths differ by the overlap's tilt, and a moment
        // along the normal, which no pressure carries, would be read through the ridge.
        let in_plane = |v: Vec3x4| v - normal * v.dot(normal);
        let around: [Vec3x4; P] = std::array::from_fn(|i| in_plane(offset[i] - c));
        let g = least_spread(&around, &carrying, in_plane(released_moment - c * released));
        let share = released / n;
        for i in 0..P {
            let l = Vec4::select(carrying[i], from[i] + share + around[i].dot(g), zero);
            wanted[i] = Vec4::select(letting_go, l, wanted[i]);
        }
    }
    // Where three points do not carry the moment either, the least change, clamped: it tips.
    let mut carried = BVec4A::splat(true);
    for i in 0..P {
        carried &= !(carrying[i] & wanted[i].cmplt(zero));
    }
    let mut spread_total = zero;
    let mut spread_to = start;
    for i in 0..P {
        let l = Vec4::select(carried, wanted[i], least[i]).max(zero);
        let l = Vec4::select(l.is_finite_mask(), l, from[i]);
        let here = active & real[i];
        spread_to[i] = Vec4::select(here, l, start[i]);
        spread_total += only(here, l);
    }
    let rescale = active & spread_total.cmpgt(zero);
    let scale = total / spread_total;
    for i in 0..P {
        let l = Vec4::select(rescale & real[i], spread_to[i] * scale, spread_to[i]);
        impulses[i] = l.to_array();
    }
}

/// The g of the least change δᵢ = g·dᵢ over the points of `mask` (offsets `d` from their centroid)
/// with Σ δᵢ·dᵢ = `moment`: g = (Σ dᵢ·dᵢᵀ)⁻¹·moment, lane by lane.
#[allow(clippy::needless_range_loop)] // point indices read as the math does
#[inline(always)]
fn least_spread<const P: usize>(d: &[Vec3x4; P], mask: &[BVec4A; P], moment: Vec3x4) -> Vec3x4 {
    let zero = Vec4::ZERO;
    // The spread Σ dᵢ·dᵢᵀ, symmetric.
    let [mut xx, mut xy, mut xz, mut yy, mut yz, mut zz] = [zero; 6];
    for i in 0..P {
        let d = d[i];
        let add = |sum: Vec4, term: Vec4| sum + Vec4::select(mask[i], term, zero);
        (xx, xy, xz) = (add(xx, d.x * d.x), add(xy, d.y * d.x), add(xz, d.z * d.x));
        (yy, yz, zz) = (add(yy, d.y * d.y), add(yz, d.z * d.y), add(zz, d.z * d.z));
    }
    // The spread is singular along the normal (and across an edge's line): the small ridge leaves
    // those directions out of the solution.
    let ridge = Vec4::splat(1e-6) * (((Vec4::ONE + xx) + yy) + zz);
    let column = |x: Vec4, y: Vec4, z: Vec4| Vec3x4 { x, y, z };
    let x_axis = column(xx + ridge, xy, xz);
    let y_axis = column(xy, yy + ridge, yz);
    let z_axis = column(xz, yz, zz + ridge);
    // The inverse's rows are the columns' cross products over the determinant (glam's
    // `Mat3::inverse`, lane by lane).
    let row_x = y_axis.cross(z_axis);
    let row_y = z_axis.cross(x_axis);
    let row_z = x_axis.cross(y_axis);
    let inv_det = Vec4::ONE / z_axis.dot(row_z);
    column(
        (row_x * inv_det).dot(moment),
        (row_y * inv_det).dot(moment),
        (row_z * inv_det).dot(moment),
    )
}

/// Two unit tangents orthogonal to each lane's unit normal `n` (Duff et al. 2017, "Building an
/// orthonormal basis, revisited"): no branch, continuous except across n.z = 0's sign flip.
#[inline(always)]
fn tangent_basis(n: Vec3x4) -> [Vec3x4; 2] {
    let sign = Vec4::ONE.copysign(n.z);
    let a = -Vec4::ONE / (sign + n.z);
    let b = n.x * n.y * a;
    [
        Vec3x4 {
            x: Vec4::ONE + sign * n.x * n.x * a,
            y: sign * b,
            z: -sign * n.x,
        },
        Vec3x4 {
            x: b,
            y: sign + n.y * n.y * a,
            z: -n.y,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_fed_warm_start_moves_towards_the_new_preload_by_at_most_the_change() {
        // 0.2 set down on a support carrying 1.0 whose preload is now 1.5: all of the change.
        assert_eq!(fed_warm_start(1.0, 0.2, 1.5), 1.2);
        // Carrying 1.4 already: up to the preload, not past it.
        assert_eq!(fed_warm_start(1.4, 0.2, 1.5), 1.5);
        // Carrying more than the preload: a load set down adds nothing.
        assert_eq!(fed_warm_start(2.0, 0.2, 1.5), 2.0);
        // Lifted off: down towards the preload, as far, and never below zero.
        assert_eq!(fed_warm_start(1.0, -0.3, 0.5), 0.7);
        assert_eq!(fed_warm_start(0.6, -0.3, 0.5), 0.5);
        assert_eq!(fed_warm_start(0.2, -0.3, 0.0), 0.0);
    }

    /// Spreads a group of four patches, one a lane (each `(impulse, point)` pairs, at most four):
    /// lane k by `moments[k]` where `spread[k]`, from an even share where `even[k]`. Returns the
    /// lanes' impulses after, point by point.
    fn spread_lanes(
        patches: [&[(f32, Vec3)]; 4],
        moments: [Vec3; 4],
        even: [bool; 4],
        spread: [bool; 4],
    ) -> [[f32; LANES]; 4] {
        let mut impulses = [[0.0; LANES]; 4];
        let mut points = [[Vec3A::ZERO; LANES]; 4];
        for (k, patch) in patches.iter().enumerate() {
            for (i, &(l, at)) in patch.iter().enumerate() {
                (impulses[i][k], points[i][k]) = (l, at.into());
            }
        }
        spread_pressure(
            &mut impulses,
            &points.map(Vec3x4::from_lanes),
            Vec4::from_array(patches.map(|patch| patch.len() as f32)),
            Vec3x4::from_lanes(moments.map(Vec3A::from)),
            Vec3x4::from_lanes([Vec3A::Y; 4]),
            BVec4A::from_array(even),
            BVec4A::from_array(spread),
        );
        impulses
    }

    /// Spreads one patch (`impulses` at points `at`) in lane 2 of a group whose other lanes are
    /// empty, starting from an even share where `even`.
    fn spread_one(impulses: &mut [f32], at: &[Vec3], moment: Vec3, even: bool) {
        let patch: Vec<(f32, Vec3)> = impulses.iter().copied().zip(at.iter().copied()).collect();
        let lane_2 = |on: bool| [false, false, on, false];
        let lanes = spread_lanes(
            [&[], &[], &patch, &[]],
            [Vec3::ZERO, Vec3::ZERO, moment, Vec3::ZERO],
            lane_2(even),
            lane_2(true),
        );
        for (i, l) in impulses.iter_mut().enumerate() {
            *l = lanes[i][2];
        }
        assert!(
            lanes
                .iter()
                .all(|l| l[0] == 0.0 && l[1] == 0.0 && l[3] == 0.0)
        );
    }

    #[test]
    fn a_load_over_a_corner_of_its_patch_lets_the_far_corner_go_and_keeps_its_moment() {
        let at = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        let square = [at(-0.5, -0.5), at(0.5, -0.5), at(0.5, 0.5), at(-0.5, 0.5)];
        // 4 N·s at (0.3, 0.3): the least change would pull the far corner (1 − 0.6 − 0.6); the
        // other three carry the load and its moment, Σ l·d = 4·(0.3, 0, 0.3).
        let mut face = [1.0; 4];
        spread_one(&mut face, &square, Vec3::new(1.2, 0.0, 1.2), true);
        for (got, want) in face.iter().zip([0.0, 0.8, 2.4, 0.8]) {
            assert!((got - want).abs() < 1e-5, "{face:?}");
        }
    }

    #[test]
    fn pressure_is_spread_to_carry_the_moment_and_keeps_its_total() {
        let at = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        let (ends, quarter) = ([at(-0.5, 0.0), at(0.5, 0.0)], Vec3::new(0.25, 0.0, 0.0));
        // Two points 1 m apart, 1 N·s each: Σ δ·d = 0.25 along x takes 0.25 from the left one.
        let mut pair = [1.0, 1.0];
        spread_one(&mut pair, &ends, quarter, true);
        assert!(
            (pair[0] - 0.75).abs() < 1e-5 && (pair[1] - 1.25).abs() < 1e-5,
            "{pair:?}"
        );
        // A square patch: the same along z, and a moment it cannot carry leaves one side empty.
        let square = [at(-0.5, -0.5), at(0.5, -0.5), at(0.5, 0.5), at(-0.5, 0.5)];
        let mut face = [1.0; 4];
        spread_one(&mut face, &square, Vec3::new(0.0, 0.0, 0.5), true);
        assert!(
            (face[0] - 0.75).abs() < 1e-5 && (face[2] - 1.25).abs() < 1e-5,
            "{face:?}"
        );
        let mut tipping = [1.0; 4];
        spread_one(&mut tipping, &square, Vec3::new(0.0, 0.0, 10.0), true);
        assert_eq!((tipping[0], tipping[1]), (0.0, 0.0));
        assert!(
            (tipping.iter().sum::<f32>() - 4.0).abs() < 1e-5,
            "{tipping:?}"
        );
        // From an even share: the warm start's own spread does not matter.
        let mut uneven = [0.5, 1.5];
        spread_one(&mut uneven, &ends, quarter, true);
        assert!((uneven[0] - 0.75).abs() < 1e-5, "{uneven:?}");
        // A single point carries no moment.
        let mut one = [1.0];
        spread_one(&mut one, &[at(0.5, 0.0)], Vec3::X, true);
        assert_eq!(one, [1.0]);
    }

    /// A change of moment moves the warm start's own spread, not an even one, and keeps the total.
    #[test]
    fn a_change_of_moment_is_added_to_the_pressure_the_patch_has() {
        let at = |x: f32| Vec3::new(x, 0.0, 0.0);
        // Carrying 0.25 along x already (0.75 and 1.25); 0.1 more takes 0.1 more from the left.
        let mut pair = [0.75, 1.25];
        spread_one(
            &mut pair,
            &[at(-0.5), at(0.5)],
            Vec3::new(0.1, 0.0, 0.0),
            false,
        );
        assert!(
            (pair[0] - 0.65).abs() < 1e-5 && (pair[1] - 1.35).abs() < 1e-5,
            "{pair:?}"
        );
        // Nothing to spread: nothing moves.
        let mut empty = [0.0, 0.0];
        spread_one(&mut empty, &[at(-0.5), at(0.5)], Vec3::X, false);
        assert_eq!(empty, [0.0, 0.0]);
    }

    /// Four patches spread at once each get, bit for bit, what they get alone: a lane reads only
    /// its own points, and one not spread (or empty) is left as it was.
    #[test]
    fn four_patches_spread_at_once_each_get_what_they_get_alone() {
        let p = |x: f32, z: f32| Vec3::new(x, 0.3, z);
        // Lane 0: two points from an even share; 1: a square from its own spread; 2: a square
        // not spread; 3: a triangle from an even share.
        let patches: [&[(f32, Vec3)]; 4] = [
            &[(0.4, p(-0.3, 0.1)), (1.1, p(0.2, 0.1))],
            &[
                (0.5, p(0.0, 0.0)),
                (0.7, p(1.0, 0.0)),
                (0.9, p(1.0, 0.5)),
                (0.2, p(0.0, 0.5)),
            ],
            &[
                (1.0, p(0.0, 0.0)),
                (1.0, p(1.0, 0.0)),
                (1.0, p(1.0, 1.0)),
                (1.0, p(0.0, 1.0)),
            ],
            &[(0.3, p(0.0, 0.0)), (0.6, p(0.4, 0.0)), (0.2, p(0.0, 0.7))],
        ];
        let moments = [
            Vec3::new(0.05, 0.0, 0.0),
            Vec3::new(-0.02, 0.0, 0.07),
            Vec3::new(0.3, 0.0, 0.3),
            Vec3::new(0.0, 0.0, -0.04),
        ];
        let (even, spread) = ([true, false, true, true], [true, true, false, true]);
        let only = |lanes: [bool; 4], of: [bool; 4]| std::array::from_fn(|k| of[k] && lanes[k]);
        let run = |lanes| spread_lanes(patches, moments, only(lanes, even), only(lanes, spread));
        let (together, before) = (run([true; 4]), run([false; 4]));
        for k in 0..LANES {
            let alone = run(std::array::from_fn(|j| j == k));
            for i in 0..4 {
                assert_eq!(
                    together[i][k].to_bits(),
                    alone[i][k].to_bits(),
                    "lane {k} point {i}"
                );
            }
        }
        assert_eq!(together.map(|l| l[2]), before.map(|l| l[2]));
        assert_ne!(together.map(|l| l[1]), before.map(|l| l[1]));
    }

    #[test]
    fn tangent_basis_is_orthonormal_for_every_octant() {
        let normals = [
            Vec3A::Y,
            Vec3A::NEG_Y,
            Vec3A::Z,
            Vec3A::NEG_Z,
            Vec3A::new(1.0, -2.0, 0.5).normalize(),
            Vec3A::new(-0.3, 0.1, -0.9).normalize(),
            Vec3A::X,
            Vec3A::new(0.0, 0.6, -0.8),
        ];
        for four in normals.chunks(4) {
            let n = Vec3x4::from_lanes([four[0], four[1], four[2], four[3]]);
            let [t1, t2] = tangent_basis(n);
            for k in 0..4 {
                let (n, t1, t2) = (n.lane(k), t1.lane(k), t2.lane(k));
                assert!((t1.length() - 1.0).abs() < 1e-5 && (t2.length() - 1.0).abs() < 1e-5);
                assert!(t1.dot(n).abs() < 1e-5 && t2.dot(n).abs() < 1e-5);
                assert!(t1.dot(t2).abs() < 1e-5, "{n} {t1} {t2}");
            }
        }
    }
}
