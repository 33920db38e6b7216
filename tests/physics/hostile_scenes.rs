//! Nothing a scene file says can make nudge panic, produce a non-finite state or take unbounded
//! memory: each reproducer found as a regression test, the corners of the representable range
//! (`physics::limits`) stepped and checked finite, and a seeded fuzzer over scene files.

use crate::common;

use common::cli::nudge;

use nudge::physics::World;
use nudge::physics::limits;
use nudge::scene::{SceneErrorKind, file};
use nudge::util::SplitMix64;

/// Writes `text` to a temporary scene file named for `name`; returns its path.
fn scene_file(name: &str, text: &[u8]) -> String {
    let path =
        std::env::temp_dir().join(format!("nudge-hostile-{}-{name}.toml", std::process::id()));
    std::fs::write(&path, text).expect("write scene");
    path.to_string_lossy().into_owned()
}

/// `nudge sim` on `text` must exit 2 with one stderr line `PATH:LINE:COLUMN: ...` containing
/// `phrase`, at most `max_len` characters long.
fn refused(name: &str, text: &[u8], line: usize, column: usize, phrase: &str) -> String {
    let path = scene_file(name, text);
    let out = nudge(&["sim", "--scene", &path, "--steps", "60"]);
    let _ = std::fs::remove_file(&path);
    let message = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{name}: {message}");
    assert!(
        message.starts_with(&format!("nudge: {path}:{line}:{column}: ")),
        "{name}: {message}"
    );
    assert!(message.contains(phrase), "{name}: {message}");
    assert_eq!(message.lines().count(), 1, "{name}: {message}");
    message
}

const SPHERE_AT: &str = "[[body]]\nshape = \"sphere\"\nradius = 1\n";

#[test]
fn a_sphere_of_1e_minus_20_m_is_refused_where_it_is_sized() {
    refused(
        "tiny",
        b"[[body]]\nshape = \"sphere\"\nradius = 1e-20\nmass = 1\nposition = [0, 1, 0]\n",
        3,
        10,
        "radius (m) must be between 0.001 and 1000, got 1e-20",
    );
}

#[test]
fn overlapping_spheres_of_54_km_and_39_nm_are_refused() {
    refused(
        "overlap",
        b"[[body]]\nshape = \"sphere\"\nradius = 54117\nposition = [0, 0, 0]\n\
          [[body]]\nshape = \"sphere\"\nradius = 3.9e-8\nposition = [0, 1, 0]\n",
        3,
        10,
        "radius (m) must be between",
    );
}

#[test]
fn dynamic_bodies_too_different_in_size_or_mass_are_refused_at_the_later_one() {
    let big = "[[body]]\nshape = \"sphere\"\nradius = 20\nmass = 1000\nposition = [0, 0, 0]\n";
    let small =
        "[[body]]\nshape = \"sphere\"\nradius = 0.001\nmass = 0.001\nposition = [0, 50, 0]\n";
    refused(
        "size-ratio",
        format!("{big}{small}").as_bytes(),
        7,
        9,
        "differ in size by a factor of 10000 at most",
    );
    let heavy = "[[body]]\nshape = \"sphere\"\nradius = 1\nmass = 1000000\nposition = [0, 0, 0]\n";
    let light = "[[body]]\nshape = \"sphere\"\nradius = 1\nmass = 0.01\nposition = [0, 5, 0]\n";
    refused(
        "mass-ratio",
        format!("{heavy}{light}").as_bytes(),
        7,
        9,
        "differ in mass by a factor of 1000000 at most",
    );
}

#[test]
fn initial_speeds_above_the_engine_caps_are_refused() {
    refused(
        "fast",
        format!("{SPHERE_AT}position = [0, 1, 0]\nvelocity = [10000, 3000, 7000]\n").as_bytes(),
        5,
        12,
        "velocity (m/s) must be finite and at most 400 long",
    );
    refused(
        "spin",
        format!("{SPHERE_AT}position = [0, 1, 0]\nangular_velocity = [0, 500, 0]\n").as_bytes(),
        5,
        20,
        "angular_velocity (rad/s) must be finite and at most 200 long",
    );
}

