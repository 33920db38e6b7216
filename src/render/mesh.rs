//! Unit meshes the renderer places by pose and size: a box and UV spheres.
//!
//! Meshes are in a unit body frame: the box spans [-1, 1]³ (scaled by the half-extents), the sphere has
//! radius 1 (scaled by the radius). Triangles wind counter-clockwise seen from outside (the front side),
//! which after projection is counter-clockwise in NDC (y up).
//!
//! Balls are drawn exactly, not with their mesh (see `render::sphere`); the sphere meshes give the
//! wires of wireframe mode and the balls' shapes in the shadow map.

use glam::{Vec2, Vec3};

use crate::geometry::Shape;

/// Sphere meshes by level of detail: (slices, stacks, largest projected radius in pixels it is used
/// for). The last one is used for anything larger.
const SPHERE_LODS: [(u32, u32, f32); 4] = [
    (6, 4, 2.5),
    (10, 6, 6.0),
    (20, 12, 20.0),
    (36, 20, f32::INFINITY),
];

/// How much to enlarge a UV sphere mesh of `slices × stacks` so its silhouette straddles the true
/// sphere instead of lying inside it: a polygon of half-angle θ per segment with circumradius
/// `R = 2r / (1 + cos θ)` deviates at most `±(R − r)` from the circle of radius r, half the error
/// of the inscribed one. θ is the larger of the longitude (π / slices) and latitude
/// (π / (2 stacks)) half-angles.
fn sphere_fit_scale(slices: u32, stacks: u32) -> f32 {
    let theta =
        (std::f32::consts::PI / slices as f32).max(std::f32::consts::PI / (2.0 * stacks as f32));
    2.0 / (1.0 + theta.cos())
}

/// Index into [`SPHERE_LODS`] of the level for a sphere of projected radius `pixel_radius`.
fn sphere_lod(pixel_radius: f32) -> usize {
    SPHERE_LODS
        .iter()
        .position(|&(_, _, limit)| pixel_radius < limit)
        .unwrap_or(SPHERE_LODS.len() - 1)
}

/// (slices, stacks) of the UV sphere mesh used at projected radius `pixel_radius`: the facets flat
/// shading gives a ball, and the wires of wireframe mode.
pub fn sphere_facets(pixel_radius: f32) -> (u32, u32) {
    let (slices, stacks, _) = SPHERE_LODS[sphere_lod(pixel_radius)];
    (slices, stacks)
}

/// The unit meshes every shape is drawn with, built once: the box and the sphere levels of detail.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSet {
    cuboid: Mesh,
    spheres: [Mesh; SPHERE_LODS.len()],
    /// [`sphere_fit_scale`] of each sphere mesh.
    sphere_scales: [f32; SPHERE_LODS.len()],
}

impl Default for MeshSet {
    fn default() -> Self {
        Self::new()
    }
}

impl MeshSet {
    /// Builds every mesh (a few hundred vertices in all).
    pub fn new() -> Self {
        Self {
            cuboid: Mesh::unit_box(),
            spheres: SPHERE_LODS.map(|(slices, stacks, _)| Mesh::uv_sphere(slices, stacks)),
            sphere_scales: SPHERE_LODS.map(|(slices, stacks, _)| sphere_fit_scale(slices, stacks)),
        }
    }

    /// The unit mesh for `shape` and the per-axis scale that sizes it; spheres pick their level of
    /// detail from their projected radius in pixels.
    pub fn for_shape(&self, shape: &Shape, pixel_radius: f32) -> (&Mesh, Vec3) {
        match *shape {
            Shape::Cuboid { half_extents } => (&self.cuboid, half_extents),
            Shape::Sphere { radius } => {
                let lod = sphere_lod(pixel_radius);
                (
                    &self.spheres[lod],
                    Vec3::splat(radius * self.sphere_scales[lod]),
                )
            }
        }
    }
}

/// An indexed triangle mesh with per-vertex normals and texture coordinates, plus the edges a
/// wireframe draws (quad outlines, not triangle diagonals).
#[derive(Clone, Debug, PartialEq)]
pub struct Mesh {
    /// Unit-frame positions.
    pub positions: Vec<Vec3>,
    /// Unit-length outward normals, one per position.
    pub normals: Vec<Vec3>,
    /// Texture coordinates in [0, 1]², one per position.
    pub uvs: Vec<Vec2>,
    /// Counter-clockwise (outward) triangles, indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
    /// Visible edges, each listed once, indices into `positions`.
    pub edges: Vec<[u32; 2]>,
}

