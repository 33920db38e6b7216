//! The joints' rows for one step (the mathematics is in the module docs of `joint`): prepared from
//! the joints and the solver bodies, warm-started and solved every sub-step (soft and biased, then
//! rigid in the relax pass) and stored back as the next step's warm start.
//!
//! A row reads the bodies' current poses: the position at the step's start plus the sub-steps'
//! translation, and the integrator's current rotation. Rotations can be large within a step (a
//! pendulum's swing), so a joint's error is measured exactly, not to first order as a contact's is.

use glam::{Mat3, Quat, Vec3, Vec3A};

use crate::physics::joint::stiffness;
use crate::physics::joint::tree::{JointTree, ScalarRow, TreeRows};
use crate::physics::joint::{JOINT_DAMPING_RATIO, Joint, JointImpulses, JointKind, Motor};
use crate::physics::solve::softness::{Softness, capped_hertz};
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::{Body, BodyId};

/// The joints of one step as the solver sees them.
#[derive(Debug, Default)]
pub(crate) struct JointRows {
    /// Sorted pairs `(a, b)`, `a < b`, of bodies a joint keeps from colliding (`drop_jointed_pairs`).
    pub(in crate::physics) no_collide: Vec<(u32, u32)>,
    rows: Vec<Prepared>,
    /// Last step's `rows` (see `prepare`).
    last_rows: Vec<Prepared>,
    /// The equality rows of the joints that form trees, solved exactly (`tree`), with each
    /// joint's rows and impulses of one pass.
    tree: JointTree,
    /// Each joint's dynamic ends as the tree's shape reads them (0, 0 for one with no equality rows).
    ends: Vec<(u32, u32)>,
    tree_rows: Vec<TreeRows>,
    tree_impulses: Vec<[f32; 6]>,
    /// Per solver body: whether anything but a tree's joints acts on it this step (scratch for
    /// [`JointRows::mark_untouched_trees`]).
    touched: Vec<bool>,
}

/// What a joint's geometry depends on that changes: each end's position and rotation (constant
/// for a static end). A sub-step's relax pass, the next sub-step's warm start and its biased pass
/// see the same poses, and so do a step's last relax pass and the next step's first passes (a
/// position is the step's start plus the sub-steps' translation, and the next step starts from that
/// sum, to the bit).
type Poses = [(Vec3A, Quat); 2];

/// Poses equal to none (NaN): what is kept for them is computed afresh.
const NO_POSES: Poses = [(Vec3A::NAN, Quat::NAN); 2];

/// One end of a joint: its solver index (0: static, sleeping or the world, which nothing moves)
/// and where it was when the step began.
#[derive(Clone, Copy, Debug)]
struct End {
    index: u32,
    start: Vec3,
    /// The rotation of an end the solver does not move (the moving ones read the integrator's).
    rotation: Quat,
    inv_mass: f32,
    inv_inertia: Mat3,
}

/// A joint prepared for this step.
#[derive(Clone, Copy, Debug)]
struct Prepared {
    joint: u32,
    a: End,
    b: End,
    kind: JointKind,
    anchor_a: Vec3,
    anchor_b: Vec3,
    axis_a: Vec3,
    reference: Quat,
    impulses: JointImpulses,
    softness: Softness,
    spring: Softness,
    /// Its friction torque or force (see `JointDesc::friction`).
    friction: f32,
    /// A ball joint's friction block's mass, (I_a⁻¹ + I_b⁻¹)⁻¹: the ends' inertias are the step's,
    /// so it is worked out once a step (zero without friction).
    friction_mass: Mat3,
    /// Whether its equality rows are solved in the tree (else by Gauss–Seidel: a loop's last joint).
    in_tree: bool,
    /// Its geometry and the poses it was computed at (see [`Poses`]).
    posed: (Poses, Geometry),
    /// The poses its tree rows (in `JointRows::tree_rows`) were built at.
    rows_at: Poses,
}

/// A pose now: position and rotation.
#[derive(Clone, Copy)]
struct Frame {
    x: Vec3,
    q: Quat,
}

/// One scalar row: J = [−lin, −ang_a, lin, ang_b] and its effective mass.
#[derive(Clone, Copy)]
struct Row {
    lin: Vec3,
    ang_a: Vec3,
    ang_b: Vec3,
    mass: f32,
}

/// `S` with `S·x = r × x`.
fn skew(r: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, r.z, -r.y),
        Vec3::new(-r.z, 0.0, r.x),
        Vec3::new(r.y, -r.x, 0.0),
    )
}

/// Two unit vectors normal to unit `a` and to each other.
fn normals(a: Vec3) -> (Vec3, Vec3) {
    let t1 = a.any_orthonormal_vector();
    (t1, a.cross(t1))
}

/// The rotation error of a weld as a rotation vector: E = q_b·q_ref⁻¹·q_a⁻¹ taken the short way.
fn rotation_error(qa: Quat, qb: Quat, reference: Quat) -> Vec3 {
    let e = qb * reference.inverse() * qa.inverse();
    let e = if e.w < 0.0 { -e } else { e };
    let v = Vec3::new(e.x, e.y, e.z);
    let s = v.length();
    if s < 1e-9 {
        2.0 * v
    } else {
        v * (2.0 * s.atan2(e.w) / s)
    }
}

