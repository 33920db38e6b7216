//! What each mode and state flag does to the picture, asserted on pixels and ids.

use glam::{Quat, Vec3};
use nudge::color::Rgb;
use nudge::geometry::{Camera, Pose, Projection, Shape, Viewport};
use nudge::render::{Drawable, Frame, Material, RenderMode, RenderOptions, Renderer};

use crate::common;

use common::render::{BACKGROUND, cube, options};

fn head_on() -> Camera {
    Camera {
        projection: Projection::Orthographic { view_height: 6.0 },
        ..Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0)
    }
}

fn render(camera: &Camera, drawables: &[Drawable], opts: &RenderOptions) -> Frame {
    let mut frame = Frame::new(1, 1);
    Renderer::new().render(
        &mut frame,
        &Viewport::new(60, 40, 1.0),
        camera,
        drawables,
        opts,
    );
    frame
}

fn pixels_of(frame: &Frame, id: u32) -> Vec<Rgb> {
    frame
        .pixels()
        .iter()
        .zip(frame.ids())
        .filter(|&(_, &i)| i == id)
        .map(|(&p, _)| p)
        .collect()
}

fn mean(pixels: &[Rgb]) -> [f64; 3] {
    let n = pixels.len().max(1) as f64;
    let sum = pixels.iter().fold([0.0; 3], |s, p| {
        [s[0] + p.r as f64, s[1] + p.g as f64, s[2] + p.b as f64]
    });
    sum.map(|c| c / n)
}

fn distinct(pixels: &[Rgb]) -> usize {
    let mut v = pixels.to_vec();
    v.sort_by_key(|p| (p.r, p.g, p.b));
    v.dedup();
    v.len()
}

#[test]
fn flat_faces_are_uniform_and_textured_wood_is_not() {
    let mut d = cube(1, Vec3::ZERO, Vec3::new(2.0, 1.5, 0.5));
    d.material = Material::Wood;
    let flat = render(&head_on(), &[d], &options(RenderMode::Flat));
    assert_eq!(distinct(&pixels_of(&flat, 1)), 1);
    let textured = render(&head_on(), &[d], &options(RenderMode::Textured));
    assert!(distinct(&pixels_of(&textured, 1)) > 5, "wood grain shows");
}

#[test]
fn a_checker_floor_alternates_and_a_plain_sphere_shows_stripes() {
    let mut floor = cube(1, Vec3::new(0.0, 0.0, 0.0), Vec3::new(2.0, 2.0, 0.5));
    floor.material = Material::Checker;
    let frame = render(&head_on(), &[floor], &options(RenderMode::Textured));
    // Two shades on the squares; a pixel a square's edge crosses shows the share of each it covers
    // (the checker is box-filtered over the pixel), so it lies between them.
    let face = pixels_of(&frame, 1);
    let (dark, light) = (
        face.iter().map(|p| p.r).min().unwrap(),
        face.iter().map(|p| p.r).max().unwrap(),
    );
    let count = |r: u8| face.iter().filter(|p| p.r == r).count();
    let between = face.len() - count(dark) - count(light);
    assert!(
        f64::from(light) > 1.15 * f64::from(dark),
        "{dark} vs {light}"
    );
    assert!(count(dark) > 0 && count(light) > 0);
    // Measured: 100 of 676 pixels (15 %) between, on the 3 edges a row of 4 squares 6.5 px wide
    // has; the squares' insides stay the two shades.
    assert!(
        between * 4 < face.len(),
        "{between} of {} px on edges",
        face.len()
    );

    let ball = Drawable::new(
        Shape::sphere(2.5),
        Pose::new(Vec3::ZERO, Quat::from_rotation_x(0.3)),
        Rgb::new(120, 120, 120),
        2,
    );
    let smooth = render(&head_on(), &[ball], &options(RenderMode::Smooth));
    let textured = render(&head_on(), &[ball], &options(RenderMode::Textured));
    let darker = smooth
        .pixels()
        .iter()
        .zip(textured.pixels())
        .filter(|(s, t)| (t.r as i32) < s.r as i32 - 5)
        .count();
    assert!(
        darker > 50,
        "stripes darken part of the sphere ({darker} px)"
    );
}

