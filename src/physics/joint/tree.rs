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

// Block arithmetic indexes rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

use glam::{Mat3, Vec3, Vec3A};

use crate::physics::solve::solver_body::{SolverBody, SolverMotion};

/// The largest block: a body's 6 degrees of freedom, or a weld's 6 rows.
const MAX: usize = 6;

/// A dense block of at most 6 × 6, row-major, f64.
#[derive(Clone, Copy, Debug)]
struct Block {
    rows: usize,
    cols: usize,
    m: [[f64; MAX]; MAX],
}

impl Block {
    fn zero(rows: usize, cols: usize) -> Self {
        Self {
            rows,
            cols,
            m: [[0.0; MAX]; MAX],
        }
    }

    /// self · other
    fn mul(&self, other: &Block) -> Block {
        let mut out = Block::zero(self.rows, other.cols);
        for i in 0..self.rows {
            for k in 0..self.cols {
                let a = self.m[i][k];
                if a != 0.0 {
                    for j in 0..other.cols {
                        out.m[i][j] += a * other.m[k][j];
                    }
                }
            }
        }
        out
    }

    /// selfᵀ · other
    fn tmul(&self, other: &Block) -> Block {
        let mut out = Block::zero(self.cols, other.cols);
        for k in 0..self.rows {
            for i in 0..self.cols {
                let a = self.m[k][i];
                if a != 0.0 {
                    for j in 0..other.cols {
                        out.m[i][j] += a * other.m[k][j];
                    }
                }
            }
        }
        out
    }

    fn sub_assign(&mut self, other: &Block) {
        for i in 0..self.rows {
            for j in 0..self.cols {
                self.m[i][j] -= other.m[i][j];
            }
        }
    }

    fn times(&self, x: &[f64; MAX]) -> [f64; MAX] {
        let mut out = [0.0; MAX];
        for (i, o) in out.iter_mut().enumerate().take(self.rows) {
            *o = (0..self.cols).map(|j| self.m[i][j] * x[j]).sum();
        }
        out
    }

    fn t_times(&self, x: &[f64; MAX]) -> [f64; MAX] {
        let mut out = [0.0; MAX];
        for (j, o) in out.iter_mut().enumerate().take(self.cols) {
            *o = (0..self.rows).map(|i| self.m[i][j] * x[i]).sum();
        }
        out
    }

    /// The inverse of a definite block (every D of the tree: positive for a body, negative for a
    /// joint) by Cholesky factorisation of ±D, L⁻¹ and then L⁻ᵀL⁻¹; Gauss–Jordan where it is not
    /// definite (a redundant row).
    fn inverse_definite(&self) -> Block {
        let n = self.rows;
        let sign = if self.m[0][0] < 0.0 { -1.0 } else { 1.0 };
        // L with ±D = L Lᵀ, lower triangular.
        let mut l = [[0.0f64; MAX]; MAX];
        for j in 0..n {
            let mut d = sign * self.m[j][j];
            for k in 0..j {
                d -= l[j][k] * l[j][k];
            }
            // (NaN fails too.)
            if d.is_nan() || d <= 1e-12 * (sign * self.m[j][j]).abs() {
                return self.inverse();
            }
            let d = d.sqrt();
            l[j][j] = d;
            for i in j + 1..n {
                let mut v = sign * self.m[i][j];
                for k in 0..j {
                    v -= l[i][k] * l[j][k];
                }
                l[i][j] = v / d;
            }
        }
        // W = L⁻¹ (lower triangular), then (±D)⁻¹ = Wᵀ W.
        let mut w = [[0.0f64; MAX]; MAX];
        for i in 0..n {
            w[i][i] = 1.0 / l[i][i];
            for j in 0..i {
                let mut v = 0.0;
                for k in j..i {
                    v -= l[i][k] * w[k][j];
                }
                w[i][j] = v / l[i][i];
            }
        }
        let mut out = Block::zero(n, n);
        for i in 0..n {
            for j in 0..=i {
                let mut v = 0.0;
                for k in i..n {
                    v += w[k][i] * w[k][j];
                }
                out.m[i][j] = sign * v;
                out.m[j][i] = sign * v;
            }
        }
        out
    }

