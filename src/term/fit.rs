//! The two-colour fit of a mosaic cell: which of its pixels show the foreground, and the two colours.
//!
//! A mosaic glyph shows each of the cell's `n` pixels (2 to 8) in one of two colours. The best glyph
//! for a cell is the split of its pixels into two groups, each shown as one colour, that least
//! misrepresents them. Error is squared OKLab distance, so for a given split each group's best colour
//! is its OKLab mean and the split's error is
//!
//! ```text
//! Σ|p|² − |S_A|²/n_A − |S_B|²/n_B        (S: a group's sum, n: its size)
//! ```
//!
//! The first term is the same for every split: the best split maximises `|S_A|²/n_A + |S_B|²/n_B`
//! (2-means with k = 2; the same objective as Otsu's threshold, in three dimensions).
//!
//! Two ways to find it ([`FitMethod`]):
//!
//! - **Exhaustive**: every split, `2^(n−1)` of them (a split and its complement are one), walked in
//!   Gray-code order so that each step moves one pixel between groups and updates `S_A` with one
//!   vector add. For an octant cell that is 128 splits at a few multiply-adds each: exact.
//! - **Axis**: the cell's dominant axis in colour space (the principal axis of its pixels'
//!   covariance, by power iteration from the pixel farthest from the mean), the pixels sorted along
//!   it, and the best of the `n − 1` thresholds (scored with the same objective, by prefix sums).
//!   What chafa-style fitters do for large cells; it can miss the optimum when the colours do not
//!   lie on a line (three colours in a cell).
//!
//! `nudge bench cells` measures both against the 4×8 reference: on the default and pyramid scenes
//! at 120×40 and 200×50 their errors agree to three decimals in every mode (the cells that matter
//! hold two or three colour clusters, which lie on a line). The exhaustive search is faster for
//! quadrants and sextants (8 and 32 splits); for octants (128 splits) the axis is about a quarter
//! faster, so octants use it ([`FitMethod::for_mode`]).
//!
//! A cell of at most two colours (an edge between flat areas) skips the search: its split is by
//! colour, and exact.
//!
//! A group's colour is the exact pixel colour when all its pixels share one (the common case: flat
//! faces, background), so a uniform region comes out bit-exact; otherwise its OKLab geometric
//! median (see `group_colour`: the split is scored by the means' closed form, the colours shown
//! minimise the summed distance a viewer sees), after which a pixel nearer the other colour joins it.

use super::cells::CellMode;
use crate::color::Rgb;
use crate::color::oklab::{Oklab, from_oklab};

/// The most pixels a cell holds (octant: 2×4).
pub const MAX_PIXELS: usize = 8;

/// How the split is searched (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FitMethod {
    /// Every split: exact.
    Exhaustive,
    /// Threshold along the dominant colour axis: a principled shortcut.
    Axis,
}

impl FitMethod {
    /// Both.
    pub const ALL: [FitMethod; 2] = [FitMethod::Exhaustive, FitMethod::Axis];

    /// The one the widgets use for `mode` (see the module docs for the measurements).
    pub const fn for_mode(mode: CellMode) -> FitMethod {
        match mode {
            CellMode::Half | CellMode::Quadrant | CellMode::Sextant => FitMethod::Exhaustive,
            CellMode::Octant => FitMethod::Axis,
        }
    }

    pub const fn name(self) -> &'static str {
        match self {
            FitMethod::Exhaustive => "exhaustive",
            FitMethod::Axis => "axis",
        }
    }
}

/// A fitted cell: `pattern` has bit i set where pixel i shows `fg`; the others show `bg`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fit {
    /// Bit i (pixel i, row-major) shows `fg`. 0 for a cell of one colour; otherwise bit 0 is set
    /// (the top-left pixel shows the foreground), so one picture has one encoding.
    pub pattern: u8,
    /// Colour of the pattern's pixels (meaningless when `pattern` is 0).
    pub fg: Rgb,
    /// Colour of the other pixels.
    pub bg: Rgb,
}

/// `1 / k` for group sizes 0 to 8, with 0 for an empty group (its sum is zero anyway).
const INV: [f32; MAX_PIXELS + 1] = [
    0.0,
    1.0,
    1.0 / 2.0,
    1.0 / 3.0,
    1.0 / 4.0,
    1.0 / 5.0,
    1.0 / 6.0,
    1.0 / 7.0,
    1.0 / 8.0,
];

#[inline]
fn norm_sq(v: [f32; 3]) -> f32 {
    v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
}

