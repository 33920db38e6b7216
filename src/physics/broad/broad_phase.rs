//! Broad phase: which bodies' bounding boxes overlap, in about linear time.
//!
//! Sorted rows swept along one axis: a uniform grid over two axes (Ericson 2005, 7.1) whose cells,
//! "rows", are kept sorted along the third axis and swept as in sort and sweep (Baraff 1992; Ericson
//! 7.5.1). Each body lies in exactly one row, so nothing is hashed, no pair is met twice and no
//! duplicate test is needed.
//!
//! ```text
//! w = sweep axis: the widest spread of the non-static centres (changed only when another axis
//!     spreads 25 % wider); u, v = the other two; boxes are stored permuted to (u, v, w)
//! large = bodies wider along u or v than 2.5 × the mean extent of the non-static bodies, or with
//!     inverted or non-finite bounds; the others are grid bodies
//! c = the widest grid body along u or v
//! row of a grid body = (⌊min_u / c⌋, ⌊min_v / c⌋); it ends at most one row further (checked exactly,
//!     else it is large), so overlapping grid bodies' rows differ by at most 1 along u and along v
//! two arrays of grid bodies, awake (awake dynamic) and resting (static, sleeping), each sorted by
//!     (row, min_w) with a table of its rows: starting from the last call's order, a stable counting
//!     sort by row (rows numbered over their bounding rectangle), then an insertion sort, O(N) while
//!     bodies keep their order along w within a row (the standard sort past a budget of moves)
//! for each awake row R:
//!     R with itself: each body a with the bodies b after it while min_w(b) ≤ max_w(a)
//!     R with the awake rows (u, v+1), (u+1, v−1), (u+1, v), (u+1, v+1) (each pair of neighbouring
//!     rows from one side only) and with the 9 resting rows around it: merge-like, each a with the b
//!     having min_w(b) ∈ [min_w(a) − E, max_w(a)], E = the widest w extent in b's array; the window
//!     start only moves forward along the row
//!     neighbour rows come from one cursor per offset in the row table (their keys grow with R's)
//! each large body: the rows that can hold a partner (the same floor argument) and, in each, a binary
//!     search for its w window; large–large pairs directly
//! pairs sorted by two stable counting sorts, by higher id then by lower id
//! ```
//! Resting bodies never scan each other, so a pile that has gone to sleep costs little. The last
//! call's sweep axis and orders only make the next call faster: the output depends on the input alone.
//!
//! Output: each overlapping pair once, as (lower id, higher id), sorted ascending. Static–static,
//! static–sleeping and sleeping–sleeping pairs are never produced: a pair needs at least one awake
//! dynamic body.
//!
//! Cost: O(N + rows + box tests + pairs), with about ρ·c²·(e + 4·(E + e)) box tests per awake body in a
//! crowd of ρ bodies per m³ and mean w extent e. Memory is linear: per body two 48-byte entries (staged
//! and sorted), its last position (4 bytes) and where it went this call and the last (a byte each); per
//! occupied row 16 bytes, and 4 bytes per row of the bounding rectangle (at most 4 per grid body +
//! 1,024, else the standard sort is used); 16 bytes per pair found.
//!
//! Measured on snapshots of the raining pit with sleeping off (steps 10, 40, 80 and 150; instructions
//! per call by callgrind, mean of the four): 1,000 bodies 0.71 M (the hash grid this replaced: 1.49 M),
//! 4,000 bodies 4.1 M (7.6 M); about 12 box tests per body for 3.5 pairs at 4,000 bodies, where the
//! hash grid made 44. Many large bodies cost far less than the hash grid's O(N) each: 900 static tiles
//! under 3,000 boxes, or 4,000 boxes of which every tenth is 3.5 times wider, took about 1.2 and 1.7 ms
//! per call where it took 10.5 and 11.3 ms (wall clock, the same noisy machine). `nudge bench kernels`
//! times this function on those four snapshots of the pit (its broad-phase rows): on 2026-11-25,
//! 0.07 ms per call at 1,000 bodies and 0.38–0.47 ms at 4,000.

use glam::{Vec3, Vec3A, Vec4};

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

