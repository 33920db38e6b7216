//! The scene file's `orientation = [x, y, z, w]` key: a unit quaternion, checked and located like
//! every other key, and kept bit for bit when it is unit already.

use glam::Quat;
use nudge::scene::{SceneErrorKind, file};

fn body(orientation_line: &str) -> String {
    format!(
        "[[body]]\nshape = \"sphere\"\nradius = 0.5\nposition = [0.0, 1.0, 0.0]\n{orientation_line}\n"
    )
}

/// Parses and expects an error at line 5, column `column`, whose message contains `needle`.
fn assert_error(text: &str, column: usize, needle: &str) {
    let err = file::parse(text, "bad.toml").expect_err(text);
    assert_eq!(err.kind, SceneErrorKind::Invalid, "{err}");
    let at = err.location.expect("located");
    assert_eq!((at.line, at.column), (5, column), "{err}");
    assert!(err.message.contains(needle), "{err}");
    assert!(err.to_string().starts_with("bad.toml:5:"), "{err}");
}

#[test]
fn a_unit_orientation_is_kept_bit_for_bit() {
    let q = Quat::from_axis_angle(glam::Vec3::new(0.3, 0.9, -0.2).normalize(), 1.234);
    let [x, y, z, w] = q.to_array();
    let scene = file::parse(
        &body(&format!("orientation = [{x}, {y}, {z}, {w}]")),
        "t.toml",
    )
    .unwrap();
    assert_eq!(
        scene.bodies[0]
            .desc
            .pose
            .rotation
            .to_array()
            .map(f32::to_bits),
        q.to_array().map(f32::to_bits)
    );
}

#[test]
fn a_nearly_unit_orientation_is_normalised() {
    let scene = file::parse(&body("orientation = [0.0, 0.0, 0.0, 1.0009]"), "t.toml").unwrap();
    assert_eq!(scene.bodies[0].desc.pose.rotation, Quat::IDENTITY);
}

#[test]
fn orientations_far_from_unit_length_are_rejected_where_they_are_written() {
    assert_error(
        &body("orientation = [0.0, 0.0, 0.0, 1.002]"),
        15,
        "unit quaternion",
    );
    assert_error(
        &body("orientation = [0.0, 0.0, 0.0, 0.0]"),
        15,
        "length within 0.001 of 1",
    );
}

#[test]
fn non_finite_orientations_are_rejected() {
    assert_error(
        &body("orientation = [nan, 0.0, 0.0, 1.0]"),
        15,
        "must be finite",
    );
    assert_error(
        &body("orientation = [0.0, inf, 0.0, 1.0]"),
        15,
        "must be finite",
    );
}

#[test]
fn orientation_with_axis_angle_is_rejected() {
    let text = body(
        "orientation = [0.0, 0.0, 0.0, 1.0]\nrotation_axis = [0.0, 1.0, 0.0]\nrotation_deg = 30.0",
    );
    assert_error(&text, 15, "cannot be given with rotation_axis");
}

#[test]
fn an_orientation_of_three_components_is_a_located_syntax_error() {
    let err = file::parse(&body("orientation = [0.0, 0.0, 1.0]"), "bad.toml").expect_err("three");
    assert_eq!(err.location.map(|l| l.line), Some(5), "{err}");
}
