//! The hands on jointed bodies (issue 30), driven as a person would: push, pull, grab, throw, freeze
//! and resize a link of the `wrecking` chain (a 50 kg ball on 20 hinged links) and the chain holds
//! together; a frozen link pins the chain there, next to the world or another frozen link, and
//! swings again once unfrozen. The inspector lists the selected body's joints live, and the joints
//! overlay draws their axes and forces, and labels the strongest.

use crate::common::joints::{all_finite, widest_joint};
use crossterm::event::{KeyCode, MouseButton, MouseEventKind};
use glam::Vec3;
use nudge::app::App;
use nudge::app::panels::joint_view::{
    JOINT_AXIS_COLOR, JOINT_FORCE_COLOR, JointFigures, MAX_FORCE_LABELS, force_text,
};
use nudge::app::panels::overlays::{OverlayKind, OverlaySet};
use nudge::bench::hands::{COLS, ROWS, app_for, frame, key, mouse, settle};
use nudge::geometry::{Camera, Shape};
use nudge::physics::BodyId;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

/// `wrecking`'s bodies: the floor, 36 boxes, then the links from the top, then the ball.
const FIRST_LINK: u32 = 37;
const LINKS: u32 = 20;
const MIDDLE: BodyId = BodyId(FIRST_LINK + 10);
const LINK_RADIUS_M: f32 = 0.12;

fn wrecking() -> App {
    let app = app_for(nudge::scene::load("wrecking").unwrap(), false);
    for i in 0..LINKS {
        let shape = *app.world().body(BodyId(FIRST_LINK + i)).shape();
        assert_eq!(shape, Shape::sphere(LINK_RADIUS_M), "link {i}");
    }
    app
}

/// Looks at `id` from 2.5 m off, so a 24 cm link covers cells the pointer can find.
fn look_at(app: &mut App, id: BodyId) {
    let target = app.world().body(id).pose().position;
    *app.camera_mut() = Camera::perspective(
        target + Vec3::new(-2.0, 0.6, -1.4),
        target,
        60f32.to_radians(),
    );
}

fn cell_of(app: &App, id: BodyId) -> (u16, u16) {
    nudge::bench::hands::cell_of(app, app.world().body(id).pose().position)
}

fn position(app: &App, id: BodyId) -> Vec3 {
    app.world().body(id).pose().position
}

/// Runs `frames` frames, returning the widest joint gap and the fastest link seen.
fn run(app: &mut App, frames: usize) -> (f32, f32) {
    let (mut gap, mut speed) = (0.0f32, 0.0f32);
    for _ in 0..frames {
        frame(app);
        assert!(all_finite(app.world()), "a NaN or an infinity");
        gap = gap.max(widest_joint(app.world()));
        for i in 0..LINKS {
            let v = app.world().body(BodyId(FIRST_LINK + i)).linear_velocity();
            speed = speed.max(v.length());
        }
    }
    (gap, speed)
}

/// The settled chain (the ball has swung through the wall and come to rest), looking at its middle.
fn settled() -> App {
    let mut app = wrecking();
    settle(&mut app);
    look_at(&mut app, MIDDLE);
    app
}

/// The widest gap a joint of the chain may open under the hands below, m. Measured: 0.18 mm under
/// every hand (the settled chain's own gap is 0.17 mm).
const MAX_GAP_M: f32 = 1e-3;

#[test]
fn a_held_push_and_a_held_pull_move_a_link_and_the_chain_holds() {
    for (button, name) in [(MouseButton::Left, "push"), (MouseButton::Right, "pull")] {
        let mut app = settled();
        let start = position(&app, MIDDLE);
        let cell = cell_of(&app, MIDDLE);
        app.handle_event(&mouse(MouseEventKind::Down(button), cell));
        assert_eq!(app.selected(), Some(MIDDLE), "{name}: the link is picked");
        let (gap, _) = run(&mut app, 30);
        app.handle_event(&mouse(MouseEventKind::Up(button), cell));
        let moved = position(&app, MIDDLE).distance(start);
        // Measured: the push 0.16 m, the pull 0.37 m.
        let least = if button == MouseButton::Left {
            0.08
        } else {
            0.15
        };
        assert!(moved > least, "{name}: moved {moved} m");
        assert!(gap < MAX_GAP_M, "{name}: gap {gap} m");
        let (gap, _) = run(&mut app, 60);
        assert!(gap < MAX_GAP_M, "{name}: gap {gap} m after");
    }
}

