//! What the renderer draws: a shape at a pose with a look, and nothing of physics.

use crate::color::Rgb;
use crate::geometry::{Pose, Shape};

/// Surface pattern used by [`crate::render::RenderMode::Textured`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Material {
    /// Procedural wood grain (solid texture in body space) with darkened face borders; for boxes.
    Wood,
    /// 1 m checker squares in body space; for floors.
    Checker,
    /// Uniform colour (spheres still get faint stripes so their spin shows).
    #[default]
    Plain,
}

/// One thing to draw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drawable {
    /// Size and kind; drawables whose shape is not [`Shape::is_valid`] are skipped.
    pub shape: Shape,
    /// `world_from_body`; drawables with a non-finite pose are skipped.
    pub pose: Pose,
    /// Base colour before lighting.
    pub color: Rgb,
    /// Pattern in textured mode.
    pub material: Material,
    /// Written to the id buffer where this drawable is visible; must differ from
    /// [`crate::render::Frame::NO_ID`]. Usually the body index.
    pub id: u32,
    /// Drawn brighter and outlined (the selection).
    pub highlighted: bool,
    /// Drawn with an icy blue tint (a frozen, i.e. static-by-user, body).
    pub frozen: bool,
    /// Drawn slightly dimmed (a sleeping body).
    pub asleep: bool,
    /// Is drawn into the shadow map: darkens the drawables behind it along the key light.
    pub casts_shadow: bool,
    /// Is darkened where another drawable casting shadows stands between it and the key light.
    pub receives_shadow: bool,
}

impl Drawable {
    /// A plain drawable that casts and receives shadows, with no state flags set.
    pub fn new(shape: Shape, pose: Pose, color: Rgb, id: u32) -> Self {
        Self {
            shape,
            pose,
            color,
            material: Material::Plain,
            id,
            highlighted: false,
            frozen: false,
            asleep: false,
            casts_shadow: true,
            receives_shadow: true,
        }
    }

    /// True when the shape and pose are finite and sane, i.e. the renderer will draw it.
    pub fn is_drawable(&self) -> bool {
        self.shape.is_valid() && self.pose.is_finite() && self.id != u32::MAX
    }
}