    /// The inverse of a square block by Gauss–Jordan elimination with partial pivoting (the
    /// blocks are definite, positive for bodies and negative for joints, so pivots do not vanish
    /// unless a row is redundant: such a row gets a zero, it constrains nothing new).
    fn inverse(&self) -> Block {
        let n = self.rows;
        let mut a = self.m;
        let mut inv = Block::zero(n, n);
        for i in 0..n {
            inv.m[i][i] = 1.0;
        }
        // A pivot is judged against its own row's diagonal: the blocks are badly scaled (a link's
        // inertia beside a joint's 1/ε), so a threshold against the largest entry zeroed real rows.
        let diagonal: [f64; MAX] = std::array::from_fn(|i| if i < n { a[i][i].abs() } else { 0.0 });
        for col in 0..n {
            let pivot = (col..n)
                .max_by(|&p, &q| a[p][col].abs().total_cmp(&a[q][col].abs()))
                .unwrap_or(col);
            if a[pivot][col].abs() <= 1e-12 * diagonal[col].max(1e-300) {
                // A redundant row: leave it out (its column and row of the inverse stay zero).
                for k in 0..n {
                    a[col][k] = 0.0;
                    inv.m[col][k] = 0.0;
                }
                continue;
            }
            a.swap(col, pivot);
            inv.m.swap(col, pivot);
            let p = 1.0 / a[col][col];
            for k in 0..n {
                a[col][k] *= p;
                inv.m[col][k] *= p;
            }
            for r in 0..n {
                if r != col && a[r][col] != 0.0 {
                    let f = a[r][col];
                    for k in 0..n {
                        a[r][k] -= f * a[col][k];
                        inv.m[r][k] -= f * inv.m[col][k];
                    }
                }
            }
        }
        inv
    }
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
    /// Index of the parent node in `nodes`, or `NONE` for a root.
    parent: u32,
    /// H[self, parent] (this node's size × its parent's).
    e: Block,
    /// D⁻¹ after factoring.
    d_inv: Block,
}

const NONE: u32 = u32::MAX;

/// One joint's equality rows for the tree: its Jacobian on each end (rows × 6: linear then
/// angular), which ends are dynamic (solver index, 0 for none), and the rows' targets.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TreeRows {
    pub rows: usize,
    pub a: u32,
    pub b: u32,
    pub j_a: [[f32; MAX]; MAX],
    pub j_b: [[f32; MAX]; MAX],
    /// The bias of each row (velocity, m/s or rad/s): the position error times the bias rate.
    pub bias: [f32; MAX],
}

impl TreeRows {
    pub fn new(a: u32, b: u32) -> Self {
        Self {
            rows: 0,
            a,
            b,
            j_a: [[0.0; MAX]; MAX],
            j_b: [[0.0; MAX]; MAX],
            bias: [0.0; MAX],
        }
    }

    /// Adds a row: linear and angular parts on A and on B, and its bias.
    pub fn push(&mut self, lin_a: Vec3, ang_a: Vec3, lin_b: Vec3, ang_b: Vec3, bias: f32) {
        let r = self.rows;
        self.j_a[r] = [lin_a.x, lin_a.y, lin_a.z, ang_a.x, ang_a.y, ang_a.z];
        self.j_b[r] = [lin_b.x, lin_b.y, lin_b.z, ang_b.x, ang_b.y, ang_b.z];
        self.bias[r] = bias;
        self.rows += 1;
    }
}

/// A joint's rows' Jacobians as a factorisation saw them: the row count, J on A and on B.
type Jacobians = (usize, [[f32; MAX]; MAX], [[f32; MAX]; MAX]);

