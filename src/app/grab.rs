//! Grab and drag: in grab mode (`h`), the left button holds the clicked point of a body on a spring
//! to the pointer, the way every windowed physics sandbox lets you drag things.
//!
//! The pointer moves on the plane through the grabbed point that faces the camera (perpendicular to
//! its view direction, at the depth the point had when grabbed), in either projection; the wheel or
//! `+`/`-` move that plane nearer or farther. Each step the spring — Box2D's mouse joint, a soft
//! constraint of [`GRAB_HERTZ`] and [`GRAB_DAMPING_RATIO`] whose force is capped at the body's mass
//! × [`GRAB_ACCEL_MAX`] — pulls the grabbed point toward the pointer's point, and a little damping
//! calms the spin it cannot reach (a held body swings about the held point). Letting go leaves the
//! body its velocity: a quick drag throws. The force is capped, so the contact solver stays in charge
//! and a body dragged into the floor stops at it.

use glam::{Vec2, Vec3};
use ratatui::layout::Rect;

use super::App;
use super::hand::{HandAction, HandReport, STRONG_FACTOR};
use super::picking::{self, Pick};
use crate::color::Rgb;
use crate::geometry::{Camera, Ray, Viewport};
use crate::physics::{BodyId, PointSpring, World};
use crate::render::tether::draw_tether;

/// Natural frequency of the grab spring, Hz. Box2D's samples use 5 Hz with the spring inside the
/// solver; applied once per 60 Hz step, a spring settles at g·(1 + hω(2ζ + hω))/ω² below the
/// pointer under gravity: 2.0 cm at 5 Hz, 1.1 cm at 8 Hz. 8 Hz still settles in about a tenth of a
/// second, without a visible wobble.
pub const GRAB_HERTZ: f32 = 8.0;
/// Damping ratio of the grab spring (Box2D's samples use 0.7: a little overshoot, quick to settle).
pub const GRAB_DAMPING_RATIO: f32 = 0.7;
/// The most the spring accelerates the body it holds, m/s²: its force cap is this times the body's
/// mass, so a heavy body follows the pointer like a light one. 3 g lifts anything against gravity
/// with room to swing it; with the strong hand's 4× it is the old ramped push's top force, which a
/// 1 kg box pinned under 1000 kg holds (4 g strong, 160 N, shifted it 2.6 cm).
pub const GRAB_ACCEL_MAX: f32 = 30.0;
/// Fastest the spring drives a held body toward the pointer, m/s: faster than a hand flicks across the
/// default scene, and what keeps a body flung past the pointer from orbiting it (see
/// [`World::spring_force`]).
pub const GRAB_MAX_SPEED: f32 = 15.0;
/// Time constant of the spin damping on a held body, s: the hand's grip. A body held by a point off
/// its centre swings about it, and a box towed across the floor by its front face turns to trail and
/// then swings past when the pointer stops; the spring cannot damp either. Box2D's joint damps spin
/// very lightly (0.5 Hz, ζ 0.1); here 0.5 s left a box flicked 2 m in a quarter second swinging 19 cm
/// about the pointer half a second later, and throws 15–35 % off (the centre swinging about the held
/// point as it is let go). 0.1 s, with the pointer smoothed, keeps both within 3 cm and 21 %, and a
/// box dragged into a wall still tips over it.
pub const GRAB_SPIN_TIME_S: f32 = 0.1;
/// Time constant the spring's target follows the pointer's point with, s. A terminal reports the
/// pointer a cell at a time (about 10 cm across the default scene), so a steady drag arrives as jumps
/// that kicked the held body, and a throw went off at whatever the last kick gave it; three 60 Hz steps
/// of smoothing spread each jump and cost 5 cm of lag at 1 m/s.
pub const POINTER_SMOOTHING_S: f32 = 0.05;
/// How far one wheel notch or `+`/`-` moves a held body nearer or farther: this fraction of its
/// distance from the camera (the zoom's step).
pub const GRAB_DEPTH_STEP: f32 = 0.1;
/// The tether's colours: the line to the pointer and the marker on the held point.
pub const TETHER_LINE: Rgb = Rgb::new(0xf0, 0xf0, 0xf0);
pub const TETHER_MARKER: Rgb = Rgb::new(0xff, 0x50, 0x40);

