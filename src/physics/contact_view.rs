//! Read-only views of the contacts and islands, for whoever wants to show them (debug overlays, the
//! inspector). Nothing here changes the world or is read by the step.
//!
//! Sign conventions are the world's: normals point from A to B (A has the lower index), separation is
//! negative when penetrating, a normal impulse is ≥ 0 and pushes B along +n.

use glam::Vec3;

use crate::physics::narrow::contact::Contact;
use crate::physics::narrow::manifold::MAX_MANIFOLD_POINTS;
use crate::physics::union_find;
use crate::physics::{BodyId, World};

/// One point of a contact as the solver left it at the end of the last step.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactPointView {
    /// Midpoint between the two surfaces, world, m.
    pub point: Vec3,
    /// Signed distance along the normal, m (negative = penetrating, positive = speculative).
    pub separation: f32,
    /// Normal force the point carried in the last sub-step, N (≥ 0): its accumulated normal
    /// impulse over the sub-step's length. (The solver warm-starts every sub-step with the
    /// impulse of the one before, so the impulse is per sub-step, not per step.)
    pub normal_force: f32,
}

impl ContactPointView {
    /// Whether the surfaces touch here (or the point pushes): not merely a speculative point
    /// waiting for an approaching body.
    pub fn touching(&self) -> bool {
        self.separation <= 0.0 || self.normal_force > 0.0
    }
}

/// One contact manifold between two bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactView {
    /// The body with the lower index.
    pub a: BodyId,
    pub b: BodyId,
    /// Unit normal from A to B, world.
    pub normal: Vec3,
    points: [ContactPointView; MAX_MANIFOLD_POINTS],
    len: usize,
    /// Friction force on B in the last sub-step, world, N, orthogonal to the normal (acts at the
    /// centroid of the points; A feels the opposite).
    pub friction_force: Vec3,
}

impl ContactView {
    /// The manifold's points (1 to 4).
    pub fn points(&self) -> &[ContactPointView] {
        &self.points[..self.len]
    }

    /// The centroid of the points, where friction acts, world, m.
    pub fn centroid(&self) -> Vec3 {
        let sum: Vec3 = self.points().iter().map(|p| p.point).sum();
        sum / self.len.max(1) as f32
    }

    /// Deepest penetration among the points, m (≥ 0; 0 when none penetrates).
    pub fn penetration(&self) -> f32 {
        self.points()
            .iter()
            .map(|p| -p.separation)
            .fold(0.0, f32::max)
    }

    /// Whether any point touches (see [`ContactPointView::touching`]).
    pub fn touching(&self) -> bool {
        self.points().iter().any(ContactPointView::touching)
    }

    /// Whether `id` is one of the two bodies.
    pub fn involves(&self, id: BodyId) -> bool {
        self.a == id || self.b == id
    }

    fn of(contact: &Contact, inv_h: f32) -> Self {
        let mut points = [ContactPointView::default(); MAX_MANIFOLD_POINTS];
        let len = contact.manifold.len.min(MAX_MANIFOLD_POINTS);
        for (i, (view, p)) in points.iter_mut().zip(contact.manifold.points()).enumerate() {
            *view = ContactPointView {
                point: p.point,
                separation: p.separation,
                normal_force: contact.impulses.normal[i] * inv_h,
            };
        }
        Self {
            a: BodyId(contact.a),
            b: BodyId(contact.b),
            normal: contact.manifold.normal,
            points,
            len,
            friction_force: contact.impulses.tangent * inv_h,
        }
    }
}

/// Marks a body in no island: static (scenery or frozen).
pub const NO_ISLAND: u32 = u32::MAX;

