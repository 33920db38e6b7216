//! First minutes, second pass (issue 28): a status bar that tells the truth. Every key is answered,
//! a push that ended says so, the line keeps the message and the way to the help at any width, the
//! rewind limit says how far back it is, small masses read in grams.

use crate::common;

use common::app::{app_on, cell_of, char_key, key, mouse, status_line};
use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEventKind};
use nudge::app::App;
use nudge::physics::BodyId;
use ratatui::layout::Rect;

fn settle(app: &mut App) {
    let mut steps = 0;
    while app.world().awake_count() > 0 && steps < 600 {
        app.step_physics();
        steps += 1;
    }
}

#[test]
fn arrows_zoom_keys_the_wheel_and_keys_that_do_nothing_each_replace_the_last_message() {
    let mut app = app_on("default", 120, 40);
    app.handle_event(&char_key('z'));
    assert_eq!(app.message(), "z: no such key (? for help)");
    // After `z` then Right the camera turned while the bar still said "z: no such key".
    for code in [KeyCode::Right, KeyCode::Left, KeyCode::Up, KeyCode::Down] {
        app.handle_event(&char_key('z'));
        app.handle_event(&key(code));
        assert_eq!(app.message(), "camera turned (c resets it)", "{code:?}");
    }
    for (event, said) in [
        (char_key('+'), "zoom 1.11× (c resets the camera)"),
        (char_key('-'), "zoom 1.00× (c resets the camera)"),
        (
            mouse(MouseEventKind::ScrollUp, (60, 20)),
            "zoom 1.11× (c resets the camera)",
        ),
        (
            mouse(MouseEventKind::ScrollDown, (60, 20)),
            "zoom 1.00× (c resets the camera)",
        ),
        (
            Event::Key(KeyEvent::new(KeyCode::Char('l'), KeyModifiers::CONTROL)),
            "screen redrawn",
        ),
        (key(KeyCode::F(5)), "F5: no such key (? for help)"),
        (key(KeyCode::PageUp), "PageUp: no such key (? for help)"),
        (key(KeyCode::Delete), "Delete: no such key (? for help)"),
        (key(KeyCode::Insert), "Insert: no such key (? for help)"),
        (key(KeyCode::End), "End: no such key (? for help)"),
    ] {
        app.handle_event(&char_key('z'));
        app.handle_event(&event);
        assert_eq!(app.message(), said, "{event:?}");
    }
}

#[test]
fn one_notch_back_in_from_the_farthest_zoom_says_the_zoom() {
    let mut app = app_on("default", 120, 40);
    for _ in 0..100 {
        app.handle_event(&mouse(MouseEventKind::ScrollDown, (60, 20)));
    }
    assert!(
        app.message().starts_with("farthest zoom"),
        "{}",
        app.message()
    );
    app.handle_event(&mouse(MouseEventKind::ScrollUp, (60, 20)));
    assert!(
        app.message().starts_with("zoom ") && app.message().ends_with("× (c resets the camera)"),
        "{}",
        app.message()
    );
}

