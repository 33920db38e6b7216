//! The world step's own tests: whole-step behaviour, and the stages against plain reference versions.

use crate::geometry::{Pose, Shape};
use crate::physics::broad::broad_phase::BroadPhase;
use crate::physics::prepare::constraint_order::SERIAL_COLOR;
use crate::physics::solve::wide_contacts::kind_of;
use crate::physics::world::*;

fn floor(world: &mut World) -> BodyId {
    world.add_body(BodyDesc::fixed(
        Shape::cuboid(Vec3::new(20.0, 0.5, 20.0)),
        Pose::from_position(Vec3::new(0.0, -0.5, 0.0)),
    ))
}

fn unit_box_at(y: f32) -> BodyDesc {
    BodyDesc::dynamic(
        Shape::cuboid(Vec3::splat(0.5)),
        Pose::from_position(Vec3::new(0.0, y, 0.0)),
        1.0,
    )
}

/// A 2D pyramid of unit boxes, `base` in the bottom row, 5 cm apart, on the floor: the physics
/// layer's own small copy of `scene::cases::pyramid` (it must not import the scene layer).
fn pyramid_world(base: usize) -> World {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    for row in 0..base {
        let count = base - row;
        for i in 0..count {
            let x = (i as f32 - 0.5 * (count as f32 - 1.0)) * 1.05;
            let mut desc = unit_box_at(0.5 + row as f32);
            desc.pose.position.x = x;
            world.add_body(desc);
        }
    }
    world
}

fn run(world: &mut World, seconds: f32) {
    let steps = (seconds / world.settings().dt).round() as usize;
    for _ in 0..steps {
        world.step();
    }
}

/// One body with more contacts than there are colours: the overflow colour's constraints share
/// that body, so they are solved one per lane group; the balls must rest on the plank all the same,
/// whether the plank is heavy (100 kg) or light (3 kg under 100 one-kilogram balls: no mass ratio
/// at any contact, 33:1 in load, which `mark_heavy_loads` finds; without it the balls jiggle by
/// 12 mm).
#[test]
fn a_body_with_more_contacts_than_colours_still_holds_everything_up() {
    for plank_mass in [100.0, 3.0] {
        let mut world = World::new(Settings {
            sleep: false,
            ..Settings::default()
        });
        floor(&mut world);
        let plank = world.add_body(BodyDesc::dynamic(
            Shape::cuboid(Vec3::new(6.0, 0.1, 6.0)),
            Pose::from_position(Vec3::new(0.0, 0.1, 0.0)),
            plank_mass,
        ));
        let radius = 0.25;
        let mut balls = Vec::new();
        for i in 0..10 {
            for k in 0..10 {
                let x = -4.5 + i as f32;
                let z = -4.5 + k as f32;
                balls.push(world.add_body(BodyDesc::dynamic(
                    Shape::sphere(radius),
                    Pose::from_position(Vec3::new(x, 0.2 + radius, z)),
                    1.0,
                )));
            }
        }
        run(&mut world, 2.0);
        let serial = world
            .scratch
            .graph
            .solve_order()
            .filter(|&(color, _)| color == SERIAL_COLOR)
            .count();
        assert!(serial > 0, "no constraint reached the serial colour");
        let top = world.body(plank).pose.position.y + 0.1;
        for &ball in &balls {
            let y = world.body(ball).pose.position.y;
            assert!(
                (y - (top + radius)).abs() < 0.001,
                "{plank_mass} kg plank: ball at {y}, plank top {top}"
            );
        }
        let plank_y = world.body(plank).pose.position.y;
        assert!(
            (plank_y - 0.1).abs() < 0.001,
            "{plank_mass} kg plank at {plank_y}"
        );
        assert!(world.max_penetration() < 0.01);
    }
}

