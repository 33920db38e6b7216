//! Scene files: a TOML description of a world, its camera and its bodies.
//!
//! # Format
//!
//! Four parts, all optional: `[world]`, `[camera]`, any number of `[[body]]` tables (a file with
//! no bodies is a valid, empty scene) and any number of `[[joint]]` tables joining them. Units are SI (metres, kilograms, seconds); angles in the file
//! are degrees; the world is right-handed with y up. Every key is listed below (the camera's exact
//! forms under Camera); any other key is an error. The tables are `scene::schema`'s, which saved
//! worlds and recordings are written and read through as well. Numbers may be written as integers (`mass = 2`); TOML's `nan` and `inf` are accepted by the
//! parser and then rejected wherever a value must be finite (everywhere).
//!
//! ```toml
//! [world]
//! gravity = [0.0, -9.81, 0.0]      # m/s², default as shown
//! dt = 0.016666667                 # fixed physics step in s, default 1/60
//!
//! [camera]                         # optional; a sensible default frames the scene
//! position = [0.0, 4.0, -12.0]     # m; default: in front (−z) and above the bodies
//! target = [0.0, 1.0, 0.0]         # m; must differ from position; default: centre of the bodies
//! projection = "perspective"       # or "orthographic"; default "perspective"
//! fov_deg = 70.0                   # vertical, in (0, 180); default 70
//!
//! [[body]]                         # a static floor slab whose top face is at y = 0
//! shape = "box"
//! half_extents = [6.0, 0.5, 4.0]
//! position = [0.0, -0.5, 0.0]
//! static = true
//!
//! [[body]]
//! shape = "box"                    # or "sphere"
//! half_extents = [0.5, 0.5, 0.5]   # m, box only
//! position = [0.0, 0.5, 0.0]       # m, centre of mass
//! rotation_axis = [0.0, 1.0, 0.0]  # optional, with rotation_deg (axis-angle)
//! rotation_deg = 30.0
//! velocity = [0.0, 0.0, 0.0]       # optional, m/s
//! angular_velocity = [0.0, 0.0, 0.0]  # optional, rad/s, world frame
//! density = 1.0                    # optional, kg/m³, default 1.0; mass = density * volume
//! mass = 2.0                       # optional, kg; overrides density
//! static = false                   # optional; static bodies never move
//! frozen = false                   # optional; a body held still until the sandbox unfreezes it
//! friction = 0.5                   # optional, >= 0, default 0.5
//! restitution = 0.0                # optional, in [0, 1], default 0
//! rolling_resistance = 0.0         # optional, >= 0, default 0 (balls roll and spin forever)
//! color = "#c08040"                # optional, "#rrggbb"
//!
//! [[body]]
//! shape = "sphere"
//! name = "ball"                    # optional, unique: what a joint calls the body
//! radius = 0.5                     # m, sphere only
//! position = [1.5, 3.0, 0.5]
//! orientation = [0.0, 0.0, 0.0, 1.0]  # optional unit quaternion [x, y, z, w], instead of axis-angle
//! velocity = [-1.0, 0.0, 0.0]
//! angular_velocity = [0.0, 0.0, 2.0]
//! density = 2.5
//! friction = 0.3
//! restitution = 0.6
//! rolling_resistance = 0.03
//!
//! [[joint]]                        # the ball swings on a hinge from the world
//! kind = "hinge"                   # ball | hinge | slider | fixed | distance
//! a = "world"                      # a body's name, its 0-based index, or "world" (the default)
//! b = "ball"
//! anchor = [1.5, 4.0, 0.5]         # m, world, in the initial pose (ball, hinge, slider, fixed)
//! axis = [0.0, 0.0, 1.0]           # hinge and slider
//! limits = [-45.0, 45.0]           # optional: degrees (hinge) or metres (slider)
//! motor_speed = 0.0                # optional, rad/s (hinge) or m/s (slider), with motor_max
//! motor_max = 5.0                  # N·m (hinge) or N (slider)
//! friction = 0.2                   # optional, N·m (ball, hinge) or N (slider): to turn or slide it
//! collide = false                  # optional: whether the two bodies still collide
//!
//! [[joint]]                        # a spring from the box's top to the ball
//! kind = "distance"
//! a = 1
//! b = "ball"
//! anchor_a = [0.0, 1.0, 0.0]       # m, world, on a (distance joints give two anchors)
//! anchor_b = [1.5, 3.0, 0.5]       # on b
//! length = 1.5                     # optional, m; default: the anchors' distance
//! min_length = 0.5                 # optional, default length (max_length alone: a rope)
//! max_length = 3.0                 # optional, default length
//! stiffness_hz = 2.0               # optional: a spring, Hz, with damping_ratio
//! damping_ratio = 0.3
//! ```
//!
//! ## Rules
//!
//! - `[world]`: `gravity` is a finite vector (default `[0, -9.81, 0]`); `dt` is finite and > 0.
//! - `[[body]]` needs `shape` (`"box"` or `"sphere"`) and `position`. A box needs `half_extents`
//!   (each finite and > 0) and must not have `radius`; a sphere needs `radius` (finite and > 0) and must
//!   not have `half_extents`.
//! - Orientation is axis-angle: `rotation_axis` (finite, not zero; normalised for you) and
//!   `rotation_deg` (finite) come together or not at all. Or a unit quaternion
//!   `orientation = [x, y, z, w]` (what a saved world uses: it loads back bit for bit): finite, within
//!   1e-3 of unit length, then normalised; never together with `rotation_axis`/`rotation_deg`.
//!   Default: no rotation.
//! - Mass: `mass` (kg) if given, else `density` (kg/m³, default 1) × volume. Both, when given, must be
//!   finite and > 0, and the resulting mass and moments of inertia must be representable (finite, > 0).
//!   Static bodies have a mass too (it is used if the body is unfrozen in the sandbox).
//! - `static = true` bodies never move; they cannot have a non-zero `velocity` or `angular_velocity`.
//! - `frozen = true` bodies are held still as static ones are (same rules), but they are bodies, not
//!   scenery: their mass is held to a dynamic body's range, they take the palette's colours, and the
//!   sandbox draws them as frozen and unfreezes them (`f`, middle click). Ctrl+S writes a body frozen
//!   in the sandbox this way. `frozen = true` with `static = true` is an error.
//! - `friction` finite and ≥ 0 (default 0.5); `restitution` in [0, 1] (default 0);
//!   `rolling_resistance` finite and ≥ 0 (default 0; a ball of radius r under normal force N meets a
//!   resisting torque up to `rolling_resistance` × N × r, so a rolling ball slows at 5/7 of it × g;
//!   the same torque resists a ball spinning in place).
//! - `color` is `"#rrggbb"`. Default: static bodies are grey (#808488); the n-th dynamic body (counting
//!   from 0 in file order, static bodies not counted) gets colour n mod 6 of the palette
//!   #c08040, #d05040, #4090d0, #60b050, #e0c040, #a060c0.
//! - Two bodies in contact use the geometric mean of their frictions, the larger restitution and the
//!   larger rolling resistance.
//! - Bodies keep their file order: the i-th `[[body]]` is body i in the world and in `nudge sim` traces.
//! - `name` is optional and unique (and not `"world"`); a joint names a body by it or by its index.
//! - `[[joint]]` needs `kind` and `b` (a body); `a` is a body or the world (left out, or `"world"`),
//!   never `b` itself, and one end at least moves (not both static). Ball, hinge, slider and fixed
//!   joints give one `anchor`; distance joints `anchor_a` and `anchor_b`; hinges and sliders an
//!   `axis` (finite, not zero). Only hinges and sliders have `limits` (lower first) and a motor
//!   (`motor_speed` and `motor_max` ≥ 0, both or neither); only distance joints have the lengths
//!   (≥ 0, `min_length` ≤ `max_length`) and a spring (`stiffness_hz` ≥ 0, `damping_ratio` ≥ 0, default
//!   0). Ball joints, hinges and sliders may have `friction` (≥ 0, default 0): the torque or force
//!   it takes to turn or slide the joint. Bodies joined by a joint do not collide with each other
//!   unless `collide = true`.
//! - The exact form a saved world writes (`scene::joints`) is accepted too: the frames in the
//!   bodies' own coordinates, `local_anchor_a`, `local_anchor_b`, `local_axis_a`, `local_axis_b` and
//!   `reference` (B's rotation relative to A's, a quaternion), bodies by index, hinge limits in
//!   radians (`limits_rad`) and the distance joint's `length`, `min_length` and `max_length` all
//!   given.
//!
//! ## Representable range
//!
//! The engine computes in f32, so a finite value is not therefore usable (see `physics::limits`).
//! Values outside these ranges are refused with a located error, in files, on the command line and in
//! the sandbox; inside them every step stays finite (`tests/physics/hostile_scenes.rs` checks the corners and
//! runs a seeded scene-file fuzzer).
//!
//! | what | range |
//! |---|---|
//! | `radius`, each of `half_extents` | 0.001 to 1000 m |
//! | each coordinate of `position`, camera `position` and `target` | within 10,000 m of the origin |
//! | mass of a dynamic body (given, or density × volume) | 1 mg to 1000 t |
//! | dynamic bodies of one scene | bounding radii within a factor of 10,000, masses within 1,000,000 |
//! | `dt` | 0.0001 to 0.1 s |
//! | `gravity` | at most 1000 m/s² long |
//! | `velocity`, `angular_velocity` | at most 400 m/s and 200 rad/s long (the engine's speed caps) |
//! | `friction`, `rolling_resistance` | at most 10 and 1 |
//! | bodies | at most 20,000 (spawning in the sandbox stops there too) |
//! | file size | at most 64 MB read |
//! | touching pairs per step | 128 per moving or sleeping body, 100,000 in all (`physics::contact_cap`): the pairs beyond are ignored, and `sim` and the status bar say so (`tests/physics/contact_caps.rs`) |
//!
//! Vectors have exactly three numbers (`orientation` four): `position = [0, 3, 0, 1]` is an error.
//! A finite number beyond what an f32 holds is refused as written (`1e308 is beyond what a 32-bit
//! float holds (±3.4e38)`), a quoted value is cut at 60 characters, and a file that is not UTF-8 is
//! reported at the line and column of its first bad byte.
//!
//! ## Camera
//!
//! - `position` and `target` are finite and must differ. `fov_deg` is the vertical field of view, in
//!   (0, 180), default 70.
//! - Orthographic cameras show a slab of height `2 · |target − position| · tan(fov_deg / 2)`: exactly
//!   what the perspective camera with the same `fov_deg` shows in the plane of the target, so the target
//!   area is framed the same way in both projections (and switching projection in the sandbox keeps it).
//! - The exact forms a recording writes (`scene::schema`: one camera table for both) are accepted too:
//!   `fov_y` (radians, in (0, π)) instead of `fov_deg`; `view_height` (m, > 0) for an orthographic
//!   slab of that height, with no field of view and no `projection = "perspective"`; `up` (finite;
//!   default +y); `near` and `far` (m, 0 < near < far; default 0.1, and far enough to see every body
//!   from the camera, at least 500).
//! - Without `[camera]`, or for keys it leaves out, the camera is computed from the bodies: it looks
//!   along +z from in front and 25° above, placed so that the dynamic bodies, where they come to rest
//!   when dropped straight down, are centred and fill the middle 90% of a 3:2 image (a 120×40
//!   terminal) across its tighter direction; the static bodies near them are kept in view top to
//!   bottom and may run off the sides. See `scene::framing` for the exact rule.
//!
//! ## Errors
//!
//! Every problem is reported as `FILE:LINE:COLUMN: what is wrong` (1-based; the column counts
//! characters), pointing at the offending value, or for a missing key at the table or the `shape` that
//! needs it, e.g. `scenes/bad.toml:7:10: radius must be finite and > 0, got -1`. `nudge` exits with
//! status 2.

