//! Scenes: what a world holds at the start, from a TOML file or built in by name.
//!
//! A scene is plain data (bodies, colours, camera, world settings); [`Scene::build_world`] turns it into a
//! physics world holding exactly the bodies it declares, in declaration order (body i ↔ `BodyId(i)`).
//! The file format is documented in [`mod@file`]; its tables, which saved worlds and recordings are
//! written and read through too, are declared once in [`schema`].

pub mod builtin;
pub mod cases;
pub mod error;
pub mod file;
pub mod framing;
pub mod joints;
pub mod mechanisms;
pub mod piles;
pub mod ragdoll;
pub mod readable;
pub mod schema;
pub mod text_file;
pub mod vector;
pub mod write;

use std::path::Path;

use crate::color::Rgb;
use crate::geometry::Camera;
use crate::physics::{BodyDesc, BodyId, JointDesc, Settings, World};

pub use error::{Location, SceneError, SceneErrorKind};

/// One body of a scene: its physics description and how it looks.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneBody {
    pub desc: BodyDesc,
    pub color: Rgb,
    /// Static because the sandbox froze it (`frozen = true` in a file, as Ctrl+S writes a body
    /// frozen with `f`), not scenery: it is drawn as a body and unfreezes with its mass. Saved as
    /// plain `static`, a frozen box came back as a checkered wall that said "part of the scenery".
    pub frozen: bool,
    /// Its name in the scene file (`name = "bob"`), which joints may use and the sandbox calls it
    /// by; none for the built-in scenes' bodies and those added at run time.
    pub name: Option<String>,
}

impl SceneBody {
    /// A body that is not frozen (scenery if `desc` is static).
    pub fn new(desc: BodyDesc, color: Rgb) -> Self {
        Self {
            desc,
            color,
            frozen: false,
            name: None,
        }
    }

    /// This body called `name` (unique in its scene).
    pub fn named(self, name: impl Into<String>) -> Self {
        Self {
            name: Some(name.into()),
            ..self
        }
    }
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
    /// Joints between the bodies (or a body and the world), in the bodies' frames.
    pub joints: Vec<JointDesc>,
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
        for joint in &self.joints {
            // A scene's joints were checked against its bodies when it was read or built.
            let _ = world.add_joint(*joint);
        }
        world
    }
}

/// Built-in scenes: (name, one-line description), in the order `nudge scenes` lists them.
pub fn builtin_scenes() -> &'static [(&'static str, &'static str)] {
    builtin::BUILTIN_SCENES
}

/// Loads a built-in scene by name, else the scene file at that path.
///
/// A built-in name wins over a file of the same name in the working directory (write `./default` for
/// the file). A name that is neither gives [`SceneErrorKind::UnknownScene`] listing the built-in names.
pub fn load(name_or_path: &str) -> Result<Scene, SceneError> {
    if let Some(scene) = builtin::by_name(name_or_path) {
        return Ok(scene);
    }
    if Path::new(name_or_path).exists() {
        return file::load_file(name_or_path);
    }
    let names: Vec<&str> = builtin_scenes().iter().map(|(name, _)| *name).collect();
    Err(SceneError::new(
        SceneErrorKind::UnknownScene,
        name_or_path,
        format!(
            "no built-in scene of that name and no such file; built-in scenes: {}",
            names.join(", ")
        ),
    ))
}