/// The layers, layer order, colouring and solve order of the current contact graph, computed the
/// plain way (lists of neighbours, a `VecDeque`, a comparison sort): `(levels, contact indices in
/// layer order, color_order, layer_order)`.
fn reference_order(world: &World) -> (Vec<u32>, Vec<u32>, Vec<u64>, Vec<u32>) {
    let s = &world.scratch;
    let n = s.solver.bodies.len();
    let edges: Vec<(usize, usize, u8)> = world
        .contacts
        .iter()
        .map(|c| {
            (
                s.solver.index[c.a as usize] as usize,
                s.solver.index[c.b as usize] as usize,
                kind_of(c.manifold.len) as u8,
            )
        })
        .collect();
    let mut levels = vec![u32::MAX; n];
    levels[0] = 0;
    let mut neighbours = vec![Vec::new(); n];
    let mut queue = std::collections::VecDeque::new();
    for &(a, b, _) in &edges {
        if a != 0 && b != 0 {
            neighbours[a].push(b);
            neighbours[b].push(a);
        } else if a != 0 || b != 0 {
            let d = a | b;
            if levels[d] != 1 {
                levels[d] = 1;
                queue.push_back(d);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        for &j in &neighbours[i] {
            if levels[j] == u32::MAX {
                levels[j] = levels[i] + 1;
                queue.push_back(j);
            }
        }
    }
    let mut order: Vec<(u32, usize)> = edges
        .iter()
        .enumerate()
        .filter(|&(_, &(a, b, _))| a != 0 || b != 0)
        .map(|(k, &(a, b, _))| (levels[a].min(levels[b]), k))
        .collect();
    order.sort();
    let mut masks = vec![0u64; n];
    let mut color_order: Vec<u64> = order
        .iter()
        .enumerate()
        .map(|(rank, &(_, k))| {
            let (a, b, kind) = edges[k];
            let color = (!(masks[a] | masks[b])).trailing_zeros().min(SERIAL_COLOR);
            for body in [a, b] {
                if body != 0 {
                    masks[body] |= 1 << color;
                }
            }
            let group = 8 * u64::from(color) + 2 * u64::from(kind) + u64::from(a == 0);
            group << 32 | rank as u64
        })
        .collect();
    color_order.sort();
    let mut layer_order = vec![0; order.len()];
    for (position, &key) in color_order.iter().enumerate() {
        layer_order[(key & 0xffff_ffff) as usize] = position as u32;
    }
    let order = order.iter().map(|&(_, k)| k as u32).collect();
    (levels, order, color_order, layer_order)
}

/// A heap of boxes and balls dropped onto the floor (contacts come and go every step), and
/// two boxes touching each other high above it (a contact not connected to any static body).
#[test]
fn the_constraint_order_is_the_plain_bfs_and_greedy_colouring_of_the_contact_graph() {
    let mut world = World::new(Settings {
        sleep: false,
        ..Settings::default()
    });
    floor(&mut world);
    for i in 0..48 {
        let (x, z, y) = ((i % 4) as f32, ((i / 4) % 4) as f32, (i / 16) as f32);
        let position = Vec3::new(0.9 * x - 1.5, 0.5 + 0.95 * y, 0.9 * z - 1.5);
        let shape = if i % 3 == 0 {
            Shape::sphere(0.45)
        } else {
            Shape::cuboid(Vec3::splat(0.45))
        };
        world.add_body(BodyDesc::dynamic(shape, Pose::from_position(position), 1.0));
    }
    world.add_body(unit_box_at(30.0));
    world.add_body(unit_box_at(31.0));
    let mut unconnected = 0;
    for _ in 0..40 {
        world.step();
        let (levels, order, color_order, layer_order) = reference_order(&world);
        let s = &world.scratch;
        assert_eq!(s.graph.levels, levels);
        let ours: Vec<u32> = s.graph.order.iter().map(|&key| key as u32).collect();
        assert_eq!(ours, order);
        assert_eq!(s.graph.color_order, color_order);
        assert_eq!(s.graph.layer_order, layer_order);
        unconnected += usize::from(levels.contains(&u32::MAX));
    }
    assert!(
        unconnected > 20,
        "the pair in the air was seen {unconnected} times"
    );
}

#[test]
fn a_step_clears_the_force_it_applied() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let id = world.add_body(unit_box_at(0.5));
    world.apply_force_at_point(id, Vec3::new(5.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0));
    world.step();
    assert_eq!(world.body(id).force, Vec3::ZERO);
    assert_eq!(world.body(id).torque, Vec3::ZERO);
    assert!(world.body(id).linear_velocity().x > 0.0);
}

#[test]
fn a_ball_on_a_frictionless_floor_keeps_its_speed() {
    let mut world = World::new(Settings::default());
    let f = floor(&mut world);
    world.set_static(f, true);
    let mut ball = BodyDesc::dynamic(
        Shape::sphere(0.5),
        Pose::from_position(Vec3::new(-10.0, 0.5, 0.0)),
        1.0,
    );
    ball.friction = 0.0;
    ball.linear_velocity = Vec3::new(3.0, 0.0, 0.0);
    let id = world.add_body(ball);
    run(&mut world, 3.0);
    let v = world.body(id).linear_velocity();
    assert!((v.x - 3.0).abs() < 1e-3, "{v}");
    assert!(v.y.abs() < 1e-2, "{v}");
}

#[test]
fn a_box_dropped_on_the_floor_comes_to_rest_on_it_and_falls_asleep() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let id = world.add_body(unit_box_at(2.0));
    run(&mut world, 3.0);
    let body = world.body(id);
    assert!(
        (body.pose().position.y - 0.5).abs() < 0.01,
        "{:?}",
        body.pose()
    );
    assert!(body.is_sleeping());
    assert_eq!(world.awake_count(), 0);
    assert!(world.max_penetration() < 0.01);
}