/// Row coordinates are clamped to ±2^30 so that bodies flung absurdly far cannot overflow; clamping is
/// monotonic and moves neighbours no further apart, so such bodies share border rows, which costs speed,
/// never correctness.
const CELL_COORD_LIMIT: f32 = (1u32 << 30) as f32;
/// Bias making clamped row coordinates non-negative `u32`s with room for ±1.
const CELL_COORD_BIAS: i64 = 1 << 31;
/// Smallest row edge, metres (keeps 1/c finite for point-like bodies).
const MIN_CELL_SIZE: f32 = 1e-3;
/// Bodies wider (along u or v) than this many mean extents of the non-static bodies are left out of
/// the row edge (tests grow as its square), so they go to the large list unless they happen to lie
/// within two rows.
const LARGE_FACTOR: f32 = 2.5;
/// Bodies that may go to the large list because the row edge (the widest body of the last call)
/// is now too narrow for them, beyond which (plus 1 per 256 bodies) the call classifies again with a
/// fresh edge.
const MISFITS_ALLOWED: usize = 8;
/// A row edge more than this many times the widest body measured (the bodies shrank, or others
/// replaced them) is replaced at once rather than on the next call.
const EDGE_SLACK: f32 = 2.0;
/// The sweep axis changes only when another axis spreads this many times wider.
const AXIS_HYSTERESIS: f32 = 1.25;

/// Where a body went this call.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
enum Place {
    /// In the awake array.
    #[default]
    Awake,
    /// In the resting array.
    Resting,
    /// In the large list.
    Large,
}

/// Reusable broad-phase state: scratch buffers, plus the last call's sweep axis, row edge and orders,
/// which only make the next call faster (the output depends on the input alone).
#[derive(Clone, Debug, Default)]
pub struct BroadPhase {
    /// Per body: where it went this call.
    place: Vec<Place>,
    /// Per body: its entry (valid for grid bodies), built once and copied into its array.
    staged: Vec<Entry>,
    /// Per body of the last call: where it went (so the bodies new to an array are known without
    /// marking the others).
    last_place: Vec<Place>,
    /// Ids of large bodies, ascending.
    large: Vec<u32>,
    /// Awake dynamic grid bodies, sorted by (row, min_w).
    awake: SortedRows,
    /// Static and sleeping grid bodies, sorted by (row, min_w).
    resting: SortedRows,
    /// Pairs as found, unsorted.
    found: PairSink,
    /// Counting-sort cursors: per body + 1 for the pairs, per row + 1 for the arrays.
    counts: Vec<u32>,
    /// The rows the grid bodies occupy, if few enough to count-sort by (see [`DenseRows`]).
    dense: Option<DenseRows>,
    /// The pairs sorted by higher id only, between the two counting sorts.
    sorted_by_higher: Vec<(u32, u32)>,
    /// Row edge of the last call, metres (0 before any call).
    cell_size: f32,
    /// Row edge for the next call: the widest grid body measured in the last (0 before any call).
    next_cell_size: f32,
    /// Bodies wider than this along u or v are left out of the row edge: `LARGE_FACTOR` × the mean
    /// extent measured in the last call, metres.
    large_above: f32,
    /// Sweep axis of the last call (0 = x, 1 = y, 2 = z).
    sweep_axis: usize,
}

/// What [`BroadPhase::classify`] measures on its way, to choose the next call's sweep axis and row edge
/// without a pass of its own (the output never depends on them, only the speed).
#[derive(Clone, Copy, Debug)]
struct Measures {
    /// Non-static bodies with finite, non-inverted bounds.
    count: u32,
    /// Sum of their largest extents, metres.
    extent_sum: f64,
    /// Bounding box of their centres, in world axes.
    lowest: Vec3A,
    highest: Vec3A,
    /// Widest extent along u or v among the bodies no wider than `large_above`, metres.
    widest: f32,
    /// Bodies no wider than `large_above` that still did not fit the rows (they straddle 3), which a
    /// fresh row edge would have fitted.
    misfits: usize,
}

/// One grid body as the sweep reads it, 48 bytes.
#[derive(Clone, Copy, Debug, Default)]
struct Entry {
    /// Bounds permuted to (u, v, w), w = sweep axis.
    min: Vec3A,
    max: Vec3A,
    /// Row: biased ⌊min_u / c⌋ in the high 32 bits, biased ⌊min_v / c⌋ in the low 32.
    row: u64,
    /// Body id.
    id: u32,
}

impl Entry {
    /// Sort order: (row, min_w). Grid bounds are finite, so `<` on floats is a total order here.
    #[inline]
    fn precedes(&self, other: &Entry) -> bool {
        self.row < other.row || (self.row == other.row && self.min.z < other.min.z)
    }

    /// Whether the boxes overlap (touching counts), as `Aabb::overlaps`.
    #[inline]
    fn overlaps(&self, other: &Entry) -> bool {
        (self.min.cmple(other.max) & other.min.cmple(self.max)).all()
    }
}