/// The joint trees of one step: their shape (which joints, in which elimination order), and the
/// buffers of each solve.
///
/// # What is kept between passes and steps
/// - The shape is kept while the joints' dynamic ends are the same as the last step's (the same
///   joints between the same awake bodies): rebuilding it walks every solver body.
/// - The factorisation is kept while the rows' Jacobians are the same bit for bit (the masses are
///   the step's): a sub-step's relax pass and the next sub-step's biased pass see the same poses.
/// - A scalar row's response and its application through the tree walk only its own tree's nodes
///   (each tree's nodes are contiguous in `nodes`), not every ragdoll of a pile.
#[derive(Debug, Default)]
pub(crate) struct JointTree {
    nodes: Vec<Node>,
    /// Per solver body: its node, or `NONE`.
    body_node: Vec<u32>,
    /// Per tree joint: its node.
    joint_node: Vec<u32>,
    /// Per node: the range of nodes of its tree (`start, end`).
    tree_of: Vec<(u32, u32)>,
    /// The joints' ends the shape was built for, and the number of solver bodies.
    shaped_for: (Vec<(u32, u32)>, usize),
    /// Whether `nodes` hold a factorisation, and the Jacobians it was made from (per tree joint,
    /// as `factor` was given them).
    factored: bool,
    factored_rows: Vec<Jacobians>,
    /// The node range the last `response` walked.
    kick_range: (u32, u32),
    /// Scratch: the right-hand side and the solution, per node; each node's D while factoring.
    x: Vec<[f64; MAX]>,
    d: Vec<Block>,
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
                e: Block::zero(0, 0),
                d_inv: Block::zero(0, 0),
            });
        }
        for (i, (node, parent)) in self.order.iter().enumerate() {
            if node != parent {
                self.nodes[i].parent = match *parent {
                    NodeKind::Body(b) => self.body_node[b as usize],
                    NodeKind::Joint(k) => self.joint_node[k as usize],
                };
            }
        }
        self.x.resize(self.nodes.len(), [0.0; MAX]);
        &self.in_tree
    }

    /// Whether the tree has any joint.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Factors the tree's system: `rows[k]` are the rows of joint k (as `shape` was given them;
    /// ignored for joints out of the tree), with the solver bodies' masses in `motions`.
    pub fn factor(&mut self, rows: &[TreeRows], motions: &[SolverMotion]) {
        if self.factored && self.same_jacobians(rows) {
            return;
        }
        self.factored = true;
        self.factored_rows.clear();
        for node in &self.nodes {
            if let NodeKind::Joint(k) = node.kind {
                let r = &rows[k as usize];
                self.factored_rows.push((r.rows, r.j_a, r.j_b));
            }
        }
        // Blocks: H_bb = M, H_jb = −J_jb, H_jj = 0; each node's D is its block less its
        // children's E_cᵀ D_c⁻¹ E_c, subtracted as each child is factored (children come first).
        let n = self.nodes.len();
        self.d.clear();
        for node in &self.nodes {
            self.d.push(match node.kind {
                NodeKind::Body(b) => {
                    let m = &motions[b as usize];
                    body_mass(m.inv_mass, &Mat3::from(m.inv_inertia))
                }
                NodeKind::Joint(k) => compliance(&rows[k as usize], motions),
            });
        }
        for i in 0..n {
            let (kind, parent) = (self.nodes[i].kind, self.nodes[i].parent);
            self.nodes[i].d_inv = self.d[i].inverse_definite();
            if parent != NONE {
                let e = coupling(kind, self.nodes[parent as usize].kind, rows);
                let s = e.tmul(&self.nodes[i].d_inv.mul(&e));
                self.d[parent as usize].sub_assign(&s);
                self.nodes[i].e = e;
            }
        }
    }

    /// Whether the tree's joints' rows have the Jacobians the factorisation was made from.
    fn same_jacobians(&self, rows: &[TreeRows]) -> bool {
        let mut kept = self.factored_rows.iter();
        self.nodes.iter().all(|node| match node.kind {
            NodeKind::Joint(k) => {
                let r = &rows[k as usize];
                kept.next()
                    .is_some_and(|&(n, j_a, j_b)| n == r.rows && j_a == r.j_a && j_b == r.j_b)
            }
            NodeKind::Body(_) => true,
        })
    }

    /// Solves the factored system against the bodies' current velocities and the rows' biases:
    /// applies Δv to the bodies and returns Δλ per joint row in `impulses`.
    pub fn solve(
        &mut self,
        rows: &[TreeRows],
        bodies: &mut [SolverBody],
        impulses: &mut [[f32; MAX]],
    ) {
        self.substitute(rows, true, 0..self.nodes.len(), |i| velocity(bodies, i));
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
    #[allow(clippy::too_many_arguments)] // one row: its two ends
    pub fn response(
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
        self.substitute(rows, false, start as usize..stop as usize, |i| {
            let mut v = [0.0; 6];
            if i != 0 && i == a {
                v = ka;
            }
            if i != 0 && i == b {
                for (v, k) in v.iter_mut().zip(kb) {
                    *v += k;
                }
            }
            v
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
    /// `velocity(i)` of solver body i (and the rows' biases when `bias`): leaves Δv per body node
    /// and Δλ per joint node in `x`.
    fn substitute(
        &mut self,
        rows: &[TreeRows],
        bias: bool,
        range: std::ops::Range<usize>,
        velocity: impl Fn(u32) -> [f64; 6],
    ) {
        // Right-hand side: 0 for bodies, J v + b for joints.
        for i in range.clone() {
            self.x[i] = [0.0; MAX];
            if let NodeKind::Joint(k) = self.nodes[i].kind {
                let r = &rows[k as usize];
                let (va, vb) = (velocity(r.a), velocity(r.b));
                for row in 0..r.rows {
                    let mut s = if bias { r.bias[row] as f64 } else { 0.0 };
                    for c in 0..6 {
                        s += r.j_a[row][c] as f64 * va[c] + r.j_b[row][c] as f64 * vb[c];
                    }
                    self.x[i][row] = s;
                }
            }
        }
        // Forward (leaves up): y_p −= E_cᵀ D_c⁻¹ y_c.
        for i in range.clone() {
            let p = self.nodes[i].parent;
            if p != NONE {
                let node = &self.nodes[i];
                let z = node.d_inv.times(&self.x[i]);
                let contribution = node.e.t_times(&z);
                for (y, c) in self.x[p as usize].iter_mut().zip(contribution) {
                    *y -= c;
                }
            }
        }
        // Backward (roots down): x_i = D_i⁻¹ (y_i − E_i x_parent).
        for i in range.rev() {
            let node = &self.nodes[i];
            let mut y = self.x[i];
            if node.parent != NONE {
                let ex = node.e.times(&self.x[node.parent as usize]);
                for (v, e) in y.iter_mut().zip(ex) {
                    *v -= e;
                }
            }
            self.x[i] = node.d_inv.times(&y);
        }
    }
}

/// Relative compliance of the rows in the exact solve: H_jj = −ε·K_jj. It makes a joint whose
/// other end is static (a leaf of the tree, whose block would be 0) invertible, and is far below
/// anything that shows in the answer (the rows are rigid to 1 part in 10⁶ of their response).
const COMPLIANCE: f64 = 1e-6;

/// −ε·J M⁻¹ Jᵀ of a joint's rows, over its dynamic ends.
fn compliance(rows: &TreeRows, motions: &[SolverMotion]) -> Block {
    let mut out = Block::zero(rows.rows, rows.rows);
    for (index, j) in [(rows.a, &rows.j_a), (rows.b, &rows.j_b)] {
        if index == 0 {
            continue;
        }
        let m = &motions[index as usize];
        let inv_inertia = Mat3::from(m.inv_inertia);
        for r in 0..rows.rows {
            let (lin_r, ang_r) = (Vec3::from_slice(&j[r][0..3]), Vec3::from_slice(&j[r][3..6]));
            let ang_r = inv_inertia * ang_r;
            for c in 0..rows.rows {
                let (lin_c, ang_c) = (Vec3::from_slice(&j[c][0..3]), Vec3::from_slice(&j[c][3..6]));
                let k = m.inv_mass * lin_r.dot(lin_c) + ang_r.dot(ang_c);
                out.m[r][c] -= COMPLIANCE * k as f64;
            }
        }
    }
    out
}

/// A body's 6 × 6 mass block: m·1 and the world inertia.
fn body_mass(inv_mass: f32, inv_inertia: &Mat3) -> Block {
    let mut b = Block::zero(6, 6);
    let m = if inv_mass > 0.0 {
        1.0 / inv_mass as f64
    } else {
        0.0
    };
    for i in 0..3 {
        b.m[i][i] = m;
    }
    let inertia = Block {
        rows: 3,
        cols: 3,
        m: {
            let mut m = [[0.0; MAX]; MAX];
            for (i, row) in m.iter_mut().enumerate().take(3) {
                for (j, v) in row.iter_mut().enumerate().take(3) {
                    *v = inv_inertia.col(j)[i] as f64;
                }
            }
            m
        },
    }
    .inverse();
    for i in 0..3 {
        for j in 0..3 {
            b.m[3 + i][3 + j] = inertia.m[i][j];
        }
    }
    b
}

/// H[node, parent]: −J (joint rows × body) or −Jᵀ (body × joint rows).
fn coupling(node: NodeKind, parent: NodeKind, rows: &[TreeRows]) -> Block {
    let jacobian = |k: u32, b: u32| {
        let r = &rows[k as usize];
        let j = if r.a == b { &r.j_a } else { &r.j_b };
        let mut out = Block::zero(r.rows, 6);
        for i in 0..r.rows {
            for c in 0..6 {
                out.m[i][c] = -(j[i][c] as f64);
            }
        }
        out
    };
    match (node, parent) {
        (NodeKind::Joint(k), NodeKind::Body(b)) => jacobian(k, b),
        (NodeKind::Body(b), NodeKind::Joint(k)) => {
            let j = jacobian(k, b);
            let mut t = Block::zero(6, j.rows);
            for i in 0..j.rows {
                for c in 0..6 {
                    t.m[c][i] = j.m[i][c];
                }
            }
            t
        }
        _ => unreachable!("the tree alternates bodies and joints"),
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
