//! Debug drawing over a rendered frame: lines, arrows and dots given in world space, projected through
//! the same camera and viewport as the scene (the same `clip_from_world` and NDC → pixel map the
//! rasterizer and picking use), so a mark sits exactly on what it annotates in either projection.
//!
//! Marks are drawn on top of the scene at full colour, after supersampling (they stay crisp). Where a
//! mark lies behind a surface it is still drawn, but dashed (lines) or as a single pixel (dots), as
//! drafting shows hidden edges: the eye can tell front from back without blending colours, which would
//! not survive quantisation to 16 colours.

use glam::{Vec2, Vec3, Vec4};

use super::Frame;
use super::clip::NON_FINITE;
use super::line::for_each_line_pixel;
use super::post::ViewDepth;
use super::view::View;
use crate::color::Rgb;
use crate::geometry::{Camera, Viewport};

/// A segment between two world points; with `head`, an arrow pointing at `to`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverlayLine {
    /// World, m.
    pub from: Vec3,
    /// World, m.
    pub to: Vec3,
    pub color: Rgb,
    /// Draw an arrowhead at `to` (in screen space, so it reads at any angle).
    pub head: bool,
}

/// A dot at a world point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverlayDot {
    /// World, m.
    pub at: Vec3,
    pub color: Rgb,
    /// Left out where it would touch a spaced dot already drawn: marks that recur along a body
    /// (a chain's joints) stay apart instead of merging into a bar that hides what they mark.
    pub spaced: bool,
}

/// The twelve edges of an axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OverlayBox {
    /// World, m; `min ≤ max` on every axis.
    pub min: Vec3,
    pub max: Vec3,
    pub color: Rgb,
}

/// Marks to draw over one frame, in world space. Reused from frame to frame (clear, then push).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overlay {
    pub boxes: Vec<OverlayBox>,
    pub lines: Vec<OverlayLine>,
    pub dots: Vec<OverlayDot>,
}

/// Arrowhead side length, pixels, and half-angle (30°, as cos and sin).
const HEAD_PIXELS: f32 = 3.0;
const HEAD_COS: f32 = 0.866_025_4;
const HEAD_SIN: f32 = 0.5;
/// A mark is hidden where it is farther than the surface drawn at its pixel by more than this
/// fraction of the surface's view depth plus [`HIDDEN_SLACK_M`]: marks lying on a surface (contact
/// points, axis-aligned boxes' bounds) stay in front of it despite rounding and mesh facets.
const HIDDEN_FRACTION: f32 = 0.02;
const HIDDEN_SLACK_M: f32 = 0.02;

impl Overlay {
    /// Removes every mark, keeping the allocations.
    pub fn clear(&mut self) {
        self.boxes.clear();
        self.lines.clear();
        self.dots.clear();
    }

    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty() && self.lines.is_empty() && self.dots.is_empty()
    }

    pub fn line(&mut self, from: Vec3, to: Vec3, color: Rgb) {
        self.lines.push(OverlayLine {
            from,
            to,
            color,
            head: false,
        });
    }

    pub fn arrow(&mut self, from: Vec3, to: Vec3, color: Rgb) {
        self.lines.push(OverlayLine {
            from,
            to,
            color,
            head: true,
        });
    }

    pub fn dot(&mut self, at: Vec3, color: Rgb) {
        self.dots.push(OverlayDot {
            at,
            color,
            spaced: false,
        });
    }

    /// A dot that is left out where it would touch another spaced dot drawn before it (see
    /// [`OverlayDot::spaced`]).
    pub fn spaced_dot(&mut self, at: Vec3, color: Rgb) {
        self.dots.push(OverlayDot {
            at,
            color,
            spaced: true,
        });
    }

    /// The twelve edges of the axis-aligned box `[min, max]` (world).
    pub fn wire_box(&mut self, min: Vec3, max: Vec3, color: Rgb) {
        self.boxes.push(OverlayBox { min, max, color });
    }
}

/// Draws `overlay` over `frame`, which holds the scene `camera` saw through `viewport` (its depth
/// buffer decides what is hidden). Boxes and lines first, dots on top.
pub fn draw_overlay(frame: &mut Frame, viewport: &Viewport, camera: &Camera, overlay: &Overlay) {
    if overlay.is_empty()
        || viewport.is_empty()
        || frame.width() != viewport.width
        || frame.height() != viewport.height
    {
        return;
    }
    let view = View::new(camera, *viewport);
    let (pixels, depth, _) = frame.buffers_mut();
    let mut painter = Painter {
        view_depth: ViewDepth::new(camera),
        width: viewport.width,
        height: viewport.height,
        pixels,
        depth,
    };
    let project = |p: Vec3| {
        let clip = view.clip_from_world * p.extend(1.0);
        (clip, view.volume.outcode(clip))
    };
    for b in &overlay.boxes {
        // Each corner projected once, not once per edge (a pile of boxes has thousands of edges).
        let corners: [(Vec4, u8); 8] =
            std::array::from_fn(|i| project(box_corner(b.min, b.max, i)));
        for i in 0..8 {
            for bit in [1, 2, 4] {
                if i & bit == 0 {
                    painter.segment(&view, corners[i], corners[i | bit], b.color, false);
                }
            }
        }
    }
    for line in &overlay.lines {
        painter.segment(
            &view,
            project(line.from),
            project(line.to),
            line.color,
            line.head,
        );
    }
    // The corners of the spaced dots drawn so far, in pixels (a few dozen: a scene's joints).
    let mut spaced: Vec<(f32, f32)> = Vec::new();
    for dot in &overlay.dots {
        painter.dot(&view, dot, &mut spaced);
    }
}

