//! An exact solve of the joints' equality rows where the joints form trees (chains, ragdolls,
//! bridges between two anchors): Baraff's linear-time elimination ("Linear-Time Dynamics using
//! Lagrange Multipliers", SIGGRAPH 1996).
//!
//! # Why not Gauss–Seidel alone
//! A chain holding a load a hundred times a link is the classic failure of sequential impulses: a
//! row's effective mass is a link's, so each sweep moves the load by a link's share of its error
//! and the chain stretches until the soft springs carry the load (13 % of its length at the
//! defaults, `tests/physics/joints.rs`); an integral term that removes that stretch winds up and
//! throws the chain apart. Mass ratios along a chain are what a joint user meets first (a wrecking
//! ball, a ragdoll's torso on its arms), so the equality rows are solved exactly instead.
//!
//! # The system
//! Per pass, with body velocities v (6 per dynamic body), joint Jacobians J and the rows' velocity
//! targets b (the bias of the position error, 0 in the relax pass), the impulses Δλ and velocity
//! changes Δv satisfy M Δv = Jᵀ Δλ and J (v + Δv) + b = 0, that is
//!
//! ```text
//! ⎡  M   −Jᵀ ⎤ ⎡Δv⎤   ⎡   0    ⎤
//! ⎣ −J    0  ⎦ ⎣Δλ⎦ = ⎣ J v + b ⎦
//! ```
//!
//! The matrix's blocks form a graph of bodies and joints, a tree when the joints among dynamic
//! bodies have no loop (a joint to a static body or the world is a leaf). Eliminating the tree's
//! nodes from the leaves up makes no fill-in: a block LDLᵀ factorisation in O(n) with blocks of at
//! most 6 × 6, then one sweep up and one down per solve. A joint that would close a loop stays out
//! of the tree and is solved by Gauss–Seidel with the other rows (limits, motors, springs, ropes).
//! A hinge's or a slider's limits and motor stay scalar rows, solved before the tree's with their
//! mass through the tree (`JointTree::response`) and applied through it (`apply_response`):
//! with the two bodies' mass alone, a limit on the hinge of a 4 g ball on a 1 m arm saw 250 times
//! too little mass and leaked to 126°; applied to the two bodies alone, the next row read the
//! ball's spin before the tree turned it into swing, and the scene blew up in a step.
//!
//! The rows are rigid here (the exact solve needs no softness to converge), and the biased pass
//! closes a joint's whole position error within the sub-step (target C/h, as a speculative
//! contact's); the relax pass removes the velocity that correction added, as for the contacts.
//! Closed more slowly (at the contacts' soft rate), the error a swing opens every sub-step lingered
//! and a double pendulum's energy wandered 2 % in 20 s; closed at once, 0.6 %
//! (`a_double_pendulum_keeps_its_energy`). The factorisation is computed in f64: the blocks of a
//! light link next to a heavy load differ by the mass ratio.
//!
//! # The factorisation
//! With the nodes in post-order (children first), node i's block is D_i = H_ii − Σ_c E_cᵀ D_c⁻¹ E_c
//! over its children c, E_c = H[c, i]. No E is stored: H[joint, body] is −J, the joint's Jacobian
//! on that body (read from its `TreeRows`), and H[body, joint] is −Jᵀ. A body's D is positive
//! definite and a joint's negative definite, so each is factored as L·Δ·Lᵀ (L unit lower
//! triangular, Δ diagonal of the block's sign), V = L⁻¹E and W = Δ⁻¹V: a child's E_cᵀ D_c⁻¹ E_c
//! is VᵀW. With Z = L⁻ᵀW = D⁻¹E kept per node (up to its sign), what a solve's sweeps pass up
//! and down is a product with Z per node, the triangular solves off that path (see [`Factor`]).
//! A body without child joints needs nothing factored (its D is its mass block, whose inverse the
//! solver has, and it carries its joint's compliance with its Schur complement); a block that is
//! not definite (a redundant row) is inverted by Gauss–Jordan, which gives that row no impulse.
//!
//! A body with one child joint c, not a root (a link of a chain, a ragdoll's upper arm), is
//! *contracted*: eliminated before its joints, while its D is still its mass block M. That makes
//! no fill-in either (its two joints become neighbours: c hangs from the parent joint p), and
//! costs no 6 × 6 factorisation: each joint's block gets J M⁻¹ Jᵀ (with the compliance, as a free
//! body's does) and c's coupling to p is G = J_c M⁻¹ J_pᵀ (R_c × R_p). The sweeps pass nothing
//! through the body; its Δv = M⁻¹ (J_cᵀ Δλ_c + J_pᵀ Δλ_p) once its joints' impulses are known. A
//! chain of ball joints is then a chain of 3 × 3 joint blocks, not of 6 × 6 bodies between them:
//! a fifth fewer instructions for a step of a 100-link chain.
//!
//! The loops run over the row counts of the joints (1 to 6) and a node's and its parent's sizes as
//! compile-time sizes (`with_rows!`, `with_sizes!`).

// Block arithmetic indexes rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

use glam::{Mat3, Vec3, Vec3A};

use crate::physics::solve::solver_body::{SolverBody, SolverMotion};

/// Calls `f::<R>(…)` with the row count `r` (1 to 6) known at compile time, so that the loops over
/// a joint's rows have fixed bounds (and unroll, without bounds checks).
macro_rules! with_rows {
    ($r:expr, $f:ident($($arg:expr),* $(,)?)) => {
        match $r {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            r => unreachable!("a joint has 1 to 6 equality rows, not {r}"),
        }
    };
}

/// Calls `f::<N, K>(…)` with a node's size `n` and its parent's `k` (1 to 6 each) known at compile
/// time.
macro_rules! with_sizes {
    ($n:expr, $k:expr, $f:ident($($arg:expr),* $(,)?)) => {
        match $n {
            1 => with_sizes!(@k 1, $k, $f($($arg),*)),
            2 => with_sizes!(@k 2, $k, $f($($arg),*)),
            3 => with_sizes!(@k 3, $k, $f($($arg),*)),
            4 => with_sizes!(@k 4, $k, $f($($arg),*)),
            5 => with_sizes!(@k 5, $k, $f($($arg),*)),
            6 => with_sizes!(@k 6, $k, $f($($arg),*)),
            n => unreachable!("a node has 1 to 6 unknowns, not {n}"),
        }
    };
    (@k $n:literal, $k:expr, $f:ident($($arg:expr),*)) => {
        match $k {
            1 => $f::<$n, 1>($($arg),*),
            2 => $f::<$n, 2>($($arg),*),
            3 => $f::<$n, 3>($($arg),*),
            4 => $f::<$n, 4>($($arg),*),
            5 => $f::<$n, 5>($($arg),*),
            6 => $f::<$n, 6>($($arg),*),
            k => unreachable!("a node has 1 to 6 unknowns, not {k}"),
        }
    };
}

