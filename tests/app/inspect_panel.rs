//! The inspector panel, headless: its numbers are the world's, it fits an 80 × 24 terminal with
//! the scene shrunk beside it, and clicks still pick what is drawn under them.

use crate::common;

use common::app::{cell_of, char_key};
use crossterm::event::{Event, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use nudge::app::panels::inspector::{
    self, BodyReport, BodyState, WorldReport, number_cols, short, short3_in,
};
use nudge::app::{App, AppConfig};
use nudge::physics::BodyId;
use nudge::render::Frame;
use nudge::scene;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

fn app_for(name: &str) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    App::new(scene::load(name).expect("built-in scene"), config)
}

fn click(app: &mut App, button: MouseButton, cell: (u16, u16)) {
    for kind in [MouseEventKind::Down(button), MouseEventKind::Up(button)] {
        app.handle_event(&Event::Mouse(MouseEvent {
            kind,
            column: cell.0,
            row: cell.1,
            modifiers: KeyModifiers::NONE,
        }));
    }
}

/// Draws the app into a fresh buffer of `cols × rows`; returns it and its text, one line per row.
fn draw(app: &mut App, cols: u16, rows: u16) -> (Buffer, Vec<String>) {
    let area = Rect::new(0, 0, cols, rows);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    let lines = (0..rows)
        .map(|y| (0..cols).map(|x| buf[(x, y)].symbol()).collect::<String>())
        .collect();
    (buf, lines)
}

#[test]
fn the_inspectors_numbers_equal_the_worlds() {
    let mut app = app_for("default");
    app.resize(Rect::new(0, 0, 140, 44));
    for _ in 0..40 {
        app.step_physics();
    }
    app.handle_event(&char_key('i'));
    app.handle_event(&char_key(' '));
    let (_, before) = draw(&mut app, 140, 44);
    assert!(
        before.iter().any(|l| l.contains("click a body")),
        "{before:#?}"
    );
    // Select body 1 by clicking its centre (paused: the click selects, the world stays put).
    let target = BodyId(1);
    let cell = cell_of(&app, app.world().body(target).pose().position);
    click(&mut app, MouseButton::Left, cell);
    assert_eq!(app.selected(), Some(target));

    let world = app.world();
    let body = world.body(target);
    let report = BodyReport::of(world, target, false).unwrap();
    assert_eq!(report.mass, body.mass());
    assert_eq!(report.inertia, body.inertia_local());
    assert_eq!(report.position, body.pose().position);
    assert_eq!(report.velocity, body.linear_velocity());
    assert_eq!(report.angular_velocity, body.angular_velocity());
    assert_eq!(report.kinetic_energy, body.kinetic_energy());
    assert_eq!(report.shape, *body.shape());
    // Contacts and depth, counted here from the manifolds that touch the body.
    let touching: Vec<_> = world
        .contacts()
        .filter(|c| (c.a == target || c.b == target) && c.touching())
        .collect();
    assert_eq!(report.contacts, touching.len());
    let deepest = touching
        .iter()
        .flat_map(|c| c.points().iter().map(|p| -p.separation))
        .fold(0.0f32, f32::max);
    assert_eq!(report.penetration, deepest);

    let expected_state = if body.is_sleeping() {
        BodyState::Asleep
    } else {
        BodyState::Awake
    };
    assert_eq!(report.state, expected_state);

    let w = WorldReport::of(world);
    assert_eq!((w.awake, w.bodies), (world.awake_count(), world.len()));
    let all_touching: Vec<_> = world.contacts().filter(|c| c.touching()).collect();
    assert_eq!(w.contacts, all_touching.len());
    // Awake, the solver handled those contacts (and speculative ones) in the last step.
    assert!(w.contacts <= world.contact_count());
    let deepest_anywhere = all_touching
        .iter()
        .map(|c| c.penetration())
        .fold(0.0f32, f32::max);
    assert_eq!(w.penetration, deepest_anywhere);
    assert_eq!(w.islands, world.island_count());
    let ke: f32 = world
        .bodies()
        .iter()
        .filter(|b| !b.is_static())
        .map(|b| b.kinetic_energy())
        .sum();
    assert!((w.kinetic_energy - ke).abs() <= 1e-6 * ke.max(1.0));
    let pe: f32 = world
        .bodies()
        .iter()
        .filter(|b| !b.is_static())
        .map(|b| b.mass() * 9.81 * b.pose().position.y)
        .sum();
    assert!((w.potential_energy - pe).abs() <= 1e-4 * pe.abs().max(1.0));

    // And the panel prints those numbers.
    let (_, lines) = draw(&mut app, 140, 44);
    let panel: String = lines
        .iter()
        .map(|l| l.chars().skip(140 - 36).collect::<String>() + "\n")
        .collect();
    let n = number_cols(inspector::WIDE_PANEL_COLS - 1);
    for expected in [
        format!("#{}", target.0),
        format!("{} kg", short(report.mass)),
        short3_in(report.inertia, n),
        short3_in(report.position, n),
        short3_in(report.velocity, n),
        short3_in(report.angular_velocity, n),
        format!("{} J", short(report.kinetic_energy)),
        format!("{}/{}", w.awake, w.bodies),
        format!("{} J", short(w.kinetic_energy)),
        format!("{} J", short(w.potential_energy)),
        short3_in(w.momentum, n),
    ] {
        assert!(panel.contains(&expected), "{expected:?} missing:\n{panel}");
    }
}

