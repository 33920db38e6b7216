//! Hands, driven as a person would (synthetic crossterm events into a headless app), in both
//! projections: a held push shoves a box along the floor and never launches it; a grab drags a box
//! to the pointer, holds it in mid-air and throws it; the pinned 1 kg box holds every hand; the grab
//! mode shows in the status bar and as a tether in the picture; the wheel moves a held body; a drag
//! may leave the terminal, be released outside it, or have its body frozen under it.

use std::process::Command;

use crossterm::event::{KeyCode, MouseButton, MouseEventKind};
use nudge::app::App;
use nudge::app::input::grab::{TETHER_LINE, TETHER_MARKER};
use nudge::app::input::hand::{PUSH_SPEED, STRONG_SPEED_FACTOR};
use nudge::bench::hands::{
    self, COLS, ROWS, app_for, cell_of, frame, key, lone_box, mouse, settle,
};
use nudge::physics::BodyId;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

use crate::common::temp::TempPath;

/// Both projections, the lone box's id and a projection's name: shared with `hands_alongside`.
pub(super) const PROJECTIONS: [bool; 2] = [false, true];
pub(super) const BOX: BodyId = BodyId(1);

pub(super) fn name(orthographic: bool) -> &'static str {
    if orthographic {
        "orthographic"
    } else {
        "perspective"
    }
}

/// Draws the app into a fresh buffer and returns it.
fn draw(app: &mut App) -> Buffer {
    let area = Rect::new(0, 0, COLS, ROWS);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    buf
}

fn status_row(buf: &Buffer) -> String {
    (0..COLS)
        .map(|x| buf[(x, ROWS - 1)].symbol().to_string())
        .collect()
}

/// Grab mode on, left button down on the lone box's centre.
fn grab_lone_box(app: &mut App) -> (u16, u16) {
    app.handle_event(&key(KeyCode::Char('h')));
    let cell = cell_of(app, app.world().body(BOX).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    assert!(app.grab_points().is_some(), "the box is held");
    cell
}

fn grab_error(app: &App) -> f32 {
    let (anchor, pointer) = app.grab_points().expect("held");
    (anchor - pointer).length()
}

#[test]
fn holding_left_on_each_box_of_the_default_scene_for_three_seconds_shoves_it_along_the_floor() {
    /// The numbers: at least this far, and still on the floor.
    const MIN_MOVE_M: f32 = 0.5;
    // Never launched: no faster than the push's speed and a little for the motor's last step.
    let max_speed = PUSH_SPEED * 1.1;
    for orthographic in PROJECTIONS {
        for body in [BodyId(1), BodyId(2)] {
            let out = hands::held_push(body, 3.0, false, orthographic);
            let view = name(orthographic);
            assert!(out.moved_m >= MIN_MOVE_M, "{view}: {out:?}");
            assert!(out.on_floor, "{view}: {out:?}");
            assert!(out.peak_speed <= max_speed, "{view}: {out:?}");
        }
    }
}

#[test]
fn the_strong_hand_shoves_faster() {
    for orthographic in PROJECTIONS {
        let gentle = hands::held_push(BodyId(2), 0.5, false, orthographic);
        let strong = hands::held_push(BodyId(2), 0.5, true, orthographic);
        assert!(
            strong.peak_speed > 1.5 * gentle.peak_speed
                && strong.peak_speed <= PUSH_SPEED * STRONG_SPEED_FACTOR * 1.1,
            "{}: {gentle:?} {strong:?}",
            name(orthographic)
        );
    }
}

#[test]
fn a_tap_nudges_a_box_a_little() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        let start = app.world().body(BOX).pose().position;
        let cell = cell_of(&app, start);
        // Down and up in the same frame, before any step.
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
        for _ in 0..60 {
            frame(&mut app);
        }
        let moved = (app.world().body(BOX).pose().position - start).length();
        assert!(
            moved > 0.02 && moved < 0.3,
            "{}: a tap moved it {moved} m",
            name(orthographic)
        );
    }
}

#[test]
fn holding_the_right_button_pulls_a_box_toward_the_camera_in_both_projections() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        let start = app.world().body(BOX).pose().position;
        let toward = -app.camera().basis().forward;
        let cell = cell_of(&app, start);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Right), cell));
        for _ in 0..30 {
            frame(&mut app);
        }
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Right), cell));
        let moved = (app.world().body(BOX).pose().position - start).dot(toward);
        assert!(moved > 0.3, "{}: pulled {moved} m", name(orthographic));
        assert!(app.world().body(BOX).linear_velocity().length() <= PUSH_SPEED * 1.1);
    }
}