/// Grid bodies of one kind group, sorted by (row, min_w).
#[derive(Clone, Debug, Default)]
struct SortedRows {
    entries: Vec<Entry>,
    /// Body ids in the last call's order: the next call starts from it.
    order: Vec<u32>,
    /// Largest `max_w − min_w` of the entries, metres.
    max_extent_w: f32,
    /// The occupied rows, ascending: each a run of entries with one row key.
    rows: Vec<Row>,
}

/// One occupied row of a [`SortedRows`]: `entries[start..end]` have row key `key`.
#[derive(Clone, Copy, Debug)]
struct Row {
    key: u64,
    start: u32,
    end: u32,
}

/// The bounding rectangle of the grid bodies' rows, numbered densely in (u, v) order, which is the
/// order of the row keys: sorting the arrays by row is then a counting sort, O(N + rows), so bodies
/// changing rows (a crowd falling across the rows) cost no more than bodies staying in theirs.
#[derive(Clone, Copy, Debug)]
struct DenseRows {
    /// Lowest biased u and v row coordinates.
    u0: u64,
    v0: u64,
    /// Rows along v.
    nv: u64,
    /// Rows in the rectangle.
    count: usize,
}

impl DenseRows {
    /// Only rectangles of at most this many rows per grid body (plus a constant) are counted: a few far
    /// outliers make the rectangle huge, and the standard sort then does better.
    const ROWS_PER_BODY: u64 = 4;
    const ROWS_EXTRA: u64 = 1024;

    /// The rectangle from `lo..=hi` biased row coordinates along u and v, if small enough for `bodies`.
    fn new(lo: (u64, u64), hi: (u64, u64), bodies: usize) -> Option<DenseRows> {
        let (nu, nv) = (hi.0.checked_sub(lo.0)? + 1, hi.1.checked_sub(lo.1)? + 1);
        // Both are at most 2^31 + 1, so the product cannot overflow.
        let count = nu * nv;
        (count <= Self::ROWS_PER_BODY * bodies as u64 + Self::ROWS_EXTRA).then_some(DenseRows {
            u0: lo.0,
            v0: lo.1,
            nv,
            count: count as usize,
        })
    }

    /// Dense number of the row with key `row` (which must lie in the rectangle).
    #[inline]
    fn index(&self, row: u64) -> usize {
        (((row >> 32) - self.u0) * self.nv + ((row & 0xffff_ffff) - self.v0)) as usize
    }
}

/// Offsets of the rows (u, v+1), (u+1, v−1), (u+1, v), (u+1, v+1): with a's own row, each pair of
/// neighbouring rows is visited from exactly one side.
const FORWARD_ROWS: [(i64, i64); 4] = [(0, 1), (1, -1), (1, 0), (1, 1)];
/// All 9 rows around a row, itself included.
const ALL_ROWS: [(i64, i64); 9] = [
    (-1, -1),
    (-1, 0),
    (-1, 1),
    (0, -1),
    (0, 0),
    (0, 1),
    (1, -1),
    (1, 0),
    (1, 1),
];

/// Row key of the row `(du, dv)` away from `row` (no carry: coordinates are within ±2^30 of 2^31).
#[inline]
fn row_offset(row: u64, (du, dv): (i64, i64)) -> u64 {
    row.wrapping_add((du * (1i64 << 32) + dv) as u64)
}

/// Start of the sweep window of a body whose min along w is `min_w`, in an array whose widest w extent
/// is `extent`: every body whose box reaches `min_w` starts at or after it. In exact arithmetic that is
/// `min_w − extent`; the extra `(extent + |min_w|) · 2^−20` covers the rounding of these few
/// operations and of the extents themselves (each off by at most 2^−24 relative), so the window never
/// misses a partner. It grows with `min_w`.
#[inline]
fn window_start(min_w: f32, extent: f32) -> f32 {
    min_w - extent - (extent + min_w.abs()) * (1.0 / (1u32 << 20) as f32)
}

impl BroadPhase {
    /// An empty broad phase; buffers grow on first use and are then reused.
    pub fn new() -> Self {
        Self::default()
    }

    /// Row edge chosen by the last [`find_pairs`](Self::find_pairs) call, metres (0 before any call).
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
        self.found.len = 0;
        let n = aabbs.len().min(kinds.len());
        debug_assert_eq!(aabbs.len(), kinds.len());
        let (aabbs, kinds) = (&aabbs[..n], &kinds[..n]);
        if !kinds.contains(&BodyKind::Dynamic) {
            // Nothing awake: no pair may touch.
            return;
        }

