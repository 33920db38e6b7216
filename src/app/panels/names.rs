//! What the status bar says about bodies. It calls a body by its name in the scene file where it
//! has one (`name = "bob"`), else "box #3" and "sphere #4" for what moves, and for the scenery
//! what it is — "floor", "wall #2", "ramp" — instead of "box #0".

use crate::app::App;
use crate::geometry::{Pose, Shape};
use crate::physics::BodyId;

/// What a static body of the scene is, from its shape and pose: a tilted box is a ramp, a flat wide
/// slab a floor, an upright thin one a wall, anything else a block (a static ball is a ball).
pub fn scenery_kind(shape: &Shape, pose: &Pose) -> &'static str {
    let Shape::Cuboid { half_extents: h } = *shape else {
        return "ball";
    };
    // Tilted: some box axis is neither level nor upright (more than a degree off).
    let up = pose.rotation * glam::Vec3::Y;
    if up.y.abs() < 1.0f32.to_radians().cos() {
        return "ramp";
    }
    let thinnest = h.x.min(h.z);
    if h.y <= 0.25 * thinnest {
        "floor"
    } else if h.y >= thinnest {
        "wall"
    } else {
        "block"
    }
}

impl App {
    /// Name of a body for messages: its name in the scene file if it has one ("bob"), else "box #3",
    /// "sphere #4", "floor", "wall #2", "ramp".
    pub(crate) fn body_name(&self, id: BodyId) -> String {
        if let Some(name) = self.scene_name_of(id) {
            return name.to_owned();
        }
        let body = self.world.body(id);
        let scenery = self.looks.get(id.index()).is_some_and(|l| l.scenery);
        if scenery {
            let kind = scenery_kind(body.shape(), body.pose());
            // There is one of most scenery; several walls are told apart by number.
            let alike = (0..self.world.len())
                .map(|i| BodyId(i as u32))
                .filter(|&other| {
                    self.looks.get(other.index()).is_some_and(|l| l.scenery)
                        && scenery_kind(
                            self.world.body(other).shape(),
                            self.world.body(other).pose(),
                        ) == kind
                })
                .count();
            return if alike > 1 {
                format!("{kind} #{}", id.0)
            } else {
                kind.to_string()
            };
        }
        let kind = match body.shape() {
            Shape::Cuboid { .. } => "box",
            Shape::Sphere { .. } => "sphere",
        };
        format!("{kind} #{}", id.0)
    }

    /// The name the scene file gives body `id`, if any (bodies added at run time have none).
    pub(crate) fn scene_name_of(&self, id: BodyId) -> Option<&str> {
        self.scene.bodies.get(id.index())?.name.as_deref()
    }

    /// Everything came to rest: a message about a push, pull or nudge no longer describes what
    /// the screen shows ("pushing box #2" used to stay on an idle scene), so the hint returns.
    pub(crate) fn came_to_rest(&mut self) {
        let stale = [
            "pushing ",
            "pulling ",
            "stopped pushing ",
            "stopped pulling ",
            "nudged ",
        ];
        if stale.iter().any(|s| self.message.starts_with(s)) {
            self.say("? for help");
        }
    }

    /// With `--hover`, what the pointer is over: "box #2 · 5.0 kg" (scenery by name alone).
    pub(crate) fn pointing_at(&self) -> Option<String> {
        if !self.config.hover {
            return None;
        }
        let id = self
            .selection
            .highlighted()
            .filter(|id| id.index() < self.world.len())?;
        let name = self.body_name(id);
        let scenery = self.looks.get(id.index()).is_some_and(|l| l.scenery);
        Some(if scenery {
            format!("under the pointer: {name}")
        } else {
            let mass = self.world.body(id).mass();
            format!(
                "under the pointer: {name} · {}",
                crate::app::panels::mass_text::mass(mass)
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::AppConfig;
    use crate::scene;

    fn names(scene_name: &str) -> Vec<String> {
        let app = App::new(scene::load(scene_name).unwrap(), AppConfig::default());
        (0..app.world().len())
            .map(|i| app.body_name(BodyId(i as u32)))
            .collect()
    }

    #[test]
    fn scenery_is_called_what_it_is_and_moving_bodies_by_shape_and_number() {
        assert_eq!(
            names("default"),
            [
                "floor",
                "box #1",
                "box #2",
                "sphere #3",
                "sphere #4",
                "wall #5",
                "wall #6",
                "wall #7",
                "wall #8"
            ]
        );
        let ramp = names("ramp");
        assert_eq!(ramp[0], "floor");
        assert_eq!(ramp[1], "ramp");
        assert_eq!(ramp[8], "wall");
        let rain = names("rain");
        assert_eq!(
            &rain[..5],
            ["floor", "wall #1", "wall #2", "wall #3", "wall #4"]
        );
    }
}
