//! Broad phase: which bodies' bounding boxes overlap, in about linear time.
//!
//! A uniform hash grid rebuilt every call (Teschner et al. 2003, "Optimized Spatial Hashing for Collision
//! Detection of Deformable Objects", for the hash; Ericson 7.1 for grids). Rebuilding costs O(N) and
//! needs no incremental state, so teleports, sleeping and freezing cost nothing extra.
//!
//! ```text
//! cell = 2.5 × mean AABB size of the non-static bodies     (each grid body covers ≤ 2 cells per axis)
//! bodies larger than a cell (floors, walls, outliers), or with inverted or non-finite bounds → "large"
//! hash each grid body's cells once into a list of distinct slots (a table of ≥ 1 slot per entry)
//! two hash grids sharing that table, each a counting sort of (slot, body) entries, ascending by id:
//!     awake grid: the awake dynamic bodies; resting grid: static and sleeping bodies
//! for each body i in id order:
//!     grid body: for each of its slots s, for each j > i in slot s of the awake grid (and, if i is
//!         awake, of the resting grid): report (i, j) if the boxes overlap and s is the slot of
//!         max(lowest cell of i, lowest cell of j), the cell of their intersection's min corner, which
//!         both cover (so a pair sharing several cells, or slots, is reported once)
//!     plus every large body j > i that overlaps and may touch
//!     large body: every body j > i that overlaps and may touch (few large bodies: O(N) each)
//!     sort i's few pairs by j
//! ```
//! Resting bodies never scan each other, so a pile that has gone to sleep costs little.
//!
//! Output: each overlapping pair once, as (lower id, higher id), sorted ascending, the same for the same
//! input. Static–static, static–sleeping and sleeping–sleeping pairs are never produced: a pair needs at
//! least one awake dynamic body.
//!
//! Memory is linear in the number of bodies: per body a cell range, a flag and a slot-list offset
//! (29 bytes); per grid body at most 8 (about 3.4 on average) slots of 4 bytes and slot entries of 48
//! bytes (id, bounds, lowest cell); two slot tables of two u32 per slot with fewer than 2 slots per
//! entry; the large list (4 bytes per large body). Buffers are reused and only grow.
//!
//! Measured (release, a noisy shared VM; the raining pit's AABBs packed into a settled pile, counted
//! with cachegrind): 1,000 bodies ≈ 0.2 ms and 2.0 M instructions, 4,000 ≈ 1.5 ms and 10.9 M
//! instructions, where an O(N²) loop takes 1.0 ms and 14.6 ms; with 90 % of the pile asleep, 4,000
//! bodies take 5.3 M instructions. The 4,000-body pile has 7× the overlapping pairs of the 1,000-body
//! one (more layers), and the cost follows N + pairs.

use glam::{Vec3, Vec3A};

use crate::geometry::Aabb;

/// How a body takes part in the broad phase.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BodyKind {
    /// Never moves; pairs only with awake dynamic bodies.
    Static,
    /// Awake and moving; pairs with every kind.
    Dynamic,
    /// Asleep; pairs only with awake dynamic bodies.
    Sleeping,
}

impl BodyKind {
    /// Whether a contact between bodies of these kinds needs solving: at least one must be awake and
    /// dynamic.
    #[inline]
    pub fn may_touch(self, other: BodyKind) -> bool {
        self == BodyKind::Dynamic || other == BodyKind::Dynamic
    }
}

/// Cell coordinates are clamped to ±2^30 so that bodies flung absurdly far cannot overflow `i32`;
/// such bodies share border cells, which costs speed, never correctness.
const CELL_COORD_LIMIT: f32 = (1u32 << 30) as f32;
/// Smallest cell edge, metres (keeps 1/cell finite for point-like bodies).
const MIN_CELL_SIZE: f32 = 1e-3;
/// Cell edge used when there is no non-static body to measure, metres.
const DEFAULT_CELL_SIZE: f32 = 1.0;