impl Mesh {
    /// The box [-1, 1]³: 6 faces × 4 vertices (so each face has its own normal and UVs), 12 triangles,
    /// 12 edges.
    pub fn unit_box() -> Self {
        let mut mesh = Mesh::empty();
        // For each face: outward normal n and tangents u, v with u × v = n, so the corner order
        // (-u-v, +u-v, +u+v, -u+v) is counter-clockwise seen from outside.
        let faces = [
            (Vec3::X, Vec3::NEG_Z, Vec3::Y),
            (Vec3::NEG_X, Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::X, Vec3::NEG_Z),
            (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            (Vec3::Z, Vec3::X, Vec3::Y),
            (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
        ];
        for (n, u, v) in faces {
            debug_assert!((u.cross(v) - n).length() < 1e-6);
            let base = mesh.positions.len() as u32;
            for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(n + su * u + sv * v);
                mesh.normals.push(n);
                mesh.uvs.push(Vec2::new(0.5 * (su + 1.0), 0.5 * (sv + 1.0)));
            }
            mesh.add_quad([base, base + 1, base + 2, base + 3]);
        }
        mesh.dedup_edges();
        mesh
    }

    /// A UV sphere of radius 1 with `slices` segments around the y axis and `stacks` from pole to pole
    /// (each at least 3 and 2). Vertices on a seam or pole are repeated so UVs stay continuous; normals
    /// are the positions. u runs with longitude, v from the north pole (0) to the south pole (1).
    pub fn uv_sphere(slices: u32, stacks: u32) -> Self {
        let slices = slices.max(3);
        let stacks = stacks.max(2);
        let mut mesh = Mesh::empty();
        for i in 0..=stacks {
            let v = i as f32 / stacks as f32;
            let (sin_phi, cos_phi) = (v * std::f32::consts::PI).sin_cos();
            for j in 0..=slices {
                let u = j as f32 / slices as f32;
                let (sin_theta, cos_theta) = (u * std::f32::consts::TAU).sin_cos();
                let p = Vec3::new(sin_phi * cos_theta, cos_phi, -sin_phi * sin_theta);
                mesh.positions.push(p);
                mesh.normals.push(p);
                mesh.uvs.push(Vec2::new(u, v));
            }
        }
        let row = slices + 1;
        for i in 0..stacks {
            for j in 0..slices {
                let a = i * row + j; // north-west
                let b = (i + 1) * row + j; // south-west
                let c = (i + 1) * row + j + 1; // south-east
                let d = i * row + j + 1; // north-east
                if i == 0 {
                    mesh.push_outward([a, b, c]);
                    mesh.edges.push([b, c]);
                    mesh.edges.push([a, b]);
                } else if i + 1 == stacks {
                    mesh.push_outward([a, b, d]);
                    mesh.edges.push([a, b]);
                } else {
                    mesh.push_outward([a, b, c]);
                    mesh.push_outward([a, c, d]);
                    mesh.edges.push([a, b]);
                    mesh.edges.push([b, c]);
                }
            }
        }
        mesh
    }

    fn empty() -> Self {
        Mesh {
            positions: Vec::new(),
            normals: Vec::new(),
            uvs: Vec::new(),
            triangles: Vec::new(),
            edges: Vec::new(),
        }
    }

    fn add_quad(&mut self, q: [u32; 4]) {
        self.push_outward([q[0], q[1], q[2]]);
        self.push_outward([q[0], q[2], q[3]]);
        for k in 0..4 {
            self.edges.push([q[k], q[(k + 1) % 4]]);
        }
    }

    /// Adds a triangle, flipping it if needed so its geometric normal points away from the origin
    /// (every mesh here is convex and centred on the origin).
    fn push_outward(&mut self, t: [u32; 3]) {
        let [a, b, c] = t.map(|i| self.positions[i as usize]);
        let outward = (b - a).cross(c - a).dot(a + b + c) >= 0.0;
        self.triangles
            .push(if outward { t } else { [t[0], t[2], t[1]] });
    }

    /// Keeps one of each pair of edges with the same end positions (a box edge borders two faces).
    fn dedup_edges(&mut self) {
        let positions = &self.positions;
        let key = |e: &[u32; 2]| {
            let (p, q) = (positions[e[0] as usize], positions[e[1] as usize]);
            let (lo, hi) = if p.to_array() <= q.to_array() {
                (p, q)
            } else {
                (q, p)
            };
            [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z].map(|v| v.round() as i32)
        };
        let mut kept: Vec<[u32; 2]> = Vec::new();
        for e in &self.edges {
            if !kept.iter().any(|k| key(k) == key(e)) {
                kept.push(*e);
            }
        }
        self.edges = kept;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_closed_and_outward(mesh: &Mesh) {
        for t in &mesh.triangles {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.length() > 1e-6, "degenerate triangle {t:?}");
            assert!(n.dot(a + b + c) > 0.0, "inward triangle {t:?}");
            let avg = (mesh.normals[t[0] as usize]
                + mesh.normals[t[1] as usize]
                + mesh.normals[t[2] as usize])
                .normalize();
            assert!(
                n.normalize().dot(avg) > 0.5,
                "normals disagree with winding"
            );
        }
    }

    #[test]
    fn the_box_has_24_vertices_12_triangles_and_12_edges() {
        let mesh = Mesh::unit_box();
        assert_eq!(mesh.positions.len(), 24);
        assert_eq!(mesh.triangles.len(), 12);
        assert_eq!(mesh.edges.len(), 12);
        assert_closed_and_outward(&mesh);
        for e in &mesh.edges {
            let d = mesh.positions[e[0] as usize] - mesh.positions[e[1] as usize];
            assert!((d.length() - 2.0).abs() < 1e-6, "edge is not a box edge");
        }
    }

    #[test]
    fn larger_spheres_get_finer_meshes_fitted_around_the_true_surface() {
        let set = MeshSet::new();
        let sphere = Shape::sphere(2.0);
        let (coarse, coarse_scale) = set.for_shape(&sphere, 1.0);
        let (fine, fine_scale) = set.for_shape(&sphere, 100.0);
        assert!(fine.triangles.len() > coarse.triangles.len());
        assert!(coarse_scale.x > fine_scale.x && fine_scale.x > 2.0);
        let (_, box_scale) = set.for_shape(&Shape::cuboid(Vec3::new(1.0, 2.0, 3.0)), 1.0);
        assert_eq!(box_scale, Vec3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn sphere_vertices_lie_on_the_unit_sphere_and_face_outward() {
        let mesh = Mesh::uv_sphere(12, 8);
        assert_eq!(mesh.triangles.len(), 2 * 12 * 8 - 2 * 12);
        for p in &mesh.positions {
            assert!((p.length() - 1.0).abs() < 1e-5);
        }
        assert_closed_and_outward(&mesh);
    }
}