/// B's angle about `axis` from the reference, in [−π, π] (the twist part of E = q_b·q_ref⁻¹·q_a⁻¹,
/// taken with w ≥ 0: q and −q are the same turn).
fn hinge_angle(qa: Quat, qb: Quat, reference: Quat, axis: Vec3) -> f32 {
    let e = qb * reference.inverse() * qa.inverse();
    let e = if e.w < 0.0 { -e } else { e };
    2.0 * Vec3::new(e.x, e.y, e.z).dot(axis).atan2(e.w)
}

impl JointRows {
    /// Prepares the joints with an awake end for sub-steps of length `h` (`hertz` is the contact
    /// frequency already capped by the sub-step), their equality rows solved exactly where they
    /// form trees when `tree` (`Settings::joint_tree`), else every joint by Gauss–Seidel.
    pub(in crate::physics) fn prepare(
        &mut self,
        joints: &[Joint],
        bodies: &[Body],
        solver_index: &[u32],
        motions: &[SolverMotion],
        (hertz, h): (f32, f32),
        tree: bool,
    ) {
        // Last step's rows, whose geometry and tree rows are kept where they still hold.
        std::mem::swap(&mut self.rows, &mut self.last_rows);
        self.rows.clear();
        if joints.is_empty() {
            return;
        }
        let softness = Softness::new(capped_hertz(2.0 * hertz, h), JOINT_DAMPING_RATIO, h);
        let end = |id: Option<BodyId>| match id {
            None => End {
                index: 0,
                start: Vec3::ZERO,
                rotation: Quat::IDENTITY,
                inv_mass: 0.0,
                inv_inertia: Mat3::ZERO,
            },
            Some(id) => {
                let body = &bodies[id.index()];
                let index = solver_index[id.index()];
                let m = &motions[index as usize];
                End {
                    index,
                    start: body.pose.position,
                    rotation: body.pose.rotation,
                    inv_mass: m.inv_mass,
                    inv_inertia: m.inv_inertia.into(),
                }
            }
        };
        for (k, joint) in joints.iter().enumerate() {
            let (a, b) = (end(joint.desc.a), end(Some(joint.desc.b)));
            if a.index == 0 && b.index == 0 {
                continue;
            }
            let spring = match joint.desc.kind {
                JointKind::Distance {
                    spring: Some(s), ..
                } => Softness::new(capped_hertz(s.hertz, h), s.damping_ratio, h),
                _ => Softness::RIGID,
            };
            let friction_mass = match joint.desc.kind {
                JointKind::Ball if joint.desc.friction > 0.0 => {
                    (a.inv_inertia + b.inv_inertia).inverse()
                }
                _ => Mat3::ZERO,
            };
            self.rows.push(Prepared {
                joint: k as u32,
                a,
                b,
                kind: joint.desc.kind,
                anchor_a: joint.desc.local_anchor_a,
                anchor_b: joint.desc.local_anchor_b,
                axis_a: joint.desc.local_axis_a,
                reference: joint.desc.reference,
                impulses: joint.impulses,
                softness,
                spring,
                friction: joint.desc.friction,
                friction_mass,
                in_tree: false,
                posed: (NO_POSES, Geometry::default()),
                rows_at: NO_POSES,
            });
        }
        self.ends.clear();
        self.ends.extend(self.rows.iter().map(|p| {
            if tree && p.has_equality_rows() {
                (p.a.index, p.b.index)
            } else {
                (0, 0)
            }
        }));
        let in_tree = self.tree.shape(&self.ends, motions.len());
        for (p, &in_tree) in self.rows.iter_mut().zip(in_tree) {
            p.in_tree = in_tree;
        }
        // The same joints as last step, in the same order: each keeps its geometry and tree rows
        // with the poses they were computed at (a step's first passes see its last one's poses).
        let kept = self.rows.len() == self.last_rows.len()
            && self.tree_rows.len() == self.rows.len()
            && self
                .rows
                .iter()
                .zip(&self.last_rows)
                .all(|(p, old)| p.same_joint(old));
        if kept {
            for (p, old) in self.rows.iter_mut().zip(&self.last_rows) {
                (p.posed, p.rows_at) = (old.posed, old.rows_at);
            }
        } else {
            self.tree_rows.clear();
            self.tree_rows.extend(
                self.rows
                    .iter()
                    .map(|p| TreeRows::new(p.a.index, p.b.index)),
            );
        }
        self.tree_impulses.clear();
        self.tree_impulses.resize(self.rows.len(), [0.0; 6]);
    }

    /// Whether any joint has an awake end this step.
    pub(in crate::physics) fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Applies the stored impulses (the warm start) with the bodies' current poses. A joint of a
    /// tree nothing else touches is not warm-started: the tree's next pass removes whatever it
    /// applies along its rows (see "Trees nothing else touches" in `tree`), so its impulses start
    /// the sub-step at zero and that pass gives them whole.
    pub(in crate::physics) fn warm_start(
        &mut self,
        bodies: &mut [SolverBody],
        motions: &[SolverMotion],
    ) {
        for (k, p) in self.rows.iter_mut().enumerate() {
            if self.tree.is_untouched(k) {
                p.impulses = JointImpulses::default();
            } else {
                p.warm_start(bodies, motions);
            }
        }
    }

