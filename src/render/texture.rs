//! Procedural textures: functions of body-space position and UV, so a pattern moves and turns with
//! its body. Each returns a brightness factor applied to the albedo.

use glam::{Vec2, Vec3};

/// `sin(x)` to about 1e-3, cheap enough per pixel (Bhaskara-style parabola with one refinement).
#[inline]
pub fn fast_sin(x: f32) -> f32 {
    use std::f32::consts::{PI, TAU};
    let x = x - TAU * (x / TAU + 0.5).floor(); // into [-π, π)
    let y = 4.0 / PI * x - 4.0 / (PI * PI) * x * x.abs();
    0.225 * (y * y.abs() - y) + y
}

/// Wood grain: growth rings around the body's y axis, warped a little so they meander, with fine
/// streaks along the grain. `p_local` in metres. Returns a factor in about [0.72, 1.04].
#[inline]
pub fn wood(p_local: Vec3) -> f32 {
    let warp = 0.35 * fast_sin(1.7 * p_local.y + 2.3 * p_local.x) + 0.2 * fast_sin(3.1 * p_local.z);
    let r = (p_local.x * p_local.x + p_local.z * p_local.z).sqrt() * 9.0 + warp;
    let ring = r - r.floor();
    // Late wood (the dark thin part of a ring) near the end of each period.
    let late = ((ring - 0.7) * 3.3).clamp(0.0, 1.0);
    let streak = 0.04 * fast_sin(41.0 * p_local.y + 7.0 * warp);
    1.0 - 0.24 * late + streak
}

/// Darkened border of a box face (from its UVs in [0, 1]²), so stacked boxes read apart. Factor 0.72
/// within 4.5 % of the face size from an edge, 1 elsewhere.
#[inline]
pub fn face_border(uv: Vec2) -> f32 {
    let edge = uv.x.min(1.0 - uv.x).min(uv.y).min(1.0 - uv.y);
    if edge < 0.045 { 0.72 } else { 1.0 }
}

/// 1 m checker in body space (all three axes, so any face shows squares). Factor 0.8 or 1.
#[inline]
pub fn checker(p_local: Vec3) -> f32 {
    let cell = p_local.x.floor() as i64 + p_local.y.floor() as i64 + p_local.z.floor() as i64;
    if cell & 1 == 0 { 1.0 } else { 0.8 }
}

/// Faint beach-ball stripes from longitude (the UV sphere's u), so a spinning sphere looks spinning.
/// Factor 0.86 or 1.
#[inline]
pub fn sphere_stripes(uv: Vec2) -> f32 {
    if ((uv.x * 8.0).floor() as i64) & 1 == 0 {
        1.0
    } else {
        0.86
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
        let a = checker(Vec3::new(0.5, 0.25, 0.5));
        let b = checker(Vec3::new(1.5, 0.25, 0.5));
        assert_ne!(a, b);
        assert_eq!(a, checker(Vec3::new(1.5, 0.25, 1.5)));
    }

    #[test]
    fn wood_varies_across_a_face_and_darkens_its_border() {
        let centre = Vec2::splat(0.5);
        let samples: Vec<f32> = (0..50)
            .map(|i| wood(Vec3::new(i as f32 * 0.01, 0.1, 0.2)))
            .collect();
        let spread = samples.iter().cloned().fold(f32::MIN, f32::max)
            - samples.iter().cloned().fold(f32::MAX, f32::min);
        assert!(spread > 0.1, "grain is visible");
        assert!(face_border(Vec2::new(0.01, 0.5)) < face_border(centre));
    }

    #[test]
    fn stripes_alternate_around_the_sphere() {
        assert_ne!(
            sphere_stripes(Vec2::new(0.01, 0.5)),
            sphere_stripes(Vec2::new(0.14, 0.5))
        );
    }
}