/// Corner `i` of the box `[min, max]`: bit 0 picks x, bit 1 y, bit 2 z (0 = min, 1 = max).
fn box_corner(min: Vec3, max: Vec3, i: usize) -> Vec3 {
    Vec3::new(
        if i & 1 == 0 { min.x } else { max.x },
        if i & 2 == 0 { min.y } else { max.y },
        if i & 4 == 0 { min.z } else { max.z },
    )
}

/// The frame's colour and depth buffers, and how to tell a hidden mark.
struct Painter<'a> {
    view_depth: ViewDepth,
    width: u32,
    height: u32,
    pixels: &'a mut [Rgb],
    depth: &'a [f32],
}

impl Painter<'_> {
    /// Whether a mark at clip depth `z` on pixel `i` is behind the surface drawn there.
    fn hidden(&self, i: usize, z: f32) -> bool {
        let surface = self.depth[i];
        // Clip depth grows with view depth: in front of the surface needs no conversion.
        z > surface
            && surface.is_finite()
            && self.view_depth.of(z)
                > self.view_depth.of(surface) * (1.0 + HIDDEN_FRACTION) + HIDDEN_SLACK_M
    }

    /// The segment between two clip positions with their outcodes, clipped to the view; hidden
    /// parts dashed (two pixels on, two off, counted along the line); with `head`, an arrowhead at
    /// the second end.
    fn segment(&mut self, view: &View, a: (Vec4, u8), b: (Vec4, u8), color: Rgb, head: bool) {
        let ((ca, oa), (cb, ob)) = (a, b);
        if (oa | ob) & NON_FINITE != 0 || oa & ob != 0 {
            return;
        }
        let clipped = if oa | ob == 0 {
            Some((ca, cb))
        } else {
            view.volume.clip_segment(ca, cb, oa | ob)
        };
        let Some((ca, cb)) = clipped else {
            return;
        };
        let (sa, za) = view.to_screen(ca);
        let (sb, zb) = view.to_screen(cb);
        let (a, b) = (sa.extend(za), sb.extend(zb));
        let (w, h) = (self.width, self.height);
        let mut step = 0u32;
        for_each_line_pixel(a, b, w, h, |i, z| {
            if step % 4 < 2 || !self.hidden(i, z) {
                self.pixels[i] = color;
            }
            step += 1;
        });
        if head {
            let shaft = Vec2::new(b.x - a.x, b.y - a.y);
            let len = shaft.length();
            if len > 1.0 {
                let back = -shaft / len * HEAD_PIXELS.min(0.5 * len);
                for sign in [-1.0, 1.0] {
                    let side = Vec2::new(
                        back.x * HEAD_COS - sign * back.y * HEAD_SIN,
                        sign * back.x * HEAD_SIN + back.y * HEAD_COS,
                    );
                    let end = Vec3::new(b.x + side.x, b.y + side.y, b.z);
                    for_each_line_pixel(b, end, w, h, |i, _| self.pixels[i] = color);
                }
            }
        }
    }

    /// A 2 × 2 dot, or a single pixel where it is hidden.
    fn dot(&mut self, view: &View, dot: &OverlayDot, spaced: &mut Vec<(f32, f32)>) {
        let clip = view.clip_from_world * dot.at.extend(1.0);
        if view.volume.outcode(clip) != 0 {
            return;
        }
        let (w, h) = (self.width as f32, self.height as f32);
        let (p, z) = view.to_screen(clip);
        let (x, y) = (p.x.floor(), p.y.floor());
        if !(x >= 0.0 && y >= 0.0 && x < w && y < h) {
            return;
        }
        if dot.spaced {
            // Two 2 × 2 squares touch when their corners are under 3 pixels apart on both axes.
            let corner = ((p.x - 0.5).floor(), (p.y - 0.5).floor());
            let touches =
                |&(cx, cy): &(f32, f32)| (cx - corner.0).abs() < 3.0 && (cy - corner.1).abs() < 3.0;
            if spaced.iter().any(touches) {
                return;
            }
            spaced.push(corner);
        }
        let centre = y as usize * self.width as usize + x as usize;
        if self.hidden(centre, z) {
            self.pixels[centre] = dot.color;
            return;
        }
        // A 2 × 2 square whose corner nearest the point is its pixel: one terminal cell across two
        // columns, so a dot reads as a dot and not as half a cell.
        let (x0, y0) = ((p.x - 0.5).floor(), (p.y - 0.5).floor());
        for dy in 0..2 {
            for dx in 0..2 {
                let (px, py) = (x0 + dx as f32, y0 + dy as f32);
                if px >= 0.0 && py >= 0.0 && px < w && py < h {
                    self.pixels[py as usize * self.width as usize + px as usize] = dot.color;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Projection;

    fn camera(projection: Projection) -> Camera {
        Camera {
            projection,
            ..Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0)
        }
    }

    /// The pixel a world point projects to, by the viewport's map.
    fn pixel_of(camera: &Camera, viewport: &Viewport, p: Vec3) -> (u32, u32) {
        let clip = camera.clip_from_world(viewport.aspect()) * p.extend(1.0);
        let px = viewport.pixel_from_ndc(Vec2::new(clip.x / clip.w, clip.y / clip.w));
        (px.x as u32, px.y as u32)
    }

    #[test]
    fn a_dot_lands_on_the_pixel_its_point_projects_to_in_both_projections() {
        let viewport = Viewport::new(64, 48, 1.0);
        for projection in [
            Projection::Perspective { fov_y: 1.0 },
            Projection::Orthographic { view_height: 8.0 },
        ] {
            let camera = camera(projection);
            let mut frame = Frame::new(64, 48);
            let mut overlay = Overlay::default();
            let p = Vec3::new(1.3, -0.7, 0.4);
            let red = Rgb::new(255, 0, 0);
            overlay.dot(p, red);
            draw_overlay(&mut frame, &viewport, &camera, &overlay);
            let (x, y) = pixel_of(&camera, &viewport, p);
            assert_eq!(frame.pixel(x, y), red, "{projection:?}");
            let painted = frame.pixels().iter().filter(|&&c| c == red).count();
            assert_eq!(painted, 4, "a 2 × 2 dot: {projection:?}");
        }
    }

    /// Spaced dots that would touch (a chain's joints seen from afar) are thinned to the first of
    /// them; plain dots (contact points) are all drawn.
    #[test]
    fn spaced_dots_that_would_touch_are_thinned_and_plain_ones_are_not() {
        let viewport = Viewport::new(64, 48, 1.0);
        let camera = camera(Projection::Perspective { fov_y: 1.0 });
        let red = Rgb::new(255, 0, 0);
        // A column of points 4.4 pixels apart, and one 1.3 pixels below the first.
        let points = [0.0f32, -0.3, -1.0, -2.0].map(|y| Vec3::new(0.0, y, 0.0));
        let painted = |spaced: bool| {
            let mut frame = Frame::new(64, 48);
            let mut overlay = Overlay::default();
            for p in points {
                if spaced {
                    overlay.spaced_dot(p, red);
                } else {
                    overlay.dot(p, red);
                }
            }
            draw_overlay(&mut frame, &viewport, &camera, &overlay);
            frame.pixels().iter().filter(|&&c| c == red).count()
        };
        // Three 2 × 2 dots spaced: the second point's is left out.
        assert_eq!(painted(true), 12);
        // Plain: the first two overlap but both are drawn.
        assert!(painted(false) > 12);
    }

    #[test]
    fn a_line_joins_the_pixels_of_its_ends_and_an_arrow_adds_a_head() {
        let viewport = Viewport::new(64, 48, 1.0);
        let camera = camera(Projection::Perspective { fov_y: 1.0 });
        let (from, to) = (Vec3::new(-2.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0));
        let green = Rgb::new(0, 255, 0);
        let count = |head: bool| {
            let mut frame = Frame::new(64, 48);
            let mut overlay = Overlay::default();
            if head {
                overlay.arrow(from, to, green);
            } else {
                overlay.line(from, to, green);
            }
            draw_overlay(&mut frame, &viewport, &camera, &overlay);
            for p in [from, to] {
                let (x, y) = pixel_of(&camera, &viewport, p);
                let near = (x.saturating_sub(1)..=x + 1)
                    .any(|x| (y.saturating_sub(1)..=y + 1).any(|y| frame.pixel(x, y) == green));
                assert!(near, "{p} not drawn");
            }
            frame.pixels().iter().filter(|&&c| c == green).count()
        };
        let plain = count(false);
        assert!(count(true) > plain);
    }

    #[test]
    fn marks_behind_the_camera_or_with_nan_draw_nothing() {
        let viewport = Viewport::new(32, 32, 1.0);
        let camera = camera(Projection::Perspective { fov_y: 1.0 });
        let mut frame = Frame::new(32, 32);
        let mut overlay = Overlay::default();
        let white = Rgb::WHITE;
        overlay.dot(Vec3::new(0.0, 0.0, -20.0), white);
        overlay.line(
            Vec3::new(0.0, 0.0, -20.0),
            Vec3::new(1.0, 0.0, -30.0),
            white,
        );
        overlay.line(Vec3::NAN, Vec3::ZERO, white);
        draw_overlay(&mut frame, &viewport, &camera, &overlay);
        assert!(frame.pixels().iter().all(|&c| c == Rgb::BLACK));
    }
}
