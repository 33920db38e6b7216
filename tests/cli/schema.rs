//! The one schema (`scene::schema`): scene files, saved worlds and recordings are written and read
//! through the same types, so what is written reads back as it was, bit for bit, in every format.

use crate::common::temp::TempPath;
use glam::{Quat, Vec3};
use nudge::geometry::{Camera, Pose, Projection, Shape};
use nudge::physics::{
    BodyDesc, BodyId, JointDesc, JointKind, Motor, PointHold, PointSpring, Settings, Spring, World,
    WorldInput,
};
use nudge::recording::{self, Recorder, Recording};
use nudge::scene::schema;
use nudge::scene::write::{exact_camera, scene_of_world, to_toml};
use nudge::scene::{self, Scene, file};

/// `scene` after `steps` steps, saved as Ctrl+S saves it.
fn saved(name: &str, steps: usize) -> (Scene, World) {
    let scene = scene::load(name).unwrap();
    let mut world = scene.build_world();
    for _ in 0..steps {
        world.step();
    }
    let colors: Vec<_> = scene.bodies.iter().map(|b| b.color).collect();
    let scenery: Vec<bool> = scene.bodies.iter().map(|b| b.desc.is_static).collect();
    (
        scene_of_world(name, &world, &colors, &scenery, &scene.camera),
        world,
    )
}

fn bits(v: Vec3) -> [u32; 3] {
    v.to_array().map(f32::to_bits)
}

#[test]
fn a_saved_world_reloads_bit_for_bit_and_saves_to_the_same_text() {
    for name in ["default", "ramp", "pyramid", "dominoes"] {
        let (scene, world) = saved(name, 90);
        let text = to_toml(&scene, &["test"]);
        let back = file::parse(&text, "saved.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(back.bodies, scene.bodies, "{name}");
        let rebuilt = back.build_world();
        for (a, b) in world.bodies().iter().zip(rebuilt.bodies()) {
            assert_eq!(bits(a.pose().position), bits(b.pose().position), "{name}");
            let rotation = |q: Quat| q.to_array().map(f32::to_bits);
            assert_eq!(rotation(a.pose().rotation), rotation(b.pose().rotation));
            assert_eq!(bits(a.linear_velocity()), bits(b.linear_velocity()));
            assert_eq!(bits(a.angular_velocity()), bits(b.angular_velocity()));
            assert_eq!(a.mass().to_bits(), b.mass().to_bits());
        }
        assert_eq!(
            back.settings.dt.to_bits(),
            scene.settings.dt.to_bits(),
            "{name}"
        );
        // Written again, the same text: nothing drifts through a save and a load.
        assert_eq!(to_toml(&back, &["test"]), text, "{name}");
    }
}

#[test]
fn floats_are_written_in_their_shortest_form_and_read_back_to_the_same_bits() {
    // toml's own f64 path would write 0.1f32 as 0.10000000149011612.
    let mut values = vec![
        0.1,
        1.0,
        -0.0,
        1.0 / 3.0,
        16_777_217.0,
        f32::MIN_POSITIVE,
        1e20,
    ];
    let mut x = 1.0e-30f32;
    while x < 1e30 {
        values.push(x);
        values.push(-x * 1.000_123_4);
        x *= 1.618_034;
    }
    let inputs: Vec<_> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| (i as u64, hold(Vec3::new(v, 1.0, 0.0))))
        .collect();
    let (recording, text) = record(&inputs, &[]);
    let lines: Vec<&str> = text.lines().filter(|l| l.starts_with("hold = ")).collect();
    for ((v, line), (_, input, _)) in values.iter().zip(lines).zip(&recording.inputs) {
        // Rust's shortest round-trip text, and always a TOML float.
        let shortest = if v % 1.0 == 0.0 {
            format!("{v}.0")
        } else {
            format!("{v}")
        };
        assert!(
            line.contains(&format!("anchor = [{shortest}, 1.0, 0.0]")),
            "{v:?}: {line}"
        );
        let WorldInput::Hold(hold) = input else {
            panic!("a hold");
        };
        assert_eq!(hold.anchor.x.to_bits(), v.to_bits(), "{line}");
    }
    let text = to_toml(&saved("default", 0).0, &[]);
    assert!(text.contains("\nfriction = 0.5\n"), "{text}");
    assert!(!text.contains("0000001"), "{text}");
}

