//! Procedural textures: functions of body-space position and UV, so a pattern moves and turns with
//! its body. Each returns a brightness factor applied to the albedo.
//!
//! **Filtered by the pixel's footprint.** A pixel samples the surface at its centre, so a pattern
//! finer than the pixels aliases: its lines land on some pixels and miss their neighbours, a
//! speckle that a finer render (or the eye) averages away. Each texture therefore takes the pixel's
//! footprint, its extents on the surface along the body axes (or in UV), from the screen-space
//! derivatives of the interpolated coordinates (the fragment stage's `Footprint`), and shows what a
//! box filter of that footprint would: the checker and the face border exactly (square waves and
//! bands integrate in closed form), the grain and stripes by their periods' [`box_gain`]. The same
//! idea as mip-mapping, without tables. Point-sampled, the checkered floor and the grain were most of
//! the error of a 2 × 4-pixel-a-cell (octant) frame against a 4 × 8 one (`nudge bench cells`).

use glam::{Vec2, Vec3};

/// `sin(x)` to about 1e-3, cheap enough per pixel (Bhaskara-style parabola with one refinement).
#[inline]
pub fn fast_sin(x: f32) -> f32 {
    use std::f32::consts::{PI, TAU};
    let x = x - TAU * (x / TAU + 0.5).floor(); // into [-π, π)
    let y = 4.0 / PI * x - 4.0 / (PI * PI) * x * x.abs();
    0.225 * (y * y.abs() - y) + y
}

/// How much of a periodic pattern's contrast a pixel shows when one period spans `period_px`
/// pixels: a box filter's gain, `sin(π/P)/(π/P)` (0.97 at 8 pixels, 0.64 at 2); below 2 pixels (the
/// Nyquist limit) a point sample can only alias, so the gain falls linearly to 0 at 1 pixel and the
/// pattern shows its mean.
#[inline]
pub fn box_gain(period_px: f32) -> f32 {
    use std::f32::consts::PI;
    if period_px >= 2.0 {
        let x = PI / period_px;
        x.sin() / x
    } else {
        (2.0 / PI) * (period_px - 1.0).max(0.0)
    }
}

/// The pixel's extent along the unit direction `d` (body space), from its extents along the body
/// axes (`footprint`, metres), taken as independent spreads.
#[inline]
fn extent_along(d: Vec3, footprint: Vec3) -> f32 {
    (d * footprint).length()
}

/// Rings a metre of radius (the growth rings' spatial frequency).
const RINGS_PER_M: f32 = 9.0;
/// Angular frequency of the streaks along the grain, rad/m.
const STREAK_RAD_PER_M: f32 = 41.0;
/// Mean of the late-wood term over a ring: `∫₀.₇¹ 3.3 (t − 0.7) dt`.
const LATE_MEAN: f32 = 0.1485;

/// Wood grain: growth rings around the body's y axis, warped a little so they meander, with fine
/// streaks along the grain. `p_local` in metres, `footprint` the pixel's extents along the body
/// axes (metres; see the module docs). Returns a factor in about [0.72, 1.04]; rings and streaks
/// lose contrast as they shrink toward the pixels ([`box_gain`]).
#[inline]
pub fn wood(p_local: Vec3, footprint: Vec3) -> f32 {
    let warp = 0.35 * fast_sin(1.7 * p_local.y + 2.3 * p_local.x) + 0.2 * fast_sin(3.1 * p_local.z);
    let radius = (p_local.x * p_local.x + p_local.z * p_local.z).sqrt();
    let r = radius * RINGS_PER_M + warp;
    let ring = r - r.floor();
    // Late wood (the dark thin part of a ring) near the end of each period.
    let late = ((ring - 0.7) * 3.3).clamp(0.0, 1.0);
    let radial = Vec3::new(p_local.x, 0.0, p_local.z) / radius.max(1e-6);
    let ring_px = 1.0 / (RINGS_PER_M * extent_along(radial, footprint)).max(1e-9);
    let late = LATE_MEAN + box_gain(ring_px) * (late - LATE_MEAN);
    let streak_px = std::f32::consts::TAU / (STREAK_RAD_PER_M * footprint.y).max(1e-9);
    let streak = 0.04 * box_gain(streak_px) * fast_sin(STREAK_RAD_PER_M * p_local.y + 7.0 * warp);
    1.0 - 0.24 * late + streak
}

