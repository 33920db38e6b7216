//! Ordered dithering that stays still: each colour becomes a fixed 2×2 pattern of palette colours
//! whose blend, in linear light, looks like it; the pattern is anchored to pixel positions.
//!
//! **Plans.** For a colour `c` we choose four palette entries (a multiset, so one to four distinct
//! colours) minimising
//!
//! ```text
//! cost(c, blend) + SPREAD_WEIGHT · mean over the four of cost(c, entry)
//! ```
//!
//! where `blend` is the four entries averaged in linear light (what the eye sees from a normal
//! distance) and `cost` is the palette's perceptual cost (OKLab distance, losing chroma charged
//! extra: see [`palette`](super::palette)). The first term asks for the right colour on average; the
//! second keeps the four near the colour itself, so textures and shadows do not turn into speckle.
//!
//! Two rules then decide between that plan and the nearest entry shown flat (issue 28):
//! - **Hue.** Where the nearest entry turns a coloured target's hue by more than
//!   [`HUE_TOLERANCE`] (or greys it), the best plan whose blend keeps the hue wins, if any: at 16
//!   colours the default scene's orange box was the flat red of its ball; now red dotted with yellow
//!   (blending to orange).
//! - **Flat unless markedly nearer.** Otherwise a pattern is used only when its blend is at most
//!   [`MARKEDLY`] times the nearest entry's OKLab distance from the colour: a pattern is a texture
//!   the picture lacks. The default scene's sky at 16 colours was black dotted with grey (0.13 from
//!   it, against 0.24 for black alone); it is flat black. That costs mean error: the default scene's
//!   at 16 colours went from 13.5 to 20.0 (the target in `tests/term/colour.rs` is 20), most of it
//!   the sky's; on coloured blocks from 18.2 to 20.6, the price of no block shown grey (2 % were).
//!
//! The search runs over the multisets of the
//! [`CANDIDATES`] cheapest single entries (Yliluoma's "positional" dithering with Knoll's ordering;
//! chafa and libcaca do much the same). A colour that an entry already shows within
//! [`SNAP_DISTANCE`] is shown flat.
//!
//! **Placement.** The plan's four entries, darkest first, go to the pixels of each 2×2 block in the
//! order of [`RANK`] (a 2×2 Bayer matrix: the darkest two on a diagonal). Which entry a pixel gets
//! depends only on its colour and its position in the image, so a still picture gives the same cells
//! every frame (ratatui's diff writes nothing) and a moving body changes only the cells it crosses.
//! A 2×2 block shows exactly the plan's blend, which is also how the eye (and the colour-error
//! measure in [`fidelity`](super::fidelity)) sees it.
//!
//! **Cost per pixel.** Plans are memoised per colour bucket (64 buckets a channel, even steps of the
//! cube root of linear light, so finest near black; the colour planned for is the middle of its
//! bucket, so the result never depends on which colour came first), in a table per thread, depth and
//! dither mode: a table lookup per pixel once warm. A plan costs a few microseconds to find; a
//! textured 200 × 50 frame needs a few thousand the first time.
//!
//! **What it costs.** At 256 colours the objects keep their hue but come out too saturated: the
//! cube's entries nearest a muted colour are nearly all more saturated than it, and since losing
//! chroma is charged extra no grey gets into a pattern to tone them down. Letting one in (a smaller
//! charge for a pattern's entries) brought the objects nearer on average but turned dark oranges
//! towards red, past the 15° of hue `tests/term/colour.rs` allows, so it is not done. At 16 colours
//! the dot patterns left are visible, as with any 16-colour dithering; they buy the hue.
//! `nudge bench render` prints the fidelity (see [`fidelity`](super::fidelity)) and the speckle of
//! every built-in scene at each depth, dithered and not.

use std::cell::RefCell;
use std::fmt;
use std::sync::LazyLock;

use ratatui::style::Color;

use super::color_depth::ColorDepth;
use super::palette::{Palette, Target, palette};
use crate::color::Rgb;
use crate::color::oklab::{Oklab, linear_to_oklab, to_linear};

/// How colours a palette lacks are shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dither {
    /// The single nearest palette colour (perceptually; see [`palette`](super::palette)).
    None,
    /// A fixed 2×2 pattern of palette colours blending to the colour (see the module docs).
    #[default]
    Ordered,
}

impl Dither {
    /// Both modes, the default first.
    pub const ALL: [Dither; 2] = [Dither::Ordered, Dither::None];

