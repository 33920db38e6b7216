//! Vertex stage: a unit mesh placed by a drawable's pose and size, into clip space.
//!
//! Positions go through `clip_from_world · world_from_unit` (scale by half-extents or radius, rotate,
//! translate). Normals go through the rotation only: no translation, and no scale (box faces stay
//! axis-aligned in body space and spheres scale uniformly, so the rotated unit normal is exact).

use glam::{Mat3, Mat4, Vec3};

use super::clip::ClipVertex;
use super::view::View;
use super::{Drawable, Mesh};

/// Vertex stage: unit mesh → clip space, with world normals (rotation only), world and body
/// positions and UVs as attributes, and each vertex's outcode.
pub(crate) fn vertex_stage(
    mesh: &Mesh,
    d: &Drawable,
    scale: Vec3,
    view: &View,
    verts: &mut Vec<ClipVertex>,
    codes: &mut Vec<u8>,
) {
    let rotation = d.pose.rotation.normalize();
    let world_from_unit = Mat4::from_scale_rotation_translation(scale, rotation, d.pose.position);
    let clip_from_unit = view.clip_from_world * world_from_unit;
    let world_from_unit_normal = Mat3::from_quat(rotation);
    verts.clear();
    codes.clear();
    for ((&p, &n), &uv) in mesh
        .positions
        .iter()
        .zip(mesh.normals.iter())
        .zip(mesh.uvs.iter())
    {
        let clip = clip_from_unit * p.extend(1.0);
        let n_world = world_from_unit_normal * n;
        let p_world = world_from_unit.transform_point3(p);
        let p_local = p * scale;
        verts.push(ClipVertex {
            clip,
            var: [
                n_world.x, n_world.y, n_world.z, p_world.x, p_world.y, p_world.z, p_local.x,
                p_local.y, p_local.z, uv.x, uv.y,
            ],
        });
        codes.push(view.volume.outcode(clip));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::Rgb;
    use crate::geometry::{Camera, Pose, Shape, Viewport};
    use glam::Quat;

    #[test]
    fn normals_are_rotated_but_never_translated_or_scaled() {
        let rotation = Quat::from_rotation_z(0.7) * Quat::from_rotation_x(-0.4);
        let d = Drawable::new(
            Shape::cuboid(Vec3::new(3.0, 0.2, 1.0)),
            Pose::new(Vec3::new(40.0, -7.0, 12.0), rotation),
            Rgb::WHITE,
            1,
        );
        let camera = Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0);
        let view = View::new(&camera, Viewport::new(10, 10, 1.0));
        let mesh = Mesh::unit_box();
        let (mut verts, mut codes) = (Vec::new(), Vec::new());
        vertex_stage(
            &mesh,
            &d,
            Vec3::new(3.0, 0.2, 1.0),
            &view,
            &mut verts,
            &mut codes,
        );
        assert_eq!(verts.len(), 24);
        for (v, n) in verts.iter().zip(&mesh.normals) {
            let n_world = Vec3::new(v.var[0], v.var[1], v.var[2]);
            assert!((n_world - rotation * *n).length() < 1e-5);
            let p_world = Vec3::new(v.var[3], v.var[4], v.var[5]);
            let p_local = Vec3::new(v.var[6], v.var[7], v.var[8]);
            assert!((d.pose.transform_point(p_local) - p_world).length() < 1e-4);
        }
    }
}
