//! Rasterizer coverage: exact regions, the fill rule over shared edges, projections, odd sizes and
//! broken input. Pixel sets are compared exactly; test geometry keeps edges at least 0.01 px away
//! from pixel centres where exact coverage is asserted.

use glam::{Quat, Vec2, Vec3};
use nudge::color::Rgb;
use nudge::geometry::{Camera, Pose, Projection, Shape, Viewport};
use nudge::render::raster::{Cull, TriangleSetup};
use nudge::render::{Drawable, Frame, Material, RenderMode, RenderOptions, Renderer};
use nudge::util::SplitMix64;

use crate::common;

use common::render::{BACKGROUND, cube, options};

fn render(
    viewport: Viewport,
    camera: &Camera,
    drawables: &[Drawable],
    opts: &RenderOptions,
) -> Frame {
    let mut frame = Frame::new(3, 3);
    Renderer::new().render(&mut frame, &viewport, camera, drawables, opts);
    frame
}

/// Pixel centres strictly inside the open interval (lo, hi) of continuous pixel coordinates.
fn centres_between(lo: f64, hi: f64, count: u32) -> Vec<u32> {
    assert!(
        (0..=count)
            .all(|i| ((i as f64 + 0.5) - lo).abs() > 0.01 && ((i as f64 + 0.5) - hi).abs() > 0.01),
        "test geometry puts an edge on a pixel centre"
    );
    (0..count)
        .filter(|&i| lo < i as f64 + 0.5 && (i as f64 + 0.5) < hi)
        .collect()
}

#[test]
fn a_box_seen_head_on_in_orthographic_covers_exactly_its_projected_rectangle() {
    let (w, h) = (40u32, 30u32);
    let viewport = Viewport::new(w, h, 1.0);
    let view_height = 10.0f64;
    let camera = Camera {
        projection: Projection::Orthographic {
            view_height: view_height as f32,
        },
        ..Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0)
    };
    let (centre, half) = (Vec3::new(0.3, -0.7, 0.0), Vec3::new(2.1, 1.3, 0.5));
    let frame = render(
        viewport,
        &camera,
        &[cube(4, centre, half)],
        &options(RenderMode::Flat),
    );

    // Looking along +z with y up, the camera's right is world −x. Visible slab: half-height 5 m,
    // half-width 5 m × aspect; pixel x = (x_view / half_w + 1) w / 2, pixel y = (1 − y_view / half_h) h / 2.
    let half_h = view_height / 2.0;
    let half_w = half_h * w as f64 / h as f64;
    let (cx, cy) = (centre.x as f64, centre.y as f64);
    let (hx, hy) = (half.x as f64, half.y as f64);
    let px = |x_view: f64| (x_view / half_w + 1.0) * w as f64 / 2.0;
    let py = |y_view: f64| (1.0 - y_view / half_h) * h as f64 / 2.0;
    let xs = centres_between(px(-(cx + hx)), px(-(cx - hx)), w);
    let ys = centres_between(py(cy + hy), py(cy - hy), h);
    assert!(xs.len() > 5 && ys.len() > 3);

    for y in 0..h {
        for x in 0..w {
            let inside = xs.contains(&x) && ys.contains(&y);
            if inside {
                assert_eq!(frame.id_at(x, y), Some(4), "({x}, {y}) should be the box");
                assert_ne!(frame.pixel(x, y), BACKGROUND);
            } else {
                assert_eq!(frame.id_at(x, y), None, "({x}, {y}) should be background");
                assert_eq!(frame.pixel(x, y), BACKGROUND);
            }
        }
    }
}

/// A jittered grid of points, some snapped onto pixel centres, pixel corners or half-pixels so that
/// edges pass exactly through sample points, triangulated with random diagonals.
fn random_mesh(rng: &mut SplitMix64, w: u32, h: u32, cells: usize) -> Vec<[Vec2; 3]> {
    let n = cells + 1;
    let step = Vec2::new((w + 4) as f32 / cells as f32, (h + 4) as f32 / cells as f32);
    let mut grid = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let mut p = Vec2::new(i as f32 * step.x - 2.0, j as f32 * step.y - 2.0);
            let interior = i > 0 && j > 0 && i < cells && j < cells;
            if interior {
                p += Vec2::new(rng.next_signed(), rng.next_signed()) * step * 0.3;
                match rng.next_u64() % 4 {
                    0 => p = p.floor() + Vec2::splat(0.5),
                    1 => p = p.round(),
                    2 => p = (p * 2.0).round() / 2.0,
                    _ => {}
                }
            }
            grid.push(p);
        }
    }
    let mut tris = Vec::new();
    for j in 0..cells {
        for i in 0..cells {
            let a = grid[j * n + i];
            let b = grid[j * n + i + 1];
            let c = grid[(j + 1) * n + i + 1];
            let d = grid[(j + 1) * n + i];
            if rng.next_u64() % 2 == 0 {
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            } else {
                tris.push([a, b, d]);
                tris.push([b, c, d]);
            }
        }
    }
    tris
}

