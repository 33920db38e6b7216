//! Islands (connected groups of awake bodies linked by touching contacts) and the decision to put them to
//! sleep.
//!
//! Islands are rebuilt every step with union–find over the solver bodies (path halving, union by index),
//! which is O(bodies + contacts · α) and needs no persistent graph. An island sleeps when every body in it
//! has been slower than the sleep thresholds for `time_to_sleep`; sleeping bodies are chained in a circular
//! list (`Body::sleep_next`) so that waking any of them wakes the whole island in O(island).

use crate::physics::scratch::refill;
use crate::physics::union_find;

/// Union–find over solver indices, with the per-root scratch the sleep pass needs. Vectors are reused
/// from step to step (no allocation in steady state).
#[derive(Debug, Default)]
pub(crate) struct Islands {
    parent: Vec<u32>,
    /// Smallest sleep time in the island, indexed by root, s.
    min_sleep_time: Vec<f32>,
    /// First and last body (world index) chained so far, indexed by root.
    first: Vec<u32>,
    last: Vec<u32>,
}

impl Islands {
    /// Starts `count` singleton sets.
    pub fn reset(&mut self, count: usize) {
        union_find::reset(&mut self.parent, count);
    }

    /// Representative of `i`'s set.
    pub fn find(&mut self, i: u32) -> u32 {
        union_find::find(&mut self.parent, i)
    }

    /// Joins the sets of `a` and `b`.
    pub fn union(&mut self, a: u32, b: u32) {
        union_find::union(&mut self.parent, a, b);
    }

    /// Given each member's sleep time (`times[i]` for solver index i; index 0 is the static dummy and is
    /// ignored), returns through `sleepy` which members belong to islands whose every body has rested at
    /// least `time_to_sleep`. `sleepy` is cleared and refilled with solver indices.
    pub fn sleepy_members(&mut self, times: &[f32], time_to_sleep: f32, sleepy: &mut Vec<u32>) {
        let n = times.len();
        refill(&mut self.min_sleep_time, n, f32::INFINITY);
        for (i, &t) in times.iter().enumerate().skip(1) {
            let root = self.find(i as u32) as usize;
            self.min_sleep_time[root] = self.min_sleep_time[root].min(t);
        }
        sleepy.clear();
        for i in 1..n {
            let root = self.find(i as u32) as usize;
            if self.min_sleep_time[root] >= time_to_sleep {
                sleepy.push(i as u32);
            }
        }
    }

    /// Clears the per-root chain ends before chaining `count` solver bodies.
    pub fn reset_chains(&mut self, count: usize) {
        refill(&mut self.first, count, u32::MAX);
        refill(&mut self.last, count, u32::MAX);
    }

    /// Appends world body `body` (solver index `member`) to its island's chain; returns the previous last
    /// body of the chain (to link to `body`), or `None` when `body` starts it.
    pub fn chain(&mut self, member: u32, body: u32) -> Option<u32> {
        let root = self.find(member) as usize;
        let previous = self.last[root];
        self.last[root] = body;
        if previous == u32::MAX {
            self.first[root] = body;
            None
        } else {
            Some(previous)
        }
    }

    /// First and last chained body of the island of `member`.
    pub fn chain_ends(&mut self, member: u32) -> (u32, u32) {
        let root = self.find(member) as usize;
        (self.first[root], self.last[root])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_island_sleeps_only_when_all_its_bodies_rested_long_enough() {
        let mut islands = Islands::default();
        islands.reset(5);
        islands.union(1, 2);
        islands.union(3, 4);
        let times = [0.0, 1.0, 1.0, 1.0, 0.1];
        let mut sleepy = Vec::new();
        islands.sleepy_members(&times, 0.5, &mut sleepy);
        assert_eq!(sleepy, vec![1, 2]);
    }
}