#[test]
fn world_settings_out_of_range_are_refused() {
    refused(
        "dt",
        b"[world]\ndt = 5\n",
        2,
        6,
        "dt (s) must be between 0.0001 and 0.1",
    );
    refused(
        "gravity",
        b"[world]\ngravity = [0, -1e6, 0]\n",
        2,
        11,
        "gravity (m/s²) must be finite and at most 1000 long",
    );
}

#[test]
fn vectors_must_have_exactly_three_numbers() {
    refused(
        "position4",
        format!("{SPHERE_AT}position = [0, 3, 0, 1]\n").as_bytes(),
        4,
        12,
        "position: invalid length 4, expected an array of exactly 3 numbers",
    );
    refused(
        "half-extents4",
        b"[[body]]\nshape = \"box\"\nhalf_extents = [0.5, 0.5, 0.5, -7]\nposition = [0, 1, 0]\n",
        3,
        16,
        "half_extents: invalid length 4",
    );
    refused(
        "target-junk",
        b"[camera]\ntarget = [0, 1, 0, \"junk\"]\n",
        2,
        10,
        "target: invalid length 4",
    );
    let million = format!("[world]\ngravity = [{}0]\n", "0, ".repeat(999_999));
    let message = refused(
        "gravity-million",
        million.as_bytes(),
        2,
        11,
        "gravity: invalid length 1000000",
    );
    assert!(message.len() < 300, "{message}");
}

#[test]
fn huge_values_give_short_messages() {
    let message = refused(
        "gravity-1e308",
        b"[world]\ngravity = 1e308\n",
        2,
        11,
        "floating point `1e308`",
    );
    assert!(message.len() < 200, "{message}");
    let colour = "x".repeat(5_000_000);
    let message = refused(
        "colour-5mb",
        format!("{SPHERE_AT}position = [0, 1, 0]\ncolor = \"{colour}\"\n").as_bytes(),
        5,
        9,
        "color must be \"#rrggbb\"",
    );
    assert!(message.len() < 300, "{} bytes", message.len());
    assert!(message.contains('…'), "{message}");
}

/// `gravity = [0, 1e308, 0]` is finite in the file, but f32 parsing made it infinity: the message
/// said "gravity must be finite, got [0, inf, 0]", a value the file never held.
#[test]
fn a_finite_number_beyond_f32_is_refused_as_written_not_as_infinity() {
    for (name, text, line, column, phrase) in [
        (
            "gravity-1e308-vector",
            "[world]\ngravity = [0, 1e308, 0]\n",
            2,
            15,
            "gravity: 1e308 is beyond what a 32-bit float holds",
        ),
        (
            "dt-1e300",
            "[world]\ndt = 1e300\n",
            2,
            6,
            "dt: 1e300 is beyond what a 32-bit float holds",
        ),
        (
            "mass-minus-1e39",
            "[[body]]\nshape = \"sphere\"\nradius = 1\nmass = -1e39\nposition = [0, 1, 0]\n",
            4,
            8,
            "mass: -1e39 is beyond what a 32-bit float holds",
        ),
    ] {
        let message = refused(name, text.as_bytes(), line, column, phrase);
        assert!(!message.contains("inf"), "{message}");
    }
    // What the file holds as infinity is still refused as not finite.
    refused(
        "dt-inf",
        b"[world]\ndt = inf\n",
        2,
        6,
        "dt must be finite and > 0, got inf",
    );
}

#[test]
fn a_long_overlay_name_is_cut_in_the_message() {
    let name = "x".repeat(100_000);
    let out = nudge(&["snapshot", "--overlay", &name]);
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{message}");
    assert!(
        message.contains(&format!("unknown overlay '{}…'", "x".repeat(60))),
        "{message}"
    );
    // clap's own "invalid value '…'" names the argument too: cut like any long word (80
    // characters), so the whole message stays a few lines (333 bytes measured).
    assert!(!message.contains(&"x".repeat(81)), "{message}");
    assert!(message.len() < 400, "{} bytes: {message}", message.len());
}

#[test]
fn a_file_that_is_not_utf8_is_located_at_its_first_bad_byte() {
    refused(
        "not-utf8",
        b"[[body]]\nshape = \"sphere\"\n# caf\xe9 \xff\nradius = 1\n",
        3,
        6,
        "not valid UTF-8",
    );
}

