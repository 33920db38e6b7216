//! The id buffer agrees with picking rays: for every pixel, the drawable the renderer shows at the
//! pixel centre is the one `Camera::ray_through_ndc` enters first within `Camera::visible_range`
//! (via `Ray::cast`). Tolerance: at least 99.5 % of the pixels covered in either buffer agree, and
//! every disagreement sits on a silhouette (its 3 × 3 neighbourhood shows more than one id in the id
//! buffer or in the ray-cast buffer), where vertex snapping may flip a pixel of a box's edge. Balls
//! are ray cast by the renderer as by picking, so on them the two agree exactly
//! (`tests/app/picking.rs`, `a_ball_is_picked_exactly_where_it_is_drawn_to_the_pixel`).

use glam::{Quat, Vec3};
use nudge::color::Rgb;
use nudge::geometry::{Camera, Pose, Projection, Shape, Viewport};
use nudge::render::{Drawable, Frame, RenderMode, RenderOptions, Renderer};

fn boxed(id: u32, centre: Vec3, half: Vec3, rotation: Quat) -> Drawable {
    Drawable::new(
        Shape::cuboid(half),
        Pose::new(centre, rotation),
        Rgb::new(200, 120, 60),
        id,
    )
}

fn ball(id: u32, centre: Vec3, radius: f32) -> Drawable {
    Drawable::new(
        Shape::sphere(radius),
        Pose::from_position(centre),
        Rgb::new(60, 120, 200),
        id,
    )
}

/// The id of the first drawable each pixel's picking ray enters, row-major.
fn ray_ids(viewport: &Viewport, camera: &Camera, drawables: &[Drawable]) -> Vec<u32> {
    let aspect = viewport.aspect();
    let mut out = Vec::new();
    for y in 0..viewport.height {
        for x in 0..viewport.width {
            let ray = camera.ray_through_ndc(viewport.ndc_of_pixel_center(x, y), aspect);
            let (t_min, mut t_max) = camera.visible_range(&ray);
            let mut best = Frame::NO_ID;
            for d in drawables {
                if let Some(hit) = ray.cast(&d.shape, &d.pose, t_min, t_max) {
                    t_max = hit.t;
                    best = d.id;
                }
            }
            out.push(best);
        }
    }
    out
}

fn on_silhouette(ids: &[u32], w: usize, h: usize, x: usize, y: usize) -> bool {
    let centre = ids[y * w + x];
    for ny in y.saturating_sub(1)..(y + 2).min(h) {
        for nx in x.saturating_sub(1)..(x + 2).min(w) {
            if ids[ny * w + nx] != centre {
                return true;
            }
        }
    }
    false
}

/// Renders and compares with ray casts; returns the number of covered pixels.
fn assert_ids_match_rays(
    name: &str,
    viewport: Viewport,
    camera: &Camera,
    drawables: &[Drawable],
    supersample: bool,
) -> usize {
    let mut renderer = Renderer::new();
    let mut frame = Frame::new(1, 1);
    let options = RenderOptions {
        mode: RenderMode::Flat,
        supersample,
        ..RenderOptions::default()
    };
    renderer.render(&mut frame, &viewport, camera, drawables, &options);
    let expected = ray_ids(&viewport, camera, drawables);
    let (w, h) = (viewport.width as usize, viewport.height as usize);
    let drawn = frame.ids();
    let mut covered = 0;
    let mut disagree = 0;
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if drawn[i] == Frame::NO_ID && expected[i] == Frame::NO_ID {
                continue;
            }
            covered += 1;
            if drawn[i] != expected[i] {
                disagree += 1;
                assert!(
                    on_silhouette(drawn, w, h, x, y) || on_silhouette(&expected, w, h, x, y),
                    "{name}: pixel ({x}, {y}) shows {} but the ray hits {} away from any edge",
                    drawn[i],
                    expected[i]
                );
            }
        }
    }
    assert!(covered > 0, "{name}: nothing drawn");
    let agreement = 1.0 - disagree as f64 / covered as f64;
    assert!(
        agreement >= 0.995,
        "{name}: only {:.2} % of {covered} covered pixels agree",
        agreement * 100.0
    );
    covered
}

fn both_projections(camera: Camera) -> [Camera; 2] {
    let fov = 60f32.to_radians();
    let perspective = Camera {
        projection: Projection::Perspective { fov_y: fov },
        ..camera
    };
    [perspective, perspective.toggled_projection(fov)]
}

fn scattered_scene() -> Vec<Drawable> {
    let mut d = vec![boxed(
        0,
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(12.0, 0.5, 12.0),
        Quat::IDENTITY,
    )];
    let mut id = 1;
    for i in 0..5 {
        for j in 0..4 {
            let centre = Vec3::new(
                i as f32 * 2.1 - 4.0,
                0.9 + 0.3 * j as f32,
                j as f32 * 2.3 - 3.0,
            );
            let rotation = Quat::from_euler(
                glam::EulerRot::XYZ,
                0.3 * i as f32,
                0.7 * j as f32,
                0.11 * (i + j) as f32,
            );
            if (i + j) % 3 == 0 {
                d.push(ball(id, centre, 0.55 + 0.1 * j as f32));
            } else {
                d.push(boxed(id, centre, Vec3::new(0.6, 0.4, 0.5), rotation));
            }
            id += 1;
        }
    }
    d
}