    /// The command-line spelling.
    pub const fn name(self) -> &'static str {
        match self {
            Dither::None => "none",
            Dither::Ordered => "ordered",
        }
    }
}

impl fmt::Display for Dither {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Rank (0 = darkest) of the plan entry each pixel of a 2×2 block shows, by `[y % 2][x % 2]`.
pub const RANK: [[usize; 2]; 2] = [[0, 2], [3, 1]];

/// Single entries the plan search combines: the cheapest this many (8 gives 330 multisets of four).
pub const CANDIDATES: usize = 8;

/// Weight of the four entries' own cost against the blend's (see the module docs). At 0.25 the
/// 256-colour background of every scene became a two-grey checkerboard (five times the bytes) for a
/// gain the eye cannot see; from 1 up the picture hardly changes.
pub const SPREAD_WEIGHT: f32 = 1.0;

/// When the nearest entry's perceptual cost is within this distance squared (OKLab, about one
/// just-noticeable difference), the colour is shown flat, undithered.
pub const SNAP_DISTANCE: f32 = 0.012;

/// A pattern that is not needed to keep a hue is used only where its blend is at most this fraction
/// of the nearest entry's OKLab distance from the colour. The default scene's dark blue-grey sky is
/// 0.24 from black and 0.13 from black dotted with grey (a ratio of 0.55): it is shown flat black.
pub const MARKEDLY: f32 = 0.5;

/// Chroma (OKLab) from which a colour's hue is kept by a pattern where the nearest entry turns it.
pub const HUE_KEPT_CHROMA: f32 = 0.04;

/// Degrees of hue a colour may turn before that counts as a different hue: the nearest entry turning
/// it further makes a pattern whose blend stays within this the plan, if there is one.
pub const HUE_TOLERANCE: f32 = 20.0;

/// Four palette positions, darkest first.
type Plan = [u8; 4];

/// The plan for `c` (see the module docs); with [`Dither::None`], the nearest entry four times.
pub fn plan(palette: &Palette, c: Rgb, dither: Dither) -> Plan {
    let linear = to_linear(c);
    let target = Target::new(linear_to_oklab(linear));
    if dither == Dither::None {
        let n = palette.nearest(&target) as u8;
        return [n; 4];
    }

    // The cheapest CANDIDATES entries, cheapest first (insertion into a short sorted list).
    let mut best: Vec<(f32, usize)> = Vec::with_capacity(CANDIDATES + 1);
    for (i, e) in palette.entries.iter().enumerate() {
        let cost = target.cost_with_chroma(e.lab, e.chroma);
        if best.len() < CANDIDATES || cost < best[best.len() - 1].0 {
            let at = best.partition_point(|&(c, _)| c <= cost);
            best.insert(at, (cost, i));
            best.truncate(CANDIDATES);
        }
    }
    let (nearest_cost, nearest) = best[0];
    if nearest_cost <= SNAP_DISTANCE * SNAP_DISTANCE {
        return [nearest as u8; 4];
    }

    // Whether the nearest entry turns a coloured target's hue (or greys it), so that a pattern
    // which keeps the hue is wanted even where it is not markedly nearer.
    let entry = &palette.entries[nearest];
    let hue_at_stake = target.chroma >= HUE_KEPT_CHROMA
        && (entry.chroma < HUE_KEPT_CHROMA / 2.0
            || hue_turn(target.lab, entry.lab) > HUE_TOLERANCE);

    let flat = ([nearest; 4], nearest_cost * (1.0 + SPREAD_WEIGHT));
    // The best plan overall, and the best whose blend keeps the hue (when the hue is at stake).
    let (mut winner, mut hue_winner) = (flat, ([nearest; 4], f32::INFINITY));
    let n = best.len();
    for i in 0..n {
        for j in i..n {
            for k in j..n {
                for l in k..n {
                    // Each candidate's cost is its spread term: computed once, above.
                    let chosen = [best[i], best[j], best[k], best[l]];
                    let spread = chosen.iter().map(|p| p.0).sum::<f32>() * 0.25;
                    let picks = chosen.map(|p| p.1);
                    let bound = if hue_at_stake {
                        winner.1.max(hue_winner.1)
                    } else {
                        winner.1
                    };
                    if SPREAD_WEIGHT * spread >= bound {
                        continue;
                    }
                    let blend = blend_of(palette, picks);
                    let total = target.cost(blend) + SPREAD_WEIGHT * spread;
                    if total < winner.1 {
                        winner = (picks, total);
                    }
                    if hue_at_stake
                        && total < hue_winner.1
                        && hue_turn(target.lab, blend) <= HUE_TOLERANCE
                    {
                        hue_winner = (picks, total);
                    }
                }
            }
        }
    }

    let mut positions = if hue_at_stake && hue_winner.1.is_finite() {
        hue_winner.0
    } else if winner.0 != flat.0 {
        // A pattern shows as a texture the truecolor picture lacks: worth it only when its blend is
        // markedly nearer than the nearest entry alone.
        let blend = blend_of(palette, winner.0).distance(target.lab);
        if blend <= MARKEDLY * entry.lab.distance(target.lab) {
            winner.0
        } else {
            flat.0
        }
    } else {
        flat.0
    };
    positions.sort_by(|&a, &b| {
        let (la, lb) = (palette.entries[a].lab.l, palette.entries[b].lab.l);
        la.total_cmp(&lb).then(a.cmp(&b))
    });
    positions.map(|p| p as u8)
}

/// What four entries blend to, in linear light, as OKLab.
fn blend_of(palette: &Palette, picks: [usize; 4]) -> Oklab {
    let mut sum = [0.0f32; 3];
    for p in picks {
        for (s, v) in sum.iter_mut().zip(palette.entries[p].linear) {
            *s += v;
        }
    }
    linear_to_oklab(sum.map(|v| v * 0.25))
}

/// The angle in degrees (0 to 180) between the OKLab hues of `a` and `b`.
fn hue_turn(a: Oklab, b: Oklab) -> f32 {
    let d = (b.b.atan2(b.a) - a.b.atan2(a.a))
        .to_degrees()
        .rem_euclid(360.0);
    d.min(360.0 - d)
}

/// Buckets per channel in the memo key.
const BUCKETS: usize = 64;
/// Entries in a memo table: one per bucket triple.
const TABLE_LEN: usize = BUCKETS * BUCKETS * BUCKETS;
/// Marks a table slot not yet planned (no palette has 255 entries, so no plan packs to this).
const UNPLANNED: u32 = u32::MAX;

/// Channel value → bucket, and bucket → the channel value planned for every value in it. Buckets are
/// even steps of the cube root of linear light (as OKLab's lightness is), so they are as fine near
/// black, where the eye is most sensitive, as elsewhere: each spans a few values mid-range and one
/// near black. The value planned for is the middle of its bucket, so a plan never depends on which
/// colour of a bucket came first.
struct Buckets {
    of_value: [u8; 256],
    middle: [u8; BUCKETS],
}

static CHANNEL_BUCKETS: LazyLock<Buckets> = LazyLock::new(|| {
    let mut of_value = [0u8; 256];
    let (mut lowest, mut highest) = ([u8::MAX; BUCKETS], [0u8; BUCKETS]);
    for v in 0..=255u8 {
        let lightness = to_linear(Rgb::new(v, v, v))[0].cbrt();
        let bucket = ((lightness * (BUCKETS - 1) as f32).round() as usize).min(BUCKETS - 1);
        of_value[usize::from(v)] = bucket as u8;
        lowest[bucket] = lowest[bucket].min(v);
        highest[bucket] = highest[bucket].max(v);
    }
    let mut middle = [0u8; BUCKETS];
    for b in 0..BUCKETS {
        if lowest[b] <= highest[b] {
            middle[b] = ((u16::from(lowest[b]) + u16::from(highest[b])) / 2) as u8;
        }
    }
    Buckets { of_value, middle }
});

/// The memo key of `c`.
#[inline]
fn key(c: Rgb) -> usize {
    let b = &CHANNEL_BUCKETS.of_value;
    (usize::from(b[usize::from(c.r)]) * BUCKETS + usize::from(b[usize::from(c.g)])) * BUCKETS
        + usize::from(b[usize::from(c.b)])
}

/// The colour planned for every colour with `c`'s key.
#[inline]
fn representative(c: Rgb) -> Rgb {
    let buckets = &*CHANNEL_BUCKETS;
    let mid = |v: u8| buckets.middle[usize::from(buckets.of_value[usize::from(v)])];
    Rgb::new(mid(c.r), mid(c.g), mid(c.b))
}

/// Memoised plans of one palette and dither mode.
struct PlanTable {
    palette: &'static Palette,
    dither: Dither,
    packed: Vec<u32>,
}

impl PlanTable {
    fn new(palette: &'static Palette, dither: Dither) -> Self {
        Self {
            palette,
            dither,
            packed: vec![UNPLANNED; TABLE_LEN],
        }
    }

