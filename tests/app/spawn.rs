//! Spawning in the sandbox: `b` and `s` drop new bodies into free space, and holding a key builds a
//! pile that stays in the world.

use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseEvent, MouseEventKind};
use nudge::app::{App, AppConfig};
use nudge::geometry::Aabb;
use nudge::scene;
use ratatui::layout::Rect;

fn app() -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load("default").unwrap(), config);
    app.resize(Rect::new(0, 0, 120, 40));
    app
}

fn press(app: &mut App, c: char) {
    app.handle_event(&Event::Key(KeyEvent::new(
        KeyCode::Char(c),
        KeyModifiers::NONE,
    )));
}

fn bounds(app: &App) -> Vec<Aabb> {
    app.world()
        .bodies()
        .iter()
        .map(|b| b.shape().aabb(b.pose()))
        .collect()
}

/// Pressing `b` thirty times before any click put thirty boxes in one place, and they exploded off
/// the world. Now each press drops a box clear of every body, or says there is no room.
#[test]
fn thirty_presses_of_b_before_any_click_put_no_box_inside_another() {
    let mut app = app();
    for _ in 0..30 {
        let before = app.world().len();
        press(&mut app, 'b');
        if app.world().len() == before {
            assert!(app.message().starts_with("no room"), "{}", app.message());
            continue;
        }
        let all = bounds(&app);
        let new = all.last().unwrap();
        for (i, other) in all[..all.len() - 1].iter().enumerate() {
            assert!(
                !new.overlaps(other),
                "body {} overlaps body {i}",
                all.len() - 1
            );
        }
        assert!(
            app.message().starts_with("spawned box #"),
            "{}",
            app.message()
        );
    }
    // The default floor is 8 m × 5 m, its four bodies still in the air at the start: room for a few.
    assert!(app.world().len() >= 5 + 5, "{} bodies", app.world().len());
}

/// Holds `key` for `seconds` as a terminal repeats it (30 presses a second, two physics steps
/// apart), lets the world run 15 s more, and checks nothing left the world: every dynamic body
/// rests on the default floor (top at y = 0, |x| ≤ 4, |z| ≤ 2.5) and none was frozen as lost.
/// A floor that fills up refuses more ("no room"), so at least `at_least` must have been placed.
fn hold_and_check(app: &mut App, keys: &[char], seconds: usize, at_least: usize) {
    let before = app.world().len();
    for i in 0..30 * seconds {
        press(app, keys[i % keys.len()]);
        app.step_physics();
        app.step_physics();
    }
    let placed = app.world().len() - before;
    assert!(placed >= at_least, "{placed} placed");
    let top = app.world().bodies()[before..]
        .iter()
        .map(|b| b.pose().position.y)
        .fold(f32::MIN, f32::max);
    assert!(
        top > 1.2,
        "a pile, not a layer: the highest new body is at y = {top}"
    );
    if placed < 30 * seconds {
        assert!(app.message().starts_with("no room"), "{}", app.message());
    }
    for _ in 0..15 * 60 {
        app.step_physics();
    }
    // The default scene's dynamic bodies (1 to 4) and the new ones; its floor and rim are static.
    let dynamic = app.world().bodies().iter().enumerate();
    for (i, body) in dynamic.filter(|&(i, _)| (1..5).contains(&i) || i >= before) {
        let p = body.pose().position;
        assert!(!body.is_static(), "body {i} was frozen (lost) at {p}");
        assert!(
            p.y > 0.0 && p.x.abs() < 4.0 && p.z.abs() < 2.5,
            "body {i} left the floor: {p}"
        );
    }
    assert!(
        app.world().max_penetration() < 0.05,
        "penetration {}",
        app.world().max_penetration()
    );
}

#[test]
fn holding_b_for_5_seconds_builds_a_pile_that_stays_on_the_floor() {
    let mut app = app();
    hold_and_check(&mut app, &['b'], 5, 12);
}

#[test]
fn holding_b_and_s_over_a_body_under_the_pointer_builds_a_pile_there() {
    let mut app = app();
    // The pointer rests over the 5 kg box (the middle button freezes nothing after two clicks).
    let cell = (80, 22);
    for _ in 0..2 {
        app.handle_event(&Event::Mouse(MouseEvent {
            kind: MouseEventKind::Moved,
            column: cell.0,
            row: cell.1,
            modifiers: KeyModifiers::NONE,
        }));
    }
    hold_and_check(&mut app, &['b', 's'], 5, 8);
}
