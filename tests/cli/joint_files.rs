//! `[[joint]]` in scene files: the world form people write, what it builds, the errors located at
//! the value that is wrong, and the exact form a saved world writes, read back bit for bit.

use glam::Vec3;
use nudge::physics::{BodyId, JointKind};
use nudge::scene::file;
use nudge::scene::write::{scene_of_world, to_toml};

const PENDULUM: &str = r#"
[[body]]
shape = "box"
half_extents = [4.0, 0.5, 4.0]
position = [0.0, -0.5, 0.0]
static = true

[[body]]
name = "bob"
shape = "sphere"
radius = 0.1
position = [1.0, 2.0, 0.0]

[[joint]]
kind = "hinge"
a = "world"
b = "bob"
anchor = [0.0, 2.0, 0.0]
axis = [0.0, 0.0, 1.0]
limits = [-45.0, 45.0]
motor_speed = 2.0
motor_max = 50.0
"#;

/// Parses `text` expecting an error at `line:column` whose message contains `phrase`.
fn rejects(text: &str, line: usize, column: usize, phrase: &str) {
    let err = match file::parse(text, "j.toml") {
        Ok(_) => panic!("should be rejected:\n{text}"),
        Err(e) => e.to_string(),
    };
    assert!(
        err.starts_with(&format!("j.toml:{line}:{column}: ")),
        "{err}"
    );
    assert!(err.contains(phrase), "{err}");
}

