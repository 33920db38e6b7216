//! Stage 6b, sleep: islands of touching awake bodies that have all rested long enough go to sleep,
//! chained so that touching any of them wakes them all.
//!
//! # Pressed springs
//! A body rests when it moves slower than the sleep thresholds (5 cm/s, as Box2D) and, with
//! `Settings::sleep_waits_for_springs`, when no touching spring holding it (a support whose load the
//! statics determine: `prepare::preload`, "Determinate loads") is pressed past where it touches over
//! its whole patch. Such a spring is still pushing its bodies back, at its rate (about 9/s at the
//! defaults) times its depth, a millimetre a second at 0.1 mm, far under the thresholds: a column
//! of thirty boxes asleep at 2 sub-steps, hit on top by a 20 g ball, was put to sleep 0.5 s later
//! with every other contact still pressed 0.1 mm, and slept 1.44 mm low; waiting for its springs,
//! it sleeps 0.17 mm from where it stood, a column of fifty 0.3 mm (1.44 mm), at 4 sub-steps
//! 0.08–0.12 mm (0.79 mm) (`nudge bench rest`, 2026-11-29;
//! `a_column_woken_by_a_ball_sleeps_where_it_stood_only_once_its_springs_rest` in
//! `tests/physics/rest.rs`). A patch with some points pressed and some apart is at rest tilted
//! (two faces that are not flush, as fallen dominoes lean on each other) and does not count:
//! judged point by point, the dominoes never slept. The tolerance, 5 % of the slop, is far above
//! the micrometres a settled column's contacts rest at.
//!
//! # Speeding up
//! Slow is not resting: a body released at rest where it is not in equilibrium starts slowly, and
//! one tipped near its critical angle stays under the thresholds for longer than the time to sleep
//! (a block 2.4 m high and 0.2 m thick, let go at 0.9 of its critical angle, moves its centre at
//! 4 cm/s half a second later): it fell asleep leaning, at every sub-step count, where it should
//! rock back upright (`a_slender_block_let_go_leaning_rocks_back_instead_of_sleeping`, in
//! `tests/physics/hard_cases.rs`). So a body whose speed has grown by more than
//! `SPEEDING_UP_FRACTION` of the linear threshold from the slowest it moved since its rest began
//! has not rested: its rest begins again.
//!
//! From the slowest, not from where the rest began: a block rocking slowly slows to nothing at
//! each end of its swing and speeds up again, and judged from the start of its rest it fell asleep
//! at the end of a swing, leaning 0.05 rad, at 8 sub-steps. Its speed, not its spin: a 0.1 m ball
//! creeping at 1.2 mm/s turns at the spin's margin, and judged by spin too, balls under a box,
//! knocked, were kept awake until they rolled away (`nudge bench rest`, box on balls woken: 61 and
//! 64 mm off in two copies of eight, against 0.8 mm asleep). A pile at rest, stirring at
//! micrometres a second, and a knocked one slowing down, never speed up so.

pub(crate) mod island;

use glam::Vec3;

use crate::physics::body::NO_BODY;
use crate::physics::scratch::refill;
use crate::physics::sleep::island::Islands;
use crate::physics::world::World;

/// How far past touching, as a fraction of the slop, a touching spring may be pressed and its bodies
/// still rest (see "Pressed springs").
const PRESSED_SLOP_FRACTION: f32 = 0.05;

/// How much of the linear sleep threshold a body's speed may have grown from the slowest it moved
/// since its rest began, and the body still rest (see "Speeding up").
const SPEEDING_UP_FRACTION: f32 = 0.25;

/// The sleep stage's buffers: the islands of touching awake bodies, each solver body's rest time,
/// and the members of the islands that fall asleep.
#[derive(Debug, Default)]
pub(in crate::physics) struct SleepState {
    pub(in crate::physics) islands: Islands,
    pub(in crate::physics) times: Vec<f32>,
    pub(in crate::physics) sleepy: Vec<u32>,
    /// By solver index: held by a pressed touching spring this step (see "Pressed springs").
    pub(in crate::physics) pressed: Vec<bool>,
}

