//! Scenes built by code, shared by the built-in scenes, the hard-case tests and `nudge bench`.

use glam::{Quat, Vec3};

use super::{Scene, SceneBody};
use crate::color::Rgb;
use crate::geometry::{Camera, Pose, Shape};
use crate::physics::{BodyDesc, Settings};

/// Colour of floors and walls.
pub const FLOOR_COLOR: Rgb = Rgb::new(0x80, 0x84, 0x88);
/// Colours handed to dynamic bodies in turn.
pub const PALETTE: [Rgb; 6] = [
    Rgb::new(0xc0, 0x80, 0x40),
    Rgb::new(0xd0, 0x50, 0x40),
    Rgb::new(0x40, 0x90, 0xd0),
    Rgb::new(0x60, 0xb0, 0x50),
    Rgb::new(0xe0, 0xc0, 0x40),
    Rgb::new(0xa0, 0x60, 0xc0),
];

/// A static slab whose top face is at y = 0.
pub fn floor(half_width: f32) -> SceneBody {
    SceneBody {
        desc: BodyDesc::fixed(
            Shape::cuboid(Vec3::new(half_width, 0.5, half_width)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ),
        color: FLOOR_COLOR,
    }
}

/// A dynamic unit-density body of the given shape at `position`.
pub fn dynamic(shape: Shape, position: Vec3, color: Rgb) -> SceneBody {
    SceneBody {
        desc: BodyDesc::dynamic(shape, Pose::from_position(position), shape.volume()),
        color,
    }
}

/// A 2D pyramid of unit boxes (half-extent 0.5) standing on the floor: `base` boxes in the bottom row,
/// one fewer in each row above (base 20 → 210 boxes). Boxes in a row are 5 cm apart.
pub fn pyramid(base: usize) -> Scene {
    let mut bodies = vec![floor(40.0)];
    let spacing = 1.05;
    for row in 0..base {
        let count = base - row;
        let y = 0.5 + row as f32;
        let x0 = -0.5 * spacing * (count as f32 - 1.0);
        for i in 0..count {
            let x = x0 + spacing * i as f32;
            let color = PALETTE[(row + i) % PALETTE.len()];
            bodies.push(dynamic(
                Shape::cuboid(Vec3::splat(0.5)),
                Vec3::new(x, y, 0.0),
                color,
            ));
        }
    }
    let height = base as f32;
    Scene {
        name: format!("pyramid({base})"),
        settings: Settings::default(),
        camera: Camera::perspective(
            Vec3::new(0.0, 0.45 * height, -1.25 * height - 4.0),
            Vec3::new(0.0, 0.4 * height, 0.0),
            70f32.to_radians(),
        ),
        bodies,
    }
}

/// `count` boxes and spheres (half-size 0.4) in a jittered grid above a 39 m × 39 m pit with 4 m walls,
/// ready to rain down. Deterministic for a given count.
pub fn rain(count: usize) -> Scene {
    let pit_half = 19.5;
    let wall_half_height = 2.0;
    let wall_half_thickness = 0.5;
    let mut bodies = vec![floor(pit_half + 2.0 * wall_half_thickness)];
    for (axis, side) in [(0, -1.0), (0, 1.0), (2, -1.0), (2, 1.0)] {
        let mut half = Vec3::new(wall_half_thickness, wall_half_height, pit_half);
        let mut center = Vec3::new(
            side * (pit_half + wall_half_thickness),
            wall_half_height,
            0.0,
        );
        if axis == 2 {
            half = Vec3::new(pit_half, wall_half_height, wall_half_thickness);
            center = Vec3::new(
                0.0,
                wall_half_height,
                side * (pit_half + wall_half_thickness),
            );
        }
        bodies.push(SceneBody {
            desc: BodyDesc::fixed(Shape::cuboid(half), Pose::from_position(center)),
            color: FLOOR_COLOR,
        });
    }

    let spacing = 1.0;
    let per_row = ((2.0 * pit_half - 1.0) / spacing) as usize; // 38
    let per_layer = per_row * per_row;
    let mut rng = SplitMix64(0x6e75_6467_6521);
    for i in 0..count {
        let layer = i / per_layer;
        let in_layer = i % per_layer;
        let (row, col) = (in_layer / per_row, in_layer % per_row);
        let jitter = Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed()) * 0.08;
        let position = Vec3::new(
            -pit_half + 1.0 + col as f32 * spacing,
            2.0 + layer as f32 * spacing * 1.2,
            -pit_half + 1.0 + row as f32 * spacing,
        ) + jitter;
        let shape = if i % 2 == 0 {
            Shape::cuboid(Vec3::splat(0.4))
        } else {
            Shape::sphere(0.4)
        };
        let axis = Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed())
            .try_normalize()
            .unwrap_or(Vec3::Y);
        let rotation = Quat::from_axis_angle(axis, rng.next_signed() * std::f32::consts::PI);
        let mut body = dynamic(shape, position, PALETTE[i % PALETTE.len()]);
        body.desc.pose.rotation = rotation;
        bodies.push(body);
    }
    Scene {
        name: format!("rain({count})"),
        settings: Settings::default(),
        camera: Camera::perspective(
            Vec3::new(0.0, 30.0, -42.0),
            Vec3::new(0.0, 0.0, 0.0),
            70f32.to_radians(),
        ),
        bodies,
    }
}

/// A small deterministic generator (SplitMix64) so scenes and tests need no `rand` dependency.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn next_unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32
    }

    /// Uniform in [-1, 1).
    pub fn next_signed(&mut self) -> f32 {
        2.0 * self.next_unit() - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pyramid_with_base_20_has_210_boxes_and_a_floor() {
        assert_eq!(pyramid(20).bodies.len(), 211);
    }

    #[test]
    fn rain_holds_exactly_the_bodies_asked_for_plus_pit() {
        assert_eq!(rain(1000).bodies.len(), 1005);
        assert_eq!(rain(1000), rain(1000));
    }
}