        if self.next_cell_size == 0.0 {
            // First call: nothing measured yet.
            self.measure(aabbs, kinds);
        }
        self.cell_size = self.next_cell_size;
        let measures = self.classify(aabbs, kinds);
        let (axis, large_above) = self.judge(&measures);
        self.large_above = large_above;
        let measured_edge = row_edge(measures.widest);
        if axis != self.sweep_axis
            || measures.misfits > MISFITS_ALLOWED + n / 256
            || self.cell_size > EDGE_SLACK * measured_edge
        {
            // The crowd turned, grew or shrank: classify again with a fresh axis and row edge.
            self.sweep_axis = axis;
            self.next_cell_size = row_edge(widest_across(aabbs, axis, large_above));
            self.cell_size = self.next_cell_size;
            self.classify(aabbs, kinds);
        } else {
            self.next_cell_size = measured_edge;
        }
        let staged = &self.staged[..n];
        let place = &self.place[..n];
        let dense = self.dense.as_ref();
        let last_place = &self.last_place[..];
        self.awake.gather(
            staged,
            place,
            last_place,
            Place::Awake,
            dense,
            &mut self.counts,
        );
        self.resting.gather(
            staged,
            place,
            last_place,
            Place::Resting,
            dense,
            &mut self.counts,
        );
        self.last_place.clear();
        self.last_place.extend_from_slice(place);

        sweep_awake(&self.awake, &mut self.found);
        if !self.resting.entries.is_empty() {
            sweep_awake_against_resting(&self.awake, &self.resting, &mut self.found);
        }
        for (k, &l) in self.large.iter().enumerate() {
            let (box_l, kind_l) = (&aabbs[l as usize], kinds[l as usize]);
            let w = self.sweep_axis;
            let probe = Entry {
                min: permute_dyn(box_l.min, w),
                max: permute_dyn(box_l.max, w),
                row: 0,
                id: l,
            };
            // Grid bodies, through the rows that can hold a partner (boxes there are permuted alike,
            // which overlap ignores).
            let inv_cell = 1.0 / self.cell_size;
            let reach = RowReach::of(&probe, inv_cell);
            overlapping_entries(&probe, &reach, &self.awake, &mut self.found);
            if kind_l == BodyKind::Dynamic {
                overlapping_entries(&probe, &reach, &self.resting, &mut self.found);
            }
            // Large–large pairs, from the lower id.
            for &j in &self.large[k + 1..] {
                if kind_l.may_touch(kinds[j as usize]) && box_l.overlaps(&aabbs[j as usize]) {
                    self.found.push((l, j));
                }
            }
        }
        sort_pairs(
            self.found.pairs(),
            n,
            &mut self.counts,
            &mut self.sorted_by_higher,
            pairs,
        );
    }

    /// First call only: measures the bodies in a pass of their own and picks the sweep axis and the
    /// row edge (later calls take them from the last call's [`Measures`]).
    fn measure(&mut self, aabbs: &[Aabb], kinds: &[BodyKind]) {
        let mut m = Measures::new();
        for (aabb, kind) in aabbs.iter().zip(kinds) {
            let (min, max) = (Vec3A::from(aabb.min), Vec3A::from(aabb.max));
            m.add(min, max, *kind);
        }
        let (axis, large_above) = self.judge(&m);
        self.sweep_axis = axis;
        self.large_above = large_above;
        self.next_cell_size = row_edge(widest_across(aabbs, axis, large_above));
    }

    /// The sweep axis (largest spread of the measured centres; the current one unless another spreads
    /// `AXIS_HYSTERESIS` times wider) and the width above which a body is left out of the row edge.
    fn judge(&self, m: &Measures) -> (usize, f32) {
        if m.count == 0 {
            return (self.sweep_axis, f32::INFINITY);
        }
        // Spread = extent of the centres' bounding box (an outlier only costs speed).
        let spread = m.highest - m.lowest;
        let current = self.sweep_axis.min(2);
        let widest = if spread.x >= spread.y && spread.x >= spread.z {
            0
        } else if spread.y >= spread.z {
            1
        } else {
            2
        };
        // Infinite spreads compare as such; `>` keeps the current axis on ties and NaN.
        let axis = if spread[widest] > AXIS_HYSTERESIS * spread[current] {
            widest
        } else {
            current
        };
        let large_above = (f64::from(LARGE_FACTOR) * m.extent_sum / f64::from(m.count)) as f32;
        (axis, large_above)
    }

    /// Sorts every body into the awake or resting array or the large list and stages the grid bodies'
    /// entries.
    /// Measures the bodies on the way (see [`Measures`]).
    fn classify(&mut self, aabbs: &[Aabb], kinds: &[BodyKind]) -> Measures {
        let n = aabbs.len();
        grow_to(&mut self.place, n, Place::Large);
        grow_to(&mut self.staged, n, Entry::default());
        self.large.clear();
        match self.sweep_axis {
            0 => self.classify_along::<0>(aabbs, kinds),
            1 => self.classify_along::<1>(aabbs, kinds),
            _ => self.classify_along::<2>(aabbs, kinds),
        }
    }

    /// [`classify`](Self::classify) for sweep axis `W` (a constant, so the permutation compiles to a
    /// shuffle).
    fn classify_along<const W: usize>(&mut self, aabbs: &[Aabb], kinds: &[BodyKind]) -> Measures {
        let inv_cell = 1.0 / self.cell_size;
        let (mut lo, mut hi) = ((u64::MAX, u64::MAX), (0u64, 0u64));
        let mut grid_bodies = 0usize;
        // Measured in (u, v, w); the centres' box is turned back to world axes at the end.
        let mut m = Measures::new();
        for (i, (aabb, kind)) in aabbs.iter().zip(kinds).enumerate() {
            let (min, max) = (permute::<W>(aabb.min), permute::<W>(aabb.max));
            let across = m.add(min, max, *kind);
            let finite = min.is_finite() && max.is_finite() && (max - min).min_element() >= 0.0;
            if finite && across <= self.large_above {
                m.widest = m.widest.max(across);
            }
            // Rows of (min_u, min_v, max_u, max_v) at once: as `cell_of`, in floats that are exact
            // integers (|x| ≤ 2^30), so differences of 2 or more cannot round down to 1.
            let cells = (Vec4::new(min.x, min.y, max.x, max.y) * inv_cell)
                .clamp(
                    Vec4::splat(-CELL_COORD_LIMIT),
                    Vec4::splat(CELL_COORD_LIMIT),
                )
                .floor();
            // The exact test the sweep relies on: the box ends at most one row after it starts.
            if !(finite && cells.z - cells.x <= 1.0 && cells.w - cells.y <= 1.0) {
                self.place[i] = Place::Large;
                self.large.push(i as u32);
                m.misfits += usize::from(finite && across <= self.large_above);
                continue;
            }
            self.place[i] = if *kind == BodyKind::Dynamic {
                Place::Awake
            } else {
                Place::Resting
            };
            let (row_u, row_v) = (
                (cells.x as i64 + CELL_COORD_BIAS) as u64,
                (cells.y as i64 + CELL_COORD_BIAS) as u64,
            );
            lo = (lo.0.min(row_u), lo.1.min(row_v));
            hi = (hi.0.max(row_u), hi.1.max(row_v));
            grid_bodies += 1;
            self.staged[i] = Entry {
                min,
                max,
                row: row_u << 32 | row_v,
                id: i as u32,
            };
        }
        self.dense = DenseRows::new(lo, hi, grid_bodies);
        m.lowest = unpermute::<W>(m.lowest);
        m.highest = unpermute::<W>(m.highest);
        m
    }
}

