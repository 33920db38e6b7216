//! Whole-world figures for display and checks: energy and momentum of the dynamic bodies.
//!
//! Static bodies (scenery and frozen ones) do not move, so they carry neither; potential energy is
//! measured from the origin along gravity (`−m g·p`), so only its changes mean anything.

use glam::Vec3;

use crate::physics::World;

impl World {
    /// Kinetic energy of the dynamic bodies, ½mv² + ½ωᵀIω summed, J.
    pub fn kinetic_energy(&self) -> f32 {
        self.dynamic_bodies().map(|b| b.kinetic_energy()).sum()
    }

    /// Gravitational potential energy of the dynamic bodies, −Σ m g·p, J (0 at the origin).
    pub fn potential_energy(&self) -> f32 {
        let g = self.settings.gravity;
        self.dynamic_bodies()
            .map(|b| -b.mass * g.dot(b.pose.position))
            .sum()
    }

    /// Linear momentum of the dynamic bodies, Σ m v, world, kg·m/s.
    pub fn linear_momentum(&self) -> Vec3 {
        self.dynamic_bodies()
            .map(|b| b.mass * b.linear_velocity)
            .sum()
    }

    fn dynamic_bodies(&self) -> impl Iterator<Item = &crate::physics::Body> {
        self.bodies.iter().filter(|b| !b.is_static)
    }
}

#[cfg(test)]
mod tests {
    use crate::geometry::{Pose, Shape};
    use crate::physics::{BodyDesc, Settings, World};
    use glam::Vec3;

    #[test]
    fn a_falling_ball_trades_potential_for_kinetic_energy() {
        let mut world = World::new(Settings::default());
        world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.5),
            Pose::from_position(Vec3::new(0.0, 10.0, 0.0)),
            2.0,
        ));
        let start = world.kinetic_energy() + world.potential_energy();
        assert!((world.potential_energy() - 2.0 * 9.81 * 10.0).abs() < 1e-3);
        for _ in 0..30 {
            world.step();
        }
        let end = world.kinetic_energy() + world.potential_energy();
        assert!(world.kinetic_energy() > 10.0);
        // Symplectic Euler loses a little per step: under 1 % over half a second.
        assert!((end - start).abs() < 0.01 * start, "{start} → {end}");
        let v = world.body(crate::physics::BodyId(0)).linear_velocity();
        assert_eq!(world.linear_momentum(), 2.0 * v);
    }
}