/// Reusable broad-phase state: scratch buffers only, so calls are independent of each other.
#[derive(Clone, Debug, Default)]
pub struct BroadPhase {
    /// Per body: `[lo_x, lo_y, lo_z, hi_x, hi_y, hi_z]` cells covered; unused for large bodies.
    cell_ranges: Vec<[i32; 6]>,
    /// Per body: whether it lives in the large list instead of the grids.
    is_large: Vec<bool>,
    /// Ids of large bodies, ascending.
    large: Vec<u32>,
    /// Distinct hash slots of each grid body's cells: body i's are
    /// `slot_list[slot_offsets[i]..slot_offsets[i + 1]]` (none for large bodies).
    slot_list: Vec<u32>,
    /// Offsets into `slot_list`; length n + 1.
    slot_offsets: Vec<u32>,
    /// Grid of the awake dynamic bodies that fit a cell.
    awake: HashGrid,
    /// Grid of the static and sleeping bodies that fit a cell.
    resting: HashGrid,
    /// Cell edge of the last call, metres.
    cell_size: f32,
}

impl BroadPhase {
    /// An empty broad phase; buffers grow on first use and are then reused.
    pub fn new() -> Self {
        Self::default()
    }

    /// Cell edge chosen by the last [`find_pairs`](Self::find_pairs) call, metres (0 before any call).
    pub fn cell_size(&self) -> f32 {
        self.cell_size
    }

    /// Fills `pairs` (cleared first) with every pair of bodies whose AABBs overlap (touching counts) and
    /// whose kinds may touch, as `(lower id, higher id)`, sorted ascending, each pair once. A body's id
    /// is its index in `aabbs` / `kinds`; if the slices differ in length the extra entries are ignored.
    /// Bodies with non-finite bounds are handled (they overlap whatever their bounds overlap under IEEE
    /// comparisons, so a NaN box overlaps nothing).
    pub fn find_pairs(&mut self, aabbs: &[Aabb], kinds: &[BodyKind], pairs: &mut Vec<(u32, u32)>) {
        pairs.clear();
        let n = aabbs.len().min(kinds.len());
        debug_assert_eq!(aabbs.len(), kinds.len());
        let (aabbs, kinds) = (&aabbs[..n], &kinds[..n]);

        let cell = choose_cell_size(aabbs, kinds);
        self.cell_size = cell;
        let inv_cell = 1.0 / cell;

        // Classify and measure.
        // Scratch arrays only grow: every entry read below is written first in this call.
        grow_to(&mut self.cell_ranges, n, [0; 6]);
        grow_to(&mut self.is_large, n, false);
        self.large.clear();
        for (i, aabb) in aabbs.iter().enumerate() {
            let size = aabb.max - aabb.min;
            // Inverted (min > max), NaN and infinite bounds go to the large list too.
            let fits = size.max_element() <= cell
                && size.min_element() >= 0.0
                && aabb.min.is_finite()
                && aabb.max.is_finite();
            self.is_large[i] = !fits;
            if !fits {
                self.large.push(i as u32);
                continue;
            }
            let lo = cell_of(aabb.min, inv_cell);
            let hi = cell_of(aabb.max, inv_cell);
            self.cell_ranges[i] = [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]];
        }
        // Hash every grid body's cells once: both grids share the table size, so the distinct slots of
        // each body serve building both grids and querying them.
        let mut total = 0usize;
        for i in 0..n {
            if !self.is_large[i] {
                total += cell_count(&self.cell_ranges[i]);
            }
        }
        let slot_count = total.next_power_of_two().max(64);
        let shift = 32 - slot_count.trailing_zeros();
        self.slot_list.clear();
        self.slot_offsets.clear();
        self.slot_offsets.push(0);
        for i in 0..n {
            if !self.is_large[i] {
                let start = self.slot_list.len();
                let list = &mut self.slot_list;
                for_each_cell(&self.cell_ranges[i], |c| {
                    // Slots fit u32: the table has at most ~2 slots per entry.
                    let slot = slot_of(c, shift) as u32;
                    // A hash collision between two cells of one body: enter the body once.
                    if !list[start..].contains(&slot) {
                        list.push(slot);
                    }
                });
            }
            self.slot_offsets.push(self.slot_list.len() as u32);
        }
        let layout = SlotLayout {
            list: &self.slot_list,
            offsets: &self.slot_offsets,
            ranges: &self.cell_ranges[..n],
            slot_count,
        };
        self.awake
            .build(aabbs, &layout, |i| kinds[i] == BodyKind::Dynamic);
        self.resting
            .build(aabbs, &layout, |i| kinds[i] != BodyKind::Dynamic);

