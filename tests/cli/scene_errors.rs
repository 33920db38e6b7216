//! Bad scene files through the real binary: `nudge sim --scene FILE --steps 1` must exit with status 2
//! and print one message naming the file, the 1-based line and column of the problem and what is wrong,
//! and never panic.

use crate::common::temp::TempPath;
use std::process::{Command, Output};

fn sim(scene: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_nudge"))
        .args(["sim", "--scene", scene, "--steps", "1"])
        .output()
        .expect("run nudge")
}

fn assert_no_panic(stderr: &str) {
    assert!(
        !stderr.contains("panicked") && !stderr.contains("RUST_BACKTRACE"),
        "panic: {stderr}"
    );
}

/// Runs `text` as a scene file and checks for exit status 2 and `FILE:line:column: ...phrase...`.
fn assert_rejected(tag: &str, text: &str, line: usize, column: usize, phrase: &str) {
    let file = TempPath::with_text(&format!("{tag}.toml"), text);
    let out = sim(file.as_str());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_no_panic(&stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    let located = format!("{}:{line}:{column}: ", file.as_str());
    assert!(
        stderr.contains(&located),
        "expected {located:?} in {stderr:?}"
    );
    assert!(stderr.contains(phrase), "expected {phrase:?} in {stderr:?}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(out.stdout.is_empty(), "nothing simulated");
}

/// A valid sphere body (lines 1–4); append one `key = value` line to test it on line 5.
const SPHERE: &str = "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0, 1, 0]\n";
/// A valid box body (lines 1–4).
const BOX: &str =
    "[[body]]\nshape = \"box\"\nhalf_extents = [0.5, 0.5, 0.5]\nposition = [0, 1, 0]\n";

/// One test per bad input: name, file text, line, column, a phrase the message must contain.
macro_rules! rejected {
    ($($name:ident: $text:expr, $line:expr, $column:expr, $phrase:expr;)*) => {
        $(
            #[test]
            fn $name() {
                assert_rejected(stringify!($name), &$text, $line, $column, $phrase);
            }
        )*
    };
}

rejected! {
    // Not TOML, or not the schema.
    malformed_toml_is_rejected_where_it_breaks:
        "[world]\ndt = 0.01\n[camera\n", 3, 8, "";
    an_unterminated_string_is_rejected:
        format!("{SPHERE}color = \"#ff0000\n"), 5, 17, "invalid basic string";
    an_unknown_top_level_table_is_rejected_at_its_name:
        "[wrold]\ndt = 0.01\n", 1, 2, "unknown field `wrold`";
    an_unknown_body_key_is_rejected_at_the_key:
        format!("{SPHERE}colour = \"#ff0000\"\n"), 5, 1, "unknown field `colour`";
    an_unknown_camera_key_is_rejected_at_the_key:
        "[camera]\nfov = 60\n", 2, 1, "unknown field `fov`";
    an_unknown_world_key_is_rejected_at_the_key:
        "[world]\ngravity = [0, -9.81, 0]\nsubsteps = 8\n", 3, 1, "unknown field `substeps`";
    a_string_where_a_number_belongs_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = \"big\"\nposition = [0, 1, 0]\n", 3, 10, "invalid type";
    a_number_where_a_bool_belongs_is_rejected:
        format!("{SPHERE}static = 1\n"), 5, 10, "invalid type";
    a_vector_with_two_components_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0, 1]\n", 4, 12, "invalid length 2";
    a_single_body_table_instead_of_an_array_is_rejected:
        "[body]\nshape = \"sphere\"\n", 1, 1, "invalid type";
    a_body_without_a_shape_is_rejected:
        "[[body]]\nradius = 0.5\nposition = [0, 1, 0]\n", 1, 1, "missing field `shape`";
    a_body_without_a_position_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 0.5\n", 1, 1, "missing field `position`";
    an_unknown_shape_is_rejected:
        "[[body]]\nshape = \"cone\"\nposition = [0, 1, 0]\n", 2, 9, "unknown variant `cone`";
    an_unknown_projection_is_rejected:
        "[camera]\nprojection = \"fisheye\"\n", 2, 14, "unknown variant `fisheye`";

    // Shape sizes.
    a_box_without_half_extents_is_rejected_at_its_shape:
        "[[body]]\nshape = \"box\"\nposition = [0, 1, 0]\n", 2, 9, "a box needs half_extents";
    a_sphere_without_a_radius_is_rejected_at_its_shape:
        "[[body]]\nshape = \"sphere\"\nposition = [0, 1, 0]\n", 2, 9, "a sphere needs radius";
    a_sphere_with_half_extents_is_rejected:
        format!("{SPHERE}half_extents = [1, 1, 1]\n"), 5, 16, "half_extents is for boxes";
    a_box_with_a_radius_is_rejected:
        format!("{BOX}radius = 1\n"), 5, 10, "radius is for spheres";
    a_zero_radius_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 0\nposition = [0, 1, 0]\n", 3, 10,
        "radius must be finite and > 0, got 0";
    a_negative_radius_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = -1\nposition = [0, 1, 0]\n", 3, 10,
        "radius must be finite and > 0, got -1";
    a_nan_radius_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = nan\nposition = [0, 1, 0]\n", 3, 10,
        "radius must be finite and > 0, got nan";
    an_infinite_radius_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = inf\nposition = [0, 1, 0]\n", 3, 10,
        "radius must be finite and > 0, got inf";
    a_zero_half_extent_is_rejected:
        "[[body]]\nshape = \"box\"\nhalf_extents = [1, 0, 1]\nposition = [0, 1, 0]\n", 3, 16,
        "half_extents must be finite and > 0, got [1, 0, 1]";
    a_negative_half_extent_is_rejected:
        "[[body]]\nshape = \"box\"\nhalf_extents = [1, 1, -2]\nposition = [0, 1, 0]\n", 3, 16,
        "half_extents must be finite and > 0";
    a_nan_half_extent_is_rejected:
        "[[body]]\nshape = \"box\"\nhalf_extents = [nan, 1, 1]\nposition = [0, 1, 0]\n", 3, 16,
        "got [nan, 1, 1]";
    an_infinite_half_extent_is_rejected:
        "[[body]]\nshape = \"box\"\nhalf_extents = [1, +inf, 1]\nposition = [0, 1, 0]\n", 3, 16,
        "got [1, inf, 1]";
    a_sphere_too_small_to_have_mass_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 1e-20\nposition = [0, 1, 0]\n", 3, 10,
        "radius (m) must be between 0.001 and 1000, got 1e-20";
    a_density_too_low_for_a_usable_mass_is_rejected:
        format!("{SPHERE}density = 1e-10\n"), 5, 11,
        "mass (kg) must be between 0.000001 and 1000000";

    // Mass and density.
    a_dynamic_body_with_zero_mass_is_rejected:
        format!("{SPHERE}mass = 0\n"), 5, 8, "mass must be finite and > 0, got 0";
    a_negative_mass_is_rejected:
        format!("{SPHERE}mass = -2.5\n"), 5, 8, "mass must be finite and > 0, got -2.5";
    a_nan_mass_is_rejected:
        format!("{SPHERE}mass = nan\n"), 5, 8, "mass must be finite and > 0, got nan";
    an_infinite_mass_is_rejected:
        format!("{SPHERE}mass = inf\n"), 5, 8, "mass must be finite and > 0, got inf";
    a_zero_density_is_rejected:
        format!("{SPHERE}density = 0\n"), 5, 11, "density must be finite and > 0, got 0";
    a_negative_density_is_rejected:
        format!("{SPHERE}density = -1\n"), 5, 11, "density must be finite and > 0, got -1";
    a_nan_density_is_rejected:
        format!("{SPHERE}density = nan\n"), 5, 11, "density must be finite and > 0, got nan";
    an_infinite_density_is_rejected:
        format!("{SPHERE}density = -inf\n"), 5, 11, "density must be finite and > 0, got -inf";
    a_density_that_overflows_the_mass_is_rejected:
        "[[body]]\nshape = \"box\"\nhalf_extents = [100, 100, 100]\nposition = [0, 1, 0]\ndensity = 1e38\n",
        5, 11, "mass = density × volume = inf kg";
    a_size_too_extreme_for_its_inertia_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 1e15\nmass = 1e10\nposition = [0, 1, 0]\n", 3, 10,
        "radius (m) must be between 0.001 and 1000, got 1e15";
    a_static_mass_too_extreme_for_its_inertia_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 1000\nmass = 1e38\nstatic = true\nposition = [0, 1, 0]\n",
        4, 8, "moments of inertia";

    // Orientation.
    a_zero_rotation_axis_is_rejected:
        format!("{SPHERE}rotation_axis = [0, 0, 0]\nrotation_deg = 30\n"), 5, 17,
        "rotation_axis must not be zero";
    a_nan_rotation_axis_is_rejected:
        format!("{SPHERE}rotation_axis = [0, nan, 0]\nrotation_deg = 30\n"), 5, 17,
        "rotation_axis must be finite";
    rotation_deg_without_an_axis_is_rejected:
        format!("{SPHERE}rotation_deg = 30\n"), 5, 16, "rotation_deg needs rotation_axis";
    a_rotation_axis_without_an_angle_is_rejected:
        format!("{SPHERE}rotation_axis = [0, 1, 0]\n"), 5, 17, "rotation_axis needs rotation_deg";
    an_infinite_rotation_angle_is_rejected:
        format!("{SPHERE}rotation_axis = [0, 1, 0]\nrotation_deg = inf\n"), 6, 16,
        "rotation_deg must be finite, got inf";

    // Vectors.
    a_nan_position_is_rejected:
        "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0, nan, 0]\n", 4, 12,
        "position must be finite, got [0, nan, 0]";
    an_infinite_velocity_is_rejected:
        format!("{SPHERE}velocity = [inf, 0, 0]\n"), 5, 12, "velocity must be finite";
    a_nan_angular_velocity_is_rejected:
        format!("{SPHERE}angular_velocity = [0, 0, nan]\n"), 5, 20, "angular_velocity must be finite";
    a_nan_gravity_is_rejected:
        "[world]\ngravity = [0, nan, 0]\n", 2, 11, "gravity must be finite";
    a_static_body_with_a_velocity_is_rejected:
        format!("{SPHERE}static = true\nvelocity = [1, 0, 0]\n"), 6, 12, "static body never moves";

    // World.
    a_zero_dt_is_rejected:
        "[world]\ndt = 0\n", 2, 6, "dt must be finite and > 0, got 0";
    a_negative_dt_is_rejected:
        "[world]\ndt = -0.01\n", 2, 6, "dt must be finite and > 0, got -0.01";
    a_nan_dt_is_rejected:
        "[world]\ndt = nan\n", 2, 6, "dt must be finite and > 0, got nan";
    an_infinite_dt_is_rejected:
        "[world]\ndt = inf\n", 2, 6, "dt must be finite and > 0, got inf";

    // Camera.
    a_zero_fov_is_rejected:
        "[camera]\nfov_deg = 0\n", 2, 11, "fov_deg must be in (0, 180) degrees, got 0";
    a_fov_of_180_degrees_is_rejected:
        "[camera]\nfov_deg = 180\n", 2, 11, "fov_deg must be in (0, 180) degrees, got 180";
    a_nan_fov_is_rejected:
        "[camera]\nfov_deg = nan\n", 2, 11, "got nan";
    a_camera_target_equal_to_its_position_is_rejected:
        "[camera]\nposition = [1, 2, 3]\ntarget = [1.0, 2.0, 3.0]\n", 3, 10,
        "camera target must differ from its position";
    an_infinite_camera_position_is_rejected:
        "[camera]\nposition = [0, inf, -5]\n", 2, 12, "camera position must be finite";

    // Surface.
    a_negative_friction_is_rejected:
        format!("{SPHERE}friction = -0.1\n"), 5, 12, "friction must be finite and >= 0, got -0.1";
    a_nan_friction_is_rejected:
        format!("{SPHERE}friction = nan\n"), 5, 12, "friction must be finite and >= 0, got nan";
    a_restitution_above_one_is_rejected:
        format!("{SPHERE}restitution = 1.5\n"), 5, 15, "restitution must be in [0, 1], got 1.5";
    a_negative_restitution_is_rejected:
        format!("{SPHERE}restitution = -0.1\n"), 5, 15, "restitution must be in [0, 1], got -0.1";
    a_nan_restitution_is_rejected:
        format!("{SPHERE}restitution = nan\n"), 5, 15, "restitution must be in [0, 1], got nan";
    a_negative_rolling_resistance_is_rejected:
        format!("{SPHERE}rolling_resistance = -0.01\n"), 5, 22,
        "rolling_resistance must be finite and >= 0, got -0.01";
    an_infinite_rolling_resistance_is_rejected:
        format!("{SPHERE}rolling_resistance = inf\n"), 5, 22,
        "rolling_resistance must be finite and >= 0, got inf";

    // Colour.
    a_colour_name_is_rejected:
        format!("{SPHERE}color = \"red\"\n"), 5, 9, "color must be \"#rrggbb\"";
    a_short_colour_is_rejected:
        format!("{SPHERE}color = \"#fff\"\n"), 5, 9, "color must be \"#rrggbb\"";
    a_colour_without_hash_is_rejected:
        format!("{SPHERE}color = \"c08040\"\n"), 5, 9, "color must be \"#rrggbb\"";
    a_colour_with_a_non_hex_digit_is_rejected:
        format!("{SPHERE}color = \"#c0804g\"\n"), 5, 9, "color must be \"#rrggbb\"";

    // The error points into the right body of several.
    an_error_in_the_third_body_points_at_the_third_body:
        format!("{BOX}{SPHERE}{SPHERE}restitution = 2\n"), 13, 15, "restitution must be in [0, 1]";
}

#[test]
fn a_file_with_no_bodies_is_fine() {
    let file = TempPath::with_text("empty.toml", "# nothing here\n[world]\ndt = 0.01\n");
    let out = sim(file.as_str());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "stderr: {stderr}");
    assert!(String::from_utf8_lossy(&out.stdout).starts_with("steps=1 bodies=0 "));
}

#[test]
fn an_unknown_name_that_is_not_a_file_lists_the_built_in_scenes() {
    let out = sim("no-such-scene-or-file");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_no_panic(&stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains("no-such-scene-or-file"), "{stderr}");
    for name in ["default", "stack", "pyramid", "ramp", "dominoes", "rain"] {
        assert!(stderr.contains(name), "{name} missing from {stderr}");
    }
}

#[test]
fn a_directory_given_as_a_scene_is_an_input_error() {
    let dir = std::env::temp_dir();
    let out = sim(dir.to_str().expect("UTF-8 temp dir"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_no_panic(&stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
    assert!(stderr.contains("cannot read scene file"), "{stderr}");
}

#[test]
fn a_file_that_is_not_utf8_is_an_input_error() {
    let path = std::env::temp_dir().join(format!("nudge-scene-{}-latin1.toml", std::process::id()));
    std::fs::write(&path, b"[world]\n# caf\xe9\n").expect("write");
    let out = sim(path.to_str().expect("UTF-8 temp path"));
    let _ = std::fs::remove_file(&path);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_no_panic(&stderr);
    assert_eq!(out.status.code(), Some(2), "stderr: {stderr}");
}