/// The largest block: a body's 6 degrees of freedom, or a weld's 6 rows.
const MAX: usize = 6;

/// A block of at most 6 × 6, row-major, f64: a node of size n uses its top-left n × n.
type Mat6 = [[f64; MAX]; MAX];

/// A node's vector: a body's 6 velocities (linear, then angular) or a joint's rows (the first n).
type Vec6 = [f64; MAX];

/// How a node's D is held once factored (see [`Factor`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Form {
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
///   solves: those make u, which nothing up the chain waits for.
/// - Inverse and Free: `m` holds D⁻¹ and `z` holds Z = D⁻¹G. The forward sweep keeps u = D⁻¹y and
///   sends Gᵀu up (Gauss–Jordan's D⁻¹ need not be symmetric), the backward sweep makes
///   x = u + Z x_parent.
#[derive(Clone, Copy, Debug)]
struct Factor {
    form: Form,
    m: Mat6,
    z: Mat6,
}

impl Factor {
    const EMPTY: Factor = Factor {
        form: Form::Free,
        m: [[0.0; MAX]; MAX],
        z: [[0.0; MAX]; MAX],
    };

    /// A free body's: M⁻¹ from its inverse mass and world inverse inertia.
    fn free(&mut self, motion: &SolverMotion) {
        self.form = Form::Free;
        self.m = [[0.0; MAX]; MAX];
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
    fn factor<const N: usize>(&mut self, d: &Mat6, sign: f64) {
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
    fn solve<const N: usize>(&self, y: &mut Vec6) {
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
    fn couple<const N: usize, const K: usize>(&mut self, g: &[[f64; K]; N], d: &mut Mat6) {
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
    fn couple_free<const R: usize>(&mut self, j: &Mat6, s: f64, d: &mut Mat6) {
        let (m, w) = (&self.m, &mut self.z);
        for r in 0..R {
            for i in 0..3 {
                w[i][r] = m[i][i] * j[r][i];
                w[3 + i][r] = (0..3).map(|k| m[3 + i][3 + k] * j[r][3 + k]).sum();
            }
        }
        for r in 0..R {
            for c in 0..=r {
                let k = s * (0..6).map(|i| j[r][i] * w[i][c]).sum::<f64>();
                d[r][c] -= k;
                if r != c {
                    d[c][r] -= k;
                }
            }
        }
    }

    /// M⁻¹t for a free or contracted body (`m` holds M⁻¹: 1/m on the diagonal, then I⁻¹).
    fn through_mass(&self, t: &Vec6) -> Vec6 {
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
    fn send_up<const N: usize, const K: usize>(&self, y: &Vec6, parent: &mut Vec6) {
        for c in 0..K {
            parent[c] += (0..N).map(|i| self.z[i][c] * y[i]).sum::<f64>();
        }
    }

    /// The backward sweep at this node: x = u + Z x_parent, `x` holding u = D⁻¹y (N), `parent`
    /// x_parent (K; none for a root).
    fn take_down<const N: usize, const K: usize>(&self, x: &mut Vec6, parent: Option<&Vec6>) {
        if let Some(xp) = parent {
            for i in 0..N {
                x[i] += (0..K).map(|c| self.z[i][c] * xp[c]).sum::<f64>();
            }
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

/// A node of the tree: a dynamic body (solver index) or a joint (index among the tree's joints).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum NodeKind {
    Body(u32),
    Joint(u32),
}

#[derive(Clone, Copy, Debug)]
struct Node {
    kind: NodeKind,
    /// Index of the parent node in `nodes` (for a joint under a contracted body, that body's
    /// parent joint), or `NONE` for a root.
    parent: u32,
    /// The edge to the parent body (for a joint under a contracted body, to that body): its joint,
    /// and whether its body is that joint's B end (else A). The coupling H[joint, body] is −J, that
    /// joint's Jacobian on that body; H[body, joint] is −Jᵀ.
    edge: (u32, bool),
    /// Whether it is a body without child joints (its D is its mass block).
    free: bool,
    /// For a body with one child joint, not a root: that joint's node (the body is eliminated
    /// first, see the module docs); else `NONE`.
    contracted: u32,
    /// For a joint under a contracted body: that body's node; else `NONE`.
    via: u32,
    /// Its own size (a joint's rows, a body's 6) and its parent's (6 for a root), as last
    /// factored.
    size: (usize, usize),
    /// D, factored.
    factor: Factor,
}

const NONE: u32 = u32::MAX;

/// A kept [`JointTree::response`]: the factorisation (`generation`) and the row (its ends and
/// Jacobian) it was for, and what it left: the inverse effective mass, the kick, and the answer
/// over its tree's nodes (`range`).
#[derive(Clone, Debug, Default)]
struct Weighed {
    generation: u64,
    row: (u32, u32, [f32; 6], [f32; 6]),
    w: f32,
    kick: [(u32, [f64; 6]); 2],
    range: (u32, u32),
    x: Vec<Vec6>,
}

/// One joint's equality rows for the tree: its Jacobian on each end (rows × 6: linear then
/// angular), which ends are dynamic (solver index, 0 for none), and the rows' targets.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TreeRows {
    pub rows: usize,
    pub a: u32,
    pub b: u32,
    pub j_a: Mat6,
    pub j_b: Mat6,
    /// The position error of each row (m or rad), the biased pass's target times its rate.
    pub error: [f32; MAX],
}

impl TreeRows {
    pub fn new(a: u32, b: u32) -> Self {
        Self {
            rows: 0,
            a,
            b,
            j_a: [[0.0; MAX]; MAX],
            j_b: [[0.0; MAX]; MAX],
            error: [0.0; MAX],
        }
    }

    /// Adds a row: linear and angular parts on A and on B, and its position error.
    pub fn push(&mut self, lin_a: Vec3, ang_a: Vec3, lin_b: Vec3, ang_b: Vec3, error: f32) {
        let r = self.rows;
        // In f64, as the solve uses it (exactly the f32 values).
        self.j_a[r] = [lin_a.x, lin_a.y, lin_a.z, ang_a.x, ang_a.y, ang_a.z].map(f64::from);
        self.j_b[r] = [lin_b.x, lin_b.y, lin_b.z, ang_b.x, ang_b.y, ang_b.z].map(f64::from);
        self.error[r] = error;
        self.rows += 1;
    }
}

/// The joint trees of one step: their shape (which joints, in which elimination order), and the
/// buffers of each solve.
///
/// # What is kept between passes and steps
/// - The shape is kept while the joints' dynamic ends are the same as the last step's (the same
///   joints between the same awake bodies): rebuilding it walks every solver body.
/// - The factorisation is kept while no joint's rows change (the masses are the step's): a
///   sub-step's relax pass and the next sub-step's biased pass see the same poses, and
///   `JointRows` keeps the rows of a joint whose ends have not moved.
/// - A scalar row's response and its application through the tree walk only its own tree's nodes
///   (each tree's nodes are contiguous in `nodes`), not every ragdoll of a pile.
/// - A scalar row's response is kept per joint while the factorisation and the row are the same
///   (a sub-step's relax pass and the next sub-step's biased pass), and given again unsolved.
#[derive(Debug, Default)]
pub(crate) struct JointTree {
    nodes: Vec<Node>,
    /// Per solver body: its node, or `NONE`.
    body_node: Vec<u32>,
    /// Per tree joint: its node.
    joint_node: Vec<u32>,
    /// Per node: the range of nodes of its tree (`start, end`).
    tree_of: Vec<(u32, u32)>,
    /// Per joint: the share of each end's J M⁻¹ Jᵀ in its block (see `joint_block`).
    shares: Vec<[f64; 2]>,
    /// The joints' ends the shape was built for, and the number of solver bodies.
    shaped_for: (Vec<(u32, u32)>, usize),
    /// Whether `nodes` hold a factorisation of this step's masses.
    factored: bool,
    /// How many factorisations there have been: which one a kept response was weighed in.
    generation: u64,
    /// Per joint: its axial row's last response (see [`JointTree::response`]).
    weighed: Vec<Weighed>,
    /// The node range the last `response` walked.
    kick_range: (u32, u32),
    /// Scratch: the right-hand side and the solution, per node; each node's D while factoring.
    x: Vec<Vec6>,
    d: Vec<Mat6>,
    /// Per node whose D fell back to Gauss–Jordan: its coupling G (see [`Factor`]), which its
    /// forward step sends up through D⁻¹ (not symmetric).
    coupling: Vec<Mat6>,
    /// The last `response`'s unit impulse: its two bodies and the velocity it gave each.
    kick: [(u32, [f64; 6]); 2],
    /// What the tree's rows carried while scalar rows were applied through it (`apply_response`),
    /// per joint, added to the pass's exact solve.
    pub pending: Vec<[f32; MAX]>,
    /// Scratch for building: union-find over solver bodies, adjacency.
    set: Vec<u32>,
    adjacency: Vec<Vec<(u32, u32)>>,
    /// Scratch for `shape`: which joints join, what the search has visited, the nodes in
    /// post-order with their parents, and the search's stack.
    in_tree: Vec<bool>,
    visited_joint: Vec<bool>,
    visited_body: Vec<bool>,
    order: Vec<(NodeKind, NodeKind)>,
    stack: Vec<(NodeKind, Option<NodeKind>, usize)>,
}

impl JointTree {
    /// Which of `ends` (each joint's dynamic ends, solver indices, 0 for none) join the tree; a
    /// joint that would close a loop among dynamic bodies is left out (`false`). `bodies` is the
    /// number of solver bodies.
    pub fn shape(&mut self, ends: &[(u32, u32)], bodies: usize) -> &[bool] {
        // A new step: the masses may have changed.
        self.factored = false;
        if self.shaped_for.1 == bodies && self.shaped_for.0 == ends {
            return &self.in_tree;
        }
        self.shaped_for.0.clear();
        self.shaped_for.0.extend_from_slice(ends);
        self.shaped_for.1 = bodies;
        self.set.clear();
        self.set.extend(0..bodies as u32);
        fn find(set: &mut [u32], mut i: u32) -> u32 {
            while set[i as usize] != i {
                set[i as usize] = set[set[i as usize] as usize];
                i = set[i as usize];
            }
            i
        }
        let in_tree = &mut self.in_tree;
        in_tree.clear();
        in_tree.resize(ends.len(), false);
        for (k, &(a, b)) in ends.iter().enumerate() {
            if a != 0 && b != 0 {
                let (ra, rb) = (find(&mut self.set, a), find(&mut self.set, b));
                if ra == rb {
                    continue;
                }
                self.set[ra as usize] = rb;
            }
            in_tree[k] = a != 0 || b != 0;
        }
        // Adjacency body → (joint, other body or 0).
        self.adjacency.iter_mut().for_each(Vec::clear);
        self.adjacency.resize(bodies, Vec::new());
        for (k, &(a, b)) in ends.iter().enumerate() {
            if !self.in_tree[k] {
                continue;
            }
            if a != 0 {
                self.adjacency[a as usize].push((k as u32, b));
            }
            if b != 0 {
                self.adjacency[b as usize].push((k as u32, a));
            }
        }
        // Depth-first from each body in index order: nodes in post-order (children first).
        self.nodes.clear();
        self.body_node.clear();
        self.body_node.resize(bodies, NONE);
        self.joint_node.clear();
        self.joint_node.resize(ends.len(), NONE);
        let (visited_joint, visited_body) = (&mut self.visited_joint, &mut self.visited_body);
        visited_joint.clear();
        visited_joint.resize(ends.len(), false);
        visited_body.clear();
        visited_body.resize(bodies, false);
        let order = &mut self.order; // (node, parent) in post-order
        order.clear();
        let stack = &mut self.stack;
        self.tree_of.clear();
        for root in 1..bodies {
            if visited_body[root] || self.adjacency[root].is_empty() {
                continue;
            }
            visited_body[root] = true;
            let start = order.len() as u32;
            // Explicit stack of (node, parent, next neighbour index).
            stack.clear();
            stack.push((NodeKind::Body(root as u32), None, 0));
            while let Some(&mut (node, parent, ref mut next)) = stack.last_mut() {
                let child = match node {
                    NodeKind::Body(i) => {
                        let adj = &self.adjacency[i as usize];
                        let mut found = None;
                        while *next < adj.len() {
                            let (joint, _) = adj[*next];
                            *next += 1;
                            if !visited_joint[joint as usize] {
                                visited_joint[joint as usize] = true;
                                found = Some(NodeKind::Joint(joint));
                                break;
                            }
                        }
                        found
                    }
                    NodeKind::Joint(k) => {
                        let (a, b) = ends[k as usize];
                        let mut found = None;
                        while *next < 2 {
                            let other = if *next == 0 { a } else { b };
                            *next += 1;
                            if other != 0 && !visited_body[other as usize] {
                                visited_body[other as usize] = true;
                                found = Some(NodeKind::Body(other));
                                break;
                            }
                        }
                        found
                    }
                };
                match child {
                    Some(c) => stack.push((c, Some(node), 0)),
                    None => {
                        stack.pop();
                        order.push((node, parent.unwrap_or(node)));
                    }
                }
            }
            let end = order.len() as u32;
            self.tree_of.resize(end as usize, (start, end));
        }
        for (node, _) in &self.order {
            let index = self.nodes.len() as u32;
            match *node {
                NodeKind::Body(i) => self.body_node[i as usize] = index,
                NodeKind::Joint(k) => self.joint_node[k as usize] = index,
            }
            self.nodes.push(Node {
                kind: *node,
                parent: NONE,
                edge: (0, false),
                free: matches!(node, NodeKind::Body(_)),
                contracted: NONE,
                via: NONE,
                size: (MAX, MAX),
                factor: Factor::EMPTY,
            });
        }
        for (i, &(node, parent)) in self.order.iter().enumerate() {
            if node == parent {
                continue;
            }
            let (p, edge) = match (node, parent) {
                (NodeKind::Joint(k), NodeKind::Body(b)) => (self.body_node[b as usize], (k, b)),
                (NodeKind::Body(b), NodeKind::Joint(k)) => (self.joint_node[k as usize], (k, b)),
                _ => unreachable!("the tree alternates bodies and joints"),
            };
            let (k, b) = edge;
            self.nodes[i].parent = p;
            self.nodes[i].edge = (k, ends[k as usize].0 != b);
            self.nodes[p as usize].free = false;
        }
        // A body with one child joint, not a root, is contracted: eliminated first, its child joint
        // hangs from its parent joint (see the module docs).
        let mut children = vec![(0u32, NONE); self.nodes.len()];
        for (i, node) in self.nodes.iter().enumerate() {
            if node.parent != NONE {
                let c = &mut children[node.parent as usize];
                *c = (c.0 + 1, i as u32);
            }
        }
        for i in 0..self.nodes.len() {
            let node = &self.nodes[i];
            if let (NodeKind::Body(_), (1, child)) = (node.kind, children[i])
                && node.parent != NONE
            {
                let parent = node.parent;
                self.nodes[i].contracted = child;
                let joint = &mut self.nodes[child as usize];
                joint.parent = parent;
                joint.via = i as u32;
            }
        }
        // The share of an end's J M⁻¹ Jᵀ in its joint's block: none for a free body (its own
        // Schur complement) or a static end, all of it for a contracted body, else the compliance.
        let share = |b: u32| match self.body_node.get(b as usize) {
            _ if b == 0 => 0.0,
            Some(&i) if i != NONE && self.nodes[i as usize].free => 0.0,
            Some(&i) if i != NONE && self.nodes[i as usize].contracted != NONE => 1.0 + COMPLIANCE,
            _ => COMPLIANCE,
        };
        self.shares.clear();
        self.shares
            .extend(ends.iter().map(|&(a, b)| [share(a), share(b)]));
        self.x.resize(self.nodes.len(), [0.0; MAX]);
        self.coupling.resize(self.nodes.len(), [[0.0; MAX]; MAX]);
        &self.in_tree
    }

    /// Whether the tree has any joint.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Factors the tree's system: `rows[k]` are the rows of joint k (as `shape` was given them;
    /// ignored for joints out of the tree), with the solver bodies' masses in `motions`, unless
    /// it is factored already and no joint's rows have changed since (`changed`).
    pub fn factor(&mut self, rows: &[TreeRows], motions: &[SolverMotion], changed: bool) {
        if self.factored && !changed {
            return;
        }
        self.factored = true;
        self.generation += 1;
        // Blocks: H_bb = M, H_jb = −J_jb, H_jj = −ε·K (see `COMPLIANCE`); each node's D is its
        // block less its children's E_cᵀ D_c⁻¹ E_c, subtracted as each child is factored
        // (children come first). A contracted body's E_cᵀ M⁻¹ E_c on its joints is subtracted
        // here, with their compliance.
        let n = self.nodes.len();
        self.d.resize(n, [[0.0; MAX]; MAX]);
        let (nodes, shares) = (&self.nodes, &self.shares);
        for (node, d) in nodes.iter().zip(&mut self.d) {
            match node.kind {
                NodeKind::Body(_) if node.free || node.contracted != NONE => {}
                NodeKind::Body(b) => body_mass(&motions[b as usize], d),
                NodeKind::Joint(k) => {
                    joint_block(&rows[k as usize], motions, shares[k as usize], d);
                }
            }
        }
        for i in 0..n {
            let node = &self.nodes[i];
            let size = |node: &Node| match node.kind {
                NodeKind::Joint(k) => rows[k as usize].rows,
                NodeKind::Body(_) => MAX,
            };
            let parent_size = match node.parent {
                NONE => MAX,
                p => size(&self.nodes[p as usize]),
            };
            let sizes = (size(node), parent_size);
            if let (NodeKind::Body(b), true) = (node.kind, node.contracted != NONE) {
                // M⁻¹, to find its velocity from its joints' impulses.
                let node = &mut self.nodes[i];
                node.size = sizes;
                node.factor.free(&motions[b as usize]);
                continue;
            }
            // A joint under a contracted body: that body's parent joint's Jacobian on it, and
            // its mass.
            let through = match (node.via, self.nodes.get(node.via as usize)) {
                (NONE, _) | (_, None) => None,
                (_, Some(body)) => {
                    let NodeKind::Body(b) = body.kind else {
                        unreachable!("a joint hangs through a body");
                    };
                    Some((edge_jacobian(body, rows), &motions[b as usize]))
                }
            };
            let (below, above) = self.d.split_at_mut(i + 1);
            let parent = (node.parent != NONE).then(|| &mut above[node.parent as usize - i - 1]);
            let node = &mut self.nodes[i];
            node.size = sizes;
            let coupling = &mut self.coupling[i];
            with_sizes!(
                sizes.0,
                sizes.1,
                factor_node(node, &below[i], parent, through, coupling, rows, motions)
            );
        }
    }

    /// Solves the factored system against the bodies' current velocities and the rows' targets,
    /// `rate` times their errors (0 in the relax pass): applies Δv to the bodies and returns Δλ
    /// per joint row in `impulses`.
    pub fn solve(
        &mut self,
        rows: &[TreeRows],
        rate: f32,
        bodies: &mut [SolverBody],
        impulses: &mut [[f32; MAX]],
    ) {
        self.substitute(rows, (Some(rate), false), 0..self.nodes.len(), |i| {
            (i != 0).then(|| velocity(bodies, i))
        });
        for i in 0..self.nodes.len() {
            match self.nodes[i].kind {
                NodeKind::Body(b) => {
                    let x = self.x[i];
                    let body = &mut bodies[b as usize];
                    body.v += Vec3A::new(x[0] as f32, x[1] as f32, x[2] as f32);
                    body.w += Vec3A::new(x[3] as f32, x[4] as f32, x[5] as f32);
                }
                NodeKind::Joint(k) => {
                    for (out, x) in impulses[k as usize].iter_mut().zip(self.x[i]) {
                        *out = x as f32;
                    }
                }
            }
        }
    }

    /// The inverse effective mass of one more row on solver bodies `a` and `b` (its Jacobian
    /// `j_a`, `j_b`: linear then angular, as `TreeRows` lays them out) with the tree's joints
    /// holding: J·Δv for a unit impulse along it, Δv being the velocity the impulse gives plus the
    /// tree's answer to it. A limit or a motor on the hinge of a light ball far from its pivot
    /// moves the ball's swing, not only its spin.
    ///
    /// `joint` is the row's joint: its last answer is kept, and given again while the tree is not
    /// refactored and the row is the same (a sub-step's relax pass and the next sub-step's biased
    /// pass see the same poses).
    #[allow(clippy::too_many_arguments)] // one row: its two ends
    pub fn response(
        &mut self,
        joint: usize,
        a: u32,
        b: u32,
        j_a: [f32; 6],
        j_b: [f32; 6],
        motions: &[SolverMotion],
        rows: &[TreeRows],
    ) -> f32 {
        if self.weighed.len() <= joint {
            self.weighed.resize_with(joint + 1, Weighed::default);
        }
        let kept = &self.weighed[joint];
        if kept.generation == self.generation && kept.row == (a, b, j_a, j_b) {
            let (start, stop) = kept.range;
            self.x[start as usize..stop as usize].copy_from_slice(&kept.x);
            (self.kick, self.kick_range) = (kept.kick, kept.range);
            return kept.w;
        }
        let w = self.respond(a, b, j_a, j_b, motions, rows);
        let (start, stop) = self.kick_range;
        let kept = &mut self.weighed[joint];
        kept.x.clear();
        kept.x
            .extend_from_slice(&self.x[start as usize..stop as usize]);
        (kept.generation, kept.row, kept.w) = (self.generation, (a, b, j_a, j_b), w);
        (kept.kick, kept.range) = (self.kick, self.kick_range);
        w
    }

    /// [`JointTree::response`], computed.
    fn respond(
        &mut self,
        a: u32,
        b: u32,
        j_a: [f32; 6],
        j_b: [f32; 6],
        motions: &[SolverMotion],
        rows: &[TreeRows],
    ) -> f32 {
        let kick = |index: u32, j: &[f32; 6]| -> [f64; 6] {
            if index == 0 {
                return [0.0; 6];
            }
            let m = &motions[index as usize];
            let lin = m.inv_mass * Vec3::from_slice(&j[0..3]);
            let ang = Mat3::from(m.inv_inertia) * Vec3::from_slice(&j[3..6]);
            [lin.x, lin.y, lin.z, ang.x, ang.y, ang.z].map(f64::from)
        };
        let (ka, kb) = (kick(a, &j_a), kick(b, &j_b));
        // The row's joint is in the tree, so its dynamic ends are nodes of one tree.
        let end = if a != 0 { a } else { b };
        let (start, stop) = self.tree_of[self.body_node[end as usize] as usize];
        self.kick_range = (start, stop);
        self.substitute(rows, (None, true), start as usize..stop as usize, |i| {
            if i == 0 || (i != a && i != b) {
                return None;
            }
            let mut v = [0.0; 6];
            if i == a {
                v = ka;
            }
            if i == b {
                for (v, k) in v.iter_mut().zip(kb) {
                    *v += k;
                }
            }
            Some(v)
        });
        self.kick = [(a, ka), (b, kb)];
        let mut w = 0.0f64;
        for (index, j, kick) in [(a, &j_a, &ka), (b, &j_b, &kb)] {
            if index == 0 {
                continue;
            }
            let node = self.body_node[index as usize];
            let dv = if node == NONE {
                [0.0; MAX]
            } else {
                self.x[node as usize]
            };
            for c in 0..6 {
                w += j[c] as f64 * (kick[c] + dv[c]);
            }
        }
        w as f32
    }

    /// Applies `impulse` times the last [`JointTree::response`]'s unit impulse to the bodies, with
    /// the tree's answer to it, so the next row reads velocities the tree's joints hold; what the
    /// tree's rows carried goes to `pending`.
    pub fn apply_response(&mut self, impulse: f32, bodies: &mut [SolverBody]) {
        let scale = impulse as f64;
        for (index, kick) in self.kick {
            if index != 0 {
                add_scaled(&mut bodies[index as usize], &kick, scale);
            }
        }
        let (start, stop) = self.kick_range;
        for i in start as usize..stop as usize {
            let x = self.x[i];
            match self.nodes[i].kind {
                NodeKind::Body(b) => add_scaled(&mut bodies[b as usize], &x, scale),
                NodeKind::Joint(k) => {
                    for (p, x) in self.pending[k as usize].iter_mut().zip(x) {
                        *p += (x * scale) as f32;
                    }
                }
            }
        }
    }

    /// Forward and back substitution over the nodes `range` (whole trees) against the velocities
    /// `velocity(i)` of solver body i (none for a body at rest, as the static dummy is, or not
    /// kicked by a `response`), and the rows' targets `rate` times their errors when `rate` is
    /// given: leaves Δv per body node and Δλ per joint node in `x`. `sparse`: most velocities are
    /// none (a `response`'s kick).
    fn substitute(
        &mut self,
        rows: &[TreeRows],
        (rate, sparse): (Option<f32>, bool),
        range: std::ops::Range<usize>,
        velocity: impl Fn(u32) -> Option<Vec6>,
    ) {
        // Right-hand side: 0 for bodies, J v + b for joints.
        for i in range.clone() {
            self.x[i] = [0.0; MAX];
            if let NodeKind::Joint(k) = self.nodes[i].kind {
                let r = &rows[k as usize];
                let (va, vb) = (velocity(r.a), velocity(r.b));
                if va.is_some() || vb.is_some() || rate.is_some() {
                    let (va, vb) = (va.unwrap_or_default(), vb.unwrap_or_default());
                    self.x[i] = with_rows!(r.rows, joint_rhs(r, &va, &vb, rate));
                }
            }
        }
        // Forward (leaves up): u_i = L_i⁻¹ y_i, and y_p −= E_iᵀ D_i⁻¹ y_i. Where y is 0 (always
        // at a free or contracted body, into which nothing flows; at most nodes for a sparse
        // kick), so are u and what goes up.
        let (nodes, x, coupling) = (&self.nodes, &mut self.x, &self.coupling);
        for i in range.clone() {
            let node = &nodes[i];
            if node.free || node.contracted != NONE || (sparse && x[i] == [0.0; MAX]) {
                continue;
            }
            let (below, above) = x.split_at_mut(i + 1);
            let parent = (node.parent != NONE).then(|| &mut above[node.parent as usize - i - 1]);
            let (n, k) = node.size;
            with_sizes!(
                n,
                k,
                forward_step(node, &coupling[i], &mut below[i], parent)
            );
        }
        // Backward (roots down): x_i = D_i⁻¹ (y_i − E_i x_parent).
        for i in range.clone().rev() {
            let node = &nodes[i];
            if node.contracted != NONE {
                continue;
            }
            let (below, above) = x.split_at_mut(i + 1);
            let parent = (node.parent != NONE).then(|| &above[node.parent as usize - i - 1]);
            let (n, k) = node.size;
            with_sizes!(n, k, backward_step(node, &mut below[i], parent));
        }
        // A contracted body's velocity from its two joints' impulses: M⁻¹ (J_cᵀ λ_c + J_pᵀ λ_p).
        for i in range {
            let node = &nodes[i];
            if node.contracted == NONE {
                continue;
            }
            let child = &nodes[node.contracted as usize];
            let (c, p) = (node.contracted as usize, node.parent as usize);
            let mut t = [0.0; MAX];
            with_rows!(
                child.size.0,
                add_transposed(edge_jacobian(child, rows), &x[c], &mut t)
            );
            with_rows!(
                node.size.1,
                add_transposed(edge_jacobian(node, rows), &x[p], &mut t)
            );
            x[i] = node.factor.through_mass(&t);
        }
    }
}

/// t += Jᵀλ for the R rows `j` of a Jacobian and their impulses `lambda`.
fn add_transposed<const R: usize>(j: &Mat6, lambda: &Vec6, t: &mut Vec6) {
    for row in 0..R {
        for c in 0..6 {
            t[c] += j[row][c] * lambda[row];
        }
    }
}

/// The Jacobian of a node's edge (see [`Node::edge`]).
fn edge_jacobian<'a>(node: &Node, rows: &'a [TreeRows]) -> &'a Mat6 {
    let r = &rows[node.edge.0 as usize];
    if node.edge.1 { &r.j_b } else { &r.j_a }
}

/// Factors a node of size N under a parent of size K (its D is `d`), keeps its coupling through
/// the factor and subtracts its Schur complement E_iᵀ D_i⁻¹ E_i from its parent's block. A joint
/// under a contracted body comes `through` it: its parent joint's Jacobian on that body, and the
/// body's mass. Where D falls back to Gauss–Jordan, its coupling G goes to `coupling`.
fn factor_node<const N: usize, const K: usize>(
    node: &mut Node,
    d: &Mat6,
    parent: Option<&mut Mat6>,
    through: Option<(&Mat6, &SolverMotion)>,
    coupling: &mut Mat6,
    rows: &[TreeRows],
    motions: &[SolverMotion],
) {
    // G = −E_i: J (N × 6) for a joint under a body, Jᵀ (6 × K) for a body under a joint, J_c M⁻¹
    // J_pᵀ (N × K) for a joint under a joint through a contracted body (the sign cancels in
    // Eᵀ D⁻¹ E).
    let j = parent.as_ref().map(|_| edge_jacobian(node, rows));
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
            factor.couple_free::<K>(j, 1.0 + COMPLIANCE, parent);
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
                    Some((jp, motion)) => joint_coupling::<N, K>(j, jp, motion),
                };
                factor.couple::<N, K>(&g, parent);
                keep(&g, factor.form, coupling);
            }
        }
    }
}

