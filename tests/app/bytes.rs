//! Over SSH every byte counts: a scene at rest writes nothing after its first frame.

use std::io;
use std::time::Duration;

use nudge::app::run::{Screen, Turn, tick};
use nudge::app::{App, AppConfig, DEFAULT_MAX_BYTES_PER_SECOND};
use nudge::bench::app::shove_bottom_row;
use nudge::scene::{self, cases};
use nudge::term::{CellMode, ColorDepth};
use ratatui::layout::Rect;

/// One frame at 30 fps.
const FRAME: Duration = Duration::from_millis(33);

/// The default scene laid out for a 120×40 terminal.
fn default_app() -> (App, Rect) {
    default_app_in(CellMode::Half)
}

/// [`default_app`] in a cell mode.
fn default_app_in(cells: CellMode) -> (App, Rect) {
    let mut app = App::new(
        scene::load("default").expect("default scene"),
        AppConfig {
            cells,
            ..AppConfig::default()
        },
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
    for cells in CellMode::ALL {
        at_rest_in(cells);
    }
}

fn at_rest_in(cells: CellMode) {
    let (mut app, area) = default_app_in(cells);
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
        "{cells}: the default scene comes to rest"
    );

    let mut screen = screen_for(area);
    let first = screen.present(&mut app).expect("first frame");
    assert!(
        first > 1000,
        "{cells}: the first frame draws the scene ({first} bytes)"
    );
    for frame in 0..60 {
        let bytes = tick(&mut app, &mut screen, FRAME).expect("tick").bytes();
        assert_eq!(
            bytes, 0,
            "{cells}: frame {frame} at rest wrote {bytes} bytes"
        );
    }
}

#[test]
fn a_moving_scene_writes_only_changed_cells() {
    let (mut app, area) = default_app();
    let mut screen = screen_for(area);
    let first = screen.present(&mut app).expect("first frame");
    let mut later = 0;
    for _ in 0..10 {
        later += tick(&mut app, &mut screen, FRAME).expect("tick").bytes();
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
        tick(&mut app, &mut screen, FRAME).expect("tick").bytes();
    }
    assert_eq!(
        app.world().awake_count(),
        0,
        "the default scene comes to rest"
    );
    let mut drawn = Vec::new();
    for _ in 0..30 {
        drawn.push(tick(&mut app, &mut screen, FRAME).expect("tick").bytes());
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

/// The bytes each frame slot of a 200×50 truecolor pyramid collapse sends, 4 s at 30 fps, with the
/// byte budget `limit` (0 = none).
fn collapse_bytes(limit: u64) -> (Vec<u64>, usize) {
    let config = AppConfig {
        color_depth: ColorDepth::TrueColor,
        max_bytes_per_second: limit,
        ..AppConfig::default()
    };
    let mut app = App::new(cases::pyramid(20), config);
    let area = Rect::new(0, 0, 200, 50);
    app.resize(area);
    let mut screen = screen_for(area);
    screen.present(&mut app).expect("first frame");
    let mut sent = Vec::new();
    let mut held = 0;
    for frame in 0..120 {
        if frame < 10 {
            shove_bottom_row(&mut app);
        }
        let turn = tick(
            &mut app,
            &mut screen,
            Duration::from_nanos(1_000_000_000 / 30),
        )
        .expect("tick");
        held += usize::from(turn == Turn::Held);
        sent.push(turn.bytes());
    }
    (sent, held)
}

fn worst_second(sent: &[u64]) -> u64 {
    sent.windows(30).map(|w| w.iter().sum()).max().unwrap_or(0)
}

/// The budget, in the worst case: truecolor (ssh drops COLORTERM, but a user may ask for it)
/// while the pyramid collapses. Without the budget its worst second is over 1 MB; with it, every
/// second is under, and only the frames over the rate are held.
#[test]
fn a_truecolor_collapse_holds_every_second_under_the_byte_budget() {
    let (unlimited, none_held) = collapse_bytes(0);
    assert_eq!(none_held, 0);
    assert!(
        worst_second(&unlimited) > DEFAULT_MAX_BYTES_PER_SECOND,
        "the collapse must be heavy enough to test the budget: worst second {} B",
        worst_second(&unlimited)
    );
    let (sent, held) = collapse_bytes(DEFAULT_MAX_BYTES_PER_SECOND);
    let worst = worst_second(&sent);
    assert!(
        worst < DEFAULT_MAX_BYTES_PER_SECOND,
        "worst second {worst} B"
    );
    assert!(held > 0 && held < 30, "{held} of 120 frames held");
}
