//! Caps on the pairs the narrow phase and solver take, so memory and time stay bounded whatever a
//! scene says.
//!
//! Bodies piled into one place make every pair a contact: 2,000 coincident boxes are two million
//! four-point manifolds, which took 5.7 GB and 8 s a step, and 5,000 coincident balls aborted on an
//! 8.5 GB allocation. No honest scene comes near the caps: a box touches a dozen neighbours of its
//! size; the heaviest load in the tests, a plank under a hundred balls, is a hundred pairs; a static
//! floor under thousands of bodies is not capped at all (static bodies never count). Beyond them
//! the step degrades instead of failing: pairs over the caps are ignored (those bodies pass through
//! each other) and [`ContactCap::dropped`] says how many, for the caller to report.
//!
//! Pairs arrive sorted by `(a, b)` and are kept in that order until a cap is reached, so the choice
//! is deterministic. Below the caps nothing is touched and traces are unchanged.

use crate::physics::broad::broad_phase::BodyKind;

/// Most pairs one moving or sleeping body may take part in per step.
pub const MAX_PAIRS_PER_BODY: u32 = 128;
/// Most pairs in a world per step (rain(4000), the largest built-in scene, has about 7,000).
pub const MAX_PAIRS: usize = 100_000;

/// The caps' scratch space and what they dropped in the last step.
#[derive(Clone, Debug, Default)]
pub struct ContactCap {
    /// Pairs per body, by body index.
    counts: Vec<u32>,
    /// Pairs ignored in the last step.
    dropped: usize,
}

impl ContactCap {
    /// Removes the pairs beyond [`MAX_PAIRS_PER_BODY`] for a non-static body and beyond
    /// [`MAX_PAIRS`] in all, keeping the order of the rest. `kinds` is indexed by body.
    pub fn apply(&mut self, pairs: &mut Vec<(u32, u32)>, kinds: &[BodyKind]) {
        self.dropped = 0;
        // Too few pairs for any body to reach its cap: the common case costs nothing more.
        if pairs.len() <= MAX_PAIRS_PER_BODY as usize {
            return;
        }
        let capped = |i: u32| kinds[i as usize] != BodyKind::Static;
        // Each body's pairs counted first (a tight loop): when no capped body has more than its cap
        // and the total is within its own, no pair is dropped and the list is left as it is.
        self.counts.clear();
        self.counts.resize(kinds.len(), 0);
        for &(a, b) in pairs.iter() {
            self.counts[a as usize] += 1;
            self.counts[b as usize] += 1;
        }
        let within = pairs.len() <= MAX_PAIRS
            && (self.counts.iter().zip(kinds))
                .all(|(&count, &kind)| count <= MAX_PAIRS_PER_BODY || kind == BodyKind::Static);
        if within {
            return;
        }
        self.counts.fill(0);
        let counts = &mut self.counts;
        let before = pairs.len();
        let mut kept = 0usize;
        pairs.retain(|&(a, b)| {
            let room = kept < MAX_PAIRS
                && !(capped(a) && counts[a as usize] >= MAX_PAIRS_PER_BODY)
                && !(capped(b) && counts[b as usize] >= MAX_PAIRS_PER_BODY);
            if room {
                counts[a as usize] += 1;
                counts[b as usize] += 1;
                kept += 1;
            }
            room
        });
        self.dropped = before - pairs.len();
    }

    /// Pairs the caps ignored in the last step (0 in any ordinary scene).
    pub fn dropped(&self) -> usize {
        self.dropped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair among `n` bodies of `kind`, sorted.
    fn all_pairs(n: u32) -> Vec<(u32, u32)> {
        (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .collect()
    }

    #[test]
    fn ordinary_pair_lists_are_untouched() {
        let mut cap = ContactCap::default();
        let kinds = vec![BodyKind::Dynamic; 20];
        let mut pairs = all_pairs(20);
        let before = pairs.clone();
        cap.apply(&mut pairs, &kinds);
        assert_eq!(pairs, before);
        assert_eq!(cap.dropped(), 0);
    }

    #[test]
    fn a_pile_is_held_to_the_per_body_cap_in_pair_order() {
        let n = 600;
        let mut cap = ContactCap::default();
        let kinds = vec![BodyKind::Dynamic; n as usize];
        let mut pairs = all_pairs(n);
        let total = pairs.len();
        cap.apply(&mut pairs, &kinds);
        let mut counts = vec![0u32; n as usize];
        for &(a, b) in &pairs {
            counts[a as usize] += 1;
            counts[b as usize] += 1;
        }
        assert!(counts.iter().all(|&c| c <= MAX_PAIRS_PER_BODY));
        assert_eq!(
            counts[0], MAX_PAIRS_PER_BODY,
            "body 0's first pairs are kept"
        );
        assert_eq!(cap.dropped(), total - pairs.len());
        assert!(pairs.windows(2).all(|w| w[0] < w[1]), "order kept");
    }

    #[test]
    fn static_bodies_are_not_capped() {
        let n = 1000u32;
        let mut kinds = vec![BodyKind::Dynamic; n as usize + 1];
        kinds[0] = BodyKind::Static;
        let mut pairs: Vec<(u32, u32)> = (1..=n).map(|b| (0, b)).collect();
        let mut cap = ContactCap::default();
        cap.apply(&mut pairs, &kinds);
        assert_eq!(pairs.len(), n as usize);
        assert_eq!(cap.dropped(), 0);
    }
}