    #[inline]
    fn plan(&mut self, c: Rgb) -> Plan {
        let slot = &mut self.packed[key(c)];
        if *slot == UNPLANNED {
            *slot = u32::from_le_bytes(plan(self.palette, representative(c), self.dither));
        }
        slot.to_le_bytes()
    }
}

thread_local! {
    /// Plan tables by [256 ordered, 256 none, 16 ordered, 16 none], allocated on first use.
    static TABLES: RefCell<[Option<PlanTable>; 4]> = const { RefCell::new([None, None, None, None]) };
}

/// Maps pixels to terminal colours at one depth and dither mode. Get one with [`with_quantizer`].
pub struct Quantizer<'t> {
    table: Option<&'t mut PlanTable>,
    /// The last colour planned and its plan as terminal colours, for even and odd rows (a
    /// half-block row alternates them, and flat images repeat colours along a row).
    memo: [Option<(Rgb, [Color; 4])>; 2],
}

impl Quantizer<'_> {
    /// The terminal colour for pixel (x, y) (image coordinates) of colour `c`.
    #[inline]
    pub fn color(&mut self, x: u32, y: u32, c: Rgb) -> Color {
        let rank = RANK[(y & 1) as usize][(x & 1) as usize];
        self.memoised_plan((y & 1) as usize, c)[rank]
    }

    /// The four terminal colours `c` is shown with, darkest first (all equal when undithered).
    pub fn plan(&mut self, c: Rgb) -> [Color; 4] {
        self.memoised_plan(0, c)
    }

    #[inline]
    fn memoised_plan(&mut self, memo: usize, c: Rgb) -> [Color; 4] {
        let Some(table) = self.table.as_deref_mut() else {
            return [Color::Rgb(c.r, c.g, c.b); 4];
        };
        match self.memo[memo] {
            Some((last, colors)) if last == c => colors,
            _ => {
                let entries = &table.palette.entries;
                let colors = table.plan(c).map(|p| entries[usize::from(p)].color);
                self.memo[memo] = Some((c, colors));
                colors
            }
        }
    }
}

