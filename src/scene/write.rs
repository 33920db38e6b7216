//! Writing a scene file: the inverse of [`super::file`], exact for the physics.
//!
//! The scene becomes [`super::schema`] tables and toml writes them, every float in Rust's shortest
//! round-trip form (the fewest digits that parse back to the same f32); orientations are written as
//! `orientation` quaternions and masses as `mass`, so a written scene builds a world whose bodies
//! have the same poses, velocities, masses and inertias bit for bit. The camera is written for people
//! (`fov_deg`; up, near and far framed again on load), so its field of view may differ in its last
//! bit; [`exact_camera`], the form recordings write, keeps every bit. Recordings write their added
//! bodies with [`body`] too.

use glam::Vec3;

use super::schema::{self, unplaced};
use super::vector::{Float, Floats};
use super::{Scene, SceneBody};
use crate::color::Rgb;
use crate::geometry::{Camera, Projection, Shape};
use crate::physics::{BodyDesc, World};

/// The scene holding `world` as it is now: every body with its current pose, velocities, mass,
/// material and static flag, coloured by `colors` (white past its end), seen by `camera`, with the
/// world's gravity and dt. A static body is scenery if `scenery` says so (or lies past its end), else
/// a frozen body (`frozen = true`). The world has no names for its bodies: the scene's are given
/// back by the caller that has them (`App::scene_now`).
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
            name: None,
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
        joints: world.joints().iter().map(|j| j.desc).collect(),
    }
}

/// The scene as scene-file text; `header` lines become comments at the top.
pub fn to_toml(scene: &Scene, header: &[&str]) -> String {
    let file = schema::SceneFile {
        world: Some(schema::World {
            gravity: Some(unplaced(floats(scene.settings.gravity))),
            dt: Some(unplaced(Float(scene.settings.dt))),
        }),
        camera: Some(unplaced(framing_camera(&scene.camera))),
        body: scene
            .bodies
            .iter()
            .map(|b| schema::Body {
                name: b.name.clone().map(unplaced),
                ..body(&b.desc, b.frozen, Some(b.color))
            })
            .collect(),
        joint: scene.joints.iter().map(super::joints::exact).collect(),
    };
    let mut out: String = header.iter().map(|line| format!("# {line}\n")).collect();
    // Only maps with keys that are not strings fail to serialize, and the schema has none.
    out += &toml::to_string(&file).expect("a scene file serializes");
    out
}

/// The body table that builds `desc` bit for bit: its orientation as a quaternion, its mass (not a
/// density), velocities unless static; `frozen = true` or `static`; its colour if it has one (a
/// recording's `add_body` has none).
pub fn body(desc: &BodyDesc, frozen: bool, color: Option<Rgb>) -> schema::Body {
    let (shape, half_extents, radius) = match desc.shape {
        Shape::Cuboid { half_extents } => (schema::Shape::Box, Some(floats(half_extents)), None),
        Shape::Sphere { radius } => (schema::Shape::Sphere, None, Some(Float(radius))),
    };
    let moving = (!desc.is_static).then_some(());
    schema::Body {
        name: None,
        shape: unplaced(shape),
        half_extents: half_extents.map(unplaced),
        radius: radius.map(unplaced),
        position: unplaced(floats(desc.pose.position)),
        rotation_axis: None,
        rotation_deg: None,
        orientation: Some(unplaced(Floats(desc.pose.rotation.to_array()))),
        velocity: moving.map(|()| unplaced(floats(desc.linear_velocity))),
        angular_velocity: moving.map(|()| unplaced(floats(desc.angular_velocity))),
        density: None,
        mass: Some(unplaced(Float(desc.mass))),
        is_static: (!frozen).then_some(desc.is_static),
        frozen: frozen.then(|| unplaced(true)),
        friction: Some(unplaced(Float(desc.friction))),
        restitution: Some(unplaced(Float(desc.restitution))),
        rolling_resistance: Some(unplaced(Float(desc.rolling_resistance))),
        color: color.map(|c| unplaced(c.to_hex())),
    }
}

/// The camera as a scene file gives it, for people to edit: position, target, projection and the
/// field of view in degrees (an orthographic camera's as the perspective angle that frames the same
/// slab at the target). Up, near and far are framed from the scene when it loads.
fn framing_camera(camera: &Camera) -> schema::Camera {
    let (projection, fov_deg) = match camera.projection {
        Projection::Perspective { fov_y } => (schema::Projection::Perspective, fov_y.to_degrees()),
        Projection::Orthographic { view_height } => {
            let distance = (camera.target - camera.position).length();
            let fov_y = 2.0 * (0.5 * view_height / distance).atan();
            (schema::Projection::Orthographic, fov_y.to_degrees())
        }
    };
    schema::Camera {
        position: Some(unplaced(floats(camera.position))),
        target: Some(unplaced(floats(camera.target))),
        projection: Some(unplaced(projection)),
        fov_deg: (fov_deg > 0.0 && fov_deg < 180.0).then(|| unplaced(Float(fov_deg))),
        ..Default::default()
    }
}

/// The camera exactly, as a recording gives it: every field, the field of view in radians.
pub fn exact_camera(camera: &Camera) -> schema::Camera {
    let (fov_y, view_height) = match camera.projection {
        Projection::Perspective { fov_y } => (Some(fov_y), None),
        Projection::Orthographic { view_height } => (None, Some(view_height)),
    };
    schema::Camera {
        position: Some(unplaced(floats(camera.position))),
        target: Some(unplaced(floats(camera.target))),
        up: Some(unplaced(floats(camera.up))),
        fov_y: fov_y.map(|v| unplaced(Float(v))),
        view_height: view_height.map(|v| unplaced(Float(v))),
        near: Some(unplaced(Float(camera.near))),
        far: Some(unplaced(Float(camera.far))),
        ..Default::default()
    }
}

/// A vector as the schema holds it.
pub fn floats(v: Vec3) -> Floats<3> {
    Floats(v.to_array())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::file;

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
