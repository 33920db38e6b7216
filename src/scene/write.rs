//! Writing a scene file: the inverse of [`super::file`], exact for the physics.
//!
//! Every float is written in Rust's shortest round-trip form (`{}` on f32: the fewest digits that
//! parse back to the same f32), orientations as `orientation` quaternions and masses as `mass`, so
//! a written scene builds a world whose bodies have the same poses, velocities, masses and inertias
//! bit for bit. The camera's field of view goes through degrees and may differ in its last bit.

use std::fmt::Write as _;

use glam::Vec3;

use super::{Scene, SceneBody};
use crate::color::Rgb;
use crate::geometry::{Camera, Projection, Shape};
use crate::physics::{BodyDesc, World};

/// The scene holding `world` as it is now: every body with its current pose, velocities, mass,
/// material and static flag, coloured by `colors` (white past its end), seen by `camera`, with the
/// world's gravity and dt. A static body is scenery if `scenery` says so (or lies past its end), else
/// a frozen body (`frozen = true`).
pub fn scene_of_world(
    name: &str,
    world: &World,
    colors: &[Rgb],
    scenery: &[bool],
    camera: &Camera,
) -> Scene {
    let bodies = world
        .bodies()
        .iter()
        .enumerate()
        .map(|(i, body)| SceneBody {
            desc: BodyDesc {
                shape: *body.shape(),
                pose: *body.pose(),
                linear_velocity: body.linear_velocity(),
                angular_velocity: body.angular_velocity(),
                mass: body.mass(),
                is_static: body.is_static(),
                friction: body.friction(),
                restitution: body.restitution(),
                rolling_resistance: body.rolling_resistance(),
            },
            color: colors.get(i).copied().unwrap_or(Rgb::WHITE),
            frozen: body.is_static() && !scenery.get(i).copied().unwrap_or(true),
        })
        .collect();
    let settings = crate::physics::Settings {
        gravity: world.settings().gravity,
        dt: world.settings().dt,
        ..Default::default()
    };
    Scene {
        name: name.to_owned(),
        settings,
        camera: *camera,
        bodies,
    }
}

/// The scene as scene-file text; `header` lines become comments at the top.
pub fn to_toml(scene: &Scene, header: &[&str]) -> String {
    let mut out = String::new();
    for line in header {
        let _ = writeln!(out, "# {line}");
    }
    let _ = writeln!(out, "[world]");
    let _ = writeln!(out, "gravity = {}", vec3(scene.settings.gravity));
    let _ = writeln!(out, "dt = {}", num(scene.settings.dt));
    let camera = &scene.camera;
    let _ = writeln!(out, "\n[camera]");
    let _ = writeln!(out, "position = {}", vec3(camera.position));
    let _ = writeln!(out, "target = {}", vec3(camera.target));
    let fov_deg = match camera.projection {
        Projection::Perspective { fov_y } => {
            let _ = writeln!(out, "projection = \"perspective\"");
            fov_y.to_degrees()
        }
        Projection::Orthographic { view_height } => {
            let _ = writeln!(out, "projection = \"orthographic\"");
            // The perspective angle that frames the same slab at the target (see the file format).
            let distance = (camera.target - camera.position).length();
            (2.0 * (0.5 * view_height / distance).atan()).to_degrees()
        }
    };
    if fov_deg > 0.0 && fov_deg < 180.0 {
        let _ = writeln!(out, "fov_deg = {}", num(fov_deg));
    }
    for body in &scene.bodies {
        let d = &body.desc;
        let _ = writeln!(out, "\n[[body]]");
        match d.shape {
            Shape::Cuboid { half_extents } => {
                let _ = writeln!(
                    out,
                    "shape = \"box\"\nhalf_extents = {}",
                    vec3(half_extents)
                );
            }
            Shape::Sphere { radius } => {
                let _ = writeln!(out, "shape = \"sphere\"\nradius = {}", num(radius));
            }
        }
        let _ = writeln!(out, "position = {}", vec3(d.pose.position));
        let [x, y, z, w] = d.pose.rotation.to_array();
        let _ = writeln!(
            out,
            "orientation = [{}, {}, {}, {}]",
            num(x),
            num(y),
            num(z),
            num(w)
        );
        if !d.is_static {
            let _ = writeln!(out, "velocity = {}", vec3(d.linear_velocity));
            let _ = writeln!(out, "angular_velocity = {}", vec3(d.angular_velocity));
        }
        let _ = writeln!(out, "mass = {}", num(d.mass));
        if body.frozen {
            let _ = writeln!(out, "frozen = true");
        } else {
            let _ = writeln!(out, "static = {}", d.is_static);
        }
        let _ = writeln!(out, "friction = {}", num(d.friction));
        let _ = writeln!(out, "restitution = {}", num(d.restitution));
        let _ = writeln!(out, "rolling_resistance = {}", num(d.rolling_resistance));
        let c = body.color;
        let _ = writeln!(out, "color = \"#{:02x}{:02x}{:02x}\"", c.r, c.g, c.b);
    }
    out
}

/// Shortest round-trip form, always a TOML float (`1` is written `1.0`, so huge values are not
/// read as out-of-range integers).
pub fn num(x: f32) -> String {
    let text = format!("{x}");
    if text.contains(['.', 'e', 'i', 'N']) {
        text
    } else {
        text + ".0"
    }
}

fn vec3(v: Vec3) -> String {
    format!("[{}, {}, {}]", num(v.x), num(v.y), num(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::file;

    #[test]
    fn floats_are_written_shortest_and_read_back_to_the_same_bits() {
        assert_eq!(num(1.0), "1.0");
        assert_eq!(num(-0.0), "-0.0");
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(1e20), "100000000000000000000.0");
        // Through the TOML reader (which parses f64 and narrows): a spread of awkward values.
        let mut x = 1.0e-30f32;
        let mut values = vec![f32::MIN_POSITIVE, f32::MAX, 1.0 / 3.0, 16_777_217.0];
        while x < 1e30 {
            values.push(x);
            values.push(-x * 1.000_123_4);
            x *= 1.618_034;
        }
        for v in values {
            let text = format!("dt = {}", num(v.abs().max(f32::MIN_POSITIVE)));
            #[derive(serde::Deserialize)]
            struct T {
                dt: f32,
            }
            let back: T = toml::from_str(&text).unwrap();
            assert_eq!(
                back.dt.to_bits(),
                v.abs().max(f32::MIN_POSITIVE).to_bits(),
                "{text}"
            );
        }
    }

    #[test]
    fn a_written_scene_parses_back_to_the_same_bodies_bit_for_bit() {
        let scene = crate::scene::builtin::by_name("ramp").unwrap();
        let mut world = scene.build_world();
        for _ in 0..50 {
            world.step();
        }
        let colors: Vec<Rgb> = scene.bodies.iter().map(|b| b.color).collect();
        let scenery: Vec<bool> = scene.bodies.iter().map(|b| b.desc.is_static).collect();
        let saved = scene_of_world("t", &world, &colors, &scenery, &scene.camera);
        let back = file::parse(&to_toml(&saved, &["test"]), "t.toml").unwrap();
        assert_eq!(back.bodies.len(), saved.bodies.len());
        for (a, b) in saved.bodies.iter().zip(&back.bodies) {
            assert_eq!(format!("{a:?}"), format!("{b:?}"));
        }
        assert_eq!(back.settings.gravity, saved.settings.gravity);
        assert_eq!(back.settings.dt.to_bits(), saved.settings.dt.to_bits());
        assert_eq!(back.camera.position, saved.camera.position);
    }
}