/// Runs `f` with a quantizer for `depth` and `dither` (truecolor passes colours through, never
/// dithered). Not re-entrant: `f` must not call `with_quantizer` itself.
pub fn with_quantizer<R>(
    depth: ColorDepth,
    dither: Dither,
    f: impl FnOnce(&mut Quantizer<'_>) -> R,
) -> R {
    let Some(palette) = palette(depth) else {
        return f(&mut Quantizer {
            table: None,
            memo: [None; 2],
        });
    };
    let slot = match (depth, dither) {
        (ColorDepth::Ansi256, Dither::Ordered) => 0,
        (ColorDepth::Ansi256, Dither::None) => 1,
        (_, Dither::Ordered) => 2,
        (_, Dither::None) => 3,
    };
    TABLES.with(|tables| {
        let mut tables = tables.borrow_mut();
        let table = tables[slot].get_or_insert_with(|| PlanTable::new(palette, dither));
        f(&mut Quantizer {
            table: Some(table),
            memo: [None; 2],
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::oklab::{from_linear, to_oklab};

    fn blend_of(depth: ColorDepth, c: Rgb) -> (Vec<Rgb>, Rgb) {
        let p = palette(depth).unwrap();
        let plan = plan(p, c, Dither::Ordered);
        let rgbs: Vec<Rgb> = plan
            .iter()
            .map(|&i| p.entries[usize::from(i)].rgb)
            .collect();
        let mut sum = [0.0f32; 3];
        for &i in &plan {
            for (s, v) in sum.iter_mut().zip(p.entries[usize::from(i)].linear) {
                *s += v * 0.25;
            }
        }
        (rgbs, from_linear(sum))
    }

    #[test]
    fn palette_colours_are_shown_flat() {
        for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            let p = palette(depth).unwrap();
            for (i, e) in p.entries.iter().enumerate() {
                assert_eq!(plan(p, e.rgb, Dither::Ordered), [i as u8; 4], "{:?}", e.rgb);
            }
        }
    }

    #[test]
    fn palette_colours_are_shown_flat_through_the_memo_buckets() {
        // Flat, by themselves or (where a bucket holds two palette values, as 95 and 98 share one)
        // by an entry within a just-noticeable difference.
        for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            let p = palette(depth).unwrap();
            with_quantizer(depth, Dither::Ordered, |q| {
                for e in &p.entries {
                    let plan = q.plan(e.rgb);
                    assert!(plan.iter().all(|&c| c == plan[0]), "{:?}: {plan:?}", e.rgb);
                    let shown = p.entries.iter().find(|s| s.color == plan[0]).unwrap();
                    assert!(e.lab.distance(shown.lab) <= SNAP_DISTANCE, "{:?}", e.rgb);
                }
            });
        }
    }

    #[test]
    fn buckets_are_finest_near_black() {
        let b = &CHANNEL_BUCKETS.of_value;
        assert_ne!(b[0], b[1]);
        assert_ne!(b[1], b[2]);
        let mid_span = (0..=255usize).filter(|&v| b[v] == b[128]).count();
        assert!((2..=6).contains(&mid_span), "{mid_span}");
    }

    #[test]
    fn a_plan_is_sorted_darkest_first() {
        let p = palette(ColorDepth::Ansi16).unwrap();
        let plan = plan(p, Rgb::new(40, 90, 40), Dither::Ordered);
        for w in plan.windows(2) {
            let (a, b) = (&p.entries[usize::from(w[0])], &p.entries[usize::from(w[1])]);
            assert!(a.lab.l <= b.lab.l, "{plan:?}");
        }
    }

    #[test]
    fn a_flat_dark_sky_stays_flat_at_16_colours() {
        // The default scene's sky: 0.24 (OKLab) from black, 0.13 from black dotted with grey.
        let p = palette(ColorDepth::Ansi16).unwrap();
        let sky = plan(p, Rgb::new(28, 32, 40), Dither::Ordered);
        assert!(sky.iter().all(|&e| e == sky[0]), "{sky:?}");
    }

    #[test]
    fn a_dark_green_keeps_its_hue_at_16_colours() {
        let c = Rgb::new(30, 80, 30);
        let (entries, blend) = blend_of(ColorDepth::Ansi16, c);
        assert!(entries.iter().any(|e| e.g > e.r), "{entries:?}");
        assert!(
            to_oklab(blend).chroma() > 0.05,
            "{blend:?} from {entries:?}"
        );
    }

    #[test]
    fn a_dithered_blend_costs_less_than_the_nearest_entry() {
        // The shaded faces of the default scene's orange box. (Its green ball's, #305828, is shown
        // flat at 16 colours: the nearest green keeps its hue and no pattern is markedly nearer.)
        for (depth, c) in [
            (ColorDepth::Ansi256, Rgb::new(0x60, 0x40, 0x20)),
            (ColorDepth::Ansi16, Rgb::new(0x60, 0x40, 0x20)),
            (ColorDepth::Ansi16, Rgb::new(0x8b, 0x5a, 0x2c)),
        ] {
            let p = palette(depth).unwrap();
            let target = Target::new(to_oklab(c));
            let nearest = p.entries[p.nearest(&target)].lab;
            let (entries, blend) = blend_of(depth, c);
            assert!(
                entries.iter().any(|&e| e != entries[0]),
                "{c:?} not dithered"
            );
            assert!(target.cost(to_oklab(blend)) < target.cost(nearest), "{c:?}");
        }
    }

    #[test]
    fn the_quantizer_places_the_plan_by_the_bayer_ranks() {
        let c = Rgb::new(0x30, 0x50, 0x28);
        with_quantizer(ColorDepth::Ansi256, Dither::Ordered, |q| {
            let plan = q.plan(c);
            for (y, row) in RANK.iter().enumerate() {
                for (x, &rank) in row.iter().enumerate() {
                    assert_eq!(q.color(x as u32 + 4, y as u32 + 6, c), plan[rank]);
                }
            }
        });
    }

    #[test]
    fn truecolor_is_never_dithered() {
        let c = Rgb::new(1, 2, 3);
        with_quantizer(ColorDepth::TrueColor, Dither::Ordered, |q| {
            assert_eq!(q.plan(c), [Color::Rgb(1, 2, 3); 4]);
        });
    }

    #[test]
    fn every_colour_in_a_bucket_gets_the_same_plan() {
        let a = Rgb::new(0x80, 0x81, 0x22);
        let b = Rgb::new(0x81, 0x80, 0x22);
        assert_eq!(key(a), key(b));
        with_quantizer(ColorDepth::Ansi16, Dither::Ordered, |q| {
            assert_eq!(q.plan(a), q.plan(b));
        });
        assert_eq!(representative(Rgb::BLACK), Rgb::BLACK);
        let near_white = representative(Rgb::WHITE);
        assert_eq!(key(near_white), key(Rgb::WHITE));
    }
}
