//! Bodies that fall off the world.
//!
//! A sandbox floor has edges: a ball pushed over one falls forever, never sleeps, and the scene never
//! comes to rest (every frame is drawn, the status bar never says idle). A body that has fallen
//! [`LOST_DEPTH`] below the bottom of everything the scene declared static can never land on anything
//! again, so it is frozen where it is (it keeps its place in the world, as every body the scene
//! declares does) and the status bar says so; `r` brings it back with the rest of the scene.

use crate::physics::{BodyId, World};
use crate::scene::Scene;

/// How far below the lowest static body a falling body counts as lost, metres: deep enough that
/// nothing the scene could do brings it back, shallow enough that it is frozen within about 3 s of
/// free fall.
pub const LOST_DEPTH: f32 = 50.0;

/// The height under which a dynamic body is lost: [`LOST_DEPTH`] below the lowest bottom of the
/// scene's scenery (its static bodies, not the frozen ones: a saved world holds the lost bodies
/// frozen where they fell); `None` when it has none (nothing to fall off).
pub fn lost_below(scene: &Scene) -> Option<f32> {
    scene
        .bodies
        .iter()
        .filter(|body| body.desc.is_static && !body.frozen)
        .map(|body| body.desc.shape.aabb(&body.desc.pose).min.y)
        .filter(|y| y.is_finite())
        .reduce(f32::min)
        .map(|floor| floor - LOST_DEPTH)
}

/// Freezes every awake dynamic body whose centre is below `height` (or not finite); returns the first
/// it froze, for the status bar.
pub fn freeze_lost(world: &mut World, height: f32) -> Option<BodyId> {
    let mut first = None;
    for i in 0..world.len() {
        let id = BodyId(i as u32);
        let body = world.body(id);
        let y = body.pose().position.y;
        let below = y < height || y.is_nan();
        if !body.is_static() && !body.is_sleeping() && below {
            world.set_static(id, true);
            first = first.or(Some(id));
        }
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    #[test]
    fn the_lost_height_is_measured_from_the_lowest_static_body() {
        let default = scene::load("default").unwrap();
        // The default floor's top is at y = 0 and it is 1 m thick.
        assert_eq!(lost_below(&default), Some(-1.0 - LOST_DEPTH));
        let mut floating = default.clone();
        floating.bodies.retain(|body| !body.desc.is_static);
        assert_eq!(lost_below(&floating), None);
    }

    #[test]
    fn only_awake_dynamic_bodies_below_the_line_are_frozen() {
        let scene = scene::load("default").unwrap();
        let mut world = scene.build_world();
        assert_eq!(freeze_lost(&mut world, -1.0 - LOST_DEPTH), None);
        // Everything above: a line over the scene freezes every dynamic body, not the floor.
        let first = freeze_lost(&mut world, 100.0);
        assert_eq!(first, Some(BodyId(1)));
        assert!(world.bodies().iter().all(|body| body.is_static()));
    }
}
