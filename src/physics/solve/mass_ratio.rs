//! Convergence help around mass ratios, in one place: which bodies and contacts get the extra
//! `mass_ratio_iterations` sweeps (a mass ratio at a contact, or a heavy load on a light body), which
//! contacts the shock pass visits, its rows, and the extra sweeps and the shock pass themselves (see
//! `contact_solver`, "Mass-ratio sweeps" and "Shock propagation").
//!
//! # Not for a blow on a pile
//!
//! A light ball landing on a resting pile (the 20 g ball on `nudge bench rest`'s running-bond
//! wall) is no mass ratio, and neither help is given to it: the pile carries such a blow as the
//! ground would (`prepare::preload::blows`). Both helps were tried first (2026-12-01):
//! - the shock pass over the whole island of a contact closing faster than 0.5 m/s, preloaded
//!   supports included, halved the wall's drift woken at 4 sub-steps (10.8 → 5.6 mm, still
//!   failing) by lifting the struck bricks 1.6 mm, and the column then sank 3 mm over a second; at
//!   4 sub-steps of 4 iterations it went from 1.8 to 2.3 mm, and at 2 sub-steps the wall fell;
//! - the extra sweeps, given to every contact of the struck body and, down the layers, of all it
//!   rests on, absorbed the ball but stirred the wall (its middle courses at 0.25 m/s for steps
//!   after), and it sank further, not less: its top course 15 mm down a second after the blow at
//!   2 sub-steps and 6 mm at 4, against 6.3 and 2.7 without.
//!
//! What converging the blow would buy, measured on the same wall as built (its bricks weigh 16 g,
//! less than the ball; woken at 4 sub-steps, 5.9 mm from where it slept 10 s after the blow at the
//! defaults; 2026-12-01). In the step the ball lands the struck brick and the two under it sink
//! 3.4–3.6 mm, past the slop, and turn at 0.5–0.7 rad/s about the wall's normal, and the next two
//! steps carry the top courses 8 mm sideways: what follows is the wall settling from that. More
//! biased passes a sub-step alone do not fix it (4, 16 and 64: 3.1, 4.8 and 1.6 mm), since the one
//! relax pass leaves the struck bricks closing at 0.1 m/s; with as many relax passes, 4 gave
//! 1.9 mm and 64 gave 0.74 mm, the struck bricks still 0.8–1.1 mm down in the landing step. So
//! even a converged solve of these soft rows sinks the wall into its slop band, and only one near
//! convergence holds it within the bench's 1 mm. Converged for the landing step and the four after
//! it alone (64 of each pass, one of each elsewhere): 0.54 mm, and 1.6 mm at 16; for the landing
//! step alone, 18.9 mm (the switch back to one pass knocks the wall again). Every step of a rain
//! lands a body on its pile, so a burst of passes over the struck island is no answer at the
//! bench's speeds. What answers it is statics: a pile at rest carries the blow to the ground as it
//! carries its weight, so the struck body is immovable for the landing's rows (0.16 mm at the
//! defaults).

use glam::Vec3;

use crate::physics::joint::{Joint, JointKind};
use crate::physics::narrow::contact::Contact;
use crate::physics::prepare::constraint_order::ConstraintOrder;
use crate::physics::prepare::preload::NO_PRELOAD;
use crate::physics::scratch::refill;
use crate::physics::solve::contact_solver::{self, PassParams, ShockRow, Side, shock_pass};
use crate::physics::solve::solver_body::{SolverBody, SolverMotion};
use crate::physics::solve::wide_contacts::{GroupRef, PointOrder, WideContacts};
use crate::physics::union_find;
use crate::physics::{Body, Settings};

