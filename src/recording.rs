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
//! scene = """
//! ...the starting world, as a scene file (bodies bit for bit, see `scene::write`)...
//! """
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
//! `spin_time`; see `physics::point_drive`), `set_static` (`body`, `is_static`), `gravity`, `wake`
//! (a body), `add_body` (a scene file's `[[body]]` table, written as a saved world writes it),
//! `add_joint` (a joint in its bodies' frames, exact: `scene::joints`), `resize` (`body`, `half_extents` or `radius`), `reset = true`, `settings` (a sub-table
//! `[input.settings]`, every setting), `camera` (a scene file's `[camera]` table, written exact: what
//! the view showed from then on; not an input to the world) and `truncate = true`: the session
//! rewound to `step` and went on differently, so every earlier input at `step` or later is dropped —
//! the file keeps the timeline actually played. Floats are written so they read back bit for bit.
//! Files written before the shared schema hold the scene in a `'''` literal string; they read the same.
//!
//! Every table is a type of `scene::schema`, written and read through serde: the header and the end
//! as toml writes them, each input on one line as above (`input_text` says why). An added body or a
//! camera is checked by the scene file's rules, so an error in one is located at its value; other
//! problems with an input are located at its `[[input]]`.
//!
//! A file that is not TOML, is of another format or version, names a body that does not exist, goes
//! back in time without a truncate, or has no `[end]` (truncated: the session did not finish writing)
//! is rejected with `FILE:LINE:COLUMN: what is wrong`.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::ops::Range;
use std::path::Path;

use glam::Vec3;
use serde::{Deserialize, Serialize};
use toml::Spanned;

use crate::geometry::{Camera, Shape};
use crate::physics::limits::{self, short, short_vec};
use crate::physics::{BodyId, PointHold, PointSpring, Settings, WorldInput};
use crate::scene::file::{Ends, Source};
use crate::scene::joints;
use crate::scene::schema::{self, unplaced};
use crate::scene::vector::Floats;
use crate::scene::write::{body, exact_camera, floats};
use crate::scene::{Location, Scene, SceneError};

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
        let header = schema::RecordingFile {
            recording: Some(schema::Header {
                format: unplaced(FORMAT.to_owned()),
                version: unplaced(VERSION),
                scene: unplaced(scene_text.to_owned()),
                settings: unplaced(settings.into()),
            }),
            ..Default::default()
        };
        let header = toml::to_string(&header).map_err(io::Error::other)?;
        write!(
            out,
            "# nudge session recording: `nudge replay FILE` plays it\n{header}"
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
            self.write(input_of(*step, input))?;
            self.last_step = *step;
        }
        Ok(())
    }

    /// The session rewound to `step` and went on differently.
    pub fn truncate(&mut self, step: u64) -> io::Result<()> {
        self.last_step = step;
        // The views written from `step` on are dropped with the inputs: the next one is written.
        self.last_camera = None;
        self.write(schema::Input {
            step,
            truncate: Some(true),
            ..Default::default()
        })
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
        self.write(schema::Input {
            step,
            camera: Some(exact_camera(camera)),
            ..Default::default()
        })
    }

    /// Pushes what is buffered to the file.
    pub fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Writes the end: the session ran `steps` steps.
    pub fn finish(mut self, steps: u64) -> io::Result<()> {
        let end = schema::RecordingFile {
            end: Some(schema::End { step: steps }),
            ..Default::default()
        };
        let end = toml::to_string(&end).map_err(io::Error::other)?;
        write!(self.out, "\n{end}")?;
        self.out.flush()
    }

    fn write(&mut self, input: schema::Input) -> io::Result<()> {
        let text = input_text(input).map_err(io::Error::other)?;
        self.out.write_all(text.as_bytes())
    }
}