/// Grabs `link` of the settled chain (with the strong hand if `strong`) and swings it 12 cells
/// to the camera's right and back over two seconds; returns how far it went from where it was
/// grabbed at most, the widest joint gap on the way and how far the held point was from the
/// pointer at the end.
fn swing(link: BodyId, strong: bool) -> (f32, f32, f32, App) {
    let mut app = wrecking();
    settle(&mut app);
    look_at(&mut app, link);
    app.handle_event(&key(KeyCode::Char('h')));
    if strong {
        app.handle_event(&key(KeyCode::Char('x')));
    }
    let start = position(&app, link);
    let cell = cell_of(&app, link);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    assert!(app.grab_points().is_some(), "{link:?} is held");
    let (mut gap, mut farthest) = (0.0f32, 0.0f32);
    for step in 0..60u16 {
        let dx = step.min(60 - step) * 12 / 30;
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + dx, cell.1),
        ));
        let (g, _) = run(&mut app, 1);
        gap = gap.max(g);
        farthest = farthest.max(position(&app, link).distance(start));
    }
    let (anchor, pointer) = app.grab_points().expect("still held");
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    assert!(app.grab_points().is_none());
    (farthest, gap, anchor.distance(pointer), app)
}

#[test]
fn the_end_link_grabbed_with_the_strong_hand_swings_the_chain_and_a_middle_link_follows_the_gentle_one()
 {
    // The gentle hand pulls with at most 30 m/s² times the held body's mass: 15 N on a 0.5 kg link,
    // which does not roll the 50 kg ball the end link hangs on (measured: 0.04 mm); the strong
    // hand's 60 N swings it (measured: 0.46 m, the held point 6 cm from the pointer at the end,
    // the chain at up to 1.5 m/s after the release).
    let end = BodyId(FIRST_LINK + LINKS - 1);
    let (farthest, gap, error, mut app) = swing(end, true);
    let (after, speed) = run(&mut app, 90);
    assert!(farthest > 0.2, "the end link swung {farthest} m");
    assert!(error < 0.2, "held {error} m from the pointer");
    assert!(speed > 0.5, "the chain swings free at {speed} m/s");
    assert!(gap.max(after) < MAX_GAP_M, "gap {gap} m, {after} m after");
    // A middle link follows the gentle hand (measured: 0.34 m).
    let (farthest, gap, _, _) = swing(MIDDLE, false);
    assert!(farthest > 0.15, "the middle link swung {farthest} m");
    assert!(gap < MAX_GAP_M, "gap {gap} m");
}

#[test]
fn a_link_thrown_swings_the_chain_and_nothing_comes_apart() {
    let mut app = settled();
    app.handle_event(&key(KeyCode::Char('h')));
    let cell = cell_of(&app, MIDDLE);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    let mut speed = 0.0;
    for dx in 1..=8u16 {
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 3 * dx, cell.1),
        ));
        let (_, s) = run(&mut app, 1);
        speed = s;
    }
    app.handle_event(&mouse(
        MouseEventKind::Up(MouseButton::Left),
        (cell.0 + 24, cell.1),
    ));
    let (gap, _) = run(&mut app, 120);
    // Measured: 0.65 m/s as the button came up (the gentle hand's 15 N on a chain of 0.5 kg links).
    assert!(speed > 0.3, "thrown at {speed} m/s");
    assert!(gap < MAX_GAP_M, "gap {gap} m");
}

