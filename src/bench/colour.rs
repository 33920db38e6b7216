//! Colour fidelity at 256 and 16 colours: every built-in scene as `nudge snapshot` draws it (120×40
//! cells, textured, 90 steps in), measured against its truecolor frame with
//! [`term::fidelity`](crate::term::fidelity), dithered and not.

use crate::app::snapshot::{SnapshotOptions, render_buffer};
use crate::render::RenderMode;
use crate::scene::{self, Scene};
use crate::term::fidelity::{Fidelity, fidelity};
use crate::term::{ColorDepth, Dither};

/// Terminal size of the fidelity frames, cells.
pub const FIDELITY_SIZE: (u16, u16) = (120, 40);
/// Physics steps before the frame is drawn.
pub const FIDELITY_STEPS: u64 = 90;

/// The error of one scene at one depth and dither mode.
#[derive(Clone, Debug, serde::Serialize)]
pub struct FidelityRow {
    pub scene: String,
    #[serde(serialize_with = "super::app::depth_name")]
    pub colors: ColorDepth,
    #[serde(serialize_with = "super::app::dither_name")]
    pub dither: Dither,
    #[serde(flatten)]
    pub fidelity: Fidelity,
}

/// The snapshot options of the fidelity frames at `colors` and `dither`.
pub fn fidelity_options(colors: ColorDepth, dither: Dither) -> SnapshotOptions {
    let (cols, rows) = FIDELITY_SIZE;
    SnapshotOptions {
        cols,
        rows,
        mode: RenderMode::Textured,
        orthographic: None,
        color_depth: colors,
        dither,
        plain: false,
        steps: FIDELITY_STEPS,
        cell_aspect: 2.0,
        overlays: Default::default(),
    }
}

/// `scene` at `colors` with and without dithering, each against its truecolor frame.
pub fn scene_fidelity(scene: &Scene, colors: ColorDepth) -> [(Dither, Fidelity); 2] {
    let (_, reference) = render_buffer(
        scene.clone(),
        &fidelity_options(ColorDepth::TrueColor, Dither::None),
    );
    Dither::ALL.map(|dither| {
        let (_, frame) = render_buffer(scene.clone(), &fidelity_options(colors, dither));
        (dither, fidelity(&reference, &frame))
    })
}

/// Every built-in scene at 256 and 16 colours, dithered (the default) and not.
pub fn run() -> anyhow::Result<Vec<FidelityRow>> {
    let mut rows = Vec::new();
    for (name, _) in scene::builtin_scenes() {
        let scene = scene::load(name)?;
        for colors in [ColorDepth::Ansi256, ColorDepth::Ansi16] {
            for (dither, fidelity) in scene_fidelity(&scene, colors) {
                rows.push(FidelityRow {
                    scene: (*name).to_string(),
                    colors,
                    dither,
                    fidelity,
                });
            }
        }
    }
    Ok(rows)
}
