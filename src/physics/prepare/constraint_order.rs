//! The order the solver visits contacts in, from the contact graph (bodies as nodes, contacts as
//! edges; static and sleeping bodies are the one dummy node 0):
//!
//! 1. **Layers**: breadth-first distance of every body from the static ones (a body on the floor is
//!    layer 1, a box on it layer 2, ...); a contact's layer is its lower body's. Shock propagation
//!    visits contacts bottom-up in this order, and the solve visits each colour bottom-up (from 4
//!    sub-steps the biased passes go top-down in turn: `wide_contacts::LayerOrder`).
//! 2. **Colouring**, greedy in layer order: a contact takes the lowest colour that neither of its
//!    dynamic bodies has yet, so the contacts of one colour share no dynamic body and can be solved
//!    four at a time in SIMD lanes (Box2D v3 colours for the same reason).
//! 3. **Solve order**: by colour, then lane-group kind (one, two or four points) and whether body A is
//!    static, then layer.
//!
//! Everything is linear in bodies and contacts: a CSR adjacency, a queue, and two counting sorts.

use crate::physics::solve::wide_contacts::GroupKind;

/// The last graph colour: constraints that find every lower colour taken share it and are solved one
/// at a time (correct, just serial).
pub(crate) const SERIAL_COLOR: u32 = 63;

/// Layers, colours and orders of one contact graph, with the scratch their passes reuse step after
/// step (no allocation once the world has reached its size).
#[derive(Debug, Default)]
pub(crate) struct ConstraintOrder {
    /// Per solver body: layer (0 = static dummy, `u32::MAX` = not connected to it).
    pub levels: Vec<u32>,
    /// Active contact indices (those with a dynamic body), sorted by (layer, index): `layer << 32 |
    /// contact`.
    pub order: Vec<u64>,
    /// `group << 32 | rank`, sorted: the solve order, rank being a contact's position in `order` and
    /// group `8 · colour + 2 · kind + (body A static)`.
    pub color_order: Vec<u64>,
    /// Per position in `order`: that contact's position in `color_order` (the constraint index), so
    /// `layer_order` lists the constraints in layer order.
    pub layer_order: Vec<u32>,
    /// CSR adjacency of the contact graph: body i's neighbours are
    /// `adjacency[adjacency_start[i]..adjacency_start[i + 1]]`.
    adjacency_start: Vec<u32>,
    adjacency: Vec<u32>,
    queue: Vec<u32>,
    sort_scratch: Vec<u64>,
    sort_counts: Vec<u32>,
    /// Per solver body: bit c set when a contact of colour c uses it.
    color_masks: Vec<u64>,
    /// Per contact: solver indices of its bodies and its lane-group kind, from which the layers,
    /// the colouring and both orders are computed, and the buffer the next step's are gathered in
    /// to be compared with them: equal (a resting pile), the orders are reused as they are.
    keys: Vec<(u32, u32, GroupKind)>,
    next_keys: Vec<(u32, u32, GroupKind)>,
    /// Solver indices of each constraint's bodies, in solve order (constraint i is `links[i]`).
    pub links: Vec<(u32, u32)>,
    /// Per contact: its constraint index, or [`NOT_IN_GRAPH`] for a contact of sleeping or static
    /// bodies alone. Lets a pass that reads the contacts themselves (over 200 bytes each) walk them
    /// in the order they are stored instead of in solve order, which visits them at random.
    pub constraint_of: Vec<u32>,
}

/// [`ConstraintOrder::constraint_of`] for a contact the solver does not see.
pub(crate) const NOT_IN_GRAPH: u32 = u32::MAX;

impl ConstraintOrder {
    /// Brings the orders up to date with this step's contacts, given by their `keys` (per contact:
    /// its bodies' solver indices and its lane-group kind) between `bodies` solver bodies:
    /// recomputed only when the keys differ from last step's (a resting pile keeps its orders),
    /// then `links` in solve order.
    pub(crate) fn update(
        &mut self,
        keys: impl Iterator<Item = (u32, u32, GroupKind)>,
        bodies: usize,
    ) {
        self.next_keys.clear();
        self.next_keys.extend(keys);
        let same_graph = self.next_keys == self.keys && self.levels.len() == bodies;
        std::mem::swap(&mut self.keys, &mut self.next_keys);
        if !same_graph {
            let keys = std::mem::take(&mut self.keys);
            self.rebuild(&keys, bodies);
            self.keys = keys;
        }
        let mut links = std::mem::take(&mut self.links);
        links.clear();
        links.extend(self.solve_order().map(|(_, k)| {
            let (a, b, _) = self.keys[k];
            (a, b)
        }));
        self.links = links;
        if !same_graph {
            let mut constraint_of = std::mem::take(&mut self.constraint_of);
            constraint_of.clear();
            constraint_of.resize(self.keys.len(), NOT_IN_GRAPH);
            for (i, (_, k)) in self.solve_order().enumerate() {
                constraint_of[k] = i as u32;
            }
            self.constraint_of = constraint_of;
        }
    }

