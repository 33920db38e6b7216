//! The hands alongside the rest of the sandbox, in both projections: a grab beside the inspector
//! panel (the view shrinks, and the cells, the picture, the pointer's ray and the tether must still
//! agree), the popups drawn over the view, the status bar's flags and the hand's report together,
//! the keys pressed while a body is held (the live settings, switching scenes); and what the issue
//! asks of every push: off-centre pushes spin, heavy bodies answer like light ones, the pointer
//! moves on the plane facing the camera.

use crossterm::event::{KeyCode, MouseButton, MouseEventKind};
use glam::Vec2;
use nudge::app::App;
use nudge::app::input::grab::TETHER_MARKER;
use nudge::bench::hands::{
    self, COLS, ROWS, app_for, cell_of, frame, key, lone_box, mouse, settle,
};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

use super::hands::{BOX, PROJECTIONS, name};

/// Draws the app into a fresh `cols` × `rows` buffer and returns it.
fn draw_at(app: &mut App, cols: u16, rows: u16) -> Buffer {
    let area = Rect::new(0, 0, cols, rows);
    let mut buf = Buffer::empty(area);
    app.draw(area, &mut buf);
    buf
}

fn row_text(buf: &Buffer, row: u16) -> String {
    (0..buf.area.width)
        .map(|x| buf[(x, row)].symbol().to_string())
        .collect()
}

fn grab_error(app: &App) -> f32 {
    let (anchor, pointer) = app.grab_points().expect("held");
    (anchor - pointer).length()
}

/// The pixel world point `p` is drawn at, in the app's viewport.
fn pixel_of(app: &App, p: glam::Vec3) -> Vec2 {
    let viewport = app.viewport();
    let clip = app.camera().clip_from_world(viewport.aspect()) * p.extend(1.0);
    viewport.pixel_from_ndc(Vec2::new(clip.x / clip.w, clip.y / clip.w))
}

#[test]
fn beside_the_inspector_every_cell_showing_the_box_grabs_it_where_the_pointer_points() {
    for orthographic in PROJECTIONS {
        let view_name = name(orthographic);
        let mut app = app_for(lone_box(0.5), orthographic);
        settle(&mut app);
        app.handle_event(&key(KeyCode::Char('i')));
        app.handle_event(&key(KeyCode::Char('h')));
        let view = app.viewport_area();
        assert!(view.width + 20 < COLS, "the view shrinks beside the panel");
        draw_at(&mut app, COLS, ROWS);
        let picture = app.frame().clone();
        assert_eq!(picture.width(), u32::from(view.width));
        let mut checked = 0;
        for row in 0..view.height {
            for col in 0..view.width {
                let (top, bottom) = (
                    picture.id_at(col.into(), 2 * u32::from(row)),
                    picture.id_at(col.into(), 2 * u32::from(row) + 1),
                );
                if top != Some(BOX.0) || bottom != Some(BOX.0) {
                    continue;
                }
                // The press grabs the box drawn there, at the point the pointer's ray meets: the
                // pointer's point is the held point until the pointer moves.
                app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), (col, row)));
                assert_eq!(app.selected(), Some(BOX), "{view_name}: cell {col},{row}");
                let error = grab_error(&app);
                assert!(error < 1e-3, "{view_name}: cell {col},{row}: {error} m");
                app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), (col, row)));
                checked += 1;
            }
        }
        assert!(checked > 30, "{view_name}: {checked} cells");
        // The panel's cells grab nothing.
        let panel = app.inspector_area().expect("open");
        app.handle_event(&mouse(
            MouseEventKind::Down(MouseButton::Left),
            (panel.x + 5, view.height / 2),
        ));
        assert!(app.grab_points().is_none(), "{view_name}");
    }
}