#[inline]
fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
fn add(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The split objective: `|S_A|²/n_A + |S_B|²/n_B` (larger is better).
#[inline]
fn score(sum_a: [f32; 3], n_a: usize, total: [f32; 3], n: usize) -> f32 {
    norm_sq(sum_a) * INV[n_a] + norm_sq(sub(total, sum_a)) * INV[n - n_a]
}

/// The best split of `lab` (2 to [`MAX_PIXELS`] pixels) by `method`, as a bit set (pixel `n − 1`
/// is always outside it). 0 when no split beats showing one colour.
pub fn split(lab: &[[f32; 3]], method: FitMethod) -> u8 {
    let n = lab.len();
    debug_assert!((1..=MAX_PIXELS).contains(&n));
    // Relative to the first pixel, so that the objective's terms are as large as the cell's spread
    // and not its distance from black: rounding then cannot make a split of equal colours win.
    let mut centred = [[0.0f32; 3]; MAX_PIXELS];
    for (c, &p) in centred.iter_mut().zip(lab) {
        *c = sub(p, lab[0]);
    }
    let centred = &centred[..n];
    let total = centred.iter().fold([0.0; 3], |s, &p| add(s, p));
    match method {
        FitMethod::Exhaustive => split_exhaustive(centred, total),
        FitMethod::Axis => split_axis(centred, total),
    }
}

fn split_exhaustive(lab: &[[f32; 3]], total: [f32; 3]) -> u8 {
    let n = lab.len();
    let mut best = (norm_sq(total) * INV[n], 0u8);
    let (mut sum_a, mut n_a, mut gray) = ([0.0f32; 3], 0usize, 0u8);
    // Gray code over the first n − 1 pixels: step i flips bit trailing_zeros(i).
    for i in 1u32..(1 << (n - 1)) {
        let bit = i.trailing_zeros() as usize;
        gray ^= 1 << bit;
        if gray & (1 << bit) != 0 {
            sum_a = add(sum_a, lab[bit]);
            n_a += 1;
        } else {
            sum_a = sub(sum_a, lab[bit]);
            n_a -= 1;
        }
        let s = score(sum_a, n_a, total, n);
        if s > best.0 {
            best = (s, gray);
        }
    }
    best.1
}

fn split_axis(lab: &[[f32; 3]], total: [f32; 3]) -> u8 {
    let n = lab.len();
    let mean = total.map(|v| v * INV[n]);
    // Covariance (unnormalised) and the pixel farthest from the mean, the power iteration's start.
    let mut cov = [0.0f32; 6]; // xx, xy, xz, yy, yz, zz
    let mut far = ([0.0f32; 3], 0.0f32);
    for &p in lab {
        let d = sub(p, mean);
        cov[0] += d[0] * d[0];
        cov[1] += d[0] * d[1];
        cov[2] += d[0] * d[2];
        cov[3] += d[1] * d[1];
        cov[4] += d[1] * d[2];
        cov[5] += d[2] * d[2];
        let r = norm_sq(d);
        if r > far.1 {
            far = (d, r);
        }
    }
    if far.1 == 0.0 {
        return 0;
    }
    let mut axis = far.0;
    for _ in 0..4 {
        let next = [
            cov[0] * axis[0] + cov[1] * axis[1] + cov[2] * axis[2],
            cov[1] * axis[0] + cov[3] * axis[1] + cov[4] * axis[2],
            cov[2] * axis[0] + cov[4] * axis[1] + cov[5] * axis[2],
        ];
        let len = norm_sq(next).sqrt();
        if len <= f32::MIN_POSITIVE {
            break;
        }
        axis = next.map(|v| v / len);
    }
    // Pixels by their place along the axis (insertion sort: n ≤ 8).
    let mut order = [(0.0f32, 0u8); MAX_PIXELS];
    for (i, &p) in lab.iter().enumerate() {
        let t = dot(sub(p, mean), axis);
        let mut j = i;
        while j > 0 && order[j - 1].0 > t {
            order[j] = order[j - 1];
            j -= 1;
        }
        order[j] = (t, i as u8);
    }
    let mut best = (norm_sq(total) * INV[n], 0u8);
    let (mut sum_a, mut pattern) = ([0.0f32; 3], 0u8);
    for (k, &(_, i)) in order[..n - 1].iter().enumerate() {
        sum_a = add(sum_a, lab[usize::from(i)]);
        pattern |= 1 << i;
        let s = score(sum_a, k + 1, total, n);
        if s > best.0 {
            best = (s, pattern);
        }
    }
    // One encoding per split: pixel n − 1 outside, as the exhaustive search has it.
    if best.1 & (1 << (n - 1)) != 0 {
        best.1 ^= ((1u16 << n) - 1) as u8;
    }
    best.1
}

/// The fitted glyph pattern and colours of a cell's pixels `rgb` (row-major; see [`Fit`]).
/// `to_lab` gives a colour's OKLab coordinates `[l, a, b]`; it is called only for cells of three
/// colours or more, the ones that need a search.
pub fn fit(rgb: &[Rgb], method: FitMethod, to_lab: &mut impl FnMut(Rgb) -> [f32; 3]) -> Fit {
    let n = rgb.len();
    debug_assert!((1..=MAX_PIXELS).contains(&n));
    let all = ((1u16 << n) - 1) as u8;
    let mut lab = [[0.0f32; 3]; MAX_PIXELS];
    let two = two_colours(rgb);
    let mut pattern = match two {
        Some(pattern) => pattern,
        None => {
            for (p, &c) in lab.iter_mut().zip(rgb) {
                *p = to_lab(c);
            }
            split(&lab[..n], method)
        }
    };
    let lab = &lab[..n];
    if pattern == 0 {
        let colour = group_colour(rgb, lab, all);
        return Fit {
            pattern: 0,
            fg: colour,
            bg: colour,
        };
    }
    if two.is_some() {
        // Both groups uniform: their own colours, exact; pixel 0's colour is the pattern.
        return Fit {
            pattern,
            fg: rgb[0],
            bg: group_colour(rgb, lab, all ^ pattern),
        };
    }
    let (fg, bg) = (
        group_colour(rgb, lab, pattern),
        group_colour(rgb, lab, all ^ pattern),
    );
    // The medians are not the means the split was scored with: a pixel may now lie nearer the
    // other group's colour. Showing it in that one only lowers the error, and keeps the invariant
    // that every pixel shows the nearer of its cell's two colours (tests/term/cells.rs).
    let (fg_lab, bg_lab) = (to_lab(fg), to_lab(bg));
    for (i, &p) in lab.iter().enumerate() {
        let (to_fg, to_bg) = (norm_sq(sub(p, fg_lab)), norm_sq(sub(p, bg_lab)));
        if pattern & (1 << i) != 0 && to_bg < to_fg {
            pattern &= !(1 << i);
        } else if pattern & (1 << i) == 0 && to_fg < to_bg {
            pattern |= 1 << i;
        }
    }
    let (pattern, fg, bg) = match pattern {
        0 => (0, bg, bg),
        p if p == all => (0, fg, fg),
        p if p & 1 == 0 => (p ^ all, bg, fg),
        p => (p, fg, bg),
    };
    Fit { pattern, fg, bg }
}

/// When the pixels hold at most two colours (an edge between flat areas, the common case), the
/// split by colour: exact, as both groups show their own colour, and found without a search. Pixel
/// 0's colour is the set; `None` for three colours or more.
fn two_colours(rgb: &[Rgb]) -> Option<u8> {
    let mut pattern = 0u8;
    let mut other = None;
    for (i, &c) in rgb.iter().enumerate() {
        if c == rgb[0] {
            pattern |= 1 << i;
        } else if *other.get_or_insert(c) != c {
            return None;
        }
    }
    Some(if other.is_some() { pattern } else { 0 })
}

/// The colour showing the pixels in `members` (non-empty): their own when they share one, else
/// their OKLab geometric median (`lab` is then filled in: only cells of one or two colours skip it,
/// and their groups are uniform).
///
/// Why the median and not the mean the split was scored with: a pixel shows the group's colour
/// whole, so what a viewer (and `nudge bench cells`, mean ΔE per pixel) sees is the sum of the
/// pixels' distances to it, which the geometric median minimises. Of a group of three dark-red
/// pixels and one white, the mean is a pink none of them has; the median stays near the dark red,
/// off by one pixel's distance instead of four fractions. Weiszfeld's iteration from the mean
/// (each step a distance-weighted mean), [`MEDIAN_STEPS`] steps: measured on the default scene's
/// octant frame, the mean error against the 4x8 reference fell from 0.62x half blocks' to 0.60x.
fn group_colour(rgb: &[Rgb], lab: &[[f32; 3]], members: u8) -> Rgb {
    let first = members.trailing_zeros() as usize;
    let (mut sum, mut count, mut uniform) = ([0.0f32; 3], 0usize, true);
    for (i, (&c, &p)) in rgb.iter().zip(lab).enumerate() {
        if members & (1 << i) != 0 {
            sum = add(sum, p);
            count += 1;
            uniform &= c == rgb[first];
        }
    }
    if uniform {
        return rgb[first];
    }
    let mut median = sum.map(|v| v * INV[count]);
    for _ in 0..MEDIAN_STEPS {
        let (mut weighted, mut weights) = ([0.0f32; 3], 0.0f32);
        for (i, &p) in lab.iter().enumerate() {
            if members & (1 << i) != 0 {
                // A pixel at the estimate would weigh infinitely: cap at 1/JND-ish distance.
                let w = 1.0 / norm_sq(sub(p, median)).sqrt().max(MEDIAN_EPS);
                weighted = add(weighted, p.map(|v| v * w));
                weights += w;
            }
        }
        median = weighted.map(|v| v / weights);
    }
    from_oklab(Oklab {
        l: median[0],
        a: median[1],
        b: median[2],
    })
}

/// Weiszfeld steps toward a group's geometric median (from its mean; 4 reach within 0.1 ΔE×100 of
/// 8 on the bench's frames).
const MEDIAN_STEPS: usize = 4;
/// Smallest distance a pixel is weighed at in the median's iteration, OKLab (a tenth of a just
/// noticeable difference): a pixel sitting on the estimate pulls hard but finitely.
const MEDIAN_EPS: f32 = 1e-3;

/// The split's squared OKLab error (the quantity both methods minimise), for tests and the bench.
pub fn split_error(lab: &[[f32; 3]], pattern: u8) -> f32 {
    let n = lab.len();
    let total = lab.iter().fold([0.0; 3], |s, &p| add(s, p));
    let mut sum_a = [0.0f32; 3];
    let mut n_a = 0;
    for (i, &p) in lab.iter().enumerate() {
        if pattern & (1 << i) != 0 {
            sum_a = add(sum_a, p);
            n_a += 1;
        }
    }
    let squares: f32 = lab.iter().map(|&p| norm_sq(p)).sum();
    (squares - score(sum_a, n_a, total, n)).max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::oklab::to_oklab;

    fn lab(c: Rgb) -> [f32; 3] {
        let p = to_oklab(c);
        [p.l, p.a, p.b]
    }

    fn labs(rgb: &[Rgb]) -> Vec<[f32; 3]> {
        rgb.iter().map(|&c| lab(c)).collect()
    }

    const K: Rgb = Rgb::BLACK;
    const W: Rgb = Rgb::WHITE;
    const R: Rgb = Rgb::new(200, 40, 30);

    #[test]
    fn a_cell_of_one_colour_is_pattern_zero_in_that_exact_colour() {
        let px = [R; 8];
        for method in FitMethod::ALL {
            let f = fit(&px, method, &mut lab);
            assert_eq!((f.pattern, f.bg), (0, R), "{method:?}");
        }
    }

    #[test]
    fn two_colours_are_split_exactly_with_the_top_left_pixel_in_front() {
        // Octant rows: K W / K W / K K / W W.
        let px = [K, W, K, W, K, K, W, W];
        for method in FitMethod::ALL {
            let f = fit(&px, method, &mut lab);
            assert_eq!(f.pattern, 0b0011_0101, "{method:?}");
            assert_eq!((f.fg, f.bg), (K, W), "{method:?}");
        }
    }

    #[test]
    fn three_colours_put_the_odd_one_with_its_nearest() {
        // Dark red is nearer red than white: red and dark red against white.
        let dark = Rgb::new(150, 30, 20);
        let px = [R, R, dark, W, W, W];
        let f = fit(&px, FitMethod::Exhaustive, &mut lab);
        assert_eq!(f.pattern, 0b00_0111);
        assert_eq!(f.bg, W);
        assert_ne!(f.fg, R, "the mean of red and dark red");
    }

    #[test]
    fn the_exhaustive_split_is_never_worse_than_the_axis_split() {
        let mut rng = crate::util::SplitMix64(3);
        for _ in 0..2000 {
            let px: Vec<Rgb> = (0..8)
                .map(|_| {
                    let v = |rng: &mut crate::util::SplitMix64| (rng.next_unit() * 255.0) as u8;
                    Rgb::new(v(&mut rng), v(&mut rng), v(&mut rng))
                })
                .collect();
            let lab = labs(&px);
            let exact = split_error(&lab, split(&lab, FitMethod::Exhaustive));
            let axis = split_error(&lab, split(&lab, FitMethod::Axis));
            assert!(exact <= axis + 1e-5, "{exact} > {axis} for {px:?}");
            // And no other split beats it.
            for p in 0..128u8 {
                assert!(exact <= split_error(&lab, p) + 1e-5, "{p:#b} beats it");
            }
        }
    }
}