    /// Recomputes everything for the contacts `keys` (per contact: its bodies' solver indices and its
    /// lane-group kind) between `bodies` solver bodies. Reads only these keys, never the contacts
    /// themselves (over 200 bytes each, visited out of order by the colouring). Scratch vectors whose
    /// every slot is written before it is read are resized without being cleared first.
    pub(crate) fn rebuild(&mut self, keys: &[(u32, u32, GroupKind)], bodies: usize) {
        let n = bodies;
        // The passes below index plain slices, whose pointers and lengths stay in registers (a
        // `Vec` field is reloaded after every store through another).

        // Layers: BFS over a CSR adjacency of the active contacts. Body i's degree is counted at
        // `adjacency_start[i + 2]`; after the prefix sum `adjacency_start[i + 1]` is where i's
        // neighbours begin and serves as its fill cursor, which leaves it where they end, so that
        // afterwards i's neighbours are `adjacency_start[i]..adjacency_start[i + 1]`.
        self.levels.clear();
        self.levels.resize(n, u32::MAX);
        self.adjacency_start.clear();
        self.adjacency_start.resize(n + 2, 0);
        self.queue.clear();
        let levels: &mut [u32] = &mut self.levels;
        let start: &mut [u32] = &mut self.adjacency_start;
        levels[0] = 0;
        for &(ia, ib, _) in keys {
            if ia != 0 && ib != 0 {
                start[ia as usize + 2] += 1;
                start[ib as usize + 2] += 1;
            } else if ia != 0 || ib != 0 {
                let d = (ia | ib) as usize;
                if levels[d] != 1 {
                    levels[d] = 1;
                    self.queue.push(d as u32);
                }
            }
        }
        for i in 2..n + 2 {
            start[i] += start[i - 1];
        }
        // Every slot is written once by the fill: resized, never cleared.
        self.adjacency.resize(start[n + 1] as usize, 0);
        let adjacency: &mut [u32] = &mut self.adjacency;
        for &(ia, ib, _) in keys {
            if ia != 0 && ib != 0 {
                let cursor_a = &mut start[ia as usize + 1];
                adjacency[*cursor_a as usize] = ib;
                *cursor_a += 1;
                let cursor_b = &mut start[ib as usize + 1];
                adjacency[*cursor_b as usize] = ia;
                *cursor_b += 1;
            }
        }
        let queue = &mut self.queue;
        let mut head = 0;
        while head < queue.len() {
            let i = queue[head] as usize;
            head += 1;
            let next = levels[i] + 1;
            for &j in &adjacency[start[i] as usize..start[i + 1] as usize] {
                if levels[j as usize] == u32::MAX {
                    levels[j as usize] = next;
                    queue.push(j);
                }
            }
        }
        // BFS dequeues in level order: the last body queued has the deepest layer.
        let deepest = queue.last().map_or(0, |&i| levels[i as usize]);

        // Active contacts in layer order (a contact's layer is its lower body's). Unconnected
        // bodies (level u32::MAX) go last, in the bucket after the deepest layer. Each key is
        // written at `count`, which only a contact with a dynamic body advances (no branch), and
        // tallied for the sort as it is made.
        let unconnected = deepest + 1;
        self.order.resize(keys.len(), 0);
        let order: &mut [u64] = &mut self.order;
        self.sort_counts.clear();
        self.sort_counts.resize(unconnected as usize + 2, 0);
        let counts: &mut [u32] = &mut self.sort_counts;
        let mut count = 0;
        for (k, &(ia, ib, _)) in keys.iter().enumerate() {
            let level = levels[ia as usize]
                .min(levels[ib as usize])
                .min(unconnected);
            let active = ia != 0 || ib != 0;
            order[count] = pack(u64::from(level), k);
            counts[level as usize + 1] += u32::from(active);
            count += usize::from(active);
        }
        self.order.truncate(count);
        counting_sort_by_high_word(
            &mut self.order,
            &mut self.sort_scratch,
            &mut self.sort_counts,
        );

        // Graph colouring, greedy in layer order (Box2D v3 colours for SIMD; we colour so that
        // consecutive constraints share no body and the CPU overlaps their dependency chains): a
        // constraint takes the lowest colour used by neither of its dynamic bodies; past 63 colours
        // everything goes to the last one (correct, just serial). The solve runs in (colour, layer)
        // order; the shock pass keeps pure layer order through `layer_order`.
        self.color_masks.clear();
        self.color_masks.resize(n, 0);
        let masks: &mut [u64] = &mut self.color_masks;
        self.color_order.resize(self.order.len(), 0);
        self.sort_counts.clear();
        self.sort_counts
            .resize(8 * (SERIAL_COLOR as usize + 1) + 1, 0);
        let counts: &mut [u32] = &mut self.sort_counts;
        for (rank, (slot, &key)) in self.color_order.iter_mut().zip(&self.order).enumerate() {
            let (ia, ib, kind) = keys[low_word(key)];
            let used = masks[ia as usize] | masks[ib as usize];
            let color = (!used).trailing_zeros().min(SERIAL_COLOR) as u64;
            // The static dummy (index 0) must keep an empty mask: marking both bodies and then
            // clearing the dummy's is one store instead of two branches.
            masks[ia as usize] |= 1 << color;
            masks[ib as usize] |= 1 << color;
            masks[0] = 0;
            // Within a colour the order does not change the result (no shared dynamic body):
            // manifolds are sorted by lane-group kind (one, two, four points) and by whether body A
            // is static, so that they pack into groups of one kind whose side A is often all static.
            let group = 8 * color + 2 * kind as u64 + u64::from(ia == 0);
            *slot = pack(group, rank);
            counts[group as usize + 1] += 1;
        }
        counting_sort_by_high_word(
            &mut self.color_order,
            &mut self.sort_scratch,
            &mut self.sort_counts,
        );
        // `color_order` holds every rank once: each slot is written.
        self.layer_order.resize(self.order.len(), 0);
        let layer_order: &mut [u32] = &mut self.layer_order;
        for (position, &key) in self.color_order.iter().enumerate() {
            layer_order[low_word(key)] = position as u32;
        }
    }
}

