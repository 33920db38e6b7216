//! Hands, measured: what a held push, a grab, a drag and a throw do, driven through the headless app
//! with synthetic mouse events as a person would (a frame of events, then the two 60 Hz steps of a
//! 30 fps frame). `tests/app/hands.rs` holds these figures to their targets in both projections;
//! `nudge bench app` prints them.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use glam::{Vec2, Vec3};
use ratatui::layout::Rect;

use crate::app::{App, AppConfig};
use crate::geometry::{Camera, Shape};
use crate::physics::BodyId;
use crate::scene::{self, Scene, cases};

/// The terminal the scenarios run in.
pub const COLS: u16 = 120;
pub const ROWS: u16 = 40;
/// Physics steps per frame: 60 Hz physics shown at 30 fps.
pub const STEPS_PER_FRAME: usize = 2;

/// The app on `scene` in a 120 × 40 terminal, in perspective or (after `p`) orthographic projection.
pub fn app_for(scene: Scene, orthographic: bool) -> App {
    let config = AppConfig {
        supersample: false,
        ..AppConfig::default()
    };
    let mut app = App::new(scene, config);
    app.resize(Rect::new(0, 0, COLS, ROWS));
    if orthographic {
        app.handle_event(&key(KeyCode::Char('p')));
    }
    app
}

pub fn key(code: KeyCode) -> Event {
    Event::Key(KeyEvent::new(code, KeyModifiers::NONE))
}

pub fn mouse(kind: MouseEventKind, cell: (u16, u16)) -> Event {
    Event::Mouse(MouseEvent {
        kind,
        column: cell.0,
        row: cell.1,
        modifiers: KeyModifiers::NONE,
    })
}

/// The terminal cell over which world point `p` is drawn (through the app's camera and viewport).
pub fn cell_of(app: &App, p: Vec3) -> (u16, u16) {
    let viewport = app.viewport();
    let clip = app.camera().clip_from_world(viewport.aspect()) * p.extend(1.0);
    let ndc = Vec2::new(clip.x / clip.w, clip.y / clip.w);
    let cell = viewport.cell_from_pixel(viewport.pixel_from_ndc(ndc));
    let area = app.viewport_area();
    (
        area.x + cell.x.max(0.0) as u16,
        area.y + cell.y.max(0.0) as u16,
    )
}

/// Steps until every body sleeps (at most 20 s).
pub fn settle(app: &mut App) {
    for _ in 0..1200 {
        if app.world().awake_count() == 0 {
            break;
        }
        app.step_physics();
    }
}

/// One 30 fps frame's physics.
pub fn frame(app: &mut App) {
    for _ in 0..STEPS_PER_FRAME {
        app.step_physics();
    }
}

/// The camera's horizontal right, unit.
fn camera_right(app: &App) -> Vec3 {
    let right = app.camera().basis().right;
    Vec3::new(right.x, 0.0, right.z).normalize_or(Vec3::X)
}

/// A held push on one body of the default scene.
#[derive(Clone, Copy, Debug)]
pub struct PushOutcome {
    pub body: BodyId,
    pub mass_kg: f32,
    /// How far its centre moved across the floor, from rest to rest, m.
    pub moved_m: f32,
    /// The fastest its centre went across the floor (while above it), m/s.
    pub peak_speed: f32,
    /// At rest on the floor at the end (not fallen off, not frozen as lost).
    pub on_floor: bool,
}

/// The default scene settles; the left button is held on `body`'s centre for `seconds` (with the
/// strong hand if `strong`), then let go, and the scene runs five seconds more.
pub fn held_push(body: BodyId, seconds: f32, strong: bool, orthographic: bool) -> PushOutcome {
    let mut app = app_for(scene::load("default").expect("built in"), orthographic);
    settle(&mut app);
    if strong {
        app.handle_event(&key(KeyCode::Char('x')));
    }
    let start = app.world().body(body).pose().position;
    let cell = cell_of(&app, start);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    let mut peak_speed = 0.0f32;
    let frames = (seconds * 30.0).round() as usize;
    for i in 0..frames + 150 {
        if i == frames {
            app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
        }
        frame(&mut app);
        peak_speed = peak_speed.max(floor_speed(&app, body));
    }
    push_outcome(&app, body, start, peak_speed)
}

