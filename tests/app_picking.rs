//! What you click is what was drawn: for every cell of the view, the body the picking ray hits is the
//! body the rasterizer's id buffer shows there.

use nudge::app::{App, AppConfig, picking};
use nudge::geometry::Projection;
use nudge::scene::{self, Scene, cases};
use ratatui::layout::Rect;

const COLS: u16 = 100;
const ROWS: u16 = 40;
/// Share of covered cells that must agree.
const MIN_AGREEMENT: f64 = 0.995;

fn scenes() -> Vec<Scene> {
    vec![
        scene::load("default").expect("default scene"),
        cases::pyramid(6),
        scene::load("ramp").expect("ramp scene"),
    ]
}

/// Camera variations applied to each scene's own camera.
fn poses(app: &mut App, index: usize) {
    let camera = app.camera_mut();
    match index {
        0 => {}
        1 => camera.orbit(0.7, 0.25),
        2 => camera.orbit(-0.9, -0.15),
        _ => camera.zoom(0.6),
    }
}

#[derive(Default)]
struct Tally {
    covered: usize,
    disagree: usize,
    disagree_off_edge: usize,
}

fn check(app: &mut App, tally: &mut Tally) {
    app.render_scene();
    let viewport = app.viewport();
    let frame = app.frame();
    let id = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= frame.width() as i64 || y >= frame.height() as i64 {
            None
        } else {
            frame.id_at(x as u32, y as u32)
        }
    };
    for row in 0..viewport.height as u16 / 2 {
        for col in 0..viewport.width as u16 {
            let (x, y) = (col as i64, 2 * row as i64);
            let top = id(x, y);
            let bottom = id(x, y + 1);
            let pick = picking::pick_cell(app.world(), app.camera(), &viewport, col, row)
                .map(|p| p.body.0);
            if top.is_none() && bottom.is_none() && pick.is_none() {
                continue;
            }
            tally.covered += 1;
            if pick == top || pick == bottom {
                continue;
            }
            tally.disagree += 1;
            // A silhouette edge: some pixel around the cell shows something else.
            let on_edge = (-1..=1).any(|dx| (-1..=2).any(|dy| id(x + dx, y + dy) != top));
            if !on_edge {
                tally.disagree_off_edge += 1;
                eprintln!("cell ({col}, {row}): drawn {top:?}/{bottom:?}, picked {pick:?}");
            }
        }
    }
}

#[test]
fn picking_agrees_with_the_id_buffer_in_every_scene_projection_and_pose() {
    for scene in scenes() {
        for orthographic in [false, true] {
            for pose in 0..4 {
                let config = AppConfig {
                    supersample: false,
                    ..AppConfig::default()
                };
                let mut app = App::new(scene.clone(), config);
                app.resize(Rect::new(0, 0, COLS, ROWS + 1));
                if orthographic {
                    let camera = app.camera().toggled_projection(1.2);
                    *app.camera_mut() = camera;
                    assert!(matches!(
                        app.camera().projection,
                        Projection::Orthographic { .. }
                    ));
                }
                poses(&mut app, pose);
                let mut tally = Tally::default();
                check(&mut app, &mut tally);
                let agreement = 1.0 - tally.disagree as f64 / tally.covered.max(1) as f64;
                assert!(tally.covered > 100, "{}: view shows the scene", scene.name);
                assert!(
                    agreement >= MIN_AGREEMENT,
                    "{} ortho={orthographic} pose={pose}: agreement {agreement:.4} over {} cells",
                    scene.name,
                    tally.covered
                );
                assert_eq!(
                    tally.disagree_off_edge, 0,
                    "{} ortho={orthographic} pose={pose}: disagreements away from silhouettes",
                    scene.name
                );
            }
        }
    }
}
