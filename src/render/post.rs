//! Whole-image passes after rasterization: depth to grey, 2× box filter, selection outline (shadows
//! are their own pass, [`super::shadow`]).

use glam::Vec3;

use super::Frame;
use crate::color::Rgb;
use crate::geometry::{Camera, Projection};

/// Converts clip depth in [0, 1] back to view depth (distance along the view direction, metres).
///
/// glam's `perspective_rh`: `z = f/(f−n) (1 − n/d)`, so `d = n / (1 − z (f−n)/f)`;
/// `orthographic_rh`: `z = (d − n)/(f − n)`, so `d = n + z (f − n)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewDepth {
    near: f32,
    far: f32,
    perspective: bool,
}

impl ViewDepth {
    /// The conversion for `camera`'s projection and near/far planes.
    pub fn new(camera: &Camera) -> Self {
        Self {
            near: camera.near,
            far: camera.far,
            perspective: matches!(camera.projection, Projection::Perspective { .. }),
        }
    }

    /// View depth in metres of a finite clip depth `z`.
    #[inline]
    pub fn of(&self, z: f32) -> f32 {
        if self.perspective {
            self.near / (1.0 - z * (self.far - self.near) / self.far).max(1e-9)
        } else {
            self.near + z * (self.far - self.near)
        }
    }
}

/// Paints covered pixels grey by view depth, nearest = bright, on a log scale normalised to the depth
/// range present in the frame (so the scene always spans the grey scale, and a long floor does not
/// flatten everything standing on it); background pixels keep their colour.
pub fn depth_to_grey(frame: &mut Frame, view_depth: ViewDepth) {
    let (pixels, depth, ids) = frame.buffers_mut();
    // Clip depth grows with view depth, so the extremes can be found on the raw buffer.
    let (mut z_lo, mut z_hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for (&z, &id) in depth.iter().zip(ids.iter()) {
        if id != Frame::NO_ID && z.is_finite() {
            z_lo = z_lo.min(z);
            z_hi = z_hi.max(z);
        }
    }
    let log_depth = |z: f32| view_depth.of(z).max(1e-6).ln();
    let (lo, hi) = (log_depth(z_lo), log_depth(z_hi));
    let scale = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
    for ((p, &z), &id) in pixels.iter_mut().zip(depth.iter()).zip(ids.iter()) {
        if id != Frame::NO_ID && z.is_finite() {
            let t = (log_depth(z) - lo) * scale;
            let g = 1.0 - 0.85 * t;
            *p = Rgb::from_unit([g, g, g]);
        }
    }
}

/// Averages each 2 × 2 block of `hi` (of size 2w × 2h) into the pixel of `lo` (w × h). Only colours:
/// depth and ids of `lo` are left untouched.
pub fn box_filter_2x(hi: &Frame, lo: &mut Frame) {
    let (w, h) = (lo.width() as usize, lo.height() as usize);
    if hi.width() as usize != 2 * w || hi.height() as usize != 2 * h {
        return;
    }
    let src = hi.pixels();
    let (dst, _, _) = lo.buffers_mut();
    for y in 0..h {
        let top = &src[2 * y * 2 * w..(2 * y + 1) * 2 * w];
        let bottom = &src[(2 * y + 1) * 2 * w..(2 * y + 2) * 2 * w];
        for (x, out) in dst[y * w..(y + 1) * w].iter_mut().enumerate() {
            let q = [top[2 * x], top[2 * x + 1], bottom[2 * x], bottom[2 * x + 1]];
            let avg =
                |c: fn(&Rgb) -> u8| ((q.iter().map(|p| c(p) as u16).sum::<u16>() + 2) / 4) as u8;
            *out = Rgb::new(avg(|p| p.r), avg(|p| p.g), avg(|p| p.b));
        }
    }
}

/// Paints `color` on every pixel of a highlighted drawable (id in `highlighted`) that has a 4-neighbour
/// showing something else: an outline just inside the silhouette.
pub fn outline(frame: &mut Frame, highlighted: &[u32], color: Rgb) {
    if highlighted.is_empty() {
        return;
    }
    let (w, h) = (frame.width() as usize, frame.height() as usize);
    let (pixels, _, ids) = frame.buffers_mut();
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let id = ids[i];
            if id == Frame::NO_ID || !highlighted.contains(&id) {
                continue;
            }
            let differs = (x > 0 && ids[i - 1] != id)
                || (x + 1 < w && ids[i + 1] != id)
                || (y > 0 && ids[i - w] != id)
                || (y + 1 < h && ids[i + w] != id);
            if differs {
                pixels[i] = color;
            }
        }
    }
}

/// Colour of a unit normal: `rgb = n / 2 + 1/2`.
#[inline]
pub fn normal_color(n: Vec3) -> Rgb {
    let c = n * 0.5 + Vec3::splat(0.5);
    Rgb::from_unit(c.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn view_depth_inverts_the_projection() {
        for projection in [
            Projection::Perspective { fov_y: 1.0 },
            Projection::Orthographic { view_height: 4.0 },
        ] {
            let camera = Camera {
                projection,
                near: 0.1,
                far: 100.0,
                ..Camera::perspective(Vec3::ZERO, Vec3::NEG_Z, 1.0)
            };
            let clip_from_world = camera.clip_from_world(1.0);
            let vd = ViewDepth::new(&camera);
            for d in [0.1f32, 1.0, 7.5, 99.0] {
                let c = clip_from_world * Vec3::new(0.0, 0.0, -d).extend(1.0);
                let back = vd.of(c.z / c.w);
                assert!((back - d).abs() < 1e-3 * d, "{projection:?}: {d} -> {back}");
            }
        }
    }

    #[test]
    fn box_filter_averages_blocks() {
        let mut hi = Frame::new(2, 2);
        hi.clear(Rgb::WHITE);
        let mut lo = Frame::new(1, 1);
        {
            let (p, _, _) = hi.buffers_mut();
            p[0] = Rgb::BLACK;
            p[1] = Rgb::BLACK;
        }
        box_filter_2x(&hi, &mut lo);
        assert_eq!(lo.pixel(0, 0), Rgb::new(128, 128, 128));
    }
}