/// Where a push left `body` of the default scene, which started at `start`.
fn push_outcome(app: &App, body: BodyId, start: Vec3, peak_speed: f32) -> PushOutcome {
    let b = app.world().body(body);
    let end = b.pose().position;
    // The default floor's top is y = 0, 8 m × 5 m about the origin.
    let on_floor = !b.is_static()
        && end.y > 0.0
        && end.y < 1.0
        && end.x.abs() < 4.0
        && end.z.abs() < 2.5
        && b.linear_velocity().length() < 0.05;
    PushOutcome {
        body,
        mass_kg: b.mass(),
        moved_m: Vec2::new(end.x - start.x, end.z - start.z).length(),
        peak_speed,
        on_floor,
    }
}

/// The fastest `body` goes across the floor (while above it), m/s.
fn floor_speed(app: &App, body: BodyId) -> f32 {
    let b = app.world().body(body);
    if b.pose().position.y > 0.0 {
        let v = b.linear_velocity();
        Vec2::new(v.x, v.z).length()
    } else {
        0.0
    }
}

/// The default scene settles; `body` is selected (a middle click freezes it, a second unfreezes it)
/// and the nudge key `key` is held for `seconds`, the terminal repeating it every frame (30 a
/// second, as key repeat does), then the scene runs five seconds more.
pub fn held_nudge(
    body: BodyId,
    key_char: char,
    seconds: f32,
    strong: bool,
    orthographic: bool,
) -> PushOutcome {
    let mut app = app_for(scene::load("default").expect("built in"), orthographic);
    settle(&mut app);
    if strong {
        app.handle_event(&key(KeyCode::Char('x')));
    }
    let start = app.world().body(body).pose().position;
    let cell = cell_of(&app, start);
    for _ in 0..2 {
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Middle), cell));
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Middle), cell));
    }
    let frames = (seconds * 30.0).round() as usize;
    let mut peak_speed = 0.0f32;
    for i in 0..frames + 150 {
        if i < frames {
            app.handle_event(&key(KeyCode::Char(key_char)));
        }
        frame(&mut app);
        peak_speed = peak_speed.max(floor_speed(&app, body));
    }
    push_outcome(&app, body, start, peak_speed)
}

/// A floor (the default scene's) and one 3 kg, 1 m box: on the floor at `height` = 0.5, or in the air,
/// seen from 5.6 m in front and 3 m up. The hands' figures (drags in cells, wheel notches as metres)
/// were measured from there; the default scene's own camera now frames its bodies at rest, from
/// half as far, where a box held 2.5 m up is at the top of the picture.
pub fn lone_box(height: f32) -> Scene {
    let mut scene = scene::load("default").expect("built in");
    scene.camera = Camera::perspective(
        Vec3::new(0.0, 3.0, -5.6),
        Vec3::new(0.0, 0.9, 0.0),
        scene::framing::DEFAULT_FOV_DEG.to_radians(),
    );
    scene.bodies.truncate(1);
    scene.bodies.push(cases::dynamic(
        Shape::cuboid(Vec3::splat(0.5)),
        Vec3::new(0.0, height, 0.0),
        crate::color::PALETTE[0],
    ));
    scene.bodies[1].desc.mass = 3.0;
    scene
}