#[test]
fn a_force_wakes_a_sleeping_stack_and_torque_is_r_cross_f() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let lower = world.add_body(unit_box_at(0.5));
    let upper = world.add_body(unit_box_at(1.5));
    run(&mut world, 2.0);
    assert!(world.body(lower).is_sleeping() && world.body(upper).is_sleeping());
    // A sideways push at the top face of the upper box: the whole island wakes.
    let force = Vec3::new(50.0, 0.0, 0.0);
    let point = Vec3::new(0.0, 2.0, 0.0);
    world.apply_force_at_point(upper, force, point);
    assert!(!world.body(lower).is_sleeping() && !world.body(upper).is_sleeping());
    let r = point - world.body(upper).pose().position;
    assert!((world.body(upper).torque - r.cross(force)).length() < 1e-4);
}

#[test]
fn changing_gravity_wakes_a_sleeping_body_and_it_follows() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let id = world.add_body(unit_box_at(0.5));
    run(&mut world, 2.0);
    assert!(world.body(id).is_sleeping());
    world.set_gravity(Vec3::new(0.0, 9.81, 0.0));
    assert!(!world.body(id).is_sleeping());
    run(&mut world, 0.5);
    assert!(world.body(id).pose().position.y > 1.0);
}

#[test]
fn an_impulse_at_the_centre_changes_only_the_linear_velocity() {
    let mut world = World::new(Settings {
        gravity: Vec3::ZERO,
        ..Settings::default()
    });
    let id = world.add_body(BodyDesc::dynamic(
        Shape::cuboid(Vec3::new(0.5, 0.25, 1.0)),
        Pose::IDENTITY,
        2.0,
    ));
    world.apply_impulse_at_point(id, Vec3::new(4.0, 0.0, 0.0), Vec3::ZERO);
    assert_eq!(world.body(id).linear_velocity(), Vec3::new(2.0, 0.0, 0.0));
    assert_eq!(world.body(id).angular_velocity(), Vec3::ZERO);
    world.apply_impulse_at_point(id, Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 0.0, 0.0));
    assert!(world.body(id).angular_velocity().z > 0.0);
}

#[test]
fn freezing_keeps_the_pose_and_drops_velocity_and_force_unfreezing_falls() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let id = world.add_body(unit_box_at(5.0));
    run(&mut world, 0.5);
    world.apply_force_at_point(id, Vec3::new(100.0, 0.0, 0.0), Vec3::new(0.0, 5.0, 0.0));
    let frozen_at = *world.body(id).pose();
    world.set_static(id, true);
    run(&mut world, 1.0);
    let body = world.body(id);
    assert_eq!(*body.pose(), frozen_at);
    assert_eq!(body.linear_velocity(), Vec3::ZERO);
    assert_eq!(world.awake_count(), 0);
    world.set_static(id, false);
    run(&mut world, 0.2);
    let body = world.body(id);
    assert!(
        body.linear_velocity().y < -1.0,
        "{}",
        body.linear_velocity()
    );
    assert!(body.linear_velocity().x.abs() < 1e-6, "no stale force");
}

#[test]
fn unfreezing_a_support_wakes_the_sleeping_box_on_it() {
    let mut world = World::new(Settings::default());
    let support = world.add_body(unit_box_at(0.5));
    let top = world.add_body(unit_box_at(1.5));
    world.set_static(support, true);
    run(&mut world, 2.0);
    assert!(world.body(top).is_sleeping());
    world.set_static(support, false);
    assert!(!world.body(top).is_sleeping());
    run(&mut world, 0.5);
    assert!(
        world.body(top).pose().position.y < 1.0,
        "falls with its support"
    );
}

#[test]
fn static_bodies_get_no_solver_body() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    world.add_body(unit_box_at(0.5));
    world.step();
    // The dummy plus one dynamic box.
    assert_eq!(world.scratch.solver.bodies.len(), 2);
    assert_eq!(world.contact_count(), 1);
}