/// The mass-ratio stage's state: which bodies and constraints get the extra sweeps, the lane
/// groups holding those constraints, and the shock pass's rows and order.
#[derive(Debug, Default)]
pub(in crate::physics) struct MassRatio {
    /// Per solver body: the mass of its dynamic neighbours, then of the bodies resting on it, kg (see
    /// `mark_heavy_loads`).
    load: Vec<f32>,
    /// Per solver body: whether it is marked (a mass ratio at one of its contacts, or a heavy load).
    pub(in crate::physics) marked: Vec<bool>,
    /// Per solver body: whether a mass ratio with a part of its own articulation marks it (see
    /// `select`).
    inner: Vec<bool>,
    /// Constraint indices (ascending: solve order) of the contacts touching a marked body, which get
    /// the extra `mass_ratio_iterations` sweeps, and the lane groups holding them, in solve order.
    constraints: Vec<u32>,
    groups: Vec<GroupRef>,
    /// The constraints the shock pass visits, in layer order.
    shock_order: Vec<u32>,
    /// Per constraint: its index in `shock_rows`, or `u32::MAX` when the shock pass skips it.
    shock_slot: Vec<u32>,
    /// Scalar copies of the constraints the shock pass visits (in solve order), and the visit order
    /// as indices into them.
    shock_rows: Vec<ShockRow>,
    shock_visit: Vec<u32>,
    /// Per solver body, when joints bind bodies together: the inverse of its articulation's mass
    /// (see [`MassRatio::weigh_articulations`]); empty without such joints (each body's own).
    articulated_inv_mass: Vec<f32>,
    /// Union–find parents over the solver bodies, then each body's root, for the articulations.
    parent: Vec<u32>,
}

impl MassRatio {
    /// Weighs the articulations: bodies that joints hold rigidly together (ball, hinge, slider,
    /// fixed joints and rods, not ropes or springs) between two awake bodies count, for the mass
    /// ratios, with the mass of all the bodies so joined; `contacts` is how many contacts the
    /// solver sees this step.
    ///
    /// Why: the contacts see each body alone, but the joint tree is solved exactly after them every
    /// sub-step (`joint::tree`), so a forearm pressed by another ragdoll's chest moves with its own
    /// ragdoll, not as a 1.5 kg box under a 20 kg one. Judged by their own masses, two thirds of the
    /// contacts in a pile of twenty ragdolls touched a marked body and their extra sweeps were a
    /// third of its step, with no gain in how the pile settles (measured: widest joint, deepest
    /// overlap and speed after 20 s were no better with them). A joint to the world or to a static
    /// body joins nothing: the world is not a mass to compare with.
    ///
    /// Two parts of one articulation still meet with their own masses (`select`): a ragdoll that
    /// falls on its own forearm squeezes 1.5 kg between 20 kg and the floor, and without the
    /// sweeps there one of the hundred random drops (`tests/physics/ragdoll.rs`) opened a joint
    /// 12 mm, where it opens 0.8 mm with them (the worst of the hundred: 2.9 mm).
    pub(in crate::physics) fn weigh_articulations(
        &mut self,
        joints: &[Joint],
        contacts: usize,
        solver_index: &[u32],
        motions: &[SolverMotion],
    ) {
        let s = self;
        s.articulated_inv_mass.clear();
        // The ratios are judged at contacts alone (`select`): a chain swinging free has none.
        if joints.is_empty() || contacts == 0 {
            return;
        }
        let rigid = |kind: &JointKind| match *kind {
            JointKind::Distance {
                min, max, spring, ..
            } => min == max && spring.is_none(),
            _ => true,
        };
        let pairs = joints
            .iter()
            .filter(|j| rigid(&j.desc.kind))
            .filter_map(|j| {
                let a = solver_index[j.desc.a?.index()];
                let b = solver_index[j.desc.b.index()];
                (a != 0 && b != 0).then_some((a, b))
            });
        let n = motions.len();
        union_find::reset(&mut s.parent, n);
        let mut any = false;
        for (a, b) in pairs {
            any |= union_find::union(&mut s.parent, a, b);
        }
        if !any {
            return;
        }
        // Each root sums its articulation's mass (in `load`, scratch until `select`), then every
        // body reads its root's.
        for i in 1..n as u32 {
            s.parent[i as usize] = union_find::find(&mut s.parent, i);
        }
        refill(&mut s.load, n, 0.0);
        for (&root, motion) in s.parent.iter().zip(motions).skip(1) {
            s.load[root as usize] += 1.0 / motion.inv_mass;
        }
        s.articulated_inv_mass.resize(n, 0.0);
        for (inv_mass, &root) in s.articulated_inv_mass.iter_mut().zip(&s.parent).skip(1) {
            *inv_mass = 1.0 / s.load[root as usize];
        }
    }