#[test]
fn normals_mode_colours_a_face_by_its_world_normal() {
    let turned = Drawable {
        pose: Pose::new(
            Vec3::ZERO,
            Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
        ),
        ..cube(1, Vec3::ZERO, Vec3::splat(1.0))
    };
    let frame = render(&head_on(), &[turned], &options(RenderMode::Normals));
    // The face toward the camera has world normal −z whatever the body's rotation: (128, 128, 0),
    // within one step of rounding.
    let p = frame.pixel(30, 20);
    assert!(
        p.r.abs_diff(128) <= 1 && p.g.abs_diff(128) <= 1 && p.b <= 1,
        "{p:?}"
    );
}

#[test]
fn depth_mode_paints_nearer_surfaces_brighter() {
    let near = cube(1, Vec3::new(-1.5, 0.0, -2.0), Vec3::splat(1.0));
    let far = cube(2, Vec3::new(1.5, 0.0, 4.0), Vec3::splat(1.0));
    let camera = Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 1.0);
    let frame = render(&camera, &[near, far], &options(RenderMode::Depth));
    let (a, b) = (mean(&pixels_of(&frame, 1)), mean(&pixels_of(&frame, 2)));
    assert!(a[0] > b[0] + 30.0, "near {a:?} vs far {b:?}");
    assert_eq!(a[0], a[2], "grey");
}

#[test]
fn wireframe_draws_edges_but_ids_still_cover_faces() {
    let d = cube(1, Vec3::ZERO, Vec3::new(2.0, 1.5, 0.5));
    let frame = render(&head_on(), &[d], &options(RenderMode::Wireframe));
    let covered = pixels_of(&frame, 1);
    let drawn = covered.iter().filter(|&&p| p != BACKGROUND).count();
    assert!(drawn > 20, "edges drawn");
    assert!(drawn < covered.len() / 2, "faces not filled");
    assert_eq!(frame.pixel(30, 20), BACKGROUND, "face interior is empty");
    assert_eq!(frame.id_at(30, 20), Some(1));
}

#[test]
fn frozen_bodies_are_icy_asleep_ones_dim_and_highlighted_ones_bright_and_outlined() {
    let base = cube(1, Vec3::ZERO, Vec3::new(2.0, 1.5, 0.5));
    let plain = mean(&pixels_of(
        &render(&head_on(), &[base], &options(RenderMode::Flat)),
        1,
    ));
    let look = |change: fn(&mut Drawable)| {
        let mut d = base;
        change(&mut d);
        render(&head_on(), &[d], &options(RenderMode::Flat))
    };

    let frozen = mean(&pixels_of(&look(|d| d.frozen = true), 1));
    assert!(
        frozen[2] > plain[2] + 40.0 && frozen[2] > frozen[0],
        "{frozen:?}"
    );

    let asleep = mean(&pixels_of(&look(|d| d.asleep = true), 1));
    assert!(
        asleep.iter().zip(plain).all(|(a, p)| *a < p - 10.0),
        "{asleep:?}"
    );

    let frame = look(|d| d.highlighted = true);
    let outline = RenderOptions::default().outline;
    let on_outline = pixels_of(&frame, 1)
        .iter()
        .filter(|&&p| p == outline)
        .count();
    assert!(on_outline > 20, "outline drawn");
    assert_ne!(
        frame.pixel(30, 20),
        outline,
        "the outline stays at the silhouette"
    );
    assert!(
        frame.pixel(30, 20).r as f64 > plain[0] + 10.0,
        "brighter inside"
    );
}

/// Renders `drawables` without and with shadows (flat mode, 80 × 60) into two frames.
fn lit_and_shaded(camera: &Camera, drawables: &[Drawable]) -> (Frame, Frame) {
    lit_and_shaded_in(camera, drawables, RenderMode::Flat)
}

