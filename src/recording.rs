//! Session recordings: the file `nudge run --record FILE` writes and `nudge replay FILE` reads.
//!
//! # Format (version 1)
//!
//! A TOML document, written as the session goes (so a crash loses only the unflushed tail):
//!
//! ```toml
//! [recording]
//! format = "nudge-recording"
//! version = 1
//! scene = '''
//! ...the starting world, as a scene file (bodies bit for bit, see `scene::write`)...
//! '''
//!
//! [recording.settings]          # every solver setting the session started with
//! gravity = [0.0, -9.81, 0.0]
//! ...
//!
//! [[input]]                     # one per input, in the order applied
//! step = 42                     # physics steps taken before it was applied
//! force = { body = 3, force = [0.0, 0.0, 12.5], point = [0.1, 0.5, -0.2] }
//!
//! [[input]]
//! step = 42
//! camera = { position = [...], target = [...], up = [...], fov_y = 1.2, near = 0.1, far = 500.0 }
//!
//! [end]
//! step = 900                    # steps the session ran: the replay runs this many
//! ```
//!
//! An input has `step` and exactly one of: `force` / `impulse` (`body`, the vector, `point`; N or
//! N·s and m, world frame), `hold` (a point held on a spring for one step: `body`, `anchor` in the
//! body's frame, the target's `from` and `to`, `hertz`, `damping_ratio`, `max_force`, `max_speed`,
//! `spin_time`; see `physics::point_drive`), `set_static` (`body`, `is_static`), `gravity`, `wake` (a body), `add_body`
//! (a body as a scene file writes it), `resize` (`body`, `half_extents` or `radius`), `reset = true`,
//! `settings` (a sub-table `[input.settings]`, every setting), `camera` (what the view showed from
//! then on; not an input to the world) and `truncate = true`: the session rewound to `step` and went
//! on differently, so every earlier input at `step` or later is dropped — the file keeps the timeline
//! actually played. Floats are written so they read back bit for bit.
//!
//! A file that is not TOML, is of another format or version, names a body that does not exist, goes
//! back in time without a truncate, or has no `[end]` (truncated: the session did not finish writing)
//! is rejected with `FILE:LINE:COLUMN: what is wrong`.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::ops::Range;
use std::path::Path;

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};
use toml::Spanned;

use crate::geometry::{Camera, Pose, Projection, Shape};
use crate::physics::limits;
use crate::physics::{BodyDesc, BodyId, PointHold, PointSpring, Settings, WorldInput};
use crate::scene::vector::Floats;
use crate::scene::write::num;
use crate::scene::{Location, Scene};

/// The only version this build reads and writes.
pub const VERSION: i64 = 1;
const FORMAT: &str = "nudge-recording";

/// A recording read back: the starting scene and settings, and the final timeline.
#[derive(Clone, Debug)]
pub struct Recording {
    pub scene: Scene,
    pub settings: Settings,
    /// World inputs of the timeline played, in order, each with its step and where it was written.
    pub inputs: Vec<(u64, WorldInput, Location)>,
    /// Camera changes, in order, each with the step from which it was shown.
    pub cameras: Vec<(u64, Camera)>,
    /// Steps the session ran.
    pub end: u64,
}

/// A recording that could not be read, and where.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordingError {
    pub source_name: String,
    pub location: Option<Location>,
    pub message: String,
}

impl std::fmt::Display for RecordingError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.location {
            Some(Location { line, column }) => {
                write!(f, "{}:{line}:{column}: {}", self.source_name, self.message)
            }
            None => write!(f, "{}: {}", self.source_name, self.message),
        }
    }
}

impl std::error::Error for RecordingError {}

/// Writes a recording as the session goes; the first write error stops it (the caller reports it).
pub struct Recorder {
    out: BufWriter<File>,
    last_camera: Option<Camera>,
    /// The step of the last entry written: entries never go back in time but through a truncate.
    last_step: u64,
}

impl Recorder {
    /// Creates `path` and writes the header: the starting world as scene text and every setting.
    pub fn create(path: &Path, scene_text: &str, settings: &Settings) -> io::Result<Self> {
        let mut out = BufWriter::new(File::create(path)?);
        let settings = toml::to_string(&RawSettings::from(settings)).map_err(io::Error::other)?;
        write!(
            out,
            "# nudge session recording: `nudge replay FILE` plays it\n\
             [recording]\nformat = \"{FORMAT}\"\nversion = {VERSION}\nscene = '''\n{scene_text}'''\n\n\
             [recording.settings]\n{settings}"
        )?;
        Ok(Self {
            out,
            last_camera: None,
            last_step: 0,
        })
    }