    /// One pass over the joints outside the tree (solved by Gauss–Seidel alone): soft and biased
    /// when `BIAS`, else rigid (the relax pass).
    pub(in crate::physics) fn solve_loose<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        motions: &[SolverMotion],
        h: f32,
    ) {
        for p in self.rows.iter_mut().filter(|p| !p.in_tree) {
            p.solve::<BIAS>(bodies, motions, h, None);
        }
    }

    /// Finds the trees nothing but their own joints acts on this step (see "Trees nothing else
    /// touches" in `tree`): none of whose bodies is in a contact (`contact_links`, the contact
    /// constraints' solver bodies), held (`held`) or an end of a joint solved outside the tree,
    /// and none of whose joints has a limit or a motor; none at all when the bodies are `damped`
    /// (damping scales a velocity along the rows into one across them). `bodies` is the number of
    /// solver bodies.
    pub(in crate::physics) fn mark_untouched_trees(
        &mut self,
        bodies: usize,
        contact_links: &[(u32, u32)],
        held: impl Iterator<Item = u32>,
        damped: bool,
    ) {
        let touched = &mut self.touched;
        touched.clear();
        touched.resize(bodies, damped);
        for &(a, b) in contact_links {
            touched[a as usize] = true;
            touched[b as usize] = true;
        }
        for i in held {
            touched[i as usize] = true;
        }
        for p in self.rows.iter().filter(|p| !p.in_tree) {
            touched[p.a.index as usize] = true;
            touched[p.b.index as usize] = true;
        }
        let rows = &self.rows;
        self.tree.mark_untouched(
            |b| touched[b as usize],
            |k| rows[k as usize].has_axial_rows(),
        );
    }

    /// One pass over the tree's joints: the tree's equality rows, exactly, and their scalar rows
    /// (friction, motors, limits) after them when `scalar_rows_last`, else before (see "Order" in
    /// `joint`). Biased when `BIAS`, else the relax pass.
    /// With `skip_untouched` (a relax pass before the step's last) the trees nothing else touches
    /// are passed over (see "Trees nothing else touches" in `tree`).
    pub(in crate::physics) fn solve_tree<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        motions: &[SolverMotion],
        h: f32,
        (skip_untouched, scalar_rows_last): (bool, bool),
    ) {
        if skip_untouched && self.tree.all_untouched() {
            // The next biased pass factors at these poses, and solves for both.
            return;
        }
        let tree = !self.tree.is_empty();
        if tree {
            let mut changed = false;
            for (p, rows) in self.rows.iter_mut().zip(&mut self.tree_rows) {
                if !p.in_tree {
                    continue;
                }
                let poses = p.poses(bodies, motions);
                if poses != p.rows_at {
                    p.tree_rows(poses, bodies, motions, rows);
                    changed = true;
                }
            }
            self.tree.factor(&self.tree_rows, motions, changed);
            self.tree.pending.clear();
            self.tree.pending.resize(self.rows.len(), [0.0; 6]);
        }
        if !tree {
            return;
        }
        if !scalar_rows_last {
            self.solve_tree_scalar_rows::<BIAS>(bodies, motions, h);
        }
        // The whole error closed within the sub-step (see `tree`).
        let rate = if BIAS { 1.0 / h } else { 0.0 };
        self.tree.solve(
            &self.tree_rows,
            rate,
            bodies,
            &mut self.tree_impulses,
            skip_untouched,
        );
        if scalar_rows_last {
            self.solve_tree_scalar_rows::<BIAS>(bodies, motions, h);
        }
        for (impulse, pending) in self.tree_impulses.iter_mut().zip(&self.tree.pending) {
            for (i, p) in impulse.iter_mut().zip(pending) {
                *i += p;
            }
        }
        for ((p, rows), impulse) in self
            .rows
            .iter_mut()
            .zip(&self.tree_rows)
            .zip(&self.tree_impulses)
        {
            if p.in_tree {
                p.take_tree_impulses(rows, impulse);
            }
        }
    }

    /// The scalar rows of the tree's joints: motors and limits with their mass through the tree and
    /// applied through it (what the tree's own rows carry meanwhile goes to `tree.pending`),
    /// friction to its two bodies alone (see "Friction" in `joint`).
    fn solve_tree_scalar_rows<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        motions: &[SolverMotion],
        h: f32,
    ) {
        // Only these joints have a row outside the tree (and need the joint's geometry).
        for p in self
            .rows
            .iter_mut()
            .filter(|p| p.in_tree && p.has_axial_rows())
        {
            p.solve::<BIAS>(
                bodies,
                motions,
                h,
                Some((&mut self.tree, &self.tree_rows[..])),
            );
        }
    }

    /// Stores each joint's impulses for the next step's warm start.
    pub(in crate::physics) fn store(&self, joints: &mut [Joint]) {
        for p in &self.rows {
            let joint = &mut joints[p.joint as usize];
            joint.impulses = p.impulses;
            joint.pull = stiffness::held_pull(joint.pull, p.pull());
        }
    }
}

impl Prepared {
    /// The impulse a sub-step its point, line or rod rows carry (`Joint::pull`), N·s.
    fn pull(&self) -> f32 {
        let i = &self.impulses;
        match self.kind {
            JointKind::Distance { .. } => (i.lower - i.upper + i.spring).abs(),
            _ => i.linear.length(),
        }
    }

    fn frame(&self, end: &End, bodies: &[SolverBody], motions: &[SolverMotion]) -> Frame {
        if end.index == 0 {
            Frame {
                x: end.start,
                q: end.rotation,
            }
        } else {
            let i = end.index as usize;
            Frame {
                x: end.start + Vec3::from(bodies[i].dp),
                q: motions[i].rotation,
            }
        }
    }