use std::ops::Range;

use glam::{Quat, Vec3};
use toml::Spanned;

use super::error::{SceneError, SceneErrorKind};
use super::framing::{self, DEFAULT_FOV_DEG};
use super::schema;
use super::text_file::read_text;
use super::vector::{Float, Floats};
mod joints;

pub(crate) use joints::Ends;

use super::{Scene, SceneBody};
use crate::color::Rgb;
use crate::color::{FLOOR_COLOR, PALETTE};
use crate::geometry::{Camera, Pose, Projection, Shape};
use crate::physics::limits::{self, short as num, short_vec as vec};
use crate::physics::{BodyDesc, Settings};

/// How far from unit length an `orientation` quaternion may be before it is an error (it is
/// normalised): room for a hand-edited or rounded file, none for a typo.
pub const ORIENTATION_TOLERANCE: f32 = 1e-3;

/// The example above, every key used once (but the camera's exact forms); kept identical to the doc
/// comment by a test.
pub const EXAMPLE: &str = include_str!("example.toml");

/// Reads and parses the scene file at `path`; messages name the file as `path` is spelled. Reads at
/// most [`MAX_FILE_BYTES`](super::text_file::MAX_FILE_BYTES); text that is not UTF-8 is reported at its first bad byte.
pub fn load_file(path: &str) -> Result<Scene, SceneError> {
    let text = read_text(path).map_err(|err| SceneError {
        location: err.location(),
        ..SceneError::new(SceneErrorKind::Io, path, err.message("scene file"))
    })?;
    parse(&text, path)
}