impl Measures {
    fn new() -> Measures {
        Measures {
            count: 0,
            extent_sum: 0.0,
            lowest: Vec3A::INFINITY,
            highest: Vec3A::NEG_INFINITY,
            widest: 0.0,
            misfits: 0,
        }
    }

    /// Counts a body with bounds `min`, `max` (in any axis order, kept in `lowest` and `highest`);
    /// returns its extent along the first two axes.
    #[inline]
    fn add(&mut self, min: Vec3A, max: Vec3A, kind: BodyKind) -> f32 {
        let size = max - min;
        let extent = size.max_element();
        if kind != BodyKind::Static && extent.is_finite() && size.min_element() >= 0.0 {
            self.count += 1;
            self.extent_sum += f64::from(extent);
            let centre = 0.5 * (min + max);
            self.lowest = self.lowest.min(centre);
            self.highest = self.highest.max(centre);
        }
        size.x.max(size.y)
    }
}

/// Row edge for a widest grid body of `widest` metres: at least `MIN_CELL_SIZE`; an infinite width
/// (no finite body measured) gives `f32::MAX`, which sends every body to the large list.
fn row_edge(widest: f32) -> f32 {
    let edge = widest.max(MIN_CELL_SIZE);
    if edge.is_finite() { edge } else { f32::MAX }
}