/// One `[[input]]` as the format shows it: its step, then its entry on one line, a table written
/// inline (`force = { body = 3, ... }`). toml's document writer would give the table a section of
/// its own (`[input.force]` and a line a key); the settings, 26 keys, keep theirs. The keys are
/// the schema's field names.
fn input_text(input: schema::Input) -> Result<String, toml::ser::Error> {
    macro_rules! one_line {
        ($($key:ident),*) => {$(
            if let Some(value) = &input.$key {
                let mut text = format!("\n[[input]]\nstep = {}\n{} = ", input.step, stringify!($key));
                value.serialize(toml::ser::ValueSerializer::new(&mut text))?;
                return Ok(text + "\n");
            }
        )*};
    }
    one_line!(
        force, impulse, hold, set_static, gravity, wake, add_body, add_joint, resize, reset,
        camera, truncate
    );
    let file = schema::RecordingFile {
        input: vec![unplaced(input)],
        ..Default::default()
    };
    Ok(format!("\n{}", toml::to_string(&file)?))
}

/// The `[[input]]` table of `input`, applied at `step`.
fn input_of(step: u64, input: &WorldInput) -> schema::Input {
    let mut table = schema::Input {
        step,
        ..Default::default()
    };
    match input {
        WorldInput::Force { body, force, point } => {
            table.force = Some(schema::Force {
                body: body.0,
                force: floats(*force),
                point: floats(*point),
            });
        }
        WorldInput::Impulse {
            body,
            impulse,
            point,
        } => {
            table.impulse = Some(schema::Impulse {
                body: body.0,
                impulse: floats(*impulse),
                point: floats(*point),
            });
        }
        WorldInput::Hold(h) => {
            table.hold = Some(schema::Hold {
                body: h.body.0,
                anchor: floats(h.anchor),
                from: floats(h.from),
                to: floats(h.to),
                hertz: h.spring.hertz,
                damping_ratio: h.spring.damping_ratio,
                max_force: h.spring.max_force,
                max_speed: h.spring.max_speed,
                spin_time: h.spin_time,
            });
        }
        WorldInput::SetStatic { body, is_static } => {
            table.set_static = Some(schema::SetStatic {
                body: body.0,
                is_static: *is_static,
            });
        }
        WorldInput::Gravity(g) => table.gravity = Some(floats(*g)),
        WorldInput::Wake(body) => table.wake = Some(body.0),
        WorldInput::AddBody(desc) => table.add_body = Some(body(desc, false, None)),
        WorldInput::AddJoint(desc) => table.add_joint = Some(joints::exact(desc)),
        WorldInput::Resize { body, shape } => {
            let (half_extents, radius) = match *shape {
                Shape::Cuboid { half_extents } => (Some(floats(half_extents)), None),
                Shape::Sphere { radius } => (None, Some(radius)),
            };
            table.resize = Some(schema::Resize {
                body: body.0,
                half_extents,
                radius,
            });
        }
        WorldInput::Reset => table.reset = Some(true),
        WorldInput::Settings(settings) => table.settings = Some((&**settings).into()),
    }
    table
}

impl From<&Settings> for schema::Settings {
    fn from(s: &Settings) -> Self {
        schema::Settings {
            gravity: floats(s.gravity),
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
            alternate_sub_steps: s.alternate_sub_steps,
            alternate_layer_order: s.alternate_layer_order,
            symmetric_relax: s.symmetric_relax,
            symmetric_biased_pass: s.symmetric_biased_pass,
            preload: s.preload,
            determinate_preload: s.determinate_preload,
            feed_load_changes: s.feed_load_changes,
            feed_moment_changes: s.feed_moment_changes,
            balance_new_supports: s.balance_new_supports,
            touching_tolerance: s.touching_tolerance,
            touching_spring: s.touching_spring,
            friction_anchors: s.friction_anchors,
            anchor_frequency_cap: s.anchor_frequency_cap,
            thin_soft_range: s.thin_soft_range,
            sleep_waits_for_springs: s.sleep_waits_for_springs,
            sleep_waits_while_speeding_up: s.sleep_waits_while_speeding_up,
            piles_carry_blows: s.piles_carry_blows,
            statics_skip_jointed: s.statics_skip_jointed,
            rolling_held_mass_alone: s.rolling_held_mass_alone,
            joint_geometric_stiffness: s.joint_geometric_stiffness,
            joint_scalar_rows_last: s.joint_scalar_rows_last,
            joint_pull_from_load: s.joint_pull_from_load,
            joint_tree: s.joint_tree,
            statics_reuse: s.statics_reuse,
        }
    }
}

