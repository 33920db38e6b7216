//! One node's block D, factored once per factorisation (see the parent module, "The
//! factorisation"): L·Δ·Lᵀ with no square roots, or Gauss–Jordan's inverse where D is not definite
//! (a redundant row), and the products the sweeps take through it.

// Block arithmetic indexes rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

use glam::Mat3;

use super::point_rows::angular_dot;
use super::{MAX, Mat6, Vec6};
use crate::physics::solve::solver_body::SolverMotion;

/// How a node's D is held once factored (see [`Factor`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Form {
    /// D = L·Δ·Lᵀ, L unit lower triangular and Δ diagonal, positive for a body (D is positive
    /// definite), negative for a joint (negative definite): `m` holds L below its diagonal and
    /// Δ⁻¹ on it.
    Ldl,
    /// `m` holds D⁻¹, by Gauss–Jordan elimination: D was not definite (a redundant row, which gets
    /// zero).
    Inverse,
    /// A body without child joints, whose D is its mass block M: `m` holds M⁻¹ = diag(1/m, I⁻¹),
    /// which the solver has, so nothing is factored.
    Free,
}

/// A node's D, factored, with its coupling to its parent seen through the factor: what the
/// substitution applies and what the node subtracts from its parent's block (its Schur
/// complement).
///
/// With G = −E, the coupling H[node, parent] up to its sign (J for a joint under a body, Jᵀ for a
/// body under a joint, J_c M⁻¹ J_pᵀ for a joint under a joint through a contracted body), N the
/// node's size and K its parent's:
/// - Ldl, D = L·Δ·Lᵀ: `m` holds L and Δ⁻¹, `z` holds Z = D⁻¹G (N × K). The Schur complement is
///   Gᵀ D⁻¹ G = VᵀW with V = L⁻¹G and W = Δ⁻¹V (and Z = L⁻ᵀW). The forward sweep sends Zᵀy up
///   and keeps u = D⁻¹y = L⁻ᵀΔ⁻¹L⁻¹y, the backward sweep makes x = u + Z x_parent. No square
///   roots: one division per pivot, the latency a chain's factorisation waits on link after
///   link. And what goes up or down a chain waits on one product per node, not on triangular
///   solves: those make u, which nothing up the chain waits for. (A ball joint's 3 × 3 block
///   inverted by its adjugate instead, one division for three, held as [`Form::Inverse`]: the chain of
///   100 links stepped to the same bits, with 2.4 % more instructions and 1 to 1.5 % less time
///   over six alternated pairs of runs; not kept, 2026-12-02.)
/// - Inverse and Free: `m` holds D⁻¹ and `z` holds Z = D⁻¹G. The forward sweep keeps u = D⁻¹y and
///   sends Gᵀu up (Gauss–Jordan's D⁻¹ need not be symmetric), the backward sweep makes
///   x = u + Z x_parent.
#[derive(Clone, Copy, Debug)]
pub(super) struct Factor {
    pub(super) form: Form,
    m: Mat6,
    z: Mat6,
}

impl Factor {
    pub(super) const EMPTY: Factor = Factor {
        form: Form::Free,
        m: [[0.0; MAX]; MAX],
        z: [[0.0; MAX]; MAX],
    };

    /// A free body's: M⁻¹ from its inverse mass and world inverse inertia. Only M⁻¹'s two blocks
    /// are written: the rest of `m` is zero from [`Factor::EMPTY`], since a node is free (or
    /// contracted) for the life of its tree's shape and nothing else writes a free factor.
    pub(super) fn free(&mut self, motion: &SolverMotion) {
        self.form = Form::Free;
        for i in 0..3 {
            self.m[i][i] = motion.inv_mass as f64;
        }
        let inv_inertia = Mat3::from(motion.inv_inertia);
        for j in 0..3 {
            let column = inv_inertia.col(j);
            for i in 0..3 {
                self.m[3 + i][3 + j] = column[i] as f64;
            }
        }
    }