#[test]
fn at_80_by_24_the_panel_collapses_and_the_scene_shrinks_beside_it() {
    let mut app = app_for("default");
    app.resize(Rect::new(0, 0, 80, 24));
    let full = app.viewport_area();
    app.handle_event(&char_key('i'));
    let view = app.viewport_area();
    assert_eq!(view.height, full.height);
    assert_eq!(view.width, 80 - inspector::NARROW_PANEL_COLS);
    assert_eq!(app.viewport().width, u32::from(view.width));
    let (_, lines) = draw(&mut app, 80, 24);
    let panel: Vec<String> = lines[..23]
        .iter()
        .map(|l| l.chars().skip(view.width as usize).collect())
        .collect();
    let text = panel.join("\n");
    // The body and world sections both fit, whole, beside a 51-column scene.
    for label in ["body", "world", "awake", "Σmv", "islands"] {
        assert!(text.contains(label), "{label} missing:\n{text}");
    }
    // No half-block of the scene under the panel.
    assert!(!text.contains('▀'), "{text}");
    // The status bar still spans the terminal.
    assert!(lines[23].contains("? help"), "{}", lines[23]);
    // Closing it gives the scene its columns back.
    app.handle_event(&char_key('i'));
    assert_eq!(app.viewport_area(), full);
}

#[test]
fn with_the_panel_open_a_click_picks_the_body_drawn_under_it() {
    // Wide and at 80 × 24 (the collapsed panel), in both projections.
    for (cols, rows) in [(100u16, 30u16), (80, 24)] {
        for orthographic in [false, true] {
            clicks_pick_what_is_drawn(cols, rows, orthographic);
        }
    }
}

fn clicks_pick_what_is_drawn(cols: u16, rows: u16, orthographic: bool) {
    let mut app = app_for("default");
    app.resize(Rect::new(0, 0, cols, rows));
    for _ in 0..30 {
        app.step_physics();
    }
    app.handle_event(&char_key(' '));
    if orthographic {
        app.handle_event(&char_key('p'));
    }
    app.handle_event(&char_key('i'));
    assert!(app.inspector_area().is_some(), "{cols}x{rows}: no panel");
    draw(&mut app, cols, rows);
    let view = app.viewport_area();
    let frame: Frame = app.frame().clone();
    assert_eq!(frame.width(), u32::from(view.width));
    let mut checked = 0;
    for row in 0..view.height {
        for col in (0..view.width).step_by(2) {
            // Cells whose two pixels show the same body (or none): the click must pick just that.
            let (top, bottom) = (
                frame.id_at(col.into(), 2 * u32::from(row)),
                frame.id_at(col.into(), 2 * u32::from(row) + 1),
            );
            if top != bottom {
                continue;
            }
            let before = app.selected();
            // Middle button, twice: select (freeze, unfreeze) leaving the world as it was.
            click(&mut app, MouseButton::Middle, (col, row));
            click(&mut app, MouseButton::Middle, (col, row));
            match top {
                Some(id) => assert_eq!(
                    app.selected(),
                    Some(BodyId(id)),
                    "{cols}x{rows} cell {col},{row}"
                ),
                None => assert_eq!(app.selected(), before, "{cols}x{rows} cell {col},{row}"),
            }
            checked += 1;
        }
    }
    assert!(checked > 300, "{cols}x{rows}: {checked}");
    // The panel's cells pick nothing.
    let before = app.selected();
    click(&mut app, MouseButton::Middle, (view.width + 3, 5));
    assert_eq!(app.selected(), before);
}

mod bytes {
    use std::io;
    use std::time::Duration;

