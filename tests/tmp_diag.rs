use glam::{Quat, Vec3};
use nudge::geometry::{Pose, Shape};
use nudge::physics::{BodyDesc, Settings, World};
use nudge::testing::penetration::max_penetration;

#[test]
fn diag() {
    let n: usize = std::env::var("N").map(|s| s.parse().unwrap()).unwrap_or(10);
    let mut world = World::new(Settings::default());
    world.add_body(BodyDesc::fixed(Shape::cuboid(Vec3::new(40.0, 0.5, 40.0)), Pose::from_position(Vec3::new(0.0, -0.5, 0.0))));
    for _ in 0..n {
        world.add_body(BodyDesc::dynamic(Shape::cuboid(Vec3::splat(0.5)), Pose::new(Vec3::new(0.0, 1.0, 0.0), Quat::IDENTITY), 1.0));
    }
    for s in 0..900 {
        world.step();
        if s % 30 == 0 {
            let maxy = world.bodies().iter().map(|b| b.pose().position.y).fold(0.0, f32::max);
            let maxv = world.bodies().iter().map(|b| b.linear_velocity().length()).fold(0.0, f32::max);
            println!("{s} maxy {maxy:.2} maxv {maxv:.2} pen {:?}", max_penetration(&world, true));
        }
    }
}