    /// Marks the bodies around a mass ratio and lists the constraints that get the extra sweeps
    /// and those the shock pass visits, from the constraints' bodies in solve order (`graph.links`,
    /// solver indices) and their layers, before anything is prepared.
    pub(in crate::physics) fn select(
        &mut self,
        graph: &ConstraintOrder,
        solver_index: &[u32],
        motions: &[SolverMotion],
        contacts: &[Contact],
        settings: &Settings,
    ) {
        let s = self;
        let links = &graph.links;
        let n = motions.len();
        // Bodies around a mass ratio (see `contact_solver`, "Mass-ratio sweeps"): both bodies of a
        // dynamic–dynamic contact whose masses differ by the threshold or more are marked; so is a
        // body that carries many times its own mass in bodies resting on it (a light plank under a
        // crowd: no single contact has a ratio, but the load has), and the bodies on it.
        refill(&mut s.marked, n, false);
        refill(&mut s.inner, n, false);
        // Per body, the mass of its dynamic neighbours: a bound on the load resting on it.
        refill(&mut s.load, n, 0.0);
        // Each body's inverse mass as the ratios see it: its articulation's where joints bind it,
        // except against a part of the same articulation, which it meets with its own.
        let (articulated, roots) = (&s.articulated_inv_mass, &s.parent);
        let inv_mass = |i: usize| articulated.get(i).copied().unwrap_or(motions[i].inv_mass);
        let same_articulation =
            |a: usize, b: usize| !articulated.is_empty() && roots[a] == roots[b];
        let mut any = false;
        for &(a, b) in links {
            let (a, b) = (a as usize, b as usize);
            let inner = same_articulation(a, b);
            let (inv_a, inv_b) = if inner {
                (motions[a].inv_mass, motions[b].inv_mass)
            } else {
                (inv_mass(a), inv_mass(b))
            };
            if a != 0 && b != 0 {
                s.load[a] += 1.0 / inv_b;
                s.load[b] += 1.0 / inv_a;
                if settings.is_mass_ratio(inv_a, inv_b) {
                    let marks = if inner { &mut s.inner } else { &mut s.marked };
                    marks[a] = true;
                    marks[b] = true;
                    any = true;
                }
            }
        }
        if let Some(up) = (-settings.gravity).try_normalize() {
            any |= mark_heavy_loads(
                contacts,
                solver_index,
                (motions.len(), inv_mass),
                up,
                &mut s.load,
                &mut s.marked,
            );
        }
        // Every contact touching a marked body gets the extra sweeps; a body marked by a ratio
        // inside its articulation gets them at its contacts inside it and with static bodies (a
        // forearm under its own chest and the floor), not at those with other articulations, which
        // meet it as the whole of it (`weigh_articulations`).
        s.constraints.clear();
        if any && settings.mass_ratio_iterations > 0 {
            for (i, &(a, b)) in links.iter().enumerate() {
                let (a, b) = (a as usize, b as usize);
                let inner =
                    (s.inner[a] || s.inner[b]) && (a == 0 || b == 0 || same_articulation(a, b));
                if s.marked[a] || s.marked[b] || inner {
                    s.constraints.push(i as u32);
                }
            }
        }
        // Everything else a mark decides (no friction anchor, the shock pass, no determinate
        // preload) goes with either kind.
        if !s.articulated_inv_mass.is_empty() {
            for (marked, &inner) in s.marked.iter_mut().zip(&s.inner) {
                *marked |= inner;
            }
        }
        // The shock pass only matters where one body supports the other (between bodies of one layer it
        // would be a second normal pass), and only around a mass ratio: it removes approach without
        // recording an impulse, so friction cannot see the load it carries. Where masses are alike the
        // soft solve converges on its own (stacks and pyramids stand without it) and friction under a
        // pushed stack stays Coulomb's; where they differ it is what keeps a heavy box on a light one.
        // Filtered every step from the (possibly reused) full layer order; `prepare_rows` drops the
        // supports the statics preload once they are known. Not around an impact either (module
        // docs, "Not for a blow on a pile").
        let (marked, levels) = (&s.marked, &graph.levels);
        s.shock_order.clear();
        s.shock_order
            .extend(graph.layer_order.iter().copied().filter(|&i| {
                let (a, b) = links[i as usize];
                levels[a as usize] != levels[b as usize]
                    && (marked[a as usize] || marked[b as usize])
            }));
    }