#[test]
fn holding_a_nudge_key_moves_a_body_steadily_and_never_launches_it() {
    // The terminal repeats a held key every frame; each press used to add another 1.5 g for 0.1 s,
    // and a second of `d` launched the 5 kg box at 120 m/s.
    for orthographic in PROJECTIONS {
        let view = name(orthographic);
        for (body, strong) in [(BodyId(1), false), (BodyId(2), false), (BodyId(2), true)] {
            let out = hands::held_nudge(body, 'd', 1.0, strong, orthographic);
            let speed = if strong {
                PUSH_SPEED * STRONG_SPEED_FACTOR
            } else {
                PUSH_SPEED
            };
            assert!(out.peak_speed <= speed * 1.1, "{view}: {out:?}");
            assert!(
                out.peak_speed >= speed * 0.8,
                "{view}, it got going: {out:?}"
            );
        }
        // A second's hold carries the box a couple of metres and it stays on the floor.
        let out = hands::held_nudge(BodyId(2), 'd', 1.0, false, orthographic);
        assert!(out.moved_m > 1.5 && out.on_floor, "{view}: {out:?}");
    }
}

#[test]
fn a_grabbed_three_kilogram_box_dragged_two_metres_follows_the_pointer_within_5_cm() {
    /// The number, half a second after the pointer stops.
    const MAX_ERROR_M: f32 = 0.05;
    for orthographic in PROJECTIONS {
        // Two metres in half a second: a brisk drag.
        let out = hands::drag_on_floor(2.0, 0.5, 0.5, orthographic);
        let view = name(orthographic);
        assert!(out.pointer_moved_m > 1.9, "{view}: {out:?}");
        assert!(out.body_moved_m > 1.9, "{view}: {out:?}");
        assert!(out.error_m < MAX_ERROR_M, "{view}: {out:?}");
    }
}

#[test]
fn a_box_grabbed_in_mid_air_and_held_still_stays_within_2_cm_of_the_pointer() {
    /// The number.
    const MAX_ERROR_M: f32 = 0.02;
    for orthographic in PROJECTIONS {
        let out = hands::hold_in_air(3.0, orthographic);
        assert!(
            out.max_error_m < MAX_ERROR_M,
            "{}: {out:?}",
            name(orthographic)
        );
    }
}

#[test]
fn a_drag_released_at_speed_throws_the_body_at_that_speed() {
    /// The band: the thrown speed over the pointer's.
    const BAND: (f32, f32) = (0.8, 1.2);
    for orthographic in PROJECTIONS {
        for speed in [2.0, 4.0, 6.0] {
            let out = hands::throw(speed, 0.5, orthographic);
            let ratio = out.thrown_speed / out.pointer_speed;
            assert!(
                ratio > BAND.0 && ratio < BAND.1,
                "{} at {speed} m/s: {out:?}",
                name(orthographic)
            );
        }
    }
}

#[test]
fn every_drag_of_one_to_six_metres_a_second_throws_at_its_speed() {
    /// The band, over drags from a cell every few frames to several cells a frame, lasting
    /// 0.4 to 1 s.
    const BAND: (f32, f32) = (0.8, 1.2);
    for orthographic in PROJECTIONS {
        let sweep = hands::throw_sweep(orthographic);
        assert_eq!(sweep.len(), 44);
        for (speed, drag_s, ratio) in sweep {
            assert!(
                ratio > BAND.0 && ratio < BAND.1,
                "{} at {speed} m/s for {drag_s} s: thrown at {ratio} × the pointer's speed",
                name(orthographic)
            );
        }
    }
}

#[test]
fn a_drag_released_outside_the_window_throws_at_the_drags_speed() {
    for orthographic in PROJECTIONS {
        let view = name(orthographic);
        let mut app = app_for(lone_box(2.5), orthographic);
        let cell = grab_lone_box(&mut app);
        for _ in 0..15 {
            frame(&mut app);
        }
        // Two cells a frame to the right, on past the window's edge; the button comes up there.
        let mut points = Vec::new();
        let mut at = cell;
        while at.0 < COLS + 10 {
            at.0 += 2;
            app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), at));
            points.push(app.grab_points().expect("held").1);
            frame(&mut app);
        }
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), at));
        assert!(app.grab_points().is_none(), "{view}");
        let last = points.len() - 1;
        let pointer = (points[last] - points[last - 15]) / 0.5;
        let thrown = app
            .world()
            .body(BOX)
            .linear_velocity()
            .dot(pointer.normalize());
        let ratio = thrown / pointer.length();
        assert!(
            ratio > 0.8 && ratio < 1.2,
            "{view}: thrown at {thrown} m/s, the pointer at {} m/s",
            pointer.length()
        );
    }
}

