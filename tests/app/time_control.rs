//! Controlling time, driven as a person would (synthetic events into a headless app): a saved world
//! loads back bit for bit; a recorded session replays to the same trace as the live one, twice;
//! rewinding and going forward again gives the world never rewound; the rewind ring keeps its
//! memory bound; bad recordings are rejected with located errors; growth keeps density gently.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use glam::Vec3;
use nudge::app::time::timeline::{MAX_REWIND_BYTES, REWIND_SECONDS};
use nudge::app::world::grow::GROWTH_SPEED;
use nudge::app::{App, AppConfig};
use nudge::physics::{BodyId, World};
use nudge::scene::{self, Scene};
use ratatui::layout::Rect;

use crate::common;

use crate::common::temp::TempPath;
use common::app::{cell_of, key};

const COLS: u16 = 120;
const ROWS: u16 = 40;

fn app_with(scene: Scene, config: AppConfig) -> App {
    let mut app = App::new(
        scene,
        AppConfig {
            supersample: false,
            ..config
        },
    );
    app.resize(Rect::new(0, 0, COLS, ROWS));
    app
}

fn app_for(name: &str) -> App {
    app_with(scene::load(name).unwrap(), AppConfig::default())
}

fn ctrl(c: char) -> Event {
    Event::Key(KeyEvent::new(KeyCode::Char(c), KeyModifiers::CONTROL))
}

fn mouse(kind: MouseEventKind, cell: (u16, u16)) -> Event {
    Event::Mouse(MouseEvent {
        kind,
        column: cell.0,
        row: cell.1,
        modifiers: KeyModifiers::NONE,
    })
}

fn cell_of_body(app: &App, id: BodyId) -> (u16, u16) {
    cell_of(app, app.world().body(id).pose().position)
}

/// The `sim` trace rows of the world now.
fn rows(world: &World) -> String {
    let mut out = Vec::new();
    nudge::sim::write_trace_rows(&mut out, world.step_count(), world).unwrap();
    String::from_utf8(out).unwrap()
}

/// The live trace: rows per step, the latest written for a step winning (a rewound timeline
/// replaces what it cut off).
#[derive(Default)]
struct LiveTrace(BTreeMap<u64, String>);

impl LiveTrace {
    fn note(&mut self, app: &App) {
        self.0.insert(app.world().step_count(), rows(app.world()));
    }

    fn steps(&mut self, app: &mut App, n: usize) {
        for _ in 0..n {
            app.step_physics();
            self.note(app);
        }
    }

    fn text(&self, end: u64) -> String {
        let mut out = format!("{}\n", nudge::sim::TRACE_HEADER);
        for (_, rows) in self.0.range(..=end) {
            out.push_str(rows);
        }
        out
    }
}

/// A session touching every kind of input: pushes and pulls held over steps (the pointer dragged
/// while the camera orbits), a key nudge, a spawn, a freeze, gravity off and on, a resize, a reset.
fn play_session(app: &mut App, trace: &mut LiveTrace) {
    trace.note(app);
    trace.steps(app, 40);
    let target = cell_of_body(app, BodyId(1));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), target));
    trace.steps(app, 12);
    app.handle_event(&key(KeyCode::Left));
    app.handle_event(&mouse(
        MouseEventKind::Drag(MouseButton::Left),
        (target.0 + 1, target.1),
    ));
    trace.steps(app, 12);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), target));
    app.handle_event(&key(KeyCode::Char('w')));
    trace.steps(app, 10);
    let ball = cell_of_body(app, BodyId(3));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Right), ball));
    trace.steps(app, 20);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Right), ball));
    app.handle_event(&key(KeyCode::Char('>')));
    trace.steps(app, 5);
    app.handle_event(&key(KeyCode::Char('b')));
    trace.steps(app, 30);
    let other = cell_of_body(app, BodyId(2));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), other));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), other));
    app.handle_event(&key(KeyCode::Char('g')));
    trace.steps(app, 20);
    app.handle_event(&key(KeyCode::Char('g')));
    trace.steps(app, 30);
    app.handle_event(&key(KeyCode::Char('r')));
    trace.steps(app, 25);
}