/// Parses scene-file text; `source_name` names it in messages and becomes the scene's name.
pub fn parse(text: &str, source_name: &str) -> Result<Scene, SceneError> {
    let file = Source::new(source_name, text);
    let raw: schema::SceneFile = toml::from_str(text).map_err(|err| {
        let span = err.span().unwrap_or(0..0);
        let message = err.message().trim_end();
        let message = match key_before(text, span.start) {
            Some(key) => format!("{key}: {message}"),
            None => message.to_owned(),
        };
        file.error_kind(SceneErrorKind::Syntax, span, &message)
    })?;

    let mut settings = Settings::default();
    if let Some(world) = &raw.world {
        if let Some(gravity) = &world.gravity {
            let g = file.finite_vec("gravity", gravity)?;
            let limit = limits::check_length("gravity (m/s²)", g, limits::MAX_GRAVITY);
            settings.gravity = file.check(gravity.span(), limit.map(|()| g))?;
        }
        if let Some(dt) = &world.dt {
            let value = file.positive("dt", dt)?;
            let limit = limits::in_range("dt (s)", value, limits::MIN_DT, limits::MAX_DT);
            settings.dt = file.check(dt.span(), limit)?;
        }
    }

    if let Some(body) = raw.body.get(limits::MAX_BODIES) {
        return Err(file.error(
            body.shape.span(),
            format!(
                "a scene holds at most {} bodies; this is body {}",
                limits::MAX_BODIES,
                limits::MAX_BODIES + 1
            ),
        ));
    }
    let mut bodies = Vec::with_capacity(raw.body.len());
    let mut dynamic_index = 0;
    for body in &raw.body {
        let scene_body = file.body(body, dynamic_index)?;
        if !scene_body.desc.is_static || scene_body.frozen {
            dynamic_index += 1;
        }
        bodies.push(scene_body);
    }

    file.check_ratios(&raw.body, &bodies)?;
    let mut names: Vec<(String, usize)> = Vec::new();
    for (i, body) in raw.body.iter().enumerate() {
        if let Some(name) = &body.name {
            let taken = name.get_ref() == "world" || names.iter().any(|(n, _)| n == name.get_ref());
            if taken {
                return Err(file.error(
                    name.span(),
                    format!(
                        "the name {:?} is taken (names are unique, and not \"world\")",
                        name.get_ref()
                    ),
                ));
            }
            names.push((name.get_ref().clone(), i));
        }
    }
    let ends = joints::Ends::Scene {
        bodies: &bodies,
        names: &names,
    };
    let joints = raw
        .joint
        .iter()
        .map(|joint| file.joint(joint, &ends))
        .collect::<Result<Vec<_>, _>>()?;
    let camera = match &raw.camera {
        Some(camera) => file.camera(camera.get_ref(), camera.span(), &bodies, true)?,
        None => {
            // A body a joint holds hangs where it is; the others are framed where they land.
            let mut held = vec![false; bodies.len()];
            for joint in &joints {
                for id in [joint.a, Some(joint.b)].into_iter().flatten() {
                    held[id.index()] = true;
                }
            }
            framing::auto_camera_held(&bodies, &held, DEFAULT_FOV_DEG.to_radians())
        }
    };
    Ok(Scene {
        name: source_name.to_owned(),
        settings,
        camera,
        bodies,
        joints,
    })
}

/// The text being parsed and its name: turns spans into located errors. Recordings check the
/// bodies and cameras they hold through it too (`recording`), so each table has one set of rules.
pub(crate) struct Source<'a> {
    name: &'a str,
    text: &'a str,
}

type Checked<T> = Result<T, SceneError>;

impl<'a> Source<'a> {
    /// `text`, named `name` in messages.
    pub(crate) fn new(name: &'a str, text: &'a str) -> Self {
        Self { name, text }
    }

    fn error_kind(&self, kind: SceneErrorKind, span: Range<usize>, message: &str) -> SceneError {
        SceneError::at(kind, self.name, self.text, span, message)
    }

