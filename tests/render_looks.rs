//! What each mode and state flag does to the picture, asserted on pixels and ids.

use glam::{Quat, Vec3};
use nudge::color::Rgb;
use nudge::geometry::{Camera, Pose, Projection, Shape, Viewport};
use nudge::render::{Drawable, Frame, Material, RenderMode, RenderOptions, Renderer};

const BACKGROUND: Rgb = Rgb::new(1, 2, 3);

fn options(mode: RenderMode) -> RenderOptions {
    RenderOptions {
        mode,
        background: BACKGROUND,
        shadows: false,
        ..RenderOptions::default()
    }
}

fn cube(id: u32, centre: Vec3, half: Vec3) -> Drawable {
    Drawable::new(
        Shape::cuboid(half),
        Pose::from_position(centre),
        Rgb::new(180, 140, 90),
        id,
    )
}

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
    assert_eq!(
        distinct(&pixels_of(&frame, 1)),
        2,
        "two checker shades on a face"
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

#[test]
fn shadows_darken_only_the_receiver_below_the_caster_along_the_light() {
    let mut floor = cube(0, Vec3::new(0.0, -0.5, 0.0), Vec3::new(8.0, 0.5, 8.0));
    floor.receives_shadow = true;
    floor.casts_shadow = false;
    let caster_centre = Vec3::new(0.0, 2.0, 0.0);
    let caster = cube(1, caster_centre, Vec3::splat(0.6));
    let camera = Camera::perspective(Vec3::new(0.0, 9.0, -9.0), Vec3::ZERO, 1.0);
    let viewport = Viewport::new(80, 60, 1.0);
    let mut renderer = Renderer::new();
    let mut lit = Frame::new(1, 1);
    let mut shaded = Frame::new(1, 1);
    let opts = options(RenderMode::Flat);
    renderer.render(&mut lit, &viewport, &camera, &[floor, caster], &opts);
    let with_shadows = RenderOptions {
        shadows: true,
        ..opts
    };
    renderer.render(
        &mut shaded,
        &viewport,
        &camera,
        &[floor, caster],
        &with_shadows,
    );

    assert_eq!(lit.ids(), shaded.ids());
    let mut darkened = 0;
    for (i, (a, b)) in lit.pixels().iter().zip(shaded.pixels()).enumerate() {
        if a != b {
            assert_eq!(shaded.ids()[i], 0, "only floor pixels change");
            assert!(b.r < a.r && b.g < a.g && b.b < a.b);
            darkened += 1;
        }
    }
    assert!(darkened > 10, "a shadow is cast ({darkened} px)");

    // The caster's centre, moved along the light onto the floor, is in shadow.
    let light = renderer.lights().key_dir;
    let foot = caster_centre - light * (caster_centre.y / light.y);
    let clip = camera.clip_from_world(viewport.aspect()) * foot.extend(1.0);
    let ndc = glam::Vec2::new(clip.x / clip.w, clip.y / clip.w);
    let p = viewport.pixel_from_ndc(ndc);
    let (x, y) = (p.x as u32, p.y as u32);
    assert_eq!(
        shaded.id_at(x, y),
        Some(0),
        "the foot point is on visible floor"
    );
    assert!(
        shaded.pixel(x, y).r < lit.pixel(x, y).r,
        "the foot point is dark"
    );
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