    /// Factors the symmetric block `d` (N × N), definite with the sign `sign` (+1 for a body, −1
    /// for a joint): L·Δ·Lᵀ, or Gauss–Jordan where a pivot vanishes (a redundant row).
    pub(super) fn factor<const N: usize>(&mut self, d: &Mat6, sign: f64) {
        self.form = Form::Ldl;
        // L's entries l_ij below the diagonal, and c_ij = l_ij·δ_j above it (in m[j][i]).
        let m = &mut self.m;
        // The loops run to N with their triangular bounds as tests, so that they unroll whole.
        for j in 0..N {
            let mut pivot = d[j][j];
            for k in 0..N {
                if k < j {
                    pivot -= m[k][j] * m[j][k];
                }
            }
            // A pivot is judged against its own diagonal: the blocks are badly scaled (a link's
            // inertia beside a joint's ε·K).
            if pivot.is_nan() || sign * pivot <= 1e-12 * d[j][j].abs() {
                self.form = Form::Inverse;
                self.m = gauss_jordan(d, N);
                return;
            }
            let inv = 1.0 / pivot;
            m[j][j] = inv;
            for i in 0..N {
                if i > j {
                    let mut c = d[i][j];
                    for k in 0..N {
                        if k < j {
                            c -= m[k][i] * m[j][k];
                        }
                    }
                    m[j][i] = c;
                    m[i][j] = c * inv;
                }
            }
        }
    }

    /// y ← D⁻¹y on its first N entries: L⁻ᵀΔ⁻¹L⁻¹y, walking L's rows both ways, or the dense
    /// D⁻¹.
    // Inlined into its sweep step, its one caller at these sizes: called, it cost a call a node.
    #[inline(always)]
    pub(super) fn solve<const N: usize>(&self, y: &mut Vec6) {
        let m = &self.m;
        match self.form {
            Form::Ldl => {
                for i in 0..N {
                    let mut v = y[i];
                    for k in 0..i {
                        v -= m[i][k] * y[k];
                    }
                    y[i] = v;
                }
                for i in 0..N {
                    y[i] *= m[i][i];
                }
                for i in (0..N).rev() {
                    for k in 0..i {
                        y[k] -= m[i][k] * y[i];
                    }
                }
            }
            Form::Inverse | Form::Free => {
                let x = *y;
                for i in 0..N {
                    y[i] = (0..N).map(|j| m[i][j] * x[j]).sum();
                }
            }
        }
    }

    /// Keeps W = Δ⁻¹L⁻¹G and Z = D⁻¹G for the coupling G (N × K), row by row, and subtracts the
    /// Schur complement Gᵀ D⁻¹ G from the parent's block `d` (K × K).
    pub(super) fn couple<const N: usize, const K: usize>(
        &mut self,
        g: &[[f64; K]; N],
        d: &mut Mat6,
    ) {
        let m = &self.m;
        match self.form {
            Form::Ldl => {
                // V = L⁻¹G and W = Δ⁻¹V, row by row.
                let mut v = *g;
                let mut w = [[0.0; K]; N];
                for i in 0..N {
                    for k in 0..i {
                        for c in 0..K {
                            v[i][c] -= m[i][k] * v[k][c];
                        }
                    }
                    for c in 0..K {
                        w[i][c] = v[i][c] * m[i][i];
                    }
                }
                // VᵀW, symmetric: its lower triangle, mirrored.
                for a in 0..K {
                    for b in 0..=a {
                        let s = (0..N).map(|i| v[i][a] * w[i][b]).sum::<f64>();
                        d[a][b] -= s;
                        if a != b {
                            d[b][a] -= s;
                        }
                    }
                }
                // Z = D⁻¹G = L⁻ᵀW, from the last row up.
                let z = &mut self.z;
                for i in (0..N).rev() {
                    z[i][..K].copy_from_slice(&w[i]);
                    for k in i + 1..N {
                        for c in 0..K {
                            z[i][c] -= m[k][i] * z[k][c];
                        }
                    }
                }
            }
            Form::Inverse | Form::Free => {
                self.through_inverse(g);
                for i in 0..N {
                    for a in 0..K {
                        for b in 0..K {
                            d[a][b] -= g[i][a] * self.z[i][b];
                        }
                    }
                }
            }
        }
    }