impl ConstraintOrder {
    /// The constraints in solve order (constraint i is the i-th), each as its graph colour and the
    /// index of its contact.
    #[inline]
    pub(crate) fn solve_order(&self) -> impl Iterator<Item = (u32, usize)> + '_ {
        self.color_order.iter().map(|&key| {
            (
                color_of_group(high_word(key)),
                self.contact_at_rank(low_word(key)),
            )
        })
    }

    /// The index of constraint `i`'s contact (`i` in solve order).
    #[inline]
    pub(crate) fn contact(&self, i: usize) -> usize {
        self.contact_at_rank(low_word(self.color_order[i]))
    }

    /// The contact index of the `rank`-th entry of `order`.
    #[inline]
    fn contact_at_rank(&self, rank: usize) -> usize {
        low_word(self.order[rank])
    }
}

/// `order` and `color_order` hold `high << 32 | low` keys, sorted by their high word (layer, or
/// colour group) and then their low word (contact index, or rank in `order`).
#[inline]
fn pack(high: u64, low: usize) -> u64 {
    high << 32 | low as u64
}

/// The high word of a packed key: a layer or a colour group.
#[inline]
fn high_word(key: u64) -> u64 {
    key >> 32
}

/// The low word of a packed key: a contact index or a rank in `order`.
#[inline]
fn low_word(key: u64) -> usize {
    (key & 0xffff_ffff) as usize
}

/// The colour of a colour group `8 · colour + 2 · kind + (body A static)`.
#[inline]
fn color_of_group(group: u64) -> u32 {
    (group >> 3) as u32
}

/// Stable counting sort of `keys` by their high 32 bits, given how many keys fall in each bucket:
/// `counts[b + 1]` for high word b (`counts[0]` = 0; callers tally while making the keys, saving a
/// pass). Keys already in ascending order of their low word stay so within a bucket, so the result is
/// sorted by the whole key: O(n + buckets) where the standard sort is O(n log n). `counts` is left
/// holding each bucket's end. `scratch` ends up holding the old `keys` buffer; it is only resized,
/// not cleared, since the scatter writes each of its slots once.
fn counting_sort_by_high_word(keys: &mut Vec<u64>, scratch: &mut Vec<u64>, counts: &mut [u32]) {
    for i in 1..counts.len() {
        counts[i] += counts[i - 1];
    }
    scratch.resize(keys.len(), 0);
    let sorted: &mut [u64] = scratch;
    for &key in keys.iter() {
        let slot = &mut counts[(key >> 32) as usize];
        sorted[*slot as usize] = key;
        *slot += 1;
    }
    std::mem::swap(keys, scratch);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bucket tally `counting_sort_by_high_word` expects.
    fn tally(keys: &[u64], buckets: usize) -> Vec<u32> {
        let mut counts = vec![0; buckets + 1];
        for &key in keys {
            counts[(key >> 32) as usize + 1] += 1;
        }
        counts
    }

    #[test]
    fn counting_sort_orders_by_high_word_and_keeps_low_word_order() {
        let mut keys = vec![2 << 32 | 1, 2, 2 << 32 | 3, 1 << 32 | 4, 5];
        let mut expected = keys.clone();
        expected.sort_unstable();
        let mut counts = tally(&keys, 3);
        counting_sort_by_high_word(&mut keys, &mut Vec::new(), &mut counts);
        assert_eq!(keys, expected);
    }

    #[test]
    fn counting_sort_ignores_whatever_a_longer_scratch_held() {
        let mut keys = vec![1 << 32 | 7, 3, 1 << 32 | 2, 9];
        let mut scratch = vec![u64::MAX; 11];
        let mut counts = tally(&keys, 2);
        counting_sort_by_high_word(&mut keys, &mut scratch, &mut counts);
        assert_eq!(keys, vec![3, 9, 1 << 32 | 7, 1 << 32 | 2]);
    }
}
