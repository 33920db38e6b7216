//! The camera the view is seen through ([`CameraView`], `App::camera`) and its way home: `c` and Home put it back where the scene framed it, and zoom stops at
//! bounds measured from that framing, so no run of wheel notches loses the scene (it used to shrink
//! to one pixel after about 120 notches out, or fly inside a body going in).

use crate::app::App;
use crate::geometry::{Camera, Projection};

/// Closest a zoom comes to the target, as a fraction of the scene's framing distance.
pub const ZOOM_IN_LIMIT: f32 = 0.1;
/// Farthest a zoom goes from the target, as a multiple of the scene's framing distance.
pub const ZOOM_OUT_LIMIT: f32 = 8.0;

/// How far `camera` is zoomed relative to `home`: distance to the target in perspective, view
/// height in orthographic, each over the home camera's equivalent.
pub fn zoom_ratio(camera: &Camera, home: &Camera) -> f32 {
    let home_distance = (home.position - home.target).length().max(1e-3);
    let home_height = match home.projection {
        Projection::Perspective { fov_y } => 2.0 * home_distance * (0.5 * fov_y).tan(),
        Projection::Orthographic { view_height } => view_height,
    };
    match camera.projection {
        Projection::Perspective { .. } => {
            (camera.position - camera.target).length() / home_distance
        }
        Projection::Orthographic { view_height } => view_height / home_height.max(1e-3),
    }
}

/// The camera the view is drawn and picked through. Changed only through its methods, which keep
/// zoom inside its bounds; the scene's framing (`home`) stays with the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraView {
    camera: Camera,
}

/// Where a zoom notch got to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Zoomed {
    /// Zoomed; the zoom relative to home (2 = twice as close).
    To(f32),
    /// Not zoomed: it would have passed the closest bound.
    Closest,
    /// Not zoomed: it would have passed the farthest bound.
    Farthest,
}

/// Reading the camera is free, so `&app.camera` still passes for a `&Camera` (the benchmarks in
/// `crate::bench` draw through it); changing it takes a method.
impl std::ops::Deref for CameraView {
    type Target = Camera;

    fn deref(&self) -> &Camera {
        &self.camera
    }
}

impl CameraView {
    pub fn new(camera: Camera) -> Self {
        Self { camera }
    }

    pub fn get(&self) -> &Camera {
        &self.camera
    }

    /// The camera itself, for tests and benchmarks that set it directly (see `App::camera_mut`).
    pub fn get_mut(&mut self) -> &mut Camera {
        &mut self.camera
    }

    /// Turns it about its target.
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.camera.orbit(yaw, pitch);
    }

    /// Perspective ↔ orthographic; returns the projection now.
    pub fn toggle_projection(&mut self) -> Projection {
        self.camera = self.camera.toggled_projection(crate::app::DEFAULT_FOV_Y);
        self.camera.projection
    }

    /// Orthographic or perspective, whichever was asked for.
    pub fn set_orthographic(&mut self, orthographic: bool) {
        let is_ortho = matches!(self.camera.projection, Projection::Orthographic { .. });
        if is_ortho != orthographic {
            self.toggle_projection();
        }
    }

    /// A replay shows the camera its recording had.
    pub fn follow(&mut self, camera: Camera) {
        self.camera = camera;
    }

    /// Zooms by `factor` (< 1 in), unless that would pass a bound measured from `home`.
    pub fn zoom(&mut self, factor: f32, home: &Camera) -> Zoomed {
        let mut zoomed = self.camera;
        zoomed.zoom(factor);
        let ratio = zoom_ratio(&zoomed, home);
        if ratio < ZOOM_IN_LIMIT && factor < 1.0 {
            Zoomed::Closest
        } else if ratio > ZOOM_OUT_LIMIT && factor > 1.0 {
            Zoomed::Farthest
        } else {
            self.camera = zoomed;
            Zoomed::To(1.0 / ratio)
        }
    }

    /// Back to `home`, keeping the projection.
    pub fn reset(&mut self, home: &Camera) {
        let perspective = matches!(self.camera.projection, Projection::Perspective { .. });
        let home_perspective = matches!(home.projection, Projection::Perspective { .. });
        self.camera = *home;
        if perspective != home_perspective {
            self.toggle_projection();
        }
    }

    /// Whether it is at `home` (up to the projection).
    pub fn is_home(&self, home: &Camera) -> bool {
        self.camera.position == home.position && self.camera.target == home.target
    }
}

impl App {
    /// Zooms by `factor` (< 1 in), unless that would pass a bound; says the zoom, or the bound.
    pub(crate) fn zoom(&mut self, factor: f32) {
        match self.camera.zoom(factor, &self.scene.camera) {
            Zoomed::Closest => self.say("closest zoom (c resets the camera)"),
            Zoomed::Farthest => self.say("farthest zoom (c resets the camera)"),
            // Every notch is answered: inside the bounds, with how far in it is.
            Zoomed::To(zoom) => self.say(format!("zoom {zoom:.2}× (c resets the camera)")),
        }
        self.dirty = true;
    }

    /// `c` or Home: the scene's own camera again (the projection is kept).
    pub(crate) fn reset_camera(&mut self) {
        self.camera.reset(&self.scene.camera);
        self.say("camera reset");
    }

    /// Whether the camera is where the scene put it (up to the projection).
    pub(crate) fn camera_is_home(&self) -> bool {
        self.camera.is_home(&self.scene.camera)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::AppConfig;

    fn app() -> App {
        App::new(crate::scene::load("default").unwrap(), AppConfig::default())
    }

    #[test]
    fn any_number_of_zoom_notches_stops_at_the_bounds() {
        let mut app = app();
        for _ in 0..500 {
            app.zoom(1.0 / 0.9);
        }
        let out = zoom_ratio(app.camera(), &app.scene.camera);
        assert!(
            (0.8 * ZOOM_OUT_LIMIT..=ZOOM_OUT_LIMIT).contains(&out),
            "{out}"
        );
        assert!(app.message().starts_with("farthest zoom"));
        for _ in 0..500 {
            app.zoom(0.9);
        }
        let inward = zoom_ratio(app.camera(), &app.scene.camera);
        assert!(
            (ZOOM_IN_LIMIT..1.2 * ZOOM_IN_LIMIT).contains(&inward),
            "{inward}"
        );
        assert!(app.message().starts_with("closest zoom"));
    }

    #[test]
    fn orthographic_zoom_is_bounded_too() {
        let mut app = app();
        app.toggle_projection();
        for _ in 0..500 {
            app.zoom(1.0 / 0.9);
        }
        assert!(zoom_ratio(app.camera(), &app.scene.camera) <= ZOOM_OUT_LIMIT);
        for _ in 0..500 {
            app.zoom(0.9);
        }
        assert!(zoom_ratio(app.camera(), &app.scene.camera) >= ZOOM_IN_LIMIT);
    }

    #[test]
    fn the_camera_resets_to_the_scenes_framing_keeping_the_projection() {
        let mut app = app();
        app.camera.orbit(1.0, 0.3);
        app.zoom(0.5);
        assert!(!app.camera_is_home());
        app.reset_camera();
        assert_eq!(*app.camera(), app.scene.camera);
        app.toggle_projection();
        app.camera.orbit(0.5, 0.0);
        app.reset_camera();
        assert!(app.camera_is_home());
        assert!(matches!(
            app.camera().projection,
            Projection::Orthographic { .. }
        ));
    }
}