#[test]
fn the_light_box_pinned_under_a_thousand_kilograms_holds_every_hand() {
    /// As `a_light_box_pinned_under_a_heavy_one_holds_the_push_the_grab_and_a_strong_nudge`.
    const MAX_SLIDE_M: f32 = 0.01;
    for orthographic in PROJECTIONS {
        let moved = hands::pinned_under_heavy(orthographic);
        assert!(moved < MAX_SLIDE_M, "{}: {moved} m", name(orthographic));
    }
}

#[test]
fn h_toggles_grab_mode_and_the_status_bar_says_so() {
    let mut app = app_for(lone_box(0.5), false);
    assert!(!status_row(&draw(&mut app)).contains("GRAB"));
    app.handle_event(&key(KeyCode::Char('h')));
    let status = status_row(&draw(&mut app));
    assert!(status.contains("GRAB"), "{status}");
    assert_eq!(app.message(), "grab: drag a body, wheel moves it (h: push)");
    // While holding, the status bar names the body, the force and what the hand does.
    settle(&mut app);
    let cell = cell_of(&app, app.world().body(BOX).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    app.handle_event(&mouse(
        MouseEventKind::Drag(MouseButton::Left),
        (cell.0 + 6, cell.1),
    ));
    frame(&mut app);
    let status = status_row(&draw(&mut app));
    assert!(
        status.contains("grabbing box #1 · ") && status.contains(" N · "),
        "{status}"
    );
    app.handle_event(&mouse(
        MouseEventKind::Up(MouseButton::Left),
        (cell.0 + 6, cell.1),
    ));
    app.handle_event(&key(KeyCode::Char('h')));
    assert!(!status_row(&draw(&mut app)).contains("GRAB"));
    assert!(app.message().starts_with("left button pushes"));
}

#[test]
fn a_grab_draws_a_marker_on_the_held_point_and_a_line_to_the_pointer() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        let cell = grab_lone_box(&mut app);
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 12, cell.1 - 4),
        ));
        app.step_physics();
        draw(&mut app);
        let (anchor, _) = app.grab_points().unwrap();
        // The marker sits on the held point, through the same camera and viewport as the scene.
        let viewport = app.viewport();
        let clip = app.camera().clip_from_world(viewport.aspect()) * anchor.extend(1.0);
        let pixel = viewport.pixel_from_ndc(glam::Vec2::new(clip.x / clip.w, clip.y / clip.w));
        let frame_px = app.frame();
        assert_eq!(
            frame_px.pixel(pixel.x as u32, pixel.y as u32),
            TETHER_MARKER,
            "{}",
            name(orthographic)
        );
        let line = frame_px
            .pixels()
            .iter()
            .filter(|&&p| p == TETHER_LINE)
            .count();
        assert!(line >= 8, "{}: {line} line pixels", name(orthographic));
        app.handle_event(&mouse(
            MouseEventKind::Up(MouseButton::Left),
            (cell.0 + 12, cell.1 - 4),
        ));
        draw(&mut app);
        assert!(
            !app.frame().pixels().contains(&TETHER_MARKER),
            "the tether goes with the grab"
        );
    }
}

#[test]
fn the_wheel_and_plus_minus_move_a_held_body_nearer_and_farther() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(2.5), orthographic);
        grab_lone_box(&mut app);
        let forward = app.camera().basis().forward;
        let depth = |app: &App| {
            (app.world().body(BOX).pose().position - app.camera().position).dot(forward)
        };
        for _ in 0..20 {
            frame(&mut app);
        }
        let camera = *app.camera();
        let start = depth(&app);
        for _ in 0..3 {
            app.handle_event(&mouse(MouseEventKind::ScrollUp, (0, 0)));
        }
        for _ in 0..30 {
            frame(&mut app);
        }
        let nearer = depth(&app);
        for _ in 0..6 {
            app.handle_event(&key(KeyCode::Char('-')));
        }
        for _ in 0..60 {
            frame(&mut app);
        }
        let farther = depth(&app);
        let view = name(orthographic);
        assert_eq!(*app.camera(), camera, "{view}: the camera did not zoom");
        assert!(nearer < start - 0.5, "{view}: {start} → {nearer}");
        assert!(farther > start + 0.5, "{view}: {nearer} → {farther}");
        assert!(grab_error(&app) < 0.05, "{view}: it follows the plane");
    }
    // Not holding anything, the wheel zooms as before.
    let mut app = app_for(lone_box(0.5), false);
    let camera = *app.camera();
    app.handle_event(&mouse(MouseEventKind::ScrollUp, (0, 0)));
    assert_ne!(*app.camera(), camera);
}

