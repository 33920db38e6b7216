//! The contact patch of a face contact: its area and the mean distance of its points from its
//! centre, which is what twist friction needs.
//!
//! Coulomb friction over a patch of uniform pressure p = N/A resists turning about the normal with at
//! most μ∫p|r − c|dA = μ·N·r̄, r̄ the mean distance from the patch centre c to its points (Goyal,
//! Ruina & Papadopoulos 1991, "Planar sliding with dry friction"). For a square of side a,
//! r̄ = a·(√2 + ln(1 + √2))/6 = 0.3826·a. The corners a manifold keeps are farther out (a/√2 =
//! 0.7071·a for the square), so friction at the corners alone, as nudge, Rapier and Jolt had it,
//! stopped a spinning box in 0.48 s instead of 0.89 s.
//!
//! Which part of the clipped face touches: the soft contact carries load through penetration, so the
//! patch is the part of the incident polygon that lies within [`TOUCH_DEPTH`] of its deepest point
//! (one more Sutherland–Hodgman clip, on the separation, which is linear over the planar face). A box
//! resting flat gets its whole face; a box tilted onto an edge a thin strip along it (r̄ → L/4 of the
//! edge's length L, the mean distance from a segment's midpoint); the strip narrows continuously as
//! the box tilts, so r̄ does not jump. A lone point has r̄ = 0 (no twist row either).
//!
//! ```text
//! c = area centroid (shoelace);  r̄ = Σ_edges I(c, p_i, p_i+1) / A, where for the triangle (c, p, q)
//! with the line pq at distance d from c and t the signed position along it from the foot of the
//! perpendicular (ρ = √(d² + t²) = |p − c|):
//!     I = ∫∫|r − c| dA = (1/6)·[d·t·ρ + d³·asinh(t/d)] from t_p to t_q      (polar, ∫sec³)
//! ```

use glam::Vec2;

use crate::physics::narrow::manifold::Patch;

/// How far above its deepest point the polygon still counts as touching, m: the depth of a contact at
/// rest (the linear slop's scale), far above the tilt noise of a box lying flat (microns).
pub(crate) const TOUCH_DEPTH: f32 = 0.001;

/// The patch of the convex polygon `points` (face coordinates, m, in order around it) with
/// separations `separations` (m, linear over the polygon): the part within `TOUCH_DEPTH` of the
/// deepest vertex.
pub fn patch(points: &[Vec2], separations: &[f32]) -> Patch {
    debug_assert_eq!(points.len(), separations.len());
    let n = points.len().min(separations.len()).min(8);
    if n == 0 {
        return Patch::default();
    }
    let deepest = separations[..n]
        .iter()
        .copied()
        .fold(f32::INFINITY, f32::min);
    let limit = deepest + TOUCH_DEPTH;
    // Sutherland–Hodgman against separation ≤ limit: at most one more vertex than the input.
    let mut touching = [Vec2::ZERO; 9];
    let mut len = 0;
    for a in 0..n {
        let b = if a + 1 == n { 0 } else { a + 1 };
        let (d_a, d_b) = (separations[a] - limit, separations[b] - limit);
        if d_a <= 0.0 {
            touching[len] = points[a];
            len += 1;
            if d_b > 0.0 {
                touching[len] = points[a].lerp(points[b], d_a / (d_a - d_b));
                len += 1;
            }
        } else if d_b <= 0.0 {
            touching[len] = points[a].lerp(points[b], d_a / (d_a - d_b));
            len += 1;
        }
    }
    polygon_patch(&touching[..len])
}

