//! Live settings, driven as a person would: every change reaches the world (through its API, so a
//! recording replays it), is echoed in the status bar, and survives a reset.

use std::time::Duration;

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers};
use nudge::app::{App, AppConfig};
use nudge::physics::World;
use nudge::scene;
use ratatui::layout::Rect;

fn app_for(name: &str) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load(name).unwrap(), config);
    app.resize(Rect::new(0, 0, 100, 30));
    app
}

fn press(app: &mut App, code: KeyCode) {
    app.handle_event(&Event::Key(KeyEvent::new(code, KeyModifiers::NONE)));
}

fn keys(app: &mut App, text: &str) {
    for c in text.chars() {
        let code = match c {
            '^' => KeyCode::Up,
            'v' => KeyCode::Down,
            '<' => KeyCode::Left,
            '>' => KeyCode::Right,
            c => KeyCode::Char(c),
        };
        press(app, code);
    }
}

#[test]
fn settings_changes_reach_the_world_and_are_echoed_in_the_status_bar() {
    let mut app = app_for("default");
    let defaults = app.world().settings().clone();
    // Rows: sub-steps, iterations, sleeping, time scale, gravity, strength, bounce above.
    keys(&mut app, "t>");
    assert_eq!(app.world().settings().substeps, defaults.substeps + 1);
    assert_eq!(app.message(), "sub-steps 5");
    keys(&mut app, "<<<<<<<<<<");
    assert_eq!(app.world().settings().substeps, 1, "sub-steps stop at 1");
    keys(&mut app, ">>>>>>>>>>>>");
    assert_eq!(app.world().settings().substeps, 8, "and at 8");
    keys(&mut app, "v>>>>>>");
    assert_eq!(app.world().settings().iterations, 4);
    assert_eq!(app.message(), "iterations 4");
    keys(&mut app, "v>");
    assert!(!app.world().settings().sleep);
    assert_eq!(app.message(), "sleeping off");
    keys(&mut app, "v<<");
    assert_eq!(app.time_scale(), 0.5);
    assert_eq!(app.message(), "time scale 0.5×");
    keys(&mut app, "vv>");
    assert!((app.world().settings().gravity.y + 15.0).abs() < 1e-6);
    assert_eq!(app.message(), "gravity 15 m/s²");
    keys(&mut app, "^>");
    assert_eq!(app.world().settings().gravity, glam::Vec3::ZERO);
    assert_eq!(app.message(), "gravity off");
    keys(&mut app, ">");
    assert!(
        (app.world().settings().gravity.y + 15.0).abs() < 1e-6,
        "back on at the strength chosen"
    );
    keys(&mut app, "vv<");
    assert_eq!(app.world().settings().restitution_threshold, 0.5);
    assert_eq!(app.message(), "bounce above 0.5 m/s");
    // t closes the panel: the arrows orbit the camera again.
    keys(&mut app, "t");
    let camera = *app.camera();
    keys(&mut app, "<");
    assert_ne!(*app.camera(), camera);
    assert_eq!(app.world().settings().restitution_threshold, 0.5);

    // A reset rebuilds the bodies and keeps every setting.
    let settings = app.world().settings().clone();
    keys(&mut app, "r");
    assert_eq!(*app.world().settings(), settings);
    assert_eq!(app.time_scale(), 0.5);
}

#[test]
fn the_time_scale_runs_fewer_steps_per_second_of_real_time() {
    let mut app = app_for("default");
    let steps = |app: &mut App| {
        let start = app.world().step_count();
        for _ in 0..60 {
            app.advance(Duration::from_secs_f64(1.0 / 60.0));
        }
        app.world().step_count() - start
    };
    let real = steps(&mut app);
    keys(&mut app, "tvvv<<<t");
    assert_eq!(app.time_scale(), 0.25);
    let slow = steps(&mut app);
    assert!((59..=61).contains(&real), "{real}");
    assert!((14..=16).contains(&slow), "{slow}");
}

#[test]
fn settings_changed_live_replay_from_a_recording() {
    let file = std::env::temp_dir().join(format!("nudge-settings-{}.toml", std::process::id()));
    let mut app = app_for("stack");
    app.start_recording(&file).unwrap();
    // The panel remembers its row: sub-steps, sleeping, bounce above, iterations (past the cell
    // aspect, wrapping round).
    let mut live = Vec::new();
    for (i, change) in ["", "t<<<t", "tvv>t", "tvvvv<<t", "tvvv>>>t"]
        .iter()
        .enumerate()
    {
        keys(&mut app, change);
        for _ in 0..30 + 7 * i {
            app.step_physics();
        }
        live.push(
            app.world()
                .bodies()
                .iter()
                .map(|b| *b.pose())
                .collect::<Vec<_>>(),
        );
    }
    let changed = app.world().settings().clone();
    assert_eq!((changed.substeps, changed.iterations), (1, 4));
    assert!(!changed.sleep);
    assert_eq!(changed.restitution_threshold, 0.25);
    app.finish_recording().unwrap();

    // The replay's world goes through the same settings at the same steps.
    let recording = nudge::recording::load(file.to_str().unwrap()).unwrap();
    let mut replay = App::replaying(&recording, AppConfig::default());
    let _ = std::fs::remove_file(&file);
    let world: &World = replay.world();
    assert_eq!(world.step_count(), 0);
    let mut at = Vec::new();
    for i in 0..5 {
        for _ in 0..30 + 7 * i {
            replay.step_physics();
        }
        at.push(
            replay
                .world()
                .bodies()
                .iter()
                .map(|b| *b.pose())
                .collect::<Vec<_>>(),
        );
    }
    assert_eq!(*replay.world().settings(), changed);
    assert_eq!(at, live);
}

/// In xterm.js the pty reports no pixel size and its cells are 8×19 px (2.375, not the guessed 2.0):
/// bodies were drawn 19 % too tall with no way to correct it (issue 28). The settings' last row
/// changes the cell aspect live, and the picture follows; the physics does not notice.
#[test]
fn the_cell_aspect_is_corrected_live_from_the_settings_and_the_picture_follows() {
    let mut app = app_for("default");
    // Columns a 1 m level span at the origin covers on screen against the rows a 1 m upright one
    // does: taller cells, more columns to the metre.
    let shape = |app: &App| {
        let viewport = app.viewport();
        let clip_from_world = app.camera().clip_from_world(viewport.aspect());
        let cell = |p: glam::Vec3| {
            let clip = clip_from_world * p.extend(1.0);
            let pixel = viewport.pixel_from_ndc(glam::Vec2::new(clip.x / clip.w, clip.y / clip.w));
            glam::Vec2::new(pixel.x, pixel.y / 2.0)
        };
        let origin = cell(glam::Vec3::ZERO);
        (cell(glam::Vec3::X) - origin).length() / (cell(glam::Vec3::Y) - origin).length()
    };
    let before = shape(&app);
    let world_before = app.world().settings().clone();
    // Up from the first row wraps to the last, the cell aspect; seven notches up: 2.0 to 2.35.
    keys(&mut app, "t^>>>>>>>");
    assert_eq!(
        app.message(),
        "cell aspect 2.35 (round bodies look round when it is right)"
    );
    let after = shape(&app);
    let ratio = after / before;
    assert!(
        (ratio - 2.35 / 2.0).abs() < 0.01,
        "{before} columns a row, then {after}"
    );
    assert_eq!(*app.world().settings(), world_before);
    // It stops at the plausible bounds.
    keys(&mut app, &"<".repeat(100));
    assert!(
        app.message().starts_with("cell aspect 0.50"),
        "{}",
        app.message()
    );
}