#[test]
fn a_drag_that_leaves_the_terminal_and_comes_back_brings_the_body_back() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(2.5), orthographic);
        let cell = grab_lone_box(&mut app);
        // Off the right edge, and below the bottom onto the floor (terminals report such cells while
        // dragging), each time back again.
        for outside in [(COLS + 15, cell.1), (cell.0, ROWS + 8)] {
            app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), outside));
            for _ in 0..15 {
                frame(&mut app);
            }
            assert!(app.grab_points().is_some(), "still held");
            app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), cell));
            for _ in 0..60 {
                frame(&mut app);
            }
            assert!(
                grab_error(&app) < 0.05,
                "{} after {outside:?}: {} m",
                name(orthographic),
                grab_error(&app)
            );
        }
    }
}

#[test]
fn releasing_outside_the_window_lets_go() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(2.5), orthographic);
        let cell = grab_lone_box(&mut app);
        let outside = (COLS + 30, ROWS + 10);
        for i in 1..=6 {
            let at = (cell.0 + i * 5, cell.1);
            app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), at));
            frame(&mut app);
        }
        app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), outside));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), outside));
        assert!(app.grab_points().is_none());
        assert!(
            app.message().starts_with("threw box #1 at "),
            "{}",
            app.message()
        );
        // Nothing pulls it any more: it flies on under gravity.
        let v0 = app.world().body(BOX).linear_velocity();
        app.step_physics();
        let v1 = app.world().body(BOX).linear_velocity();
        let gravity_dv = app.world().settings().gravity * app.world().settings().dt;
        assert!((v1 - v0 - gravity_dv).length() < 1e-3, "{v0} → {v1}");
    }
    // A terminal that loses the release reports motion without a button: that lets go too.
    let mut app = app_for(lone_box(2.5), false);
    let cell = grab_lone_box(&mut app);
    frame(&mut app);
    app.handle_event(&mouse(MouseEventKind::Moved, cell));
    assert!(app.grab_points().is_none());
}

#[test]
fn a_body_frozen_while_grabbed_is_let_go_and_stays_put() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(2.5), orthographic);
        let cell = grab_lone_box(&mut app);
        for _ in 0..10 {
            frame(&mut app);
        }
        // Middle-click it where it is drawn now, the left button still down.
        let here = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), here));
        assert!(app.world().body(BOX).is_static());
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 10, cell.1),
        ));
        let pose = *app.world().body(BOX).pose();
        for _ in 0..30 {
            frame(&mut app);
        }
        assert_eq!(*app.world().body(BOX).pose(), pose, "frozen stays put");
        assert!(app.grab_points().is_none(), "the hand let go");
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
        draw(&mut app);
    }
}

#[test]
fn a_session_of_grabs_drags_and_throws_replays_to_the_same_trace() {
    let recording = TempPath::new("hands.toml");
    let trace = TempPath::new("hands.csv");
    let mut app = app_for(lone_box(2.5), false);
    app.start_recording(&recording.0).unwrap();
    let mut live = String::from(nudge::sim::TRACE_HEADER);
    live.push('\n');
    let note = |app: &App, live: &mut String| {
        let mut rows = Vec::new();
        nudge::sim::write_trace_rows(&mut rows, app.world().step_count(), app.world()).unwrap();
        live.push_str(&String::from_utf8(rows).unwrap());
    };
    note(&app, &mut live);
    let cell = grab_lone_box(&mut app);
    let step = |app: &mut App, live: &mut String, n: usize| {
        for _ in 0..n {
            app.step_physics();
            note(app, live);
        }
    };
    step(&mut app, &mut live, 20);
    for i in 1..=8 {
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 3 * i, cell.1),
        ));
        step(&mut app, &mut live, 2);
    }
    app.handle_event(&key(KeyCode::Char('+')));
    step(&mut app, &mut live, 10);
    app.handle_event(&mouse(
        MouseEventKind::Up(MouseButton::Left),
        (cell.0 + 24, cell.1),
    ));
    step(&mut app, &mut live, 30);
    app.handle_event(&key(KeyCode::Char('h')));
    let here = cell_of(&app, app.world().body(BOX).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), here));
    step(&mut app, &mut live, 20);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), here));
    step(&mut app, &mut live, 10);
    app.finish_recording().unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_nudge"))
        .args([
            "replay",
            recording.0.to_str().unwrap(),
            "--trace",
            trace.0.to_str().unwrap(),
        ])
        .output()
        .expect("run nudge replay");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let replayed = std::fs::read_to_string(&trace.0).unwrap();
    assert_eq!(replayed, live, "the replay's trace is the live session's");
    // It did move: the throw carried it off.
    assert!(live.lines().count() > 100);
}