/// A body held by one of its points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grab {
    pub body: BodyId,
    /// The held point in the body's frame, m.
    pub anchor_local: Vec3,
    /// Distance of the pointer's plane from the camera, along its view direction, m; > 0.
    pub depth: f32,
    /// The pointer's cell (absolute terminal coordinates); may lie outside the view.
    pub cell: (u16, u16),
    /// Shift was held when the button went down.
    pub strong: bool,
    /// Where the spring pulls: the pointer's point, smoothed (see [`POINTER_SMOOTHING_S`]); `None`
    /// until the first step.
    pub target: Option<Vec3>,
}

impl Grab {
    /// Holds the point `pick` hit, with the pointer at `cell`.
    pub fn new(
        world: &World,
        camera: &Camera,
        pick: &Pick,
        cell: (u16, u16),
        strong: bool,
    ) -> Self {
        let pose = world.body(pick.body).pose();
        let depth = (pick.hit.point - camera.position).dot(camera.basis().forward);
        Self {
            body: pick.body,
            anchor_local: pose.inverse_transform_point(pick.hit.point),
            depth: depth.max(camera.near),
            cell,
            strong,
            target: None,
        }
    }

    /// The held point in the world now, m.
    pub fn anchor(&self, world: &World) -> Vec3 {
        world
            .body(self.body)
            .pose()
            .transform_point(self.anchor_local)
    }

    /// The pointer's point: where the ray through its cell meets the grab's plane.
    pub fn pointer_point(
        &self,
        camera: &Camera,
        viewport: &Viewport,
        viewport_cells: Rect,
    ) -> Vec3 {
        let ray = pointer_ray(camera, viewport, viewport_cells, self.cell);
        point_at_depth(camera, &ray, self.depth)
    }

    /// The spring for a body of `mass` (kg).
    pub fn spring(mass: f32, strong: bool) -> PointSpring {
        let strength = if strong { STRONG_FACTOR } else { 1.0 };
        PointSpring {
            hertz: GRAB_HERTZ,
            damping_ratio: GRAB_DAMPING_RATIO,
            max_force: mass * GRAB_ACCEL_MAX * strength,
            max_speed: GRAB_MAX_SPEED,
        }
    }

    /// Applies this step's spring force at the held point, and the spin damping (as a couple: the
    /// world takes forces at points).
    pub fn apply(
        &mut self,
        world: &mut World,
        camera: &Camera,
        viewport: &Viewport,
        viewport_cells: Rect,
        strong: bool,
    ) -> HandReport {
        let anchor = self.anchor(world);
        let pointer = self.pointer_point(camera, viewport, viewport_cells);
        let follow = 1.0 - (-world.settings().dt / POINTER_SMOOTHING_S).exp();
        let target = match self.target {
            Some(target) => target + (pointer - target) * follow,
            None => pointer,
        };
        self.target = Some(target);
        let spring = Self::spring(world.body(self.body).mass(), strong || self.strong);
        let force = world.spring_force(self.body, anchor, target, &spring);
        if force != Vec3::ZERO {
            world.apply_force_at_point(self.body, force, anchor);
        }
        let torque = world.spin_damping_torque(self.body, GRAB_SPIN_TIME_S);
        apply_torque(world, self.body, torque);
        HandReport {
            action: HandAction::Grab,
            body: self.body,
            force_n: force.length(),
            measure: (anchor - pointer).length(),
            out_of_reach: false,
        }
    }

    /// Moves the pointer's plane nearer the camera (or farther) by [`GRAB_DEPTH_STEP`].
    pub fn move_depth(&mut self, camera: &Camera, nearer: bool) {
        let factor = if nearer {
            1.0 - GRAB_DEPTH_STEP
        } else {
            1.0 / (1.0 - GRAB_DEPTH_STEP)
        };
        self.depth = (self.depth * factor).clamp(2.0 * camera.near, 0.5 * camera.far);
    }
}

/// A torque (N·m, world) as a couple of forces: `F = τ × u` at the centre of mass plus a unit arm u
/// perpendicular to τ, and −F at the centre (u × (τ × u) = τ when u ⟂ τ, |u| = 1).
fn apply_torque(world: &mut World, body: BodyId, torque: Vec3) {
    let Some(axis) = torque.try_normalize() else {
        return;
    };
    let arm = axis.any_orthonormal_vector();
    let force = torque.cross(arm);
    let centre = world.body(body).pose().position;
    world.apply_force_at_point(body, force, centre + arm);
    world.apply_force_at_point(body, -force, centre);
}