#[test]
fn beside_the_inspector_a_box_dragged_two_metres_follows_the_pointer_within_5_cm() {
    for orthographic in PROJECTIONS {
        let mut app = app_for(lone_box(0.5), orthographic);
        app.handle_event(&key(KeyCode::Char('i')));
        let out = hands::drag_on_floor_in(app, 2.0, 0.5, 0.5);
        let view = name(orthographic);
        assert!(out.pointer_moved_m > 1.9, "{view}: {out:?}");
        assert!(out.error_m < 0.05, "{view}: {out:?}");
    }
}

#[test]
fn beside_the_inspector_the_tether_is_drawn_through_the_narrowed_view_and_a_drag_over_the_panel_comes_back()
 {
    for orthographic in PROJECTIONS {
        let view_name = name(orthographic);
        let mut app = app_for(lone_box(2.5), orthographic);
        app.handle_event(&key(KeyCode::Char('i')));
        app.handle_event(&key(KeyCode::Char('h')));
        let cell = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 6, cell.1 - 3),
        ));
        app.step_physics();
        draw_at(&mut app, COLS, ROWS);
        let (anchor, _) = app.grab_points().expect("held");
        let marker = pixel_of(&app, anchor);
        assert_eq!(
            app.frame().pixel(marker.x as u32, marker.y as u32),
            TETHER_MARKER,
            "{view_name}: the marker sits on the held point"
        );
        // Over the panel (the box goes on behind it, where the view would be), and back.
        let panel = app.inspector_area().expect("open");
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (panel.x + panel.width / 2, cell.1),
        ));
        for _ in 0..30 {
            frame(&mut app);
        }
        assert!(app.grab_points().is_some(), "{view_name}: still held");
        let buf = draw_at(&mut app, COLS, ROWS);
        assert!(
            row_text(&buf, ROWS - 1).contains("grabbing box #1 · "),
            "{view_name}"
        );
        app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), cell));
        for _ in 0..60 {
            frame(&mut app);
        }
        assert!(grab_error(&app) < 0.05, "{view_name}: {}", grab_error(&app));
        // The held point is drawn under the pointer again.
        let here = cell_of(&app, app.grab_points().expect("held").0);
        assert!(
            here.0.abs_diff(cell.0) <= 1 && here.1.abs_diff(cell.1) <= 1,
            "{view_name}: drawn at {here:?}, the pointer at {cell:?}"
        );
    }
}

#[test]
fn the_status_bar_keeps_the_flags_the_body_and_the_force_at_80_columns() {
    for orthographic in PROJECTIONS {
        let view_name = name(orthographic);
        let mut app = app_for(lone_box(2.5), orthographic);
        app.resize(Rect::new(0, 0, 80, 24));
        app.handle_event(&key(KeyCode::Char('x')));
        app.handle_event(&key(KeyCode::Char('g')));
        app.handle_event(&key(KeyCode::Char('h')));
        let cell = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        app.handle_event(&mouse(
            MouseEventKind::Drag(MouseButton::Left),
            (cell.0 + 5, cell.1),
        ));
        frame(&mut app);
        let status = row_text(&draw_at(&mut app, 80, 24), 23);
        for part in [
            "STRONG",
            "GRAB",
            "NO GRAVITY",
            "grabbing box #1 · ",
            " N · ",
        ] {
            assert!(status.contains(part), "{view_name}: {part} in {status}");
        }
        // Pushing: the mode's flag goes, the report names the push.
        app.handle_event(&mouse(
            MouseEventKind::Up(MouseButton::Left),
            (cell.0 + 5, cell.1),
        ));
        app.handle_event(&key(KeyCode::Char('h')));
        let here = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), here));
        frame(&mut app);
        let status = row_text(&draw_at(&mut app, 80, 24), 23);
        assert!(!status.contains("GRAB"), "{view_name}: {status}");
        for part in ["STRONG", "NO GRAVITY", "pushing box #1 · ", " N · ", " m/s"] {
            assert!(status.contains(part), "{view_name}: {part} in {status}");
        }
    }
}

