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
/// The one-pixel ring around the marker. At 16 colours the default scene's orange box is shown in
/// xterm's red, and a red marker on it was lost (`nudge bench render`, colour marks); a black ring
/// sets a bright marker off from anything mid or light, and the bright core reads on dark ground.
/// Black is exact in every palette.
const MARKER_OUTLINE: Rgb = Rgb::BLACK;

/// Draws a line from world point `anchor` to `pointer` in `line`, then a square marker at `anchor`
/// in `marker`, ringed in black. Points behind a perspective camera draw nothing.
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
    let ring = MARKER_HALF_PX + 1;
    for y in cy - ring..=cy + ring {
        for x in cx - ring..=cx + ring {
            if x >= 0 && y >= 0 && (x as u32) < width && (y as u32) < height {
                let core = (x - cx).abs() <= MARKER_HALF_PX && (y - cy).abs() <= MARKER_HALF_PX;
                pixels[y as usize * width as usize + x as usize] =
                    if core { marker } else { MARKER_OUTLINE };
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

    #[test]
    fn the_marker_is_ringed_in_black_so_it_reads_on_a_body_of_its_own_colour() {
        let viewport = Viewport::new(40, 20, 1.0);
        let camera = Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0);
        let mut frame = Frame::new(40, 20);
        let marker = Rgb::new(255, 80, 64);
        frame.clear(marker);
        draw_tether(
            &mut frame,
            &viewport,
            &camera,
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 0.0),
            Rgb::WHITE,
            marker,
        );
        // A 3 × 3 core about the anchor's pixel (20, 10), a one-pixel black ring about it, and the
        // picture untouched beyond.
        for y in 8..=12u32 {
            for x in 18..=22u32 {
                let core = x.abs_diff(20) <= 1 && y.abs_diff(10) <= 1;
                let want = if core { marker } else { MARKER_OUTLINE };
                assert_eq!(frame.pixel(x, y), want, "({x}, {y})");
            }
        }
        assert_eq!(frame.pixel(17, 10), marker);
        assert_eq!(frame.pixel(20, 13), marker);
    }
}
