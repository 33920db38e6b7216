//! Debug overlays, headless: marks land on what they annotate, through the scene's own camera and
//! viewport, in both projections; `--overlay` is checked like every other flag.

use crate::common;

use common::app::char_key;
use common::cli::nudge;
use glam::{Quat, Vec2, Vec3};
use nudge::app::panels::overlays::{OverlayKind, OverlaySet};
use nudge::app::{App, AppConfig};
use nudge::color::Rgb;
use nudge::geometry::{Camera, Pose, Shape};
use nudge::physics::BodyDesc;
use nudge::scene::{Scene, SceneBody, cases};
use ratatui::layout::Rect;

const COLS: u16 = 120;
const ROWS: u16 = 40;

fn app_for(scene: Scene, orthographic: bool) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene, config);
    if orthographic {
        *app.camera_mut() = app.camera().toggled_projection(nudge::app::DEFAULT_FOV_Y);
    }
    app.resize(Rect::new(0, 0, COLS, ROWS));
    app
}

/// Continuous pixel coordinates of world point `p` in the app's viewport.
fn pixel_of(app: &App, p: Vec3) -> Vec2 {
    let viewport = app.viewport();
    let clip = app.camera().clip_from_world(viewport.aspect()) * p.extend(1.0);
    viewport.pixel_from_ndc(Vec2::new(clip.x / clip.w, clip.y / clip.w))
}

/// Pixels of the last frame painted exactly `color`, as (x, y).
fn pixels_of_color(app: &App, color: Rgb) -> Vec<Vec2> {
    let frame = app.frame();
    let w = frame.width() as usize;
    frame
        .pixels()
        .iter()
        .enumerate()
        .filter(|&(_, &c)| c == color)
        .map(|(i, _)| Vec2::new((i % w) as f32, (i / w) as f32))
        .collect()
}

/// A floor, a box resting on it and a frozen box in the air beside it.
fn resting_box_scene() -> Scene {
    let mut scene = cases::pyramid(1);
    scene.bodies.truncate(1);
    scene.bodies.push(cases::dynamic(
        Shape::cuboid(Vec3::splat(0.5)),
        Vec3::new(0.0, 0.5, 0.0),
        nudge::color::PALETTE[0],
    ));
    scene.bodies.push(SceneBody {
        frozen: false,
        name: None,
        desc: BodyDesc::fixed(
            Shape::cuboid(Vec3::splat(0.4)),
            Pose::from_position(Vec3::new(2.5, 1.5, 0.0)),
        ),
        color: nudge::color::PALETTE[2],
    });
    scene.camera = Camera::perspective(Vec3::new(1.0, 3.0, -6.0), Vec3::new(1.0, 0.5, 0.0), 1.1);
    scene
}

#[test]
fn contact_dots_appear_where_a_box_rests_on_the_floor_and_nowhere_else() {
    for orthographic in [false, true] {
        let mut app = app_for(resting_box_scene(), orthographic);
        for _ in 0..60 {
            app.step_physics();
        }
        let yellow = OverlayKind::Contacts.color();
        app.render_scene();
        assert!(
            pixels_of_color(&app, yellow).is_empty(),
            "the scene alone has no pixel of the contact colour"
        );

        app.set_overlays("contacts".parse().unwrap());
        app.render_scene();
        let contacts: Vec<_> = app.world().contacts().collect();
        assert_eq!(contacts.len(), 1, "the resting box and the floor");
        let points: Vec<Vec3> = contacts[0].points().iter().map(|p| p.point).collect();
        assert_eq!(points.len(), 4);
        for p in &points {
            // Under the box, on the floor's top face.
            assert!(
                p.y.abs() < 0.01 && p.x.abs() < 0.51 && p.z.abs() < 0.51,
                "{p}"
            );
        }
        let dots = pixels_of_color(&app, yellow);
        assert!(dots.len() >= 4, "orthographic {orthographic}: {dots:?}");
        let projected: Vec<Vec2> = points.iter().map(|&p| pixel_of(&app, p)).collect();
        for dot in &dots {
            let nearest = projected
                .iter()
                .map(|p| (*p - (*dot + Vec2::splat(0.5))).length())
                .fold(f32::INFINITY, f32::min);
            assert!(
                nearest <= 1.5,
                "orthographic {orthographic}: a dot at {dot} is {nearest} px from every contact"
            );
        }
        // Each point has its dot (the two behind the box as single hidden-style pixels).
        for p in &projected {
            let found = dots
                .iter()
                .any(|d| (*d + Vec2::splat(0.5) - *p).length() <= 1.5);
            assert!(found, "orthographic {orthographic}: no dot at {p}");
        }
    }
}

