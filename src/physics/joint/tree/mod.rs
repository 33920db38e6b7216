//! An exact solve of the joints' equality rows where the joints form trees (chains, ragdolls,
//! bridges between two anchors): Baraff's linear-time elimination ("Linear-Time Dynamics using
//! Lagrange Multipliers", SIGGRAPH 1996).
//!
//! # Why not Gauss–Seidel alone
//! A chain holding a load a hundred times a link is the classic failure of sequential impulses: a
//! row's effective mass is a link's, so each sweep moves the load by a link's share of its error
//! and the chain stretches until the soft springs carry the load (13 % of its length at the
//! defaults with `Settings::joint_tree` off, 25 % swinging; `tests/physics/joints.rs`,
//! `a_chain_holds_a_load_a_hundred_times_a_link_only_with_the_exact_tree`); an integral term
//! that removes that stretch winds up and throws the chain apart. Mass ratios along a chain are
//! what a joint user meets first (a wrecking ball, a ragdoll's torso on its arms), so the
//! equality rows are solved exactly instead.
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
//! A hinge's or a slider's limits and motor stay scalar rows, solved after the tree's (see "Order"
//! in `joint`) with their mass through the tree (`JointTree::response`) and applied through it
//! (`apply_response`): with the two bodies' mass alone, a limit on the hinge of a 4 g ball on a 1 m
//! arm saw 250 times too little mass and leaked to 126°; applied to the two bodies alone, the next
//! row read the ball's spin before the tree turned it into swing, and the scene blew up in a step.
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
//! compile-time sizes (`with_rows!`, `with_sizes!`); the sweeps call each node's steps at its
//! sizes as its factorisation chose them ([`Sweeps`]).
//!
//! # Masses
//! A body weighs in the tree with its inverse mass and its world inverse inertia at its rotation
//! when the tree is factored, not at the step's start as the contacts take it, each principal
//! moment raised to the step's floor as every row raises it (`SolverMotion::inertia_floor`; see
//! "Geometric stiffness" in `joint`). The rows and the masses then depend on the poses alone (and
//! on the floors, which change only when a joint's held pull does), so a step's first passes,
//! which see the poses of the last step's last pass to the bit, find the factorisation made: four
//! a step, not five (a hanging chain of 100 links, 877 M → 830 M instructions over 600 steps). What is kept is what a world
//! computing it afresh computes (`a_jointed_world_restores_bit_for_bit` restores into a fresh
//! world). `nudge bench corpus` gives the pendulum periods as before to the digit; the double
//! pendulum's energy and the heavy chain's stretch stay inside their bounds
//! (`tests/physics/joints.rs`).
//!
//! The factorisation is about 40 % of a swinging chain's step, but it cannot be kept for a whole
//! step (tried 2026-12-01, factoring at the step's first pass only). Kept with the rows moved on
//! to the sub-step's poses, the solve no longer matches its factor (Z holds the old Jacobians)
//! and a plain pendulum blew up within 100 steps. Kept with the rows too, only their position
//! errors taken afresh (a linearisation frozen for the step), the 90° pendulum's period came out
//! 7 % short (2.19 s for 2.37 s), and the heavy chain stretched 15 m of its 2.2 m.
//!
//! # Trees nothing else touches
//! Each pass is a projection: the biased pass makes v ← P_b(v) = v − M⁻¹Jᵀ(JM⁻¹Jᵀ)⁻¹(Jv + b),
//! the relax pass the same with b = 0. A velocity change along the rows, M⁻¹Jᵀλ, is removed by
//! the next projection at the same poses, and a change that does not depend on v (gravity, the
//! warm start) passes through either way; so a relax pass, such changes and the next sub-step's
//! biased pass leave the bodies, and the rows' impulses in all, as the changes and the biased pass
//! alone do. The relax pass and the next sub-step's biased pass see the same poses (see
//! [`JointTree`]), so where nothing else reads or changes a tree's velocities between them (no
//! contact on its bodies, no hold, no joint solved outside the tree, no limit or motor, whose
//! rows clamp; no damping, which scales v; the speed caps aside), the relax pass is left to the
//! biased pass, and only the last sub-step's is solved; nor is such a tree warm-started, since
//! its biased pass removes the warm start too (`JointRows::warm_start`). A hanging chain or
//! pendulum then makes five solves a step, not eight, for the same motion to rounding
//! (`an_untouched_trees_relax_pass_is_left_to_the_next_biased_pass`).
//!
//! # What it costs
//! About what Gauss–Seidel costs for the same joints, for a solve that holds where Gauss–Seidel
//! stretches. By callgrind over 300 steps (2026-12-03), with `Settings::joint_tree` on and off:
//! the swinging chain of 100 links 356 M and 326 M instructions (its widest joint 0.4 mm and
//! 53 mm), the pile of 20 ragdolls 3.03 G and 2.42 G (8 mm and 112 mm); `nudge bench mechanisms`
//! times both. Rapier's impulse joints, Gauss–Seidel too, take 1.61 G of its 2.72 G on the same
//! pile, about what the tree with its scalar rows takes of ours (1.5 G); its chain is 527 M. So
//! what keeps the pile's step above Rapier's is its contacts as much as its joints: with every
//! joint by Gauss–Seidel the pile is still 0.92 × Rapier's time (`rapier-bench --versus`).
//!
//! Here the tree's shape, its factorisation and its solves; in `factor` one node's block and its
//! L·Δ·Lᵀ; in `steps` what the factorisation and the sweeps do at each node; in `point_rows` the
//! dot products that leave out a point row's exact zeros.

