//! Input fuzzing: a seeded stream of keys, clicks, drags, wheel turns and resizes (to zero, one
//! cell and very large terminals) into the headless sandbox, with time passing and frames drawn.
//! Nothing may panic, and the world must stay finite whatever is pushed, pulled, spawned or resized.
//! Each session is recorded: the recording must read back and replay to the very same world.

use std::time::Duration;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use nudge::app::{App, AppConfig};
use nudge::physics::World;
use nudge::recording::{self, Recording};
use nudge::scene::builtin;
use nudge::util::SplitMix64;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

fn random_event(rng: &mut SplitMix64, area: Rect) -> Event {
    let pick = |rng: &mut SplitMix64, n: u64| (rng.next_u64() % n) as usize;
    let modifiers = [
        KeyModifiers::NONE,
        KeyModifiers::SHIFT,
        KeyModifiers::CONTROL,
        KeyModifiers::ALT,
    ][pick(rng, 4)];
    match pick(rng, 10) {
        0..=3 => {
            let keys = "wasdeWASDEbsfxgmprn.<>[]+-?ohitc 123456789";
            let code = match pick(rng, 12) {
                0 => KeyCode::Up,
                1 => KeyCode::Down,
                2 => KeyCode::Left,
                3 => KeyCode::Right,
                4 => KeyCode::Tab,
                5 => KeyCode::BackTab,
                6 => KeyCode::Home,
                7 => KeyCode::F(1),
                _ => KeyCode::Char(keys.chars().nth(pick(rng, keys.len() as u64)).unwrap()),
            };
            Event::Key(KeyEvent::new(code, modifiers))
        }
        4..=8 => {
            let button = [MouseButton::Left, MouseButton::Right, MouseButton::Middle][pick(rng, 3)];
            let kind = match pick(rng, 7) {
                0 | 1 => MouseEventKind::Down(button),
                2 | 3 => MouseEventKind::Drag(button),
                4 => MouseEventKind::Up(button),
                5 => MouseEventKind::ScrollUp,
                _ => MouseEventKind::ScrollDown,
            };
            // Sometimes outside the terminal: a report from before a shrink.
            let column = (rng.next_u64() % (u64::from(area.width) + 20)) as u16;
            let row = (rng.next_u64() % (u64::from(area.height) + 20)) as u16;
            Event::Mouse(MouseEvent {
                kind,
                column,
                row,
                modifiers,
            })
        }
        _ => {
            let (cols, rows) = match pick(rng, 5) {
                0 => (0, 0),
                1 => (1, 1),
                2 => (500, 200),
                _ => (
                    1 + (rng.next_u64() % 200) as u16,
                    1 + (rng.next_u64() % 60) as u16,
                ),
            };
            Event::Resize(cols, rows)
        }
    }
}

/// The world a recording's replay ends with: every input applied at its step, those at the last
/// step too (the session ended after them).
fn replayed(recording: &Recording) -> World {
    let mut world = recording.scene.build_world_with(recording.settings.clone());
    let bodies: Vec<_> = recording.scene.bodies.iter().map(|b| b.desc).collect();
    let mut inputs = recording.inputs.iter().peekable();
    for _ in 0..recording.end {
        let now = world.step_count();
        while let Some((_, input, _)) = inputs.next_if(|(step, ..)| *step == now) {
            world.apply_input(input, &bodies).unwrap();
        }
        world.step();
    }
    for (_, input, _) in inputs {
        world.apply_input(input, &bodies).unwrap();
    }
    world
}

/// Plays `app` on to the end of its timeline, ends its recording at `path`, reads it back and checks
/// it replays to the app's world.
fn check_recording(app: &mut App, path: &std::path::Path, what: &str) {
    // Played on to the end of its timeline, then one more step: inputs a rewound timeline holds
    // for the step it stands at are applied before that step (the replay applies those of the
    // last step too).
    while app.timeline().rewound_steps(app.world()) > 0 {
        app.step_physics();
    }
    app.step_physics();
    app.finish_recording().unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let recording = recording::parse(&text, &path.display().to_string())
        .unwrap_or_else(|err| panic!("{what}: the recording is refused: {err}"));
    assert_eq!(app.world().step_count(), recording.end, "{what}");
    let world = replayed(&recording);
    assert_eq!(world.len(), app.world().len(), "{what}: bodies");
    for (i, (a, b)) in world.bodies().iter().zip(app.world().bodies()).enumerate() {
        assert!(
            a.pose() == b.pose()
                && a.linear_velocity() == b.linear_velocity()
                && a.angular_velocity() == b.angular_velocity(),
            "{what}: body {i} replays differently"
        );
    }
}

fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

#[test]
fn a_view_changed_while_rewound_keeps_the_recording_readable() {
    // Found by fuzzing: the camera moved after `[` was written at the rewound step, behind the
    // inputs already written after it, and `nudge replay` refused the file.
    let path = std::env::temp_dir().join(format!("nudge-rewound-view-{}.toml", std::process::id()));
    let recording_app = || {
        let mut app = App::new(builtin::by_name("default").unwrap(), AppConfig::default());
        app.resize(Rect::new(0, 0, 80, 24));
        app.start_recording(&path).unwrap();
        for step in 0..40 {
            if step == 30 {
                app.handle_event(&key(KeyCode::Char('b')));
                app.handle_event(&key(KeyCode::Right));
            }
            app.step_physics();
        }
        app.handle_event(&key(KeyCode::Char('[')));
        app.handle_event(&key(KeyCode::Left));
        app.step_physics();
        app
    };
    let mut app = recording_app();
    app.handle_event(&key(KeyCode::Char(']')));
    app.handle_event(&key(KeyCode::Char(']')));
    assert_eq!(app.world().step_count(), 40, "back at the present");
    check_recording(&mut app, &path, "rewound view");
    // A change made while rewound cuts the future off: the recording still reads and replays.
    let mut app = recording_app();
    app.handle_event(&key(KeyCode::Char('s')));
    app.step_physics();
    assert_eq!(
        app.world().step_count(),
        27,
        "one step after the rewound one"
    );
    check_recording(&mut app, &path, "rewound view, then a sphere");
    let _ = std::fs::remove_file(&path);
}

#[test]
fn a_settings_change_then_a_reset_replays_the_same() {
    // Found by fuzzing: sub-steps changed in the settings panel, then `r` before the next step,
    // and the recording lost the change (the replay stepped with the old sub-steps).
    let path =
        std::env::temp_dir().join(format!("nudge-settings-reset-{}.toml", std::process::id()));
    let mut app = App::new(builtin::by_name("default").unwrap(), AppConfig::default());
    app.resize(Rect::new(0, 0, 80, 24));
    app.start_recording(&path).unwrap();
    for _ in 0..10 {
        app.step_physics();
    }
    for code in [
        KeyCode::Char('t'),
        KeyCode::Right,
        KeyCode::Esc,
        KeyCode::Char('r'),
    ] {
        app.handle_event(&key(code));
    }
    assert_eq!(app.world().settings().substeps, 5, "the panel's first row");
    for _ in 0..10 {
        app.step_physics();
    }
    check_recording(&mut app, &path, "sub-steps, then a reset");
    let _ = std::fs::remove_file(&path);
}

#[test]
fn random_input_never_panics_and_the_world_stays_finite() {
    let save_dir = std::env::temp_dir().join(format!("nudge-app-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&save_dir).unwrap();
    let mut rng = SplitMix64(0xf022);
    for scene in ["default", "stack", "dominoes"] {
        let config = AppConfig {
            supersample: false,
            save_dir: Some(save_dir.clone()),
            ..AppConfig::default()
        };
        let mut app = App::new(builtin::by_name(scene).unwrap(), config);
        let record = save_dir.join(format!("{scene}-recording.toml"));
        app.start_recording(&record).unwrap();
        let mut area = Rect::new(0, 0, 100, 30);
        app.resize(area);
        let (start_bodies, mut most_bodies, mut draws) = (app.world().len(), 0, 0);
        for event_index in 0..1500 {
            let event = random_event(&mut rng, area);
            if let Event::Resize(cols, rows) = event {
                area = Rect::new(0, 0, cols, rows);
            }
            app.handle_event(&event);
            if event_index % 5 == 0 {
                app.advance(Duration::from_millis(rng.next_u64() % 100));
            }
            if event_index % 25 == 0 && area.area() <= 200 * 60 {
                let mut buffer = Buffer::empty(area);
                app.draw(area, &mut buffer);
                draws += 1;
            }
            most_bodies = most_bodies.max(app.world().len());
            let finite = app.world().bodies().iter().all(|b| {
                b.pose().is_finite()
                    && b.linear_velocity().is_finite()
                    && b.angular_velocity().is_finite()
            });
            assert!(
                finite,
                "{scene}: non-finite after event {event_index}: {event:?}"
            );
        }
        // The stream must have reached the sandbox: bodies spawned, frames drawn.
        assert!(
            most_bodies > start_bodies && draws > 20,
            "{scene}: {most_bodies} bodies at most, {draws} frames drawn"
        );
        check_recording(&mut app, &record, scene);
    }
    let _ = std::fs::remove_dir_all(&save_dir);
}