/// Area and mean radius of the convex polygon `points` (in order, at most 9; a degenerate one is
/// measured as a segment).
///
/// Per edge, asinh(t_q/d) − asinh(t_p/d) = ln((t_q + ρ_q)/(t_p + ρ_p)): one logarithm, with
/// t + ρ = d²/(ρ − t) for t < 0 so nothing cancels; the ρ are per vertex, shared by two edges.
pub(crate) fn polygon_patch(points: &[Vec2]) -> Patch {
    let n = points.len().min(9);
    if n < 2 {
        return Patch::default();
    }
    // Relative to the first vertex, for precision far from the face centre.
    let origin = points[0];
    let mut local = [Vec2::ZERO; 9];
    let mut lengths = [0.0f32; 9];
    let (mut twice_area, mut moment, mut perimeter) = (0.0f32, Vec2::ZERO, 0.0f32);
    for i in 0..n {
        local[i] = points[i] - origin;
    }
    for i in 0..n {
        let (p, q) = (local[i], local[if i + 1 == n { 0 } else { i + 1 }]);
        let cross = p.perp_dot(q);
        twice_area += cross;
        moment += (p + q) * cross;
        lengths[i] = (q - p).length();
        perimeter += lengths[i];
    }
    let area = 0.5 * twice_area.abs();
    // Thinner than a ten-thousandth of its perimeter squared: a segment, traced there and back
    // (perimeter 2L), whose mean distance from its midpoint is L/4.
    if area <= 1e-4 * perimeter * perimeter {
        return Patch {
            area: 0.0,
            mean_radius: perimeter / 8.0,
        };
    }
    let centre = moment / (3.0 * twice_area);
    let mut rho = [0.0f32; 9];
    for i in 0..n {
        local[i] -= centre;
        rho[i] = local[i].length();
    }
    let mut integral = 0.0f32;
    for i in 0..n {
        let j = if i + 1 == n { 0 } else { i + 1 };
        let length = lengths[i];
        if length <= 0.0 {
            continue;
        }
        let (p, q) = (local[i], local[j]);
        let along = (q - p) / length;
        // Distance of the edge's line from the centre (≥ 0 for a convex polygon around it), and the
        // ends' positions along it from the foot of the perpendicular.
        let d = p.perp_dot(along).abs();
        let (t_p, t_q) = (p.dot(along), q.dot(along));
        let mut term = d * (t_q * rho[j] - t_p * rho[i]);
        // d³·(asinh(t_q/d) − asinh(t_p/d)) → 0 as d → 0 (the centre on the edge's line).
        if d > 1e-6 * length {
            let d2 = d * d;
            let rise = |t: f32, r: f32| if t >= 0.0 { t + r } else { d2 / (r - t) };
            term += d2 * d * (rise(t_q, rho[j]) / rise(t_p, rho[i])).ln();
        }
        integral += term;
    }
    Patch {
        area,
        mean_radius: (integral / 6.0).abs() / area,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rectangle(a: f32, b: f32) -> [Vec2; 4] {
        [
            Vec2::new(a / 2.0, b / 2.0),
            Vec2::new(-a / 2.0, b / 2.0),
            Vec2::new(-a / 2.0, -b / 2.0),
            Vec2::new(a / 2.0, -b / 2.0),
        ]
    }

    /// The mean distance from the centre of an a × b rectangle to its points, by a fine midpoint sum.
    fn rectangle_mean_radius_numerically(a: f32, b: f32) -> f32 {
        let n = 400;
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let x = (i as f64 + 0.5) / n as f64 - 0.5;
                let y = (j as f64 + 0.5) / n as f64 - 0.5;
                sum += ((x * a as f64).powi(2) + (y * b as f64).powi(2)).sqrt();
            }
        }
        (sum / (n * n) as f64) as f32
    }

    #[test]
    fn a_square_has_mean_radius_0_3826_of_its_side() {
        let expected = (2f32.sqrt() + (1.0 + 2f32.sqrt()).ln()) / 6.0;
        assert!((expected - 0.3826).abs() < 1e-4);
        for side in [0.1, 1.0, 3.0] {
            let p = polygon_patch(&rectangle(side, side));
            assert!((p.area - side * side).abs() < 1e-5 * side * side, "{p:?}");
            assert!(
                (p.mean_radius - expected * side).abs() < 1e-5 * side,
                "{p:?}"
            );
        }
    }

    #[test]
    fn rectangles_of_any_aspect_ratio_match_the_integral() {
        for (a, b) in [(1.0, 0.5), (2.0, 0.2), (0.3, 1.7), (1.0, 0.01)] {
            let got = polygon_patch(&rectangle(a, b)).mean_radius;
            let expected = rectangle_mean_radius_numerically(a, b);
            assert!(
                (got - expected).abs() < 1e-3 * expected,
                "{a} x {b}: {got} vs {expected}"
            );
        }
    }

    #[test]
    fn the_patch_does_not_depend_on_where_the_polygon_starts_or_where_it_lies() {
        let square = rectangle(1.0, 1.0);
        let moved: Vec<Vec2> = square.iter().map(|p| *p + Vec2::new(40.0, -7.0)).collect();
        let turned = [square[2], square[3], square[0], square[1]];
        let reference = polygon_patch(&square);
        for other in [polygon_patch(&moved), polygon_patch(&turned)] {
            assert!(
                (other.mean_radius - reference.mean_radius).abs() < 1e-4,
                "{other:?}"
            );
        }
    }

    #[test]
    fn a_segment_has_a_quarter_of_its_length_and_a_point_nothing() {
        let segment = [Vec2::new(-0.5, 0.0), Vec2::new(0.5, 0.0)];
        assert_eq!(polygon_patch(&segment).mean_radius, 0.25);
        assert_eq!(polygon_patch(&[Vec2::ONE]).mean_radius, 0.0);
        assert_eq!(polygon_patch(&[]).mean_radius, 0.0);
    }

    #[test]
    fn a_face_lying_flat_touches_everywhere_and_a_tilted_one_along_its_low_edge() {
        let square = rectangle(1.0, 1.0);
        let flat = patch(&square, &[-0.001, -0.0010001, -0.001, -0.0009999]);
        assert!((flat.mean_radius - 0.3826).abs() < 1e-3, "{flat:?}");
        // Tilted about the edge x = −0.5 by 0.1 rad: only a strip 1 cm wide touches, nearly a
        // segment of length 1.
        let tilted = square.map(|p| 0.1 * (p.x + 0.5) - 0.001);
        let strip = patch(&square, &tilted);
        assert!((strip.area - 0.01).abs() < 1e-4, "{strip:?}");
        assert!((strip.mean_radius - 0.25).abs() < 0.01, "{strip:?}");
        // A little tilt: a wide strip, between the two.
        let slight = square.map(|p| 0.0015 * (p.x + 0.5) - 0.001);
        let wide = patch(&square, &slight);
        assert!(wide.mean_radius > strip.mean_radius && wide.mean_radius < flat.mean_radius);
    }
}