    fn velocity(end: &End, bodies: &[SolverBody]) -> (Vec3, Vec3) {
        let b = &bodies[end.index as usize];
        (b.v.into(), b.w.into())
    }

    /// Applies `linear` at arms `arm_a`, `arm_b` and `angular` to B, their opposites to A.
    fn apply(
        &self,
        bodies: &mut [SolverBody],
        linear: Vec3,
        arm_a: Vec3,
        arm_b: Vec3,
        angular: Vec3,
    ) {
        for (end, sign, arm) in [(&self.a, -1.0, arm_a), (&self.b, 1.0, arm_b)] {
            if end.index == 0 {
                continue;
            }
            let body = &mut bodies[end.index as usize];
            body.v += Vec3A::from(sign * end.inv_mass * linear);
            body.w += Vec3A::from(sign * (end.inv_inertia * (arm.cross(linear) + angular)));
        }
    }

    /// A scalar row along `lin` (at arms `arm_a`, `arm_b`) plus an angular part `ang` on both.
    fn row(&self, lin: Vec3, arm_a: Vec3, arm_b: Vec3, ang: Vec3) -> Row {
        let (ang_a, ang_b) = (arm_a.cross(lin) + ang, arm_b.cross(lin) + ang);
        let k = (self.a.inv_mass + self.b.inv_mass) * lin.length_squared()
            + ang_a.dot(self.a.inv_inertia * ang_a)
            + ang_b.dot(self.b.inv_inertia * ang_b);
        Row {
            lin,
            ang_a,
            ang_b,
            mass: if k > 0.0 { 1.0 / k } else { 0.0 },
        }
    }

    /// J·v of a row.
    fn row_speed(&self, row: &Row, bodies: &[SolverBody]) -> f32 {
        let (va, wa) = Self::velocity(&self.a, bodies);
        let (vb, wb) = Self::velocity(&self.b, bodies);
        row.lin.dot(vb - va) + row.ang_b.dot(wb) - row.ang_a.dot(wa)
    }

    /// Applies a scalar row's impulse: through the tree (with what its joints answer) when the
    /// row's mass came from it, else to the two bodies.
    fn apply_through(
        &self,
        bodies: &mut [SolverBody],
        row: &Row,
        impulse: f32,
        through: &mut Option<(&mut JointTree, &[TreeRows])>,
    ) {
        match through {
            Some((tree, _)) => tree.apply_response(impulse, bodies),
            None => self.apply_row(bodies, row, impulse),
        }
    }

    fn apply_row(&self, bodies: &mut [SolverBody], row: &Row, impulse: f32) {
        for (end, sign, ang) in [(&self.a, -1.0, row.ang_a), (&self.b, 1.0, row.ang_b)] {
            if end.index == 0 {
                continue;
            }
            let body = &mut bodies[end.index as usize];
            body.v += Vec3A::from(sign * end.inv_mass * impulse * row.lin);
            body.w += Vec3A::from(sign * impulse * (end.inv_inertia * ang));
        }
    }

    /// The joint's geometry now: frames, arms and anchor points; kept while its ends' poses are
    /// those it was computed at.
    fn geometry(&mut self, bodies: &[SolverBody], motions: &[SolverMotion]) -> Geometry {
        self.geometry_at(self.poses(bodies, motions), bodies, motions)
    }

    /// [`Self::geometry`] with its ends' poses now, `poses`, already taken.
    fn geometry_at(
        &mut self,
        poses: Poses,
        bodies: &[SolverBody],
        motions: &[SolverMotion],
    ) -> Geometry {
        if poses != self.posed.0 {
            self.posed = (poses, self.geometry_now(bodies, motions));
        }
        self.posed.1
    }

    fn geometry_now(&self, bodies: &[SolverBody], motions: &[SolverMotion]) -> Geometry {
        let (fa, fb) = (
            self.frame(&self.a, bodies, motions),
            self.frame(&self.b, bodies, motions),
        );
        let (ra, rb) = (fa.q * self.anchor_a, fb.q * self.anchor_b);
        Geometry {
            qa: fa.q,
            qb: fb.q,
            ra,
            rb,
            d: (fb.x + rb) - (fa.x + ra),
            // Only a hinge and a slider have an axis.
            axis: match self.kind {
                JointKind::Hinge { .. } | JointKind::Slider { .. } => {
                    (fa.q * self.axis_a).normalize()
                }
                JointKind::Ball | JointKind::Fixed | JointKind::Distance { .. } => Vec3::ZERO,
            },
        }
    }