/// Body 1's point `anchor` pulled from 1 m up to 1.1 m over a step, as a grab pulls it.
fn hold(anchor: Vec3) -> WorldInput {
    WorldInput::Hold(PointHold {
        body: BodyId(1),
        anchor,
        from: Vec3::Y,
        to: Vec3::new(0.0, 1.1, 0.0),
        spring: PointSpring {
            hertz: 8.0,
            damping_ratio: 0.7,
            max_force: 300.0,
            max_speed: 6.0,
        },
        spin_time: 0.1,
    })
}

/// Writes a recording of the default scene holding `inputs` and `cameras`, and reads it back.
fn record(inputs: &[(u64, WorldInput)], cameras: &[(u64, Camera)]) -> (Recording, String) {
    let file = TempPath::new("recording.toml");
    let (scene, _) = saved("default", 0);
    let settings = Settings {
        substeps: 7,
        preload: true,
        ..Settings::default()
    };
    let mut recorder = Recorder::create(&file.0, &to_toml(&scene, &["test"]), &settings).unwrap();
    let mut cameras = cameras.iter().peekable();
    for input in inputs {
        while let Some((step, camera)) = cameras.next_if(|(step, _)| *step <= input.0) {
            recorder.camera(*step, camera).unwrap();
        }
        recorder.inputs(std::slice::from_ref(input)).unwrap();
    }
    for (step, camera) in cameras {
        recorder.camera(*step, camera).unwrap();
    }
    recorder
        .finish(inputs.last().map_or(0, |i| i.0).max(100))
        .unwrap();
    let text = std::fs::read_to_string(&file.0).unwrap();
    let recording = recording::parse(&text, "rec.toml").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(recording.settings, settings);
    (recording, text)
}

#[test]
fn every_input_and_camera_a_recording_holds_reads_back_as_it_was_written() {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let mut spun = BodyDesc::dynamic(
        Shape::cuboid(v(0.3, 0.2, 0.1)),
        Pose::new(v(0.1, 2.0, -0.3), Quat::from_rotation_y(0.7)),
        0.7,
    );
    spun.linear_velocity = v(0.1, -0.2, 0.3);
    spun.angular_velocity = v(1.5, 0.0, -0.25);
    spun.friction = 0.3;
    spun.restitution = 0.6;
    spun.rolling_resistance = 0.01;
    let inputs = [
        (
            1,
            WorldInput::Force {
                body: BodyId(1),
                force: v(0.0, 0.1, 12.5),
                point: v(0.1, 0.5, -0.2),
            },
        ),
        (
            2,
            WorldInput::Impulse {
                body: BodyId(2),
                impulse: v(1.0 / 3.0, 0.0, -2.0),
                point: v(0.0, 0.7, 0.0),
            },
        ),
        (3, hold(v(0.1, 0.2, 0.3))),
        (
            4,
            WorldInput::SetStatic {
                body: BodyId(1),
                is_static: true,
            },
        ),
        (5, WorldInput::Gravity(v(0.0, -1.62, 0.0))),
        (6, WorldInput::Wake(BodyId(2))),
        (7, WorldInput::AddBody(spun)),
        (
            8,
            WorldInput::Resize {
                body: BodyId(1),
                shape: Shape::cuboid(v(0.6, 0.5, 0.4)),
            },
        ),
        (
            9,
            WorldInput::Resize {
                body: BodyId(2),
                shape: Shape::sphere(0.45),
            },
        ),
        (
            10,
            WorldInput::Settings(Box::new(Settings {
                iterations: 3,
                ..Settings::default()
            })),
        ),
        (11, WorldInput::Reset),
    ];
    let perspective = Camera {
        up: v(0.0, 1.0, 0.1),
        near: 0.05,
        far: 321.5,
        ..Camera::perspective(v(0.1, 4.0, -12.0), v(0.0, 1.0, 0.3), 1.1)
    };
    let orthographic = Camera {
        projection: Projection::Orthographic { view_height: 7.25 },
        ..perspective
    };
    // Straight down at the target, along its up: drawn as ever (`Camera::basis` falls back), so
    // read as ever.
    let top_down = Camera::perspective(v(0.0, 10.0, 0.0), Vec3::ZERO, 1.0);
    let cameras = [(0, perspective), (6, orthographic), (11, top_down)];
    let (recording, text) = record(&inputs, &cameras);
    let read: Vec<_> = recording
        .inputs
        .iter()
        .map(|(step, input, _)| (*step, input.clone()))
        .collect();
    assert_eq!(read, inputs);
    assert_eq!(recording.cameras, cameras);
    assert_eq!(recording.end, 100);
    // One input a line, as the format shows them; the settings in a table of their own.
    for key in [
        "force",
        "impulse",
        "hold",
        "set_static",
        "add_body",
        "resize",
        "camera",
    ] {
        assert!(text.contains(&format!("\n{key} = {{ ")), "{key}: {text}");
    }
    assert!(text.contains("\n[input.settings]\n"), "{text}");
}

