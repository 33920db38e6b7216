//! A tether drawn over a finished frame: a line between two world points and a marker at the first,
//! so a spring the user holds can be seen (the grab point on the body, the pointer's point in space).
//!
//! Drawn through the same camera and viewport as the scene, after it and without a depth test: the
//! held point is on the body's near side, and the line must show even where a body passes in front.

use glam::{Vec3, Vec4};

use super::Frame;
use super::line::for_each_line_pixel;
use crate::color::Rgb;
use crate::geometry::{Camera, Viewport};

/// Half the side of the square marker, pixels: a 3 × 3 block (a cell and a half tall on screen).
const MARKER_HALF_PX: i32 = 1;

/// Draws a line from world point `anchor` to `pointer` in `line`, then a square marker at `anchor`
/// in `marker`. Points behind a perspective camera draw nothing.
pub fn draw_tether(
    frame: &mut Frame,
    viewport: &Viewport,
    camera: &Camera,
    anchor: Vec3,
    pointer: Vec3,
    line: Rgb,
    marker: Rgb,
) {
    if frame.width() != viewport.width || frame.height() != viewport.height {
        return;
    }
    let clip_from_world = camera.clip_from_world(viewport.aspect());
    let to_pixel = |p: Vec3| -> Option<Vec3> {
        let clip: Vec4 = clip_from_world * p.extend(1.0);
        if clip.w <= 1e-6 || !clip.is_finite() {
            return None;
        }
        let ndc = clip.truncate() / clip.w;
        let pixel = viewport.pixel_from_ndc(ndc.truncate());
        Some(pixel.extend(ndc.z))
    };
    let (Some(a), Some(b)) = (to_pixel(anchor), to_pixel(pointer)) else {
        return;
    };
    let (width, height) = (frame.width(), frame.height());
    let (pixels, _, _) = frame.buffers_mut();
    for_each_line_pixel(a, b, width, height, |i, _| pixels[i] = line);
    let (cx, cy) = (a.x.floor() as i32, a.y.floor() as i32);
    for y in cy - MARKER_HALF_PX..=cy + MARKER_HALF_PX {
        for x in cx - MARKER_HALF_PX..=cx + MARKER_HALF_PX {
            if x >= 0 && y >= 0 && (x as u32) < width && (y as u32) < height {
                pixels[y as usize * width as usize + x as usize] = marker;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tether_joins_the_projected_points_and_marks_the_anchor() {
        let viewport = Viewport::new(40, 20, 1.0);
        let camera = Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0);
        let mut frame = Frame::new(40, 20);
        let (line, marker) = (Rgb::new(1, 2, 3), Rgb::new(9, 9, 9));
        draw_tether(
            &mut frame,
            &viewport,
            &camera,
            Vec3::ZERO,
            Vec3::new(-8.0, 0.0, 0.0),
            line,
            marker,
        );
        // The origin projects to the centre; camera right is world −x seen from −z, so −x is to the
        // right of the image.
        assert_eq!(frame.pixel(20, 10), marker);
        let right_of_marker = (22..40).filter(|&x| frame.pixel(x, 10) == line).count();
        let left_of_marker = (0..19).filter(|&x| frame.pixel(x, 10) == line).count();
        assert!(
            right_of_marker > 4 && left_of_marker == 0,
            "{right_of_marker} {left_of_marker}"
        );
    }

    #[test]
    fn points_behind_the_camera_draw_nothing() {
        let viewport = Viewport::new(40, 20, 1.0);
        let camera = Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0);
        let mut frame = Frame::new(40, 20);
        draw_tether(
            &mut frame,
            &viewport,
            &camera,
            Vec3::new(0.0, 0.0, -20.0),
            Vec3::ZERO,
            Rgb::WHITE,
            Rgb::WHITE,
        );
        assert!(frame.pixels().iter().all(|&p| p == Rgb::BLACK));
    }
}
