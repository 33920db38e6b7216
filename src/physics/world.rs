//! The world: bodies plus the step that moves them.
//!
//! SCAFFOLD: integrates free bodies only, no contacts. The dynamics work replaces this file's internals
//! behind the same public API.

use glam::Vec3;

use super::{Body, BodyDesc, BodyId, Settings};
use crate::geometry::{Ray, RayHit};

pub struct World {
    settings: Settings,
    bodies: Vec<Body>,
}

impl World {
    pub fn new(settings: Settings) -> Self {
        Self {
            settings,
            bodies: Vec::new(),
        }
    }

    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    pub fn settings_mut(&mut self) -> &mut Settings {
        &mut self.settings
    }

    /// Adds a body; ids are handed out in order, starting at 0.
    pub fn add_body(&mut self, desc: BodyDesc) -> BodyId {
        self.bodies.push(Body::from_desc(&desc));
        BodyId(self.bodies.len() as u32 - 1)
    }

    pub fn len(&self) -> usize {
        self.bodies.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
    }

    pub fn body(&self, id: BodyId) -> &Body {
        &self.bodies[id.index()]
    }

    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// Dynamic bodies that are not asleep.
    pub fn awake_count(&self) -> usize {
        self.bodies
            .iter()
            .filter(|b| !b.is_static && !b.sleeping)
            .count()
    }

    /// Applies `force` (N, world) at `point` (world) during the next step only; wakes the body.
    pub fn apply_force_at_point(&mut self, id: BodyId, force: Vec3, point: Vec3) {
        let body = &mut self.bodies[id.index()];
        if body.is_static || !force.is_finite() || !point.is_finite() {
            return;
        }
        body.force += force;
        body.torque += (point - body.pose.position).cross(force);
        body.sleeping = false;
    }

    /// Freezes (`true`) or unfreezes a body. A frozen body keeps its pose with zero velocity and no
    /// pending force; an unfrozen one wakes and falls.
    pub fn set_static(&mut self, id: BodyId, is_static: bool) {
        let body = &mut self.bodies[id.index()];
        body.is_static = is_static;
        body.linear_velocity = Vec3::ZERO;
        body.angular_velocity = Vec3::ZERO;
        body.force = Vec3::ZERO;
        body.torque = Vec3::ZERO;
        body.sleeping = false;
    }

    /// The nearest body whose surface the ray enters within `[t_min, t_max]`.
    pub fn cast_ray(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(BodyId, RayHit)> {
        let mut best: Option<(BodyId, RayHit)> = None;
        for (i, body) in self.bodies.iter().enumerate() {
            let limit = best.map_or(t_max, |(_, hit)| hit.t);
            if let Some(hit) = ray.cast(&body.shape, &body.pose, t_min, limit) {
                best = Some((BodyId(i as u32), hit));
            }
        }
        best
    }

    /// Advances the world by one fixed step of `settings.dt`.
    pub fn step(&mut self) {
        let dt = self.settings.dt;
        for body in &mut self.bodies {
            if body.is_static {
                continue;
            }
            let accel = self.settings.gravity + body.force / body.mass;
            body.linear_velocity += accel * dt;
            body.pose.position += body.linear_velocity * dt;
            body.force = Vec3::ZERO;
            body.torque = Vec3::ZERO;
        }
    }
}