#[cfg(unix)]
#[test]
fn dev_zero_is_read_up_to_the_cap_and_refused() {
    let out = nudge(&["sim", "--scene", "/dev/zero", "--steps", "1"]);
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{message}");
    assert!(message.contains("larger than 64 MB"), "{message}");
}

#[cfg(unix)]
#[test]
fn a_recording_from_dev_zero_is_refused_too() {
    let out = nudge(&["replay", "/dev/zero", "--trace", "/dev/null"]);
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{message}");
    assert!(message.contains("larger than 64 MB"), "{message}");
}

#[test]
fn command_line_counts_have_upper_bounds() {
    for (flag, value, phrase) in [
        ("--steps", "10000001", "--steps must be at most 10000000"),
        (
            "--substeps",
            "65",
            "--substeps must be at least 1 and at most 64",
        ),
        (
            "--iterations",
            "1000000",
            "--iterations must be at least 1 and at most 64",
        ),
    ] {
        let mut args = vec!["sim", "--scene", "default", "--steps", "1"];
        if flag == "--steps" {
            args[4] = value;
        } else {
            args.extend([flag, value]);
        }
        let out = nudge(&args);
        let message = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag}: {message}");
        assert!(message.contains(phrase), "{flag}: {message}");
    }
    let out = nudge(&["snapshot", "--steps", "99999999999"]);
    assert_eq!(out.status.code(), Some(2));
}

/// Every body's pose and velocities are finite.
fn all_finite(world: &World) -> bool {
    world.bodies().iter().all(|b| {
        b.pose().is_finite() && b.linear_velocity().is_finite() && b.angular_velocity().is_finite()
    })
}

/// Steps the scene `steps` times, asserting every state finite.
fn stays_finite(name: &str, text: &str, steps: usize) {
    let scene = file::parse(text, name).unwrap_or_else(|e| panic!("{e}"));
    let mut world = scene.build_world();
    for step in 1..=steps {
        world.step();
        assert!(all_finite(&world), "{name}: non-finite at step {step}");
    }
}

/// A body of each extreme: the smallest and lightest at the fastest speeds, the largest dynamic
/// body the ratios allow, on the largest static floor, under the strongest gravity.
fn corners(dt: f32, gravity: f32) -> String {
    let mut text = format!("[world]\ngravity = [0, {gravity}, 0]\ndt = {dt}\n");
    text += "[[body]]\nshape = \"box\"\nhalf_extents = [1000, 1, 1000]\nposition = [0, -1, 0]\nstatic = true\n";
    for (shape, size, mass, position, velocity, spin) in [
        (
            "sphere",
            "radius = 0.001",
            0.001,
            [0.0, 0.0005, 0.0],
            [0.0, -400.0, 0.0],
            [200.0, 0.0, 0.0],
        ),
        (
            "sphere",
            "radius = 9.9",
            1000.0,
            [0.0, 5.0, 0.0],
            [0.0, -400.0, 0.0],
            [0.0; 3],
        ),
        (
            "box",
            "half_extents = [0.001, 0.001, 0.001]",
            0.001,
            [0.005, 0.001, 0.0],
            [400.0, 0.0, 0.0],
            [0.0; 3],
        ),
        (
            "box",
            "half_extents = [7, 7, 0.001]",
            1000.0,
            [0.005, 3.0, 0.0],
            [0.0, 0.0, -400.0],
            [0.0, 200.0, 0.0],
        ),
        (
            "sphere",
            "radius = 0.001",
            0.001,
            [9999.0, 0.001, -9999.0],
            [0.0, 0.0, 400.0],
            [0.0; 3],
        ),
    ] {
        text += &format!(
            "[[body]]\nshape = \"{shape}\"\n{size}\nmass = {mass}\nposition = {position:?}\n\
             velocity = {velocity:?}\nangular_velocity = {spin:?}\n"
        );
    }
    text
}

#[test]
fn the_corners_of_the_range_stay_finite() {
    for dt in [limits::MIN_DT, 1.0 / 60.0, limits::MAX_DT] {
        for gravity in [0.0, -limits::MAX_GRAVITY] {
            stays_finite(
                &format!("corners dt={dt} g={gravity}"),
                &corners(dt, gravity),
                300,
            );
        }
    }
}