#[test]
fn ids_match_rays_for_scattered_boxes_and_spheres_in_both_projections() {
    let drawables = scattered_scene();
    let camera = Camera::perspective(Vec3::new(3.0, 6.0, -11.0), Vec3::new(0.0, 0.5, 0.0), 1.0);
    for camera in both_projections(camera) {
        for viewport in [Viewport::new(160, 96, 1.0), Viewport::new(121, 77, 2.0)] {
            let name = format!(
                "{:?} {}x{}",
                camera.projection, viewport.width, viewport.height
            );
            let covered = assert_ids_match_rays(&name, viewport, &camera, &drawables, false);
            assert!(covered > viewport.width as usize * viewport.height as usize / 4);
        }
    }
}

#[test]
fn ids_stay_exact_with_supersampling() {
    let drawables = scattered_scene();
    let camera = Camera::perspective(Vec3::new(-4.0, 5.0, -9.0), Vec3::new(0.0, 0.5, 0.0), 1.0);
    for camera in both_projections(camera) {
        let name = format!("supersampled {:?}", camera.projection);
        assert_ids_match_rays(
            &name,
            Viewport::new(100, 60, 1.0),
            &camera,
            &drawables,
            true,
        );
    }
}

#[test]
fn ids_match_rays_for_a_pyramid_seen_from_a_corner() {
    let mut drawables = vec![boxed(
        0,
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(20.0, 0.5, 20.0),
        Quat::IDENTITY,
    )];
    let mut id = 1;
    for row in 0..6 {
        for i in 0..6 - row {
            let x = (i as f32 - 0.5 * (5 - row) as f32) * 1.05;
            drawables.push(boxed(
                id,
                Vec3::new(x, 0.5 + row as f32, 0.0),
                Vec3::splat(0.5),
                Quat::IDENTITY,
            ));
            id += 1;
        }
    }
    let camera = Camera::perspective(Vec3::new(7.0, 4.0, -8.0), Vec3::new(0.0, 2.0, 0.0), 1.0);
    for camera in both_projections(camera) {
        let name = format!("pyramid {:?}", camera.projection);
        assert_ids_match_rays(
            &name,
            Viewport::new(140, 90, 1.0),
            &camera,
            &drawables,
            false,
        );
    }
}

#[test]
fn a_box_straddling_the_near_plane_shows_exactly_its_visible_part() {
    // The camera hovers just above a long slab that extends behind it: the near plane cuts the top
    // face, whose visible part must fill the lower half of the image up to the slab's far edge,
    // with nothing smeared above the horizon and no face lost.
    let slab = boxed(
        7,
        Vec3::new(0.0, -0.6, 1.0),
        Vec3::new(3.0, 0.5, 4.0),
        Quat::from_rotation_y(0.2),
    );
    let ahead = ball(8, Vec3::new(0.5, 0.3, 6.0), 0.6);
    let camera = Camera {
        near: 0.3,
        ..Camera::perspective(Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, -0.4, 1.0), 1.2)
    };
    for camera in both_projections(camera) {
        let name = format!("near-plane slab {:?}", camera.projection);
        let viewport = Viewport::new(120, 80, 1.0);
        assert_ids_match_rays(&name, viewport, &camera, &[slab, ahead], false);
    }
}

#[test]
fn a_camera_inside_a_box_sees_through_it_to_what_is_outside() {
    let room = boxed(
        1,
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::splat(2.0),
        Quat::from_rotation_z(0.3),
    );
    let outside = boxed(
        2,
        Vec3::new(0.3, 0.0, 6.0),
        Vec3::splat(1.0),
        Quat::from_rotation_x(0.5),
    );
    let camera = Camera::perspective(Vec3::new(0.2, 0.1, -0.5), Vec3::new(0.0, 0.0, 5.0), 1.2);
    for camera in both_projections(camera) {
        let name = format!("inside {:?}", camera.projection);
        let viewport = Viewport::new(90, 60, 1.0);
        assert_ids_match_rays(&name, viewport, &camera, &[room, outside], false);
        let mut frame = Frame::new(1, 1);
        Renderer::new().render(
            &mut frame,
            &viewport,
            &camera,
            &[room, outside],
            &RenderOptions::default(),
        );
        // An orthographic camera is a plane, not a point: rays from the parts of the plane outside
        // the box do hit it, so only the perspective eye is truly inside.
        if matches!(camera.projection, Projection::Perspective { .. }) {
            assert!(
                !frame.ids().contains(&1),
                "{name}: the box around the eye is culled"
            );
        }
        assert!(frame.ids().contains(&2), "{name}: the box outside is seen");
    }
}

#[test]
fn a_huge_floor_under_a_tiny_near_plane_is_drawn_whole() {
    // The floor's triangles pass behind the eye; cut at a 1 mm near plane they reach 10⁵ NDC units
    // sideways, far beyond the guard band, so the near-clipped polygons must be clipped again.
    let floor = boxed(
        3,
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(100.0, 0.5, 100.0),
        Quat::from_rotation_y(0.3),
    );
    let camera = Camera {
        near: 0.001,
        ..Camera::perspective(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.6, 5.0), 1.2)
    };
    for viewport in [Viewport::new(200, 100, 1.0), Viewport::new(37, 23, 1.0)] {
        let covered = assert_ids_match_rays("huge floor", viewport, &camera, &[floor], false);
        assert!(covered > viewport.width as usize * viewport.height as usize / 3);
    }
}