#[test]
fn a_frozen_link_pins_the_chain_beside_the_world_or_another_frozen_link_and_swings_once_unfrozen() {
    let mut app = settled();
    // Pushed aside, then frozen where the push left it (the button still down).
    let cell = cell_of(&app, MIDDLE);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    run(&mut app, 20);
    let here = cell_of(&app, MIDDLE);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), here));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), here));
    assert!(app.world().body(MIDDLE).is_static(), "{}", app.message());
    let pinned = *app.world().body(MIDDLE).pose();
    let (gap, _) = run(&mut app, 90);
    assert_eq!(
        *app.world().body(MIDDLE).pose(),
        pinned,
        "the frozen link stays put"
    );
    assert!(gap < MAX_GAP_M, "gap {gap} m below the frozen link");
    // The next link down hangs from it: below it, a link's length away.
    let below = position(&app, BodyId(MIDDLE.0 + 1));
    let offset = below - pinned.position;
    // Measured: 0.297 m below, 4 cm aside (the link is 0.3 m long).
    assert!(offset.y < -0.25 && offset.length() < 0.31, "{offset:?}");
    // Its neighbour above frozen too (a joint between two frozen bodies), and the top link (a joint
    // between a frozen body and the world): nothing moves, nothing blows up.
    for id in [BodyId(MIDDLE.0 - 1), BodyId(FIRST_LINK)] {
        look_at(&mut app, id);
        let cell = cell_of(&app, id);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
        assert!(
            app.world().body(id).is_static(),
            "{id:?}: {}",
            app.message()
        );
    }
    let (gap, _) = run(&mut app, 60);
    assert!(gap < MAX_GAP_M, "gap {gap} m");
    assert_eq!(*app.world().body(MIDDLE).pose(), pinned);
    // A joint between two frozen ends holds nothing the solver computes: it shows no force.
    let world = app.world();
    let between = (world.joints().iter())
        .find(|j| j.desc.b == MIDDLE)
        .expect("the middle link's joint above");
    assert_eq!(JointFigures::of(world, between).force, Vec3::ZERO);
    // Unfrozen, the middle link swings back down from where it was pinned.
    for id in [BodyId(MIDDLE.0 - 1), BodyId(FIRST_LINK), MIDDLE] {
        look_at(&mut app, id);
        let cell = cell_of(&app, id);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
        assert!(
            !app.world().body(id).is_static(),
            "{id:?}: {}",
            app.message()
        );
    }
    let (gap, speed) = run(&mut app, 60);
    let moved = position(&app, MIDDLE).distance(pinned.position);
    // Measured: 0.11 m in two seconds, at up to 0.57 m/s.
    assert!(
        moved > 0.04 && speed > 0.2,
        "moved {moved} m at {speed} m/s once unfrozen"
    );
    assert!(gap < MAX_GAP_M, "gap {gap} m");
}

#[test]
fn a_link_grown_and_shrunk_stays_jointed() {
    let mut app = settled();
    let cell = cell_of(&app, MIDDLE);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    assert_eq!(app.selected(), Some(MIDDLE));
    for _ in 0..3 {
        app.handle_event(&key(KeyCode::Char('>')));
    }
    let (gap, _) = run(&mut app, 60);
    let Shape::Sphere { radius } = *app.world().body(MIDDLE).shape() else {
        panic!("a link is a sphere");
    };
    assert!(
        (radius - LINK_RADIUS_M * 1.1f32.powi(3)).abs() < 1e-3,
        "r {radius}"
    );
    assert!(gap < MAX_GAP_M, "gap {gap} m grown");
    for _ in 0..6 {
        app.handle_event(&key(KeyCode::Char('<')));
    }
    let (gap, _) = run(&mut app, 60);
    assert!(gap < MAX_GAP_M, "gap {gap} m shrunk");
}

fn draw(app: &mut App) -> Vec<String> {
    let area = Rect::new(0, 0, COLS, ROWS);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    (0..ROWS)
        .map(|y| (0..COLS).map(|x| buf[(x, y)].symbol()).collect::<String>())
        .collect()
}

/// The inspector's column (right of its border), trimmed, row by row.
fn panel_rows(app: &mut App) -> Vec<String> {
    let screen = draw(app);
    let panel = app.inspector_area().expect("the inspector is shown");
    screen
        .iter()
        .map(|row| {
            row.chars()
                .skip(usize::from(panel.x) + 1)
                .collect::<String>()
                .trim()
                .to_string()
        })
        .collect()
}