        // Query, body by body in id order: every body meets the awake bodies above it; awake bodies
        // also meet the resting ones above them. Resting bodies never scan each other, so a pile that
        // has gone to sleep costs little.
        for i in 0..n {
            let group_start = pairs.len();
            let (box_i, kind_i) = (&aabbs[i], kinds[i]);
            let id_i = i as u32;
            if self.is_large[i] {
                for j in (i + 1)..n {
                    if kind_i.may_touch(kinds[j]) && box_i.overlaps(&aabbs[j]) {
                        pairs.push((id_i, j as u32));
                    }
                }
                continue;
            }
            let range = &self.cell_ranges[i];
            let slots_i =
                &self.slot_list[self.slot_offsets[i] as usize..self.slot_offsets[i + 1] as usize];
            self.awake.query(id_i, box_i, range, slots_i, shift, pairs);
            if kind_i == BodyKind::Dynamic {
                self.resting
                    .query(id_i, box_i, range, slots_i, shift, pairs);
            }
            let first_large = self.large.partition_point(|&j| j <= id_i);
            for &j in &self.large[first_large..] {
                if kind_i.may_touch(kinds[j as usize]) && box_i.overlaps(&aabbs[j as usize]) {
                    pairs.push((id_i, j));
                }
            }
            // A body meets each partner once (see `HashGrid::build`), so sorting is all that is left.
            pairs[group_start..].sort_unstable();
        }
    }
}

/// Where the grid bodies go: each body's distinct hash slots (shared by both grids), cell ranges and the
/// table size. Large bodies have no slots.
struct SlotLayout<'a> {
    list: &'a [u32],
    offsets: &'a [u32],
    ranges: &'a [[i32; 6]],
    slot_count: usize,
}

impl SlotLayout<'_> {
    fn slots_of(&self, i: usize) -> &[u32] {
        &self.list[self.offsets[i] as usize..self.offsets[i + 1] as usize]
    }
}

/// One body in one slot of a [`HashGrid`]: everything a query reads, in one 48-byte record.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    /// Bounds (SIMD-width vectors).
    min: Vec3A,
    max: Vec3A,
    /// Lowest cell the body covers, for the reported-once test.
    lo: [i32; 3],
    /// Body id.
    id: u32,
}

/// A spatial hash of grid bodies, rebuilt by a counting sort: slot `s` holds entries
/// `slot_start[s]..slot_start[s + 1]`, ascending by body id, each body at most once per slot, so a
/// query scans contiguous memory.
#[derive(Clone, Debug, Default)]
struct HashGrid {
    /// Slot starts; length = slot count + 1.
    slot_start: Vec<u32>,
    /// Fill cursor per slot, scratch of the counting sort.
    cursor: Vec<u32>,
    /// The entries, grouped by slot.
    entries: Vec<Entry>,
    /// Entries in use (the arrays may be longer: they only grow).
    used: usize,
}