    fn warm_start(&mut self, bodies: &mut [SolverBody], motions: &[SolverMotion]) {
        let g = self.geometry(bodies, motions);
        let i = self.impulses;
        let axial = i.motor + i.lower - i.upper + i.spring;
        // The rows across an axis (a hinge's two angular rows, a slider's two lines) kept their
        // impulse as a world vector; the axis has turned since, so only its part across the axis
        // now is theirs. Applied whole, the rest turned the hinge about its free axis (or pushed
        // the slider along it) every sub-step: energy from nowhere, and a chain of hinges whipped.
        let across = |v: Vec3| v - g.axis * g.axis.dot(v);
        // A hinge's or a slider's friction is along its axis now (as its axial rows are).
        let friction = match self.kind {
            JointKind::Hinge { .. } | JointKind::Slider { .. } => g.axis * g.axis.dot(i.friction),
            _ => i.friction,
        };
        self.impulses.friction = friction;
        match self.kind {
            JointKind::Ball | JointKind::Fixed => {
                self.apply(bodies, i.linear, g.ra, g.rb, i.angular + friction);
            }
            JointKind::Hinge { .. } => {
                self.apply(
                    bodies,
                    i.linear,
                    g.ra,
                    g.rb,
                    across(i.angular) + g.axis * axial + friction,
                );
            }
            JointKind::Slider { .. } => {
                // The line rows' impulse is across the axis; the axial rows' along it.
                self.apply(
                    bodies,
                    across(i.linear) + g.axis * axial + friction,
                    g.ra + g.d,
                    g.rb,
                    i.angular,
                );
            }
            JointKind::Distance { .. } => {
                let u = g.d.try_normalize().unwrap_or(Vec3::Y);
                self.apply(bodies, u * axial, g.ra, g.rb, Vec3::ZERO);
            }
        }
    }

