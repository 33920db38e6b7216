//! The sandbox driven as a person would: synthetic crossterm events into a headless app.

use crossterm::event::{Event, KeyCode, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use glam::Vec3;
use nudge::app::{App, AppConfig};
use nudge::geometry::{Camera, Shape};
use nudge::physics::BodyId;
use nudge::scene::{Scene, cases};
use ratatui::layout::Rect;

use crate::common;

use common::app::{cell_of, key};

const COLS: u16 = 120;
const ROWS: u16 = 40;

/// Floor, a support box and a box on top of it, seen from the front.
fn tower_scene() -> Scene {
    let mut scene = cases::pyramid(1);
    scene.bodies.truncate(1);
    for y in [0.5, 1.5] {
        scene.bodies.push(cases::dynamic(
            Shape::cuboid(Vec3::splat(0.5)),
            Vec3::new(0.0, y, 0.0),
            nudge::color::PALETTE[0],
        ));
    }
    scene.camera = Camera::perspective(Vec3::new(0.0, 2.5, -7.0), Vec3::new(0.0, 1.0, 0.0), 1.2);
    scene
}

fn app_for(scene: Scene) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene, config);
    app.resize(Rect::new(0, 0, COLS, ROWS));
    app
}

fn mouse(kind: MouseEventKind, cell: (u16, u16), modifiers: KeyModifiers) -> Event {
    Event::Mouse(MouseEvent {
        kind,
        column: cell.0,
        row: cell.1,
        modifiers,
    })
}

fn hold(app: &mut App, button: MouseButton, cell: (u16, u16), steps: usize) {
    app.handle_event(&mouse(
        MouseEventKind::Down(button),
        cell,
        KeyModifiers::NONE,
    ));
    for _ in 0..steps {
        app.step_physics();
    }
    app.handle_event(&mouse(MouseEventKind::Up(button), cell, KeyModifiers::NONE));
}

fn distance_to_camera(app: &App, id: BodyId) -> f32 {
    (app.world().body(id).pose().position - app.camera().position).length()
}

const TOP: BodyId = BodyId(2);
const SUPPORT: BodyId = BodyId(1);

#[test]
fn holding_the_left_button_on_a_box_pushes_it_away_from_the_camera() {
    let mut app = app_for(tower_scene());
    let before = distance_to_camera(&app, SUPPORT);
    let cell = cell_of(&app, Vec3::new(0.0, 0.5, -0.5));
    hold(&mut app, MouseButton::Left, cell, 30);
    let after = distance_to_camera(&app, SUPPORT);
    assert!(
        after > before + 0.05,
        "pushed box moved from {before} to {after}"
    );
}

#[test]
fn holding_the_right_button_pulls_a_box_toward_the_camera() {
    let mut app = app_for(tower_scene());
    let before = distance_to_camera(&app, SUPPORT);
    let cell = cell_of(&app, Vec3::new(0.0, 0.5, -0.5));
    hold(&mut app, MouseButton::Right, cell, 30);
    let after = distance_to_camera(&app, SUPPORT);
    assert!(
        after < before - 0.05,
        "pulled box moved from {before} to {after}"
    );
}

#[test]
fn a_push_near_a_box_edge_spins_it() {
    let mut app = app_for(tower_scene());
    let cell = cell_of(&app, Vec3::new(0.4, 0.5, -0.5));
    hold(&mut app, MouseButton::Left, cell, 20);
    let spin = app.world().body(SUPPORT).angular_velocity();
    assert!(
        spin.y.abs() > 0.2,
        "angular velocity after an off-centre push: {spin}"
    );
}

#[test]
fn middle_click_f_click_and_ctrl_click_each_freeze_a_box() {
    let cell_top = |app: &App| cell_of(app, Vec3::new(0.0, 1.5, -0.5));

    let mut app = app_for(tower_scene());
    let cell = cell_top(&app);
    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Middle),
        cell,
        KeyModifiers::NONE,
    ));
    assert!(app.world().body(TOP).is_static(), "middle click");

    let mut app = app_for(tower_scene());
    app.handle_event(&key(KeyCode::Char('f')));
    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Left),
        cell,
        KeyModifiers::NONE,
    ));
    assert!(app.world().body(TOP).is_static(), "f then click");

    let mut app = app_for(tower_scene());
    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Left),
        cell,
        KeyModifiers::CONTROL,
    ));
    assert!(app.world().body(TOP).is_static(), "ctrl+click");
    assert!(
        app.message().contains("froze"),
        "message: {}",
        app.message()
    );
}