/// The recording at `path` and an app replaying it, sized like the live ones.
fn replay_of(path: &Path) -> (nudge::recording::Recording, App) {
    let recording = nudge::recording::load(path.to_str().unwrap()).unwrap();
    let mut replay = App::replaying(
        &recording,
        AppConfig {
            supersample: false,
            ..AppConfig::default()
        },
    );
    replay.resize(Rect::new(0, 0, COLS, ROWS));
    (recording, replay)
}

fn replay_trace(recording: &Path) -> (std::process::Output, String) {
    let out = TempPath::new("replay.csv");
    let output = Command::new(env!("CARGO_BIN_EXE_nudge"))
        .args([
            "replay",
            recording.to_str().unwrap(),
            "--trace",
            out.0.to_str().unwrap(),
        ])
        .output()
        .expect("run nudge replay");
    let text = std::fs::read_to_string(&out.0).unwrap_or_default();
    (output, text)
}

#[test]
fn a_recorded_session_replays_headless_to_the_live_trace_twice() {
    let file = TempPath::new("session.toml");
    let mut app = app_for("default");
    app.start_recording(&file.0).unwrap();
    let mut live = LiveTrace::default();
    play_session(&mut app, &mut live);
    app.finish_recording().unwrap();
    let end = app.world().step_count();
    let text = std::fs::read_to_string(&file.0).unwrap();
    for kind in [
        "force =",
        "set_static =",
        "gravity =",
        "add_body =",
        "resize =",
        "reset = true",
        "camera =",
    ] {
        assert!(text.contains(kind), "the recording holds a {kind} input");
    }
    let (first, a) = replay_trace(&file.0);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let (_, b) = replay_trace(&file.0);
    assert_eq!(a, b, "two replays give the same bytes");
    assert_eq!(
        a,
        live.text(end),
        "the replay's trace is the live session's"
    );
}

#[test]
fn a_replay_in_the_app_shows_the_recorded_camera_and_world_at_every_step() {
    let file = TempPath::new("session.toml");
    let mut app = app_for("default");
    app.start_recording(&file.0).unwrap();
    let mut live = LiveTrace::default();
    play_session(&mut app, &mut live);
    app.finish_recording().unwrap();
    let (recording, mut replay) = replay_of(&file.0);
    // World-changing input is ignored while replaying.
    replay.handle_event(&key(KeyCode::Char('g')));
    replay.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), (60, 20)));
    let mut shown = LiveTrace::default();
    shown.note(&replay);
    while replay.world().step_count() < recording.end {
        replay.step_physics();
        shown.note(&replay);
    }
    assert_eq!(shown.text(recording.end), live.text(recording.end));
    assert_eq!(
        replay.camera(),
        app.camera(),
        "the view ends where the session's did"
    );
}

/// In a replay `[` said "rewound 41.3 s" a second into a 42 s recording: it counted back from the
/// recording's end. The status bar says where in the recording the picture is.
#[test]
fn rewinding_a_replay_says_where_in_the_recording_it_is() {
    let file = TempPath::new("replay-position.toml");
    let mut app = app_for("default");
    app.start_recording(&file.0).unwrap();
    for _ in 0..600 {
        app.step_physics();
    }
    app.finish_recording().unwrap();
    let (_, mut replay) = replay_of(&file.0);
    for _ in 0..100 {
        replay.step_physics();
    }
    replay.handle_event(&key(KeyCode::Char('[')));
    assert_eq!(replay.world().step_count(), 85);
    assert_eq!(
        replay.message(),
        "at 1.4 s of 10.0 s ([ back, ] forward, space plays)"
    );
    replay.handle_event(&key(KeyCode::Char(']')));
    replay.handle_event(&key(KeyCode::Char(']')));
    assert_eq!(
        replay.message(),
        "at 1.9 s of 10.0 s ([ back, ] forward, space plays)"
    );
}