#[test]
fn a_recordings_scene_is_a_scene_file_and_its_tables_are_the_scene_files_tables() {
    let (recording, text) = record(&[], &[]);
    // The embedded scene is scene-file text: it reads as the saved world it is.
    let (scene, _) = saved("default", 0);
    let back = file::parse(&to_toml(&scene, &["test"]), "rec.toml").unwrap();
    assert_eq!(recording.scene, back);
    assert!(text.contains("scene = \"\"\"\n# test\n[world]\n"), "{text}");

    // An added body is a [[body]] table: the scene file's forms are accepted there, and the
    // same rules refuse what a scene file refuses, located at the value.
    let with = |entry: &str| {
        text.replace(
            "\n[end]\n",
            &format!("\n[[input]]\nstep = 1\n{entry}\n\n[end]\n"),
        )
    };
    let friendly = with(
        "add_body = { shape = \"box\", half_extents = [0.5, 0.5, 0.5], position = [0, 3, 0], \
         rotation_axis = [0, 1, 0], rotation_deg = 90, density = 2, color = \"#ff0000\" }",
    );
    let read = recording::parse(&friendly, "rec.toml").unwrap();
    let WorldInput::AddBody(desc) = read.inputs[0].1 else {
        panic!("an added body");
    };
    assert_eq!(desc.mass, 2.0);
    assert!(
        desc.pose
            .rotation
            .angle_between(Quat::from_rotation_y(1.5707964))
            < 1e-6
    );
    let bad = with("add_body = { shape = \"sphere\", radius = -1, position = [0, 3, 0] }");
    let err = recording::parse(&bad, "rec.toml").unwrap_err().to_string();
    let (line, column) = bad
        .lines()
        .enumerate()
        .find_map(|(i, l)| Some((i + 1, l.find("-1")? + 1)))
        .unwrap();
    assert!(
        err.starts_with(&format!(
            "rec.toml:{line}:{column}: radius must be finite and > 0"
        )),
        "{err}"
    );

    // A recorded camera is a [camera] table: a scene file reads the exact form a recording
    // writes, and a recording the friendly form a scene file uses.
    let exact = "[camera]\nposition = [0.5, 3.0, -9.0]\ntarget = [0.0, 1.0, 0.0]\n\
                 up = [0.0, 1.0, 0.0]\nfov_y = 1.1\nnear = 0.2\nfar = 250.0\n";
    let camera = file::parse(exact, "cam.toml").unwrap().camera;
    assert_eq!(
        camera,
        Camera {
            near: 0.2,
            far: 250.0,
            ..Camera::perspective(Vec3::new(0.5, 3.0, -9.0), Vec3::Y, 1.1)
        }
    );
    let friendly = with("camera = { position = [0, 2, -8], target = [0, 1, 0], fov_deg = 60 }");
    let read = recording::parse(&friendly, "rec.toml").unwrap();
    let shown = read.cameras.last().unwrap().1;
    assert_eq!(
        shown.projection,
        Projection::Perspective {
            fov_y: 60f32.to_radians()
        }
    );
    let both = file::parse("[camera]\nfov_deg = 60\nfov_y = 1.0\n", "cam.toml").unwrap_err();
    assert_eq!(
        both.to_string(),
        "cam.toml:3:9: fov_y (radians) and fov_deg (degrees) are one angle: give one"
    );
}

