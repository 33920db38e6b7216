//! The automatic camera: where to look from when a scene does not say.
//!
//! The camera looks at the centre of the *framed boxes* from in front (negative z) and above, at
//! [`AUTO_ELEVATION_DEG`], from the smallest distance at which every corner of every framed box falls
//! inside [`FRAMING_FILL`] of the image of a [`FRAMING_ASPECT`] view (a 120×40 terminal of 1:2 cells).
//!
//! The framed boxes are the bounds of the dynamic bodies plus the parts of static bodies near them, so
//! an 80 m floor under a 2 m stack does not shrink the stack to a dot. Precisely: D = union of the
//! dynamic bodies' boxes; E = the x–z footprint of D grown on every side by max(largest half-extent of
//! D, 1 m); framed boxes = each dynamic box, and each static box that reaches into E clipped to E in x
//! and z (whole in y). Without dynamic bodies they are all the bodies' boxes.

use glam::Vec3;

use super::SceneBody;
use crate::geometry::{Aabb, Camera, Projection};

/// Vertical field of view of cameras that do not give one, degrees.
pub const DEFAULT_FOV_DEG: f32 = 70.0;
/// Angle of the automatic camera's line of sight below the horizontal, degrees.
pub const AUTO_ELEVATION_DEG: f32 = 25.0;
/// Displayed width / height the automatic framing is computed for.
pub const FRAMING_ASPECT: f32 = 1.5;
/// Fraction of the half-width and half-height of the image the framed boxes may cover, in (0, 1].
pub const FRAMING_FILL: f32 = 0.9;
/// Camera position of a scene with no bodies at all (the doc example's view of the origin).
pub const EMPTY_SCENE_POSITION: Vec3 = Vec3::new(0.0, 4.0, -12.0);
/// Camera target of a scene with no bodies at all.
pub const EMPTY_SCENE_TARGET: Vec3 = Vec3::new(0.0, 1.0, 0.0);
/// Far plane of scene cameras unless the scene needs more, metres.
pub const DEFAULT_FAR: f32 = 500.0;

/// The world boxes the automatic camera frames (see the module docs); empty for a scene without bodies.
pub fn framed_boxes(bodies: &[SceneBody]) -> Vec<Aabb> {
    let bounds = |body: &SceneBody| body.desc.shape.aabb(&body.desc.pose);
    let mut boxes: Vec<Aabb> = bodies
        .iter()
        .filter(|b| !b.desc.is_static)
        .map(bounds)
        .collect();
    let Some(dynamic) = union(&boxes) else {
        return bodies.iter().map(bounds).collect();
    };
    let grow = dynamic.half_extents().max_element().max(1.0);
    let (lo, hi) = (dynamic.min - grow, dynamic.max + grow);
    boxes.extend(
        bodies
            .iter()
            .filter(|b| b.desc.is_static)
            .map(bounds)
            .filter(|b| b.min.x <= hi.x && b.max.x >= lo.x && b.min.z <= hi.z && b.max.z >= lo.z)
            .map(|b| {
                Aabb::new(
                    Vec3::new(b.min.x.max(lo.x), b.min.y, b.min.z.max(lo.z)),
                    Vec3::new(b.max.x.min(hi.x), b.max.y, b.max.z.min(hi.z)),
                )
            }),
    );
    boxes
}

/// The union of `boxes`, `None` when there are none.
pub fn union(boxes: &[Aabb]) -> Option<Aabb> {
    let (first, rest) = boxes.split_first()?;
    Some(rest.iter().fold(*first, |acc, b| acc.union(b)))
}

/// A perspective camera with vertical field of view `fov_y` (radians, in (0, π)) framing `bodies` as
/// the module docs describe.
pub fn auto_camera(bodies: &[SceneBody], fov_y: f32) -> Camera {
    let boxes = framed_boxes(bodies);
    if boxes.is_empty() {
        return scene_camera(EMPTY_SCENE_POSITION, EMPTY_SCENE_TARGET, fov_y, 0.0);
    }
    framing_camera(&boxes, fov_y)
}

/// A perspective camera with vertical field of view `fov_y` (radians, in (0, π)) looking at the centre
/// of the union of `boxes` from in front and above, just far enough away that every corner of every box
/// is inside the fill region. With no boxes, the empty-scene camera.
pub fn framing_camera(boxes: &[Aabb], fov_y: f32) -> Camera {
    let Some(bounds) = union(boxes) else {
        return scene_camera(EMPTY_SCENE_POSITION, EMPTY_SCENE_TARGET, fov_y, 0.0);
    };
    let target = bounds.center();
    let elevation = AUTO_ELEVATION_DEG.to_radians();
    // Unit vector from the target toward the eye: back along −z and up.
    let to_eye = Vec3::new(0.0, elevation.sin(), -elevation.cos());
    let forward = -to_eye;
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    // A corner at view offsets (x, y) and depth offset z (along `forward`, relative to the target) is
    // inside the fill region when |y| ≤ tan_y (d + z) and |x| ≤ tan_x (d + z); solve each for d, and
    // keep every corner at least 0.5 m in front of the eye.
    let tan_y = (0.5 * fov_y).tan() * FRAMING_FILL;
    let tan_x = tan_y * FRAMING_ASPECT;
    let mut distance: f32 = 1.0;
    for b in boxes {
        for corner in corners(b) {
            let rel = corner - target;
            let (x, y, z) = (rel.dot(right), rel.dot(up), rel.dot(forward));
            distance = distance
                .max(y.abs() / tan_y - z)
                .max(x.abs() / tan_x - z)
                .max(0.5 - z);
        }
    }
    let radius = bounds.half_extents().length();
    scene_camera(target + to_eye * distance, target, fov_y, radius)
}