fn lit_and_shaded_in(camera: &Camera, drawables: &[Drawable], mode: RenderMode) -> (Frame, Frame) {
    let viewport = Viewport::new(80, 60, 1.0);
    let mut renderer = Renderer::new();
    let mut lit = Frame::new(1, 1);
    let mut shaded = Frame::new(1, 1);
    let opts = options(mode);
    renderer.render(&mut lit, &viewport, camera, drawables, &opts);
    let with_shadows = RenderOptions {
        shadows: true,
        ..opts
    };
    renderer.render(&mut shaded, &viewport, camera, drawables, &with_shadows);
    (lit, shaded)
}

/// The pixel showing world point `p` (its centre's pixel), if it is in the 80 × 60 image.
fn pixel_of(camera: &Camera, p: Vec3) -> Option<(u32, u32)> {
    let viewport = Viewport::new(80, 60, 1.0);
    let clip = camera.clip_from_world(viewport.aspect()) * p.extend(1.0);
    let ndc = glam::Vec2::new(clip.x / clip.w, clip.y / clip.w);
    let q = viewport.pixel_from_ndc(ndc);
    (q.x >= 0.0 && q.y >= 0.0 && q.x < 80.0 && q.y < 60.0).then_some((q.x as u32, q.y as u32))
}

/// Where the ray from `p` along the light meets the plane `y = height`.
fn along_light_to_height(p: Vec3, height: f32) -> Vec3 {
    let light = Renderer::new().lights().key_dir;
    p - light * ((p.y - height) / light.y)
}

/// The pixel showing world point `foot` shows drawable `receiver` and is darker with shadows than
/// without (`what` names the case in failure messages).
fn assert_dark_at(
    camera: &Camera,
    lit: &Frame,
    shaded: &Frame,
    foot: Vec3,
    receiver: u32,
    what: &str,
) {
    let (x, y) =
        pixel_of(camera, foot).unwrap_or_else(|| panic!("{what}: the point is off the image"));
    assert_eq!(
        shaded.id_at(x, y),
        Some(receiver),
        "{what}: the point shows the receiver"
    );
    let (a, b) = (lit.pixel(x, y), shaded.pixel(x, y));
    assert!(
        b.r < a.r && b.g < a.g,
        "{what}: the point is dark ({a:?} -> {b:?})"
    );
}

/// Every changed pixel got darker in all channels and kept its id; returns how many changed and
/// their ids.
fn darkened_pixels(lit: &Frame, shaded: &Frame) -> Vec<u32> {
    assert_eq!(lit.ids(), shaded.ids(), "shadows never change ids");
    let mut ids = Vec::new();
    for (i, (a, b)) in lit.pixels().iter().zip(shaded.pixels()).enumerate() {
        if a != b {
            assert!(b.r <= a.r && b.g <= a.g && b.b <= a.b, "{a:?} -> {b:?}");
            assert!(b.r < a.r || b.g < a.g || b.b < a.b);
            ids.push(shaded.ids()[i]);
        }
    }
    ids
}

#[test]
fn shadows_darken_the_floor_at_the_casters_foot_point_along_the_light() {
    let floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(8.0, 0.5, 8.0));
    let caster_centre = Vec3::new(0.0, 2.0, 0.0);
    let caster = cube(1, caster_centre, Vec3::splat(0.6));
    let camera = Camera::perspective(Vec3::new(0.0, 9.0, -9.0), Vec3::ZERO, 1.0);
    let (lit, shaded) = lit_and_shaded(&camera, &[floor, caster]);
    let darkened = darkened_pixels(&lit, &shaded);
    assert!(
        darkened.len() > 10,
        "a shadow is cast ({} px)",
        darkened.len()
    );
    assert!(
        darkened.iter().all(|&id| id == 0),
        "only the floor is darkened: the caster is lit, and never shadows itself"
    );
    let foot = along_light_to_height(caster_centre, 0.0);
    assert_dark_at(
        &camera,
        &lit,
        &shaded,
        foot,
        0,
        "the caster's foot on the floor",
    );
}