/// Enters grab mode and presses the left button on `body`'s centre.
fn grab(app: &mut App, body: BodyId) -> (u16, u16) {
    app.handle_event(&key(KeyCode::Char('h')));
    let cell = cell_of(app, app.world().body(body).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    cell
}

/// The grabbed point and the pointer's point, m.
fn grab_error(app: &App) -> f32 {
    app.grab_points()
        .map_or(f32::INFINITY, |(anchor, pointer)| {
            (anchor - pointer).length()
        })
}

/// A drag across the floor.
#[derive(Clone, Copy, Debug)]
pub struct DragOutcome {
    /// How far the pointer's point went, m.
    pub pointer_moved_m: f32,
    /// How far the grabbed point went, m.
    pub body_moved_m: f32,
    /// Distance from the grabbed point to the pointer's point `settle_s` after the pointer stopped, m.
    pub error_m: f32,
}

/// The 3 kg box rests on the floor; it is grabbed at its centre and the pointer drags it `distance`
/// metres sideways (toward −x, across the screen) over `drag_s`, then holds still for `settle_s`.
pub fn drag_on_floor(distance: f32, drag_s: f32, settle_s: f32, orthographic: bool) -> DragOutcome {
    drag_on_floor_in(
        app_for(lone_box(0.5), orthographic),
        distance,
        drag_s,
        settle_s,
    )
}

/// [`drag_on_floor`] in `app`, an app on [`lone_box`] (with the inspector open, say).
pub fn drag_on_floor_in(mut app: App, distance: f32, drag_s: f32, settle_s: f32) -> DragOutcome {
    settle(&mut app);
    let body = BodyId(1);
    let start_cell = grab(&mut app, body);
    let (anchor0, pointer0) = app.grab_points().expect("grabbed");
    let right = camera_right(&app);
    let goal = pointer0 + right * distance;
    let frames = (drag_s * 30.0).round().max(1.0) as usize;
    let mut cell = start_cell;
    for i in 1..=frames {
        let at = pointer0.lerp(goal, i as f32 / frames as f32);
        cell = cell_of(&app, at);
        app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), cell));
        frame(&mut app);
    }
    for _ in 0..(settle_s * 30.0).round() as usize {
        frame(&mut app);
    }
    let (anchor, pointer) = app.grab_points().expect("still held");
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    DragOutcome {
        pointer_moved_m: (pointer - pointer0).length(),
        body_moved_m: (anchor - anchor0).length(),
        error_m: (anchor - pointer).length(),
    }
}

/// A box held still in mid-air.
#[derive(Clone, Copy, Debug)]
pub struct HoldOutcome {
    /// The largest distance from the held point to the pointer's point over the last second, m.
    pub max_error_m: f32,
    /// At the end, m.
    pub error_m: f32,
}

/// The 3 kg box is grabbed in mid-air (2.5 m up) as the scene starts and held still under gravity
/// for `seconds`; the error is measured over the last second.
pub fn hold_in_air(seconds: f32, orthographic: bool) -> HoldOutcome {
    let mut app = app_for(lone_box(2.5), orthographic);
    grab(&mut app, BodyId(1));
    let frames = (seconds * 30.0).round() as usize;
    let mut max_error_m = 0.0f32;
    for i in 0..frames {
        frame(&mut app);
        if i + 30 >= frames {
            max_error_m = max_error_m.max(grab_error(&app));
        }
    }
    HoldOutcome {
        max_error_m,
        error_m: grab_error(&app),
    }
}

/// A throw: the pointer dragged at a steady speed, then let go.
#[derive(Clone, Copy, Debug)]
pub struct ThrowOutcome {
    /// The pointer's point's mean speed over the drag, m/s.
    pub pointer_speed: f32,
    /// The body's speed along the drag just after the release, m/s.
    pub thrown_speed: f32,
}

/// The 3 kg box is grabbed in mid-air, held 0.5 s, then the pointer moves sideways at `speed` m/s for
/// `drag_s` and the button comes up.
pub fn throw(speed: f32, drag_s: f32, orthographic: bool) -> ThrowOutcome {
    let mut app = app_for(lone_box(2.5), orthographic);
    let body = BodyId(1);
    grab(&mut app, body);
    for _ in 0..15 {
        frame(&mut app);
    }
    let (_, pointer0) = app.grab_points().expect("grabbed");
    let right = camera_right(&app);
    let frames = (drag_s * 30.0).round() as usize;
    let mut cell = (0, 0);
    let mut history = Vec::new();
    for i in 1..=frames {
        let at = pointer0 + right * (speed * i as f32 / 30.0);
        cell = cell_of(&app, at);
        app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), cell));
        history.push(app.grab_points().expect("held").1);
        frame(&mut app);
    }
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    // Over the whole drag: the pointer moves a cell at a time, so over a few frames its speed is
    // anything from 0 to a cell per frame.
    let last = history.len() - 1;
    let pointer_speed = (history[last] - history[0]).dot(right) / (last as f32 / 30.0);
    app.step_physics();
    ThrowOutcome {
        pointer_speed,
        thrown_speed: app.world().body(body).linear_velocity().dot(right),
    }
}

