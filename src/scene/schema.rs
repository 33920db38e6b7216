//! The one schema: the serde types scene files, saved worlds and recordings are read and written
//! through.
//!
//! Recordings used to write their TOML with `format!` and read it back through their own copies of
//! the scene file's body and camera tables, each copy with its own checks, so a key added to one
//! was missing from the other (a recorded body had no colour or density, a scene camera no `up`).
//! Every table of every format is now declared once, here, deriving both `Serialize` and
//! `Deserialize`: a new key is a new field, read and written everywhere it appears.
//!
//! - A scene file is a [`SceneFile`]: `[world]`, `[camera]`, `[[body]]`. A saved world (Ctrl+S) is
//!   a scene file written by `scene::write`; it uses the exact forms (`orientation`, `mass`).
//! - A recording is a [`RecordingFile`]: its `[recording]` header embeds the starting world as
//!   scene-file text (a [`SceneFile`] again), its `add_body` inputs are [`Body`] tables and its
//!   `camera` inputs [`Camera`] tables, the same types the scene file uses.
//!
//! Where the formats wrote one thing two ways, both are accepted wherever the table appears: a body's
//! rotation is an `orientation` quaternion (exact: what the writers use) or `rotation_axis` with
//! `rotation_deg` (for people); a camera's field of view is `fov_deg` (degrees, for people) or
//! `fov_y` (radians, exact), and `up`, `near`, `far` and `view_height` are optional (framed from the
//! scene when left out). The checks live with the readers, once each: `scene::file` turns a
//! [`Body`] or a [`Camera`] into what the world and the renderer use, with errors located at
//! `FILE:LINE:COLUMN` through the [`Spanned`] values (spans are ignored when writing; values built
//! for writing carry [`unplaced`] ones), and `recording` checks its inputs and settings.
//!
//! Floats are [`Float`]s and `f32`s, serialized as f32: toml 1 prints an f32 in Rust's shortest
//! round-trip form (`0.1`, not the `0.10000000149011612` of the f64 it would be widened to), whole
//! numbers with `.0` (so `1e20` is not read back as an out-of-range integer), and the reader narrows
//! the f64 it parses back to the same f32. So a written world reads back bit for bit
//! (`tests/cli/schema.rs` pins both, should a toml update change how it prints floats).

use serde::{Deserialize, Serialize};
use toml::Spanned;

use super::vector::{Float, Floats};

/// A value for writing: the span is only meaningful in a value read from text.
pub fn unplaced<T>(value: T) -> Spanned<T> {
    Spanned::new(0..0, value)
}

/// A scene file, or a saved world.
#[derive(Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub world: Option<World>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<Spanned<Camera>>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub body: Vec<Body>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joint: Vec<Joint>,
}

/// `[world]`: gravity (m/s²) and the fixed step (s); solver knobs are not part of a scene.
#[derive(Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct World {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gravity: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt: Option<Spanned<Float>>,
}

/// `projection = "perspective" | "orthographic"`.
#[derive(Serialize, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    Perspective,
    Orthographic,
}

/// A camera: `[camera]` in a scene file (every key optional), `camera = { ... }` in a recording
/// (written exact: `up`, `fov_y` or `view_height`, `near`, `far`). Metres and radians but for
/// `fov_deg`; `fov_deg` and `fov_y` are one angle (give one), and `view_height` sets an
/// orthographic slab (no field of view with it).
#[derive(Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub up: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub projection: Option<Spanned<Projection>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov_y: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub view_height: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub near: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub far: Option<Spanned<Float>>,
}

/// `shape = "box" | "sphere"`.
#[derive(Serialize, Deserialize, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum Shape {
    Box,
    Sphere,
}

/// A body: one `[[body]]` of a scene file, or a recording's `add_body = { ... }`. Only `shape`, its
/// size and `position` are required; `scene::file` documents every key and its default. An added
/// body's `color` is read and checked but not used: the sandbox colours a body it adds from the
/// palette by its index, live and in a replay alike.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Body {
    /// Optional, unique: what a joint calls the body.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<Spanned<String>>,
    pub shape: Spanned<Shape>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_extents: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<Spanned<Float>>,
    pub position: Spanned<Floats<3>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_axis: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_deg: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation: Option<Spanned<Floats<4>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_velocity: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub density: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass: Option<Spanned<Float>>,
    #[serde(rename = "static", skip_serializing_if = "Option::is_none")]
    pub is_static: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frozen: Option<Spanned<bool>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restitution: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling_resistance: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color: Option<Spanned<String>>,
}

/// A recording, as read; written a part at a time as the session goes (`recording::Recorder`):
/// the header, then each input, then the end.
#[derive(Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RecordingFile {
    /// Required; optional here so the writer can write the other parts alone.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recording: Option<Header>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub input: Vec<Spanned<Input>>,
    /// Absent while the session is still being written, or if it never finished.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end: Option<End>,
}

/// `[recording]`.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Header {
    /// `"nudge-recording"`.
    pub format: Spanned<String>,
    pub version: Spanned<i64>,
    /// The starting world as scene-file text (a [`SceneFile`]), bit for bit.
    pub scene: Spanned<String>,
    pub settings: Spanned<Settings>,
}

/// `[end]`.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct End {
    /// Steps the session ran.
    pub step: u64,
}