impl SortedRows {
    /// Collects the staged entries of the bodies placed in `group` (both slices of this call's
    /// length), in the last call's order first (new members after), and sorts them by (row, min_w):
    /// by row with a stable counting sort when the rows are `dense`, then by an insertion sort, which
    /// costs O(N) when the bodies kept their order along w within their rows; past a budget of moves
    /// the standard sort takes over.
    fn gather(
        &mut self,
        staged: &[Entry],
        place: &[Place],
        last_place: &[Place],
        group: Place,
        dense: Option<&DenseRows>,
        counts: &mut Vec<u32>,
    ) {
        let n = place.len();
        // `order` holds exactly the bodies placed in `group` last call, each once.
        let is_new = |i: usize| last_place.get(i) != Some(&group);
        self.entries.clear();
        if let Some(dense) = dense {
            counts.clear();
            counts.resize(dense.count + 1, 0);
            let mut members = 0;
            for i in 0..n {
                if place[i] == group {
                    counts[dense.index(staged[i].row) + 1] += 1;
                    members += 1;
                }
            }
            for k in 0..dense.count {
                counts[k + 1] += counts[k];
            }
            // Every entry is written below: `members` bodies, one slot each.
            self.entries.resize(members, Entry::default());
            let mut placed = 0;
            for &id in &self.order {
                let i = id as usize;
                if i < n && place[i] == group {
                    let slot = &mut counts[dense.index(staged[i].row)];
                    self.entries[*slot as usize] = staged[i];
                    *slot += 1;
                    placed += 1;
                }
            }
            if placed < members {
                for i in 0..n {
                    if place[i] == group && is_new(i) {
                        let slot = &mut counts[dense.index(staged[i].row)];
                        self.entries[*slot as usize] = staged[i];
                        *slot += 1;
                    }
                }
            }
        } else {
            for &id in &self.order {
                let i = id as usize;
                if i < n && place[i] == group {
                    self.entries.push(staged[i]);
                }
            }
            for i in 0..n {
                if place[i] == group && is_new(i) {
                    self.entries.push(staged[i]);
                }
            }
        }
        self.order.clear();
        let mut max_extent_w = 0.0f32;
        for e in &self.entries {
            max_extent_w = max_extent_w.max(e.max.z - e.min.z);
        }
        self.max_extent_w = max_extent_w;
        let budget = 8 * self.entries.len() + 64;
        if !insertion_sort(&mut self.entries, budget) {
            self.entries
                .sort_unstable_by(|a, b| a.row.cmp(&b.row).then(a.min.z.total_cmp(&b.min.z)));
        }
        self.order.extend(self.entries.iter().map(|e| e.id));
        self.rows.clear();
        for (k, e) in self.entries.iter().enumerate() {
            match self.rows.last_mut() {
                Some(row) if row.key == e.row => row.end = k as u32 + 1,
                _ => self.rows.push(Row {
                    key: e.row,
                    start: k as u32,
                    end: k as u32 + 1,
                }),
            }
        }
    }
}

/// Sorts by [`Entry::precedes`], giving up (returning false, the slice partly sorted) after `budget`
/// moves.
fn insertion_sort(entries: &mut [Entry], budget: usize) -> bool {
    let mut moves = 0usize;
    for i in 1..entries.len() {
        if !entries[i].precedes(&entries[i - 1]) {
            continue;
        }
        let x = entries[i];
        let mut j = i;
        while j > 0 && x.precedes(&entries[j - 1]) {
            entries[j] = entries[j - 1];
            j -= 1;
        }
        entries[j] = x;
        moves += i - j;
        if moves > budget {
            return false;
        }
    }
    true
}

/// Awake–awake pairs: each row meets itself (each body the bodies after it) and the four forward rows.
fn sweep_awake(array: &SortedRows, found: &mut PairSink) {
    let (rows, entries) = (&array.rows[..], &array.entries[..]);
    let mut cursors = [0usize; FORWARD_ROWS.len()];
    for row in rows {
        let own = &entries[row.start as usize..row.end as usize];
        for (p, a) in own.iter().enumerate() {
            found.scan(a, &own[p + 1..]);
        }
        for (cursor, &offset) in cursors.iter_mut().zip(&FORWARD_ROWS) {
            if let Some(other) = find_row(rows, cursor, row_offset(row.key, offset)) {
                sweep_rows(own, &entries[other], array.max_extent_w, found);
            }
        }
    }
}

/// Awake–resting pairs: each awake row meets the 9 rows around it in the resting array.
fn sweep_awake_against_resting(awake: &SortedRows, resting: &SortedRows, found: &mut PairSink) {
    let mut cursors = [0usize; ALL_ROWS.len()];
    for row in &awake.rows {
        let own = &awake.entries[row.start as usize..row.end as usize];
        for (cursor, &offset) in cursors.iter_mut().zip(&ALL_ROWS) {
            if let Some(other) = find_row(&resting.rows, cursor, row_offset(row.key, offset)) {
                sweep_rows(own, &resting.entries[other], resting.max_extent_w, found);
            }
        }
    }
}