// Block arithmetic indexes rows and columns as the formulas do.
#![allow(clippy::needless_range_loop)]

use glam::{Mat3, Vec3, Vec3A};

use crate::physics::body::inv_inertia_world;
use crate::physics::joint::stiffness::floored;
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::union_find;

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

mod factor;
mod point_rows;
mod steps;
#[cfg(test)]
mod tests;

use factor::{Factor, Form};
use steps::{
    COMPLIANCE, add_scaled, add_transposed, backward_step, body_mass, edge_is_point, edge_jacobian,
    factor_node, forward_step, joint_block, joint_rhs, velocity,
};

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
    /// The sweeps' steps at its sizes, chosen when it is factored (by `factor_node`, which has
    /// them as compile-time sizes): each sweep then calls one function per node instead of
    /// matching on its two sizes.
    sweeps: Sweeps,
    /// D, factored.
    factor: Factor,
}

/// A node's steps at its size N and its parent's K: a joint's right-hand side ([`joint_rhs`] of
/// its N rows; a body has none), the forward and the backward step ([`forward_step`],
/// [`backward_step`]).
#[derive(Clone, Copy, Debug)]
struct Sweeps {
    rhs: fn(&TreeRows, &Vec6, &Vec6, Option<f32>) -> Vec6,
    forward: fn(&Node, &Mat6, &mut Vec6, Option<&mut Vec6>),
    backward: fn(&Node, &mut Vec6, &Vec6),
}

impl Sweeps {
    fn at<const N: usize, const K: usize>() -> Self {
        Self {
            rhs: joint_rhs::<N>,
            forward: forward_step::<N, K>,
            backward: backward_step::<N, K>,
        }
    }
}

const NONE: u32 = u32::MAX;

/// One scalar row outside the tree (a limit or a motor) on solver bodies `a` and `b` (0: none),
/// with its Jacobian on each, linear then angular, as [`TreeRows`] lays them out.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct ScalarRow {
    pub a: u32,
    pub b: u32,
    pub j_a: [f32; 6],
    pub j_b: [f32; 6],
}