/// Width of the darkened border, a fraction of the face size.
const BORDER: f32 = 0.045;

/// Darkened border of a box face (from its UVs in [0, 1]²), so stacked boxes read apart: factor
/// 0.72 within 4.5 % of the face size from an edge, 1 elsewhere, box-filtered over `footprint_uv`
/// (the pixel's extents in UV; 0 for a point sample). The band on each axis covers a share of the
/// footprint; the border is their union.
#[inline]
pub fn face_border(uv: Vec2, footprint_uv: Vec2) -> f32 {
    // Share of [t − f/2, t + f/2] inside (−∞, B] ∪ [1 − B, ∞).
    let covered = |t: f32, f: f32| {
        if f <= 1e-6 {
            return if t.min(1.0 - t) < BORDER { 1.0 } else { 0.0 };
        }
        let low = ((BORDER - (t - 0.5 * f)) / f).clamp(0.0, 1.0);
        let high = ((t + 0.5 * f - (1.0 - BORDER)) / f).clamp(0.0, 1.0);
        (low + high).min(1.0)
    };
    let (cu, cv) = (covered(uv.x, footprint_uv.x), covered(uv.y, footprint_uv.y));
    let border = 1.0 - (1.0 - cu) * (1.0 - cv);
    1.0 - 0.28 * border
}

/// A ±1 square wave of period 2 (+1 on `[0, 1)`), box-filtered over `[t − f/2, t + f/2]`: the
/// difference of its integral, a triangle wave, over the width.
#[inline]
fn filtered_square(t: f32, f: f32) -> f32 {
    if f <= 1e-6 {
        return if (t.floor() as i64) & 1 == 0 {
            1.0
        } else {
            -1.0
        };
    }
    let integral = |x: f32| 1.0 - ((x - 2.0 * (0.5 * x).floor()) - 1.0).abs();
    (integral(t + 0.5 * f) - integral(t - 0.5 * f)) / f
}

/// 1 m checker in body space (all three axes, so any face shows squares): factor 1 or 0.8, box-
/// filtered over `footprint` (the pixel's extents along the body axes, metres). The checker is the
/// product of three square waves, so its filter is the product of theirs: a distant floor turns
/// a uniform 0.9 instead of moiré, and squares a few pixels wide keep sharp centres.
#[inline]
pub fn checker(p_local: Vec3, footprint: Vec3) -> f32 {
    let sign = filtered_square(p_local.x, footprint.x)
        * filtered_square(p_local.y, footprint.y)
        * filtered_square(p_local.z, footprint.z);
    0.9 + 0.1 * sign
}