#[test]
fn a_fast_ball_stops_at_a_thin_wall_instead_of_tunnelling() {
    let mut world = World::new(Settings {
        gravity: Vec3::ZERO,
        ..Settings::default()
    });
    world.add_body(BodyDesc::fixed(
        Shape::cuboid(Vec3::new(0.05, 2.0, 2.0)),
        Pose::from_position(Vec3::new(5.0, 0.0, 0.0)),
    ));
    let mut ball = BodyDesc::dynamic(Shape::sphere(0.1), Pose::IDENTITY, 1.0);
    ball.linear_velocity = Vec3::new(200.0, 0.0, 0.0);
    let id = world.add_body(ball);
    run(&mut world, 0.5);
    let x = world.body(id).pose().position.x;
    assert!(x < 4.95 - 0.1 + 0.01, "ball at x = {x}");
}

#[test]
fn the_same_scene_gives_bit_identical_results() {
    let mut a = pyramid_world(5);
    let mut b = pyramid_world(5);
    run(&mut a, 1.0);
    run(&mut b, 1.0);
    for (x, y) in a.bodies().iter().zip(b.bodies()) {
        assert_eq!(x.pose(), y.pose());
    }
}

#[test]
fn reused_broad_phase_pairs_are_exactly_those_of_a_fresh_broad_phase() {
    let mut world = pyramid_world(6);
    world.settings_mut().sleep = false;
    let reused_steps = steps_reusing_exact_pairs(&mut world, 120, |_| {});
    assert!(reused_steps > 60, "reused on {reused_steps} of 120 steps");
}

/// Bodies in steady motion keep the broad phase's pairs for several steps, since their fat boxes
/// reach ahead along their velocity (`FAT_LEAD`), and the pairs are still exactly a fresh broad
/// phase's. A row of boxes 2 cm apart gliding sideways at 3 m/s (5 cm a step: grown by their
/// margin alone, their fat boxes were given up and the broad phase ran on all 120 steps; reaching
/// ahead, it is reused on 102), with no gravity and nothing to stop them.
#[test]
fn gliding_bodies_reuse_the_broad_phases_pairs_exactly() {
    let mut world = World::new(Settings {
        gravity: Vec3::ZERO,
        sleep: false,
        ..Settings::default()
    });
    for i in 0..12 {
        let mut desc = unit_box_at(2.0);
        desc.pose.position.x = 1.02 * i as f32;
        desc.linear_velocity = Vec3::new(0.0, 0.0, 3.0);
        world.add_body(desc);
    }
    let reused_steps = steps_reusing_exact_pairs(&mut world, 120, |pairs| {
        assert_eq!(pairs.len(), 11, "each box and its neighbour");
    });
    assert!(reused_steps > 60, "reused on {reused_steps} of 120 steps");
}

/// Steps `world` `steps` times, checking after each step that its pairs are exactly a fresh broad
/// phase's on the same boxes (and whatever `check` asks of them); returns on how many steps the
/// broad phase's pairs were reused rather than found again.
fn steps_reusing_exact_pairs(
    world: &mut World,
    steps: usize,
    check: impl Fn(&[(u32, u32)]),
) -> usize {
    let mut fresh = BroadPhase::new();
    let mut expected = Vec::new();
    let mut reused_steps = 0;
    for _ in 0..steps {
        world.step();
        let s = &world.scratch.pair_finder;
        reused_steps += usize::from(s.reuses > 0);
        fresh.find_pairs(&s.aabbs, &s.kinds, &mut expected);
        assert_eq!(s.pairs, expected);
        check(&s.pairs);
    }
    reused_steps
}

#[test]
fn bad_input_is_ignored_and_never_produces_nan() {
    let mut world = World::new(Settings::default());
    floor(&mut world);
    let id = world.add_body(unit_box_at(0.5));
    world.apply_force_at_point(id, Vec3::NAN, Vec3::ZERO);
    world.apply_impulse_at_point(id, Vec3::new(1e30, 0.0, 0.0), Vec3::new(0.0, 1e30, 0.0));
    world.apply_force_at_point(BodyId(99), Vec3::ONE, Vec3::ZERO);
    run(&mut world, 1.0);
    let body = world.body(id);
    assert!(body.pose().is_finite() && body.linear_velocity().is_finite());
    assert!(body.linear_velocity().length() <= world.settings().max_linear_speed * 1.001);
}