impl World {
    /// Every persistent contact (sleeping pairs and speculative ones included), sorted by `(a, b)`.
    pub fn contacts(&self) -> impl ExactSizeIterator<Item = ContactView> + '_ {
        let h = self.settings.dt / self.settings.substep_count() as f32;
        let inv_h = if h > 0.0 { 1.0 / h } else { 0.0 };
        self.contacts.iter().map(move |c| ContactView::of(c, inv_h))
    }

    /// Labels every body with its island: bodies linked through contacts between dynamic bodies
    /// (touching or speculative, as the solver links them) or joints share the label, which is the smallest
    /// body index among them; static bodies get [`NO_ISLAND`] (they join nothing, as in the solver).
    /// `labels` is cleared and refilled, one entry per body.
    pub fn island_labels(&self, labels: &mut Vec<u32>) {
        // Union–find by smallest index (`union_find`).
        union_find::reset(labels, self.bodies.len());
        // A joint links its bodies as a contact does (they sleep and wake together).
        let joined = self
            .joints
            .iter()
            .filter_map(|j| j.desc.a.map(|a| (a.0, j.desc.b.0)));
        for (a, b) in self.contacts.iter().map(|c| (c.a, c.b)).chain(joined) {
            if self.bodies[a as usize].is_static || self.bodies[b as usize].is_static {
                continue;
            }
            union_find::union(labels, a, b);
        }
        for i in 0..labels.len() {
            labels[i] = if self.bodies[i].is_static {
                NO_ISLAND
            } else {
                union_find::find(labels, i as u32)
            };
        }
    }

    /// Number of islands: groups of dynamic bodies linked by contacts or joints (see
    /// [`World::island_labels`]).
    pub fn island_count(&self) -> usize {
        let mut labels = Vec::new();
        self.island_labels(&mut labels);
        labels
            .iter()
            .enumerate()
            .filter(|&(i, &l)| l == i as u32)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Pose, Shape};
    use crate::physics::{BodyDesc, Settings};

    fn floor_and_boxes(xs: &[(f32, f32)]) -> World {
        let mut world = World::new(Settings::default());
        world.add_body(BodyDesc::fixed(
            Shape::cuboid(Vec3::new(10.0, 0.5, 10.0)),
            Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
        ));
        for &(x, y) in xs {
            world.add_body(BodyDesc::dynamic(
                Shape::cuboid(Vec3::splat(0.5)),
                Pose::from_position(Vec3::new(x, y, 0.0)),
                1.0,
            ));
        }
        world
    }

    #[test]
    fn a_resting_box_carries_its_weight_on_four_points() {
        let mut world = floor_and_boxes(&[(0.0, 0.5)]);
        for _ in 0..60 {
            world.step();
        }
        let contacts: Vec<ContactView> = world.contacts().collect();
        assert_eq!(contacts.len(), 1);
        let c = &contacts[0];
        assert_eq!((c.a, c.b), (BodyId(0), BodyId(1)));
        assert!((c.normal - Vec3::Y).length() < 1e-4, "{}", c.normal);
        assert_eq!(c.points().len(), 4);
        assert!(
            c.points()
                .iter()
                .all(|p| p.touching() && p.point.y.abs() < 0.01)
        );
        // The points hold the box's weight, 1 kg × 9.81 m/s².
        let total: f32 = c.points().iter().map(|p| p.normal_force).sum();
        assert!((total - 9.81).abs() < 0.05, "{total}");
        assert!(c.friction_force.length() < 1e-3);
        assert!((c.centroid() - Vec3::ZERO).length() < 0.01);
    }

    #[test]
    fn islands_join_touching_bodies_and_leave_out_static_ones() {
        // A stack of two, and a lone box far away: two islands over one floor.
        let world = {
            let mut w = floor_and_boxes(&[(0.0, 0.5), (0.0, 1.5), (5.0, 0.5)]);
            for _ in 0..10 {
                w.step();
            }
            w
        };
        let mut labels = Vec::new();
        world.island_labels(&mut labels);
        assert_eq!(labels, vec![NO_ISLAND, 1, 1, 3]);
        assert_eq!(world.island_count(), 2);
    }

    #[test]
    fn a_joint_joins_its_bodies_in_one_island() {
        use crate::physics::{JointDesc, JointKind};
        let mut world = floor_and_boxes(&[(0.0, 0.5), (5.0, 0.5)]);
        let (a, b) = (BodyId(1), BodyId(2));
        let (pa, pb) = (*world.body(a).pose(), *world.body(b).pose());
        let mid = Vec3::new(2.5, 0.5, 0.0);
        let rod = JointKind::Distance {
            length: 2.5,
            min: 2.5,
            max: 2.5,
            spring: None,
        };
        world
            .add_joint(JointDesc::at(
                rod,
                Some((a, pa)),
                (b, pb),
                mid,
                mid,
                Vec3::Y,
                false,
            ))
            .unwrap();
        assert_eq!(world.island_count(), 1);
    }
}