    use nudge::app::panels::overlays::OverlaySet;
    use nudge::app::run::{Screen, Turn, tick};
    use nudge::app::{App, AppConfig, DEFAULT_MAX_BYTES_PER_SECOND};
    use nudge::bench::app::shove_bottom_row;
    use nudge::scene::{self, cases};
    use nudge::term::ColorDepth;
    use ratatui::layout::Rect;

    const FRAME: Duration = Duration::from_nanos(1_000_000_000 / 30);

    fn open_everything(app: &mut App) {
        app.handle_event(&super::char_key('i'));
        app.set_overlays(OverlaySet::ALL);
    }

    #[test]
    fn with_the_panel_and_every_overlay_on_a_scene_at_rest_writes_zero_bytes() {
        let mut app = App::new(scene::load("default").unwrap(), AppConfig::default());
        let area = Rect::new(0, 0, 120, 40);
        app.resize(area);
        open_everything(&mut app);
        for _ in 0..1200 {
            if app.world().awake_count() == 0 {
                break;
            }
            app.step_physics();
        }
        assert_eq!(app.world().awake_count(), 0);
        let mut screen = Screen::fixed(io::sink(), area).unwrap();
        assert!(screen.present(&mut app).unwrap() > 1000);
        // One last frame may replace the rates with "idle"; then nothing.
        let sent: Vec<u64> = (0..60)
            .map(|_| tick(&mut app, &mut screen, FRAME).unwrap().bytes())
            .collect();
        assert!(sent[1..].iter().all(|&b| b == 0), "{sent:?}");
    }

    #[test]
    fn with_the_panel_and_every_overlay_on_a_truecolor_collapse_keeps_the_byte_budget() {
        let config = AppConfig {
            color_depth: ColorDepth::TrueColor,
            ..AppConfig::default()
        };
        let mut app = App::new(cases::pyramid(20), config);
        let area = Rect::new(0, 0, 200, 50);
        app.resize(area);
        open_everything(&mut app);
        let mut screen = Screen::fixed(io::sink(), area).unwrap();
        screen.present(&mut app).unwrap();
        let mut sent = Vec::new();
        let mut drawn = 0;
        for frame in 0..120 {
            if frame < 10 {
                shove_bottom_row(&mut app);
            }
            let turn = tick(&mut app, &mut screen, FRAME).unwrap();
            drawn += usize::from(matches!(turn, Turn::Drawn(_)));
            sent.push(turn.bytes());
        }
        let worst: u64 = sent.windows(30).map(|w| w.iter().sum()).max().unwrap();
        assert!(
            worst < DEFAULT_MAX_BYTES_PER_SECOND,
            "worst second {worst} B"
        );
        assert!(
            drawn > 30,
            "the panel still updates live: {drawn} frames drawn"
        );
    }
}

#[test]
fn the_panel_shows_the_steps_stages_timed_only_while_it_is_open() {
    let mut app = app_for("pyramid");
    let (cols, rows) = (140u16, 50u16);
    app.resize(Rect::new(0, 0, cols, rows));
    assert!(
        !app.world().is_profiling(),
        "closed, the step reads no clock"
    );
    app.handle_event(&char_key('i'));
    assert!(app.world().is_profiling());
    for _ in 0..10 {
        app.step_physics();
    }
    let (_, lines) = draw(&mut app, cols, rows);
    let view = app.viewport_area();
    let text: String = lines
        .iter()
        .map(|l| l.chars().skip(view.width as usize).collect::<String>() + "\n")
        .collect();
    for label in [
        " step ", "broad", "narrow", "prepare", "solve", "integr.", "store", "sleep",
    ] {
        assert!(text.contains(label), "{label:?} missing:\n{text}");
    }
    // The solve of a falling pyramid was timed: its row reads a time above zero, and the stages'
    // bars are drawn (how long each bar is depends on the machine's timings, so only the slowest
    // stage's is sure to show: a test must not fail on a loaded machine).
    let solve = text.lines().find(|l| l.starts_with("│solve")).unwrap();
    let solve_ms: f64 = solve
        .trim_start_matches("│solve")
        .split_whitespace()
        .next()
        .and_then(|ms| ms.parse().ok())
        .unwrap_or_else(|| panic!("no time on {solve:?}"));
    assert!(solve_ms > 0.0, "{solve}");
    assert!(text.contains('▪'), "no stage has a bar:\n{text}");
    // A reset keeps it on; closing the panel turns it off.
    app.handle_event(&char_key('r'));
    assert!(app.world().is_profiling());
    app.handle_event(&char_key('i'));
    assert!(!app.world().is_profiling());
}
