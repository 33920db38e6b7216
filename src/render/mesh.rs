//! Unit meshes the renderer places by pose and size: a box and UV spheres.
//!
//! Meshes are in a unit body frame: the box spans [-1, 1]³ (scaled by the half-extents), the sphere has
//! radius 1 (scaled by the radius). Triangles wind counter-clockwise seen from outside (the front side),
//! which after projection is counter-clockwise in NDC (y up).

use glam::{Vec2, Vec3};

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
    fn sphere_vertices_lie_on_the_unit_sphere_and_face_outward() {
        let mesh = Mesh::uv_sphere(12, 8);
        assert_eq!(mesh.triangles.len(), 2 * 12 * 8 - 2 * 12);
        for p in &mesh.positions {
            assert!((p.length() - 1.0).abs() < 1e-5);
        }
        assert_closed_and_outward(&mesh);
    }
}
