//! Where the time goes, by stage, for the inspector's profile: the world step's stages (timed by the
//! physics while the panel is open), and a frame's: the renderer's shadow pass and the rest of
//! rasterizing (from [`crate::render::RenderTimings`]), the debug overlays, the
//! half-block map onto cells, and the terminal write (ratatui's diff, escape encoding and the
//! write itself). Each is smoothed like the status bar's figures.

use ratatui::style::{Color, Style};
use ratatui::text::{Line, Span};

use crate::app::panels::inspector::Section;
use crate::physics::{Stage, StepProfile};

/// Exponential moving average weight of the newest sample.
const SMOOTHING: f64 = 0.1;

/// One smoothed stage time, ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Smoothed(pub f64);

impl Smoothed {
    pub fn record(&mut self, ms: f64) {
        self.0 = if self.0 == 0.0 {
            ms
        } else {
            self.0 + SMOOTHING * (ms - self.0)
        };
    }
}

/// A frame's stages, smoothed, ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameProfile {
    pub shadow: Smoothed,
    pub raster: Smoothed,
    pub overlay: Smoothed,
    pub map: Smoothed,
    pub write: Smoothed,
}

impl FrameProfile {
    /// The stages by name, in pipeline order.
    pub fn stages(&self) -> [(&'static str, f64); 5] {
        [
            ("raster", self.raster.0),
            ("shadow", self.shadow.0),
            ("overlay", self.overlay.0),
            ("map", self.map.0),
            ("write", self.write.0),
        ]
    }
}

/// The world step's stages (see [`crate::physics::profile`]), smoothed, ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepStages(pub [Smoothed; 7]);

impl StepStages {
    pub fn record(&mut self, profile: &StepProfile) {
        for (smoothed, stage) in self.0.iter_mut().zip(Stage::ALL) {
            smoothed.record(profile.get(stage).as_secs_f64() * 1e3);
        }
    }

    /// The stages by short name, in step order.
    pub fn stages(&self) -> [(&'static str, f64); 7] {
        let short = |stage: Stage| match stage {
            Stage::BroadPhase => "broad",
            Stage::NarrowPhase => "narrow",
            Stage::Prepare => "prepare",
            Stage::Solve => "solve",
            Stage::Integrate => "integr.",
            Stage::RestitutionStore => "store",
            Stage::Sleep => "sleep",
        };
        let mut out = [("", 0.0); 7];
        for (i, stage) in Stage::ALL.into_iter().enumerate() {
            out[i] = (short(stage), self.0[i].0);
        }
        out
    }
}

/// A table of stage times with a bar each, scaled to the largest, under a title with their sum.
pub fn stage_section(title: &str, stages: &[(&str, f64)], bar_cols: usize) -> Section {
    let total: f64 = stages.iter().map(|(_, ms)| ms).sum();
    let top = stages.iter().map(|&(_, ms)| ms).fold(0.0, f64::max);
    let lines = stages
        .iter()
        .map(|&(name, ms)| {
            let filled = if top > 0.0 {
                (ms / top * bar_cols as f64).round() as usize
            } else {
                0
            };
            Line::from(vec![
                Span::styled(format!("{name:<8}"), Style::default().fg(Color::Gray)),
                Span::raw(format!("{ms:>6.3} ")),
                Span::styled("▪".repeat(filled), Style::default().fg(Color::LightGreen)),
            ])
        })
        .collect();
    Section {
        title: format!("{title} {total:.3} ms"),
        lines,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_scale_to_the_costliest_stage() {
        let section = stage_section("frame", &[("a", 2.0), ("b", 0.5), ("c", 0.0)], 8);
        assert_eq!(section.title, "frame 2.500 ms");
        let text: Vec<String> = section
            .lines
            .iter()
            .map(|l| l.spans.iter().map(|s| s.content.to_string()).collect())
            .collect();
        assert_eq!(text[0], "a        2.000 ▪▪▪▪▪▪▪▪");
        assert_eq!(text[1], "b        0.500 ▪▪");
        assert_eq!(text[2], "c        0.000 ");
    }

    #[test]
    fn smoothing_starts_at_the_first_sample() {
        let mut s = Smoothed::default();
        s.record(4.0);
        assert_eq!(s.0, 4.0);
        s.record(14.0);
        assert_eq!(s.0, 5.0);
    }
}