#[test]
fn a_small_box_on_a_big_dynamic_box_darkens_the_big_boxs_top_under_it_along_the_light() {
    let big = cube(1, Vec3::new(0.0, 1.0, 0.0), Vec3::new(3.0, 1.0, 3.0));
    let small_centre = Vec3::new(0.0, 2.6, 0.0);
    let small = cube(2, small_centre, Vec3::splat(0.6));
    // Seen from where the light goes (+x, +z), so the shadow is in front of the small box.
    let camera = Camera::perspective(Vec3::new(6.0, 9.0, 7.0), Vec3::new(0.0, 2.0, 0.0), 1.0);
    let (lit, shaded) = lit_and_shaded(&camera, &[big, small]);
    let darkened = darkened_pixels(&lit, &shaded);
    let on_big = darkened.iter().filter(|&&id| id == 1).count();
    assert!(on_big > 5, "the big box's top is shadowed ({on_big} px)");
    assert!(!darkened.contains(&2), "the small box is lit");
    // The light grazing the centre of the small box's top meets the big box's top beyond it.
    let top_centre = small_centre + Vec3::Y * 0.6;
    let foot = along_light_to_height(top_centre, 2.0);
    assert_dark_at(
        &camera,
        &lit,
        &shaded,
        foot,
        1,
        "the small box's foot on the big box",
    );
}

#[test]
fn a_body_never_darkens_itself() {
    let rotated = Drawable {
        pose: Pose::new(
            Vec3::new(0.3, 1.0, 0.2),
            Quat::from_rotation_z(0.5) * Quat::from_rotation_x(0.7),
        ),
        ..cube(1, Vec3::ZERO, Vec3::new(1.5, 0.4, 0.8))
    };
    let ball = Drawable::new(
        Shape::sphere(1.2),
        Pose::from_position(Vec3::new(-1.0, 0.5, 0.0)),
        Rgb::new(200, 200, 200),
        2,
    );
    let camera = Camera::perspective(Vec3::new(2.0, 4.0, -6.0), Vec3::ZERO, 1.0);
    for lone in [rotated, ball] {
        for mode in [RenderMode::Flat, RenderMode::Smooth, RenderMode::Textured] {
            let (lit, shaded) = lit_and_shaded_in(&camera, &[lone], mode);
            assert_eq!(lit, shaded, "{mode:?}");
        }
    }
}

#[test]
fn surfaces_facing_away_from_the_light_are_not_darkened_again() {
    // A box and a ball in the shadow of a big box above them along the light. Seen from the side,
    // their lit faces are darkened; seen from where the light goes, only faces turned away from the
    // light show, and those keep their colour.
    let light = Renderer::new().lights().key_dir;
    let centre = Vec3::new(0.0, 1.0, 0.0);
    let occluder = cube(1, centre - 4.0 * light, Vec3::splat(1.5));
    let boxed = Drawable {
        pose: Pose::new(centre, Quat::from_rotation_y(0.3)),
        ..cube(2, Vec3::ZERO, Vec3::new(0.6, 0.5, 0.4))
    };
    let ball = Drawable::new(
        Shape::sphere(0.5),
        Pose::from_position(centre),
        Rgb::new(200, 200, 200),
        2,
    );
    for receiver in [boxed, ball] {
        let scene = [occluder, receiver];
        let side = Camera::perspective(centre + Vec3::new(-5.0, 1.0, 0.5), centre, 0.8);
        let (lit, shaded) = lit_and_shaded(&side, &scene);
        let darkened = darkened_pixels(&lit, &shaded);
        assert!(
            darkened.iter().filter(|&&id| id == 2).count() > 20,
            "shadowed"
        );
        let downstream = Camera::perspective(centre + 5.0 * light, centre, 0.8);
        for mode in [RenderMode::Flat, RenderMode::Smooth] {
            let (lit, shaded) = lit_and_shaded_in(&downstream, &scene, mode);
            assert!(pixels_of(&lit, 2).len() > 100);
            assert_eq!(pixels_of(&lit, 2), pixels_of(&shaded, 2), "{mode:?}");
        }
    }
}