    fn solve<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        motions: &[SolverMotion],
        h: f32,
        mut through: Option<(&mut JointTree, &[TreeRows])>,
    ) {
        let g = self.geometry(bodies, motions);
        let soft = if BIAS { self.softness } else { Softness::RIGID };
        if self.friction > 0.0 {
            self.solve_friction(bodies, &g, h);
        }
        match self.kind {
            JointKind::Ball if !self.in_tree => self.solve_point(bodies, &g, &soft),
            JointKind::Ball => {}
            JointKind::Fixed => {
                if !self.in_tree {
                    self.solve_weld(bodies, &g, &soft);
                    self.solve_point(bodies, &g, &soft);
                }
            }
            JointKind::Hinge { limits, motor } => {
                let mut angular =
                    self.axial((Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, g.axis), &through);
                if let Some(m) = motor {
                    self.solve_motor(bodies, &mut angular, m, h, &mut through);
                }
                if let Some([lo, hi]) = limits {
                    let angle = hinge_angle(g.qa, g.qb, self.reference, g.axis);
                    let range = (angle, lo, hi);
                    self.solve_limits::<BIAS>(bodies, &mut angular, range, h, &mut through);
                }
                if !self.in_tree {
                    self.solve_hinge_axes(bodies, &g, &soft);
                    self.solve_point(bodies, &g, &soft);
                }
            }
            JointKind::Slider { limits, motor } => {
                let mut along = self.axial((g.axis, g.ra + g.d, g.rb, Vec3::ZERO), &through);
                if let Some(m) = motor {
                    self.solve_motor(bodies, &mut along, m, h, &mut through);
                }
                if let Some([lo, hi]) = limits {
                    let range = (g.axis.dot(g.d), lo, hi);
                    self.solve_limits::<BIAS>(bodies, &mut along, range, h, &mut through);
                }
                if !self.in_tree {
                    self.solve_weld(bodies, &g, &soft);
                    self.solve_lines(bodies, &g, &soft);
                }
            }
            JointKind::Distance {
                length,
                min,
                max,
                spring,
            } => {
                let u = g.d.try_normalize().unwrap_or(Vec3::Y);
                let len = g.d.length();
                let row = self.row(u, g.ra, g.rb, Vec3::ZERO);
                if min >= max && spring.is_none() {
                    if self.in_tree {
                        return;
                    }
                    // A rod: one bilateral row, carried in `lower`.
                    let (bias, ms, is) = soft_terms(&soft, len - length);
                    let speed = self.row_speed(&row, bodies);
                    let delta = -row.mass * ms * (speed + bias) - is * self.impulses.lower;
                    self.impulses.lower += delta;
                    self.apply_row(bodies, &row, delta);
                    return;
                }
                if spring.is_some() {
                    // A physical force: the same soft row in the biased and the relax pass.
                    let (bias, ms, is) = soft_terms(&self.spring, len - length);
                    let speed = self.row_speed(&row, bodies);
                    let delta = -row.mass * ms * (speed + bias) - is * self.impulses.spring;
                    self.impulses.spring += delta;
                    self.apply_row(bodies, &row, delta);
                }
                let lo = if min > 0.0 { min } else { f32::NEG_INFINITY };
                let mut row = Axial { row, weighed: true };
                self.solve_limits::<BIAS>(bodies, &mut row, (len, lo, max), h, &mut None);
            }
        }
    }

    /// Whether the joint has equality rows (all but distance joints with a range or a spring).
    fn has_equality_rows(&self) -> bool {
        match self.kind {
            JointKind::Distance {
                min, max, spring, ..
            } => min >= max && spring.is_none(),
            _ => true,
        }
    }

    /// Whether it has a motor, limits or friction: rows along its free axes, besides its
    /// equality rows.
    fn has_axial_rows(&self) -> bool {
        self.friction > 0.0
            || match self.kind {
                JointKind::Hinge { limits, motor } | JointKind::Slider { limits, motor } => {
                    limits.is_some() || motor.is_some()
                }
                JointKind::Ball | JointKind::Fixed | JointKind::Distance { .. } => false,
            }
    }

    /// Its ends' poses now (see [`Poses`]).
    fn poses(&self, bodies: &[SolverBody], motions: &[SolverMotion]) -> Poses {
        [&self.a, &self.b].map(|end| match end.index as usize {
            // A static end's own rotation (the dummy's is the identity).
            0 => (Vec3A::from(end.start), end.rotation),
            i => (Vec3A::from(end.start) + bodies[i].dp, motions[i].rotation),
        })
    }

    /// Whether `self` is `old` a step later: the same joint between the same ends, so that what
    /// `old` computed at poses `self` is still at holds for it.
    fn same_joint(&self, old: &Prepared) -> bool {
        (self.joint, self.a.index, self.b.index) == (old.joint, old.a.index, old.b.index)
            && self.kind == old.kind
            && (self.anchor_a, self.anchor_b, self.axis_a)
                == (old.anchor_a, old.anchor_b, old.axis_a)
            && self.reference == old.reference
    }

    /// Its equality rows for the tree, from the current geometry: rigid, with their position
    /// errors (the biased pass's target, see `tree`). `poses` are its ends' poses now, as the caller
    /// took them to see whether the rows are stale (not taken twice).
    fn tree_rows(
        &mut self,
        poses: Poses,
        bodies: &[SolverBody],
        motions: &[SolverMotion],
        out: &mut TreeRows,
    ) {
        let g = self.geometry_at(poses, bodies, motions);
        self.rows_at = self.posed.0;
        out.rows = 0;
        out.point = matches!(
            self.kind,
            JointKind::Ball | JointKind::Fixed | JointKind::Hinge { .. }
        );
        let point = |out: &mut TreeRows| push_point_rows(out, &g);
        let weld = |out: &mut TreeRows| {
            let c = rotation_error(g.qa, g.qb, self.reference);
            for (e, c) in [(Vec3::X, c.x), (Vec3::Y, c.y), (Vec3::Z, c.z)] {
                out.push(Vec3::ZERO, -e, Vec3::ZERO, e, c);
            }
        };
        match self.kind {
            JointKind::Ball => point(out),
            JointKind::Fixed => {
                point(out);
                weld(out);
            }
            JointKind::Hinge { .. } => {
                point(out);
                let axis_b = (g.qb * self.reference.inverse() * g.qa.inverse()) * g.axis;
                let c = g.axis.cross(axis_b);
                let (t1, t2) = normals(g.axis);
                for t in [t1, t2] {
                    out.push(Vec3::ZERO, -t, Vec3::ZERO, t, t.dot(c));
                }
            }
            JointKind::Slider { .. } => {
                let (t1, t2) = normals(g.axis);
                for t in [t1, t2] {
                    out.push(-t, -(g.ra + g.d).cross(t), t, g.rb.cross(t), t.dot(g.d));
                }
                weld(out);
            }
            JointKind::Distance { length, .. } => {
                let u = g.d.try_normalize().unwrap_or(Vec3::Y);
                out.push(-u, -g.ra.cross(u), u, g.rb.cross(u), g.d.length() - length);
            }
        }
    }

    /// Adds the tree's impulses for its rows (as `tree_rows` laid them out) to the joint's.
    fn take_tree_impulses(&mut self, rows: &TreeRows, impulse: &[f32; 6]) {
        let along = |k: usize, from: usize| -> Vec3 {
            Vec3::new(
                rows.j_b[k][from] as f32,
                rows.j_b[k][from + 1] as f32,
                rows.j_b[k][from + 2] as f32,
            )
        };
        let i = &mut self.impulses;
        match self.kind {
            JointKind::Ball => i.linear += Vec3::from_slice(&impulse[0..3]),
            JointKind::Fixed => {
                i.linear += Vec3::from_slice(&impulse[0..3]);
                i.angular += Vec3::from_slice(&impulse[3..6]);
            }
            JointKind::Hinge { .. } => {
                i.linear += Vec3::from_slice(&impulse[0..3]);
                i.angular += along(3, 3) * impulse[3] + along(4, 3) * impulse[4];
            }
            JointKind::Slider { .. } => {
                i.linear += along(0, 0) * impulse[0] + along(1, 0) * impulse[1];
                i.angular += Vec3::from_slice(&impulse[2..5]);
            }
            JointKind::Distance { .. } => i.lower += impulse[0],
        }
    }

    /// The point block: p_b − p_a = 0.
    fn solve_point(&mut self, bodies: &mut [SolverBody], g: &Geometry, soft: &Softness) {
        let (sa, sb) = (skew(g.ra), skew(g.rb));
        let k = Mat3::from_diagonal(Vec3::splat(self.a.inv_mass + self.b.inv_mass))
            - sa * self.a.inv_inertia * sa
            - sb * self.b.inv_inertia * sb;
        let (va, wa) = Self::velocity(&self.a, bodies);
        let (vb, wb) = Self::velocity(&self.b, bodies);
        let speed = (vb + wb.cross(g.rb)) - (va + wa.cross(g.ra));
        let delta = -soft.mass_scale * (k.inverse() * (speed + soft.bias_rate * g.d))
            - soft.impulse_scale * self.impulses.linear;
        if delta.is_finite() {
            self.impulses.linear += delta;
            self.apply(bodies, delta, g.ra, g.rb, Vec3::ZERO);
        }
    }

    /// The weld block: no relative rotation.
    fn solve_weld(&mut self, bodies: &mut [SolverBody], g: &Geometry, soft: &Softness) {
        let k = self.a.inv_inertia + self.b.inv_inertia;
        let c = rotation_error(g.qa, g.qb, self.reference);
        let (_, wa) = Self::velocity(&self.a, bodies);
        let (_, wb) = Self::velocity(&self.b, bodies);
        let delta = -soft.mass_scale * (k.inverse() * (wb - wa + soft.bias_rate * c))
            - soft.impulse_scale * self.impulses.angular;
        if delta.is_finite() {
            self.impulses.angular += delta;
            self.apply(bodies, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, delta);
        }
    }

    /// The hinge's two axis rows: B turns only about A's axis.
    fn solve_hinge_axes(&mut self, bodies: &mut [SolverBody], g: &Geometry, soft: &Softness) {
        let (t1, t2) = normals(g.axis);
        let k = self.a.inv_inertia + self.b.inv_inertia;
        let (k11, k12, k22) = (t1.dot(k * t1), t1.dot(k * t2), t2.dot(k * t2));
        let det = k11 * k22 - k12 * k12;
        if det <= 0.0 {
            return;
        }
        let axis_b = (g.qb * self.reference.inverse() * g.qa.inverse()) * g.axis;
        let c = g.axis.cross(axis_b);
        let (_, wa) = Self::velocity(&self.a, bodies);
        let (_, wb) = Self::velocity(&self.b, bodies);
        let w = wb - wa;
        let (r1, r2) = (
            t1.dot(w) + soft.bias_rate * t1.dot(c),
            t2.dot(w) + soft.bias_rate * t2.dot(c),
        );
        let old = self.impulses.angular;
        let (o1, o2) = (t1.dot(old), t2.dot(old));
        let l1 = -soft.mass_scale * (k22 * r1 - k12 * r2) / det - soft.impulse_scale * o1;
        let l2 = -soft.mass_scale * (k11 * r2 - k12 * r1) / det - soft.impulse_scale * o2;
        let delta = t1 * l1 + t2 * l2;
        self.impulses.angular = t1 * (o1 + l1) + t2 * (o2 + l2);
        self.apply(bodies, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, delta);
    }

    /// The slider's two line rows: B's anchor stays on A's axis through A's anchor.
    fn solve_lines(&mut self, bodies: &mut [SolverBody], g: &Geometry, soft: &Softness) {
        let (t1, t2) = normals(g.axis);
        let old = self.impulses.linear;
        let mut total = Vec3::ZERO;
        for t in [t1, t2] {
            let row = self.row(t, g.ra + g.d, g.rb, Vec3::ZERO);
            let (bias, ms, is) = soft_terms(soft, t.dot(g.d));
            let speed = self.row_speed(&row, bodies);
            let delta = -row.mass * ms * (speed + bias) - is * t.dot(old);
            total += t * (t.dot(old) + delta);
            self.apply_row(bodies, &row, delta);
        }
        self.impulses.linear = total;
    }

    /// An axial row (a motor's or a limit's: `lin`, `arm_a`, `arm_b` and `ang` as [`Self::row`]
    /// takes them), its mass to be weighed through the tree when the joint is in it (see
    /// [`Axial`]): then the two bodies' mass is not worked out, nothing would read it.
    fn axial(
        &self,
        (lin, arm_a, arm_b, ang): (Vec3, Vec3, Vec3, Vec3),
        through: &Option<(&mut JointTree, &[TreeRows])>,
    ) -> Axial {
        if through.is_none() {
            return Axial {
                row: self.row(lin, arm_a, arm_b, ang),
                weighed: true,
            };
        }
        let (ang_a, ang_b) = (arm_a.cross(lin) + ang, arm_b.cross(lin) + ang);
        Axial {
            row: Row {
                lin,
                ang_a,
                ang_b,
                mass: 0.0,
            },
            weighed: false,
        }
    }

    /// Gives `axial` its mass through the tree if it has not got it yet: J·Δv for a unit impulse
    /// with the tree's joints holding. An axial row of a joint in the tree moves what the tree
    /// holds together, not the two bodies alone. It leaves the tree ready to apply the row
    /// (`JointTree::apply_response`).
    fn weigh(&self, axial: &mut Axial, through: &mut Option<(&mut JointTree, &[TreeRows])>) {
        if axial.weighed {
            return;
        }
        axial.weighed = true;
        let Some((tree, rows)) = through else {
            return;
        };
        let row = &axial.row;
        let j = |lin: Vec3, ang: Vec3| [lin.x, lin.y, lin.z, ang.x, ang.y, ang.z];
        let scalar = ScalarRow {
            a: self.a.index,
            b: self.b.index,
            j_a: j(-row.lin, -row.ang_a),
            j_b: j(row.lin, row.ang_b),
        };
        let w = tree.response(self.joint as usize, scalar, rows);
        axial.row.mass = if w > 0.0 { 1.0 / w } else { 0.0 };
    }

    /// The friction rows: the relative motion along the free axes (a ball joint's turn, a hinge's
    /// about its axis, a slider's along it) stopped with at most the joint's friction over the
    /// sub-step. Their mass is the two bodies' alone, not the tree's as a motor's is (see
    /// "Friction" in `joint`).
    fn solve_friction(&mut self, bodies: &mut [SolverBody], g: &Geometry, h: f32) {
        let max = self.friction * h;
        let row = match self.kind {
            JointKind::Ball => {
                let (_, wa) = Self::velocity(&self.a, bodies);
                let (_, wb) = Self::velocity(&self.b, bodies);
                let old = self.impulses.friction;
                let new = (old - self.friction_mass * (wb - wa)).clamp_length_max(max);
                if new.is_finite() {
                    self.impulses.friction = new;
                    self.apply(bodies, Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, new - old);
                }
                return;
            }
            JointKind::Hinge { .. } => self.row(Vec3::ZERO, Vec3::ZERO, Vec3::ZERO, g.axis),
            JointKind::Slider { .. } => self.row(g.axis, g.ra + g.d, g.rb, Vec3::ZERO),
            JointKind::Fixed | JointKind::Distance { .. } => return,
        };
        let old = g.axis.dot(self.impulses.friction);
        let new = (old - row.mass * self.row_speed(&row, bodies)).clamp(-max, max);
        self.impulses.friction = g.axis * new;
        self.apply_row(bodies, &row, new - old);
    }

    /// A motor on `axial`: its speed driven to the motor's with at most its torque or force
    /// over the sub-step.
    fn solve_motor(
        &mut self,
        bodies: &mut [SolverBody],
        axial: &mut Axial,
        motor: Motor,
        h: f32,
        through: &mut Option<(&mut JointTree, &[TreeRows])>,
    ) {
        self.weigh(axial, through);
        let (row, max_impulse) = (&axial.row, motor.max * h);
        let old = self.impulses.motor;
        let new = (old - row.mass * (self.row_speed(row, bodies) - motor.speed))
            .clamp(-max_impulse, max_impulse);
        self.impulses.motor = new;
        self.apply_through(bodies, row, new - old, through);
    }

    /// The lower and upper limits of `value` on `axial` (`range`: value, lower, upper; one-sided,
    /// speculative while inside). A limit that holds no impulse and that the row's speed does not
    /// carry past within the sub-step gets none whatever the row's mass: it is left without
    /// weighing the row through the tree, which would walk the whole tree.
    fn solve_limits<const BIAS: bool>(
        &mut self,
        bodies: &mut [SolverBody],
        axial: &mut Axial,
        (value, lo, hi): (f32, f32, f32),
        h: f32,
        through: &mut Option<(&mut JointTree, &[TreeRows])>,
    ) {
        let terms = |c: f32| {
            if c > 0.0 {
                (c / h, 1.0, 0.0)
            } else if BIAS {
                soft_terms(&self.softness, c)
            } else {
                (0.0, 1.0, 0.0)
            }
        };
        if lo.is_finite() {
            let (bias, ms, is) = terms(value - lo);
            let speed = self.row_speed(&axial.row, bodies);
            let old = self.impulses.lower;
            if old != 0.0 || speed + bias < 0.0 {
                self.weigh(axial, through);
                let row = &axial.row;
                let new = (old - row.mass * ms * (speed + bias) - is * old).max(0.0);
                self.impulses.lower = new;
                self.apply_through(bodies, row, new - old, through);
            }
        }
        if hi.is_finite() {
            let (bias, ms, is) = terms(hi - value);
            let speed = -self.row_speed(&axial.row, bodies);
            let old = self.impulses.upper;
            if old != 0.0 || speed + bias < 0.0 {
                self.weigh(axial, through);
                let row = &axial.row;
                let new = (old - row.mass * ms * (speed + bias) - is * old).max(0.0);
                self.impulses.upper = new;
                self.apply_through(bodies, row, old - new, through);
            }
        }
    }
}