#[test]
fn triangles_sharing_edges_paint_every_pixel_exactly_once() {
    let mut rng = SplitMix64(0x5eed);
    let (w, h) = (37u32, 23u32);
    let mut edges = 0;
    for round in 0..200 {
        let cells = 2 + round % 9;
        let tris = random_mesh(&mut rng, w, h, cells);
        for cull in [Cull::None, Cull::Back] {
            let mut writes = vec![0u32; (w * h) as usize];
            for tri in &tris {
                // The grid's triangles run clockwise as seen on screen (and so in NDC): back faces.
                // Reverse them all for back-face culling; when not culling, reverse a random half so
                // both orientations are exercised.
                let reverse = match cull {
                    Cull::Back => true,
                    Cull::None => rng.next_u64() % 2 == 0,
                };
                let tri = if reverse {
                    [tri[0], tri[2], tri[1]]
                } else {
                    *tri
                };
                if let Some(setup) = TriangleSetup::new(tri, w, h, cull) {
                    setup.for_each_pixel(|i, _| writes[i] += 1);
                }
                edges += 3;
            }
            for (i, &count) in writes.iter().enumerate() {
                assert_eq!(
                    count,
                    1,
                    "round {round} {cull:?}: pixel ({}, {}) painted {count} times",
                    i as u32 % w,
                    i as u32 / w
                );
            }
        }
    }
    assert!(edges > 10_000);
}

#[test]
fn a_fan_around_a_pixel_centre_paints_it_once() {
    let (w, h) = (9u32, 9u32);
    let centre = Vec2::new(4.5, 4.5);
    for spokes in 3..12 {
        let mut writes = vec![0u32; 81];
        let rim: Vec<Vec2> = (0..spokes)
            .map(|k| {
                let a = k as f32 / spokes as f32 * std::f32::consts::TAU;
                // Scaled so the fan covers the whole image.
                centre + 12.0 * Vec2::new(a.cos(), a.sin())
            })
            .collect();
        for k in 0..spokes {
            let tri = [centre, rim[k], rim[(k + 1) % spokes]];
            if let Some(setup) = TriangleSetup::new(tri, w, h, Cull::None) {
                setup.for_each_pixel(|i, _| writes[i] += 1);
            }
        }
        assert!(
            writes.iter().all(|&c| c == 1),
            "{spokes} spokes: {writes:?}"
        );
    }
}

#[test]
fn perspective_shrinks_distant_boxes_and_orthographic_does_not() {
    let viewport = Viewport::new(120, 60, 1.0);
    let near = cube(1, Vec3::new(-3.0, 0.0, 4.0), Vec3::splat(0.8));
    let far = cube(2, Vec3::new(3.0, 0.0, 14.0), Vec3::splat(0.8));
    let eye = Camera::perspective(Vec3::new(0.0, 0.0, -6.0), Vec3::new(0.0, 0.0, 5.0), 1.0);
    let count = |frame: &Frame, id: u32| frame.ids().iter().filter(|&&i| i == id).count();

    let frame = render(viewport, &eye, &[near, far], &options(RenderMode::Flat));
    let (n, f) = (count(&frame, 1), count(&frame, 2));
    assert!(n > 3 * f && f > 0, "perspective: near {n} px, far {f} px");

    let ortho = eye.toggled_projection(1.0);
    let frame = render(viewport, &ortho, &[near, far], &options(RenderMode::Flat));
    let (n, f) = (count(&frame, 1), count(&frame, 2));
    assert!(
        n > 0 && n.abs_diff(f) <= 2,
        "orthographic: near {n} px, far {f} px"
    );
}

