//! First minutes, second pass (issue 28): Esc closes what is open before it quits, one key does not
//! lose a changed world, and one panel's key opens it from another.

use crate::common;

use common::app::{cell_of, char_key, key, screen, status_line};
use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use nudge::app::{App, AppConfig};
use nudge::physics::BodyId;
use nudge::scene;
use ratatui::layout::Rect;

const COLS: u16 = 120;
const ROWS: u16 = 40;

fn app_with(name: &str, save_dir: Option<std::path::PathBuf>) -> App {
    let config = AppConfig {
        supersample: false,
        save_dir,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load(name).unwrap(), config);
    app.resize(Rect::new(0, 0, COLS, ROWS));
    app
}

/// Something a user does to the world.
type Change<'a> = dyn Fn(&mut App) + 'a;

fn fresh() -> App {
    app_with("default", None)
}

fn middle_click(app: &mut App, cell: (u16, u16)) {
    app.handle_event(&Event::Mouse(MouseEvent {
        kind: MouseEventKind::Down(MouseButton::Middle),
        column: cell.0,
        row: cell.1,
        modifiers: KeyModifiers::NONE,
    }));
}

/// The default scene with box #2 frozen by a middle click: a world the user changed.
fn changed() -> App {
    let mut app = fresh();
    let cell = cell_of(&app, app.world().body(BodyId(2)).pose().position);
    middle_click(&mut app, cell);
    assert_eq!(app.message(), "froze box #2");
    app
}

#[test]
fn esc_closes_the_inspector_the_freeze_prompt_and_the_help_before_it_quits() {
    let mut app = fresh();
    app.handle_event(&char_key('i'));
    assert!(app.inspector_area().is_some());
    app.handle_event(&key(KeyCode::Esc));
    assert!(app.inspector_area().is_none(), "Esc closed the inspector");
    assert_eq!(app.message(), "inspector closed");
    assert!(!app.should_quit());

    app.handle_event(&char_key('f'));
    assert!(status_line(&mut app, COLS, ROWS).contains("FREEZE"));
    app.handle_event(&key(KeyCode::Esc));
    assert_eq!(app.message(), "freeze cancelled");
    assert!(!status_line(&mut app, COLS, ROWS).contains("FREEZE"));
    assert!(!app.should_quit());

    // "any key closes", q and Esc too.
    for closing in [char_key('q'), key(KeyCode::Esc)] {
        app.handle_event(&char_key('?'));
        assert!(
            screen(&mut app, COLS, ROWS)
                .join("\n")
                .contains("any key closes")
        );
        app.handle_event(&closing);
        assert!(
            !screen(&mut app, COLS, ROWS)
                .join("\n")
                .contains("any key closes")
        );
        assert!(!app.should_quit());
    }

    // With nothing open and nothing changed, Esc quits at once.
    app.handle_event(&key(KeyCode::Esc));
    assert!(app.should_quit());
}

#[test]
fn a_changed_world_asks_once_before_q_or_esc_quits() {
    for (code, name) in [(KeyCode::Char('q'), "q"), (KeyCode::Esc, "Esc")] {
        let mut app = changed();
        app.handle_event(&key(code));
        assert!(!app.should_quit(), "{name} quit a changed world at once");
        assert_eq!(
            app.message(),
            format!("unsaved world: {name} again to quit · Ctrl+S saves")
        );
        assert!(status_line(&mut app, COLS, ROWS).contains("again to quit"));
        app.handle_event(&key(code));
        assert!(app.should_quit(), "{name} twice");
    }
    // Another key in between changes the mind: the next q asks again.
    let mut app = changed();
    app.handle_event(&char_key('q'));
    app.handle_event(&char_key('m'));
    app.handle_event(&char_key('q'));
    assert!(!app.should_quit());
    // Ctrl+C, the terminal's interrupt, leaves at once.
    app.handle_event(&Event::Key(KeyEvent::new(
        KeyCode::Char('c'),
        KeyModifiers::CONTROL,
    )));
    assert!(app.should_quit());
}

