//! How each body of the world is drawn: the bridge from physics bodies to the renderer's `Drawable`s.

use crate::color::Rgb;
use crate::geometry::Shape;
use crate::physics::{BodyId, World};
use crate::render::{Drawable, Material};

/// Per-body appearance that the world does not know about.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyLook {
    pub color: Rgb,
    /// Static in the scene file (floors, walls, ramps), as opposed to frozen (at run time, or
    /// `frozen = true` in the file).
    pub scenery: bool,
}

impl BodyLook {
    /// The looks of a scene's bodies, in body order.
    pub fn of_scene(scene: &crate::scene::Scene) -> Vec<BodyLook> {
        scene
            .bodies
            .iter()
            .map(|b| BodyLook {
                color: b.color,
                scenery: b.desc.is_static && !b.frozen,
            })
            .collect()
    }
}

/// Fills `out` with one drawable per body, in body order (drawable id = body index).
pub fn drawables(
    world: &World,
    looks: &[BodyLook],
    highlighted: Option<BodyId>,
    out: &mut Vec<Drawable>,
) {
    out.clear();
    for (i, body) in world.bodies().iter().enumerate() {
        let look = looks.get(i);
        let scenery = look.is_some_and(|l| l.scenery);
        let material = match body.shape() {
            Shape::Cuboid { .. } if scenery => Material::Checker,
            Shape::Cuboid { .. } => Material::Wood,
            Shape::Sphere { .. } => Material::Plain,
        };
        out.push(Drawable {
            shape: *body.shape(),
            pose: *body.pose(),
            color: look.map_or(Rgb::WHITE, |l| l.color),
            material,
            id: i as u32,
            highlighted: highlighted == Some(BodyId(i as u32)),
            frozen: body.is_static() && !scenery,
            asleep: body.is_sleeping(),
            casts_shadow: true,
            receives_shadow: true,
        });
    }
}