#[test]
fn a_sphere_on_the_floor_shadows_the_floor() {
    let floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(20.0, 0.5, 20.0));
    let centre = Vec3::new(1.0, 0.8, 0.5);
    let ball = Drawable::new(
        Shape::sphere(0.8),
        Pose::from_position(centre),
        Rgb::new(200, 60, 60),
        1,
    );
    // Seen from where the light goes (+x, +z), so the shadow is in front of the ball.
    let camera = Camera::perspective(Vec3::new(6.0, 6.0, 7.0), Vec3::new(1.0, 0.0, 0.5), 1.0);
    for mode in [RenderMode::Flat, RenderMode::Smooth, RenderMode::Textured] {
        let (lit, shaded) = lit_and_shaded_in(&camera, &[floor, ball], mode);
        let darkened = darkened_pixels(&lit, &shaded);
        assert!(darkened.len() > 10, "{mode:?}: {} px", darkened.len());
        assert!(
            darkened.iter().all(|&id| id == 0),
            "{mode:?}: only the floor"
        );
        let foot = along_light_to_height(centre, 0.0);
        assert_dark_at(&camera, &lit, &shaded, foot, 0, &format!("{mode:?}"));
    }
}

#[test]
fn shadows_stay_put_when_only_the_camera_moves() {
    // Floor points fully shadowed seen from the first camera (found by casting each pixel's picking
    // ray) are darkened, within a pixel, seen from the others wherever the floor shows there; the
    // casters' foot points are dark from every camera that sees them.
    let floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(10.0, 0.5, 10.0));
    let a = cube(1, Vec3::new(-1.5, 1.5, 0.0), Vec3::splat(0.5));
    let b_centre = Vec3::new(1.5, 1.0, 1.0);
    let b = Drawable::new(
        Shape::sphere(0.6),
        Pose::from_position(b_centre),
        Rgb::WHITE,
        2,
    );
    let scene = [floor, a, b];
    let feet = [
        along_light_to_height(a.pose.position, 0.0),
        along_light_to_height(b_centre, 0.0),
    ];
    let viewport = Viewport::new(80, 60, 1.0);
    let cameras = [
        Vec3::new(0.0, 8.0, -9.0),
        Vec3::new(8.0, 7.0, -2.0),
        Vec3::new(-3.0, 9.0, 8.0),
        Vec3::new(5.0, 7.0, 8.0),
    ]
    .map(|eye| Camera::perspective(eye, Vec3::ZERO, 1.1));
    let (lit, shaded) = lit_and_shaded(&cameras[0], &scene);
    let mut dark_points = Vec::new();
    for y in 0..60 {
        for x in 0..80 {
            let (l, s) = (lit.pixel(x, y), shaded.pixel(x, y));
            // Full darkening on the floor: SHADOW_FACTOR (0.58) within rounding.
            if shaded.id_at(x, y) != Some(0) || (s.r as f32) > 0.6 * l.r as f32 {
                continue;
            }
            let ray =
                cameras[0].ray_through_ndc(viewport.ndc_of_pixel_center(x, y), viewport.aspect());
            let (t0, t1) = cameras[0].visible_range(&ray);
            if let Some(hit) = ray.cast(&floor.shape, &floor.pose, t0, t1) {
                dark_points.push(hit.point);
            }
        }
    }
    assert!(
        dark_points.len() > 20,
        "{} dark floor points",
        dark_points.len()
    );
    let mut feet_seen = 0;
    for camera in &cameras {
        let (lit, shaded) = lit_and_shaded(camera, &scene);
        let (mut seen, mut dark) = (0, 0);
        for &p in &dark_points {
            let Some((x, y)) = pixel_of(camera, p) else {
                continue;
            };
            if shaded.id_at(x, y) != Some(0) {
                continue;
            }
            seen += 1;
            // Within a pixel: the pixel centre is up to half a pixel from the point.
            let near_dark = (x.saturating_sub(1)..=x + 1).any(|nx| {
                (y.saturating_sub(1)..=y + 1).any(|ny| {
                    shaded.id_at(nx, ny) == Some(0) && shaded.pixel(nx, ny).r < lit.pixel(nx, ny).r
                })
            });
            dark += usize::from(near_dark);
        }
        assert!(
            seen > 10,
            "{seen} of the points seen from {}",
            camera.position
        );
        assert_eq!(dark, seen, "points still dark from {}", camera.position);
        for foot in feet {
            let Some((x, y)) = pixel_of(camera, foot) else {
                continue;
            };
            if shaded.id_at(x, y) == Some(0) {
                feet_seen += 1;
                assert!(
                    shaded.pixel(x, y).r < lit.pixel(x, y).r,
                    "{foot} dark from {}",
                    camera.position
                );
            }
        }
    }
    assert!(feet_seen >= 4, "foot points seen {feet_seen} times");
}