    fn error(&self, span: Range<usize>, message: impl AsRef<str>) -> SceneError {
        self.error_kind(SceneErrorKind::Invalid, span, message.as_ref())
    }

    /// A range check's result, its message located at `span`.
    fn check<T>(&self, span: Range<usize>, result: Result<T, String>) -> Checked<T> {
        result.map_err(|message| self.error(span, message))
    }

    /// The sizes and masses of the dynamic bodies differ by at most [`limits::MAX_SIZE_RATIO`] and
    /// [`limits::MAX_MASS_RATIO`]; an error is located at the later body of the offending pair.
    fn check_ratios(&self, raw: &[schema::Body], bodies: &[SceneBody]) -> Checked<()> {
        type Measure = fn(&BodyDesc) -> f32;
        let measures: [(&str, &str, f32, Measure); 2] = [
            ("size", "m", limits::MAX_SIZE_RATIO, |d| {
                d.shape.bounding_radius()
            }),
            ("mass", "kg", limits::MAX_MASS_RATIO, |d| d.mass),
        ];
        for (what, unit, most, measure) in measures {
            let mut extremes: Option<((usize, f32), (usize, f32))> = None;
            for (i, body) in bodies.iter().enumerate() {
                // A frozen body counts: the sandbox may unfreeze it.
                if body.desc.is_static && !body.frozen {
                    continue;
                }
                let v = measure(&body.desc);
                let ((lo_i, lo), (hi_i, hi)) = *extremes.get_or_insert(((i, v), (i, v)));
                let (lo, hi) = (
                    if v < lo { (i, v) } else { (lo_i, lo) },
                    if v > hi { (i, v) } else { (hi_i, hi) },
                );
                extremes = Some((lo, hi));
                if hi.1 > most * lo.1 {
                    return Err(self.error(
                        raw[i].shape.span(),
                        format!(
                            "dynamic bodies of one scene may differ in {what} by a factor of {} at most: \
                             [[body]] #{} is {} {unit}, [[body]] #{} is {} {unit}",
                            num(most),
                            lo.0 + 1,
                            num(lo.1),
                            hi.0 + 1,
                            num(hi.1)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// The value of key `name`, which must be finite and ≥ 0.
    fn non_negative(&self, value: &Spanned<Float>, name: &str) -> Result<f32, SceneError> {
        let x = value.get_ref().0;
        if x.is_finite() && x >= 0.0 {
            Ok(x)
        } else {
            Err(self.error(
                value.span(),
                format!("{name} must be finite and >= 0, got {}", num(x)),
            ))
        }
    }

    fn finite(&self, key: &str, value: &Spanned<Float>) -> Checked<f32> {
        let v = value.get_ref().0;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                format!("{key} must be finite, got {}", num(v)),
            ))
        }
    }

    fn positive(&self, key: &str, value: &Spanned<Float>) -> Checked<f32> {
        let v = value.get_ref().0;
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                format!("{key} must be finite and > 0, got {}", num(v)),
            ))
        }
    }

    fn finite_vec(&self, key: &str, value: &Spanned<Floats<3>>) -> Checked<Vec3> {
        let v = Vec3::from_array(value.get_ref().0);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.error(
                value.span(),
                format!("{key} must be finite, got {}", vec(v)),
            ))
        }
    }

    /// A body, coloured from the palette by `dynamic_index` (counting the bodies before it that are
    /// not scenery) unless it names its colour.
    pub(crate) fn body(&self, raw: &schema::Body, dynamic_index: usize) -> Checked<SceneBody> {
        let shape = self.shape(raw)?;
        let position = self.finite_vec("position", &raw.position)?;
        self.check(
            raw.position.span(),
            limits::check_position("position", position),
        )?;
        let rotation = self.rotation(raw)?;
        let frozen = match &raw.frozen {
            Some(f) if *f.get_ref() && raw.is_static == Some(true) => {
                return Err(self.error(
                    f.span(),
                    "a body is either static (scenery) or frozen (a body held still), not both",
                ));
            }
            Some(f) => *f.get_ref(),
            None => false,
        };
        let is_static = raw.is_static.unwrap_or(false) || frozen;
        let caps = Settings::default();
        let linear_velocity = self.velocity(
            "velocity",
            raw.velocity.as_ref(),
            is_static,
            ("m/s", caps.max_linear_speed),
        )?;
        let angular_velocity = self.velocity(
            "angular_velocity",
            raw.angular_velocity.as_ref(),
            is_static,
            ("rad/s", caps.max_angular_speed),
        )?;
        // A frozen body's mass is a dynamic body's: the sandbox may unfreeze it.
        let mass = self.mass(raw, &shape, is_static && !frozen)?;

        let mut desc = BodyDesc::dynamic(shape, Pose::new(position, rotation), mass);
        desc.is_static = is_static;
        desc.linear_velocity = linear_velocity;
        desc.angular_velocity = angular_velocity;
        if let Some(friction) = &raw.friction {
            let mu = self.non_negative(friction, "friction")?;
            let limit = limits::in_range("friction", mu, 0.0, limits::MAX_FRICTION);
            desc.friction = self.check(friction.span(), limit)?;
        }
        if let Some(restitution) = &raw.restitution {
            let e = restitution.get_ref().0;
            if !(0.0..=1.0).contains(&e) {
                return Err(self.error(
                    restitution.span(),
                    format!("restitution must be in [0, 1], got {}", num(e)),
                ));
            }
            desc.restitution = e;
        }
        if let Some(rolling) = &raw.rolling_resistance {
            let mu = self.non_negative(rolling, "rolling_resistance")?;
            let limit = limits::in_range(
                "rolling_resistance",
                mu,
                0.0,
                limits::MAX_ROLLING_RESISTANCE,
            );
            desc.rolling_resistance = self.check(rolling.span(), limit)?;
        }

        let color = match &raw.color {
            Some(text) => Rgb::from_hex(text.get_ref()).ok_or_else(|| {
                self.error(
                    text.span(),
                    format!(
                        "color must be \"#rrggbb\" (six hex digits), got {:?}",
                        text.get_ref()
                    ),
                )
            })?,
            None if is_static && !frozen => FLOOR_COLOR,
            None => PALETTE[dynamic_index % PALETTE.len()],
        };
        Ok(SceneBody {
            desc,
            color,
            frozen,
            name: raw.name.as_ref().map(|name| name.get_ref().clone()),
        })
    }

    /// The shape, with exactly the size key its kind needs.
    fn shape(&self, raw: &schema::Body) -> Checked<Shape> {
        match *raw.shape.get_ref() {
            schema::Shape::Box => {
                if let Some(radius) = &raw.radius {
                    return Err(self.error(
                        radius.span(),
                        "radius is for spheres; a box takes half_extents = [x, y, z]",
                    ));
                }
                let Some(half_extents) = &raw.half_extents else {
                    return Err(self.error(
                        raw.shape.span(),
                        "a box needs half_extents = [x, y, z] (metres)",
                    ));
                };
                let h = Vec3::from_array(half_extents.get_ref().0);
                if !(h.is_finite() && h.cmpgt(Vec3::ZERO).all()) {
                    return Err(self.error(
                        half_extents.span(),
                        format!("half_extents must be finite and > 0, got {}", vec(h)),
                    ));
                }
                let shape = Shape::cuboid(h);
                self.check(half_extents.span(), limits::check_shape(&shape))?;
                Ok(shape)
            }
            schema::Shape::Sphere => {
                if let Some(half_extents) = &raw.half_extents {
                    return Err(self.error(
                        half_extents.span(),
                        "half_extents is for boxes; a sphere takes radius",
                    ));
                }
                let Some(radius) = &raw.radius else {
                    return Err(self.error(raw.shape.span(), "a sphere needs radius = r (metres)"));
                };
                let shape = Shape::sphere(self.positive("radius", radius)?);
                self.check(radius.span(), limits::check_shape(&shape))?;
                Ok(shape)
            }
        }
    }

    /// Axis-angle orientation (both keys or neither), or a unit quaternion `orientation`.
    fn rotation(&self, raw: &schema::Body) -> Checked<Quat> {
        if let Some(orientation) = &raw.orientation {
            return self.orientation(orientation, raw);
        }
        match (&raw.rotation_axis, &raw.rotation_deg) {
            (None, None) => Ok(Quat::IDENTITY),
            (Some(axis), None) => Err(self.error(
                axis.span(),
                "rotation_axis needs rotation_deg (the angle about it, degrees)",
            )),
            (None, Some(deg)) => Err(self.error(
                deg.span(),
                "rotation_deg needs rotation_axis (the axis to turn about)",
            )),
            (Some(axis), Some(deg)) => {
                let a = self.finite_vec("rotation_axis", axis)?;
                let Some(unit) = a.try_normalize() else {
                    return Err(self.error(
                        axis.span(),
                        format!("rotation_axis must not be zero, got {}", vec(a)),
                    ));
                };
                let angle = self.finite("rotation_deg", deg)?.to_radians();
                Ok(Quat::from_axis_angle(unit, angle).normalize())
            }
        }
    }

    /// `orientation = [x, y, z, w]`: finite, within [`ORIENTATION_TOLERANCE`] of unit length, alone.
    /// Normalised, unless it is unit already to f32 precision (|q|² within 1e-6 of 1, the rule the
    /// world applies to poses), so a saved orientation loads back bit for bit.
    fn orientation(&self, value: &Spanned<Floats<4>>, raw: &schema::Body) -> Checked<Quat> {
        if raw.rotation_axis.is_some() || raw.rotation_deg.is_some() {
            return Err(self.error(
                value.span(),
                "orientation cannot be given with rotation_axis and rotation_deg: choose one",
            ));
        }
        let q = Quat::from_array(value.get_ref().0);
        let [x, y, z, w] = q.to_array();
        let shown = format!("[{}, {}, {}, {}]", num(x), num(y), num(z), num(w));
        if !q.is_finite() {
            return Err(self.error(
                value.span(),
                format!("orientation must be finite, got {shown}"),
            ));
        }
        let length = q.length();
        if (length - 1.0).abs() > ORIENTATION_TOLERANCE {
            return Err(self.error(
                value.span(),
                format!(
                    "orientation must be a unit quaternion [x, y, z, w] (length within {ORIENTATION_TOLERANCE} of 1), \
                     got {shown} of length {}",
                    num(length)
                ),
            ));
        }
        Ok(if (q.length_squared() - 1.0).abs() > 1e-6 {
            q.normalize()
        } else {
            q
        })
    }

    fn velocity(
        &self,
        key: &str,
        value: Option<&Spanned<Floats<3>>>,
        is_static: bool,
        (unit, cap): (&str, f32),
    ) -> Checked<Vec3> {
        let Some(value) = value else {
            return Ok(Vec3::ZERO);
        };
        let v = self.finite_vec(key, value)?;
        if is_static && v != Vec3::ZERO {
            return Err(self.error(
                value.span(),
                format!(
                    "a static body never moves, so {key} must be zero, got {}",
                    vec(v)
                ),
            ));
        }
        // Faster than the engine's cap would be cut to it silently at the first step.
        let limit = limits::check_length(&format!("{key} ({unit})"), v, cap);
        self.check(value.span(), limit.map(|()| v))
    }

    /// `mass`, else `density` × volume; the mass and inertia must be usable by the solver.
    /// A dynamic body's mass must lie in [`limits::MIN_MASS`, `limits::MAX_MASS`]; a static body's
    /// only be usable (it matters only if the sandbox unfreezes the body).
    fn mass(&self, raw: &schema::Body, shape: &Shape, is_static: bool) -> Checked<f32> {
        let density = match &raw.density {
            Some(density) => self.positive("density", density)?,
            None => 1.0,
        };
        let (mass, span) = match &raw.mass {
            Some(mass) => (self.positive("mass", mass)?, mass.span()),
            None => {
                let mass = density * shape.volume();
                let span = raw
                    .density
                    .as_ref()
                    .map_or_else(|| raw.shape.span(), |d| d.span());
                if !(mass.is_finite() && mass > 0.0) {
                    return Err(self.error(
                        span,
                        format!(
                            "mass = density × volume = {} kg must be finite and > 0; \
                             the body is too small, too large or too dense",
                            num(mass)
                        ),
                    ));
                }
                (mass, span)
            }
        };
        if !is_static {
            let limit = limits::in_range("mass (kg)", mass, limits::MIN_MASS, limits::MAX_MASS);
            self.check(span.clone(), limit)?;
        }
        let inertia = shape.principal_inertia(mass);
        if !(inertia.is_finite() && inertia.cmpgt(Vec3::ZERO).all()) {
            return Err(self.error(
                span,
                format!(
                    "moments of inertia {} kg·m² are not finite and > 0; \
                     size and mass are too extreme",
                    vec(inertia)
                ),
            ));
        }
        Ok(mass)
    }

    /// A camera table (`table_span` is where it is), keys it leaves out taken from the automatic
    /// camera for `bodies`: `[camera]` in a scene file, `camera = { ... }` in a recording. The
    /// representable range of positions holds where `bounded` (a scene: it frames a world to build);
    /// a recorded camera is what the sandbox showed, wherever it had gone.
    pub(crate) fn camera(
        &self,
        raw: &schema::Camera,
        table_span: Range<usize>,
        bodies: &[SceneBody],
        bounded: bool,
    ) -> Checked<Camera> {
        let fov_y = match (&raw.fov_deg, &raw.fov_y) {
            (Some(_), Some(fov_y)) => {
                return Err(self.error(
                    fov_y.span(),
                    "fov_y (radians) and fov_deg (degrees) are one angle: give one",
                ));
            }
            (Some(fov), None) => {
                let v = fov.get_ref().0;
                if !(v > 0.0 && v < 180.0) {
                    return Err(self.error(
                        fov.span(),
                        format!("fov_deg must be in (0, 180) degrees, got {}", num(v)),
                    ));
                }
                v.to_radians()
            }
            (None, Some(fov)) => {
                let v = fov.get_ref().0;
                if !(v > 0.0 && v < std::f32::consts::PI) {
                    return Err(self.error(
                        fov.span(),
                        format!("fov_y must be in (0, π) radians, got {}", num(v)),
                    ));
                }
                v
            }
            (None, None) => DEFAULT_FOV_DEG.to_radians(),
        };
        let projection = raw.projection.as_ref().map(|p| *p.get_ref());
        let view_height = match &raw.view_height {
            Some(height) => {
                if raw.fov_deg.is_some() || raw.fov_y.is_some() {
                    return Err(self.error(
                        height.span(),
                        "view_height sets an orthographic view: give it or a field of view \
                         (fov_deg, fov_y), not both",
                    ));
                }
                if projection == Some(schema::Projection::Perspective) {
                    return Err(self.error(
                        height.span(),
                        "view_height is for projection = \"orthographic\"",
                    ));
                }
                Some(self.positive("view_height", height)?)
            }
            None => None,
        };
        // Framing the bodies costs a pass over them: only for a camera that leaves keys out.
        let auto = || framing::auto_camera(bodies, fov_y);
        let point = |key: &str, value: &Option<Spanned<Floats<3>>>, default: fn(Camera) -> Vec3| {
            let Some(value) = value else {
                return Ok(default(auto()));
            };
            let v = self.finite_vec(key, value)?;
            if bounded {
                self.check(value.span(), limits::check_position(key, v))?;
            }
            Ok(v)
        };
        let position = point("camera position", &raw.position, |c| c.position)?;
        let target = point("camera target", &raw.target, |c| c.target)?;
        if (target - position).try_normalize().is_none() {
            let span = raw
                .target
                .as_ref()
                .or(raw.position.as_ref())
                .map_or(table_span.clone(), |s| s.span());
            return Err(self.error(
                span,
                format!(
                    "camera target must differ from its position, both are {}",
                    vec(target)
                ),
            ));
        }
        let framed_far = || {
            let radius = framing::union(&framing::framed_boxes(bodies)).map_or(0.0, |b| {
                b.half_extents().length() + (b.center() - target).length()
            });
            framing::scene_camera(position, target, fov_y, radius).far
        };
        let mut camera = Camera::perspective(position, target, fov_y);
        if let Some(up) = &raw.up {
            // Not checked against the view: a camera straight above its target has always been
            // drawn (`Camera::basis` falls back to a fixed frame), and recordings of one hold +y.
            camera.up = self.finite_vec("camera up", up)?;
        }
        if let Some(near) = &raw.near {
            camera.near = self.positive("near", near)?;
        }
        camera.far = match &raw.far {
            Some(far) => self.positive("far", far)?,
            None => framed_far(),
        };
        if camera.near >= camera.far {
            let span = raw
                .far
                .as_ref()
                .or(raw.near.as_ref())
                .map_or(table_span, |s| s.span());
            return Err(self.error(
                span,
                format!(
                    "camera near must be < far, got near {} and far {}",
                    num(camera.near),
                    num(camera.far)
                ),
            ));
        }
        if let Some(view_height) = view_height {
            camera.projection = Projection::Orthographic { view_height };
        } else if projection == Some(schema::Projection::Orthographic) {
            camera.projection = framing::orthographic_matching(&camera, fov_y);
        }
        Ok(camera)
    }
}