#[test]
fn the_inspector_lists_the_selected_links_joints_with_their_forces_live() {
    let mut app = wrecking();
    let top = BodyId(FIRST_LINK);
    app.handle_event(&key(KeyCode::Char(' ')));
    look_at(&mut app, top);
    app.handle_event(&key(KeyCode::Char('i')));
    let cell = cell_of(&app, top);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    assert_eq!(app.selected(), Some(top));
    app.handle_event(&key(KeyCode::Char(' ')));
    run(&mut app, 10);
    let first = panel_rows(&mut app);
    let at = first
        .iter()
        .position(|r| r.starts_with("joints (2)"))
        .unwrap_or_else(|| panic!("{first:#?}"));
    assert!(first[at + 1].starts_with("hinge world"), "{first:#?}");
    assert!(first[at + 2].starts_with("τ ") && first[at + 2].contains(" N·m  ax "));
    assert!(first[at + 3].starts_with("hinge link 2"), "{first:#?}");
    // The scene names its links: the inspector's title gives the name and what the body is.
    assert!(
        first.iter().any(|r| r.contains("link 1 (sphere #37)")),
        "{first:#?}"
    );
    // The force it lists is the one the world has on it: the top hinge holds the chain and the
    // swinging ball (measured: 446 N).
    let newtons = |row: &str| -> f32 {
        let words: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(words.last(), Some(&"N"), "{row}");
        words[words.len() - 2].parse().unwrap()
    };
    let world = app.world();
    let held = JointFigures::of(world, &world.joints()[0]).force.length();
    let shown = newtons(&first[at + 1]);
    assert!(
        (shown - held).abs() < 0.1 && held > 100.0,
        "{shown} N shown, {held} N held"
    );
    run(&mut app, 10);
    let later = panel_rows(&mut app);
    assert_ne!(
        later[at + 1],
        first[at + 1],
        "it updates as the chain swings"
    );
}

#[test]
fn the_joints_overlay_draws_axes_and_forces_on_the_chain_and_nothing_when_off() {
    let mut app = wrecking();
    look_at(&mut app, MIDDLE);
    run(&mut app, 10);
    let count = |app: &App, color| app.frame().pixels().iter().filter(|&&c| c == color).count();
    let screen = draw(&mut app);
    assert!(!screen.iter().any(|row| row.contains(" N ")), "{screen:#?}");
    assert_eq!(count(&app, JOINT_AXIS_COLOR), 0);
    assert_eq!(count(&app, JOINT_FORCE_COLOR), 0);
    app.handle_event(&key(KeyCode::Char('o')));
    app.handle_event(&key(KeyCode::Char(OverlayKind::Joints.key())));
    let mut joints = OverlaySet::default();
    joints.insert(OverlayKind::Joints);
    assert_eq!(app.overlays(), joints);
    app.handle_event(&key(KeyCode::Esc));
    let screen = draw(&mut app);
    let (axes, forces) = (
        count(&app, JOINT_AXIS_COLOR),
        count(&app, JOINT_FORCE_COLOR),
    );
    // Measured: 90 and 119 pixels.
    assert!(
        axes > 20 && forces > 20,
        "axes {axes} px, forces {forces} px"
    );
    // The strongest joints' forces in view are written beside them, rows apart (measured: 6
    // labels, the most there may be, 443 N to 425 N down the chain's upper half).
    let world = app.world();
    let texts: Vec<String> = (world.joints().iter())
        .map(|j| force_text(JointFigures::of(world, j).force.length()))
        .collect();
    let view = &screen[..usize::from(ROWS - 1)];
    let mut labels = Vec::new();
    for row in view {
        let words: Vec<&str> = row.split_whitespace().collect();
        for pair in words.windows(2).filter(|w| w[1] == "N") {
            let number = pair[0].trim_start_matches(|c: char| !c.is_ascii_digit());
            labels.push(format!("{number} N"));
        }
    }
    assert!(
        (3..=MAX_FORCE_LABELS).contains(&labels.len()),
        "{labels:?}: {view:#?}"
    );
    for label in &labels {
        assert!(
            texts.contains(label),
            "{label} is no joint's force: {texts:?}"
        );
    }
}