#[test]
fn a_grab_is_recorded_as_held_points_and_a_bad_one_is_rejected_where_it_is() {
    let recording = TempPath::new("hold.toml");
    let mut app = app_for(lone_box(2.5), false);
    app.start_recording(&recording.0).unwrap();
    let cell = grab_lone_box(&mut app);
    app.handle_event(&mouse(
        MouseEventKind::Drag(MouseButton::Left),
        (cell.0 + 4, cell.1),
    ));
    frame(&mut app);
    app.handle_event(&mouse(
        MouseEventKind::Up(MouseButton::Left),
        (cell.0 + 4, cell.1),
    ));
    frame(&mut app);
    app.finish_recording().unwrap();
    let good = std::fs::read_to_string(&recording.0).unwrap();
    assert_eq!(good.matches("\nhold = { body = 1, ").count(), 2, "{good}");
    let bad = good.replacen("hertz = 8.0", "hertz = -8.0", 1);
    std::fs::write(&recording.0, &bad).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_nudge"))
        .args(["replay", recording.0.to_str().unwrap()])
        .output()
        .expect("run nudge replay");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    // Located at the input it is in (its `[[input]]` header, two lines above).
    let line = bad
        .lines()
        .position(|l| l.contains("hertz = -8.0"))
        .unwrap()
        - 1;
    assert!(
        stderr.contains(&format!(":{line}:")) && stderr.contains("a hold has hertz"),
        "{stderr}"
    );
}

#[test]
fn a_held_body_cannot_be_dragged_through_the_floor() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        app.handle_event(&key(KeyCode::Char('x')));
        let cell = grab_lone_box(&mut app);
        // Far below the floor, in one jump.
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0, ROWS - 2),
        ));
        let mut lowest = f32::INFINITY;
        for _ in 0..60 {
            frame(&mut app);
            lowest = lowest.min(app.world().body(BOX).pose().position.y);
        }
        // The box's centre stays half a box above the floor's top (y = 0), less a contact's give.
        assert!(
            lowest > 0.45,
            "{}: lowest centre {lowest}",
            name(orthographic)
        );
    }
}

#[test]
fn a_push_reaches_a_metre_and_dragging_after_the_body_reaches_on() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        let start = app.world().body(BOX).pose().position;
        let cell = cell_of(&app, start);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        for _ in 0..45 {
            frame(&mut app);
        }
        let held = app.world().body(BOX).pose().position;
        let view = name(orthographic);
        assert!(
            app.message()
                .ends_with("is out of reach (press again or drag to push on)"),
            "{view}: {}",
            app.message()
        );
        // Following it with the pointer pushes it on.
        let follow = cell_of(&app, held);
        app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), follow));
        for _ in 0..30 {
            frame(&mut app);
        }
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), follow));
        for _ in 0..60 {
            frame(&mut app);
        }
        let first = (held - start).length();
        let then = (app.world().body(BOX).pose().position - held).length();
        assert!(first > 0.9 && first < 2.0, "{view}: first push {first} m");
        assert!(then > 0.5, "{view}: pushed on {then} m");
    }
}

/// `physics_hard_cases` holds the pinned 1 kg box against the hands as plain numbers (the physics
/// tests do not import the app): they must be the app's figures.
#[test]
fn the_pinned_box_case_pushes_with_the_hands_figures() {
    use nudge::app::input::grab::Grab;
    use nudge::app::input::hand::{KEY_NUDGE_STEPS, STRONG_FACTOR, push_limits};
    use nudge::app::input::nudge::nudge_force;
    let mass = nudge::scene::cases::MASS_RATIO_LIGHT_KG;
    assert_eq!(mass, 1.0);
    assert_eq!(push_limits(mass, true).1, 60.0, "the strong push");
    assert_eq!(Grab::spring(mass, true).max_force, 120.0, "the strong grab");
    let nudge = STRONG_FACTOR * nudge_force(mass, glam::Vec3::X, false).x;
    assert_eq!(nudge, 60.0, "the strong key nudge");
    assert_eq!(KEY_NUDGE_STEPS, 6, "the key nudge's steps");
}