/// Faint beach-ball stripes from longitude (the UV sphere's u), so a spinning sphere looks spinning.
/// Factor 0.86 or 1, fading to 0.93 as the stripes shrink toward the pixels: `p_local` (metres, on
/// the sphere) gives the circle of latitude, 8 periods around it, and `footprint` the pixel's
/// extents along the body axes.
#[inline]
pub fn sphere_stripes(uv: Vec2, p_local: Vec3, footprint: Vec3) -> f32 {
    let radius = (p_local.x * p_local.x + p_local.z * p_local.z).sqrt();
    let around = Vec3::new(-p_local.z, 0.0, p_local.x) / radius.max(1e-6);
    let period_px =
        std::f32::consts::TAU * radius / 8.0 / extent_along(around, footprint).max(1e-9);
    let contrast = 0.07 * box_gain(period_px);
    if ((uv.x * 8.0).floor() as i64) & 1 == 0 {
        0.93 + contrast
    } else {
        0.93 - contrast
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fast_sin_is_close_to_sin() {
        let mut x = -20.0f32;
        while x < 20.0 {
            assert!((fast_sin(x) - x.sin()).abs() < 2e-3, "{x}");
            x += 0.01;
        }
    }

    #[test]
    fn checker_alternates_between_neighbouring_squares() {
        let a = checker(Vec3::new(0.5, 0.25, 0.5), Vec3::splat(0.1));
        let b = checker(Vec3::new(1.5, 0.25, 0.5), Vec3::splat(0.1));
        // Inside a square a small footprint sees one shade (to f32 rounding of the integral).
        assert!((a - 1.0).abs() < 1e-5 && (b - 0.8).abs() < 1e-5, "{a} {b}");
        let c = checker(Vec3::new(1.5, 0.25, 1.5), Vec3::splat(0.1));
        assert!((a - c).abs() < 1e-5, "{a} {c}");
    }

    #[test]
    fn checker_fades_when_squares_get_smaller_than_pixels() {
        // A pixel two squares wide covers one of each: the mean, wherever it falls.
        for x in [0.1, 0.5, 1.3, 2.9] {
            let f = checker(Vec3::new(x, 0.25, 0.5), Vec3::new(2.0, 0.0, 0.0));
            assert!((f - 0.9).abs() < 1e-5, "{x}: {f}");
        }
        // Half a pixel on each side of an edge: half of each square.
        let f = checker(Vec3::new(1.0, 0.25, 0.5), Vec3::new(0.5, 0.0, 0.0));
        assert!((f - 0.9).abs() < 1e-6, "{f}");
        // Filtering across y, along which a floor's top face does not vary, changes nothing.
        assert_eq!(
            checker(Vec3::new(0.5, 0.25, 0.5), Vec3::new(0.0, 0.0, 0.0)),
            1.0
        );
    }

    #[test]
    fn wood_varies_across_a_face_and_darkens_its_border() {
        let centre = Vec2::splat(0.5);
        let samples: Vec<f32> = (0..50)
            .map(|i| wood(Vec3::new(i as f32 * 0.01, 0.1, 0.2), Vec3::splat(0.002)))
            .collect();
        let spread = samples.iter().cloned().fold(f32::MIN, f32::max)
            - samples.iter().cloned().fold(f32::MAX, f32::min);
        assert!(spread > 0.1, "grain is visible");
        assert!(face_border(Vec2::new(0.01, 0.5), Vec2::ZERO) < face_border(centre, Vec2::ZERO));
    }

    #[test]
    fn grain_finer_than_the_pixels_shows_its_mean() {
        // Pixels of 0.5 m: rings 0.22 px apart, streaks 0.3 px: both at their mean, so neighbouring
        // pixels agree where point samples would flicker between late and early wood.
        for i in 0..50 {
            let f = wood(Vec3::new(i as f32 * 0.037, 0.1, 0.2), Vec3::splat(0.5));
            assert!((f - (1.0 - 0.24 * LATE_MEAN)).abs() < 1e-6, "{f}");
        }
        // That mean is the rings' average: fine point samples of the full grain agree with it.
        let n = 20_000;
        let mean: f32 = (0..n)
            .map(|i| wood(Vec3::new(0.3 + i as f32 * 1e-4, 0.1, 0.2), Vec3::ZERO))
            .sum::<f32>()
            / n as f32;
        assert!((mean - (1.0 - 0.24 * LATE_MEAN)).abs() < 0.01, "{mean}");
    }

    #[test]
    fn a_face_border_thinner_than_a_pixel_darkens_by_the_share_it_covers() {
        // A footprint of 0.09 (twice the band) centred on the face's edge lies wholly in the
        // band (the neighbouring face's border continues it); centred on the band's inner edge,
        // half in it.
        let f = face_border(Vec2::new(0.0, 0.5), Vec2::new(0.09, 0.0));
        assert!((f - 0.72).abs() < 1e-6, "{f}");
        let f = face_border(Vec2::new(0.045, 0.5), Vec2::new(0.09, 0.0));
        assert!((f - (1.0 - 0.28 * 0.5)).abs() < 1e-6, "{f}");
        // Far from the edges a small footprint changes nothing; one as wide as the face sees both
        // bands: 9 % of it.
        assert_eq!(face_border(Vec2::splat(0.5), Vec2::splat(0.2)), 1.0);
        let f = face_border(Vec2::new(0.5, 0.5), Vec2::new(1.0, 0.0));
        assert!((f - (1.0 - 0.28 * 0.09)).abs() < 1e-5, "{f}");
    }

    #[test]
    fn box_gain_is_whole_for_wide_periods_and_gone_at_one_pixel() {
        assert!(box_gain(100.0) > 0.999);
        assert!((box_gain(2.0) - 2.0 / std::f32::consts::PI).abs() < 1e-6);
        assert_eq!(box_gain(1.0), 0.0);
        assert_eq!(box_gain(0.3), 0.0);
    }

    #[test]
    fn stripes_alternate_around_the_sphere() {
        let fine = Vec3::splat(0.001);
        assert_ne!(
            sphere_stripes(Vec2::new(0.01, 0.5), Vec3::X, fine),
            sphere_stripes(Vec2::new(0.14, 0.5), Vec3::X, fine)
        );
    }
}
