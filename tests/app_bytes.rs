//! Over SSH every byte counts: a scene at rest writes nothing after its first frame.

use std::io;
use std::time::Duration;

use nudge::app::run::{Screen, tick};
use nudge::app::{App, AppConfig};
use nudge::scene;
use ratatui::layout::Rect;

/// One frame at 30 fps.
const FRAME: Duration = Duration::from_millis(33);

/// The default scene laid out for a 120×40 terminal.
fn default_app() -> (App, Rect) {
    let mut app = App::new(
        scene::load("default").expect("default scene"),
        AppConfig::default(),
    );
    let area = Rect::new(0, 0, 120, 40);
    app.resize(area);
    (app, area)
}

/// A screen of `area` that counts its bytes and throws them away.
fn screen_for(area: Rect) -> Screen<io::Sink> {
    Screen::fixed(io::sink(), area).expect("screen")
}

#[test]
fn a_scene_at_rest_writes_zero_bytes_per_frame_after_the_first() {
    let (mut app, area) = default_app();
    // Let everything settle and fall asleep (at most 20 simulated seconds).
    for _ in 0..1200 {
        if app.world().awake_count() == 0 {
            break;
        }
        app.step_physics();
    }
    assert_eq!(
        app.world().awake_count(),
        0,
        "the default scene comes to rest"
    );

    let mut screen = screen_for(area);
    let first = screen.present(&mut app).expect("first frame");
    assert!(
        first > 1000,
        "the first frame draws the scene ({first} bytes)"
    );
    for frame in 0..60 {
        let bytes = tick(&mut app, &mut screen, FRAME).expect("tick");
        assert_eq!(bytes, 0, "frame {frame} at rest wrote {bytes} bytes");
    }
}

#[test]
fn a_moving_scene_writes_only_changed_cells() {
    let (mut app, area) = default_app();
    let mut screen = screen_for(area);
    let first = screen.present(&mut app).expect("first frame");
    let mut later = 0;
    for _ in 0..10 {
        later += tick(&mut app, &mut screen, FRAME).expect("tick");
    }
    assert!(
        later / 10 < first,
        "a moving frame ({}) costs less than a full one ({first})",
        later / 10
    );
}

#[test]
fn coming_to_rest_draws_one_last_idle_frame_then_nothing() {
    let (mut app, area) = default_app();
    let mut screen = screen_for(area);
    screen.present(&mut app).expect("first frame");
    // Run until the world sleeps (at most 20 s of frames).
    for _ in 0..600 {
        if app.world().awake_count() == 0 {
            break;
        }
        tick(&mut app, &mut screen, FRAME).expect("tick");
    }
    assert_eq!(
        app.world().awake_count(),
        0,
        "the default scene comes to rest"
    );
    let mut drawn = Vec::new();
    for _ in 0..30 {
        drawn.push(tick(&mut app, &mut screen, FRAME).expect("tick"));
    }
    let frames_with_bytes = drawn.iter().filter(|&&b| b > 0).count();
    assert!(frames_with_bytes <= 1, "after rest: {drawn:?}");
    assert!(
        drawn[1..].iter().all(|&b| b == 0),
        "nothing after the idle frame: {drawn:?}"
    );

    let mut buffer = ratatui::buffer::Buffer::empty(area);
    app.draw(area, &mut buffer);
    let status: String = (0..area.width)
        .map(|x| buffer[(x, area.height - 1)].symbol().to_string())
        .collect();
    assert!(status.contains("idle"), "status bar: {status}");
}