impl World {
    /// Step 6b: islands over touching contacts between awake bodies; an island whose bodies all rested
    /// (see "Pressed springs") for `time_to_sleep` goes to sleep with zero velocity.
    #[inline(never)]
    pub(in crate::physics) fn update_sleep(&mut self, dt: f32) {
        let set = &self.settings;
        let s = &mut self.scratch;
        let n = s.solver.bodies.len();
        let (lin2, ang2) = (
            set.sleep_linear_threshold * set.sleep_linear_threshold,
            set.sleep_angular_threshold * set.sleep_angular_threshold,
        );
        s.sleep.times.clear();
        s.sleep.times.push(0.0);
        let mut rested = false;
        refill(&mut s.sleep.pressed, n, false);
        if set.sleep_waits_for_springs {
            let tolerance = set.linear_slop * PRESSED_SLOP_FRACTION;
            s.wide.mark_pressed_springs(tolerance, &mut s.sleep.pressed);
        }
        let speeding_up = set.sleep_linear_threshold * SPEEDING_UP_FRACTION;
        for (i, m) in s.solver.motions.iter().enumerate().skip(1) {
            let body = &mut self.bodies[m.body as usize];
            let speed = body.linear_velocity.length();
            if body.sleep_time == 0.0 {
                body.rest_speed = speed;
            }
            let sped_up =
                set.sleep_waits_while_speeding_up && speed > body.rest_speed + speeding_up;
            body.rest_speed = body.rest_speed.min(speed);
            // A body the position pass moved is not resting, so a crowd cannot fall asleep
            // overlapping.
            if !s.deep.moved(i)
                && !s.sleep.pressed[i]
                && !sped_up
                && body.linear_velocity.length_squared() < lin2
                && body.angular_velocity.length_squared() < ang2
            {
                body.sleep_time += dt;
            } else {
                body.sleep_time = 0.0;
            }
            s.sleep.times.push(body.sleep_time);
            rested |= body.sleep_time >= set.time_to_sleep;
        }
        // An island sleeps when all its bodies have rested long enough: none has, none sleeps (the
        // usual case in a moving scene, which thus skips the islands).
        if !rested {
            return;
        }
        s.sleep.islands.reset(n);
        for &(a, b) in &s.graph.links {
            if a != 0 && b != 0 {
                s.sleep.islands.union(a, b);
            }
        }
        // A joint holds its bodies in one island, as a contact does.
        for joint in &self.joints {
            let Some(a) = joint.desc.a else { continue };
            let (a, b) = (
                s.solver.index[a.index()],
                s.solver.index[joint.desc.b.index()],
            );
            if a != 0 && b != 0 {
                s.sleep.islands.union(a, b);
            }
        }
        s.sleep
            .islands
            .sleepy_members(&s.sleep.times, set.time_to_sleep, &mut s.sleep.sleepy);
        if s.sleep.sleepy.is_empty() {
            return;
        }
        s.sleep.islands.reset_chains(n);
        for &i in &s.sleep.sleepy {
            let body_index = s.solver.motions[i as usize].body;
            if let Some(previous) = s.sleep.islands.chain(i, body_index) {
                self.bodies[previous as usize].sleep_next = body_index;
            }
            let body = &mut self.bodies[body_index as usize];
            body.sleeping = true;
            body.linear_velocity = Vec3::ZERO;
            body.angular_velocity = Vec3::ZERO;
        }
        for &i in &s.sleep.sleepy {
            let (first, last) = s.sleep.islands.chain_ends(i);
            self.bodies[last as usize].sleep_next = first;
        }
    }

    /// Wakes body `index` and, if it was asleep, every body of its island.
    pub(in crate::physics) fn wake_island(&mut self, index: u32) {
        let mut i = index;
        loop {
            let body = &mut self.bodies[i as usize];
            body.sleeping = false;
            body.sleep_time = 0.0;
            let next = body.sleep_next;
            body.sleep_next = NO_BODY;
            if next == NO_BODY || next == index {
                break;
            }
            i = next;
        }
    }

    /// Wakes every body that shared a contact with body `index` last step.
    pub(in crate::physics) fn wake_neighbours(&mut self, index: u32) {
        for k in 0..self.contacts.len() {
            let (a, b) = (self.contacts[k].a, self.contacts[k].b);
            if a == index && !self.bodies[b as usize].is_static {
                self.wake_island(b);
            } else if b == index && !self.bodies[a as usize].is_static {
                self.wake_island(a);
            }
        }
    }

    /// Wakes every sleeping body with its island.
    pub(in crate::physics) fn wake_all(&mut self) {
        for i in 0..self.bodies.len() {
            if self.bodies[i].sleeping {
                self.wake_island(i as u32);
            }
        }
    }
}