#[test]
fn an_aabb_overlay_encloses_the_bodys_pixels() {
    for orthographic in [false, true] {
        let mut scene = cases::pyramid(1);
        scene.bodies.clear();
        let mut body = cases::dynamic(
            Shape::cuboid(Vec3::new(0.9, 0.4, 0.6)),
            Vec3::new(0.2, 1.0, 0.0),
            nudge::color::PALETTE[1],
        );
        body.desc.pose.rotation = Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.3).normalize(), 0.7);
        scene.bodies.push(body);
        scene.camera =
            Camera::perspective(Vec3::new(1.5, 3.0, -5.0), Vec3::new(0.2, 1.0, 0.0), 1.1);
        let mut app = app_for(scene, orthographic);
        let line_colour = OverlayKind::Aabbs.color();
        app.render_scene();
        assert!(pixels_of_color(&app, line_colour).is_empty());
        app.set_overlays("aabbs".parse().unwrap());
        app.render_scene();

        let frame = app.frame();
        let w = frame.width() as usize;
        let body: Vec<Vec2> = frame
            .ids()
            .iter()
            .enumerate()
            .filter(|&(_, &id)| id == 0)
            .map(|(i, _)| Vec2::new((i % w) as f32, (i / w) as f32))
            .collect();
        let lines = pixels_of_color(&app, line_colour);
        assert!(!body.is_empty() && !lines.is_empty());
        let bounds = |ps: &[Vec2]| {
            ps.iter().fold(
                (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
                |(lo, hi), p| (lo.min(*p), hi.max(*p)),
            )
        };
        let (body_lo, body_hi) = bounds(&body);
        let (box_lo, box_hi) = bounds(&lines);
        assert!(
            box_lo.cmple(body_lo).all() && box_hi.cmpge(body_hi).all(),
            "orthographic {orthographic}: body {body_lo}..{body_hi} outside box {box_lo}..{box_hi}"
        );
        // And the box is the body's, not just something big: its corners project onto its outline.
        let aabb = app.world().bodies()[0]
            .shape()
            .aabb(app.world().bodies()[0].pose());
        for i in 0..8 {
            let corner = Vec3::new(
                if i & 1 == 0 { aabb.min.x } else { aabb.max.x },
                if i & 2 == 0 { aabb.min.y } else { aabb.max.y },
                if i & 4 == 0 { aabb.min.z } else { aabb.max.z },
            );
            let p = pixel_of(&app, corner);
            let near = lines
                .iter()
                .any(|l| (*l + Vec2::splat(0.5) - p).length() <= 1.5);
            assert!(
                near,
                "orthographic {orthographic}: corner {corner} at {p} not drawn"
            );
        }
    }
}

#[test]
fn every_overlay_at_once_keeps_ids_and_depth_as_picking_sees_them() {
    let mut app = app_for(resting_box_scene(), false);
    for _ in 0..30 {
        app.step_physics();
    }
    app.render_scene();
    let (ids, depths) = (app.frame().ids().to_vec(), app.frame().depths().to_vec());
    app.set_overlays(OverlaySet::ALL);
    app.render_scene();
    assert_eq!(app.frame().ids(), &ids[..]);
    assert_eq!(app.frame().depths(), &depths[..]);
}

#[test]
fn an_unknown_overlay_name_exits_2_listing_the_valid_names() {
    for command in ["snapshot", "run"] {
        let out = nudge(&[command, "--overlay", "contacts,bogus"]);
        assert_eq!(out.status.code(), Some(2), "{command}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains("unknown overlay 'bogus'"), "{command}: {err}");
        for kind in OverlayKind::ALL {
            assert!(err.contains(kind.name()), "{command}: {err}");
        }
    }
}

#[test]
fn a_snapshot_with_overlays_draws_their_colours_at_every_depth() {
    // The contact yellow as each depth writes it (fg or bg): truecolor, xterm-256's 226, and the
    // 16-colour bright yellow (SGR 93 / 103).
    let yellows: [(&str, &[&str]); 3] = [
        ("truecolor", &["2;255;255;0m"]),
        ("256", &["5;226m"]),
        ("16", &["[93m", "[103m", ";93m", ";103m", "[93;", "[103;"]),
    ];
    for (colors, yellow) in yellows {
        let snapshot = |extra: &[&str]| {
            let mut args = vec![
                "snapshot", "--size", "60x20", "--steps", "60", "--colors", colors,
            ];
            args.extend_from_slice(extra);
            let output = nudge(&args);
            assert!(output.status.success(), "{colors}");
            String::from_utf8_lossy(&output.stdout).into_owned()
        };
        let plain = snapshot(&[]);
        let marked = snapshot(&["--overlay", "contacts,aabbs"]);
        let has_yellow = |text: &str| yellow.iter().any(|y| text.contains(y));
        assert!(!has_yellow(&plain), "{colors}: yellow without the overlay");
        assert!(has_yellow(&marked), "{colors}: no contact yellow\n{marked}");
    }
}

#[test]
fn o_opens_the_overlay_menu_where_digits_toggle_and_o_closes_it() {
    let mut app = app_for(resting_box_scene(), false);
    app.handle_event(&char_key('1'));
    assert!(
        app.overlays().is_empty(),
        "digits do nothing outside the menu"
    );
    app.handle_event(&char_key('o'));
    app.handle_event(&char_key('1'));
    app.handle_event(&char_key('4'));
    app.handle_event(&char_key('8'));
    assert_eq!(app.overlays().to_string(), "contacts,aabbs,sleep");
    assert!(app.message().contains("sleep: on"), "{}", app.message());
    app.handle_event(&char_key('4'));
    app.handle_event(&char_key('o'));
    app.handle_event(&char_key('2'));
    assert_eq!(app.overlays().to_string(), "contacts,sleep");
    // The menu is drawn while open and lists every overlay with its key.
    app.handle_event(&char_key('o'));
    let area = Rect::new(0, 0, 80, 24);
    let mut buf = ratatui::buffer::Buffer::empty(area);
    app.draw(area, &mut buf);
    let text: String = (0..area.height)
        .map(|y| {
            (0..area.width)
                .map(|x| buf[(x, y)].symbol())
                .collect::<String>()
                + "\n"
        })
        .collect();
    for kind in OverlayKind::ALL {
        assert!(text.contains(&format!("{} ", kind.key())), "{text}");
        assert!(text.contains(kind.name()), "{text}");
    }
    // Another key closes the menu and does its usual job.
    app.handle_event(&char_key(' '));
    assert!(app.is_paused());
}