/// A recording as the writer before the shared schema wrote it: the scene in a literal string,
/// every body key written, the camera with `fov_y`.
const OLD_RECORDING: &str = "# nudge session recording: `nudge replay FILE` plays it
[recording]
format = \"nudge-recording\"
version = 1
scene = '''
# recorded from default
[world]
gravity = [0.0, -9.81, 0.0]
dt = 0.016666668

[camera]
position = [0.0, 3.0, -9.0]
target = [0.0, 1.0, 0.0]
projection = \"perspective\"
fov_deg = 70.0

[[body]]
shape = \"box\"
half_extents = [6.0, 0.5, 4.0]
position = [0.0, -0.5, 0.0]
orientation = [0.0, 0.0, 0.0, 1.0]
mass = 96.0
static = true
friction = 0.5
restitution = 0.0
rolling_resistance = 0.0
color = \"#808488\"

[[body]]
shape = \"box\"
half_extents = [0.5, 0.5, 0.5]
position = [0.0, 0.5, 0.0]
orientation = [0.0, 0.0, 0.0, 1.0]
velocity = [0.0, 0.0, 0.0]
angular_velocity = [0.0, 0.0, 0.0]
mass = 1.0
static = false
friction = 0.5
restitution = 0.0
rolling_resistance = 0.0
color = \"#c08040\"
'''

[recording.settings]
gravity = [0.0, -9.81, 0.0]
dt = 0.016666668
substeps = 4
iterations = 1
sleep = true
linear_damping = 0.0
angular_damping = 0.0
contact_hertz = 30.0
contact_damping_ratio = 10.0
max_push_out_velocity = 3.0
restitution_threshold = 1.0
linear_slop = 0.005
speculative_distance = 0.1
manifold_reuse_distance = 0.01
sleep_linear_threshold = 0.05
sleep_angular_threshold = 0.05
time_to_sleep = 0.5
max_linear_speed = 400.0
max_angular_speed = 200.0
shock_propagation = true
mass_ratio_threshold = 100.0
mass_ratio_iterations = 2

[[input]]
step = 0
camera = { position = [0.0, 3.0, -9.0], target = [0.0, 1.0, 0.0], up = [0.0, 1.0, 0.0], fov_y = 1.2217305, near = 0.1, far = 500.0 }