/// J_c M⁻¹ J_pᵀ (N × K): the coupling of a joint's N rows `jc` and its parent joint's K rows `jp`
/// on the contracted body between them (its inverse mass and world inverse inertia in `motion`).
fn joint_coupling<const N: usize, const K: usize>(
    jc: &Mat6,
    jp: &Mat6,
    motion: &SolverMotion,
) -> [[f64; K]; N] {
    let inv_mass = motion.inv_mass as f64;
    let i = Mat3::from(motion.inv_inertia)
        .to_cols_array()
        .map(f64::from);
    // M⁻¹ J_pᵀ, column by column (one per parent row); `i` holds I⁻¹'s columns.
    let mut w = [[0.0; MAX]; K];
    for c in 0..K {
        let (x, y, z) = (jp[c][3], jp[c][4], jp[c][5]);
        w[c] = [
            inv_mass * jp[c][0],
            inv_mass * jp[c][1],
            inv_mass * jp[c][2],
            i[0] * x + i[3] * y + i[6] * z,
            i[1] * x + i[4] * y + i[7] * z,
            i[2] * x + i[5] * y + i[8] * z,
        ];
    }
    let mut g = [[0.0; K]; N];
    for r in 0..N {
        for c in 0..K {
            let mut s = 0.0;
            for k in 0..6 {
                s += jc[r][k] * w[c][k];
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
fn joint_rhs<const R: usize>(r: &TreeRows, va: &Vec6, vb: &Vec6, rate: Option<f32>) -> Vec6 {
    let mut y = [0.0; MAX];
    for row in 0..R {
        let mut s = rate.map_or(0.0, |rate| (rate * r.error[row]) as f64);
        for c in 0..6 {
            s += r.j_a[row][c] * va[c] + r.j_b[row][c] * vb[c];
        }
        y[row] = s;
    }
    y
}

/// The forward sweep's step at a node of size N under a parent of size K: y_parent −=
/// E_iᵀ D_i⁻¹ y_i, and u = D_i⁻¹y_i kept in `x`.
fn forward_step<const N: usize, const K: usize>(
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
/// E_i x_p) = u + Z x_p, from the forward sweep's u in `x` and x_p in `parent` (none for a root).
fn backward_step<const N: usize, const K: usize>(node: &Node, x: &mut Vec6, parent: Option<&Vec6>) {
    node.factor.take_down::<N, K>(x, parent);
}

/// Relative compliance of the rows in the exact solve: H_jj = −ε·K_jj. It makes a joint whose
/// other end is static (a leaf of the tree, whose block would be 0) invertible, and is far below
/// anything that shows in the answer (the rows are rigid to 1 part in 10⁶ of their response).
const COMPLIANCE: f64 = 1e-6;

/// A joint's block before its children's Schur complements: d = −Σ s_e·J_e M_e⁻¹ J_eᵀ over its
/// ends e, with `share` s_e (A's, B's): ε (the compliance, `COMPLIANCE`) for an end that is a node
/// of the tree; 1 + ε for a contracted body (its own Schur complement, J M⁻¹ Jᵀ, with the
/// compliance); 0 for a free body, which subtracts its 1 + ε with its own Schur complement, and
/// for a static end.
fn joint_block(rows: &TreeRows, motions: &[SolverMotion], share: [f64; 2], d: &mut Mat6) {
    // Only its rows' corner is read.
    with_rows!(rows.rows, clear_corner(d));
    for ((index, j), s) in [(rows.a, &rows.j_a), (rows.b, &rows.j_b)]
        .into_iter()
        .zip(share)
    {
        if s != 0.0 {
            let motion = &motions[index as usize];
            with_rows!(rows.rows, subtract_free(motion, j, s, d));
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
fn subtract_free<const R: usize>(motion: &SolverMotion, j: &Mat6, s: f64, d: &mut Mat6) {
    let inv_mass = s * motion.inv_mass as f64;
    let inv_inertia = Mat3::from(motion.inv_inertia);
    let inv_inertia: [[f64; 3]; 3] =
        std::array::from_fn(|r| std::array::from_fn(|c| s * inv_inertia.col(c)[r] as f64));
    // s·I⁻¹·ang_r per row.
    let u: [[f64; 3]; R] = std::array::from_fn(|r| {
        std::array::from_fn(|a| (0..3).map(|b| inv_inertia[a][b] * j[r][3 + b]).sum())
    });
    for r in 0..R {
        for c in 0..=r {
            let lin: f64 = (0..3).map(|a| j[r][a] * j[c][a]).sum();
            let ang: f64 = (0..3).map(|a| u[r][a] * j[c][3 + a]).sum();
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
fn body_mass(motion: &SolverMotion, d: &mut Mat6) {
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

fn velocity(bodies: &[SolverBody], index: u32) -> [f64; 6] {
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
fn add_scaled(body: &mut SolverBody, dv: &[f64], scale: f64) {
    let at = |i: usize| (dv[i] * scale) as f32;
    body.v += Vec3A::new(at(0), at(1), at(2));
    body.w += Vec3A::new(at(3), at(4), at(5));
}

#[cfg(test)]
mod tests {
    use glam::{Mat3A, Quat, Vec3};

    use super::*;
    use crate::util::SplitMix64;

    /// A dynamic body of random mass and inertia (mass ratios up to 100), turned at random.
    fn motion(rng: &mut SplitMix64) -> SolverMotion {
        let mut scale = || 10f32.powf(rng.next_signed());
        let (inv_mass, moments) = (scale(), Vec3::new(scale(), scale(), scale()));
        let turn = Quat::from_euler(
            glam::EulerRot::XYZ,
            rng.next_signed() * 3.0,
            rng.next_signed() * 3.0,
            rng.next_signed() * 3.0,
        );
        let r = Mat3::from_quat(turn);
        SolverMotion {
            inv_mass,
            inv_inertia: Mat3A::from(r * Mat3::from_diagonal(moments) * r.transpose()),
            ..SolverMotion::DUMMY
        }
    }

    fn random_rows(rng: &mut SplitMix64, (a, b): (u32, u32), rows: usize) -> TreeRows {
        let mut r = TreeRows::new(a, b);
        let mut v = || Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
        for _ in 0..rows {
            let (la, aa, lb, ab, error) = (v(), v(), v(), v(), v().x);
            r.push(la, aa, lb, ab, error);
        }
        r
    }

    /// The solution of the dense system `h x = y` by Gaussian elimination with partial pivoting.
    fn dense_solve(mut h: Vec<Vec<f64>>, mut y: Vec<f64>) -> Vec<f64> {
        let n = y.len();
        for col in 0..n {
            let p = (col..n)
                .max_by(|&p, &q| h[p][col].abs().total_cmp(&h[q][col].abs()))
                .unwrap();
            h.swap(col, p);
            y.swap(col, p);
            for r in col + 1..n {
                let f = h[r][col] / h[col][col];
                for c in col..n {
                    h[r][c] -= f * h[col][c];
                }
                y[r] -= f * y[col];
            }
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|c| h[i][c] * x[c]).sum();
            x[i] = (y[i] - s) / h[i][i];
        }
        x
    }

    /// The tree's solve of branching trees (joints of 1, 3, 5 and 6 rows, to the world at either
    /// end, free bodies among them, a joint closing a loop left out) is the dense solve of the
    /// same system, H = [M −Jᵀ; −J −ε·K], to the f32 the answer is given in.
    #[test]
    fn the_tree_solves_the_dense_system() {
        let mut rng = SplitMix64(7);
        let ends: Vec<(u32, u32)> = vec![
            (0, 1),
            (1, 2),
            (2, 3),
            (2, 4),
            (4, 5),
            (5, 0),
            (3, 6),
            (7, 6),
            (7, 4), // closes the loop 2–3–6–7–4
            (8, 0),
            (8, 9),
        ];
        let counts = [3, 5, 3, 6, 1, 3, 3, 5, 3, 6, 1];
        let bodies = 10;
        let motions: Vec<SolverMotion> = std::iter::once(SolverMotion::DUMMY)
            .chain((1..bodies).map(|_| motion(&mut rng)))
            .collect();
        let rows: Vec<TreeRows> = ends
            .iter()
            .zip(counts)
            .map(|(&e, n)| random_rows(&mut rng, e, n))
            .collect();
        let mut start = vec![SolverBody::DUMMY; bodies];
        for b in &mut start[1..] {
            let mut v = || Vec3A::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
            (b.v, b.w) = (v(), v());
        }
        let mut tree = JointTree::default();
        let in_tree = tree.shape(&ends, bodies).to_vec();
        assert_eq!(in_tree.iter().filter(|&&t| !t).count(), 1);
        assert!(!in_tree[8]);
        tree.factor(&rows, &motions, true);
        let mut solved = start.clone();
        let mut impulses = vec![[0.0f32; MAX]; ends.len()];
        tree.solve(&rows, 1.0, &mut solved, &mut impulses);

        // The dense system: 6 unknowns per body 1.., then each tree joint's rows.
        let joints: Vec<usize> = (0..ends.len()).filter(|&k| in_tree[k]).collect();
        let mut offset = vec![0; ends.len()];
        let mut n = 6 * (bodies - 1);
        for &k in &joints {
            offset[k] = n;
            n += counts[k];
        }
        let mut h = vec![vec![0.0; n]; n];
        let mut y = vec![0.0; n];
        for b in 1..bodies {
            let mut d = [[0.0; MAX]; MAX];
            body_mass(&motions[b], &mut d);
            for i in 0..6 {
                for j in 0..6 {
                    h[6 * (b - 1) + i][6 * (b - 1) + j] = d[i][j];
                }
            }
        }
        for &k in &joints {
            let r = &rows[k];
            let o = offset[k];
            let mut d = [[0.0; MAX]; MAX];
            let share = [r.a, r.b].map(|e| if e == 0 { 0.0 } else { COMPLIANCE });
            joint_block(r, &motions, share, &mut d);
            for i in 0..r.rows {
                for j in 0..r.rows {
                    h[o + i][o + j] = d[i][j];
                }
                y[o + i] = r.error[i] as f64;
            }
            for (end, j) in [(r.a, &r.j_a), (r.b, &r.j_b)] {
                if end == 0 {
                    continue;
                }
                let v = velocity(&start, end);
                let ob = 6 * (end as usize - 1);
                for i in 0..r.rows {
                    for c in 0..6 {
                        h[o + i][ob + c] = -j[i][c];
                        h[ob + c][o + i] = -j[i][c];
                        y[o + i] += j[i][c] * v[c];
                    }
                }
            }
        }
        let x = dense_solve(h, y);

        let largest = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let close = |got: f64, want: f64| (got - want).abs() <= 1e-5 * largest;
        for b in 1..bodies {
            let (before, after) = (velocity(&start, b as u32), velocity(&solved, b as u32));
            for c in 0..6 {
                let want = x[6 * (b - 1) + c];
                assert!(close(after[c] - before[c], want), "body {b}: Δv {c}");
            }
        }
        for &k in &joints {
            for i in 0..counts[k] {
                let want = x[offset[k] + i];
                assert!(close(impulses[k][i] as f64, want), "joint {k}: row {i}");
            }
        }
    }

    /// A joint with a row twice over: its block is singular, the factorisation falls back to
    /// Gauss–Jordan, and the repeated row gets no impulse of its own; the joint still holds.
    #[test]
    fn a_redundant_row_gets_zero() {
        let mut rng = SplitMix64(11);
        let motions = [SolverMotion::DUMMY, motion(&mut rng)];
        let mut rows = random_rows(&mut rng, (0, 1), 3);
        rows.j_b[3] = rows.j_b[0];
        rows.error[3] = rows.error[0];
        rows.rows = 4;
        let mut bodies = [SolverBody::DUMMY; 2];
        bodies[1].v = Vec3A::new(0.3, -0.2, 0.5);
        bodies[1].w = Vec3A::new(-0.4, 0.1, 0.2);
        let mut tree = JointTree::default();
        tree.shape(&[(0, 1)], 2);
        tree.factor(std::slice::from_ref(&rows), &motions, true);
        let mut impulses = [[0.0f32; MAX]];
        tree.solve(std::slice::from_ref(&rows), 1.0, &mut bodies, &mut impulses);
        let node = tree.joint_node[0] as usize;
        assert_eq!(tree.nodes[node].factor.form, Form::Inverse);
        let impulse = impulses[0];
        assert!(impulse.iter().all(|i| i.is_finite()), "{impulse:?}");
        assert!(impulse[0] == 0.0 || impulse[3] == 0.0, "{impulse:?}");
        let v = velocity(&bodies, 1);
        for row in 0..4 {
            let speed: f64 = (0..6).map(|c| rows.j_b[row][c] * v[c]).sum();
            assert!(
                (speed + rows.error[row] as f64).abs() < 1e-5,
                "row {row}: {speed}"
            );
        }
    }

    /// Redundant rows on both joints of a contracted body (world – 1 – 2 – 3, body 2 contracted,
    /// its joints' blocks falling back to Gauss–Jordan): every row still holds after the solve.
    #[test]
    fn redundant_rows_through_a_contracted_body_hold() {
        let mut rng = SplitMix64(13);
        let motions: Vec<SolverMotion> = std::iter::once(SolverMotion::DUMMY)
            .chain((1..4).map(|_| motion(&mut rng)))
            .collect();
        let ends = [(0, 1), (1, 2), (2, 3)];
        let mut rows: Vec<TreeRows> = ends.iter().map(|&e| random_rows(&mut rng, e, 3)).collect();
        for r in &mut rows[1..] {
            (r.j_a[3], r.j_b[3], r.error[3]) = (r.j_a[1], r.j_b[1], r.error[1]);
            r.rows = 4;
        }
        let mut bodies = vec![SolverBody::DUMMY; 4];
        for b in &mut bodies[1..] {
            let mut v = || Vec3A::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
            (b.v, b.w) = (v(), v());
        }
        let mut tree = JointTree::default();
        tree.shape(&ends, 4);
        tree.factor(&rows, &motions, true);
        let body = &tree.nodes[tree.body_node[2] as usize];
        assert_ne!(body.contracted, NONE, "body 2 is contracted");
        for k in 1..3 {
            let node = tree.joint_node[k] as usize;
            assert_eq!(tree.nodes[node].factor.form, Form::Inverse, "joint {k}");
        }
        let mut impulses = vec![[0.0f32; MAX]; 3];
        tree.solve(&rows, 1.0, &mut bodies, &mut impulses);
        assert!(
            impulses.iter().flatten().all(|i| i.is_finite()),
            "{impulses:?}"
        );
        for (k, r) in rows.iter().enumerate() {
            let (va, vb) = (velocity(&bodies, r.a), velocity(&bodies, r.b));
            for row in 0..r.rows {
                let speed: f64 = (0..6)
                    .map(|c| r.j_a[row][c] * va[c] + r.j_b[row][c] * vb[c])
                    .sum();
                assert!(
                    (speed + r.error[row] as f64).abs() < 1e-4,
                    "joint {k}, row {row}: {speed}"
                );
            }
        }
    }
}