    /// After the statics (`preload`, per constraint) and the lanes (`wide`): the shock pass's scalar
    /// rows and visit order, and the lane groups holding the constraints that get the extra sweeps.
    ///
    /// The shock pass skips the supports the statics preload. Around a mass ratio those are the
    /// statically indeterminate ones (`prepare::preload`), a body on several supports, where the pass
    /// did harm: it pushes the upper body translationally at each contact in turn, as if that contact
    /// alone held it, so each sub-step put the load on whichever it visited and the body rocked on the
    /// rest (an 8 kg box on four 4 g balls rocked and walked two of them 0.2 m out in a minute).
    /// Their springs, preloaded with the lever rule's split, hold them instead.
    pub(in crate::physics) fn prepare_rows(
        &mut self,
        graph: &ConstraintOrder,
        wide: &WideContacts,
        contacts: &[Contact],
        bodies: &[Body],
        preload: &[f32],
    ) {
        let s = self;
        s.shock_order.retain(|&i| preload[i as usize] == NO_PRELOAD);
        // The shock pass reads scalar constraints: `shock_slot` says which constraints keep one, and
        // where.
        refill(&mut s.shock_slot, graph.links.len(), u32::MAX);
        for &i in &s.shock_order {
            s.shock_slot[i as usize] = 0;
        }
        for (kept, slot) in s
            .shock_slot
            .iter_mut()
            .filter(|slot| **slot == 0)
            .enumerate()
        {
            *slot = kept as u32;
        }
        s.shock_rows.clear();
        // The shock pass's rows, in solve order as `shock_slot` numbers them, with the friction rows
        // the lanes prepared.
        if !s.shock_order.is_empty() {
            for (i, &slot) in s.shock_slot.iter().enumerate() {
                if slot == u32::MAX {
                    continue;
                }
                let c = &contacts[graph.contact(i)];
                let (a, b) = graph.links[i];
                let side = |index: u32, body: u32| Side {
                    index,
                    position: bodies[body as usize].pose.position,
                    level: graph.levels[index as usize],
                };
                s.shock_rows.push(contact_solver::prepare_shock(
                    c,
                    &side(a, c.a),
                    &side(b, c.b),
                    wide.friction_rows(i as u32),
                ));
            }
        }
        wide.groups_of(&s.constraints, &mut s.groups);
        s.shock_visit.clear();
        s.shock_visit
            .extend(s.shock_order.iter().map(|&i| s.shock_slot[i as usize]));
    }

    /// `passes` more Gauss–Seidel passes over the lane groups of the contacts around a mass ratio
    /// (packed apart from the other contacts, see `WideContacts::push`), each visiting the points
    /// opposite to the pass before when `alternate` (see [`PointOrder`]).
    pub(in crate::physics) fn passes<const BIAS: bool>(
        &self,
        wide: &mut WideContacts,
        solver_bodies: &mut [SolverBody],
        params: &PassParams,
        passes: u32,
        alternate: bool,
        order: &mut PointOrder,
    ) {
        for _ in 0..passes {
            if self.groups.is_empty() {
                return;
            }
            *order = order.next(alternate);
            wide.solve_groups::<BIAS>(&self.groups, solver_bodies, params, *order);
        }
    }

