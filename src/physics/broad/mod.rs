//! Stage 1, the broad-phase driver: the step's candidate body pairs, from the broad phase run on fat
//! boxes and reused while no box leaves its fat box, and the sleeping islands an awake body touches,
//! woken before anything is collided.

pub mod broad_phase;
pub mod contact_cap;

use crate::geometry::Aabb;
use crate::physics::broad::broad_phase::{BodyKind, BroadPhase};
use crate::physics::broad::contact_cap::ContactCap;
use crate::physics::fast_bodies::gravity_reach;
use crate::physics::narrow::collide::collide;
use crate::physics::narrow::contact_margin;
use crate::physics::world::World;
use crate::physics::{Body, Settings};

impl World {
    /// Step 1, the broad phase: the step's candidate pairs (see [`PairFinder::find`]), less those
    /// of bodies joined by a joint that keeps them from colliding.
    pub(in crate::physics) fn find_pairs(&mut self, dt: f32) {
        self.scratch
            .pair_finder
            .find(&self.bodies, &self.settings, dt);
        if !self.joints.is_empty() {
            self.drop_jointed_pairs();
        }
    }

    /// A pair of an awake dynamic body and a sleeping one whose shapes are within the pair's contact
    /// margin (a contact would be made) wakes the sleeper's island; repeated until no island wakes, so a
    /// chain of touching sleeping islands all wake together. Overlapping bounding boxes alone are not
    /// enough: two islands a few centimetres apart would wake each other in turn forever. Returns whether
    /// any woke.
    pub(in crate::physics) fn wake_touched_sleepers(&mut self, dt: f32) -> bool {
        // Bodies only wake in here, so a body sleeping now was sleeping when the kinds were taken: with
        // no sleeper among them (sleeping off, or all awake) there is nothing to wake, and a pair
        // without one is skipped before its bodies are read.
        if !self.scratch.pair_finder.kinds.contains(&BodyKind::Sleeping) {
            return false;
        }
        let mut any = false;
        loop {
            let mut woke = false;
            for k in 0..self.scratch.pair_finder.pairs.len() {
                let (a, b) = self.scratch.pair_finder.pairs[k];
                let kinds = &self.scratch.pair_finder.kinds;
                if kinds[a as usize] != BodyKind::Sleeping
                    && kinds[b as usize] != BodyKind::Sleeping
                {
                    continue;
                }
                let (ba, bb) = (&self.bodies[a as usize], &self.bodies[b as usize]);
                let sleeper = if ba.is_awake_dynamic() && bb.sleeping {
                    b
                } else if bb.is_awake_dynamic() && ba.sleeping {
                    a
                } else {
                    continue;
                };
                let margin = contact_margin(ba, bb, dt, &self.settings);
                if !collide(&ba.shape, &ba.pose, &bb.shape, &bb.pose, margin).is_empty() {
                    self.wake_island(sleeper);
                    woke = true;
                }
            }
            if !woke {
                return any;
            }
            any = true;
        }
    }
}

/// The broad phase's state between steps: the grid, the boxes and kinds of this step, the fat boxes
/// the grid last ran on with the candidates it found there, and the step's pairs (the stage's
/// output, read by the narrow phase).
#[derive(Debug, Default)]
pub(in crate::physics) struct PairFinder {
    broad_phase: BroadPhase,
    pub(in crate::physics) aabbs: Vec<Aabb>,
    pub(in crate::physics) kinds: Vec<BodyKind>,
    /// The step's pairs, sorted by `(a, b)`, `a < b`.
    pub(in crate::physics) pairs: Vec<(u32, u32)>,
    /// Holds the pairs to bounded counts (see `contact_cap`).
    pub(in crate::physics) cap: ContactCap,
    /// Enlarged ("fat") boxes the broad phase last ran on, the kinds it saw, and the pairs it found:
    /// reused while every body's box stays inside its fat box.
    fat_aabbs: Vec<Aabb>,
    fat_kinds: Vec<BodyKind>,
    pub(in crate::physics) candidates: Vec<(u32, u32)>,
    /// Steps the current candidates were reused (0: the grid ran this step), and how many grid runs
    /// in a row were never reused (a scene where something always moves: there fat boxes only
    /// cost, see `FAT_GIVE_UP`).
    pub(in crate::physics) reuses: u32,
    unused_runs: u32,
}

