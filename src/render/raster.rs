//! Rasterization stage: which pixel centres a screen-space triangle covers.
//!
//! Triangle setup (Pineda 1988; Giesen, "Triangle rasterization in practice", 2013):
//! - vertices are snapped to a fixed-point grid of 1/256 pixel, so edge functions are exact integers;
//! - for the edge from `p` to `q`, `E(s) = (q.x - p.x)(s.y - p.y) - (q.y - p.y)(s.x - p.x)`; with pixel y
//!   pointing down, a triangle counter-clockwise in NDC (a front face) has `E_ab(c) < 0`. Back faces are
//!   dropped (when culling) and every edge function is negated for front faces so "inside" is `E ≥ 0`;
//! - top-left rule: a centre exactly on an edge belongs to the triangle only if that edge is a top edge
//!   (horizontal, interior below) or a left edge, implemented as a bias of −1 on the other edges. Two
//!   triangles sharing an edge see it with opposite directions, so exactly one owns such a centre: no
//!   crack, no pixel painted twice;
//! - the edge functions step incrementally across the bounding box of covered centres, clamped to the
//!   image (pixel `(x, y)` is sampled at `(x + 0.5, y + 0.5)`);
//! - barycentric weights are `E_i / 2A`, where `E_i` is the edge opposite vertex `i`.

use glam::Vec2;

/// Bits of sub-pixel precision of snapped vertex positions.
pub const SUBPIXEL_BITS: u32 = 8;
const ONE: i64 = 1 << SUBPIXEL_BITS;
const HALF: i64 = ONE / 2;
/// Largest |coordinate| in pixels (2²¹) accepted by [`TriangleSetup::new`]; the clip stage's guard band
/// keeps real geometry inside. Snapped coordinates then fit in 30 bits and every edge-function value
/// (a difference of two products of 31-bit differences) in 62, so the `i64` arithmetic cannot overflow.
pub const MAX_COORDINATE: f32 = 2_097_152.0;

/// Which triangles to drop by orientation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cull {
    /// Keep only front faces (counter-clockwise in NDC).
    Back,
    /// Keep both orientations.
    None,
}

/// A triangle ready to scan: integer edge functions at the first pixel centre and their steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleSetup {
    /// Inclusive pixel range of the scan, inside the image.
    x0: u32,
    x1: u32,
    y0: u32,
    y1: u32,
    /// Image width in pixels (row stride).
    width: usize,
    /// Biased edge functions at the centre of pixel `(x0, y0)`, edge `i` opposite vertex `i`.
    e_start: [i64; 3],
    step_x: [i64; 3],
    step_y: [i64; 3],
    /// 1 / (twice the snapped area), in sub-pixel² units.
    inv_area: f32,
    /// True when the triangle faces the camera (counter-clockwise in NDC).
    front: bool,
}

#[inline]
fn snap(v: Vec2) -> Option<[i64; 2]> {
    let ok = |c: f32| c.is_finite() && c.abs() <= MAX_COORDINATE;
    // Round half away from zero without a libm call (baseline x86-64 has no rounding instruction).
    let round = |c: f32| {
        let s = c * ONE as f32;
        (s + 0.5f32.copysign(s)) as i64
    };
    (ok(v.x) && ok(v.y)).then(|| [round(v.x), round(v.y)])
}

impl TriangleSetup {
    /// Sets up the triangle with pixel-space vertices `screen` (x right, y down) for an image of
    /// `width × height`. `None` when it is culled, degenerate after snapping, covers no pixel centre
    /// of the image, or has a non-finite or huge coordinate.
    pub fn new(screen: [Vec2; 3], width: u32, height: u32, cull: Cull) -> Option<Self> {
        if width == 0 || height == 0 {
            return None;
        }
        let v = [snap(screen[0])?, snap(screen[1])?, snap(screen[2])?];
        let edge = |p: [i64; 2], q: [i64; 2], s: [i64; 2]| {
            (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])
        };
        let area2 = edge(v[0], v[1], v[2]);
        let front = area2 < 0;
        if area2 == 0 || (cull == Cull::Back && !front) {
            return None;
        }
        let sign: i64 = if front { -1 } else { 1 };

        let min_x = v[0][0].min(v[1][0]).min(v[2][0]);
        let max_x = v[0][0].max(v[1][0]).max(v[2][0]);
        let min_y = v[0][1].min(v[1][1]).min(v[2][1]);
        let max_y = v[0][1].max(v[1][1]).max(v[2][1]);
        // First and last pixel whose centre (i·ONE + HALF) lies in [min, max].
        let first = |min: i64| (min - HALF + ONE - 1).div_euclid(ONE);
        let last = |max: i64| (max - HALF).div_euclid(ONE);
        let x0 = first(min_x).max(0);
        let x1 = last(max_x).min(width as i64 - 1);
        let y0 = first(min_y).max(0);
        let y1 = last(max_y).min(height as i64 - 1);
        if x0 > x1 || y0 > y1 {
            return None;
        }