    /// The constraints that get the extra sweeps (ascending constraint indices).
    pub(in crate::physics) fn swept_constraints(&self) -> &[u32] {
        &self.constraints
    }

    /// Whether the shock pass has anything to visit this step.
    pub(in crate::physics) fn has_shock_rows(&self) -> bool {
        !self.shock_order.is_empty()
    }

    /// The shock pass of one sub-step over the rows `prepare_rows` built, each with its lanes'
    /// current mean bias.
    pub(in crate::physics) fn run_shock_pass(
        &mut self,
        wide: &WideContacts,
        solver_bodies: &mut [SolverBody],
    ) {
        let s = self;
        for &i in &s.shock_order {
            let slot = s.shock_slot[i as usize] as usize;
            s.shock_rows[slot].bias_mean = wide.bias_mean(i);
        }
        shock_pass(&s.shock_rows, &s.shock_visit, solver_bodies);
    }
}

/// Cosine of the steepest contact normal (from vertical) through which a body counts as resting on
/// another: 45°.
const RESTING_MIN_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// A body carrying this many times its own mass in bodies resting on it gets the mass-ratio sweeps:
/// low enough that a plank under a hundred 1 kg balls gets them at 6 kg (16.7:1) as at 3 kg, both of
/// which let the balls jiggle without them (the 3 kg plank is the heavy-load row of `nudge bench
/// physics`'s fixes table, pinned by `tests/physics/convergence_fixes.rs`), and far above what
/// a pile makes (a 0.27 kg ball would need nine 0.5 kg boxes resting on it), so crowds pay nothing.
const HEAVY_LOAD_RATIO: f32 = 16.0;