#[test]
fn rewinding_and_going_forward_again_gives_the_world_never_rewound() {
    let mut app = app_for("pyramid");
    let mut live = LiveTrace::default();
    // Knock the pyramid: a held push, so there are inputs inside the rewound span.
    live.steps(&mut app, 30);
    let target = cell_of_body(&app, BodyId(5));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), target));
    live.steps(&mut app, 40);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), target));
    live.steps(&mut app, 100);
    let now = app.world().step_count();
    let present = app.world().snapshot();
    for _ in 0..8 {
        app.handle_event(&key(KeyCode::Char('[')));
    }
    assert_eq!(app.world().step_count(), now - 8 * 15);
    assert!(app.message().contains("rewound 2.0 s"), "{}", app.message());
    assert!(app.is_paused());
    // The world at each rewound step is the one the live run had there.
    assert_eq!(rows(app.world()), live.0[&app.world().step_count()]);
    for _ in 0..8 {
        app.handle_event(&key(KeyCode::Char(']')));
    }
    assert_eq!(app.world().snapshot().first_difference(&present), None);
    // Back again, then on by stepping (space and steps), through the recorded push.
    app.handle_event(&key(KeyCode::Char('[')));
    app.handle_event(&key(KeyCode::Char('[')));
    app.handle_event(&key(KeyCode::Char(' ')));
    while app.world().step_count() < now {
        app.step_physics();
    }
    assert_eq!(app.world().snapshot().first_difference(&present), None);
    assert_eq!(app.timeline().rewound_steps(app.world()), 0);
}

#[test]
fn a_new_input_after_a_rewind_starts_a_new_timeline_which_the_recording_keeps() {
    let file = TempPath::new("branch.toml");
    let mut app = app_for("default");
    app.start_recording(&file.0).unwrap();
    let mut live = LiveTrace::default();
    live.note(&app);
    live.steps(&mut app, 60);
    app.handle_event(&key(KeyCode::Char('g')));
    live.steps(&mut app, 60);
    for _ in 0..3 {
        app.handle_event(&key(KeyCode::Char('[')));
    }
    let branch = app.world().step_count();
    assert_eq!(branch, 120 - 45);
    // A push where the old timeline had none: the future is cut off here.
    let target = cell_of_body(&app, BodyId(1));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), target));
    live.steps(&mut app, 10);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), target));
    assert_eq!(
        app.timeline().end(),
        app.world().step_count(),
        "the old future is gone"
    );
    live.steps(&mut app, 80);
    app.finish_recording().unwrap();
    let end = app.world().step_count();
    let text = std::fs::read_to_string(&file.0).unwrap();
    assert!(
        text.contains("truncate = true"),
        "the recording says where the timeline turned"
    );
    let (output, trace) = replay_trace(&file.0);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert_eq!(
        trace,
        live.text(end),
        "the replay follows the timeline actually played"
    );
}

#[test]
fn the_rewind_ring_keeps_thirty_seconds_within_its_memory_bound() {
    let mut app = app_for("pyramid");
    let span = (REWIND_SECONDS * 60.0) as u64;
    for _ in 0..span + 300 {
        app.step_physics();
    }
    let timeline = app.timeline();
    let now = app.world().step_count();
    assert!(
        now - timeline.oldest() >= span,
        "at least 30 s kept: {}",
        now - timeline.oldest()
    );
    assert!(
        now - timeline.oldest() <= span + 30,
        "not much more: {}",
        now - timeline.oldest()
    );
    assert!(timeline.bytes() <= MAX_REWIND_BYTES);
    // A tighter bound: fewer seconds, never more bytes (one keyframe is always kept).
    let one = app.world().snapshot().bytes();
    let budget = 10 * one;
    app.timeline_mut().set_max_bytes(budget);
    for _ in 0..60 {
        app.step_physics();
        assert!(
            app.timeline().bytes() <= budget,
            "{} > {budget}",
            app.timeline().bytes()
        );
    }
    assert!(app.timeline().keyframe_count() >= 9);
    // Rewinding stops at the oldest keyframe.
    for _ in 0..100 {
        app.handle_event(&key(KeyCode::Char('[')));
    }
    assert_eq!(app.world().step_count(), app.timeline().oldest());
    assert!(
        app.message().contains("can't rewind further"),
        "{}",
        app.message()
    );
}

