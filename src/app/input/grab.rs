//! Grab and drag: in grab mode (`h`), the left button holds the clicked point of a body on a spring
//! to the pointer, the way every windowed physics sandbox lets you drag things.
//!
//! The pointer moves on the plane through the grabbed point that faces the camera (perpendicular to
//! its view direction, at the depth the point had when grabbed), in either projection; the wheel or
//! `+`/`-` move that plane nearer or farther. The spring — Box2D's mouse joint, a soft constraint of
//! [`GRAB_HERTZ`] and [`GRAB_DAMPING_RATIO`] whose force is capped at the body's mass ×
//! [`GRAB_ACCEL_MAX`] — pulls the grabbed point toward a target that follows the pointer
//! continuously (see [`crate::app::input::pointer_track`]), and a little damping calms the spin it cannot reach
//! (a held body swings about the held point). The physics solves it in every sub-step, the target
//! moving steadily across the step ([`PointHold`]). The spring damps the held point's velocity
//! relative to the target's, so a body dragged at a steady speed moves at that speed, and letting go
//! leaves it that velocity: a quick drag throws at the drag's speed. The force is capped, so the
//! contact solver stays in charge and a body dragged into the floor stops at it.

use glam::{Vec2, Vec3};

use crate::app::App;
use crate::app::input::hand::{HandAction, HandReport, STRONG_FACTOR};
use crate::app::input::picking::{Pick, ScreenView};
use crate::app::input::pointer_track::PointerTrack;
use crate::color::Rgb;
use crate::geometry::{Camera, Ray};
use crate::physics::{BodyId, PointHold, PointSpring, World};
use crate::render::tether::draw_tether;

/// Natural frequency of the grab spring, Hz. Solved in every sub-step, the spring settles g/ω² below
/// the pointer under gravity: 3.9 mm at 8 Hz, 9.9 mm at Box2D's 5 Hz (1.1 and 2.0 cm when it was
/// applied once per 60 Hz step). 8 Hz settles in about a tenth of a second, without a visible
/// wobble.
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
/// [`PointHold`]).
pub const GRAB_MAX_SPEED: f32 = 15.0;
/// Time constant of the spin damping on a held body, s: the hand's grip. A body held by a point off
/// its centre swings about it, and a box towed across the floor by its front face turns to trail and
/// then swings past when the pointer stops; the spring cannot damp either. Box2D's joint damps spin
/// very lightly (0.5 Hz, ζ 0.1); here 0.5 s left a box flicked 2 m in a quarter second swinging 19 cm
/// about the pointer half a second later, and throws 15–35 % off (the centre swinging about the held
/// point as it is let go). With the spring in the solver, 0.1 s still let 3 of 88 throws go off over
/// 1.2 × the pointer's speed (up to 1.235); 0.05 s keeps them within 0.87–1.18.
pub const GRAB_SPIN_TIME_S: f32 = 0.05;
/// The hand's follow-through on letting go, s: it gives the held point the pointer's velocity, as far
/// as the spring's capped force can in this time (1.5 m/s of change at the cap's 3 g).
pub const FOLLOW_THROUGH_S: f32 = 0.05;
/// How far one wheel notch or `+`/`-` moves a held body nearer or farther: this fraction of its
/// distance from the camera (the zoom's step).
pub const GRAB_DEPTH_STEP: f32 = 0.1;
/// The tether's colours: the line to the pointer and the marker on the held point.
pub const TETHER_LINE: Rgb = Rgb::new(0xf0, 0xf0, 0xf0);
pub const TETHER_MARKER: Rgb = Rgb::new(0xff, 0x50, 0x40);

/// A body held by one of its points.
#[derive(Clone, Debug, PartialEq)]
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
    /// Where the spring pulls, in cells: the pointer followed between its reports.
    pub track: PointerTrack,
    /// How fast the spring's target moved over the last step, world, m/s: the hand's velocity.
    pub velocity: Vec3,
}

impl Grab {
    /// Holds the point `pick` hit, with the pointer at `cell`, in the view `view`.
    pub fn new(
        world: &World,
        view: &ScreenView,
        pick: &Pick,
        cell: (u16, u16),
        strong: bool,
    ) -> Self {
        let camera = &view.camera;
        let pose = world.body(pick.body).pose();
        let depth = (pick.hit.point - camera.position).dot(camera.basis().forward);
        let exact = view.cell_position_of(pick.hit.point);
        Self {
            body: pick.body,
            anchor_local: pose.inverse_transform_point(pick.hit.point),
            depth: depth.max(camera.near),
            cell,
            strong,
            track: PointerTrack::new(cell, exact),
            velocity: Vec3::ZERO,
        }
    }

    /// The held point in the world now, m.
    pub fn anchor(&self, world: &World) -> Vec3 {
        world
            .body(self.body)
            .pose()
            .transform_point(self.anchor_local)
    }

