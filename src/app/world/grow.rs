//! `<` and `>`: shrink or grow the selected body by 10 % per press, at the same density.
//!
//! A press does not jump to the new size: the body's surface moves at most [`GROWTH_SPEED`], so a
//! body grown into its neighbours overlaps them by millimetres a step, which the contacts push out
//! gently (a 1 m box grown 10 % at once into the stack above it overlapped 5 cm in one step, and a
//! held key threw the boxes above it at over 3 m/s).

use crate::app::App;
use crate::geometry::Shape;
use crate::physics::limits;

/// Size change per press.
pub const RESIZE_FACTOR: f32 = 1.1;
/// Fastest a growth body's surface moves, m/s (a held key asks for more; the body follows at
/// this pace).
pub const GROWTH_SPEED: f32 = 0.25;

/// A change of size in progress: the body is on its way to `to`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Growth {
    pub body: crate::physics::BodyId,
    pub to: Shape,
}

/// Half the largest size of a shape, m.
fn reach(shape: &Shape) -> f32 {
    match *shape {
        Shape::Cuboid { half_extents } => half_extents.max_element(),
        Shape::Sphere { radius } => radius,
    }
}

/// The shape one step of `dt_s` gives on the way from `current` to `to` (the same kind, scaled
/// uniformly), the surface moving at most [`GROWTH_SPEED`]; exactly `to` once within reach.
pub fn size_step(current: &Shape, to: &Shape, dt_s: f32) -> Shape {
    let (now, target) = (reach(current), reach(to));
    let most = GROWTH_SPEED * dt_s;
    if (target - now).abs() <= most {
        return *to;
    }
    let factor = (now + most.copysign(target - now)) / now;
    match *current {
        Shape::Cuboid { half_extents } => Shape::cuboid(half_extents * factor),
        Shape::Sphere { radius } => Shape::sphere(radius * factor),
    }
}

/// Smallest and largest size, m: a box's shortest and longest edge, a ball's diameter.
pub const MIN_SIZE: f32 = 0.05;
pub const MAX_SIZE: f32 = 20.0;

/// `shape` scaled by `factor`, the factor cut so that its smallest size stays at or above
/// [`MIN_SIZE`] and its largest at or below [`MAX_SIZE`]; `None` when it is at the limit already.
/// A body a scene file made smaller or larger than these (files may go from 1 mm to 2 km) only
/// moves toward them: shrinking never grows it, growing never shrinks it.
pub fn resized(shape: &Shape, factor: f32) -> Option<Shape> {
    let (smallest, largest) = match *shape {
        Shape::Cuboid { half_extents } => (
            2.0 * half_extents.min_element(),
            2.0 * half_extents.max_element(),
        ),
        Shape::Sphere { radius } => (2.0 * radius, 2.0 * radius),
    };
    let factor = if factor < 1.0 {
        factor.max(MIN_SIZE / smallest).min(1.0)
    } else {
        factor.min(MAX_SIZE / largest).max(1.0)
    };
    if (factor - 1.0).abs() < 1e-6 {
        return None;
    }
    Some(match *shape {
        Shape::Cuboid { half_extents } => Shape::cuboid(half_extents * factor),
        Shape::Sphere { radius } => Shape::sphere(radius * factor),
    })
}

impl App {
    /// Grows (`larger`) or shrinks the selected body, at [`GROWTH_SPEED`] over the next steps (a
    /// press during a resize of the same body goes on from its target).
    pub(crate) fn grow_selected(&mut self, larger: bool) {
        let Some(id) = self.selection.selected() else {
            self.say("click a body first to select it");
            return;
        };
        let name = self.body_name(id);
        let factor = if larger {
            RESIZE_FACTOR
        } else {
            1.0 / RESIZE_FACTOR
        };
        let from = match self.growth {
            Some(r) if r.body == id => r.to,
            _ => *self.world.body(id).shape(),
        };
        let body = self.world.body(id);
        let mass_of = |to: &Shape| body.mass() * to.volume() / body.shape().volume();
        // The masses physics handles bound a resize too (a 1 m box of 1,000 t grows past them);
        // scenery never moves, so its nominal mass does not matter.
        let scenery = self.looks.get(id.index()).is_some_and(|l| l.scenery);
        let Some(to) = resized(&from, factor)
            .filter(|to| scenery || (limits::MIN_MASS..=limits::MAX_MASS).contains(&mass_of(to)))
        else {
            self.say(format!(
                "{name} is as {} as it gets",
                if larger { "large" } else { "small" }
            ));
            return;
        };
        let mass = mass_of(&to);
        self.growth = Some(Growth { body: id, to });
        let size = match to {
            Shape::Cuboid { half_extents } => format!("{:.2} m", 2.0 * half_extents.max_element()),
            Shape::Sphere { radius } => format!("{:.2} m across", 2.0 * radius),
        };
        self.say(format!(
            "{name}: {size}, {}",
            crate::app::panels::mass_text::mass(mass)
        ));
    }

    /// Before a step: the next step of a resize in progress.
    pub(crate) fn grow_step(&mut self) {
        let Some(r) = &mut self.growth else {
            return;
        };
        if r.body.index() >= self.world.len() {
            self.growth = None;
            return;
        }
        let dt = self.world.settings().dt;
        let shape = size_step(self.world.body(r.body).shape(), &r.to, dt);
        let done = shape == r.to;
        self.world.set_shape(r.body, shape);
        if done {
            self.growth = None;
        }
    }

    /// Whether a resize is in progress (the app keeps drawing).
    pub fn is_growing(&self) -> bool {
        self.growth.is_some()
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

    #[test]
    fn a_resize_keeps_the_mass_within_what_physics_handles() {
        let text = "[[body]]\nshape = \"box\"\nhalf_extents = [0.5, 0.5, 0.5]\nposition = [0, 1, 0]\n\
                    mass = 1e6\n";
        let scene = crate::scene::file::parse(text, "heavy").unwrap();
        let mut app = App::new(scene, crate::app::AppConfig::default());
        app.selection.select(crate::physics::BodyId(0));
        app.grow_selected(true);
        assert_eq!(app.growth, None, "{}", app.message());
        assert!(
            app.message().contains("as large as it gets"),
            "{}",
            app.message()
        );
        app.grow_selected(false);
        assert!(app.growth.is_some(), "{}", app.message());
    }

    #[test]
    fn a_body_beyond_the_sizes_only_moves_toward_them() {
        // A 2 cm ball from a scene file: `<` used to grow it to 5 cm.
        assert_eq!(resized(&Shape::sphere(0.01), 1.0 / RESIZE_FACTOR), None);
        assert!(radius(resized(&Shape::sphere(0.01), RESIZE_FACTOR)) > 0.01);
        // A 2 km plate 2 mm thick: `>` used to cut it to 20 m and 0.02 mm, below the smallest
        // size physics handles (`physics::limits::MIN_SIZE`).
        let plate = Shape::cuboid(Vec3::new(1000.0, 0.001, 1000.0));
        assert_eq!(resized(&plate, RESIZE_FACTOR), None);
        assert_eq!(
            resized(&plate, 1.0 / RESIZE_FACTOR),
            None,
            "its thinnest side is below 5 cm"
        );
    }
}