/// The world ray through the centre of terminal cell `cell` (absolute), through the camera and
/// viewport the view is drawn with. A cell outside the view gives the ray its image would have if
/// the view went on: a drag may leave the view and come back.
pub fn pointer_ray(
    camera: &Camera,
    viewport: &Viewport,
    viewport_cells: Rect,
    cell: (u16, u16),
) -> Ray {
    let col = f32::from(cell.0) - f32::from(viewport_cells.x);
    let row = f32::from(cell.1) - f32::from(viewport_cells.y);
    let pixel = Vec2::new(col + 0.5, 2.0 * row + 1.0);
    picking::ray_through_pixel(camera, viewport, pixel)
}

/// Where `ray` (from the camera) meets the plane facing the camera at `depth` along its view
/// direction. Perspective rays start at the eye and orthographic ones on the camera plane; either way
/// the point is `depth` ahead of the camera.
pub fn point_at_depth(camera: &Camera, ray: &Ray, depth: f32) -> Vec3 {
    let forward = camera.basis().forward;
    let along = ray.dir.dot(forward).max(1e-6);
    let t = (depth - (ray.origin - camera.position).dot(forward)) / along;
    ray.at(t)
}

impl App {
    /// `h`: the left button pushes, or grabs.
    pub(crate) fn toggle_grab_mode(&mut self) {
        self.ui.grab_mode = !self.ui.grab_mode;
        // Whatever the hand held, it lets go.
        let _ = self.hand.release();
        self.say(if self.ui.grab_mode {
            "left button grabs: drag a body, wheel or + - moves it nearer/farther (h: push)"
        } else {
            "left button pushes (h: grab)"
        });
    }

    /// The left button went down on a dynamic body in grab mode.
    pub(crate) fn start_grab(&mut self, pick: &Pick, cell: (u16, u16), strong: bool) {
        let grab = Grab::new(&self.world, &self.camera, pick, cell, strong);
        self.hand.hold(grab);
        let name = self.body_name(pick.body);
        let max =
            Grab::spring(self.world.body(pick.body).mass(), strong || self.ui.strong).max_force;
        self.say(format!("grabbing {name} (at most {max:.0} N)"));
    }

    /// A button came up: the hand lets go; a grabbed body flies on with its velocity.
    pub(crate) fn release_hand(&mut self) {
        if let Some(body) = self.hand.release()
            && body.index() < self.world.len()
        {
            let name = self.body_name(body);
            let speed = self.world.body(body).linear_velocity().length();
            self.say(if speed >= 0.5 {
                format!("threw {name} at {speed:.1} m/s")
            } else {
                format!("let go of {name}")
            });
        }
        self.dirty = true;
    }

    /// Wheel or `+`/`-` while holding a body: moves it nearer (or farther). False if nothing is held.
    pub(crate) fn move_grab(&mut self, nearer: bool) -> bool {
        let camera = self.camera;
        let Some(grab) = self.hand.grab_mut() else {
            return false;
        };
        grab.move_depth(&camera, nearer);
        let depth = grab.depth;
        self.say(format!(
            "holding it {depth:.1} m from the camera ({})",
            if nearer { "nearer" } else { "farther" }
        ));
        true
    }

    /// While a body is held: the held point and the pointer's point, world, m.
    pub fn grab_points(&self) -> Option<(Vec3, Vec3)> {
        let grab = self.hand.grab()?;
        if grab.body.index() >= self.world.len() {
            return None;
        }
        let pointer = grab.pointer_point(&self.camera, &self.viewport(), self.viewport_area());
        Some((grab.anchor(&self.world), pointer))
    }

    /// Draws the held point's marker and the line to the pointer over the frame.
    pub(crate) fn draw_grab_tether(&mut self) {
        let Some((anchor, pointer)) = self.grab_points() else {
            return;
        };
        let viewport = self.viewport();
        draw_tether(
            &mut self.frame,
            &viewport,
            &self.camera,
            anchor,
            pointer,
            TETHER_LINE,
            TETHER_MARKER,
        );
    }
}