#[test]
fn degenerate_shadow_scenes_render_without_panicking() {
    let camera = Camera::perspective(Vec3::new(0.0, 5.0, -8.0), Vec3::ZERO, 1.0);
    let shadows = RenderOptions {
        shadows: true,
        ..options(RenderMode::Smooth)
    };
    let far = Vec3::new(5000.0, 0.0, 0.0);
    let far_camera = Camera::perspective(far + Vec3::new(0.0, 5.0, -8.0), far, 1.0);
    let huge_floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(1e6, 0.5, 1e6));
    let scenes: Vec<(Camera, Vec<Drawable>)> = vec![
        (camera, vec![]),
        (camera, vec![huge_floor]),
        (
            camera,
            vec![
                huge_floor,
                cube(1, Vec3::new(0.0, 0.5, 0.0), Vec3::splat(0.5)),
            ],
        ),
        (
            far_camera,
            vec![
                cube(0, far - Vec3::Y * 0.5, Vec3::new(8.0, 0.5, 8.0)),
                cube(1, far + Vec3::new(0.0, 1.0, 0.0), Vec3::splat(0.5)),
                cube(2, Vec3::new(0.0, 1.0, 0.0), Vec3::splat(0.5)),
            ],
        ),
        (
            camera,
            vec![
                cube(0, Vec3::ZERO, Vec3::splat(1e-7)),
                cube(1, Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 1e-6, 1.0)),
                cube(2, Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1e-6)),
            ],
        ),
    ];
    for (camera, drawables) in &scenes {
        let mut frame = Frame::new(1, 1);
        for supersample in [false, true] {
            Renderer::new().render(
                &mut frame,
                &Viewport::new(40, 30, 1.0),
                camera,
                drawables,
                &RenderOptions {
                    supersample,
                    ..shadows
                },
            );
            assert_eq!(frame.pixels().len(), 40 * 30);
        }
    }
    // A body resting on a floor at x = 5000 still shadows it.
    let (lit, shaded) = lit_and_shaded(&far_camera, &scenes[3].1);
    let darkened = darkened_pixels(&lit, &shaded);
    assert!(darkened.len() > 10, "{} px", darkened.len());
}

#[test]
fn supersampling_keeps_ids_and_smooths_only_edges() {
    let d = Drawable {
        pose: Pose::new(Vec3::ZERO, Quat::from_rotation_z(0.4)),
        ..cube(1, Vec3::ZERO, Vec3::new(2.0, 1.2, 0.5))
    };
    let plain = render(&head_on(), &[d], &options(RenderMode::Flat));
    let ss = render(
        &head_on(),
        &[d],
        &RenderOptions {
            supersample: true,
            ..options(RenderMode::Flat)
        },
    );
    assert_eq!(plain.ids(), ss.ids());
    let (w, h) = (plain.width(), plain.height());
    let mut blended = 0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let id = plain.id_at(x, y);
            let interior = [
                (0, 1),
                (2, 1),
                (1, 0),
                (1, 2),
                (0, 0),
                (2, 2),
                (0, 2),
                (2, 0),
            ]
            .iter()
            .all(|&(dx, dy)| plain.id_at(x + dx - 1, y + dy - 1) == id);
            if interior {
                assert_eq!(plain.pixel(x, y), ss.pixel(x, y), "({x}, {y}) interior");
            } else if plain.pixel(x, y) != ss.pixel(x, y) {
                blended += 1;
            }
        }
    }
    assert!(blended > 10, "edges are antialiased");
}

