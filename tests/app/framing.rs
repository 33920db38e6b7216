//! The default scene's own camera frames its bodies as they settle: the user's report was "the top
//! 40 % of the picture is empty sky" (the bodies, dropped onto the floor, came to rest in the lower
//! half of a view framed around where they started). Measured on the id buffer, at 120 × 40 cells.

use crate::common::app::app_on;

/// Rows from the top of the picture to the first pixel of a dynamic body, and the rows the dynamic
/// bodies span, as fractions of the picture's height; and whether static pixels (the floor) show
/// below the lowest body pixel.
fn measure(name: &str, steps: usize) -> (f32, f32, bool) {
    let mut app = app_on(name, 120, 41);
    for _ in 0..steps {
        app.step_physics();
    }
    app.render_scene();
    let frame = app.frame();
    let dynamic: Vec<bool> = app
        .world()
        .bodies()
        .iter()
        .map(|b| !b.is_static())
        .collect();
    let (w, h) = (frame.width(), frame.height());
    let rows_with = |wanted: bool| -> Vec<u32> {
        (0..h)
            .filter(|&y| {
                (0..w).any(|x| {
                    frame
                        .id_at(x, y)
                        .is_some_and(|id| dynamic.get(id as usize) == Some(&wanted))
                })
            })
            .collect()
    };
    let bodies = rows_with(true);
    let (top, bottom) = (bodies[0], *bodies.last().unwrap());
    let floor_below = rows_with(false).iter().any(|&y| y > bottom);
    (
        top as f32 / h as f32,
        (bottom + 1 - top) as f32 / h as f32,
        floor_below,
    )
}

#[test]
fn the_default_scene_at_rest_fills_its_picture_under_little_sky_with_the_floor_below() {
    // 5 s: every body has landed and stopped.
    let (sky, span, floor_below) = measure("default", 300);
    assert!(
        sky <= 0.25,
        "sky above the bodies: {sky:.2} of the height (was 0.42)"
    );
    assert!(
        span >= 0.35,
        "the bodies span {span:.2} of the height (0.42)"
    );
    assert!(floor_below, "the floor shows under the bodies");
}

#[test]
fn the_default_scene_s_bodies_fall_into_the_picture_from_above() {
    // At the start they are still in the air above where they land: the top of the picture.
    let (sky, _, floor_below) = measure("default", 0);
    assert_eq!(sky, 0.0);
    assert!(floor_below);
}