[[input]]
step = 3
add_body = { shape = \"sphere\", radius = 0.25, position = [0.0, 3.0, 0.0], orientation = [0.0, 0.0, 0.0, 1.0], velocity = [0.0, 0.0, 0.0], angular_velocity = [0.0, 0.0, 0.0], mass = 0.06544985, static = false, friction = 0.5, restitution = 0.0, rolling_resistance = 0.02 }

[[input]]
step = 5
force = { body = 1, force = [0.0, 0.0, 12.5], point = [0.1, 0.5, -0.2] }

[end]
step = 10
";

#[test]
fn a_recording_written_before_the_shared_schema_reads_as_it_did() {
    let recording = recording::parse(OLD_RECORDING, "old.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(recording.scene.bodies.len(), 2);
    assert_eq!(recording.settings.substeps, 4);
    assert!(recording.settings.spread_row && !recording.settings.preload);
    assert_eq!(
        recording.cameras,
        [(
            0,
            Camera::perspective(Vec3::new(0.0, 3.0, -9.0), Vec3::Y, 1.2217305)
        )]
    );
    let WorldInput::AddBody(ball) = recording.inputs[0].1 else {
        panic!("an added body");
    };
    assert_eq!(ball.shape, Shape::sphere(0.25));
    assert_eq!((ball.mass, ball.rolling_resistance), (0.06544985, 0.02));
    assert_eq!(recording.inputs[1].0, 5);
    assert_eq!(recording.end, 10);
}

/// The camera keys scene files took from recordings (`up`, `fov_y`, `view_height`, `near`, `far`):
/// a camera written with them into a scene file reads back as it was, in both projections.
#[test]
fn the_camera_keys_scene_files_share_with_recordings_round_trip_through_a_scene_file() {
    let perspective = Camera {
        up: Vec3::new(0.1, 1.0, 0.0),
        near: 0.03,
        far: 1234.5,
        ..Camera::perspective(Vec3::new(3.0, 2.0, -7.0), Vec3::new(0.1, 0.2, 0.3), 0.9)
    };
    let orthographic = Camera {
        projection: Projection::Orthographic { view_height: 4.75 },
        ..perspective
    };
    for camera in [perspective, orthographic] {
        let scene = schema::SceneFile {
            camera: Some(schema::unplaced(exact_camera(&camera))),
            ..Default::default()
        };
        let text = toml::to_string(&scene).unwrap();
        assert_eq!(
            file::parse(&text, "cam.toml").unwrap().camera,
            camera,
            "{text}"
        );
    }
}

#[test]
fn every_joint_kind_a_recording_holds_reads_back_as_it_was_written() {
    let v = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let motor = Some(Motor {
        speed: 1.0 / 3.0,
        max: 12.5,
    });
    let kinds = [
        JointKind::Ball,
        JointKind::Fixed,
        JointKind::Hinge {
            limits: Some([-0.7, 0.25]),
            motor,
        },
        JointKind::Slider {
            limits: None,
            motor,
        },
        JointKind::Distance {
            length: 1.1,
            min: 0.0,
            max: 1.5,
            spring: Some(Spring {
                hertz: 3.0,
                damping_ratio: 0.1,
            }),
        },
        JointKind::Distance {
            length: 0.7,
            min: 0.7,
            max: 0.7,
            spring: None,
        },
    ];
    let inputs: Vec<(u64, WorldInput)> = kinds
        .iter()
        .enumerate()
        .map(|(i, &kind)| {
            let a = (i % 2 == 0).then_some((
                BodyId(2),
                Pose::new(v(0.3, 1.0, 0.1), Quat::from_rotation_x(0.3)),
            ));
            let desc = JointDesc::at(
                kind,
                a,
                (
                    BodyId(1),
                    Pose::new(v(-0.2, 2.0, 0.0), Quat::from_rotation_z(1.1)),
                ),
                v(0.1, 1.5, 0.2),
                v(0.1 / 3.0, 1.7, 0.2),
                v(0.2, 1.0, -0.4),
                i == 3,
            );
            // Friction where a kind has it (a ball joint, a hinge, a slider).
            let desc = match kind {
                JointKind::Ball | JointKind::Hinge { .. } | JointKind::Slider { .. } => {
                    desc.with_friction(0.1 + i as f32 / 7.0)
                }
                _ => desc,
            };
            (i as u64 + 1, WorldInput::AddJoint(desc))
        })
        .collect();
    let (recording, text) = record(&inputs, &[]);
    assert!(text.contains("add_joint = { kind = \"hinge\""), "{text}");
    assert!(text.contains("friction = "), "{text}");
    let read: Vec<(u64, WorldInput)> = recording
        .inputs
        .iter()
        .map(|(step, input, _)| (*step, input.clone()))
        .collect();
    assert_eq!(read, inputs);
}

#[test]
fn a_recorded_joint_that_makes_no_joint_is_refused_where_it_is_written() {
    let (_, text) = record(
        &[(
            1,
            WorldInput::AddJoint(JointDesc::at(
                JointKind::Ball,
                None,
                (BodyId(1), Pose::IDENTITY),
                Vec3::ZERO,
                Vec3::ZERO,
                Vec3::Y,
                false,
            )),
        )],
        &[],
    );
    let bad = text.replace("kind = \"ball\"", "kind = \"hinge\", limits = [1.0, -1.0]");
    let err = recording::parse(&bad, "rec.toml").unwrap_err().to_string();
    assert!(err.contains("lower first"), "{err}");
    assert!(err.starts_with("rec.toml:"), "{err}");
}

/// The built-in scenes name their parts ("link 3", "door", "wrecking ball"): every name is
/// unique, and a scene written as a file reads back with the same names.
#[test]
fn the_built_in_scenes_names_are_unique_and_read_back_from_their_files() {
    for &(name, _) in scene::builtin_scenes() {
        let scene = scene::load(name).unwrap();
        let names: Vec<Option<String>> = scene.bodies.iter().map(|b| b.name.clone()).collect();
        let mut given: Vec<&String> = names.iter().flatten().collect();
        given.sort();
        given.dedup();
        assert_eq!(
            given.len(),
            names.iter().flatten().count(),
            "{name}: {names:?}"
        );
        let text = to_toml(&scene, &[]);
        let back = file::parse(&text, "scene.toml").unwrap_or_else(|e| panic!("{name}: {e}"));
        let back: Vec<Option<String>> = back.bodies.iter().map(|b| b.name.clone()).collect();
        assert_eq!(back, names, "{name}");
    }
}