    /// The pointer was reported at `cell`.
    pub fn report(&mut self, cell: (u16, u16)) {
        self.cell = cell;
        self.track.report(cell);
    }

    /// The world point on the grab's plane drawn at `at` (cells).
    fn plane_point(&self, view: &ScreenView, at: Vec2) -> Vec3 {
        point_at_depth(&view.camera, &view.ray_through(at), self.depth)
    }

    /// The pointer's point: where the ray through its cell (at the held point's place in the cell)
    /// meets the grab's plane.
    pub fn pointer_point(&self, view: &ScreenView) -> Vec3 {
        self.plane_point(view, self.track.pointer())
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

    /// Holds the point for the next step, the target gliding on by a step's worth.
    pub fn apply(&mut self, world: &mut World, view: &ScreenView, strong: bool) -> HandReport {
        // What the spring pulled with over the last step, for the status bar.
        let pulled = world.hold_force(self.body).length();
        let (from, to) = self.track.advance();
        let spring = Self::spring(world.body(self.body).mass(), strong || self.strong);
        let from = self.plane_point(view, from);
        let to = self.plane_point(view, to);
        self.velocity = (to - from) / world.settings().dt;
        world.hold_point(PointHold {
            body: self.body,
            anchor: self.anchor_local,
            from,
            to,
            spring,
            spin_time: GRAB_SPIN_TIME_S,
        });
        let pointer = self.pointer_point(view);
        HandReport {
            action: HandAction::Grab,
            body: self.body,
            force_n: pulled,
            measure: (self.anchor(world) - pointer).length(),
            target_speed: 0.0,
            out_of_reach: false,
        }
    }

    /// Lets go, the held point leaving at the hand's velocity: the impulse at the held point that
    /// gives it [`Grab::velocity`], J = K⁻¹·(u − v_point), at most what the spring's capped force gives
    /// in [`FOLLOW_THROUGH_S`]. The spring keeps the held point at the target's velocity only on
    /// average: a body still catching up with the pointer (flicked from rest, or swinging about the
    /// held point) went off up to 25 % faster or slower than the drag. Returns the impulse, N·s.
    pub fn let_go(&self, world: &mut World, strong: bool) -> Vec3 {
        if self.body.index() >= world.len() || world.body(self.body).is_static() {
            return Vec3::ZERO;
        }
        let anchor = self.anchor(world);
        let k = world.point_compliance(self.body, anchor);
        if k.determinant().abs() <= f32::MIN_POSITIVE {
            return Vec3::ZERO;
        }
        let wanted = k.inverse() * (self.velocity - world.point_velocity(self.body, anchor));
        let spring = Self::spring(world.body(self.body).mass(), strong || self.strong);
        let impulse = wanted.clamp_length_max(spring.max_force * FOLLOW_THROUGH_S);
        if impulse.is_finite() {
            world.apply_impulse_at_point(self.body, impulse, anchor);
            impulse
        } else {
            Vec3::ZERO
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
        let grabbing = self.ui.toggle_grab_mode();
        // Whatever the hand held, it lets go.
        let _ = self.hand.release();
        self.say(if grabbing {
            "grab: drag a body, wheel moves it (h: push)"
        } else {
            "left button pushes (h: grab)"
        });
    }

    /// The left button went down on a dynamic body in grab mode.
    pub(crate) fn start_grab(&mut self, pick: &Pick, cell: (u16, u16), strong: bool) {
        let grab = Grab::new(&self.world, &self.screen_view(), pick, cell, strong);
        self.hand.hold(grab);
        let name = self.body_name(pick.body);
        let max = Grab::spring(
            self.world.body(pick.body).mass(),
            strong || self.ui.strong(),
        )
        .max_force;
        self.say(format!("grabbing {name} (at most {max:.0} N)"));
    }

    /// A button came up: the hand lets go; a grabbed body flies on at the hand's velocity.
    pub(crate) fn release_hand(&mut self) {
        if let Some(grab) = self.hand.release()
            && grab.body.index() < self.world.len()
        {
            grab.let_go(&mut self.world, self.ui.strong());
            let body = grab.body;
            let name = self.body_name(body);
            let speed = self.world.body(body).linear_velocity().length();
            self.say(if speed >= 0.5 {
                format!("threw {name} at {speed:.1} m/s")
            } else {
                format!("let go of {name}")
            });
        }
        self.say_push_ended();
        self.dirty = true;
    }

    /// Wheel or `+`/`-` while holding a body: moves it nearer (or farther). False if nothing is held.
    pub(crate) fn move_grab(&mut self, nearer: bool) -> bool {
        let camera = *self.camera.get();
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
        let pointer = grab.pointer_point(&self.screen_view());
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
            self.camera.get(),
            anchor,
            pointer,
            TETHER_LINE,
            TETHER_MARKER,
        );
    }
}