#[test]
fn a_frozen_box_stays_put_without_support_and_falls_when_unfrozen() {
    let mut app = app_for(tower_scene());
    let cell = cell_of(&app, Vec3::new(0.0, 1.5, -0.5));
    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Middle),
        cell,
        KeyModifiers::NONE,
    ));
    let frozen_at = *app.world().body(TOP).pose();

    // Shove the support out from under it.
    for _ in 0..90 {
        let center = app.world().body(SUPPORT).pose().position;
        app.world_mut()
            .apply_force_at_point(SUPPORT, Vec3::new(60.0, 0.0, 0.0), center);
        app.step_physics();
    }
    assert!(
        app.world().body(SUPPORT).pose().position.x > 1.2,
        "support is gone"
    );
    assert_eq!(
        *app.world().body(TOP).pose(),
        frozen_at,
        "frozen box did not move"
    );

    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Middle),
        cell,
        KeyModifiers::NONE,
    ));
    assert!(!app.world().body(TOP).is_static());
    for _ in 0..90 {
        app.step_physics();
    }
    let y = app.world().body(TOP).pose().position.y;
    assert!(y < 0.6, "unfrozen box fell to the floor: y = {y}");
}

#[test]
fn clicks_on_background_or_status_bar_change_nothing() {
    let mut clicked = app_for(tower_scene());
    let mut control = app_for(tower_scene());
    for cell in [(0, 0), (COLS - 1, 0), (COLS / 2, ROWS - 1)] {
        for button in [MouseButton::Left, MouseButton::Right, MouseButton::Middle] {
            clicked.handle_event(&mouse(
                MouseEventKind::Down(button),
                cell,
                KeyModifiers::NONE,
            ));
            clicked.step_physics();
            clicked.handle_event(&mouse(MouseEventKind::Up(button), cell, KeyModifiers::NONE));
            control.step_physics();
        }
    }
    for (a, b) in clicked
        .world()
        .bodies()
        .iter()
        .zip(control.world().bodies())
    {
        assert_eq!(a.pose(), b.pose());
        assert_eq!(a.is_static(), b.is_static());
    }
}

#[test]
fn keys_pause_step_reset_and_cycle_modes() {
    let mut app = app_for(tower_scene());
    let mode = app.render_mode();
    app.handle_event(&key(KeyCode::Char('m')));
    assert_ne!(app.render_mode(), mode);
    app.handle_event(&key(KeyCode::Char(' ')));
    assert!(app.is_paused());
    let before = *app.world().body(TOP).pose();
    app.advance(std::time::Duration::from_secs(1));
    assert_eq!(
        *app.world().body(TOP).pose(),
        before,
        "paused world does not move"
    );
    app.handle_event(&key(KeyCode::Char('q')));
    assert!(app.should_quit());
}

#[test]
fn drawing_at_any_size_never_panics() {
    for (cols, rows) in [(1, 1), (10, 3), (400, 120), (0, 0), (2, 1)] {
        let mut app = app_for(tower_scene());
        let area = Rect::new(0, 0, cols, rows);
        let mut buffer = ratatui::buffer::Buffer::empty(area);
        app.draw(area, &mut buffer);
        app.handle_event(&Event::Resize(cols, rows));
        app.handle_event(&mouse(
            MouseEventKind::Down(MouseButton::Left),
            (0, 0),
            KeyModifiers::NONE,
        ));
        app.step_physics();
    }
}

/// A ball knocked over the default floor's edge would fall forever and keep the scene awake; once it
/// has fallen `LOST_DEPTH` below the floor it is frozen, the status bar says so, the rest comes to
/// rest and the app goes idle; `r` brings the ball back.
#[test]
fn a_ball_knocked_off_the_floor_is_frozen_once_lost_and_the_scene_goes_idle() {
    let mut app = app_for(nudge::scene::load("default").expect("default scene"));
    let ball = BodyId(3);
    assert!(matches!(
        app.world().body(ball).shape(),
        Shape::Sphere { .. }
    ));
    let centre = app.world().body(ball).pose().position;
    // Toward the near edge (−z, 1.9 m away), where nothing stands in the way.
    app.world_mut()
        .apply_impulse_at_point(ball, Vec3::new(0.0, 0.0, -6.0), centre);
    let mut steps = 0;
    while app.world().awake_count() > 0 && steps < 60 * 30 {
        app.step_physics();
        steps += 1;
    }
    let body = app.world().body(ball);
    assert!(body.is_static(), "the lost ball is frozen");
    let depth = -1.0 - nudge::app::world::lost::LOST_DEPTH;
    let y = body.pose().position.y;
    assert!(
        y < depth && y > depth - 2.0,
        "frozen just past the line: y = {y}"
    );
    assert_eq!(app.world().awake_count(), 0, "the scene came to rest");
    assert!(
        app.message().contains("sphere #3 fell off the world"),
        "{}",
        app.message()
    );
    app.handle_event(&key(KeyCode::Char('r')));
    let back = app.world().body(ball);
    assert!(!back.is_static() && back.pose().position.y > 0.0);
}