/// An axial row and whether its mass is final: a tree joint's row is first made with the two
/// bodies' mass and weighed through the tree (`Prepared::weigh`) only when a motor or an active
/// limit needs it.
struct Axial {
    row: Row,
    weighed: bool,
}

/// Pushes the three rows that hold a joint's anchors together (geometry `g`): row k is
/// (−e_k, −r_a × e_k) on A and (e_k, r_b × e_k) on B. The crosses are written out (each is two of
/// the arm's components): full cross products cost a swinging chain of 100 links 21 M more
/// instructions over 600 steps. Inlined always: as a closure of `tree_rows` the compiler once
/// left it a call, 7.5 M instructions more for the ragdoll pile over 300 steps.
#[inline(always)]
fn push_point_rows(out: &mut TreeRows, g: &Geometry) {
    let (a, b, d) = (g.ra, g.rb, g.d);
    let v = Vec3::new;
    for (e, turn_a, turn_b, c) in [
        (Vec3::X, v(0.0, -a.z, a.y), v(0.0, b.z, -b.y), d.x),
        (Vec3::Y, v(a.z, 0.0, -a.x), v(-b.z, 0.0, b.x), d.y),
        (Vec3::Z, v(-a.y, a.x, 0.0), v(b.y, -b.x, 0.0), d.z),
    ] {
        out.push(-e, turn_a, e, turn_b, c);
    }
}

/// (bias, mass scale, impulse scale) of a soft row with error `c`.
fn soft_terms(soft: &Softness, c: f32) -> (f32, f32, f32) {
    (soft.bias_rate * c, soft.mass_scale, soft.impulse_scale)
}

/// A joint's geometry at one moment.
#[derive(Clone, Copy, Debug, Default)]
struct Geometry {
    qa: Quat,
    qb: Quat,
    /// Arms from the centres to the anchors, world.
    ra: Vec3,
    rb: Vec3,
    /// B's anchor less A's.
    d: Vec3,
    /// A's axis, world (a hinge's or a slider's; zero for the other kinds).
    axis: Vec3,
}