#[test]
fn a_hinge_from_the_world_builds_as_written() {
    let scene = file::parse(PENDULUM, "p.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.joints.len(), 1);
    let joint = scene.joints[0];
    assert_eq!(joint.a, None);
    assert_eq!(joint.b, BodyId(1));
    match joint.kind {
        JointKind::Hinge {
            limits: Some([lo, hi]),
            motor: Some(m),
        } => {
            assert!(
                (lo + 45f32.to_radians()).abs() < 1e-6 && (hi - 45f32.to_radians()).abs() < 1e-6
            );
            assert_eq!((m.speed, m.max), (2.0, 50.0));
        }
        other => panic!("{other:?}"),
    }
    // The bob starts 1 m from the pivot and stays there.
    let mut world = scene.build_world();
    for _ in 0..120 {
        world.step();
    }
    let bob = world.body(BodyId(1)).pose().position;
    assert!(
        (bob.distance(Vec3::new(0.0, 2.0, 0.0)) - 1.0).abs() < 1e-3,
        "{bob}"
    );
    // The motor drives it up to its upper limit, 45° above the horizontal, and presses on it
    // with its full 50 N·m, a thousand times the bob's weight's torque: the soft limit gives by
    // 50 N·m over k = m·ω² (the bob's 4.2 g·m² about the pivot at 60 Hz), 4.8°. (Under gravity
    // alone a limit holds a 10 kg arm within 0.01°: `tests/physics/joints.rs`.)
    let angle = (bob.y - 2.0).atan2(bob.x).to_degrees();
    assert!((45.0..50.5).contains(&angle), "{angle}°");
}

#[test]
fn a_scene_with_joints_saves_and_loads_back_bit_for_bit() {
    let scene = file::parse(PENDULUM, "p.toml").unwrap();
    let mut world = scene.build_world();
    for _ in 0..37 {
        world.step();
    }
    let colors: Vec<_> = scene.bodies.iter().map(|b| b.color).collect();
    let scenery: Vec<_> = scene.bodies.iter().map(|b| b.desc.is_static).collect();
    let saved = scene_of_world("saved", &world, &colors, &scenery, &scene.camera);
    let text = to_toml(&saved, &[]);
    assert!(
        text.contains("[[joint]]") && text.contains("limits_rad"),
        "{text}"
    );
    let loaded = file::parse(&text, "saved.toml").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(loaded.joints, saved.joints);
    // The file builds the world the saved scene builds: stepped on, they agree bit for bit (a save
    // keeps no warm start, so the live world itself goes on a little differently).
    let (mut from_save, mut from_file) = (saved.build_world(), loaded.build_world());
    for _ in 0..60 {
        from_save.step();
        from_file.step();
    }
    assert_eq!(
        from_save.snapshot().first_difference(&from_file.snapshot()),
        None
    );
}

#[test]
fn bad_joints_are_refused_where_they_are_written() {
    let with = |from: &str, to: &str| {
        assert!(PENDULUM.contains(from), "{from}");
        PENDULUM.replace(from, to)
    };
    rejects(
        &with(r#"b = "bob""#, r#"b = "bobby""#),
        17,
        5,
        "no body is named \"bobby\"",
    );
    rejects(
        &with(r#"a = "world""#, r#"a = "bob""#),
        17,
        5,
        "two different bodies",
    );
    rejects(
        &with("axis = [0.0, 0.0, 1.0]", "axis = [0.0, 0.0, 0.0]"),
        19,
        8,
        "axis must not be zero",
    );
    rejects(
        &with("limits = [-45.0, 45.0]", "limits = [45.0, -45.0]"),
        20,
        10,
        "lower first",
    );
    rejects(
        &with(r#"kind = "hinge""#, r#"kind = "hinged""#),
        15,
        8,
        "unknown joint kind",
    );
    rejects(&with("b = \"bob\"", "b = 7"), 17, 5, "there is no body 7");
    rejects(
        &with("motor_max = 50.0\n", ""),
        21,
        15,
        "both motor_speed and motor_max",
    );
    // Two static ends.
    rejects(&with(r#"b = "bob""#, "b = 0"), 17, 5, "a moving body");
    // A negative length, and a length on a hinge.
    let rope = r#"
[[body]]
name = "bob"
shape = "sphere"
radius = 0.1
position = [1.0, 2.0, 0.0]

[[joint]]
kind = "distance"
b = "bob"
anchor_a = [0.0, 2.0, 0.0]
anchor_b = [1.0, 2.0, 0.0]
max_length = -1.0
"#;
    rejects(rope, 13, 14, "max_length must be finite and >= 0");
    rejects(
        &with("motor_max = 50.0", "motor_max = 50.0\nlength = 1.0"),
        23,
        10,
        "a hinge joint has no length",
    );
    // A name used twice.
    rejects(
        &with(
            "[[joint]]",
            "[[body]]\nname = \"bob\"\nshape = \"sphere\"\nradius = 0.1\nposition = [0.0, 5.0, 0.0]\n\n[[joint]]",
        ),
        15,
        8,
        "taken",
    );
}

/// `friction` on a ball joint, a hinge or a slider: read, saved and read back; refused on a
/// joint that has no free axis to resist, and when negative.
#[test]
fn joint_friction_reads_saves_and_is_refused_where_it_means_nothing() {
    let with_friction = PENDULUM.replace("motor_max = 50.0", "motor_max = 50.0\nfriction = 0.25");
    let scene = file::parse(&with_friction, "f.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.joints[0].friction, 0.25);
    let ball = with_friction
        .replace(r#"kind = "hinge""#, r#"kind = "ball""#)
        .replace("axis = [0.0, 0.0, 1.0]\n", "")
        .replace("limits = [-45.0, 45.0]\n", "")
        .replace("motor_speed = 2.0\nmotor_max = 50.0\n", "");
    let scene = file::parse(&ball, "f.toml").unwrap_or_else(|e| panic!("{e}\n{ball}"));
    assert_eq!(scene.joints[0].friction, 0.25);
    let world = scene.build_world();
    let colors: Vec<_> = scene.bodies.iter().map(|b| b.color).collect();
    let scenery: Vec<_> = scene.bodies.iter().map(|b| b.desc.is_static).collect();
    let saved = scene_of_world("saved", &world, &colors, &scenery, &scene.camera);
    let text = to_toml(&saved, &[]);
    assert!(text.contains("friction = 0.25"), "{text}");
    let loaded = file::parse(&text, "saved.toml").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(loaded.joints, saved.joints);

    let fixed = ball.replace(r#"kind = "ball""#, r#"kind = "fixed""#);
    rejects(&fixed, 19, 12, "a fixed joint has no friction");
    rejects(
        &with_friction.replace("friction = 0.25", "friction = -0.25"),
        23,
        12,
        "friction must be finite and >= 0",
    );
}

#[test]
fn a_rope_is_max_length_alone_and_a_spring_pulls_to_its_length() {
    let scene = file::parse(
        r#"
[[body]]
shape = "sphere"
radius = 0.1
position = [0.0, 1.0, 0.0]

[[joint]]
kind = "distance"
b = 0
anchor_a = [0.0, 2.0, 0.0]
anchor_b = [0.0, 1.0, 0.0]
max_length = 1.5

[[joint]]
kind = "distance"
a = "world"
b = 0
anchor_a = [0.0, 0.0, 0.0]
anchor_b = [0.0, 1.0, 0.0]
stiffness_hz = 1.0
damping_ratio = 0.5
"#,
        "r.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    match scene.joints[0].kind {
        JointKind::Distance {
            length,
            min,
            max,
            spring: None,
        } => assert_eq!((length, min, max), (1.0, 0.0, 1.5)),
        other => panic!("{other:?}"),
    }
    match scene.joints[1].kind {
        JointKind::Distance {
            length,
            min,
            max,
            spring: Some(s),
        } => {
            assert_eq!((length, min, max), (1.0, 1.0, 1.0));
            assert_eq!((s.hertz, s.damping_ratio), (1.0, 0.5));
        }
        other => panic!("{other:?}"),
    }
}

/// A chain hangs where its joints hold it: the automatic camera frames its links where they are,
/// not on the floor where they would land if dropped.
#[test]
fn the_automatic_camera_frames_a_hanging_chain_where_it_hangs() {
    let mut text = String::from(
        "[[body]]\nshape = \"box\"\nhalf_extents = [6.0, 0.5, 6.0]\nposition = [0.0, -0.5, 0.0]\nstatic = true\n",
    );
    for i in 0..6 {
        text += &format!(
            "\n[[body]]\nshape = \"sphere\"\nradius = 0.1\nposition = [0.0, {}, 0.0]\n\n[[joint]]\nkind = \"ball\"\n{}b = {}\nanchor = [0.0, {}, 0.0]\n",
            6.0 - 0.2 * i as f32 - 0.1,
            if i == 0 {
                String::new()
            } else {
                format!("a = {i}\n")
            },
            i + 1,
            6.0 - 0.2 * i as f32
        );
    }
    let scene = file::parse(&text, "chain.toml").unwrap_or_else(|e| panic!("{e}\n{text}"));
    let camera = scene.camera;
    let clip = camera.clip_from_world(1.5);
    for body in &scene.bodies[1..] {
        let p = clip * body.desc.pose.position.extend(1.0);
        let ndc = p.truncate() / p.w;
        assert!(
            ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0,
            "a link at {ndc} is out of the picture"
        );
    }
}