/// The hand moves heavy bodies too: its force limit scales with the mass under the pointer. A fixed 20 N
/// could not overcome the floor's friction under the default scene's 5 kg box (24.5 N), so a click
/// on it did nothing.
#[test]
fn holding_the_left_button_pushes_the_default_scenes_heavy_box() {
    let mut app = app_for(nudge::scene::load("default").expect("default scene"));
    let heavy = BodyId(2);
    assert_eq!(app.world().body(heavy).mass(), 5.0);
    while app.world().awake_count() > 0 {
        app.step_physics();
    }
    let before = app.world().body(heavy).pose().position;
    let cell = cell_of(&app, before);
    app.handle_event(&mouse(
        MouseEventKind::Down(MouseButton::Left),
        cell,
        KeyModifiers::NONE,
    ));
    for _ in 0..30 {
        app.step_physics();
    }
    // While held, the status bar shows the body, the force, the pointed-at point's speed and the
    // speed the hand leans in up to (the one its cap applies to).
    let message = app.message().to_string();
    assert!(
        message.starts_with("pushing box #2 · ")
            && message.contains(" N · point at ")
            && message.ends_with(" m/s (hand: 2.5)"),
        "{message}"
    );
    app.handle_event(&mouse(
        MouseEventKind::Up(MouseButton::Left),
        cell,
        KeyModifiers::NONE,
    ));
    let moved = (app.world().body(heavy).pose().position - before).length();
    assert!(moved > 0.05, "the 5 kg box moved {moved} m");
    // Let go, it says so at once (issue 28: "pushing" stayed for a second after the button).
    let message = app.message();
    assert!(
        message.starts_with("stopped pushing box #2 · its centre at ") && message.ends_with(" m/s"),
        "{message}"
    );
}

/// A body named in its scene file is called by that name (the name its joints may use), and
/// Ctrl+S writes the name back, so the saved file names it too.
#[test]
fn a_body_named_in_its_scene_file_is_called_by_its_name_and_saved_with_it() {
    let text = r#"
[camera]
position = [0.0, 2.0, -6.0]
target = [0.0, 0.5, 0.0]

[[body]]
shape = "box"
half_extents = [4.0, 0.5, 4.0]
position = [0.0, -0.5, 0.0]
static = true

[[body]]
name = "bob"
shape = "box"
half_extents = [0.5, 0.5, 0.5]
position = [0.0, 0.5, 0.0]

[[body]]
shape = "box"
half_extents = [0.5, 0.5, 0.5]
position = [1.5, 0.5, 0.0]
"#;
    let scene = nudge::scene::file::parse(text, "named").expect("scene");
    let dir = std::env::temp_dir().join(format!("nudge-named-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut app = App::new(
        scene,
        AppConfig {
            supersample: false,
            save_dir: Some(dir.clone()),
            ..AppConfig::default()
        },
    );
    app.resize(Rect::new(0, 0, COLS, ROWS));
    for (body, name) in [(1, "bob"), (2, "box #2")] {
        let cell = cell_of(&app, app.world().body(BodyId(body)).pose().position);
        hold(&mut app, MouseButton::Left, cell, 1);
        assert!(
            app.message().contains(&format!("pushing {name} ")),
            "{}",
            app.message()
        );
    }
    app.handle_event(&Event::Key(crossterm::event::KeyEvent::new(
        KeyCode::Char('s'),
        KeyModifiers::CONTROL,
    )));
    let message = app.message().to_owned();
    let path = message.strip_prefix("saved ").expect("saved");
    let saved = nudge::scene::file::load_file(path).expect("the saved file loads");
    let names: Vec<Option<&str>> = saved.bodies.iter().map(|b| b.name.as_deref()).collect();
    assert_eq!(names, [None, Some("bob"), None]);
    let _ = std::fs::remove_dir_all(&dir);
}
