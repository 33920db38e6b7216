//! The steps of the factorisation and the sweeps, node by node: a joint's block from its rows and
//! its ends' masses, a node's factor and the Schur complement it hands its parent, and the
//! products each sweep passes up and down (see the parent module, "The factorisation").

// Block arithmetic indexes rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

use glam::{Mat3, Vec3A};

use super::point_rows::{angular_dot, linear_dot};
use super::{Form, MAX, Mat6, Node, NodeKind, Sweeps, TreeRows, Vec6};
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};

/// t += Jᵀλ for the R rows `j` of a Jacobian and their impulses `lambda` (`point`: see
/// [`TreeRows::point`]).
#[inline(always)]
pub(super) fn add_transposed<const R: usize>(j: &Mat6, point: bool, lambda: &Vec6, t: &mut Vec6) {
    for row in 0..R {
        if point {
            if row < 3 {
                t[row] += j[row][row] * lambda[row];
            }
            for c in 3..6 {
                if c != 3 + row {
                    t[c] += j[row][c] * lambda[row];
                }
            }
        } else {
            for c in 0..6 {
                t[c] += j[row][c] * lambda[row];
            }
        }
    }
}

/// The Jacobian of a node's edge (see [`Node::edge`]).
pub(super) fn edge_jacobian<'a>(node: &Node, rows: &'a [TreeRows]) -> &'a Mat6 {
    let r = &rows[node.edge.0 as usize];
    if node.edge.1 { &r.j_b } else { &r.j_a }
}

/// Whether the joint of a node's edge holds a point (see [`TreeRows::point`]).
pub(super) fn edge_is_point(node: &Node, rows: &[TreeRows]) -> bool {
    rows[node.edge.0 as usize].point
}

/// Factors a node of size N under a parent of size K (its D is `d`), keeps its coupling through
/// the factor and subtracts its Schur complement E_iᵀ D_i⁻¹ E_i from its parent's block. A joint
/// under a contracted body comes `through` it: its parent joint's Jacobian on that body, and the
/// body's mass. Where D falls back to Gauss–Jordan, its coupling G goes to `coupling`. Sets its
/// sweeps' steps at these sizes ([`Sweeps`]).
pub(super) fn factor_node<const N: usize, const K: usize>(
    node: &mut Node,
    d: &Mat6,
    parent: Option<&mut Mat6>,
    through: Option<(&Mat6, bool, &SolverMotion)>,
    coupling: &mut Mat6,
    rows: &[TreeRows],
    motions: &[SolverMotion],
) {
    // G = −E_i: J (N × 6) for a joint under a body, Jᵀ (6 × K) for a body under a joint, J_c M⁻¹
    // J_pᵀ (N × K) for a joint under a joint through a contracted body (the sign cancels in
    // Eᵀ D⁻¹ E).
    node.sweeps = Sweeps::at::<N, K>();
    let j = parent.as_ref().map(|_| edge_jacobian(node, rows));
    let point = edge_is_point(node, rows);
    let factor = &mut node.factor;
    let keep = |g: &[[f64; K]; N], form: Form, coupling: &mut Mat6| {
        if form == Form::Inverse {
            for (kept, g) in coupling.iter_mut().zip(g) {
                kept[..K].copy_from_slice(g);
            }
        }
    };
    match node.kind {
        NodeKind::Body(b) if node.free => {
            let (Some(j), Some(parent)) = (j, parent) else {
                unreachable!("a free body hangs from a joint");
            };
            factor.free(&motions[b as usize]);
            // J M⁻¹ Jᵀ, with the joint's compliance on this end (see `joint_block`).
            factor.couple_free::<K>(j, point, 1.0 + COMPLIANCE, parent);
        }
        NodeKind::Body(_) => {
            factor.factor::<6>(d, 1.0);
            if let (Some(j), Some(parent)) = (j, parent) {
                let g = transposed::<K>(j);
                factor.couple::<6, K>(&g, parent);
                let g: [[f64; K]; N] = std::array::from_fn(|i| g[i % 6]);
                keep(&g, factor.form, coupling);
            }
        }
        NodeKind::Joint(_) => {
            factor.factor::<N>(d, -1.0);
            if let (Some(j), Some(parent)) = (j, parent) {
                let g: [[f64; K]; N] = match through {
                    None => std::array::from_fn(|row| std::array::from_fn(|c| j[row][c])),
                    Some((jp, parent_point, motion)) => {
                        joint_coupling::<N, K>((j, point), (jp, parent_point), motion)
                    }
                };
                factor.couple::<N, K>(&g, parent);
                keep(&g, factor.form, coupling);
            }
        }
    }
}