    /// Appends inputs, each with the step it was applied at.
    pub fn inputs(&mut self, inputs: &[(u64, WorldInput)]) -> io::Result<()> {
        for (step, input) in inputs {
            let text = input_text(*step, input)?;
            self.out.write_all(text.as_bytes())?;
            self.last_step = *step;
        }
        Ok(())
    }

    /// The session rewound to `step` and went on differently.
    pub fn truncate(&mut self, step: u64) -> io::Result<()> {
        self.last_step = step;
        // The views written from `step` on are dropped with the inputs: the next one is written.
        self.last_camera = None;
        write!(self.out, "\n[[input]]\nstep = {step}\ntruncate = true\n")
    }

    /// Records the view from `step` on, if it changed. A view of a rewound past the file has gone
    /// beyond is not written (found by fuzzing: a camera moved after `[` was written behind later
    /// inputs, and the file was refused); the first view written once the session goes on from
    /// there, after a truncate or past the last entry, is whatever it shows then.
    pub fn camera(&mut self, step: u64, camera: &Camera) -> io::Result<()> {
        if self.last_camera == Some(*camera) || step < self.last_step {
            return Ok(());
        }
        self.last_camera = Some(*camera);
        self.last_step = step;
        write!(
            self.out,
            "\n[[input]]\nstep = {step}\ncamera = {}\n",
            camera_text(camera)
        )
    }