#[test]
fn a_saved_world_loads_back_bit_for_bit_and_ctrl_s_names_the_file() {
    let dir = TempPath::new("saves");
    std::fs::create_dir(&dir.0).unwrap();
    let config = AppConfig {
        save_dir: Some(dir.0.clone()),
        ..AppConfig::default()
    };
    let mut app = app_with(scene::load("default").unwrap(), config);
    for _ in 0..20 {
        app.step_physics();
    }
    // Mid-air and spinning, one body frozen, gravity changed.
    let target = cell_of_body(&app, BodyId(2));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), target));
    app.handle_event(&key(KeyCode::Char('g')));
    app.handle_event(&key(KeyCode::Char('b')));
    for _ in 0..7 {
        app.step_physics();
    }
    app.handle_event(&ctrl('s'));
    let message = app.message().to_string();
    assert!(message.starts_with("saved "), "{message}");
    let path = message.trim_start_matches("saved ");
    assert!(Path::new(path).starts_with(&dir.0), "{path}");
    let name = Path::new(path).file_name().unwrap().to_str().unwrap();
    assert!(
        name.starts_with("nudge-")
            && name.ends_with(".toml")
            && name.len() == "nudge-YYYYMMDD-HHMMSS.toml".len(),
        "{name}"
    );
    let loaded = scene::load(path).unwrap();
    let world = loaded.build_world();
    let saved = app.world();
    assert_eq!(world.len(), saved.len());
    let bits = |w: &World, i: usize| {
        let b = w.body(BodyId(i as u32));
        let p = b.pose();
        let floats = [
            p.position.to_array().to_vec(),
            p.rotation.to_array().to_vec(),
            b.linear_velocity().to_array().to_vec(),
            b.angular_velocity().to_array().to_vec(),
            vec![
                b.mass(),
                b.friction(),
                b.restitution(),
                b.rolling_resistance(),
            ],
            b.inertia_local().to_array().to_vec(),
        ]
        .concat();
        (
            floats.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            b.is_static(),
            *b.shape(),
        )
    };
    for i in 0..saved.len() {
        assert_eq!(bits(&world, i), bits(saved, i), "body {i}");
    }
    assert!(
        world.body(BodyId(2)).is_static(),
        "frozen is saved as static"
    );
    assert_eq!(world.settings().gravity, Vec3::ZERO);
    assert_eq!(world.settings().dt.to_bits(), saved.settings().dt.to_bits());
    assert_eq!(loaded.camera.position, app.camera().position);
    assert_eq!(loaded.camera.target, app.camera().target);
    // Run on from both: the same future.
    let mut from_file = world;
    let mut from_app = World::new(Default::default());
    from_app.restore(&saved.snapshot());
    for _ in 0..60 {
        from_file.step();
        from_app.step();
    }
    let (a, b) = (rows(&from_file), rows(&from_app));
    let strip = |t: &str| {
        t.lines()
            .map(|l| l.split_once(',').unwrap().1.to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        strip(&a),
        strip(&b),
        "the loaded world moves as the saved one"
    );
    // `nudge sim` reads it too.
    let status = Command::new(env!("CARGO_BIN_EXE_nudge"))
        .args(["sim", "--scene", path, "--steps", "2"])
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
}

/// A body frozen in the sandbox was saved as `static = true`: loaded back it was scenery, drawn
/// checkered like the floor, and a click to unfreeze it said "part of the scenery".
#[test]
fn a_body_frozen_when_saved_loads_back_frozen_and_unfreezes_with_its_mass() {
    let dir = TempPath::new("frozen-saves");
    std::fs::create_dir(&dir.0).unwrap();
    let config = AppConfig {
        save_dir: Some(dir.0.clone()),
        ..AppConfig::default()
    };
    let mut app = app_with(scene::load("default").unwrap(), config.clone());
    for _ in 0..20 {
        app.step_physics();
    }
    let target = cell_of_body(&app, BodyId(2));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), target));
    assert_eq!(app.message(), "froze box #2");
    app.handle_event(&ctrl('s'));
    let path = app.message().trim_start_matches("saved ").to_string();
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.matches("frozen = true").count(), 1, "{text}");
    assert_eq!(
        text.matches("static = true").count(),
        5,
        "the floor and its rim's four walls: {text}"
    );

    let loaded = scene::load(&path).unwrap();
    let frozen: Vec<bool> = loaded.bodies.iter().map(|b| b.frozen).collect();
    assert_eq!(
        frozen,
        [false, false, true, false, false, false, false, false, false]
    );
    assert!(loaded.bodies[2].desc.is_static);
    // Its own colour, not the floor's.
    assert_eq!(
        loaded.bodies[2].color,
        scene::load("default").unwrap().bodies[2].color
    );

    let mut back = app_with(loaded, config);
    let target = cell_of_body(&back, BodyId(2));
    back.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), target));
    assert_eq!(back.message(), "unfroze box #2");
    let body = back.world().body(BodyId(2));
    assert!(!body.is_static());
    assert_eq!(body.mass(), 5.0);
    // The floor is still scenery.
    let floor = cell_of(&back, Vec3::new(-0.8, 0.0, -1.2));
    back.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), floor));
    assert_eq!(back.message(), "floor is part of the scenery");
}