impl HashGrid {
    /// Rebuilds the grid from the grid bodies `i` (those with slots) with `member(i)`.
    fn build(&mut self, aabbs: &[Aabb], layout: &SlotLayout, member: impl Fn(usize) -> bool) {
        let slots = layout.slot_count;
        let has_members =
            (0..layout.ranges.len()).any(|i| member(i) && !layout.slots_of(i).is_empty());
        if !has_members {
            // Nothing to hash (a scene without sleepers, or asleep as a whole): skip the table.
            self.used = 0;
            return;
        }
        self.slot_start.clear();
        self.slot_start.resize(slots + 1, 0);
        for i in 0..layout.ranges.len() {
            if member(i) {
                for &slot in layout.slots_of(i) {
                    self.slot_start[slot as usize + 1] += 1;
                }
            }
        }
        for s in 0..slots {
            self.slot_start[s + 1] += self.slot_start[s];
        }
        let used = self.slot_start[slots] as usize;
        self.used = used;
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.slot_start[..slots]);
        // Every entry below `used` is written by the fill; the arrays only grow.
        grow_to(&mut self.entries, used, Entry::default());
        // Bodies in id order keep every slot sorted by id.
        for (i, range) in layout.ranges.iter().enumerate() {
            let body_slots = layout.slots_of(i);
            if body_slots.is_empty() || !member(i) {
                continue;
            }
            let entry = Entry {
                min: Vec3A::from(aabbs[i].min),
                max: Vec3A::from(aabbs[i].max),
                lo: [range[0], range[1], range[2]],
                id: i as u32,
            };
            for &slot in body_slots {
                let k = self.cursor[slot as usize] as usize;
                self.entries[k] = entry;
                self.cursor[slot as usize] += 1;
            }
        }
    }

    /// Appends `(id_i, j)` for every body j > `id_i` in this grid whose bounds overlap `box_i`, once
    /// each: body i visits each of its distinct slots once, meets j at most once per slot, and takes the
    /// pair only in the slot of the lowest cell both cover, `max(lowest cell of i, lowest cell of j)`.
    fn query(
        &self,
        id_i: u32,
        box_i: &Aabb,
        range: &[i32; 6],
        slots_i: &[u32],
        shift: u32,
        pairs: &mut Vec<(u32, u32)>,
    ) {
        if self.used == 0 {
            return;
        }
        let lo_i = [range[0], range[1], range[2]];
        let (min_i, max_i) = (Vec3A::from(box_i.min), Vec3A::from(box_i.max));
        for &slot in slots_i {
            let slot = slot as usize;
            let (start, end) = (
                self.slot_start[slot] as usize,
                self.slot_start[slot + 1] as usize,
            );
            // Ascending ids: walk down from the top and stop at i.
            for e in self.entries[start..end].iter().rev() {
                if e.id <= id_i {
                    break;
                }
                if (e.min.cmple(max_i) & min_i.cmple(e.max)).all()
                    && slot_of(first_shared_cell(lo_i, e.lo), shift) == slot
                {
                    pairs.push((id_i, e.id));
                }
            }
        }
    }
}

/// Makes `v` at least `len` long (new entries = `fill`), never shorter: scratch whose stale tail is
/// never read.
fn grow_to<T: Clone>(v: &mut Vec<T>, len: usize, fill: T) {
    if v.len() < len {
        v.resize(len, fill);
    }
}

/// Cell edge in units of the mean AABB size of the non-static bodies. At least 2 keeps every typical
/// body in the grid (≤ 2 cells per axis); 1 would send the larger half of a mixed population to the
/// quadratic large list. Instruction counts on the raining pit (1,000 / 4,000 bodies, falling, piled,
/// piled and 90 % asleep) favour 2.5 over 1.5, 2 and 3.
const CELL_FACTOR: f32 = 2.5;

/// `CELL_FACTOR` × the mean largest AABB edge of the non-static bodies with finite bounds, metres.
fn choose_cell_size(aabbs: &[Aabb], kinds: &[BodyKind]) -> f32 {
    let mut sum = 0.0f64;
    let mut count = 0u32;
    for (aabb, kind) in aabbs.iter().zip(kinds) {
        let extent = (aabb.max - aabb.min).max_element();
        if *kind != BodyKind::Static && extent.is_finite() && extent >= 0.0 {
            sum += f64::from(extent);
            count += 1;
        }
    }
    if count == 0 {
        return DEFAULT_CELL_SIZE;
    }
    let cell = (f64::from(CELL_FACTOR) * sum / f64::from(count)) as f32;
    if cell.is_finite() {
        cell.max(MIN_CELL_SIZE)
    } else {
        DEFAULT_CELL_SIZE
    }
}

/// Integer cell holding point `p`.
#[inline]
fn cell_of(p: Vec3, inv_cell: f32) -> [i32; 3] {
    let c = (p * inv_cell).clamp(
        Vec3::splat(-CELL_COORD_LIMIT),
        Vec3::splat(CELL_COORD_LIMIT),
    );
    [floor_i32(c.x), floor_i32(c.y), floor_i32(c.z)]
}

/// ⌊x⌋ for |x| ≤ 2^30 without a libm call (the baseline x86-64 target has no SSE4.1 `roundss`).
#[inline]
fn floor_i32(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x { t - 1 } else { t }
}