/// The entry range of the row with `key`, if occupied, searching from `cursor`, which only moves
/// forward: the keys looked up through one cursor grow.
#[inline]
fn find_row(rows: &[Row], cursor: &mut usize, key: u64) -> Option<std::ops::Range<usize>> {
    while *cursor < rows.len() && rows[*cursor].key < key {
        *cursor += 1;
    }
    let row = rows.get(*cursor)?;
    (row.key == key).then_some(row.start as usize..row.end as usize)
}

/// Every overlapping pair of a body of row `own` and one of the different row `other` (both sorted by
/// min_w, `extent` the widest w extent in `other`'s array): a merge-like sweep whose window start only
/// moves forward.
#[inline]
fn sweep_rows(own: &[Entry], other: &[Entry], extent: f32, found: &mut PairSink) {
    let mut q = 0;
    for a in own {
        let start_w = window_start(a.min.z, extent);
        while q < other.len() && other[q].min.z < start_w {
            q += 1;
        }
        found.scan(a, &other[q..]);
    }
}

/// Largest extent across the sweep axis `W` (along u or v) of the boxes no wider than `large_above`
/// with non-negative sizes, metres (0 if none).
fn widest_across(aabbs: &[Aabb], w: usize, large_above: f32) -> f32 {
    match w {
        0 => widest_across_along::<0>(aabbs, large_above),
        1 => widest_across_along::<1>(aabbs, large_above),
        _ => widest_across_along::<2>(aabbs, large_above),
    }
}

/// [`widest_across`] for sweep axis `W`.
fn widest_across_along<const W: usize>(aabbs: &[Aabb], large_above: f32) -> f32 {
    let mut widest = 0.0f32;
    for aabb in aabbs {
        let size = permute::<W>(aabb.max) - permute::<W>(aabb.min);
        let across = size.x.max(size.y);
        // `across <= large_above` is false for NaN.
        if across <= large_above && size.min_element() >= 0.0 && across > widest {
            widest = across;
        }
    }
    widest
}

/// The rows that can hold a grid body overlapping a large body's box: biased row coordinates
/// `u.0..=u.1` by `v.0..=v.1`. A grid body b overlaps box L only if b.min_u ≤ L.max_u, so its row
/// ⌊b.min_u / c⌋ ≤ ⌊L.max_u / c⌋, and L.min_u ≤ b.max_u, so ⌊L.min_u / c⌋ ≤ ⌊b.max_u / c⌋ ≤ its row + 1
/// (floor is monotonic; grid bodies end at most one row after they start); likewise along v. This
/// needs nothing of L, not even min ≤ max; a NaN bound gives some range, and a NaN box overlaps
/// nothing anyway.
struct RowReach {
    u: (u64, u64),
    v: (u64, u64),
}

impl RowReach {
    fn of(probe: &Entry, inv_cell: f32) -> RowReach {
        let biased = |x: f32| (i64::from(cell_of(x, inv_cell)) + CELL_COORD_BIAS) as u64;
        RowReach {
            u: (biased(probe.min.x) - 1, biased(probe.max.x)),
            v: (biased(probe.min.y) - 1, biased(probe.max.y)),
        }
    }

    #[inline]
    fn holds(&self, key: u64) -> bool {
        let (u, v) = (key >> 32, key & 0xffff_ffff);
        self.u.0 <= u && u <= self.u.1 && self.v.0 <= v && v <= self.v.1
    }
}

/// Reports `probe` (a large body) with every entry of `array` whose box overlaps it: in each row of
/// `reach`, from the first entry whose box can reach the probe along w (a binary search) while the
/// entries start before the probe ends. O(rows + log + partners in range).
fn overlapping_entries(probe: &Entry, reach: &RowReach, array: &SortedRows, found: &mut PairSink) {
    let start_w = window_start(probe.min.z, array.max_extent_w);
    for row in array.rows.iter().filter(|row| reach.holds(row.key)) {
        let entries = &array.entries[row.start as usize..row.end as usize];
        // A NaN start finds 0: the whole row is scanned.
        let first = entries.partition_point(|e| e.min.z < start_w);
        for e in &entries[first..] {
            if e.min.z > probe.max.z {
                break;
            }
            // A branch here: a large body overlaps runs of neighbouring entries, which predicts well.
            if probe.overlaps(e) {
                found.push((probe.id.min(e.id), probe.id.max(e.id)));
            }
        }
    }
}

/// The pairs found so far, `buffer[..len]`, appended without a branch on whether a pair is kept (the
/// overlap tests are unpredictable, so a branch would be mispredicted often).
#[derive(Clone, Debug, Default)]
struct PairSink {
    /// Found pairs, then scratch (it only grows).
    buffer: Vec<(u32, u32)>,
    /// Pairs found.
    len: usize,
}

