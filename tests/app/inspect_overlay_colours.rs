//! The overlays read at every colour depth: each mark colour reaches the screen as one flat palette
//! entry (dithering never breaks a one-pixel line into a pattern), the marks stay apart from each
//! other, and the island and sleep tints stay apart in 16 colours.

use nudge::app::panels::overlays::{
    ASLEEP_COLOR, AWAKE_COLOR, AXIS_COLORS, FROZEN_COLOR, ISLAND_COLORS, OverlayKind,
};
use nudge::color::Rgb;
use nudge::term::{ColorDepth, Dither, HalfBlocks, quantize};
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::widgets::Widget;

/// Every colour a line or point overlay draws with.
fn mark_colors() -> Vec<(String, Rgb)> {
    let mut marks: Vec<(String, Rgb)> = [
        OverlayKind::Contacts,
        OverlayKind::Normals,
        OverlayKind::Friction,
        OverlayKind::Aabbs,
        OverlayKind::Velocity,
    ]
    .iter()
    .map(|k| (k.name().to_string(), k.color()))
    .collect();
    for (axis, color) in ["x", "y", "z"].iter().zip(AXIS_COLORS) {
        marks.push((format!("axis {axis}"), color));
    }
    marks
}

/// The terminal colours a 4 × 4 image of `color` is drawn with.
fn shown(color: Rgb, depth: ColorDepth, dither: Dither) -> Vec<Color> {
    let pixels = vec![color; 16];
    let mut buf = Buffer::empty(Rect::new(0, 0, 4, 2));
    HalfBlocks::new(&pixels, 4, 4, depth)
        .with_dither(dither)
        .render(buf.area, &mut buf);
    let mut colors = Vec::new();
    for cell in buf.content() {
        for c in [cell.fg, cell.bg] {
            if c != Color::Reset && !colors.contains(&c) {
                colors.push(c);
            }
        }
    }
    colors
}

#[test]
fn every_mark_colour_is_one_flat_entry_and_the_marks_stay_apart_at_every_depth() {
    for depth in [
        ColorDepth::TrueColor,
        ColorDepth::Ansi256,
        ColorDepth::Ansi16,
    ] {
        for dither in Dither::ALL {
            let mut seen: Vec<(String, Color)> = Vec::new();
            for (name, color) in mark_colors() {
                let colors = shown(color, depth, dither);
                assert_eq!(
                    colors,
                    [quantize(color, depth)],
                    "{name} at {depth:?}, {dither:?} dither: not one flat entry"
                );
                if let Some((other, _)) = seen.iter().find(|(_, c)| *c == colors[0]) {
                    panic!(
                        "{name} and {other} look alike at {depth:?}: {:?}",
                        colors[0]
                    );
                }
                seen.push((name, colors[0]));
            }
        }
    }
}

#[test]
fn island_and_sleep_tints_stay_apart_in_16_colours() {
    for (what, tints) in [
        ("islands", ISLAND_COLORS.to_vec()),
        ("sleep", vec![AWAKE_COLOR, ASLEEP_COLOR, FROZEN_COLOR]),
    ] {
        for depth in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            let shown: Vec<Color> = tints.iter().map(|&c| quantize(c, depth)).collect();
            for (i, a) in shown.iter().enumerate() {
                assert!(
                    !shown[..i].contains(a),
                    "{what} tint {i} looks like another at {depth:?}: {shown:?}"
                );
            }
        }
    }
}

/// The joints overlay shares its colours with overlays of the same meaning (force: the normals'
/// magenta) or seldom shown with it (the contacts' yellow), as every bright entry of 16 colours is
/// taken; within the joints' own picture the links, the axes and the forces stay apart.
#[test]
fn the_joints_links_axes_and_forces_are_flat_and_apart_at_every_depth() {
    use nudge::app::panels::joint_view::{JOINT_AXIS_COLOR, JOINT_FORCE_COLOR};
    use nudge::app::panels::overlays::JOINT_COLOR;
    let marks = [
        ("links", JOINT_COLOR),
        ("axes", JOINT_AXIS_COLOR),
        ("forces", JOINT_FORCE_COLOR),
    ];
    for depth in [
        ColorDepth::TrueColor,
        ColorDepth::Ansi256,
        ColorDepth::Ansi16,
    ] {
        for dither in Dither::ALL {
            let mut seen: Vec<(&str, Color)> = Vec::new();
            for (name, color) in marks {
                let colors = shown(color, depth, dither);
                assert_eq!(colors, [quantize(color, depth)], "{name} at {depth:?}");
                assert!(
                    !seen.iter().any(|(_, c)| *c == colors[0]),
                    "{name} looks like another joint mark at {depth:?}: {seen:?}"
                );
                seen.push((name, colors[0]));
            }
        }
    }
}