    /// A free body's coupling to its joint, whose R rows on it are `j`: keeps Z = M⁻¹Jᵀ (6 × R,
    /// from M⁻¹'s blocks: 1/m and I⁻¹) and subtracts s·J M⁻¹ Jᵀ = s·J Z from the joint's block `d`.
    pub(super) fn couple_free<const R: usize>(
        &mut self,
        j: &Mat6,
        point: bool,
        s: f64,
        d: &mut Mat6,
    ) {
        let (m, w) = (&self.m, &mut self.z);
        for r in 0..R {
            for i in 0..3 {
                w[i][r] = m[i][i] * j[r][i];
                let row = [m[3 + i][3], m[3 + i][4], m[3 + i][5]];
                w[3 + i][r] = angular_dot(&row, &j[r], r, point);
            }
        }
        for r in 0..R {
            for c in 0..=r {
                // Point rows (`TreeRows::point`): row r's linear part is ±e_r (none past 3), so
                // of the linear terms only i = r = c is not an exact zero.
                let mut sum = -0.0; // where `Sum` starts
                if !point {
                    for i in 0..3 {
                        sum += j[r][i] * w[i][c];
                    }
                } else if r < 3 && r == c {
                    sum += j[r][r] * w[r][c];
                }
                for i in 3..6 {
                    if !(point && i == 3 + r) {
                        sum += j[r][i] * w[i][c];
                    }
                }
                let k = s * sum;
                d[r][c] -= k;
                if r != c {
                    d[c][r] -= k;
                }
            }
        }
    }

    /// M⁻¹t for a free or contracted body (`m` holds M⁻¹: 1/m on the diagonal, then I⁻¹).
    pub(super) fn through_mass(&self, t: &Vec6) -> Vec6 {
        let m = &self.m;
        std::array::from_fn(|i| {
            if i < 3 {
                m[i][i] * t[i]
            } else {
                (3..6).map(|k| m[i][k] * t[k]).sum()
            }
        })
    }

    /// Keeps Z = D⁻¹G (Inverse and Free: `m` holds D⁻¹) for the coupling G (N × K).
    fn through_inverse<const N: usize, const K: usize>(&mut self, g: &[[f64; K]; N]) {
        for i in 0..N {
            let mut z = [0.0; K];
            for k in 0..N {
                for c in 0..K {
                    z[c] += self.m[i][k] * g[k][c];
                }
            }
            self.z[i][..K].copy_from_slice(&z);
        }
    }

    /// What the forward sweep sends up from this node's y (N) when D⁻¹ is symmetric (an L·Δ·Lᵀ):
    /// y_parent −= E_iᵀ D_i⁻¹ y_i = Zᵀy (K), straight from y.
    // Inlined into its sweep step, its one caller at these sizes: called, it cost a call a node.
    #[inline(always)]
    pub(super) fn send_up<const N: usize, const K: usize>(&self, y: &Vec6, parent: &mut Vec6) {
        for c in 0..K {
            parent[c] += (0..N).map(|i| self.z[i][c] * y[i]).sum::<f64>();
        }
    }

    /// The backward sweep at this node: x = u + Z x_parent, `x` holding u = D⁻¹y (N), `xp`
    /// x_parent (K; a root takes no step).
    // Inlined into its sweep step, its one caller at these sizes: called, it cost a call a node.
    #[inline(always)]
    pub(super) fn take_down<const N: usize, const K: usize>(&self, x: &mut Vec6, xp: &Vec6) {
        for i in 0..N {
            x[i] += (0..K).map(|c| self.z[i][c] * xp[c]).sum::<f64>();
        }
    }
}

/// The inverse of the square block `a` (n × n) by Gauss–Jordan elimination with partial pivoting
/// (the blocks are definite, positive for bodies and negative for joints, so pivots do not vanish
/// unless a row is redundant: such a row gets a zero, it constrains nothing new).
fn gauss_jordan(a: &Mat6, n: usize) -> Mat6 {
    let mut a = *a;
    let mut inv = [[0.0; MAX]; MAX];
    for i in 0..n {
        inv[i][i] = 1.0;
    }
    // A pivot is judged against its own row's diagonal: the blocks are badly scaled (a link's
    // inertia beside a joint's 1/ε), so a threshold against the largest entry zeroed real rows.
    let diagonal: Vec6 = std::array::from_fn(|i| if i < n { a[i][i].abs() } else { 0.0 });
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))
            .unwrap_or(col);
        if a[pivot][col].abs() <= 1e-12 * diagonal[col].max(1e-300) {
            // A redundant row: leave it out (its column and row of the inverse stay zero).
            for k in 0..n {
                a[col][k] = 0.0;
                inv[col][k] = 0.0;
            }
            continue;
        }
        a.swap(col, pivot);
        inv.swap(col, pivot);
        let p = 1.0 / a[col][col];
        for k in 0..n {
            a[col][k] *= p;
            inv[col][k] *= p;
        }
        for r in 0..n {
            if r != col && a[r][col] != 0.0 {
                let f = a[r][col];
                for k in 0..n {
                    a[r][k] -= f * a[col][k];
                    inv[r][k] -= f * inv[col][k];
                }
            }
        }
    }
    inv
}
