//! Union–find over indices 0..n, kept in a plain `Vec<u32>` of parents that its owner reuses step
//! after step: islands to sleep, the articulations of the mass ratios, the loops of the joint tree,
//! the impacts' islands and the islands the app shows are all rebuilt from scratch every step.
//!
//! Paths are halved on every `find`, and a union hangs the larger root under the smaller, so a
//! set's representative is its smallest index: deterministic, whatever order the unions come in.

/// Makes `parent` `count` singleton sets.
pub(crate) fn reset(parent: &mut Vec<u32>, count: usize) {
    parent.clear();
    parent.extend(0..count as u32);
}

/// The representative of `i`'s set (its smallest index).
pub(crate) fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let grand = parent[parent[i as usize] as usize];
        parent[i as usize] = grand;
        i = grand;
    }
    i
}

/// Joins the sets of `a` and `b`; returns whether they were apart.
pub(crate) fn union(parent: &mut [u32], a: u32, b: u32) -> bool {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
    ra != rb
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_is_named_by_its_smallest_index_whatever_the_order_of_unions() {
        let mut parent = Vec::new();
        reset(&mut parent, 6);
        assert!(union(&mut parent, 5, 3));
        assert!(union(&mut parent, 4, 5));
        assert!(!union(&mut parent, 3, 4));
        assert!(union(&mut parent, 1, 2));
        let representatives: Vec<u32> = (0..6).map(|i| find(&mut parent, i)).collect();
        assert_eq!(representatives, [0, 1, 1, 3, 3, 3]);
    }
}