#[test]
fn the_side_of_a_long_box_shows_in_perspective_only() {
    // A beam along +z, left of the line of sight: its +x side faces the eye. In perspective that side
    // is seen; an orthographic view along +z sees it edge-on, so only the front face shows.
    let beam = cube(3, Vec3::new(-2.0, 0.0, 10.0), Vec3::new(0.5, 0.5, 10.0));
    let camera = Camera::perspective(Vec3::new(0.0, 0.0, -5.0), Vec3::new(0.0, 0.0, 5.0), 1.0);
    let viewport = Viewport::new(80, 60, 1.0);
    // Normals mode: the +x side is (255, 128, 128), the −z front face (128, 128, 0).
    let side = Rgb::new(255, 128, 128);
    let front = Rgb::new(128, 128, 0);
    let count = |frame: &Frame, c: Rgb| frame.pixels().iter().filter(|&&p| p == c).count();

    let frame = render(viewport, &camera, &[beam], &options(RenderMode::Normals));
    assert!(count(&frame, side) > 20, "perspective shows the side face");
    assert!(count(&frame, front) > 0);

    let frame = render(
        viewport,
        &camera.toggled_projection(1.0),
        &[beam],
        &options(RenderMode::Normals),
    );
    assert_eq!(count(&frame, side), 0, "orthographic sees the side edge-on");
    assert!(count(&frame, front) > 20);
}

#[test]
fn tiny_and_odd_buffer_sizes_render_in_every_mode() {
    let drawables = [
        cube(1, Vec3::ZERO, Vec3::splat(2.5)),
        Drawable::new(
            Shape::sphere(0.7),
            Pose::from_position(Vec3::new(1.5, 0.5, -0.5)),
            Rgb::WHITE,
            2,
        ),
    ];
    let camera = Camera::perspective(Vec3::new(0.5, 1.0, -6.0), Vec3::ZERO, 1.0);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(5, 5);
    for (w, h) in [
        (0, 0),
        (0, 7),
        (7, 0),
        (1, 1),
        (1, 2),
        (2, 1),
        (3, 7),
        (400, 240),
        (1, 1),
    ] {
        for mode in RenderMode::ALL {
            for supersample in [false, true] {
                let opts = RenderOptions {
                    supersample,
                    ..options(mode)
                };
                let viewport = Viewport::new(w, h, 1.0);
                renderer.render(&mut frame, &viewport, &camera, &drawables, &opts);
                let len = (w * h) as usize;
                assert_eq!((frame.width(), frame.height()), (w, h));
                assert_eq!(frame.pixels().len(), len);
                assert_eq!(frame.ids().len(), len);
                assert_eq!(frame.depths().len(), len);
                if len > 0 {
                    // The box covers the image centre whatever the size.
                    assert_eq!(frame.id_at(w / 2, h / 2), Some(1), "{w}x{h} {mode}");
                }
            }
        }
    }
}

#[test]
fn nan_and_infinite_inputs_are_skipped_without_harm() {
    let good = cube(1, Vec3::ZERO, Vec3::splat(1.0));
    // Non-finite inputs (ids 10..=14) must never show; finite but absurd ones (ids 20..=23) may show
    // wherever they land, but must not panic or corrupt the frame.
    let mut broken = Vec::new();
    for (bad, id) in [
        (f32::NAN, 10),
        (f32::INFINITY, 10),
        (f32::NEG_INFINITY, 10),
        (1e30, 20),
        (-1e30, 20),
    ] {
        broken.push(cube(id, Vec3::new(bad, 0.0, 0.0), Vec3::splat(1.0)));
        broken.push(cube(
            id + 1,
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(1.0, bad, 1.0),
        ));
        broken.push(Drawable::new(
            Shape::sphere(bad),
            Pose::from_position(Vec3::new(1.0, 1.0, 1.0)),
            Rgb::WHITE,
            id + 2,
        ));
        let mut d = cube(id + 3, Vec3::new(1.0, 0.0, 0.0), Vec3::splat(0.5));
        d.pose.rotation = Quat::from_xyzw(bad, 0.0, 0.0, 1.0);
        broken.push(d);
    }
    let mut zero_rotation = cube(14, Vec3::new(-1.0, 0.0, 0.0), Vec3::splat(0.5));
    zero_rotation.pose.rotation = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
    broken.push(zero_rotation);
    broken.push(cube(24, Vec3::new(0.0, 0.0, 3.0e4), Vec3::splat(2.0e4)));
    broken.push(cube(
        Frame::NO_ID,
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::splat(0.5),
    ));

    let camera = Camera::perspective(Vec3::new(0.0, 0.5, -6.0), Vec3::ZERO, 1.0);
    let viewport = Viewport::new(64, 48, 1.0);
    for mode in RenderMode::ALL {
        for supersample in [false, true] {
            let mut all = broken.clone();
            all.push(good);
            let opts = RenderOptions {
                supersample,
                ..options(mode)
            };
            let frame = render(viewport, &camera, &all, &opts);
            assert!(
                frame.ids().contains(&1),
                "{mode}: the good box is still drawn"
            );
            for id in 10..=14 {
                assert!(
                    !frame.ids().contains(&id),
                    "{mode}: non-finite drawable {id} drawn"
                );
            }
            assert!(frame.depths().iter().all(|d| !d.is_nan()));
        }
    }

    let mut nan_camera = camera;
    nan_camera.position.x = f32::NAN;
    let frame = render(
        viewport,
        &nan_camera,
        &[good],
        &options(RenderMode::Textured),
    );
    assert!(frame.pixels().iter().all(|&p| p == BACKGROUND));
}