    /// Pushes what is buffered to the file.
    pub fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Writes the end: the session ran `steps` steps.
    pub fn finish(mut self, steps: u64) -> io::Result<()> {
        write!(self.out, "\n[end]\nstep = {steps}\n")?;
        self.out.flush()
    }
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

fn camera_text(camera: &Camera) -> String {
    let projection = match camera.projection {
        Projection::Perspective { fov_y } => format!("fov_y = {}", num(fov_y)),
        Projection::Orthographic { view_height } => format!("view_height = {}", num(view_height)),
    };
    format!(
        "{{ position = {}, target = {}, up = {}, {projection}, near = {}, far = {} }}",
        vec3(camera.position),
        vec3(camera.target),
        vec3(camera.up),
        num(camera.near),
        num(camera.far)
    )
}

fn desc_text(d: &BodyDesc) -> String {
    let shape = match d.shape {
        Shape::Cuboid { half_extents } => {
            format!("shape = \"box\", half_extents = {}", vec3(half_extents))
        }
        Shape::Sphere { radius } => format!("shape = \"sphere\", radius = {}", num(radius)),
    };
    let [x, y, z, w] = d.pose.rotation.to_array();
    format!(
        "{{ {shape}, position = {}, orientation = [{}, {}, {}, {}], velocity = {}, \
         angular_velocity = {}, mass = {}, static = {}, friction = {}, restitution = {}, \
         rolling_resistance = {} }}",
        vec3(d.pose.position),
        num(x),
        num(y),
        num(z),
        num(w),
        vec3(d.linear_velocity),
        vec3(d.angular_velocity),
        num(d.mass),
        d.is_static,
        num(d.friction),
        num(d.restitution),
        num(d.rolling_resistance)
    )
}

fn input_text(step: u64, input: &WorldInput) -> io::Result<String> {
    let mut out = format!("\n[[input]]\nstep = {step}\n");
    let _ = match input {
        WorldInput::Force { body, force, point } => writeln!(
            out,
            "force = {{ body = {}, force = {}, point = {} }}",
            body.0,
            vec3(*force),
            vec3(*point)
        ),
        WorldInput::Impulse {
            body,
            impulse,
            point,
        } => writeln!(
            out,
            "impulse = {{ body = {}, impulse = {}, point = {} }}",
            body.0,
            vec3(*impulse),
            vec3(*point)
        ),
        WorldInput::Hold(h) => writeln!(
            out,
            "hold = {{ body = {}, anchor = {}, from = {}, to = {}, hertz = {}, damping_ratio = {}, \
             max_force = {}, max_speed = {}, spin_time = {} }}",
            h.body.0,
            vec3(h.anchor),
            vec3(h.from),
            vec3(h.to),
            num(h.spring.hertz),
            num(h.spring.damping_ratio),
            num(h.spring.max_force),
            num(h.spring.max_speed),
            num(h.spin_time)
        ),
        WorldInput::SetStatic { body, is_static } => writeln!(
            out,
            "set_static = {{ body = {}, is_static = {is_static} }}",
            body.0
        ),
        WorldInput::Gravity(g) => writeln!(out, "gravity = {}", vec3(*g)),
        WorldInput::Wake(body) => writeln!(out, "wake = {}", body.0),
        WorldInput::AddBody(desc) => writeln!(out, "add_body = {}", desc_text(desc)),
        // Nothing in the sandbox adds a joint during a session (they come with the scene, built
        // before the journal starts), and the recording schema has no joints yet.
        WorldInput::AddJoint(_) => {
            return Err(io::Error::other(
                "a joint added during a session cannot be recorded yet",
            ));
        }
        WorldInput::Resize { body, shape } => {
            let size = match shape {
                Shape::Cuboid { half_extents } => format!("half_extents = {}", vec3(*half_extents)),
                Shape::Sphere { radius } => format!("radius = {}", num(*radius)),
            };
            writeln!(out, "resize = {{ body = {}, {size} }}", body.0)
        }
        WorldInput::Reset => writeln!(out, "reset = true"),
        WorldInput::Settings(settings) => {
            let table =
                toml::to_string(&RawSettings::from(&**settings)).map_err(io::Error::other)?;
            write!(out, "[input.settings]\n{table}")
        }
    };
    Ok(out)
}

/// Every solver setting, as the file spells it.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSettings {
    gravity: Floats<3>,
    dt: f32,
    substeps: u32,
    iterations: u32,
    sleep: bool,
    linear_damping: f32,
    angular_damping: f32,
    contact_hertz: f32,
    contact_damping_ratio: f32,
    max_push_out_velocity: f32,
    restitution_threshold: f32,
    linear_slop: f32,
    speculative_distance: f32,
    manifold_reuse_distance: f32,
    sleep_linear_threshold: f32,
    sleep_angular_threshold: f32,
    time_to_sleep: f32,
    max_linear_speed: f32,
    max_angular_speed: f32,
    shock_propagation: bool,
    mass_ratio_threshold: f32,
    mass_ratio_iterations: u32,
    /// Absent from recordings made before the switch existed: on, as it always was.
    #[serde(default = "on")]
    spread_row: bool,
    #[serde(default = "on")]
    alternate_point_order: bool,
    /// Absent from recordings made before the switch existed: off, as it was.
    #[serde(default)]
    preload: bool,
    /// Absent from recordings made before the switch existed: on, the default.
    #[serde(default = "on")]
    determinate_preload: bool,
}

fn on() -> bool {
    true
}

impl From<&Settings> for RawSettings {
    fn from(s: &Settings) -> Self {
        RawSettings {
            gravity: Floats(s.gravity.to_array()),
            dt: s.dt,
            substeps: s.substeps,
            iterations: s.iterations,
            sleep: s.sleep,
            linear_damping: s.linear_damping,
            angular_damping: s.angular_damping,
            contact_hertz: s.contact_hertz,
            contact_damping_ratio: s.contact_damping_ratio,
            max_push_out_velocity: s.max_push_out_velocity,
            restitution_threshold: s.restitution_threshold,
            linear_slop: s.linear_slop,
            speculative_distance: s.speculative_distance,
            manifold_reuse_distance: s.manifold_reuse_distance,
            sleep_linear_threshold: s.sleep_linear_threshold,
            sleep_angular_threshold: s.sleep_angular_threshold,
            time_to_sleep: s.time_to_sleep,
            max_linear_speed: s.max_linear_speed,
            max_angular_speed: s.max_angular_speed,
            shock_propagation: s.shock_propagation,
            mass_ratio_threshold: s.mass_ratio_threshold,
            mass_ratio_iterations: s.mass_ratio_iterations,
            spread_row: s.spread_row,
            alternate_point_order: s.alternate_point_order,
            preload: s.preload,
            determinate_preload: s.determinate_preload,
        }
    }
}