/// Every solver setting (`physics::Settings`), as a recording spells it. A mirror of that struct,
/// not a derive on it: physics knows nothing of files (see the layers in `lib.rs`), and a setting
/// added there must say here what recordings made before it meant (the `default`s below).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    pub gravity: Floats<3>,
    pub dt: f32,
    pub substeps: u32,
    pub iterations: u32,
    pub sleep: bool,
    pub linear_damping: f32,
    pub angular_damping: f32,
    pub contact_hertz: f32,
    pub contact_damping_ratio: f32,
    pub max_push_out_velocity: f32,
    pub restitution_threshold: f32,
    pub linear_slop: f32,
    pub speculative_distance: f32,
    pub manifold_reuse_distance: f32,
    pub sleep_linear_threshold: f32,
    pub sleep_angular_threshold: f32,
    pub time_to_sleep: f32,
    pub max_linear_speed: f32,
    pub max_angular_speed: f32,
    pub shock_propagation: bool,
    pub mass_ratio_threshold: f32,
    pub mass_ratio_iterations: u32,
    /// Absent from recordings made before the switch existed: on, as it always was.
    #[serde(default = "on")]
    pub spread_row: bool,
    #[serde(default = "on")]
    pub alternate_point_order: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub alternate_sub_steps: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub alternate_layer_order: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub symmetric_relax: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub symmetric_biased_pass: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub preload: bool,
    /// Absent from recordings made before the switch existed: on, the default.
    #[serde(default = "on")]
    pub determinate_preload: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub feed_load_changes: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub feed_moment_changes: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub balance_new_supports: bool,
    /// Absent from recordings made before the setting existed: 0, as it was.
    #[serde(default)]
    pub touching_tolerance: f32,
    /// Absent from recordings made before the switch existed: on (they pushed a determinate
    /// support back inside the slop band alone, by a law no switch keeps).
    #[serde(default = "on")]
    pub touching_spring: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub friction_anchors: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub anchor_frequency_cap: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub thin_soft_range: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub sleep_waits_for_springs: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub sleep_waits_while_speeding_up: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub piles_carry_blows: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub statics_skip_jointed: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub rolling_held_mass_alone: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub joint_geometric_stiffness: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub joint_scalar_rows_last: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub joint_pull_from_load: bool,
    /// Absent from recordings made before the switch existed: on, as the joints were solved.
    #[serde(default = "on")]
    pub joint_tree: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    pub statics_reuse: bool,
}

fn on() -> bool {
    true
}

/// One `[[input]]`: its `step` and exactly one entry (see `recording` for what each means).
#[derive(Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Input {
    /// Physics steps taken before the entry was applied.
    pub step: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force: Option<Force>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub impulse: Option<Impulse>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hold: Option<Hold>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub set_static: Option<SetStatic>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gravity: Option<Floats<3>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wake: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub add_body: Option<Body>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub add_joint: Option<Joint>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resize: Option<Resize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reset: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub settings: Option<Settings>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub camera: Option<Camera>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub truncate: Option<bool>,
}

/// `force = { ... }`: N at a world point (m).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Force {
    pub body: u32,
    pub force: Floats<3>,
    pub point: Floats<3>,
}

/// `impulse = { ... }`: N·s at a world point (m).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Impulse {
    pub body: u32,
    pub impulse: Floats<3>,
    pub point: Floats<3>,
}

/// `hold = { ... }`: a point held on a spring for one step (`physics::point_drive`).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hold {
    pub body: u32,
    /// In the body's frame.
    pub anchor: Floats<3>,
    pub from: Floats<3>,
    pub to: Floats<3>,
    pub hertz: f32,
    pub damping_ratio: f32,
    pub max_force: f32,
    pub max_speed: f32,
    pub spin_time: f32,
}

/// `set_static = { ... }`.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SetStatic {
    pub body: u32,
    pub is_static: bool,
}

/// A joint: `[[joint]]` in a scene file, `add_joint = { ... }` in a recording. `kind` is `ball`,
/// `hinge`, `slider`, `fixed` or `distance`; `a` and `b` name a body by its `name` or its 0-based
/// index (`a` may be `"world"`, or left out, for the world).
///
/// Given two ways, as a body's rotation is: for people, `anchor` (ball, hinge, slider, fixed) or
/// `anchor_a` and `anchor_b` (distance), and `axis` (hinge, slider), in world coordinates in the
/// scene's initial pose, with hinge `limits` in degrees; exact, as saved worlds and recordings
/// write it, `local_anchor_a`, `local_anchor_b`, `local_axis_a`, `local_axis_b` and `reference`
/// (B's rotation relative to A's) in the bodies' frames, with hinge limits in radians
/// (`limits_rad`). Slider limits are metres either way. A motor is `motor_speed` (rad/s or m/s)
/// with `motor_max` (N·m or N); a distance joint has `length` (default: the anchors' distance),
/// `min_length` and `max_length` (default: `length`; a rope is `max_length` alone) and, for a
/// spring, `stiffness_hz` with `damping_ratio`. A ball joint, a hinge or a slider may have
/// `friction` (N·m, or N for a slider).
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Joint {
    pub kind: Spanned<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<Spanned<BodyRef>>,
    pub b: Spanned<BodyRef>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub anchor: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub anchor_a: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub anchor_b: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub axis: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub local_anchor_a: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub local_anchor_b: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub local_axis_a: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub local_axis_b: Option<Spanned<Floats<3>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<Spanned<Floats<4>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits: Option<Spanned<Floats<2>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limits_rad: Option<Spanned<Floats<2>>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub motor_speed: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub motor_max: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_length: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_length: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness_hz: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_ratio: Option<Spanned<Float>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub collide: Option<bool>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction: Option<Spanned<Float>>,
}

/// A joint's end: a body's index, or its name (or `"world"`).
#[derive(Serialize, Deserialize, Clone, PartialEq, Eq, Debug)]
#[serde(untagged)]
pub enum BodyRef {
    Index(u32),
    Name(String),
}

/// `resize = { ... }`: `half_extents` for a box or `radius` for a sphere.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Resize {
    pub body: u32,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub half_extents: Option<Floats<3>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius: Option<f32>,
}