/// The drag speeds (m/s) and lengths (s) of [`throw_sweep`]: from a slow drag, where the pointer
/// moves a cell every few frames, to a flick of several cells a frame.
pub const SWEEP_SPEEDS: [f32; 11] = [1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0];
pub const SWEEP_DRAGS: [f32; 4] = [0.4, 0.6, 0.8, 1.0];

/// Every throw of [`SWEEP_SPEEDS`] × [`SWEEP_DRAGS`] in one projection: (speed, drag length, thrown
/// speed over the pointer's).
pub fn throw_sweep(orthographic: bool) -> Vec<(f32, f32, f32)> {
    let mut out = Vec::new();
    for speed in SWEEP_SPEEDS {
        for drag in SWEEP_DRAGS {
            let t = throw(speed, drag, orthographic);
            out.push((speed, drag, t.thrown_speed / t.pointer_speed));
        }
    }
    out
}

/// A hand the sandbox gives, for [`pinned_under_heavy`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PinnedHand {
    /// The left button held where the box is drawn.
    Push,
    /// The right button held.
    Pull,
    /// Grab mode: grabbed and dragged 3 m sideways and down into the floor.
    GrabDrag,
    /// A nudge key held (repeated every frame): `d` sideways, `e` up.
    Key(char),
}

impl PinnedHand {
    pub const ALL: [PinnedHand; 5] = [
        PinnedHand::Push,
        PinnedHand::Pull,
        PinnedHand::GrabDrag,
        PinnedHand::Key('d'),
        PinnedHand::Key('e'),
    ];
}

/// The 1 kg box pinned under 1000 kg, handled for 2 s by `hand` with the strong hand on. Returns the
/// most it moved, during or in the second after, m.
pub fn pinned_under_heavy_by(hand: PinnedHand, orthographic: bool) -> f32 {
    let light = BodyId(1);
    let mut app = app_for(cases::mass_ratio(), orthographic);
    settle(&mut app);
    app.handle_event(&key(KeyCode::Char('x')));
    let start = app.world().body(light).pose().position;
    let mut cell = cell_of(&app, start);
    let button = match hand {
        PinnedHand::Push | PinnedHand::GrabDrag => MouseButton::Left,
        PinnedHand::Pull => MouseButton::Right,
        PinnedHand::Key(_) => MouseButton::Middle,
    };
    if hand == PinnedHand::GrabDrag {
        app.handle_event(&key(KeyCode::Char('h')));
    }
    app.handle_event(&mouse(MouseEventKind::Down(button), cell));
    if hand == PinnedHand::GrabDrag {
        cell = cell_of(&app, start + camera_right(&app) * 3.0 - Vec3::Y * 0.3);
        app.handle_event(&mouse(MouseEventKind::Drag(button), cell));
    }
    if let PinnedHand::Key(_) = hand {
        // Selected by a middle click, which froze it; a second one unfreezes it.
        app.handle_event(&mouse(MouseEventKind::Up(button), cell));
        app.handle_event(&mouse(MouseEventKind::Down(button), cell));
        assert!(!app.world().body(light).is_static());
    }
    let mut worst = 0.0f32;
    for i in 0..90 {
        match hand {
            PinnedHand::Key(c) if i < 60 => app.handle_event(&key(KeyCode::Char(c))),
            _ if i == 60 => app.handle_event(&mouse(MouseEventKind::Up(button), cell)),
            _ => {}
        }
        frame(&mut app);
        let moved = (app.world().body(light).pose().position - start).length();
        worst = worst.max(moved);
    }
    worst
}

/// The most the 1 kg box pinned under 1000 kg moves under any hand (see [`pinned_under_heavy_by`]),
/// m.
pub fn pinned_under_heavy(orthographic: bool) -> f32 {
    PinnedHand::ALL
        .iter()
        .map(|&hand| pinned_under_heavy_by(hand, orthographic))
        .fold(0.0, f32::max)
}

/// One measured figure, in both projections, beside the number.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Figure {
    pub name: String,
    pub perspective: f32,
    pub orthographic: f32,
    pub unit: &'static str,
    /// The number, as text ("≥ 0.5").
    pub target: &'static str,
}