impl RawSettings {
    /// The settings, if every value is one the solver can use.
    fn settings(&self) -> Result<Settings, String> {
        let s = Settings {
            gravity: Vec3::from_array(self.gravity.0),
            dt: self.dt,
            substeps: self.substeps,
            iterations: self.iterations,
            sleep: self.sleep,
            linear_damping: self.linear_damping,
            angular_damping: self.angular_damping,
            contact_hertz: self.contact_hertz,
            contact_damping_ratio: self.contact_damping_ratio,
            max_push_out_velocity: self.max_push_out_velocity,
            restitution_threshold: self.restitution_threshold,
            linear_slop: self.linear_slop,
            speculative_distance: self.speculative_distance,
            manifold_reuse_distance: self.manifold_reuse_distance,
            sleep_linear_threshold: self.sleep_linear_threshold,
            sleep_angular_threshold: self.sleep_angular_threshold,
            time_to_sleep: self.time_to_sleep,
            max_linear_speed: self.max_linear_speed,
            max_angular_speed: self.max_angular_speed,
            shock_propagation: self.shock_propagation,
            mass_ratio_threshold: self.mass_ratio_threshold,
            mass_ratio_iterations: self.mass_ratio_iterations,
            spread_row: self.spread_row,
            alternate_point_order: self.alternate_point_order,
            preload: self.preload,
            determinate_preload: self.determinate_preload,
        };
        let floats = [
            s.dt,
            s.linear_damping,
            s.angular_damping,
            s.contact_hertz,
            s.contact_damping_ratio,
            s.max_push_out_velocity,
            s.restitution_threshold,
            s.linear_slop,
            s.speculative_distance,
            s.manifold_reuse_distance,
            s.sleep_linear_threshold,
            s.sleep_angular_threshold,
            s.time_to_sleep,
            s.max_linear_speed,
            s.max_angular_speed,
            s.mass_ratio_threshold,
        ];
        if !s.gravity.is_finite() || floats.iter().any(|x| !x.is_finite()) {
            return Err("every setting must be finite".into());
        }
        if s.dt <= 0.0 {
            return Err(format!("dt must be > 0, got {}", num(s.dt)));
        }
        limits::check_settings(&s)?;
        Ok(s)
    }
}

/// Reads and checks the recording at `path`; messages name it as `path` is spelled.
pub fn load(path: &str) -> Result<Recording, RecordingError> {
    // Bounded like a scene file: `nudge replay /dev/zero` read until memory ran out.
    let text = crate::scene::text_file::read_text(path).map_err(|err| RecordingError {
        source_name: path.to_owned(),
        location: err.location(),
        message: err.message("recording"),
    })?;
    parse(&text, path)
}

#[derive(Deserialize)]
struct ProbeFile {
    recording: Option<Spanned<ProbeHeader>>,
}