/// The cells of the one bordered box drawn from the top row (the live settings or the overlay
/// menu): its corners found in the drawn buffer.
fn popup_box(buf: &Buffer) -> Rect {
    let top: Vec<&str> = (0..buf.area.width).map(|x| buf[(x, 0)].symbol()).collect();
    let left = top.iter().position(|&s| s == "┌").expect("a box");
    let right_edge = top.iter().rposition(|&s| s == "┐").expect("a box");
    let bottom = (1..buf.area.height)
        .find(|&y| buf[(left as u16, y)].symbol() == "└")
        .expect("its bottom");
    Rect::new(left as u16, 0, (right_edge - left + 1) as u16, bottom + 1)
}

/// Moves the camera sideways until the lone box's centre is drawn in `area`'s middle cell.
fn show_the_box_in(app: &mut App, area: Rect) -> (u16, u16) {
    let goal = (area.x + area.width / 2, area.y + area.height / 2);
    for _ in 0..200 {
        let at = cell_of(app, app.world().body(BOX).pose().position);
        if at == goal {
            return at;
        }
        let basis = app.camera().basis();
        let shift = basis.right * 0.02 * (f32::from(at.0) - f32::from(goal.0))
            + basis.up * 0.02 * (f32::from(goal.1) - f32::from(at.1));
        let camera = app.camera_mut();
        camera.position += shift;
        camera.target += shift;
    }
    panic!("the box never reached {goal:?}");
}

#[test]
fn a_click_on_the_live_settings_or_the_overlay_menu_reaches_no_body_hidden_under_it() {
    for orthographic in PROJECTIONS {
        for (open, grab) in [('t', false), ('t', true), ('o', false), ('o', true)] {
            let view_name = name(orthographic);
            let mut app = app_for(lone_box(0.5), orthographic);
            settle(&mut app);
            if grab {
                app.handle_event(&key(KeyCode::Char('h')));
            }
            app.handle_event(&key(KeyCode::Char(open)));
            let buf = draw_at(&mut app, COLS, ROWS);
            let popup = popup_box(&buf);
            let cell = show_the_box_in(&mut app, popup);
            let start = *app.world().body(BOX).pose();
            for button in [MouseButton::Left, MouseButton::Right] {
                app.handle_event(&mouse(MouseEventKind::Down(button), cell));
                for _ in 0..15 {
                    frame(&mut app);
                }
                app.handle_event(&mouse(MouseEventKind::Up(button), cell));
            }
            assert!(app.grab_points().is_none(), "{view_name} {open}");
            assert_eq!(*app.world().body(BOX).pose(), start, "{view_name} {open}");
            let hint = if open == 't' {
                "settings: "
            } else {
                "overlays: "
            };
            assert!(app.message().starts_with(hint), "{}", app.message());
            // Closed, the same click reaches the box.
            app.handle_event(&key(if open == 't' {
                KeyCode::Char('t')
            } else {
                KeyCode::Esc
            }));
            app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
            assert_eq!(app.selected(), Some(BOX), "{view_name} {open}");
        }
    }
}

#[test]
fn with_the_live_settings_open_plus_and_minus_move_a_held_body_and_change_a_setting_otherwise() {
    for orthographic in PROJECTIONS {
        let view_name = name(orthographic);
        let mut app = app_for(lone_box(2.5), orthographic);
        let settings = app.world().settings().clone();
        app.handle_event(&key(KeyCode::Char('h')));
        let cell = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        app.handle_event(&key(KeyCode::Char('t')));
        let forward = app.camera().basis().forward;
        let depth =
            |app: &App| (app.grab_points().expect("held").1 - app.camera().position).dot(forward);
        let before = depth(&app);
        for _ in 0..3 {
            app.handle_event(&key(KeyCode::Char('+')));
        }
        assert!(depth(&app) < before - 0.5, "{view_name}: nearer");
        app.handle_event(&key(KeyCode::Char('-')));
        assert!(
            app.message().starts_with("holding it "),
            "{}",
            app.message()
        );
        assert_eq!(*app.world().settings(), settings, "{view_name}");
        // Let go, + changes the highlighted setting (sub-steps) again.
        app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
        app.handle_event(&key(KeyCode::Char('+')));
        assert_eq!(app.world().settings().substeps, settings.substeps + 1);
    }
}