impl PairFinder {
    /// Step 1: world AABBs (awake bodies' boxes swept over the step and grown by half the speculative
    /// distance each, so every pair within its contact margin overlaps) into the broad phase. Pairs have
    /// at least one awake dynamic body and come sorted by `(a, b)`, `a < b`.
    ///
    /// The broad phase runs on fat boxes (each awake body's box reaching `FAT_LEAD` steps ahead along
    /// its velocity and grown by `FAT_MARGIN` of its size) and
    /// its pairs are kept as candidates while every body's box stays inside its fat box and no body
    /// changed kind: any two overlapping boxes then have overlapping fat boxes, so filtering the
    /// candidates by the exact boxes gives exactly the pairs a fresh broad phase would (Box2D's fat
    /// AABBs, with the whole broad phase rerun when one box leaves). A resting pile skips the broad
    /// phase; a run on exact boxes (a crowd that keeps moving, see `FAT_GIVE_UP`) has nothing to filter.
    pub(in crate::physics) fn find(&mut self, bodies: &[Body], settings: &Settings, dt: f32) {
        let s = self;
        let half_margin = 0.5 * settings.speculative_distance;
        let reach = gravity_reach(settings.gravity, dt, settings.speculative_distance);
        s.aabbs.clear();
        s.kinds.clear();
        for body in bodies {
            let mut aabb = body.shape.aabb(&body.pose);
            let kind = if body.is_static {
                BodyKind::Static
            } else if body.sleeping {
                BodyKind::Sleeping
            } else {
                let motion = body.linear_velocity * dt;
                let moved = Aabb::new(aabb.min + motion, aabb.max + motion);
                aabb = aabb.union(&moved).expanded(half_margin + reach);
                BodyKind::Dynamic
            };
            s.aabbs.push(aabb);
            s.kinds.push(kind);
        }
        let still_inside = s.fat_kinds == s.kinds
            && s.fat_aabbs.len() == s.aabbs.len()
            && s.fat_aabbs
                .iter()
                .zip(&s.aabbs)
                .all(|(fat, aabb)| fat.contains(aabb));
        // Whether the candidates came from fat boxes (reused or new) and need filtering by the exact ones.
        let filter = if still_inside {
            s.reuses += 1;
            true
        } else {
            // Each awake body's fat box reaches `FAT_LEAD` steps ahead along its velocity, so a
            // body in steady motion stays inside for several steps (a swinging chain, a falling
            // crowd): grown by the margin alone, such a body leaves within a step or two, and the
            // broad phase ran on every step of a swinging 100-link chain (43 M instructions over
            // 600 steps; 23 M reaching ahead) and of a rain of 4,000 bodies (818 M over 150 steps;
            // 546 M).
            s.unused_runs = if s.reuses == 0 { s.unused_runs + 1 } else { 0 };
            s.reuses = 0;
            let fatten = s.unused_runs < FAT_GIVE_UP || s.unused_runs % FAT_RETRY == 0;
            if fatten {
                s.fat_aabbs.clear();
                s.fat_aabbs
                    .extend(s.aabbs.iter().zip(&s.kinds).zip(bodies).map(
                        |((aabb, kind), body)| {
                            let margin = FAT_MARGIN * (aabb.max - aabb.min).max_element();
                            if *kind == BodyKind::Dynamic {
                                let lead = body.linear_velocity * (FAT_LEAD * dt);
                                let ahead = Aabb::new(aabb.min + lead, aabb.max + lead);
                                aabb.union(&ahead).expanded(margin)
                            } else {
                                *aabb
                            }
                        },
                    ));
            } else {
                s.fat_aabbs.clone_from(&s.aabbs);
            }
            s.fat_kinds.clone_from(&s.kinds);
            s.broad_phase
                .find_pairs(&s.fat_aabbs, &s.fat_kinds, &mut s.candidates);
            fatten
        };
        if filter {
            // Keep the candidates whose exact boxes overlap: each written in place and the count
            // advanced only for a keeper (no branch to mispredict, no capacity checks).
            let aabbs = &s.aabbs;
            s.pairs.clear();
            s.pairs.resize(s.candidates.len(), (0, 0));
            let mut kept = 0;
            for &(a, b) in &s.candidates {
                s.pairs[kept] = (a, b);
                kept += usize::from(aabbs[a as usize].overlaps(&aabbs[b as usize]));
            }
            s.pairs.truncate(kept);
        } else {
            // Exact boxes: the candidates are the pairs.
            s.pairs.clone_from(&s.candidates);
        }
        s.cap.apply(&mut s.pairs, &s.kinds);
    }
}

/// How much each awake body's broad-phase box is grown for reuse, as a fraction of its largest edge
/// (a 1 m box: 10 cm). Larger keeps the broad phase's pairs valid longer but adds candidates to filter.
const FAT_MARGIN: f32 = 0.1;

/// How many steps of its present velocity an awake body's fat box reaches ahead of it (Box2D's
/// `b2_aabbMultiplier`): a body moving steadily stays inside for about that many steps.
const FAT_LEAD: f32 = 4.0;

/// After this many grid runs in a row whose candidates were never reused (something always
/// leaves its fat box, as in a raining crowd), the boxes stay exact except on every `FAT_RETRY`th
/// run: there fat boxes would only make each run costlier.
const FAT_GIVE_UP: u32 = 4;
const FAT_RETRY: u32 = 16;