/// The settings `raw` gives, if every value is one the solver can use.
fn settings_of(raw: &schema::Settings) -> Result<Settings, String> {
    let s = Settings {
        gravity: Vec3::from_array(raw.gravity.0),
        dt: raw.dt,
        substeps: raw.substeps,
        iterations: raw.iterations,
        sleep: raw.sleep,
        linear_damping: raw.linear_damping,
        angular_damping: raw.angular_damping,
        contact_hertz: raw.contact_hertz,
        contact_damping_ratio: raw.contact_damping_ratio,
        max_push_out_velocity: raw.max_push_out_velocity,
        restitution_threshold: raw.restitution_threshold,
        linear_slop: raw.linear_slop,
        speculative_distance: raw.speculative_distance,
        manifold_reuse_distance: raw.manifold_reuse_distance,
        sleep_linear_threshold: raw.sleep_linear_threshold,
        sleep_angular_threshold: raw.sleep_angular_threshold,
        time_to_sleep: raw.time_to_sleep,
        max_linear_speed: raw.max_linear_speed,
        max_angular_speed: raw.max_angular_speed,
        shock_propagation: raw.shock_propagation,
        mass_ratio_threshold: raw.mass_ratio_threshold,
        mass_ratio_iterations: raw.mass_ratio_iterations,
        spread_row: raw.spread_row,
        alternate_point_order: raw.alternate_point_order,
        alternate_sub_steps: raw.alternate_sub_steps,
        alternate_layer_order: raw.alternate_layer_order,
        symmetric_relax: raw.symmetric_relax,
        symmetric_biased_pass: raw.symmetric_biased_pass,
        preload: raw.preload,
        determinate_preload: raw.determinate_preload,
        feed_load_changes: raw.feed_load_changes,
        feed_moment_changes: raw.feed_moment_changes,
        balance_new_supports: raw.balance_new_supports,
        touching_tolerance: raw.touching_tolerance,
        touching_spring: raw.touching_spring,
        friction_anchors: raw.friction_anchors,
        anchor_frequency_cap: raw.anchor_frequency_cap,
        thin_soft_range: raw.thin_soft_range,
        sleep_waits_for_springs: raw.sleep_waits_for_springs,
        sleep_waits_while_speeding_up: raw.sleep_waits_while_speeding_up,
        piles_carry_blows: raw.piles_carry_blows,
        statics_skip_jointed: raw.statics_skip_jointed,
        rolling_held_mass_alone: raw.rolling_held_mass_alone,
        joint_geometric_stiffness: raw.joint_geometric_stiffness,
        joint_scalar_rows_last: raw.joint_scalar_rows_last,
        joint_pull_from_load: raw.joint_pull_from_load,
        joint_tree: raw.joint_tree,
        statics_reuse: raw.statics_reuse,
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
        s.touching_tolerance,
    ];
    if !s.gravity.is_finite() || floats.iter().any(|x| !x.is_finite()) {
        return Err("every setting must be finite".into());
    }
    if s.dt <= 0.0 {
        return Err(format!("dt must be > 0, got {}", short(s.dt)));
    }
    limits::check_settings(&s)?;
    Ok(s)
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

/// The header's `format` and `version` alone, read leniently (other keys ignored, either may be
/// missing) before the whole file is read as a [`schema::RecordingFile`]: another format or version
/// is named as such, not as an unknown key.
#[derive(Deserialize)]
struct ProbeFile {
    recording: Option<Spanned<ProbeHeader>>,
}

#[derive(Deserialize)]
struct ProbeHeader {
    format: Option<Spanned<String>>,
    version: Option<Spanned<i64>>,
}

impl schema::Hold {
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

/// The shape a resize gives: `half_extents` for a box or `radius` for a sphere.
fn resized(resize: &schema::Resize) -> Result<Shape, String> {
    let shape = match (resize.half_extents, resize.radius) {
        (Some(h), None) => Shape::cuboid(Vec3::from_array(h.0)),
        (None, Some(r)) => Shape::sphere(r),
        _ => return Err("a resize has half_extents (a box) or radius (a sphere)".into()),
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
        Err(format!("{name} must be finite, got {}", short_vec(v)))
    }
}

/// What one `[[input]]` holds.
enum Entry {
    World(WorldInput),
    Camera(Camera),
    Truncate,
}

/// Why an input was refused: a message for the input as a whole, or a body or a camera refused by
/// the scene file's rules, located at its value.
enum Refusal {
    Input(String),
    Value(SceneError),
}

impl From<String> for Refusal {
    fn from(message: String) -> Self {
        Refusal::Input(message)
    }
}

impl From<SceneError> for Refusal {
    fn from(err: SceneError) -> Self {
        Refusal::Value(err)
    }
}

impl schema::Input {
    /// The entry, checked. `source` is the recording's text (an added body or a camera is checked
    /// there as a scene file's is), `span` this input's place in it and `scene` the starting
    /// world, which frames a camera that leaves keys out.
    fn entry(&self, source: &Source, span: Range<usize>, scene: &Scene) -> Result<Entry, Refusal> {
        let given = [
            self.force.is_some(),
            self.impulse.is_some(),
            self.hold.is_some(),
            self.set_static.is_some(),
            self.gravity.is_some(),
            self.wake.is_some(),
            self.add_body.is_some(),
            self.add_joint.is_some(),
            self.resize.is_some(),
            self.reset.is_some(),
            self.settings.is_some(),
            self.camera.is_some(),
            self.truncate.is_some(),
        ];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(Refusal::Input(
                "an input has a step and exactly one of force, impulse, hold, set_static, gravity, \
                 wake, add_body, add_joint, resize, reset, settings, camera, truncate"
                    .into(),
            ));
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
            Entry::World(WorldInput::AddBody(source.body(desc, 0)?.desc))
        } else if let Some(joint) = &self.add_joint {
            // Whether its bodies exist when it is applied is checked with the other inputs'.
            let ends = Ends::Count(u32::MAX as usize);
            Entry::World(WorldInput::AddJoint(source.joint(joint, &ends)?))
        } else if let Some(r) = &self.resize {
            Entry::World(WorldInput::Resize {
                body: BodyId(r.body),
                shape: resized(r)?,
            })
        } else if let Some(reset) = self.reset {
            if !reset {
                return Err(Refusal::Input("reset is written reset = true".into()));
            }
            Entry::World(WorldInput::Reset)
        } else if let Some(settings) = &self.settings {
            Entry::World(WorldInput::Settings(Box::new(settings_of(settings)?)))
        } else if let Some(camera) = &self.camera {
            Entry::Camera(source.camera(camera, span, &scene.bodies, false)?)
        } else {
            if self.truncate != Some(true) {
                return Err(Refusal::Input("truncate is written truncate = true".into()));
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
    let no_header = || {
        at(
            0..0,
            format!("not a nudge recording: no [recording] table (expected format = \"{FORMAT}\")"),
        )
    };
    let probe: ProbeFile = toml::from_str(text).map_err(syntax)?;
    let Some(header) = probe.recording else {
        return Err(no_header());
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
    let raw: schema::RecordingFile = toml::from_str(text).map_err(syntax)?;
    let header = raw.recording.ok_or_else(no_header)?;

    let scene_span = header.scene.span();
    let scene_line = Location::of_offset(text, scene_span.start).line;
    let scene = crate::scene::file::parse(header.scene.get_ref(), source_name).map_err(|err| {
        RecordingError {
            source_name: source_name.to_owned(),
            // The scene text starts on the line after `scene = """`.
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
    let settings =
        settings_of(header.settings.get_ref()).map_err(|m| at(header.settings.span(), m))?;

    let source = Source::new(source_name, text);
    let mut inputs: Vec<(u64, WorldInput, Location)> = Vec::new();
    let mut cameras: Vec<(u64, Camera)> = Vec::new();
    let mut last_step = 0;
    for input in &raw.input {
        let span = input.span();
        let step = input.get_ref().step;
        let entry = input
            .get_ref()
            .entry(&source, span.clone(), &scene)
            .map_err(|refusal| match refusal {
                Refusal::Input(message) => at(span.clone(), message),
                Refusal::Value(err) => RecordingError {
                    source_name: source_name.to_owned(),
                    location: err.location,
                    message: err.message,
                },
            })?;
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
            WorldInput::AddJoint(desc) => desc.a.filter(|a| a.index() >= bodies).or(Some(desc.b)),
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
