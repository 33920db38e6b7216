//! Built-in scenes and a complete scene file, through the library and through the binary.

use glam::{Quat, Vec3};
use nudge::geometry::Shape;
use nudge::scene::{self, SceneErrorKind};

use crate::common;

use common::cli::nudge;

/// Body counts each built-in scene declares (its description plus floors, ramps and walls).
const EXPECTED_BODIES: &[(&str, usize)] = &[
    ("default", 9),   // floor, 2 boxes, 2 balls, the rim's 4 walls
    ("stack", 9),     // floor, 8 boxes
    ("pyramid", 211), // floor, 210 boxes
    ("ramp", 9),      // floor, ramp, 3 boxes, 3 balls, catch wall
    ("dominoes", 14), // floor, 12 dominoes, ball
    ("pendulum", 7),  // floor, beam, 2 posts, 3 bobs
    ("cradle", 9),    // floor, beam, 2 posts, 5 balls
    ("chain", 32),    // floor, beam, 30 links
    ("bridge", 18),   // floor, 2 towers, 12 planks, 3 boxes
    ("door", 5),      // floor, 2 posts, lintel, door
    ("rain", 1005),   // floor, 4 walls, 1000 bodies
    ("wrecking", 58), // floor, 36 boxes, 20 links, the ball
    ("ragdoll", 17),  // floor, 5 stairs, 11 parts
];

#[test]
fn every_built_in_scene_builds_a_world_with_exactly_its_bodies() {
    let listed: Vec<&str> = scene::builtin_scenes().iter().map(|(n, _)| *n).collect();
    let expected: Vec<&str> = EXPECTED_BODIES.iter().map(|(n, _)| *n).collect();
    assert_eq!(listed, expected);
    for &(name, count) in EXPECTED_BODIES {
        let scene = scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(scene.name, name);
        assert_eq!(scene.bodies.len(), count, "{name}");
        let world = scene.build_world();
        assert_eq!(world.len(), count, "{name}");
        // Every joint the scene declares made it into the world (each is checked when added).
        assert_eq!(world.joints().len(), scene.joints.len(), "{name}");
        for (i, (body, in_world)) in scene.bodies.iter().zip(world.bodies()).enumerate() {
            let d = &body.desc;
            assert!(d.shape.is_valid(), "{name} body {i}");
            assert!(d.pose.is_finite(), "{name} body {i}");
            assert!(
                (d.pose.rotation.length() - 1.0).abs() < 1e-5,
                "{name} body {i}"
            );
            assert!(d.mass.is_finite() && d.mass > 0.0, "{name} body {i}");
            assert!((0.0..=1.0).contains(&d.restitution) && d.friction >= 0.0);
            assert_eq!(in_world.pose(), &d.pose, "{name} body {i} in scene order");
        }
        assert!(scene.bodies.iter().any(|b| !b.desc.is_static), "{name}");
        let camera = scene.camera;
        assert!((camera.target - camera.position).length() > 1e-3, "{name}");
        assert!(
            camera.position.z < camera.target.z,
            "{name}: camera in front"
        );
        assert!(camera.position.y > camera.target.y, "{name}: camera above");
    }
}

#[test]
fn nudge_scenes_lists_every_built_in_scene_with_its_description() {
    let out = nudge(&["scenes"]);
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    for (name, description) in scene::builtin_scenes() {
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(name) && l.ends_with(description)),
            "{name} missing: {stdout}"
        );
    }
}

#[test]
fn nudge_sim_runs_every_built_in_scene_by_name() {
    for &(name, count) in EXPECTED_BODIES {
        let out = nudge(&["sim", "--scene", name, "--steps", "1"]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            stdout.starts_with(&format!("steps=1 bodies={count} ")),
            "{stdout}"
        );
    }
}

/// The documented example (every key) written to a file, loaded, simulated and traced by the binary:
/// what the file says is what the world starts with. Tolerance: values pass through f32 text
/// formatting unchanged (shortest round-trip), rotations compared to 1e-6 rad.
#[test]
fn the_full_example_file_round_trips_through_nudge_sim() {
    let dir = std::env::temp_dir();
    let scene_path = dir.join(format!("nudge-scene-{}-example.toml", std::process::id()));
    let trace_path = dir.join(format!("nudge-scene-{}-example.csv", std::process::id()));
    std::fs::write(&scene_path, scene::file::EXAMPLE).expect("write example");
    let scene_arg = scene_path.to_str().expect("UTF-8 path");

    let loaded = scene::load(scene_arg).expect("example loads");
    assert_eq!(loaded.bodies.len(), 3);
    assert_eq!(loaded.name, scene_arg);

    let out = nudge(&[
        "sim",
        "--scene",
        scene_arg,
        "--steps",
        "1",
        "--trace",
        trace_path.to_str().expect("UTF-8 path"),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let trace = std::fs::read_to_string(&trace_path).unwrap_or_default();
    let _ = std::fs::remove_file(&scene_path);
    let _ = std::fs::remove_file(&trace_path);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.starts_with("steps=1 bodies=3 "), "{stdout}");

    // Step-0 rows: step,body,px,py,pz,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz.
    let rows: Vec<Vec<f32>> = trace
        .lines()
        .skip(1)
        .filter(|l| l.starts_with("0,"))
        .map(|l| l.split(',').map(|v| v.parse().expect("number")).collect())
        .collect();
    assert_eq!(rows.len(), 3);
    let cube = &rows[1];
    assert_eq!(&cube[2..5], &[0.0, 0.5, 0.0]);
    let q = Quat::from_xyzw(cube[5], cube[6], cube[7], cube[8]);
    assert!(q.angle_between(Quat::from_rotation_y(30f32.to_radians())) < 1e-6);
    let ball = &rows[2];
    assert_eq!(&ball[2..5], &[1.5, 3.0, 0.5]);
    assert_eq!(&ball[9..15], &[-1.0, 0.0, 0.0, 0.0, 0.0, 2.0]);
    assert_eq!(loaded.bodies[2].desc.shape, Shape::sphere(0.5));
    assert_eq!(loaded.camera.position, Vec3::new(0.0, 4.0, -12.0));
}

#[test]
fn a_built_in_name_wins_and_an_unknown_name_is_an_unknown_scene() {
    assert_eq!(scene::load("default").expect("built in").name, "default");
    let err = scene::load("definitely-not-a-scene").expect_err("unknown");
    assert_eq!(err.kind, SceneErrorKind::UnknownScene);
    assert!(err.to_string().contains(
        "default, stack, pyramid, ramp, dominoes, pendulum, cradle, chain, bridge, door, rain"
    ));
}