#[test]
fn saving_into_an_unwritable_directory_says_so_and_the_sandbox_carries_on() {
    let config = AppConfig {
        save_dir: Some(PathBuf::from("/nonexistent/nudge/saves")),
        ..AppConfig::default()
    };
    let mut app = app_with(scene::load("default").unwrap(), config);
    app.handle_event(&ctrl('s'));
    assert!(
        app.message()
            .starts_with("could not save into /nonexistent/nudge/saves"),
        "{}",
        app.message()
    );
    assert!(!app.should_quit());
    let before = app.world().step_count();
    app.step_physics();
    assert_eq!(app.world().step_count(), before + 1);
}

/// Runs `nudge replay FILE --trace OUT` on `text` and expects exit status 2 and a message at
/// `FILE:LINE:` containing `needle`.
fn assert_rejected(text: &str, line: usize, needle: &str) {
    let file = TempPath::new("bad.toml");
    std::fs::write(&file.0, text).unwrap();
    let (output, _) = replay_trace(&file.0);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let prefix = format!("nudge: {}:{line}:", file.0.display());
    assert!(
        stderr.starts_with(&prefix),
        "expected {prefix}..., got {stderr}"
    );
    assert!(stderr.contains(needle), "expected {needle:?} in {stderr}");
}

fn good_recording() -> String {
    let file = TempPath::new("good.toml");
    let mut app = app_for("default");
    app.start_recording(&file.0).unwrap();
    let mut live = LiveTrace::default();
    live.steps(&mut app, 10);
    let target = cell_of_body(&app, BodyId(1));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), target));
    live.steps(&mut app, 3);
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), target));
    live.steps(&mut app, 3);
    app.finish_recording().unwrap();
    std::fs::read_to_string(&file.0).unwrap()
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines().position(|l| l.contains(needle)).expect(needle) + 1
}

#[test]
fn truncated_corrupted_and_wrong_version_recordings_are_rejected_where_they_go_wrong() {
    let good = good_recording();
    let lines = good.lines().count();
    // Cut at a line boundary: no [end].
    let cut = good.rsplit_once("\n[end]").unwrap().0;
    assert_rejected(cut, cut.lines().count(), "truncated: no [end] table");
    // Cut inside a line.
    let half = &good[..good.rfind("force = {").unwrap() + 20];
    assert_rejected(half, half.lines().count(), "");
    // Another version, another format.
    let v2 = good.replace("version = 1", "version = 2");
    assert_rejected(
        &v2,
        line_of(&v2, "version = 2"),
        "recording version 2 is not supported",
    );
    let other = good.replace("format = \"nudge-recording\"", "format = \"something\"");
    assert_rejected(&other, line_of(&other, "format ="), "not a nudge recording");
    // A body that does not exist.
    let first_force = good.find("force = { body = 1").unwrap();
    let mut bad_body = good.clone();
    bad_body.replace_range(
        first_force..first_force + "force = { body = 1".len(),
        "force = { body = 99",
    );
    assert_rejected(
        &bad_body,
        line_of(&bad_body, "body = 99") - 2,
        "body 99 does not exist",
    );
    // Garbage in the middle.
    let mut garbage = good.clone();
    let at = good.find("[[input]]").unwrap();
    garbage.insert_str(at, "@@@ not toml\n");
    assert_rejected(&garbage, line_of(&garbage, "@@@"), "");
    // Time going backwards.
    let back = good.replacen("step = 10\n", "step = 1000\n", 1);
    assert_rejected(
        &back,
        line_of(&back, "step = 11") - 1,
        "comes before the previous input's step 1000",
    );
    // A bad value in the embedded scene, located in the recording.
    let scene_bad = good.replacen("mass = 3.0", "mass = -3.0", 1);
    assert_rejected(
        &scene_bad,
        line_of(&scene_bad, "mass = -3.0"),
        "embedded scene: mass must be finite and > 0",
    );
    assert!(lines > 20);
}