#[test]
fn switching_scenes_keeps_the_grab_mode_and_lets_go() {
    let mut app = app_for(lone_box(2.5), false);
    app.handle_event(&key(KeyCode::Char('h')));
    let cell = cell_of(&app, app.world().body(BOX).pose().position);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    app.handle_event(&key(KeyCode::Char('n')));
    assert!(app.grab_points().is_none(), "the hand let go");
    let status = row_text(&draw_at(&mut app, COLS, ROWS), ROWS - 1);
    assert!(status.contains("GRAB"), "{status}");
}

/// The lone box on the floor, of `mass` kg, pushed with the left button held `frames` frames at the
/// point drawn `offset_right` metres right of its centre (along the camera's right). Returns how far
/// its centre went and its spin about the vertical (rad/s).
fn push_lone_box(mass: f32, offset_right: f32, frames: usize, orthographic: bool) -> (f32, f32) {
    let mut scene = lone_box(0.5);
    scene.bodies[1].desc.mass = mass;
    let mut app = app_for(scene, orthographic);
    settle(&mut app);
    let start = app.world().body(BOX).pose().position;
    let right = app.camera().basis().right;
    let cell = cell_of(&app, start + right * offset_right);
    app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
    for _ in 0..frames {
        frame(&mut app);
    }
    let spin = app.world().body(BOX).angular_velocity().y;
    app.handle_event(&mouse(MouseEventKind::Up(MouseButton::Left), cell));
    let moved = (app.world().body(BOX).pose().position - start).length();
    (moved, spin)
}

#[test]
fn an_off_centre_push_spins_a_box_one_way_or_the_other() {
    for orthographic in PROJECTIONS {
        let view = name(orthographic);
        let (_, left) = push_lone_box(3.0, -0.4, 10, orthographic);
        let (_, right) = push_lone_box(3.0, 0.4, 10, orthographic);
        // Seen from above the camera, a push on the right edge turns the box anticlockwise.
        assert!(
            right > 3.0 && left < -3.0,
            "{view}: {left} and {right} rad/s"
        );
    }
}

#[test]
fn a_heavy_box_answers_a_push_like_a_light_one() {
    for orthographic in PROJECTIONS {
        let (light, _) = push_lone_box(3.0, 0.0, 20, orthographic);
        let (heavy, _) = push_lone_box(300.0, 0.0, 20, orthographic);
        assert!(light > 0.3, "{}: {light} m", name(orthographic));
        assert!(
            (heavy / light - 1.0).abs() < 0.1,
            "{}: 3 kg {light} m, 300 kg {heavy} m",
            name(orthographic)
        );
    }
}

#[test]
fn the_pointer_moves_on_the_plane_through_the_grabbed_point_facing_the_camera() {
    for orthographic in PROJECTIONS {
        let view = name(orthographic);
        let mut app = app_for(lone_box(2.5), orthographic);
        app.handle_event(&key(KeyCode::Char('h')));
        let cell = cell_of(&app, app.world().body(BOX).pose().position);
        app.handle_event(&mouse(MouseEventKind::Down(MouseButton::Left), cell));
        let forward = app.camera().basis().forward;
        let eye = app.camera().position;
        let (anchor, _) = app.grab_points().expect("held");
        let depth = (anchor - eye).dot(forward);
        // Everywhere the pointer goes, in the view and out of it, its point is at that depth.
        for at in [
            (0, 0),
            (COLS - 1, ROWS - 2),
            (cell.0 + 30, cell.1),
            (COLS + 20, ROWS + 5),
        ] {
            app.handle_event(&mouse(MouseEventKind::Drag(MouseButton::Left), at));
            let (_, pointer) = app.grab_points().expect("held");
            let off = (pointer - eye).dot(forward) - depth;
            assert!(
                off.abs() < 1e-3 * depth,
                "{view}: at {at:?} the point is {off} m off the plane"
            );
        }
    }
}