#[test]
fn spawning_resizing_pushing_and_nudging_count_as_changes_and_looking_does_not() {
    // Looking around changes nothing: q quits at once.
    let mut app = fresh();
    for code in [
        KeyCode::Left,
        KeyCode::Char('+'),
        KeyCode::Char('m'),
        KeyCode::Char('p'),
    ] {
        app.handle_event(&key(code));
    }
    for _ in 0..30 {
        app.step_physics();
    }
    app.handle_event(&char_key('q'));
    assert!(app.should_quit(), "{}", app.message());

    let spawn = |app: &mut App| {
        app.handle_event(&Event::Mouse(MouseEvent {
            kind: MouseEventKind::Moved,
            column: COLS / 2,
            row: ROWS / 2,
            modifiers: KeyModifiers::NONE,
        }));
        app.handle_event(&char_key('b'));
    };
    let select = |app: &mut App| {
        let cell = cell_of(app, app.world().body(BodyId(1)).pose().position);
        middle_click(app, cell);
        middle_click(app, cell);
        assert!(!app.world().body(BodyId(1)).is_static());
    };
    let resize = |app: &mut App| {
        select(app);
        app.handle_event(&char_key('<'));
    };
    let push = |app: &mut App| {
        let cell = cell_of(app, app.world().body(BodyId(1)).pose().position);
        for kind in [
            MouseEventKind::Down(MouseButton::Left),
            MouseEventKind::Up(MouseButton::Left),
        ] {
            app.handle_event(&Event::Mouse(MouseEvent {
                kind,
                column: cell.0,
                row: cell.1,
                modifiers: KeyModifiers::NONE,
            }));
        }
        for _ in 0..10 {
            app.step_physics();
        }
    };
    let nudge = |app: &mut App| {
        select(app);
        app.handle_event(&char_key('w'));
    };
    let gravity = |app: &mut App| app.handle_event(&char_key('g'));
    let changes: [(&str, &Change<'_>); 5] = [
        ("spawn", &spawn),
        ("resize", &resize),
        ("push", &push),
        ("nudge", &nudge),
        ("gravity", &gravity),
    ];
    for (what, change) in changes {
        let mut app = fresh();
        change(&mut app);
        app.handle_event(&char_key('q'));
        assert!(!app.should_quit(), "{what}: quit without asking");
        assert!(app.message().contains("again to quit"), "{what}");
    }
}

#[test]
fn after_ctrl_s_one_q_quits_and_n_asks_before_switching_away_from_a_changed_world() {
    let dir = std::env::temp_dir().join(format!("nudge-nothing-lost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut app = app_with("default", Some(dir.clone()));
    let cell = cell_of(&app, app.world().body(BodyId(2)).pose().position);
    middle_click(&mut app, cell);
    app.handle_event(&char_key('n'));
    assert_eq!(app.scene_name(), "default", "n switched away at once");
    assert_eq!(
        app.message(),
        "unsaved world: n again to switch scenes · Ctrl+S saves"
    );
    app.handle_event(&Event::Key(KeyEvent::new(
        KeyCode::Char('s'),
        KeyModifiers::CONTROL,
    )));
    assert!(app.message().starts_with("saved "), "{}", app.message());
    app.handle_event(&char_key('n'));
    assert_eq!(app.scene_name(), "stack", "saved: n switches at once");
    // The new scene is unchanged: q quits at once.
    app.handle_event(&char_key('q'));
    assert!(app.should_quit());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn one_panel_key_opens_that_panel_from_another() {
    let mut app = fresh();
    // t then o: the settings close and the overlay menu opens.
    app.handle_event(&char_key('t'));
    app.handle_event(&char_key('o'));
    assert!(!app.message().contains("no such key"), "{}", app.message());
    assert_eq!(app.message(), "overlays: 1-9 toggle, o closes");
    assert!(
        screen(&mut app, COLS, ROWS)
            .join("\n")
            .contains("overlays · 1-9 toggle")
    );
    // o then t: the menu closes and the settings open.
    app.handle_event(&char_key('t'));
    assert!(app.message().starts_with("settings: "), "{}", app.message());
    assert!(
        !screen(&mut app, COLS, ROWS)
            .join("\n")
            .contains("overlays · 1-9 toggle")
    );
    // t then i: the settings close and the inspector opens.
    app.handle_event(&char_key('i'));
    assert_eq!(app.message(), "inspector (i closes)");
    assert!(app.inspector_area().is_some());
    app.handle_event(&char_key('i'));
    // o then i.
    app.handle_event(&char_key('o'));
    app.handle_event(&char_key('i'));
    assert_eq!(app.message(), "inspector (i closes)");
    assert!(
        !screen(&mut app, COLS, ROWS)
            .join("\n")
            .contains("overlays · 1-9 toggle")
    );
    // And Esc closes each, the inspector last, without quitting.
    app.handle_event(&char_key('t'));
    app.handle_event(&key(KeyCode::Esc));
    assert_eq!(app.message(), "settings closed");
    app.handle_event(&key(KeyCode::Esc));
    assert_eq!(app.message(), "inspector closed");
    assert!(!app.should_quit());
}