/// Marks (in `marked`, per solver body) every awake body carrying at least [`HEAVY_LOAD_RATIO`] times
/// its own mass in awake bodies resting on it directly (contact normal within 45° of `up`), and those
/// bodies; returns whether it marked any. `bodies` is the solver body count and each one's inverse
/// mass as the ratios see it (`MassRatio::weigh_articulations`). `load` comes in holding, per
/// solver body, the mass of all its dynamic neighbours (a bound on what rests on it) and is then
/// scratch.
///
/// Why: a plank under a crowd of balls has no mass ratio at any one contact, yet Gauss–Seidel
/// converges on it as slowly as under one heavy body (each sweep moves it by its share of the total),
/// so it needs the same extra sweeps.
fn mark_heavy_loads(
    contacts: &[Contact],
    solver_index: &[u32],
    bodies: (usize, impl Fn(usize) -> f32),
    up: Vec3,
    load: &mut [f32],
    marked: &mut [bool],
) -> bool {
    // (bottom, top) solver indices of a contact where one body rests on the other.
    let resting = |c: &Contact| {
        let (a, b) = (solver_index[c.a as usize], solver_index[c.b as usize]);
        let tilt = c.manifold.normal.dot(up);
        if a == 0 || b == 0 || tilt.abs() < RESTING_MIN_COS {
            None
        } else if tilt > 0.0 {
            // The normal points from A to B, so B is on top.
            Some((a as usize, b as usize))
        } else {
            Some((b as usize, a as usize))
        }
    };
    let (n, inv_mass) = bodies;
    let heavy = |load: &[f32], i: usize| load[i] * inv_mass(i) >= HEAVY_LOAD_RATIO;
    // The bound rules out almost every step.
    if !(1..n).any(|i| heavy(load, i)) {
        return false;
    }
    load.fill(0.0);
    for (bottom, top) in contacts.iter().filter_map(resting) {
        load[bottom] += 1.0 / inv_mass(top);
    }
    let mut any = false;
    for (bottom, top) in contacts.iter().filter_map(resting) {
        if heavy(load, bottom) {
            marked[bottom] = true;
            marked[top] = true;
            any = true;
        }
    }
    any
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use crate::geometry::{Pose, Shape};
    use crate::physics::joint::{JointDesc, JointKind};
    use crate::physics::{BodyDesc, BodyId, Settings, World};

    /// A floor (body 0), a 20 kg box on it (1) and a 1 kg box resting on that (2), awake; with the
    /// two boxes' ids and poses.
    fn light_on_heavy() -> (World, [(BodyId, Pose); 2]) {
        let mut world = World::new(Settings {
            sleep: false,
            ..Settings::default()
        });
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ));
        let mut add = |half: f32, y: f32, mass: f32| {
            let pose = Pose::from_position(Vec3::new(0.0, y, 0.0));
            let id = world.add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::splat(half)),
                pose,
                mass,
            ));
            (id, pose)
        };
        let heavy = add(0.5, 0.5, 20.0);
        let light = add(0.25, 1.25, 1.0);
        (world, [heavy, light])
    }

    /// The light box on the heavy one; with `joined`, welded to a second 20 kg box beside the
    /// heavy one (a ragdoll's hand on another ragdoll's chest). Returns which solver bodies the
    /// mass-ratio stage marked after a step.
    fn marked_after_a_step(joined: bool) -> Vec<bool> {
        let (mut world, [_, light]) = light_on_heavy();
        if joined {
            let pose = Pose::from_position(Vec3::new(0.0, 1.25, 0.6));
            let cube = Shape::cuboid(Vec3::splat(0.25));
            let other = world.add_body(BodyDesc::dynamic(cube, pose, 20.0));
            let at = Vec3::new(0.0, 1.25, 0.25);
            let weld = JointDesc::at(
                JointKind::Fixed,
                Some(light),
                (other, pose),
                at,
                at,
                Vec3::Y,
                false,
            );
            world.add_joint(weld).expect("a weld");
        }
        world.step();
        world.scratch.mass_ratio.marked.clone()
    }

    /// The light box on the heavy one, welded to it with `collide` on, and a free 21 kg box beside
    /// it on the same support (3): returns the body pairs (world indices, lower first) whose
    /// contacts get the extra sweeps after a step.
    fn swept_pairs_around_an_inner_ratio() -> Vec<(u32, u32)> {
        let (mut world, [heavy, light]) = light_on_heavy();
        world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::splat(0.25)),
            Pose::from_position(Vec3::new(0.5, 1.25, 0.0)),
            21.0,
        ));
        let at = Vec3::new(0.0, 1.0, 0.0);
        let weld = JointDesc::at(JointKind::Fixed, Some(heavy), light, at, at, Vec3::Y, true);
        world.add_joint(weld).expect("a weld");
        world.step();
        let s = &world.scratch;
        let world_index = |solver: u32| {
            if solver == 0 {
                0
            } else {
                s.solver.motions[solver as usize].body
            }
        };
        let mut pairs: Vec<(u32, u32)> = s
            .mass_ratio
            .constraints
            .iter()
            .map(|&i| {
                let (a, b) = s.graph.links[i as usize];
                let (a, b) = (world_index(a), world_index(b));
                (a.min(b), a.max(b))
            })
            .collect();
        pairs.sort_unstable();
        pairs
    }

    /// A ratio inside an articulation (a forearm under its own chest) gets the extra sweeps at the
    /// part's contacts inside it and with static bodies, not at those with other bodies, which meet
    /// it as the whole articulation.
    #[test]
    fn a_ratio_inside_an_articulation_sweeps_only_its_own_and_static_contacts() {
        // Bodies: 0 floor, 1 heavy, 2 light (welded to 1), 3 free box beside 2.
        assert_eq!(swept_pairs_around_an_inner_ratio(), [(0, 1), (1, 2)]);
    }

    /// A light body resting on a heavy one is a mass ratio (both marked for the extra sweeps), but
    /// not when the light one is welded into an articulation as heavy as its support: it moves
    /// with its articulation (`MassRatio::weigh_articulations`).
    #[test]
    fn a_light_part_of_a_heavy_articulation_is_no_mass_ratio() {
        assert!(marked_after_a_step(false).iter().any(|&m| m));
        assert!(!marked_after_a_step(true).iter().any(|&m| m));
    }
}
