//! Every built-in scene, left alone, keeps its bodies in its world and comes to rest.

use nudge::physics::World;
use nudge::scene::{self, Scene};

const STEPS_PER_SECOND: usize = 60;

/// The top of the scene's lowest static body: a dynamic body whose centre is below it has left the
/// world (it fell past every edge).
fn lowest_ground(scene: &Scene) -> f32 {
    scene
        .bodies
        .iter()
        .filter(|b| b.desc.is_static)
        .map(|b| b.desc.shape.aabb(&b.desc.pose).max.y)
        .fold(f32::INFINITY, f32::min)
}

fn lowest_dynamic_centre(world: &World) -> f32 {
    world
        .bodies()
        .iter()
        .filter(|b| !b.is_static())
        .map(|b| b.pose().position.y)
        .fold(f32::INFINITY, f32::min)
}

/// Steps `scene` for `seconds`; returns the world and when it first had no body awake.
fn run(scene: &Scene, seconds: usize) -> (World, Option<f32>) {
    let mut world = scene.build_world();
    let mut idle_at = None;
    for step in 1..=seconds * STEPS_PER_SECOND {
        world.step();
        if idle_at.is_none() && world.awake_count() == 0 {
            idle_at = Some(step as f32 / STEPS_PER_SECOND as f32);
        }
    }
    (world, idle_at)
}

/// `ramp`'s balls rolled off its floor (y ≈ −520 m after 15 s) and `dominoes`' ball did too; `rain`
/// had 40 % of its bodies awake after 30 s (balls rolling for ever, then, resisting rolling, spinning
/// in place for ever). The bound is 35 s since bodies speeding up stopped counting as resting
/// (`physics::sleep`, "Speeding up"): Newton's cradle used to be put to sleep at 24.5 s, frozen at
/// the end of a swing while its balls still swung at up to 9 cm/s, and now swings until 30.6 s.
#[test]
fn every_built_in_scene_keeps_its_bodies_for_60_seconds_and_rests_within_35() {
    for (name, _) in scene::builtin_scenes() {
        let scene = scene::load(name).unwrap();
        let ground = lowest_ground(&scene);
        let (world, idle_at) = run(&scene, 60);
        let lowest = lowest_dynamic_centre(&world);
        assert!(
            lowest > ground - 0.01,
            "{name}: a body left the world (centre at y = {lowest}, ground at {ground})"
        );
        assert!(
            idle_at.is_some_and(|t| t <= 35.0),
            "{name}: idle at {idle_at:?} s"
        );
    }
}
