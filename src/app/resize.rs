//! `<` and `>`: shrink or grow the selected body by 10 % per press, at the same density.

use super::App;
use crate::geometry::Shape;

/// Size change per press.
pub const RESIZE_FACTOR: f32 = 1.1;
/// Smallest and largest size, m: a box's shortest and longest edge, a ball's diameter.
pub const MIN_SIZE: f32 = 0.05;
pub const MAX_SIZE: f32 = 20.0;

/// `shape` scaled by `factor`, the factor cut so that its smallest size stays at or above
/// [`MIN_SIZE`] and its largest at or below [`MAX_SIZE`]; `None` when it is at the limit already.
pub fn resized(shape: &Shape, factor: f32) -> Option<Shape> {
    let (smallest, largest) = match *shape {
        Shape::Cuboid { half_extents } => (
            2.0 * half_extents.min_element(),
            2.0 * half_extents.max_element(),
        ),
        Shape::Sphere { radius } => (2.0 * radius, 2.0 * radius),
    };
    let factor = factor.max(MIN_SIZE / smallest).min(MAX_SIZE / largest);
    if (factor - 1.0).abs() < 1e-6 {
        return None;
    }
    Some(match *shape {
        Shape::Cuboid { half_extents } => Shape::cuboid(half_extents * factor),
        Shape::Sphere { radius } => Shape::sphere(radius * factor),
    })
}

impl App {
    /// Grows (`grow`) or shrinks the selected body; the world wakes it and its neighbours, which a
    /// grown body pushes out at the contacts' limited push-out speed.
    pub(crate) fn resize_selected(&mut self, grow: bool) {
        let Some(id) = self.selected else {
            self.say("click a body first to select it");
            return;
        };
        let name = self.body_name(id);
        let factor = if grow {
            RESIZE_FACTOR
        } else {
            1.0 / RESIZE_FACTOR
        };
        let Some(shape) = resized(self.world.body(id).shape(), factor) else {
            self.say(format!(
                "{name} is as {} as it gets",
                if grow { "large" } else { "small" }
            ));
            return;
        };
        self.world.set_shape(id, shape);
        let size = match shape {
            Shape::Cuboid { half_extents } => format!("{:.2} m", 2.0 * half_extents.max_element()),
            Shape::Sphere { radius } => format!("{:.2} m across", 2.0 * radius),
        };
        let mass = self.world.body(id).mass();
        self.say(format!("{name}: {size}, {mass:.3} kg"));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn radius(shape: Option<Shape>) -> f32 {
        match shape {
            Some(Shape::Sphere { radius }) => radius,
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn sizes_stop_at_five_centimetres_and_twenty_metres() {
        // 5.2 cm across shrinks to the 5 cm floor, not below; at the floor it stays.
        let shrunk = radius(resized(&Shape::sphere(0.026), 1.0 / RESIZE_FACTOR));
        assert!((shrunk - 0.025).abs() < 1e-7, "{shrunk}");
        assert_eq!(resized(&Shape::sphere(0.025), 1.0 / RESIZE_FACTOR), None);
        // A 19 m slab grows to 20 m, keeping its proportions.
        let Some(Shape::Cuboid { half_extents }) =
            resized(&Shape::cuboid(Vec3::new(9.5, 0.5, 1.0)), RESIZE_FACTOR)
        else {
            panic!("a box stays a box");
        };
        assert!(
            (half_extents - Vec3::new(10.0, 0.5 * 20.0 / 19.0, 20.0 / 19.0))
                .abs()
                .max_element()
                < 1e-5
        );
        assert_eq!(
            resized(&Shape::cuboid(Vec3::new(10.0, 1.0, 1.0)), RESIZE_FACTOR),
            None
        );
        // In between, 10 % a press.
        let Some(Shape::Cuboid { half_extents }) =
            resized(&Shape::cuboid(Vec3::splat(0.5)), RESIZE_FACTOR)
        else {
            panic!("a box stays a box");
        };
        assert!((half_extents - Vec3::splat(0.55)).abs().max_element() < 1e-6);
    }
}