#[test]
fn coincident_bodies_stay_finite() {
    let mut text = String::new();
    for _ in 0..20 {
        text += "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0, 1, 0]\n";
        text += "[[body]]\nshape = \"box\"\nhalf_extents = [0.5, 0.5, 0.5]\nposition = [0, 1, 0]\n";
    }
    stays_finite("coincident", &text, 300);
}

/// One scene file, sometimes valid and sometimes not, from a mix of ordinary values, the edges of
/// the representable range, extremes and wrong types.
fn random_scene(rng: &mut SplitMix64) -> String {
    fn pick<'a>(rng: &mut SplitMix64, options: &[&'a str]) -> &'a str {
        options[(rng.next_u64() % options.len() as u64) as usize]
    }
    fn number(rng: &mut SplitMix64, wild: bool) -> String {
        if !wild {
            return format!("{}", 0.05 + rng.next_unit() * 3.0);
        }
        match rng.next_u64() % 8 {
            0..=3 => format!("{}", (rng.next_unit() - 0.3) * 10.0),
            4 => pick(
                rng,
                &[
                    "0", "-0.0", "1e-3", "1e3", "1e4", "-1e4", "0.1", "1e-4", "400", "200", "1000",
                    "1e6",
                ],
            )
            .into(),
            5 => pick(
                rng,
                &[
                    "1e-20",
                    "1e38",
                    "-1e38",
                    "3.4e38",
                    "1e-45",
                    "nan",
                    "inf",
                    "-inf",
                    "9999999999",
                ],
            )
            .into(),
            6 => format!("{}", rng.next_u64() as i64),
            _ => pick(rng, &["\"x\"", "true", "[]", "[1, 2]", "{ a = 1 }"]).into(),
        }
    }
    fn vector(rng: &mut SplitMix64, n: usize, wild: bool) -> String {
        let len = if wild && rng.next_u64() % 10 == 0 {
            (rng.next_u64() % 6) as usize
        } else {
            n
        };
        let items: Vec<String> = (0..len).map(|_| number(rng, wild)).collect();
        format!("[{}]", items.join(", "))
    }
    // Half the files hold only ordinary values, so that many are accepted and stepped.
    let wild = rng.next_u64() % 2 == 0;
    let mut text = String::new();
    if rng.next_u64() % 3 == 0 {
        text += &format!(
            "[world]\ngravity = {}\ndt = {}\n",
            vector(rng, 3, wild),
            number(rng, wild)
        );
    }
    if rng.next_u64() % 4 == 0 {
        text += &format!(
            "[camera]\nposition = {}\ntarget = {}\n",
            vector(rng, 3, wild),
            vector(rng, 3, wild)
        );
    }
    for _ in 0..(rng.next_u64() % 6) {
        let shape = if wild {
            pick(rng, &["box", "sphere", "sphere", "cone"])
        } else {
            pick(rng, &["box", "sphere"])
        };
        text += &format!("[[body]]\nshape = \"{shape}\"\n");
        match (shape, rng.next_u64() % 8) {
            (_, 0) => {}
            ("box", _) => text += &format!("half_extents = {}\n", vector(rng, 3, wild)),
            _ => text += &format!("radius = {}\n", number(rng, wild)),
        }
        text += &format!("position = {}\n", vector(rng, 3, wild));
        for key in [
            "velocity",
            "angular_velocity",
            "rotation_axis",
            "orientation",
        ] {
            if rng.next_u64() % 4 == 0 {
                let n = if key == "orientation" { 4 } else { 3 };
                text += &format!("{key} = {}\n", vector(rng, n, wild));
            }
        }
        for key in [
            "mass",
            "density",
            "friction",
            "restitution",
            "rolling_resistance",
            "rotation_deg",
        ] {
            if rng.next_u64() % 4 == 0 {
                text += &format!("{key} = {}\n", number(rng, wild));
            }
        }
        if rng.next_u64() % 5 == 0 {
            text += &format!("static = {}\n", pick(rng, &["true", "false", "1"]));
        }
        if rng.next_u64() % 20 == 0 {
            text += "colour = \"#ffffff\"\n";
        }
    }
    // Now and then, damage the text itself: cut it short or flip a byte.
    match rng.next_u64() % 10 {
        _ if !wild => {}
        0 if !text.is_empty() => {
            let cut = (rng.next_u64() % text.len() as u64) as usize;
            let cut = (0..=cut)
                .rev()
                .find(|&i| text.is_char_boundary(i))
                .unwrap_or(0);
            text.truncate(cut);
        }
        1 if !text.is_empty() => {
            let at = (rng.next_u64() % text.len() as u64) as usize;
            if text.is_char_boundary(at) && text.is_char_boundary(at + 1) {
                let c = pick(rng, &["[", "]", "\"", "=", "\n", "#", ","]);
                text.replace_range(at..at + 1, c);
            }
        }
        _ => {}
    }
    text
}