#[test]
fn random_scenes_cameras_and_sizes_never_break_the_buffers() {
    // Random bodies (some huge, tiny, far, non-finite), cameras (some inside bodies, some degenerate)
    // and image sizes, in every mode: the frame must always have the viewport's size, ids must name
    // drawn drawables, and covered depths must lie in [0, 1] (up to 1e-4 of rounding).
    let mut rng = SplitMix64(0xdecade);
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(0, 0);
    let mut rounds_with_something_drawn = 0;
    let wild = |rng: &mut SplitMix64, scale: f32| match rng.next_u64() % 12 {
        0 => f32::NAN,
        1 => 1e20 * rng.next_signed(),
        2 => 1e-20,
        _ => scale * rng.next_signed(),
    };
    for round in 0..150 {
        let count = (rng.next_u64() % 12) as u32;
        let drawables: Vec<Drawable> = (0..count)
            .map(|id| {
                let shape = if rng.next_u64() % 2 == 0 {
                    Shape::cuboid(Vec3::new(
                        wild(&mut rng, 3.0).abs(),
                        wild(&mut rng, 3.0).abs(),
                        wild(&mut rng, 3.0).abs(),
                    ))
                } else {
                    Shape::sphere(wild(&mut rng, 3.0).abs())
                };
                let position = Vec3::new(
                    wild(&mut rng, 8.0),
                    wild(&mut rng, 8.0),
                    wild(&mut rng, 8.0),
                );
                let rotation = Quat::from_xyzw(
                    wild(&mut rng, 1.0),
                    wild(&mut rng, 1.0),
                    wild(&mut rng, 1.0),
                    wild(&mut rng, 1.0),
                );
                let mut d = Drawable::new(shape, Pose::new(position, rotation), Rgb::WHITE, id);
                d.receives_shadow = rng.next_u64() % 3 == 0;
                d.highlighted = rng.next_u64() % 4 == 0;
                d.material =
                    [Material::Wood, Material::Checker, Material::Plain][(id % 3) as usize];
                d
            })
            .collect();
        let mut camera = Camera::perspective(
            Vec3::new(
                wild(&mut rng, 10.0),
                wild(&mut rng, 10.0),
                wild(&mut rng, 10.0),
            ),
            Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed()),
            0.2 + 2.5 * rng.next_unit(),
        );
        camera.near = 0.01 + rng.next_unit();
        if rng.next_u64() % 2 == 0 {
            camera = camera.toggled_projection(1.0);
        }
        let viewport = Viewport::new(
            (rng.next_u64() % 48) as u32,
            (rng.next_u64() % 32) as u32,
            0.5 + 2.0 * rng.next_unit(),
        );
        let mode = RenderMode::ALL[round % RenderMode::ALL.len()];
        let opts = RenderOptions {
            mode,
            supersample: rng.next_u64() % 3 == 0,
            shadows: true,
            ..RenderOptions::default()
        };
        renderer.render(&mut frame, &viewport, &camera, &drawables, &opts);
        let len = viewport.width as usize * viewport.height as usize;
        assert_eq!(frame.pixels().len(), len);
        if frame.ids().iter().any(|&id| id != Frame::NO_ID) {
            rounds_with_something_drawn += 1;
        }
        for (&id, &z) in frame.ids().iter().zip(frame.depths()) {
            if id == Frame::NO_ID {
                assert!(z.is_infinite(), "round {round}: background with depth {z}");
            } else {
                assert!(
                    drawables[id as usize].is_drawable(),
                    "round {round}: id {id}"
                );
                assert!(
                    (-1e-4..=1.0 + 1e-4).contains(&z),
                    "round {round}: depth {z}"
                );
            }
        }
    }
    assert!(
        rounds_with_something_drawn > 25,
        "only {rounds_with_something_drawn} rounds drew anything"
    );
}
