//! `n` / `N`: the next / previous built-in scene, without quitting. The new scene starts as it would
//! from the command line (its camera, gravity on, its own physics settings, a fresh timeline); what
//! the user chose about the view and the hand (render mode, overlays, inspector, strong hand, grab,
//! pause) and what is known of the terminal (layout, colour depth, late probe replies) are kept.

use crate::app::App;
use crate::scene::{self, builtin};

impl App {
    /// Switches to the built-in scene after (or before) the current one in `nudge scenes` order; a
    /// scene from a file is followed by the first.
    pub(crate) fn cycle_scene(&mut self, forward: bool) {
        if self.timeline.is_recording() {
            self.say("a recording holds one scene (q ends it, then switch)");
            return;
        }
        let scenes = scene::builtin_scenes();
        let next = match scenes.iter().position(|(name, _)| *name == self.scene.name) {
            Some(i) if forward => (i + 1) % scenes.len(),
            Some(i) => (i + scenes.len() - 1) % scenes.len(),
            None if forward => 0,
            None => scenes.len() - 1,
        };
        let (name, description) = scenes[next];
        let Some(scene) = builtin::by_name(name) else {
            return;
        };
        let mut app = App::new(scene, self.config.clone());
        app.area = self.area;
        if let Some(cell) = self.selection.pointer() {
            app.selection.point_at(cell);
        }
        app.render_options.mode = self.render_options.mode;
        self.ui.carry_to(&mut app.ui);
        // What the user chose to see of the physics stays too, as in Box2D's samples app.
        self.inspect.carry_to(&mut app.inspect);
        app.world.set_profiling(app.inspector_open());
        app.late_replies = std::mem::take(&mut self.late_replies);
        *self = app;
        self.say(format!("{name}: {description} (n next, N previous)"));
    }

    /// The name of the scene shown.
    pub fn scene_name(&self) -> &str {
        &self.scene.name
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::app::AppConfig;
    use crate::render::RenderMode;

    #[test]
    fn n_visits_every_built_in_scene_in_order_and_wraps_and_capital_n_goes_back() {
        let mut app = App::new(scene::load("default").unwrap(), AppConfig::default());
        let names: Vec<&str> = scene::builtin_scenes().iter().map(|(n, _)| *n).collect();
        for expected in names.iter().skip(1).chain(names.iter().take(1)) {
            app.cycle_scene(true);
            assert_eq!(app.scene_name(), *expected);
            assert_eq!(app.world().len(), app.scene.bodies.len());
            assert_eq!(*app.camera(), app.scene.camera);
            assert!(app.message().starts_with(expected), "{}", app.message());
        }
        app.cycle_scene(false);
        assert_eq!(app.scene_name(), *names.last().unwrap());
    }

    /// Switching scenes dropped the grab mode (`h`), the overlays and the inspector: the status bar's
    /// GRAB flag vanished with the old scene.
    #[test]
    fn switching_scenes_keeps_the_render_mode_the_pause_the_hand_and_the_overlays() {
        let mut app = App::new(scene::load("stack").unwrap(), AppConfig::default());
        app.render_options.mode = RenderMode::Wireframe;
        app.ui.pause();
        app.ui.toggle_grab_mode();
        app.toggle_inspector();
        let mut overlays = app.overlays();
        overlays.insert(crate::app::panels::overlays::OverlayKind::Contacts);
        app.set_overlays(overlays);
        app.toggle_gravity();
        app.cycle_scene(true);
        assert_eq!(app.scene_name(), "pyramid");
        assert_eq!(app.render_mode(), RenderMode::Wireframe);
        assert!(app.is_paused());
        assert!(app.ui.grab_mode());
        assert!(app.inspector_open());
        assert_eq!(app.overlays(), overlays);
        assert!(app.ui.gravity_on(), "a new scene starts with gravity on");
    }

    #[test]
    fn switching_scenes_keeps_the_overlays_and_the_inspector() {
        let mut app = App::new(scene::load("stack").unwrap(), AppConfig::default());
        let overlays: crate::app::panels::overlays::OverlaySet = "contacts,sleep".parse().unwrap();
        app.set_overlays(overlays);
        app.toggle_inspector();
        app.cycle_scene(true);
        assert_eq!(app.overlays(), overlays);
        assert!(app.inspector_open());
        assert!(
            app.world().is_profiling(),
            "the open panel's step profile goes on"
        );
    }
}