/// The key of a `key = value` line when byte `offset` lies in its value, so that serde's messages
/// ("invalid type: integer `1`, expected a boolean") can say which key they are about.
fn key_before(text: &str, offset: usize) -> Option<&str> {
    let before = text.get(..offset)?;
    let line = &before[before.rfind('\n').map_or(0, |i| i + 1)..];
    let (key, _) = line.split_once('=')?;
    let key = key.trim();
    let bare = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
    (!key.is_empty() && key.chars().all(bare)).then_some(key)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_ok(text: &str) -> Scene {
        parse(text, "t.toml").unwrap_or_else(|e| panic!("{e}"))
    }

    /// Parses `text`, expecting an error at `line:column` whose message contains `phrase`.
    fn rejects(text: &str, line: usize, column: usize, phrase: &str) -> SceneError {
        let err = parse(text, "t.toml").expect_err("should be rejected");
        let shown = err.to_string();
        assert!(
            shown.starts_with(&format!("t.toml:{line}:{column}: ")),
            "{shown}"
        );
        assert!(shown.contains(phrase), "{shown}");
        err
    }

    const SPHERE: &str = "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0, 1, 0]\n";

    #[test]
    fn the_doc_comment_example_is_the_example_file() {
        let source = include_str!("file.rs");
        let start = source.find("//! ```toml\n").unwrap() + "//! ```toml\n".len();
        let end = start + source[start..].find("//! ```\n").unwrap();
        let from_doc: String = source[start..end]
            .lines()
            .map(|l| {
                format!(
                    "{}\n",
                    l.strip_prefix("//!")
                        .unwrap()
                        .strip_prefix(' ')
                        .unwrap_or("")
                )
            })
            .collect();
        let trimmed: String = EXAMPLE
            .lines()
            .map(|l| format!("{}\n", l.trim_end()))
            .collect();
        assert_eq!(from_doc, trimmed);
    }

    #[test]
    fn the_example_sets_every_value_it_names() {
        let scene = parse_ok(EXAMPLE);
        assert_eq!(scene.name, "t.toml");
        assert_eq!(scene.settings.gravity, Vec3::new(0.0, -9.81, 0.0));
        assert_eq!(scene.settings.dt, 0.016666667);
        assert_eq!(scene.camera.position, Vec3::new(0.0, 4.0, -12.0));
        assert_eq!(scene.camera.target, Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(
            scene.camera.projection,
            Projection::Perspective {
                fov_y: 70f32.to_radians()
            }
        );
        assert_eq!(scene.bodies.len(), 3);

        let floor = &scene.bodies[0];
        assert!(floor.desc.is_static);
        assert_eq!(floor.color, FLOOR_COLOR);
        assert_eq!(floor.desc.mass, 6.0 * 0.5 * 4.0 * 8.0);

        let cube = &scene.bodies[1].desc;
        assert_eq!(cube.shape, Shape::cuboid(Vec3::splat(0.5)));
        assert_eq!(cube.pose.position, Vec3::new(0.0, 0.5, 0.0));
        let expected = Quat::from_rotation_y(30f32.to_radians());
        assert!(cube.pose.rotation.angle_between(expected) < 1e-6);
        assert_eq!(cube.mass, 2.0, "mass overrides density");
        assert!(!cube.is_static);
        assert_eq!((cube.friction, cube.restitution), (0.5, 0.0));
        assert_eq!(scene.bodies[1].color, Rgb::new(0xc0, 0x80, 0x40));

        let ball = &scene.bodies[2];
        assert_eq!(ball.desc.shape, Shape::sphere(0.5));
        assert_eq!(ball.desc.linear_velocity, Vec3::new(-1.0, 0.0, 0.0));
        assert_eq!(ball.desc.angular_velocity, Vec3::new(0.0, 0.0, 2.0));
        let volume = 4.0 / 3.0 * std::f32::consts::PI * 0.125;
        assert!((ball.desc.mass - 2.5 * volume).abs() < 1e-6);
        assert_eq!((ball.desc.friction, ball.desc.restitution), (0.3, 0.6));
        assert_eq!(ball.desc.rolling_resistance, 0.03);
        assert_eq!(
            ball.color, PALETTE[1],
            "second dynamic body, palette index 1"
        );
        assert_eq!(scene.joints.len(), 2);
        assert_eq!(scene.joints[0].friction, 0.2);
    }

    #[test]
    fn an_empty_file_is_an_empty_scene_with_default_settings() {
        let scene = parse_ok("");
        assert!(scene.bodies.is_empty());
        assert_eq!(scene.settings, Settings::default());
        assert_eq!(scene.camera.position, framing::EMPTY_SCENE_POSITION);
    }

    #[test]
    fn integers_are_accepted_where_numbers_are_expected() {
        let scene = parse_ok(
            "[[body]]\nshape = \"box\"\nhalf_extents = [1, 1, 1]\nposition = [0, 2, 0]\nmass = 2\n",
        );
        assert_eq!(scene.bodies[0].desc.mass, 2.0);
    }

    #[test]
    fn without_a_camera_the_view_is_from_in_front_and_above() {
        let scene = parse_ok(SPHERE);
        let camera = scene.camera;
        assert!(camera.position.z < camera.target.z);
        assert!(camera.position.y > camera.target.y);
        assert!((camera.target - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-5);
    }

    #[test]
    fn an_orthographic_camera_shows_what_the_perspective_one_shows_at_the_target() {
        let text = format!(
            "[camera]\nposition = [0, 0, -10]\ntarget = [0, 0, 0]\nprojection = \"orthographic\"\nfov_deg = 90\n{SPHERE}"
        );
        let Projection::Orthographic { view_height } = parse_ok(&text).camera.projection else {
            panic!("not orthographic");
        };
        assert!((view_height - 20.0).abs() < 1e-4, "{view_height}");
    }

    #[test]
    fn a_partial_camera_takes_the_rest_from_the_automatic_one() {
        let only_target = parse_ok(&format!("[camera]\ntarget = [1, 0, 0]\n{SPHERE}"));
        let auto = parse_ok(SPHERE).camera;
        assert_eq!(only_target.camera.position, auto.position);
        assert_eq!(only_target.camera.target, Vec3::X);
    }

    #[test]
    fn default_colours_follow_the_palette_by_dynamic_index_and_static_bodies_are_grey() {
        let text = format!(
            "[[body]]\nshape = \"box\"\nhalf_extents = [5, 0.5, 5]\nposition = [0, -0.5, 0]\nstatic = true\n{SPHERE}{SPHERE}"
        );
        let colors: Vec<Rgb> = parse_ok(&text).bodies.iter().map(|b| b.color).collect();
        assert_eq!(colors, [FLOOR_COLOR, PALETTE[0], PALETTE[1]]);
    }

    #[test]
    fn a_frozen_body_is_held_still_but_is_a_body_not_scenery() {
        let text = format!("{SPHERE}frozen = true\n{SPHERE}");
        let scene = parse_ok(&text);
        assert!(scene.bodies[0].frozen && scene.bodies[0].desc.is_static);
        assert!(!scene.bodies[1].frozen && !scene.bodies[1].desc.is_static);
        // The palette's colours, counted as a dynamic body is.
        let colors: Vec<Rgb> = scene.bodies.iter().map(|b| b.color).collect();
        assert_eq!(colors, [PALETTE[0], PALETTE[1]]);
        assert!(!parse_ok(&format!("{SPHERE}frozen = false\n")).bodies[0].frozen);
    }

    #[test]
    fn frozen_and_static_together_are_rejected_at_frozen() {
        rejects(
            &format!("{SPHERE}static = true\nfrozen = true\n"),
            6,
            10,
            "either static (scenery) or frozen",
        );
    }

    #[test]
    fn a_frozen_body_is_held_to_the_dynamic_ranges() {
        rejects(
            &format!("{SPHERE}frozen = true\nvelocity = [1, 0, 0]\n"),
            6,
            12,
            "a static body never moves",
        );
        // A static body may weigh what it likes; a frozen one may be unfrozen.
        parse_ok(&format!("{SPHERE}static = true\nmass = 1e9\n"));
        rejects(
            &format!("{SPHERE}frozen = true\nmass = 1e9\n"),
            6,
            8,
            "mass (kg) must be between",
        );
    }

    #[test]
    fn malformed_toml_is_located() {
        rejects("[world\ndt = 1\n", 1, 7, "");
    }

    #[test]
    fn serde_messages_about_a_value_name_its_key() {
        rejects(
            &format!("{SPHERE}static = 1\n"),
            5,
            10,
            "static: invalid type: integer `1`, expected a boolean",
        );
        rejects(
            "[world]\ngravity = [0, 1, \"x\"]\n",
            2,
            18,
            "gravity: invalid type: string",
        );
    }

    #[test]
    fn an_unknown_key_is_located_at_the_key() {
        let err = rejects(
            &format!("{SPHERE}radiuss = 1\n"),
            5,
            1,
            "unknown field `radiuss`",
        );
        assert_eq!(err.kind, SceneErrorKind::Syntax);
    }

    #[test]
    fn a_wrong_type_is_located_at_the_value() {
        rejects("[world]\ndt = \"fast\"\n", 2, 6, "invalid type");
    }

    #[test]
    fn a_vector_of_the_wrong_length_is_rejected() {
        rejects("[world]\ngravity = [0, -9.81]\n", 2, 11, "");
    }

    #[test]
    fn an_unknown_shape_names_the_choices() {
        rejects(
            "[[body]]\nshape = \"cone\"\nposition = [0, 0, 0]\n",
            2,
            9,
            "unknown variant `cone`",
        );
    }

    #[test]
    fn a_negative_radius_is_located_at_the_value() {
        let err = rejects(
            "[[body]]\nshape = \"sphere\"\nradius = -1\nposition = [0, 1, 0]\n",
            3,
            10,
            "radius must be finite and > 0, got -1",
        );
        assert_eq!(err.kind, SceneErrorKind::Invalid);
    }

    #[test]
    fn nan_and_inf_are_parsed_and_rejected() {
        rejects(
            "[[body]]\nshape = \"sphere\"\nradius = nan\nposition = [0, 1, 0]\n",
            3,
            10,
            "got nan",
        );
        rejects(
            "[[body]]\nshape = \"sphere\"\nradius = 1\nposition = [0, -inf, 0]\n",
            4,
            12,
            "position must be finite, got [0, -inf, 0]",
        );
    }

    #[test]
    fn a_body_whose_mass_underflows_is_rejected() {
        rejects(
            "[[body]]\nshape = \"sphere\"\nradius = 1e-3\ndensity = 1e-40\nposition = [0, 1, 0]\n",
            4,
            11,
            "mass = density × volume",
        );
    }

    #[test]
    fn a_body_whose_inertia_overflows_is_rejected() {
        rejects(
            "[[body]]\nshape = \"sphere\"\nradius = 1000\nmass = 1e38\nstatic = true\nposition = [0, 1, 0]\n",
            4,
            8,
            "moments of inertia",
        );
    }

    #[test]
    fn a_static_body_cannot_be_given_a_velocity() {
        rejects(
            &format!("{SPHERE}static = true\nvelocity = [1, 0, 0]\n"),
            6,
            12,
            "static body never moves",
        );
    }

    #[test]
    fn a_camera_looking_at_its_own_position_is_rejected() {
        rejects(
            "[camera]\nposition = [1, 2, 3]\ntarget = [1, 2, 3]\n",
            3,
            10,
            "camera target must differ from its position",
        );
    }
}