/// With gravity off a tapped box drifts for many seconds with no force on it: the bar said
/// "pushing box #1 · 45 N" all that while.
#[test]
fn a_tap_with_gravity_off_says_the_push_ended_once_it_has() {
    let mut app = app_on("default", 120, 40);
    settle(&mut app);
    app.handle_event(&char_key('g'));
    let cell = cell_of(&app, app.world().body(BodyId(1)).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    app.step_physics();
    assert!(
        app.message().starts_with("pushing box #1 · "),
        "{}",
        app.message()
    );
    // A tap pushes for 0.1 s (six steps), then lets go.
    for _ in 0..6 {
        app.step_physics();
    }
    let message = app.message().to_string();
    assert!(
        message.starts_with("stopped pushing box #1 · its centre at "),
        "{message}"
    );
    let speed = app.world().body(BodyId(1)).linear_velocity().length();
    assert!(speed > 0.05, "the tap moved it: {speed}");
    for _ in 0..60 {
        app.step_physics();
    }
    assert_eq!(app.message(), message, "nothing pushes it any more");
    assert!(
        status_line(&mut app, 120, 40).contains("stopped pushing box #1"),
        "{}",
        status_line(&mut app, 120, 40)
    );
}

/// At 60×12 with every flag on, the bar lost "? help" and the message; at 40 columns it ended in
/// "│ FR".
#[test]
fn with_every_flag_on_a_narrow_bar_keeps_the_message_and_the_help() {
    for (cols, flags) in [(60, "PAUSE STRONG GRAB 0 g FREEZE"), (40, "P S G 0 F")] {
        let mut app = app_on("default", cols, 12);
        for c in [' ', 'x', 'h', 'g', 'f'] {
            app.handle_event(&char_key(c));
        }
        let line = status_line(&mut app, cols, 12);
        assert!(
            line.starts_with(&format!("{flags} │ ? help │ click a body")),
            "{cols}: {line}"
        );
        let wide = status_line(&mut app, 160, 40);
        assert!(
            wide.contains("PAUSED │ STRONG │ GRAB │ NO GRAVITY │ FREEZE: click a body"),
            "{wide}"
        );
    }
}

#[test]
fn at_the_oldest_moment_kept_the_rewind_says_how_far_back_it_is() {
    let mut app = app_on("default", 120, 40);
    for _ in 0..150 {
        app.step_physics();
    }
    for _ in 0..20 {
        app.handle_event(&char_key('['));
    }
    assert_eq!(app.world().step_count(), app.timeline().oldest());
    // Every press at the limit says the same, measured from the present (it said "0.0 s kept").
    for _ in 0..2 {
        app.handle_event(&char_key('['));
        assert_eq!(
            app.message(),
            "can't rewind further: the oldest moment kept, 2.5 s back"
        );
    }
}

#[test]
fn a_body_shrunk_to_a_few_centimetres_shows_its_mass_in_grams() {
    let mut app = app_on("default", 120, 40);
    settle(&mut app);
    let cell = cell_of(&app, app.world().body(BodyId(1)).pose().position);
    for _ in 0..2 {
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
    }
    assert_eq!(app.selected(), Some(BodyId(1)));
    // Each press shrinks it by a tenth: 31 presses, to 5 cm (1/1.1^31 of its size).
    for _ in 0..31 {
        app.handle_event(&char_key('<'));
    }
    let message = app.message().to_string();
    assert!(message.starts_with("box #1: 0.05 m, "), "{message}");
    assert!(
        message.ends_with(" g") && !message.contains("0.000"),
        "{message}"
    );
    let grams: f32 = message
        .trim_end_matches(" g")
        .rsplit(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(grams > 0.1 && grams < 10.0, "{message}");
}

/// Ctrl+click never reaches the app in a stock xterm: a frozen body tells how to unfreeze it in a
/// way that works everywhere, and so does the help.
#[test]
fn a_click_on_a_frozen_body_names_a_way_to_unfreeze_that_needs_no_middle_button() {
    let mut app = app_on("default", 120, 40);
    settle(&mut app);
    let cell = cell_of(&app, app.world().body(BodyId(1)).pose().position);
    app.handle_event(&char_key('f'));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    assert_eq!(app.message(), "froze box #1");
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    assert_eq!(
        app.message(),
        "box #1 is frozen (middle button, or f then click, unfreezes)"
    );
    let help = nudge::app::input::CONTROLS
        .iter()
        .find(|(keys, _)| keys.contains("f then click"))
        .unwrap();
    assert!(help.1.contains("Ctrl+click: not xterm"), "{help:?}");
}

/// After `h` the grab mode's long message pushed the colour depth off a 120-column bar.
#[test]
fn after_h_a_busy_120_column_bar_still_shows_the_colour_depth() {
    use nudge::app::run::{Screen, tick};
    use std::time::Duration;
    let (cols, rows) = (120, 40);
    let mut app = app_on("default", cols, rows);
    let mut screen = Screen::fixed(Vec::new(), Rect::new(0, 0, cols, rows)).unwrap();
    // Run as the terminal loop does, so that the line carries its timings and byte rate.
    for _ in 0..40 {
        tick(&mut app, &mut screen, Duration::from_millis(33)).unwrap();
    }
    let before = status_line(&mut app, cols, rows);
    assert!(
        before.contains(" ms │ ") && before.contains("B/s"),
        "{before}"
    );
    app.handle_event(&char_key('h'));
    let line = status_line(&mut app, cols, rows);
    assert!(line.contains(app.message()), "{line}");
    assert!(
        line.contains("GRAB") && line.contains("truecolor"),
        "{line}"
    );
}