/// A few thousand generated scene files: each is either refused with a located error, or accepted
/// and steps 30 times with every state finite.
#[test]
fn fuzzed_scene_files_are_refused_with_a_location_or_stay_finite() {
    let mut rng = SplitMix64(0x17_17_17);
    let (mut accepted, mut refused) = (0, 0);
    for case in 0..3000 {
        let text = random_scene(&mut rng);
        match file::parse(&text, "fuzz.toml") {
            Ok(scene) => {
                accepted += 1;
                let mut world = scene.build_world();
                for step in 1..=30 {
                    world.step();
                    assert!(all_finite(&world), "case {case}, step {step}:\n{text}");
                }
            }
            Err(err) => {
                refused += 1;
                assert!(
                    matches!(err.kind, SceneErrorKind::Syntax | SceneErrorKind::Invalid),
                    "case {case}: {err}"
                );
                assert!(
                    err.location.is_some(),
                    "case {case}: unlocated {err}\n{text}"
                );
                assert!(err.to_string().len() < 400, "case {case}: {err}");
            }
        }
    }
    // The generator must exercise both sides.
    assert!(
        accepted > 300 && refused > 300,
        "{accepted} accepted, {refused} refused"
    );
}

/// A short recording with a gravity change and a spawned box, as the sandbox writes it.
fn recording_text() -> String {
    use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
    let path = std::env::temp_dir().join(format!("nudge-hostile-{}-rec.toml", std::process::id()));
    let scene = nudge::scene::builtin::by_name("default").unwrap();
    let mut app = nudge::app::App::new(scene, nudge::app::AppConfig::default());
    app.resize(ratatui::layout::Rect::new(0, 0, 80, 24));
    app.start_recording(&path).unwrap();
    for key in ['g', 'b'] {
        app.handle_event(&Event::Key(KeyEvent::new(
            KeyCode::Char(key),
            KeyModifiers::NONE,
        )));
        app.step_physics();
    }
    app.finish_recording().unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let _ = std::fs::remove_file(&path);
    text
}

/// `nudge replay` on `text` must exit 2 with a message at line `line` containing `phrase`.
fn replay_refused(name: &str, text: &str, line: usize, phrase: &str) {
    let path = scene_file(name, text.as_bytes());
    let out = nudge(&["replay", &path, "--trace", "/dev/null"]);
    let _ = std::fs::remove_file(&path);
    let message = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {message}");
    assert!(
        message.starts_with(&format!("nudge: {path}:{line}:")),
        "{name}: {message}"
    );
    assert!(message.contains(phrase), "{name}: {message}");
}

#[test]
fn recordings_hold_to_the_same_ranges_and_vector_lengths() {
    let good = recording_text();
    let line_of =
        |text: &str, needle: &str| text.lines().position(|l| l.contains(needle)).expect(needle) + 1;
    let gravity = good.find("gravity = [").expect("a gravity input");
    let mut four = good.clone();
    four.insert_str(gravity + "gravity = [".len(), "1, ");
    replay_refused(
        "rec-gravity4",
        &four,
        line_of(&four, "gravity = [1, "),
        "invalid length 4",
    );
    let half = good.find("half_extents = [").expect("a spawned box");
    let mut tiny = good.clone();
    tiny.insert_str(half + "half_extents = [".len(), "1e-20, ");
    let end = tiny[half..].find(']').unwrap() + half;
    let inside = tiny[half + "half_extents = [".len()..end].to_owned();
    let three: Vec<&str> = inside.split(", ").take(3).collect();
    tiny.replace_range(half + "half_extents = [".len()..end, &three.join(", "));
    replay_refused(
        "rec-tiny",
        &tiny,
        line_of(&tiny, "half_extents = [1e-20"),
        "half_extents (m) must each be between 0.001 and 1000",
    );
}
