//! Scenes: what a world holds at the start, from a TOML file or built in by name.
//!
//! A scene is plain data (bodies, colours, camera, world settings); [`Scene::build_world`] turns it into a
//! physics world holding exactly the bodies it declares, in declaration order (body i ↔ `BodyId(i)`).

pub mod cases;

use crate::color::Rgb;
use crate::geometry::Camera;
use crate::physics::{BodyDesc, BodyId, Settings, World};

/// One body of a scene: its physics description and how it looks.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneBody {
    pub desc: BodyDesc,
    pub color: Rgb,
}

/// A whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Built-in name or file path, for messages.
    pub name: String,
    /// Gravity and dt from the file; solver knobs at their defaults.
    pub settings: Settings,
    pub camera: Camera,
    pub bodies: Vec<SceneBody>,
}

impl Scene {
    /// A physics world with exactly this scene's bodies, `BodyId(i)` being `bodies[i]`.
    pub fn build_world(&self) -> World {
        self.build_world_with(self.settings.clone())
    }

    /// Same, with other solver settings (gravity and dt still from the scene unless changed by the caller).
    pub fn build_world_with(&self, settings: Settings) -> World {
        let mut world = World::new(settings);
        for (i, body) in self.bodies.iter().enumerate() {
            let id = world.add_body(body.desc);
            debug_assert_eq!(id, BodyId(i as u32));
        }
        world
    }
}

/// A scene that could not be loaded; `Display` names the file, line and column where known.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    pub message: String,
}

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}

/// Built-in scenes: (name, one-line description).
pub fn builtin_scenes() -> &'static [(&'static str, &'static str)] {
    &[
        ("pyramid", "210 boxes in a 20-box-base pyramid"),
        ("rain", "1,000 boxes and balls raining into a walled pit"),
    ]
}

/// Loads a built-in scene by name or a scene file by path.
pub fn load(name_or_path: &str) -> Result<Scene, SceneError> {
    match name_or_path {
        "pyramid" => Ok(cases::pyramid(20)),
        "rain" => Ok(cases::rain(1000)),
        other => Err(SceneError {
            message: format!(
                "{other}: no such built-in scene, and scene files are not supported yet"
            ),
        }),
    }
}