/// The lowest cell covered by both of two overlapping boxes whose lowest cells are `lo_a` and `lo_b`:
/// floor is monotonic, so it is `max(lo_a, lo_b)` per axis, the cell of the min corner of their
/// intersection. Testing a pair only in its slot reports it once however many cells it shares.
#[inline]
fn first_shared_cell(lo_a: [i32; 3], lo_b: [i32; 3]) -> [i32; 3] {
    [
        lo_a[0].max(lo_b[0]),
        lo_a[1].max(lo_b[1]),
        lo_a[2].max(lo_b[2]),
    ]
}

#[inline]
fn cell_count(r: &[i32; 6]) -> usize {
    ((r[3] - r[0] + 1) * (r[4] - r[1] + 1) * (r[5] - r[2] + 1)) as usize
}

/// Calls `f` for every cell of the range, x outermost. Half-open ranges: `RangeInclusive` iteration
/// compiles to noticeably slower code in this hot loop.
#[inline(always)]
fn for_each_cell(r: &[i32; 6], mut f: impl FnMut([i32; 3])) {
    for x in r[0]..r[3] + 1 {
        for y in r[1]..r[4] + 1 {
            for z in r[2]..r[5] + 1 {
                f([x, y, z]);
            }
        }
    }
}

/// Hash slot of a cell among `2^(32 − shift)` slots: Teschner et al.'s (2003) prime mix, then
/// Fibonacci hashing (Knuth 6.4), which takes the well-mixed high bits; the low bits of the prime mix
/// alone collide badly for the small coordinate ranges of a compact scene.
#[inline]
fn slot_of(c: [i32; 3], shift: u32) -> usize {
    let h = (c[0] as u32).wrapping_mul(73_856_093)
        ^ (c[1] as u32).wrapping_mul(19_349_663)
        ^ (c[2] as u32).wrapping_mul(83_492_791);
    (h.wrapping_mul(0x9e37_79b9) >> shift) as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box(x: f32) -> Aabb {
        Aabb::from_center_half_extents(Vec3::new(x, 0.0, 0.0), Vec3::splat(0.5))
    }

    #[test]
    fn a_row_of_touching_boxes_pairs_each_with_its_neighbours() {
        let aabbs: Vec<Aabb> = (0..5).map(|i| unit_box(i as f32 * 0.9)).collect();
        let kinds = vec![BodyKind::Dynamic; 5];
        let mut pairs = Vec::new();
        BroadPhase::new().find_pairs(&aabbs, &kinds, &mut pairs);
        assert_eq!(pairs, vec![(0, 1), (1, 2), (2, 3), (3, 4)]);
    }

    #[test]
    fn static_and_sleeping_bodies_pair_only_with_awake_dynamic_ones() {
        let floor = Aabb::new(Vec3::splat(-100.0), Vec3::new(100.0, 0.0, 100.0));
        let aabbs = vec![floor, floor, unit_box(0.0), unit_box(0.5), unit_box(0.9)];
        let kinds = vec![
            BodyKind::Static,
            BodyKind::Static,
            BodyKind::Sleeping,
            BodyKind::Sleeping,
            BodyKind::Dynamic,
        ];
        let mut pairs = Vec::new();
        BroadPhase::new().find_pairs(&aabbs, &kinds, &mut pairs);
        assert_eq!(pairs, vec![(0, 4), (1, 4), (2, 4), (3, 4)]);
    }

    #[test]
    fn nan_and_infinite_bounds_do_not_panic() {
        let nan = Aabb::new(Vec3::splat(f32::NAN), Vec3::splat(f32::NAN));
        let everything = Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::splat(f32::INFINITY));
        let far = Aabb::from_center_half_extents(Vec3::splat(1e30), Vec3::splat(0.5));
        let aabbs = vec![nan, everything, far, unit_box(0.0)];
        let kinds = vec![BodyKind::Dynamic; 4];
        let mut pairs = Vec::new();
        BroadPhase::new().find_pairs(&aabbs, &kinds, &mut pairs);
        assert_eq!(pairs, vec![(1, 2), (1, 3)]);
    }
}