/// J_c M⁻¹ J_pᵀ (N × K): the coupling of a joint's N rows `jc` and its parent joint's K rows `jp`
/// on the contracted body between them (its inverse mass and world inverse inertia in `motion`),
/// each with whether it holds a point (see [`TreeRows::point`]).
fn joint_coupling<const N: usize, const K: usize>(
    (jc, c_point): (&Mat6, bool),
    (jp, p_point): (&Mat6, bool),
    motion: &SolverMotion,
) -> [[f64; K]; N] {
    let inv_mass = motion.inv_mass as f64;
    let i = Mat3::from(motion.inv_inertia)
        .to_cols_array()
        .map(f64::from);
    // M⁻¹ J_pᵀ, column by column (one per parent row); `i` holds I⁻¹'s columns.
    let mut w = [[0.0; MAX]; K];
    for c in 0..K {
        w[c] = [
            inv_mass * jp[c][0],
            inv_mass * jp[c][1],
            inv_mass * jp[c][2],
            angular_dot(&[i[0], i[3], i[6]], &jp[c], c, p_point),
            angular_dot(&[i[1], i[4], i[7]], &jp[c], c, p_point),
            angular_dot(&[i[2], i[5], i[8]], &jp[c], c, p_point),
        ];
    }
    let mut g = [[0.0; K]; N];
    for r in 0..N {
        for c in 0..K {
            let mut s = linear_dot(&jc[r], r, c_point, &w[c], c, p_point);
            for k in 3..6 {
                // Point rows' angular zeros (`TreeRows::point`).
                if !(c_point && k == 3 + r) {
                    s += jc[r][k] * w[c][k];
                }
            }
            g[r][c] = s;
        }
    }
    g
}

/// Jᵀ (6 × R) of a Jacobian's R rows, in f64.
fn transposed<const R: usize>(j: &Mat6) -> [[f64; R]; 6] {
    std::array::from_fn(|c| std::array::from_fn(|row| j[row][c]))
}

/// J v + b of a joint's R rows, with its ends' velocities `va`, `vb` and b = `rate`·C (none: 0).
pub(super) fn joint_rhs<const R: usize>(
    r: &TreeRows,
    va: &Vec6,
    vb: &Vec6,
    rate: Option<f32>,
) -> Vec6 {
    let mut y = [0.0; MAX];
    for row in 0..R {
        let mut s = rate.map_or(0.0, |rate| (rate * r.error[row]) as f64);
        // Point rows (`TreeRows::point`): only the exact zeros are left out.
        if !r.point {
            for c in 0..3 {
                s += r.j_a[row][c] * va[c] + r.j_b[row][c] * vb[c];
            }
        } else if row < 3 {
            s += r.j_a[row][row] * va[row] + r.j_b[row][row] * vb[row];
        }
        for c in 3..6 {
            if !(r.point && c == 3 + row) {
                s += r.j_a[row][c] * va[c] + r.j_b[row][c] * vb[c];
            }
        }
        y[row] = s;
    }
    y
}

/// The forward sweep's step at a node of size N under a parent of size K: y_parent −=
/// E_iᵀ D_i⁻¹ y_i, and u = D_i⁻¹y_i kept in `x`.
pub(super) fn forward_step<const N: usize, const K: usize>(
    node: &Node,
    coupling: &Mat6,
    x: &mut Vec6,
    mut parent: Option<&mut Vec6>,
) {
    let f = &node.factor;
    let y = *x;
    // Sent up first, from y: the parent waits on it, nothing waits on u.
    if let (Some(parent), Form::Ldl) = (parent.as_deref_mut(), f.form) {
        f.send_up::<N, K>(&y, parent);
    }
    f.solve::<N>(x);
    // Gauss–Jordan's D⁻¹ need not be symmetric (and a free body sends nothing): Gᵀu, with the
    // coupling G kept when it was factored.
    if let (Some(parent), Form::Inverse) = (parent, f.form) {
        for row in 0..N {
            for c in 0..K {
                parent[c] += coupling[row][c] * x[row];
            }
        }
    }
}

/// The backward sweep's step at a node of size N under a parent of size K: x_i = D_i⁻¹ (y_i −
/// E_i x_p) = u + Z x_p, from the forward sweep's u in `x` and x_p in `parent` (a root has no
/// step: its x is its u).
pub(super) fn backward_step<const N: usize, const K: usize>(
    node: &Node,
    x: &mut Vec6,
    parent: &Vec6,
) {
    node.factor.take_down::<N, K>(x, parent);
}

/// Relative compliance of the rows in the exact solve: H_jj = −ε·K_jj. It makes a joint whose
/// other end is static (a leaf of the tree, whose block would be 0) invertible, and is far below
/// anything that shows in the answer (the rows are rigid to 1 part in 10⁶ of their response).
pub(super) const COMPLIANCE: f64 = 1e-6;