/// The eight corners of a box.
pub fn corners(b: &Aabb) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// A perspective camera whose far plane reaches past a scene of bounding radius `radius_m` around
/// `target` (never nearer than [`DEFAULT_FAR`]).
pub fn scene_camera(position: Vec3, target: Vec3, fov_y: f32, radius_m: f32) -> Camera {
    let mut camera = Camera::perspective(position, target, fov_y);
    let reach = 2.0 * ((target - position).length() + radius_m);
    if reach.is_finite() {
        camera.far = camera.far.max(DEFAULT_FAR).max(reach);
    }
    camera
}

/// The orthographic projection showing, at the target's distance, what a perspective camera with
/// vertical field of view `fov_y` shows there: view height = 2 · |target − position| · tan(fov_y / 2).
pub fn orthographic_matching(camera: &Camera, fov_y: f32) -> Projection {
    let distance = (camera.target - camera.position).length();
    Projection::Orthographic {
        view_height: 2.0 * distance * (0.5 * fov_y).tan(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Pose, Shape};
    use crate::physics::BodyDesc;

    fn body(shape: Shape, position: Vec3, is_static: bool) -> SceneBody {
        let pose = Pose::from_position(position);
        SceneBody {
            frozen: false,
            desc: if is_static {
                BodyDesc::fixed(shape, pose)
            } else {
                BodyDesc::dynamic(shape, pose, 1.0)
            },
            color: crate::color::Rgb::WHITE,
        }
    }

    fn ndc(camera: &Camera, p: Vec3) -> Vec3 {
        let clip = camera.clip_from_world(FRAMING_ASPECT) * p.extend(1.0);
        clip.truncate() / clip.w
    }

    #[test]
    fn a_huge_floor_is_clipped_to_the_region_around_the_dynamic_bodies() {
        let bodies = [
            body(
                Shape::cuboid(Vec3::new(40.0, 0.5, 40.0)),
                Vec3::new(0.0, -0.5, 0.0),
                true,
            ),
            body(Shape::sphere(0.5), Vec3::new(0.0, 2.0, 0.0), false),
        ];
        let framed = framed_boxes(&bodies);
        assert_eq!(framed.len(), 2);
        assert_eq!(framed[1].min, Vec3::new(-1.5, -1.0, -1.5));
        assert_eq!(framed[1].max, Vec3::new(1.5, 0.0, 1.5));
        let far_wall = body(Shape::cuboid(Vec3::ONE), Vec3::new(10.0, 1.0, 0.0), true);
        assert_eq!(
            framed_boxes(&[bodies[0].clone(), bodies[1].clone(), far_wall]),
            framed
        );
    }

    #[test]
    fn the_auto_camera_sees_every_corner_of_the_framed_boxes_from_in_front_and_above() {
        let bodies = [
            body(
                Shape::cuboid(Vec3::new(6.0, 0.5, 2.0)),
                Vec3::new(0.0, -0.5, 0.0),
                true,
            ),
            body(
                Shape::cuboid(Vec3::splat(0.5)),
                Vec3::new(3.0, 4.0, 0.0),
                false,
            ),
            body(Shape::sphere(0.3), Vec3::new(-3.0, 0.3, 1.0), false),
        ];
        let camera = auto_camera(&bodies, DEFAULT_FOV_DEG.to_radians());
        assert!(camera.position.z < camera.target.z && camera.position.y > camera.target.y);
        let mut max_abs = Vec3::ZERO;
        for corner in framed_boxes(&bodies).iter().flat_map(corners) {
            let p = ndc(&camera, corner);
            assert!(p.z > 0.0 && p.z < 1.0, "corner {corner} depth {}", p.z);
            max_abs = max_abs.max(p.abs());
        }
        // Inside the fill region (tolerance 1e-4 NDC) and touching it on at least one side.
        assert!(max_abs.x <= FRAMING_FILL + 1e-4 && max_abs.y <= FRAMING_FILL + 1e-4);
        assert!(max_abs.x.max(max_abs.y) >= FRAMING_FILL - 1e-3, "{max_abs}");
    }

    #[test]
    fn an_empty_scene_gets_the_documented_default_view() {
        let camera = auto_camera(&[], DEFAULT_FOV_DEG.to_radians());
        assert_eq!(camera.position, EMPTY_SCENE_POSITION);
        assert_eq!(camera.target, EMPTY_SCENE_TARGET);
    }

    #[test]
    fn the_matching_orthographic_view_shows_the_perspective_slab_at_the_target() {
        let camera =
            Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 90f32.to_radians());
        let Projection::Orthographic { view_height } =
            orthographic_matching(&camera, 90f32.to_radians())
        else {
            panic!("not orthographic");
        };
        assert!((view_height - 20.0).abs() < 1e-4);
    }
}