/// A kept [`JointTree::response`]: the factorisation (`generation`) and the row it was for, and
/// what it left: the inverse effective mass, the kick, and the answer over its tree's nodes
/// (`range`).
#[derive(Clone, Debug, Default)]
struct Weighed {
    generation: u64,
    row: ScalarRow,
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
    /// Whether the rows hold a point together first (ball, hinge, weld): row k < 3 has the linear
    /// part −e_k on A and e_k on B and an angular part r × e_k, whose k-th component is zero, and
    /// the rows after them have no linear part. The products with J then skip those columns
    /// (the same sums to the bit: only exact zeros are left out): 8 % fewer instructions for a
    /// swinging chain of 100 links (820 M → 785 M over 600 steps for the linear zeros, → 755 M
    /// with the angular ones; `point_rows_skip_only_exact_zeros`). Each product spells its
    /// branches out: through one helper giving the linear columns as a range the chain took
    /// 843 M, with the ranges chained as iterators 1,067 M, and with J M⁻¹ Jᵀ's rows built by
    /// `array::from_fn` 821 M.
    pub point: bool,
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
            point: false,
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
/// - The factorisation is kept while no joint's rows and no body's mass or rotation change (see
///   "Masses" in the module docs): a sub-step's relax pass and the next sub-step's biased pass
///   see the same poses, and so do a step's last pass and the next step's first; `JointRows`
///   keeps the rows of a joint whose ends have not moved, across steps too.
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
    /// Each tree's range of nodes.
    trees: Vec<(u32, u32)>,
    /// Per node: whether nothing but its tree's own joints acts on the tree this step (see "Trees
    /// nothing else touches" in the module docs).
    untouched: Vec<bool>,
    /// Per joint: the share of each end's J M⁻¹ Jᵀ in its block (see `joint_block`).
    shares: Vec<[f64; 2]>,
    /// The joints' ends the shape was built for, and the number of solver bodies.
    shaped_for: (Vec<(u32, u32)>, usize),
    /// Whether `nodes` hold a factorisation.
    factored: bool,
    /// Per solver body (written for the tree's bodies): its motion as last factored, with its world
    /// inverse inertia at its rotation then (see "Masses" in the module docs).
    masses: Vec<SolverMotion>,
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
        if self.shaped_for.1 == bodies && self.shaped_for.0 == ends {
            return &self.in_tree;
        }
        self.factored = false;
        self.shaped_for.0.clear();
        self.shaped_for.0.extend_from_slice(ends);
        self.shaped_for.1 = bodies;
        union_find::reset(&mut self.set, bodies);
        let in_tree = &mut self.in_tree;
        in_tree.clear();
        in_tree.resize(ends.len(), false);
        for (k, &(a, b)) in ends.iter().enumerate() {
            if a != 0 && b != 0 && !union_find::union(&mut self.set, a, b) {
                continue;
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
        self.trees.clear();
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
            self.trees.push((start, end));
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
                sweeps: Sweeps::at::<MAX, MAX>(),
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
    /// ignored for joints out of the tree), with the solver bodies' masses and rotations in
    /// `motions`, unless it is factored already and neither a joint's rows (`changed`) nor a
    /// body's mass have changed since.
    pub fn factor(&mut self, rows: &[TreeRows], motions: &[SolverMotion], changed: bool) {
        if self.masses.len() < motions.len() {
            self.masses.resize(motions.len(), SolverMotion::DUMMY);
        }
        let bodies = || {
            self.nodes.iter().filter_map(|node| match node.kind {
                NodeKind::Body(b) => Some(b as usize),
                NodeKind::Joint(_) => None,
            })
        };
        // Its moments as the step's other rows weigh it: exactly its own where the floor is under
        // them.
        let moments = |m: &SolverMotion| floored(m.inertia_local, m.inertia_floor);
        let weighed_as = |kept: &SolverMotion, m: &SolverMotion| {
            (kept.inv_mass, kept.inertia_local, kept.rotation)
                == (m.inv_mass, moments(m), m.rotation)
        };
        if self.factored && !changed && bodies().all(|b| weighed_as(&self.masses[b], &motions[b])) {
            return;
        }
        for b in bodies() {
            let m = &motions[b];
            let inertia_local = moments(m);
            self.masses[b] = SolverMotion {
                inv_inertia: inv_inertia_world(m.rotation, inertia_local.recip()),
                inertia_local,
                ..*m
            };
        }
        self.factored = true;
        self.generation += 1;
        let motions = &self.masses;
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
                    Some((
                        edge_jacobian(body, rows),
                        edge_is_point(body, rows),
                        &motions[b as usize],
                    ))
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

    /// Marks the trees nothing but their own joints acts on this step: none of whose bodies is
    /// `touched` (by a contact, a hold or a joint solved outside the tree) and none of whose joints
    /// has a limit or a motor (`scalar`).
    pub fn mark_untouched(&mut self, touched: impl Fn(u32) -> bool, scalar: impl Fn(u32) -> bool) {
        self.untouched.clear();
        for &(start, end) in &self.trees {
            let nodes = &self.nodes[start as usize..end as usize];
            let untouched = nodes.iter().all(|node| match node.kind {
                NodeKind::Body(b) => !touched(b),
                NodeKind::Joint(k) => !scalar(k),
            });
            self.untouched.extend(nodes.iter().map(|_| untouched));
        }
    }

    /// Whether joint `k` is in a tree [`JointTree::mark_untouched`] marked (none outside the tree).
    pub fn is_untouched(&self, k: usize) -> bool {
        let node = self.joint_node.get(k).copied().unwrap_or(NONE);
        node != NONE && self.untouched.get(node as usize) == Some(&true)
    }

    /// Whether every tree is untouched (see [`JointTree::mark_untouched`]).
    pub fn all_untouched(&self) -> bool {
        self.untouched.iter().all(|&u| u)
    }

    /// Solves the factored system against the bodies' current velocities and the rows' targets,
    /// `rate` times their errors (0 in the relax pass): applies Δv to the bodies and returns Δλ
    /// per joint row in `impulses`. With `skip_untouched`, the trees
    /// [`JointTree::mark_untouched`] marked are left as they are, and their Δλ are zero.
    pub fn solve(
        &mut self,
        rows: &[TreeRows],
        rate: f32,
        bodies: &mut [SolverBody],
        impulses: &mut [[f32; MAX]],
        skip_untouched: bool,
    ) {
        for t in 0..self.trees.len() {
            let (start, end) = self.trees[t];
            let range = start as usize..end as usize;
            if skip_untouched && self.untouched.get(range.start) == Some(&true) {
                for node in &self.nodes[range] {
                    if let NodeKind::Joint(k) = node.kind {
                        impulses[k as usize] = [0.0; MAX];
                    }
                }
                continue;
            }
            self.substitute(rows, (Some(rate), false), range.clone(), |i| {
                (i != 0).then(|| velocity(bodies, i))
            });
            self.apply(range, bodies, impulses);
        }
    }

    /// Applies a solve's answer over the nodes `range`: Δv to the bodies, Δλ to `impulses`.
    fn apply(
        &self,
        range: std::ops::Range<usize>,
        bodies: &mut [SolverBody],
        impulses: &mut [[f32; MAX]],
    ) {
        for (node, x) in self.nodes[range.clone()].iter().zip(&self.x[range]) {
            match node.kind {
                NodeKind::Body(b) => {
                    let body = &mut bodies[b as usize];
                    body.v += Vec3A::new(x[0] as f32, x[1] as f32, x[2] as f32);
                    body.w += Vec3A::new(x[3] as f32, x[4] as f32, x[5] as f32);
                }
                NodeKind::Joint(k) => {
                    for (out, x) in impulses[k as usize].iter_mut().zip(x) {
                        *out = *x as f32;
                    }
                }
            }
        }
    }

    /// The inverse effective mass of one more row with the tree's joints holding: J·Δv for a unit impulse along it, Δv being the velocity the impulse gives plus the
    /// tree's answer to it. A limit or a motor on the hinge of a light ball far from its pivot
    /// moves the ball's swing, not only its spin.
    ///
    /// `joint` is the row's joint: its last answer is kept, and given again while the tree is not
    /// refactored and the row is the same (a sub-step's relax pass and the next sub-step's biased
    /// pass see the same poses).
    pub fn response(&mut self, joint: usize, row: ScalarRow, rows: &[TreeRows]) -> f32 {
        if self.weighed.len() <= joint {
            self.weighed.resize_with(joint + 1, Weighed::default);
        }
        let kept = &self.weighed[joint];
        if kept.generation == self.generation && kept.row == row {
            let (start, stop) = kept.range;
            self.x[start as usize..stop as usize].copy_from_slice(&kept.x);
            (self.kick, self.kick_range) = (kept.kick, kept.range);
            return kept.w;
        }
        let w = self.respond(row, rows);
        let (start, stop) = self.kick_range;
        let kept = &mut self.weighed[joint];
        kept.x.clear();
        kept.x
            .extend_from_slice(&self.x[start as usize..stop as usize]);
        (kept.generation, kept.row, kept.w) = (self.generation, row, w);
        (kept.kick, kept.range) = (self.kick, self.kick_range);
        w
    }

    /// [`JointTree::response`], computed.
    fn respond(&mut self, row: ScalarRow, rows: &[TreeRows]) -> f32 {
        let motions = &self.masses;
        let ScalarRow { a, b, j_a, j_b } = row;
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
        let range = self.kick_range.0 as usize..self.kick_range.1 as usize;
        for (node, x) in self.nodes[range.clone()].iter().zip(&self.x[range]) {
            match node.kind {
                NodeKind::Body(b) => add_scaled(&mut bodies[b as usize], x, scale),
                NodeKind::Joint(k) => {
                    // Its rows alone: nothing reads a joint's impulses past them.
                    let rows = node.size.0;
                    for (p, x) in self.pending[k as usize][..rows].iter_mut().zip(x) {
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
        for (x, node) in self.x[range.clone()]
            .iter_mut()
            .zip(&self.nodes[range.clone()])
        {
            *x = [0.0; MAX];
            if let NodeKind::Joint(k) = node.kind {
                let r = &rows[k as usize];
                let (va, vb) = (velocity(r.a), velocity(r.b));
                if va.is_some() || vb.is_some() || rate.is_some() {
                    let (va, vb) = (va.unwrap_or_default(), vb.unwrap_or_default());
                    *x = (node.sweeps.rhs)(r, &va, &vb, rate);
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
            (node.sweeps.forward)(node, &coupling[i], &mut below[i], parent);
        }
        // Backward (roots down): x_i = D_i⁻¹ (y_i − E_i x_parent). A root's x is its u, as the
        // forward sweep left it.
        for i in range.clone().rev() {
            let node = &nodes[i];
            if node.contracted != NONE || node.parent == NONE {
                continue;
            }
            let (below, above) = x.split_at_mut(i + 1);
            let parent = &above[node.parent as usize - i - 1];
            (node.sweeps.backward)(node, &mut below[i], parent);
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
                add_transposed(
                    edge_jacobian(child, rows),
                    edge_is_point(child, rows),
                    &x[c],
                    &mut t
                )
            );
            with_rows!(
                node.size.1,
                add_transposed(
                    edge_jacobian(node, rows),
                    edge_is_point(node, rows),
                    &x[p],
                    &mut t
                )
            );
            x[i] = node.factor.through_mass(&t);
        }
    }
}