/// A joint's block before its children's Schur complements: d = −Σ s_e·J_e M_e⁻¹ J_eᵀ over its
/// ends e, with `share` s_e (A's, B's): ε (the compliance, `COMPLIANCE`) for an end that is a node
/// of the tree; 1 + ε for a contracted body (its own Schur complement, J M⁻¹ Jᵀ, with the
/// compliance); 0 for a free body, which subtracts its 1 + ε with its own Schur complement, and
/// for a static end.
pub(super) fn joint_block(
    rows: &TreeRows,
    motions: &[SolverMotion],
    share: [f64; 2],
    d: &mut Mat6,
) {
    // Only its rows' corner is read.
    with_rows!(rows.rows, clear_corner(d));
    for ((index, j), s) in [(rows.a, &rows.j_a), (rows.b, &rows.j_b)]
        .into_iter()
        .zip(share)
    {
        if s != 0.0 {
            let motion = &motions[index as usize];
            with_rows!(rows.rows, subtract_free(motion, j, rows.point, s, d));
        }
    }
}

/// Zeroes d's top-left R × R corner.
fn clear_corner<const R: usize>(d: &mut Mat6) {
    for row in &mut d[..R] {
        row[..R].fill(0.0);
    }
}

/// d −= s·J M⁻¹ Jᵀ for the R rows `j` of a Jacobian on a body (its inverse mass and world inverse
/// inertia in `motion`): entry (r, c) is s·(lin_r·lin_c / m + ang_r·I⁻¹·ang_c), computed once
/// for both halves.
fn subtract_free<const R: usize>(
    motion: &SolverMotion,
    j: &Mat6,
    point: bool,
    s: f64,
    d: &mut Mat6,
) {
    let inv_mass = s * motion.inv_mass as f64;
    let inv_inertia = Mat3::from(motion.inv_inertia);
    let inv_inertia: [[f64; 3]; 3] =
        std::array::from_fn(|r| std::array::from_fn(|c| s * inv_inertia.col(c)[r] as f64));
    // s·I⁻¹·ang_r per row.
    let mut u = [[0.0; 3]; R];
    for r in 0..R {
        for a in 0..3 {
            u[r][a] = angular_dot(&inv_inertia[a], &j[r], r, point);
        }
    }
    for r in 0..R {
        for c in 0..=r {
            let lin = linear_dot(&j[r], r, point, &j[c], c, point);
            let ang = angular_dot(&u[r], &j[c], c, point);
            let k = inv_mass * lin + ang;
            d[r][c] -= k;
            if r != c {
                d[c][r] -= k;
            }
        }
    }
}

/// d = M, a body's 6 × 6 mass block: m·1 and the world inertia (the inverse of the solver's
/// inverse inertia).
pub(super) fn body_mass(motion: &SolverMotion, d: &mut Mat6) {
    *d = [[0.0; MAX]; MAX];
    let m = if motion.inv_mass > 0.0 {
        1.0 / motion.inv_mass as f64
    } else {
        0.0
    };
    for i in 0..3 {
        d[i][i] = m;
    }
    let inv = Mat3::from(motion.inv_inertia);
    let [a, b, c, e, f, g, h, i, k] = [
        inv.x_axis.x,
        inv.y_axis.x,
        inv.z_axis.x,
        inv.x_axis.y,
        inv.y_axis.y,
        inv.z_axis.y,
        inv.x_axis.z,
        inv.y_axis.z,
        inv.z_axis.z,
    ]
    .map(f64::from);
    // The inverse of ⎡a b c; e f g; h i k⎤ by its adjugate.
    let adjugate = [
        [f * k - g * i, c * i - b * k, b * g - c * f],
        [g * h - e * k, a * k - c * h, c * e - a * g],
        [e * i - f * h, b * h - a * i, a * f - b * e],
    ];
    let det = a * adjugate[0][0] + b * adjugate[1][0] + c * adjugate[2][0];
    for r in 0..3 {
        for s in 0..3 {
            d[3 + r][3 + s] = adjugate[r][s] / det;
        }
    }
}

pub(super) fn velocity(bodies: &[SolverBody], index: u32) -> [f64; 6] {
    if index == 0 {
        return [0.0; 6];
    }
    let b = &bodies[index as usize];
    [
        b.v.x as f64,
        b.v.y as f64,
        b.v.z as f64,
        b.w.x as f64,
        b.w.y as f64,
        b.w.z as f64,
    ]
}

/// Adds `scale` times the velocity change `dv` (linear, then angular) to `body`.
pub(super) fn add_scaled(body: &mut SolverBody, dv: &[f64], scale: f64) {
    let at = |i: usize| (dv[i] * scale) as f32;
    body.v += Vec3A::new(at(0), at(1), at(2));
    body.w += Vec3A::new(at(3), at(4), at(5));
}