#[test]
fn rendering_again_gives_the_same_frame_whatever_came_before() {
    let scene = [
        cube(1, Vec3::ZERO, Vec3::splat(1.0)),
        Drawable::new(
            Shape::sphere(0.8),
            Pose::from_position(Vec3::new(1.5, 1.0, -1.0)),
            Rgb::WHITE,
            2,
        ),
    ];
    let camera = Camera::perspective(Vec3::new(1.0, 2.0, -6.0), Vec3::ZERO, 1.0);
    let viewport = Viewport::new(50, 30, 1.0);
    let opts = RenderOptions::default();
    let mut fresh = Frame::new(1, 1);
    Renderer::new().render(&mut fresh, &viewport, &camera, &scene, &opts);

    let mut renderer = Renderer::new();
    let mut frame = Frame::new(1, 1);
    let big = Viewport::new(200, 120, 1.0);
    let ss = RenderOptions {
        supersample: true,
        mode: RenderMode::Normals,
        ..opts
    };
    renderer.render(&mut frame, &big, &camera, &scene, &ss);
    renderer.render(&mut frame, &viewport, &camera, &scene, &opts);
    assert_eq!(frame, fresh);
}

#[test]
fn textures_are_perspective_correct() {
    // A checker floor seen at a slant: each pixel's checker square must be the one its picking ray
    // hits. Affine (non-perspective) interpolation would bend the square boundaries away from the
    // true ones by several pixels. Specular is off so the floor shows exactly two colours within 5 m
    // (farther, the checker fades to grey as squares shrink toward a pixel); pixels whose 3 × 3
    // neighbourhood straddles a boundary are skipped.
    let mut floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(6.0, 0.5, 6.0));
    floor.material = Material::Checker;
    let camera = Camera::perspective(Vec3::new(0.3, 2.2, -3.0), Vec3::new(0.0, 0.0, 2.0), 1.2);
    let viewport = Viewport::new(120, 80, 1.0);
    let mut renderer = Renderer::new();
    renderer.set_lights(nudge::render::Lights {
        specular: 0.0,
        ..*renderer.lights()
    });
    let mut frame = Frame::new(1, 1);
    renderer.render(
        &mut frame,
        &viewport,
        &camera,
        &[floor],
        &options(RenderMode::Textured),
    );
    let (w, h) = (viewport.width, viewport.height);
    let parity = |x: u32, y: u32| -> Option<bool> {
        let ray = camera.ray_through_ndc(viewport.ndc_of_pixel_center(x, y), viewport.aspect());
        let (t0, t1) = camera.visible_range(&ray);
        let hit = ray.cast(&floor.shape, &floor.pose, t0, t1.min(5.0))?;
        let p = hit.point - floor.pose.position;
        Some((p.x.floor() as i64 + p.y.floor() as i64 + p.z.floor() as i64) & 1 == 0)
    };
    let mut light = None;
    let mut dark = None;
    let mut checked = 0;
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let Some(even) = parity(x, y) else { continue };
            let uniform =
                (0..3).all(|dy| (0..3).all(|dx| parity(x + dx - 1, y + dy - 1) == Some(even)));
            if !uniform || frame.id_at(x, y) != Some(0) {
                continue;
            }
            let slot = if even { &mut light } else { &mut dark };
            let colour = frame.pixel(x, y);
            let reference: Rgb = *slot.get_or_insert(colour);
            // Within one rounding step of the square's colour.
            assert!(
                reference.r.abs_diff(colour.r) <= 1 && reference.g.abs_diff(colour.g) <= 1,
                "pixel ({x}, {y}) is {colour:?}, its square {reference:?}"
            );
            checked += 1;
        }
    }
    assert!(checked > 2000, "{checked} pixels checked");
    let (light, dark) = (light.unwrap(), dark.unwrap());
    assert!(light.r.abs_diff(dark.r) > 10, "{light:?} vs {dark:?}");
}
