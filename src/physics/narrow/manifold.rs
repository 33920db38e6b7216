//! Contact manifolds: what the narrow phase hands the solver.
//!
//! Sign convention: `separation` is the signed distance between the surfaces along `normal`;
//! positive = apart (a speculative contact), negative = penetrating.

use glam::Vec3;

/// Maximum points in one manifold (a face-on-face box contact needs four).
pub const MAX_MANIFOLD_POINTS: usize = 4;

/// One point of contact between bodies A and B.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactPoint {
    /// Midpoint between the two surfaces, world space.
    pub point: Vec3,
    /// Signed distance along the manifold normal, metres (negative = penetration).
    pub separation: f32,
    /// Identifies the pair of features (faces, edges, vertices) that made this point, stable from step
    /// to step while the same features touch, so the solver can warm-start it.
    pub id: u32,
}

/// The region where two faces touch, as twist friction needs it (see `collide::patch`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Patch {
    /// Area of the touching region, m² (0 for a segment or a point).
    pub area: f32,
    /// Mean distance from the patch's centre to its points, m: for a square of side a, 0.3826·a; a
    /// segment, a quarter of its length; a point, 0.
    pub mean_radius: f32,
}

/// Contact between two shapes: a shared normal and up to four points.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Manifold {
    /// Unit normal pointing from A to B, world space.
    pub normal: Vec3,
    pub points: [ContactPoint; MAX_MANIFOLD_POINTS],
    /// Number of valid entries in `points`, 0..=4.
    pub len: usize,
    /// The touching region the points stand for (zero for a single point).
    pub patch: Patch,
    /// How far B moved relative to A from the start of the step to the moment of impact, world
    /// space, m: zero unless the manifold was taken at its time of impact (see
    /// `collide::at_impact`). The points then ride with A (each is where A's surface point of the
    /// impact is at the start of the step), and B's anchors are `point − approach − x_b`, so both
    /// bodies' lever arms are those of the moment of impact.
    pub approach: Vec3,
}

impl Manifold {
    pub fn points(&self) -> &[ContactPoint] {
        &self.points[..self.len]
    }

    pub fn push(&mut self, point: ContactPoint) {
        if self.len < MAX_MANIFOLD_POINTS {
            self.points[self.len] = point;
            self.len += 1;
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}