impl PairSink {
    /// Ensures room for `more` pairs after the found ones.
    #[inline]
    fn make_room(&mut self, more: usize) {
        if self.buffer.len() < self.len + more {
            let wanted = (self.len + more).max(2 * self.buffer.len()).max(64);
            self.buffer.resize(wanted, (0, 0));
        }
    }

    /// Appends a's pair with every entry of `window` (sorted by min_w) that overlaps it, up to the first
    /// entry that starts after a ends. Each pair is written anyway and overwritten by the next one if
    /// not kept; the count lives in a register meanwhile.
    #[inline]
    fn scan(&mut self, a: &Entry, window: &[Entry]) {
        self.make_room(window.len());
        let mut len = self.len;
        let buffer = &mut self.buffer[..];
        for b in window {
            if b.min.z > a.max.z {
                break;
            }
            buffer[len] = (a.id.min(b.id), a.id.max(b.id));
            len += usize::from(a.overlaps(b));
        }
        self.len = len;
    }

    /// Appends `pair`.
    fn push(&mut self, pair: (u32, u32)) {
        self.make_room(1);
        self.buffer[self.len] = pair;
        self.len += 1;
    }

    /// The pairs found.
    fn pairs(&self) -> &[(u32, u32)] {
        &self.buffer[..self.len]
    }
}

/// Writes `found` into `pairs` sorted: two stable counting sorts (least significant key first), by
/// higher id into `scratch`, then by lower id into `pairs`: O(pairs + n), where a comparison sort is
/// O(pairs · log pairs).
fn sort_pairs(
    found: &[(u32, u32)],
    n: usize,
    counts: &mut Vec<u32>,
    scratch: &mut Vec<(u32, u32)>,
    pairs: &mut Vec<(u32, u32)>,
) {
    scratch.clear();
    scratch.resize(found.len(), (0, 0));
    counting_sort(found, n, counts, scratch, |pair| pair.1);
    pairs.clear();
    pairs.resize(found.len(), (0, 0));
    counting_sort(scratch, n, counts, pairs, |pair| pair.0);
}

/// Stable counting sort of `input` into `output` (same length) by `key(pair) < n`.
fn counting_sort(
    input: &[(u32, u32)],
    n: usize,
    counts: &mut Vec<u32>,
    output: &mut [(u32, u32)],
    key: impl Fn(&(u32, u32)) -> u32,
) {
    counts.clear();
    counts.resize(n + 1, 0);
    for pair in input {
        counts[key(pair) as usize + 1] += 1;
    }
    for i in 0..n {
        counts[i + 1] += counts[i];
    }
    for pair in input {
        let slot = &mut counts[key(pair) as usize];
        output[*slot as usize] = *pair;
        *slot += 1;
    }
}

/// Makes `v` at least `len` long (new entries = `fill`), never shorter: scratch whose stale tail is
/// never read.
fn grow_to<T: Clone>(v: &mut Vec<T>, len: usize, fill: T) {
    if v.len() < len {
        v.resize(len, fill);
    }
}

/// `p` as (u, v, w) for sweep axis `W`: a rotation of (x, y, z), so u = W + 1 and v = W + 2 (mod 3).
#[inline(always)]
fn permute<const W: usize>(p: Vec3) -> Vec3A {
    match W {
        0 => Vec3A::new(p.y, p.z, p.x),
        1 => Vec3A::new(p.z, p.x, p.y),
        _ => Vec3A::new(p.x, p.y, p.z),
    }
}

/// The inverse of [`permute`]: (u, v, w) back to (x, y, z).
#[inline(always)]
fn unpermute<const W: usize>(p: Vec3A) -> Vec3A {
    match W {
        0 => Vec3A::new(p.z, p.x, p.y),
        1 => Vec3A::new(p.y, p.z, p.x),
        _ => p,
    }
}

/// [`permute`] for a sweep axis known only at run time.
fn permute_dyn(p: Vec3, w: usize) -> Vec3A {
    match w {
        0 => permute::<0>(p),
        1 => permute::<1>(p),
        _ => permute::<2>(p),
    }
}

/// Integer row coordinate of `x` (clamped to ±2^30 rows).
#[inline]
fn cell_of(x: f32, inv_cell: f32) -> i32 {
    floor_i32((x * inv_cell).clamp(-CELL_COORD_LIMIT, CELL_COORD_LIMIT))
}

/// ⌊x⌋ for |x| ≤ 2^30 without a libm call (the baseline x86-64 target has no SSE4.1 `roundss`).
/// NaN gives 0 (callers have checked finiteness).
#[inline]
fn floor_i32(x: f32) -> i32 {
    let t = x as i32;
    if (t as f32) > x { t - 1 } else { t }
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
