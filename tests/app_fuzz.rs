//! Input fuzzing: a seeded stream of keys, clicks, drags, wheel turns and resizes (to zero, one
//! cell and very large terminals) into the headless sandbox, with time passing and frames drawn.
//! Nothing may panic, and the world must stay finite whatever is pushed, pulled, spawned or resized.

use std::time::Duration;

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use nudge::app::{App, AppConfig};
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
    }
    let _ = std::fs::remove_dir_all(&save_dir);
}