        let start = [x0 * ONE + HALF, y0 * ONE + HALF];
        let mut e_start = [0; 3];
        let mut step_x = [0; 3];
        let mut step_y = [0; 3];
        for i in 0..3 {
            let p = v[(i + 1) % 3];
            let q = v[(i + 2) % 3];
            let (dx, dy) = (sign * (q[0] - p[0]), sign * (q[1] - p[1]));
            let top_left = (dy == 0 && dx > 0) || dy < 0;
            let bias = if top_left { 0 } else { -1 };
            e_start[i] = sign * edge(p, q, start) + bias;
            step_x[i] = -dy * ONE;
            step_y[i] = dx * ONE;
        }
        Some(Self {
            x0: x0 as u32,
            x1: x1 as u32,
            y0: y0 as u32,
            y1: y1 as u32,
            width: width as usize,
            e_start,
            step_x,
            step_y,
            inv_area: (1.0 / (area2.abs() as f64)) as f32,
            front,
        })
    }

    /// How the barycentric weights change a pixel to the right and a pixel down: `(∂l/∂x, ∂l/∂y)`
    /// (constant over the triangle, as the weights are affine in screen space).
    pub fn weight_steps(&self) -> ([f32; 3], [f32; 3]) {
        let inv = self.inv_area;
        (
            self.step_x.map(|s| s as f32 * inv),
            self.step_y.map(|s| s as f32 * inv),
        )
    }

    /// True for a front face (counter-clockwise in NDC).
    pub fn is_front(&self) -> bool {
        self.front
    }

    /// Calls `visit(index, weights)` for every covered pixel centre, in row-major order, where
    /// `index = y * width + x` and `weights` are the barycentric weights of the three vertices
    /// (non-negative, summing to 1 up to rounding).
    #[inline]
    pub fn for_each_pixel(&self, mut visit: impl FnMut(usize, [f32; 3])) {
        let inv = self.inv_area;
        let mut row = self.e_start;
        for y in self.y0..=self.y1 {
            let mut e = row;
            let base = y as usize * self.width;
            let mut seen = false;
            for x in self.x0..=self.x1 {
                if (e[0] | e[1] | e[2]) >= 0 {
                    seen = true;
                    visit(
                        base + x as usize,
                        [e[0] as f32 * inv, e[1] as f32 * inv, e[2] as f32 * inv],
                    );
                } else if seen {
                    // A convex shape: once a row leaves the triangle it does not come back.
                    break;
                }
                e[0] += self.step_x[0];
                e[1] += self.step_x[1];
                e[2] += self.step_x[2];
            }
            row[0] += self.step_y[0];
            row[1] += self.step_y[1];
            row[2] += self.step_y[2];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn covered(tri: [Vec2; 3], w: u32, h: u32, cull: Cull) -> Vec<usize> {
        let mut out = Vec::new();
        if let Some(setup) = TriangleSetup::new(tri, w, h, cull) {
            setup.for_each_pixel(|i, _| out.push(i));
        }
        out
    }

    #[test]
    fn a_front_face_is_kept_and_its_mirror_culled() {
        // Counter-clockwise in NDC = clockwise on a y-down screen.
        let front = [
            Vec2::new(1.0, 7.0),
            Vec2::new(7.0, 7.0),
            Vec2::new(1.0, 1.0),
        ];
        let back = [front[0], front[2], front[1]];
        assert!(!covered(front, 8, 8, Cull::Back).is_empty());
        assert!(covered(back, 8, 8, Cull::Back).is_empty());
        assert_eq!(
            covered(front, 8, 8, Cull::None),
            covered(back, 8, 8, Cull::None)
        );
    }

    #[test]
    fn a_square_of_two_triangles_covers_its_centres_exactly_once() {
        let (a, b, c, d) = (
            Vec2::new(1.0, 1.0),
            Vec2::new(5.0, 1.0),
            Vec2::new(5.0, 4.0),
            Vec2::new(1.0, 4.0),
        );
        let mut all = covered([a, b, c], 8, 8, Cull::None);
        all.extend(covered([a, c, d], 8, 8, Cull::None));
        all.sort();
        let expected: Vec<usize> = (1..4)
            .flat_map(|y| (1..5).map(move |x| y * 8 + x))
            .collect();
        assert_eq!(all, expected);
    }

    #[test]
    fn weights_reproduce_the_pixel_centre() {
        let tri = [
            Vec2::new(0.3, 0.2),
            Vec2::new(9.7, 1.1),
            Vec2::new(2.2, 8.9),
        ];
        let setup = TriangleSetup::new(tri, 10, 10, Cull::None).unwrap();
        setup.for_each_pixel(|i, l| {
            let centre = Vec2::new((i % 10) as f32 + 0.5, (i / 10) as f32 + 0.5);
            let p = l[0] * tri[0] + l[1] * tri[1] + l[2] * tri[2];
            assert!((p - centre).length() < 0.01, "{p} vs {centre}");
            assert!((l[0] + l[1] + l[2] - 1.0).abs() < 1e-4);
        });
    }

    #[test]
    fn huge_or_non_finite_coordinates_are_rejected() {
        let ok = [Vec2::ZERO, Vec2::new(4.0, 0.0), Vec2::new(0.0, 4.0)];
        let mut bad = ok;
        bad[1].x = f32::NAN;
        assert!(TriangleSetup::new(bad, 4, 4, Cull::None).is_none());
        bad[1].x = 1e9;
        assert!(TriangleSetup::new(bad, 4, 4, Cull::None).is_none());
        assert!(TriangleSetup::new(ok, 0, 4, Cull::None).is_none());
    }
}
