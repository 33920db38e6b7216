//! The sandbox in every cell mode: `v` cycles the mode live, the view re-renders at the mode's
//! resolution and draws its glyphs, the status bar names it, and the overlays, the inspector and a
//! click work as in half blocks.

use crate::common;

use common::app::{cell_of, char_key};
use crossterm::event::{Event, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use nudge::app::panels::overlays::OverlaySet;
use nudge::app::{App, AppConfig};
use nudge::scene;
use nudge::term::CellMode;
use nudge::term::glyphs::pattern_of;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;

const AREA: Rect = Rect::new(0, 0, 100, 30);

fn default_app(cells: CellMode) -> App {
    let config = AppConfig {
        cells,
        ..AppConfig::default()
    };
    let mut app = App::new(scene::load("default").expect("default scene"), config);
    app.resize(AREA);
    app
}

fn draw(app: &mut App) -> Buffer {
    let mut buf = Buffer::empty(AREA);
    app.draw(AREA, &mut buf);
    buf
}

fn row_text(buf: &Buffer, y: u16, from: u16, to: u16) -> String {
    (from..to).map(|x| buf[(x, y)].symbol()).collect()
}

/// Every cell of the view shows a glyph of `mode`, and some show more than half blocks can.
fn assert_view_in(buf: &Buffer, view: Rect, mode: CellMode) {
    let mut finer = 0;
    for y in view.top()..view.bottom() {
        for x in view.left()..view.right() {
            let symbol = buf[(x, y)].symbol();
            assert!(
                pattern_of(mode, symbol).is_some(),
                "{mode}: ({x}, {y}) shows {symbol:?}"
            );
            finer += usize::from(!matches!(symbol, " " | "▀" | "▄" | "█"));
        }
    }
    assert_eq!(
        finer > 0,
        mode != CellMode::Half,
        "{mode}: {finer} finer glyphs"
    );
}

#[test]
fn v_cycles_the_cell_mode_and_the_view_follows_it() {
    let mut app = default_app(CellMode::Half);
    let mut expected = CellMode::Half;
    for _ in 0..5 {
        let buf = draw(&mut app);
        let view = app.viewport_area();
        let (w, h) = expected.pixels_per_cell();
        assert_eq!(
            (app.frame().width(), app.frame().height()),
            (u32::from(view.width) * w, u32::from(view.height) * h),
            "{expected}: the frame is rendered at the mode's resolution"
        );
        assert_view_in(&buf, view, expected);
        let status = row_text(&buf, AREA.bottom() - 1, 0, AREA.width);
        // Beside the colour depth, when not the default half blocks.
        assert_eq!(
            status.contains(&format!("truecolor {expected}")),
            expected != CellMode::Half,
            "{expected}: {status}"
        );
        app.handle_event(&char_key('v'));
        expected = expected.next();
        assert!(app.message().contains(expected.name()), "{}", app.message());
    }
}

#[test]
fn the_inspector_and_overlays_are_the_same_in_every_mode() {
    let panel = |cells| {
        let mut app = default_app(cells);
        app.set_overlays(OverlaySet::ALL);
        for _ in 0..30 {
            app.step_physics();
        }
        app.handle_event(&char_key(' '));
        app.handle_event(&char_key('i'));
        let buf = draw(&mut app);
        let view = app.viewport_area();
        assert!(app.inspector_area().is_some(), "{cells}: no panel");
        assert_view_in(&buf, view, cells);
        // The panel, right of the view, down to its timings (which differ from draw to draw).
        (0..AREA.height - 1)
            .map(|y| row_text(&buf, y, view.right(), AREA.width))
            .take_while(|line| !line.contains(" step "))
            .collect::<Vec<_>>()
    };
    let half = panel(CellMode::Half);
    assert!(half.iter().any(|l| l.contains("awake")), "{half:#?}");
    for cells in [CellMode::Quadrant, CellMode::Sextant, CellMode::Octant] {
        assert_eq!(panel(cells), half, "{cells}");
    }
}

#[test]
fn a_click_selects_the_body_drawn_under_it_in_every_mode() {
    for cells in CellMode::ALL {
        let mut app = default_app(cells);
        // Landed first: the camera frames the bodies at rest, and they start above the picture.
        for _ in 0..120 {
            app.step_physics();
        }
        draw(&mut app);
        // Each dynamic body: a middle click (select and freeze) on the cell over its centre.
        for index in 0..app.world().len() {
            let id = nudge::physics::BodyId(index as u32);
            let body = app.world().body(id);
            if body.is_static() {
                continue;
            }
            let cell = cell_of(&app, body.pose().position);
            let drawn = {
                let (w, h) = cells.pixels_per_cell();
                let (x, y) = (u32::from(cell.0) * w, u32::from(cell.1) * h);
                app.frame().id_at(x + w / 2, y + h / 2)
            };
            assert_eq!(
                drawn,
                Some(index as u32),
                "{cells}: body {index} is drawn there"
            );
            for kind in [
                MouseEventKind::Down(MouseButton::Middle),
                MouseEventKind::Up(MouseButton::Middle),
            ] {
                app.handle_event(&Event::Mouse(MouseEvent {
                    kind,
                    column: cell.0,
                    row: cell.1,
                    modifiers: KeyModifiers::NONE,
                }));
            }
            assert_eq!(app.selected(), Some(id), "{cells}: body {index}");
        }
    }
}
