//! Line rasterization for wireframes: a DDA over a segment clipped to the image.

use glam::{Vec2, Vec3};

/// Calls `visit(index, z)` for the pixels a segment between pixel-space points `a` and `b`
/// (x right, y down, z = clip depth) passes through, one pixel per step along the major axis.
/// The segment is first clipped to the image rectangle (Liang–Barsky), so the walk is bounded by
/// `width + height` steps whatever the input; non-finite input draws nothing.
pub fn for_each_line_pixel(
    a: Vec3,
    b: Vec3,
    width: u32,
    height: u32,
    mut visit: impl FnMut(usize, f32),
) {
    if width == 0 || height == 0 || !a.is_finite() || !b.is_finite() {
        return;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    // Liang–Barsky: for each side, p·t ≤ q keeps the inside.
    let sides = [
        (-d.x, a.x),
        (d.x, width as f32 - a.x),
        (-d.y, a.y),
        (d.y, height as f32 - a.y),
    ];
    for (p, q) in sides {
        if p == 0.0 {
            if q < 0.0 {
                return;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return;
    }
    let (p, q) = (a + t0 * d, a + t1 * d);
    let span = Vec2::new(q.x - p.x, q.y - p.y).abs().max_element();
    let steps = span.ceil().clamp(1.0, (width + height) as f32 * 2.0) as u32;
    let step = (q - p) / steps as f32;
    let mut s = p;
    for _ in 0..=steps {
        let (x, y) = (s.x.floor(), s.y.floor());
        if x >= 0.0 && y >= 0.0 && x < width as f32 && y < height as f32 {
            visit(y as usize * width as usize + x as usize, s.z);
        }
        s += step;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_horizontal_line_covers_its_row_and_nothing_else() {
        let mut hit = Vec::new();
        for_each_line_pixel(
            Vec3::new(-5.0, 2.5, 0.5),
            Vec3::new(50.0, 2.5, 0.5),
            10,
            4,
            |i, _| hit.push(i),
        );
        hit.dedup();
        assert_eq!(hit, (20..30).collect::<Vec<_>>());
    }

    #[test]
    fn lines_outside_or_broken_draw_nothing() {
        let mut count = 0;
        let mut visit = |_: usize, _: f32| count += 1;
        for_each_line_pixel(
            Vec3::new(-5.0, -1.0, 0.0),
            Vec3::new(-1.0, -9.0, 0.0),
            10,
            4,
            &mut visit,
        );
        for_each_line_pixel(
            Vec3::new(f32::NAN, 1.0, 0.0),
            Vec3::new(3.0, 1.0, 0.0),
            10,
            4,
            &mut visit,
        );
        for_each_line_pixel(Vec3::ZERO, Vec3::new(1e30, 1e30, 0.0), 0, 4, &mut visit);
        assert_eq!(count, 0);
    }
}