#[derive(Deserialize)]
struct ProbeHeader {
    format: Option<Spanned<String>>,
    version: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    recording: RawHeader,
    #[serde(default)]
    input: Vec<Spanned<RawInput>>,
    end: Option<RawEnd>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHeader {
    #[allow(dead_code, reason = "checked by the probe")]
    format: String,
    #[allow(dead_code, reason = "checked by the probe")]
    version: i64,
    scene: Spanned<String>,
    settings: Spanned<RawSettings>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEnd {
    step: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInput {
    step: u64,
    force: Option<RawForce>,
    impulse: Option<RawImpulse>,
    hold: Option<RawHold>,
    set_static: Option<RawSetStatic>,
    gravity: Option<Floats<3>>,
    wake: Option<u32>,
    add_body: Option<RawDesc>,
    resize: Option<RawResize>,
    reset: Option<bool>,
    settings: Option<RawSettings>,
    camera: Option<RawCamera>,
    truncate: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawForce {
    body: u32,
    force: Floats<3>,
    point: Floats<3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawImpulse {
    body: u32,
    impulse: Floats<3>,
    point: Floats<3>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHold {
    body: u32,
    anchor: Floats<3>,
    from: Floats<3>,
    to: Floats<3>,
    hertz: f32,
    damping_ratio: f32,
    max_force: f32,
    max_speed: f32,
    spin_time: f32,
}

impl RawHold {
    fn hold(&self) -> Result<PointHold, String> {
        let hold = PointHold {
            body: BodyId(self.body),
            anchor: finite3("anchor", self.anchor)?,
            from: finite3("from", self.from)?,
            to: finite3("to", self.to)?,
            spring: PointSpring {
                hertz: self.hertz,
                damping_ratio: self.damping_ratio,
                max_force: self.max_force,
                max_speed: self.max_speed,
            },
            spin_time: self.spin_time,
        };
        if !hold.is_valid() {
            return Err(
                "a hold has hertz and max_speed finite and > 0, damping_ratio, max_force \
                        and spin_time finite and >= 0"
                    .into(),
            );
        }
        Ok(hold)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSetStatic {
    body: u32,
    is_static: bool,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawResize {
    body: u32,
    half_extents: Option<Floats<3>>,
    radius: Option<f32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDesc {
    shape: String,
    half_extents: Option<Floats<3>>,
    radius: Option<f32>,
    position: Floats<3>,
    orientation: Floats<4>,
    velocity: Floats<3>,
    angular_velocity: Floats<3>,
    mass: f32,
    #[serde(rename = "static")]
    is_static: bool,
    friction: f32,
    restitution: f32,
    rolling_resistance: f32,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    position: Floats<3>,
    target: Floats<3>,
    up: Floats<3>,
    fov_y: Option<f32>,
    view_height: Option<f32>,
    near: f32,
    far: f32,
}

fn shape_of(
    kind: Option<&str>,
    half_extents: Option<Floats<3>>,
    radius: Option<f32>,
) -> Result<Shape, String> {
    let shape = match (kind, half_extents, radius) {
        (Some("box") | None, Some(h), None) => Shape::cuboid(Vec3::from_array(h.0)),
        (Some("sphere") | None, None, Some(r)) => Shape::sphere(r),
        _ => return Err("a shape is \"box\" with half_extents or \"sphere\" with radius".into()),
    };
    if !shape.is_valid() {
        return Err(format!("sizes must be finite and > 0, got {shape:?}"));
    }
    limits::check_shape(&shape)?;
    Ok(shape)
}

fn finite3(name: &str, v: Floats<3>) -> Result<Vec3, String> {
    let v = Vec3::from_array(v.0);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{name} must be finite, got {}", vec3(v)))
    }
}

impl RawDesc {
    fn desc(&self) -> Result<BodyDesc, String> {
        let shape = shape_of(Some(self.shape.as_str()), self.half_extents, self.radius)?;
        let rotation = Quat::from_array(self.orientation.0);
        if !rotation.is_finite() || (rotation.length() - 1.0).abs() > 1e-3 {
            return Err("orientation must be a finite unit quaternion [x, y, z, w]".into());
        }
        let mass = self.mass;
        if !(mass.is_finite() && mass > 0.0) {
            return Err(format!("mass must be finite and > 0, got {}", num(mass)));
        }
        let materials = [self.friction, self.restitution, self.rolling_resistance];
        if materials.iter().any(|x| !(x.is_finite() && *x >= 0.0)) || self.restitution > 1.0 {
            return Err("friction, restitution and rolling_resistance must be finite and >= 0 (restitution <= 1)".into());
        }
        if !self.is_static {
            limits::in_range("mass (kg)", mass, limits::MIN_MASS, limits::MAX_MASS)?;
        }
        // The representable range holds for recordings as for scene files.
        let position = finite3("position", self.position)?;
        limits::check_position("position", position)?;
        let caps = Settings::default();
        let linear_velocity = finite3("velocity", self.velocity)?;
        limits::check_length("velocity (m/s)", linear_velocity, caps.max_linear_speed)?;
        let angular_velocity = finite3("angular_velocity", self.angular_velocity)?;
        limits::check_length(
            "angular_velocity (rad/s)",
            angular_velocity,
            caps.max_angular_speed,
        )?;
        Ok(BodyDesc {
            shape,
            pose: Pose::new(position, rotation),
            linear_velocity,
            angular_velocity,
            mass,
            is_static: self.is_static,
            friction: self.friction,
            restitution: self.restitution,
            rolling_resistance: self.rolling_resistance,
        })
    }
}

impl RawCamera {
    fn camera(&self) -> Result<Camera, String> {
        let position = finite3("camera position", self.position)?;
        let target = finite3("camera target", self.target)?;
        let up = finite3("camera up", self.up)?;
        let projection = match (self.fov_y, self.view_height) {
            (Some(fov_y), None) if fov_y > 0.0 && fov_y < std::f32::consts::PI => {
                Projection::Perspective { fov_y }
            }
            (None, Some(view_height)) if view_height.is_finite() && view_height > 0.0 => {
                Projection::Orthographic { view_height }
            }
            _ => return Err("a camera has fov_y in (0, π) or view_height > 0, not both".into()),
        };
        if position == target || !(self.near > 0.0 && self.far > self.near && self.far.is_finite())
        {
            return Err("camera position and target must differ, and 0 < near < far".into());
        }
        Ok(Camera {
            position,
            target,
            up,
            projection,
            near: self.near,
            far: self.far,
        })
    }
}

/// What one `[[input]]` holds.
enum Entry {
    World(WorldInput),
    Camera(Camera),
    Truncate,
}

impl RawInput {
    fn entry(&self) -> Result<Entry, String> {
        let given = [
            self.force.is_some(),
            self.impulse.is_some(),
            self.hold.is_some(),
            self.set_static.is_some(),
            self.gravity.is_some(),
            self.wake.is_some(),
            self.add_body.is_some(),
            self.resize.is_some(),
            self.reset.is_some(),
            self.settings.is_some(),
            self.camera.is_some(),
            self.truncate.is_some(),
        ];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(
                "an input has a step and exactly one of force, impulse, hold, set_static, gravity, \
                 wake, add_body, resize, reset, settings, camera, truncate"
                    .into(),
            );
        }
        Ok(if let Some(f) = &self.force {
            Entry::World(WorldInput::Force {
                body: BodyId(f.body),
                force: finite3("force", f.force)?,
                point: finite3("point", f.point)?,
            })
        } else if let Some(i) = &self.impulse {
            Entry::World(WorldInput::Impulse {
                body: BodyId(i.body),
                impulse: finite3("impulse", i.impulse)?,
                point: finite3("point", i.point)?,
            })
        } else if let Some(h) = &self.hold {
            Entry::World(WorldInput::Hold(h.hold()?))
        } else if let Some(s) = &self.set_static {
            Entry::World(WorldInput::SetStatic {
                body: BodyId(s.body),
                is_static: s.is_static,
            })
        } else if let Some(g) = self.gravity {
            let g = finite3("gravity", g)?;
            limits::check_length("gravity (m/s²)", g, limits::MAX_GRAVITY)?;
            Entry::World(WorldInput::Gravity(g))
        } else if let Some(body) = self.wake {
            Entry::World(WorldInput::Wake(BodyId(body)))
        } else if let Some(desc) = &self.add_body {
            Entry::World(WorldInput::AddBody(desc.desc()?))
        } else if let Some(r) = &self.resize {
            Entry::World(WorldInput::Resize {
                body: BodyId(r.body),
                shape: shape_of(None, r.half_extents, r.radius)?,
            })
        } else if let Some(reset) = self.reset {
            if !reset {
                return Err("reset is written reset = true".into());
            }
            Entry::World(WorldInput::Reset)
        } else if let Some(settings) = &self.settings {
            Entry::World(WorldInput::Settings(Box::new(settings.settings()?)))
        } else if let Some(camera) = &self.camera {
            Entry::Camera(camera.camera()?)
        } else {
            if self.truncate != Some(true) {
                return Err("truncate is written truncate = true".into());
            }
            Entry::Truncate
        })
    }
}

/// Parses recording text; `source_name` names it in messages.
pub fn parse(text: &str, source_name: &str) -> Result<Recording, RecordingError> {
    let at = |span: Range<usize>, message: String| RecordingError {
        source_name: source_name.to_owned(),
        location: Some(Location::of_offset(text, span.start)),
        message,
    };
    let syntax = |err: toml::de::Error| {
        at(
            err.span().unwrap_or(0..0),
            err.message().trim_end().to_owned(),
        )
    };
    // The header first, leniently, so another format or version is named as such rather than as
    // an unknown key.
    let probe: ProbeFile = toml::from_str(text).map_err(syntax)?;
    let Some(header) = probe.recording else {
        return Err(at(
            0..0,
            format!("not a nudge recording: no [recording] table (expected format = \"{FORMAT}\")"),
        ));
    };
    let header_span = header.span();
    let header = header.into_inner();
    match header.format {
        Some(format) if format.get_ref() == FORMAT => {}
        Some(format) => {
            return Err(at(
                format.span(),
                format!(
                    "not a nudge recording: format is {:?}, expected \"{FORMAT}\"",
                    format.get_ref()
                ),
            ));
        }
        None => {
            return Err(at(
                header_span,
                format!("[recording] needs format = \"{FORMAT}\""),
            ));
        }
    }
    match header.version {
        Some(version) if *version.get_ref() == VERSION => {}
        Some(version) => {
            return Err(at(
                version.span(),
                format!(
                    "recording version {} is not supported; this nudge reads version {VERSION}",
                    version.get_ref()
                ),
            ));
        }
        None => {
            return Err(at(
                header_span,
                format!("[recording] needs version = {VERSION}"),
            ));
        }
    }
    let raw: RawFile = toml::from_str(text).map_err(syntax)?;

    let scene_span = raw.recording.scene.span();
    let scene_line = Location::of_offset(text, scene_span.start).line;
    let scene =
        crate::scene::file::parse(raw.recording.scene.get_ref(), source_name).map_err(|err| {
            RecordingError {
                source_name: source_name.to_owned(),
                // The scene text starts on the line after `scene = '''`.
                location: Some(err.location.map_or(
                    Location {
                        line: scene_line,
                        column: 1,
                    },
                    |l| Location {
                        line: l.line + scene_line,
                        column: l.column,
                    },
                )),
                message: format!("embedded scene: {}", err.message),
            }
        })?;
    let settings = raw
        .recording
        .settings
        .get_ref()
        .settings()
        .map_err(|m| at(raw.recording.settings.span(), m))?;

    let mut inputs: Vec<(u64, WorldInput, Location)> = Vec::new();
    let mut cameras: Vec<(u64, Camera)> = Vec::new();
    let mut last_step = 0;
    for input in &raw.input {
        let span = input.span();
        let step = input.get_ref().step;
        let entry = input.get_ref().entry().map_err(|m| at(span.clone(), m))?;
        if let Entry::Truncate = entry {
            inputs.retain(|(s, ..)| *s < step);
            cameras.retain(|(s, _)| *s < step);
            last_step = step;
            continue;
        }
        if step < last_step {
            return Err(at(
                span,
                format!(
                    "step {step} comes before the previous input's step {last_step} without a truncate"
                ),
            ));
        }
        last_step = step;
        match entry {
            Entry::World(world_input) => {
                inputs.push((step, world_input, Location::of_offset(text, span.start)))
            }
            Entry::Camera(camera) => cameras.push((step, camera)),
            Entry::Truncate => unreachable!("handled above"),
        }
    }
    // Problems with the end are shown on the last line written.
    let last = text.trim_end().len();
    let last_line = text[..last].rfind('\n').map_or(0, |i| i + 1)..last;
    let Some(end) = raw.end else {
        return Err(at(
            last_line.clone(),
            format!(
                "truncated: no [end] table (the session did not finish writing it); the last input is at step {last_step}"
            ),
        ));
    };
    if end.step < last_step {
        return Err(at(
            last_line,
            format!(
                "[end] step {} is before the last input's step {last_step}",
                end.step
            ),
        ));
    }
    // Every body named must exist when its input is applied.
    let mut bodies = scene.bodies.len();
    for (_, input, location) in &inputs {
        let named = match input {
            WorldInput::Force { body, .. }
            | WorldInput::Impulse { body, .. }
            | WorldInput::Hold(PointHold { body, .. })
            | WorldInput::SetStatic { body, .. }
            | WorldInput::Wake(body)
            | WorldInput::Resize { body, .. } => Some(*body),
            WorldInput::AddBody(_) => {
                bodies += 1;
                None
            }
            WorldInput::AddJoint(desc) => Some(desc.b),
            WorldInput::Reset => {
                bodies = scene.bodies.len();
                None
            }
            WorldInput::Gravity(_) | WorldInput::Settings(_) => None,
        };
        if let Some(body) = named
            && body.index() >= bodies
        {
            return Err(RecordingError {
                source_name: source_name.to_owned(),
                location: Some(*location),
                message: format!(
                    "body {} does not exist (the world has {bodies} bodies then)",
                    body.0
                ),
            });
        }
    }
    Ok(Recording {
        scene,
        settings,
        inputs,
        cameras,
        end: end.step,
    })
}