#[test]
fn a_grown_body_keeps_its_density_and_pushes_its_neighbours_away_gently() {
    let mut app = app_for("stack");
    // Let the stack settle, select its second box.
    for _ in 0..120 {
        app.step_physics();
    }
    let id = BodyId(2);
    let cell = cell_of_body(&app, id);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
    let body = app.world().body(id);
    let density = body.mass() / body.shape().volume();
    // Five presses as a held key repeats them: one every two steps at 60 Hz (the body follows at
    // its growth speed).
    let mut fastest: f32 = 0.0;
    for _ in 0..5 {
        app.handle_event(&key(KeyCode::Char('>')));
        for _ in 0..2 {
            app.step_physics();
            for b in app.world().bodies() {
                fastest = fastest.max(b.linear_velocity().length());
            }
        }
    }
    while app.is_growing() {
        app.step_physics();
    }
    let body = app.world().body(id);
    let grown = body.mass() / body.shape().volume();
    assert!(
        (grown / density - 1.0).abs() < 1e-5,
        "density {density} → {grown}"
    );
    assert!(app.message().contains("kg"), "{}", app.message());
    for _ in 0..120 {
        app.step_physics();
        for b in app.world().bodies() {
            fastest = fastest.max(b.linear_velocity().length());
        }
    }
    // Grown 61 % in the middle of a stack: the boxes above ride up on its top face, which moves at
    // twice the growth speed (the bottom face pushes it up off the box below). Nothing is thrown
    // faster than that (at once, 5 cm of overlap in one step threw them at over 3 m/s).
    assert!(fastest < 1.2 * 2.0 * GROWTH_SPEED, "fastest {fastest} m/s");
    assert!(
        app.world().max_penetration() < 0.01,
        "{}",
        app.world().max_penetration()
    );
    // Shrinking back: mass follows.
    for _ in 0..5 {
        app.handle_event(&key(KeyCode::Char('<')));
    }
    while app.is_growing() {
        app.step_physics();
    }
    let body = app.world().body(id);
    assert!((body.mass() / body.shape().volume() / density - 1.0).abs() < 1e-5);
}

/// Saved while gravity was off, a world wrote `gravity = [0.0, 0.0, 0.0]`; loaded back, the
/// sandbox said gravity was on and `g` toggled between nothing and nothing.
#[test]
fn a_world_saved_with_gravity_off_loads_with_gravity_off_and_g_turns_it_on() {
    let dir = TempPath::new("gravity-off");
    std::fs::create_dir(&dir.0).unwrap();
    let config = AppConfig {
        save_dir: Some(dir.0.clone()),
        ..AppConfig::default()
    };
    let mut app = app_with(scene::load("default").unwrap(), config.clone());
    app.handle_event(&key(KeyCode::Char('g')));
    app.handle_event(&ctrl('s'));
    let path = app.message().trim_start_matches("saved ").to_string();

    let mut back = app_with(scene::load(&path).unwrap(), config);
    assert_eq!(back.world().settings().gravity, Vec3::ZERO);
    let mut screen = ratatui::buffer::Buffer::empty(Rect::new(0, 0, COLS, ROWS));
    back.draw(Rect::new(0, 0, COLS, ROWS), &mut screen);
    let status: String = (0..COLS)
        .map(|x| screen[(x, ROWS - 1)].symbol().to_string())
        .collect();
    assert!(status.contains("NO GRAVITY"), "{status}");
    back.handle_event(&key(KeyCode::Char('g')));
    assert_eq!(back.message(), "gravity on");
    for _ in 0..2 {
        back.step_physics();
    }
    assert_eq!(back.world().settings().gravity, Vec3::new(0.0, -9.81, 0.0));
}