/// Every figure of the hands, measured in both projections.
pub fn figures() -> Vec<Figure> {
    // Each run measured once per projection, whatever figures are read off it.
    fn both<T>(f: impl Fn(bool) -> T) -> (T, T) {
        (f(false), f(true))
    }
    let mut rows = Vec::new();
    let mut push = |name: String, (p, o): (f32, f32), unit, target| {
        rows.push(Figure {
            name,
            perspective: p,
            orthographic: o,
            unit,
            target,
        })
    };
    for (body, label) in [(BodyId(1), "3 kg box"), (BodyId(2), "5 kg box")] {
        let (p, o) = both(|o| held_push(body, 3.0, false, o));
        push(
            format!("held push 3 s, {label}: moved"),
            (p.moved_m, o.moved_m),
            "m",
            "≥ 0.5, on the floor",
        );
        push(
            format!("held push 3 s, {label}: peak speed"),
            (p.peak_speed, o.peak_speed),
            "m/s",
            "2–3",
        );
    }
    let drag = both(|o| 100.0 * drag_on_floor(2.0, 0.5, 0.5, o).error_m);
    push(
        "grab, 3 kg box dragged 2 m in 0.5 s: off the pointer 0.5 s later".into(),
        drag,
        "cm",
        "< 5",
    );
    let beside_panel = both(|o| {
        let mut app = app_for(lone_box(0.5), o);
        app.handle_event(&key(KeyCode::Char('i')));
        100.0 * drag_on_floor_in(app, 2.0, 0.5, 0.5).error_m
    });
    push(
        "the same with the inspector open (the view beside it)".into(),
        beside_panel,
        "cm",
        "< 5",
    );
    let flick = both(|o| 100.0 * drag_on_floor(2.0, 0.25, 0.5, o).error_m);
    push(
        "grab, flicked 2 m in 0.25 s: off the pointer 0.5 s later".into(),
        flick,
        "cm",
        "",
    );
    let held = both(|o| 100.0 * hold_in_air(3.0, o).max_error_m);
    push(
        "grab, held still in mid-air: most off the pointer over 1 s".into(),
        held,
        "cm",
        "< 2",
    );
    for speed in [2.0, 4.0, 6.0] {
        let ratio = both(|o| {
            let t = throw(speed, 0.5, o);
            t.thrown_speed / t.pointer_speed
        });
        push(
            format!("throw at {speed} m/s: thrown / pointer speed"),
            ratio,
            "",
            "0.8–1.2",
        );
    }
    // Lowest and highest thrown / pointer speed of the sweep, per projection.
    let (p, o) = both(|o| {
        throw_sweep(o)
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), t| {
                (lo.min(t.2), hi.max(t.2))
            })
    });
    push(
        "throws 1-6 m/s over 0.4-1 s (44 a projection): lowest thrown / pointer".into(),
        (p.0, o.0),
        "",
        "≥ 0.8",
    );
    push(
        "throws 1-6 m/s over 0.4-1 s: highest thrown / pointer".into(),
        (p.1, o.1),
        "",
        "≤ 1.2",
    );
    for (strong, label, target) in [
        (false, "", "steady (≤ 2.5)"),
        (true, ", strong", "steady (≤ 5)"),
    ] {
        let nudge = both(|o| held_nudge(BodyId(2), 'd', 1.0, strong, o).peak_speed);
        push(
            format!("held nudge key d 1 s{label}, 5 kg box: peak speed"),
            nudge,
            "m/s",
            target,
        );
    }
    let pinned = both(|o| 1000.0 * pinned_under_heavy(o));
    push(
        "1 kg under 1000 kg, strong push, pull, grab, held d and e: moved".into(),
        pinned,
        "mm",
        "< 10",
    );
    rows
}

/// The section's table, as `nudge bench` prints it.
pub(super) fn print_table(figures: &[Figure], out: &mut dyn std::io::Write) -> std::io::Result<()> {
    use super::table::Table;
    writeln!(
        out,
        "hands: the headless app driven with synthetic mouse events, 120x40, 30 frames a second"
    )?;
    let mut table = Table::new(&["figure", "unit", "perspective", "orthographic", "issue"]);
    for f in figures {
        table.push(vec![
            f.name.clone(),
            f.unit.to_string(),
            format!("{:.2}", f.perspective),
            format!("{:.2}", f.orthographic),
            f.target.to_string(),
        ]);
    }
    table.write(out)
}
