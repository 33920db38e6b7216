//! The pointer's path between reports: where a grab's spring pulls, moving continuously.
//!
//! A terminal reports the pointer a cell at a time (about 10 cm across the default scene), and only
//! when it enters another cell. Pulling toward each reported cell as it comes makes a steady drag a
//! train of jumps: every jump kicks the held body, and a throw goes off at whatever the last kick gave
//! it. What the reports do tell exactly is how many cells the pointer crossed and (to a frame) when,
//! so the track estimates the pointer's speed from them and glides toward the latest report at that
//! speed:
//!
//! - **Speed**: the least-squares slope of cell position against time over the reports of the last
//!   [`SPEED_WINDOW_STEPS`] (a frame's timing error on each report averages out over several), at
//!   most a cell in the time since the frame after the last report (a pointer that has not left its
//!   cell for a while is slowing down or has stopped).
//! - **Glide**: each step the target moves straight toward the latest report by that speed, faster
//!   if it trails by more than a cell ([`CATCH_UP_STEPS`]) or the pointer stopped
//!   ([`SETTLE_STEPS`]), and never past it.
//!
//! At a steady drag the target thus moves at the drag's speed, a cell or so behind the pointer, and a
//! body held on it keeps that speed when let go. Everything is counted in physics steps and cells, so
//! it is the same on every run, and its output reaches the world as a [`crate::physics::PointHold`],
//! which is journaled: a recording replays it without this module.

use std::collections::VecDeque;

use glam::Vec2;

/// Reports this many steps (0.25 s at 60 Hz) before the latest estimate the pointer's speed.
pub const SPEED_WINDOW_STEPS: u32 = 24;
/// The target may trail the latest report by a cell, the pointer's own uncertainty; beyond that it
/// closes the excess at least this many steps' fraction a step (0.1 s: it catches up with a pointer
/// that sped up)...
pub const CATCH_UP_STEPS: f32 = 6.0;
/// ...and within the cell this many (0.25 s: it comes to rest on a pointer that stopped). Closing the
/// whole gap in 0.1 s instead made the target's speed a sawtooth: the gap grows by a cell at each
/// report, and a cell in 0.1 s is 1 m/s across the default scene.
pub const SETTLE_STEPS: f32 = 15.0;
/// Steps between two frames, when the pointer's reports come, at the slowest frame rate (30 fps).
const REPORT_STEPS: u32 = 2;
/// Reports kept: enough to cover the window at any speed a terminal reports.
const KEPT: usize = 32;

/// A pointer followed in cell coordinates (absolute terminal columns and rows, fractional; the
/// centre of cell (c, r) is (c + ½, r + ½)).
#[derive(Clone, Debug, PartialEq)]
pub struct PointerTrack {
    /// Reported positions (the cell's centre plus `offset`) with the step they came in, oldest first.
    reports: VecDeque<(u32, Vec2)>,
    /// Where in its cell the held point was drawn when grabbed, from the cell's centre: every report
    /// is taken to stand for that place in its cell, so a press alone does not move the body.
    offset: Vec2,
    /// The target, cells.
    position: Vec2,
    /// Steps taken since the grab.
    now: u32,
}

/// The centre of terminal cell `cell`, in cells.
pub fn cell_centre(cell: (u16, u16)) -> Vec2 {
    Vec2::new(f32::from(cell.0) + 0.5, f32::from(cell.1) + 0.5)
}

impl PointerTrack {
    /// A pointer at `cell`, over the held point drawn at `exact` (cells).
    pub fn new(cell: (u16, u16), exact: Vec2) -> Self {
        let offset = if exact.is_finite() {
            (exact - cell_centre(cell)).clamp(Vec2::splat(-0.5), Vec2::splat(0.5))
        } else {
            Vec2::ZERO
        };
        let start = cell_centre(cell) + offset;
        Self {
            reports: VecDeque::from([(0, start)]),
            offset,
            position: start,
            now: 0,
        }
    }

    /// The pointer was reported at `cell`.
    pub fn report(&mut self, cell: (u16, u16)) {
        let at = cell_centre(cell) + self.offset;
        if self.reports.back().is_some_and(|&(_, last)| last == at) {
            return;
        }
        if self.reports.len() == KEPT {
            self.reports.pop_front();
        }
        self.reports.push_back((self.now, at));
    }

    /// Where the pointer was last reported (its cell, at the held point's place in it), cells.
    pub fn pointer(&self) -> Vec2 {
        self.reports.back().map_or(self.position, |&(_, at)| at)
    }

    /// The target now, cells.
    pub fn target(&self) -> Vec2 {
        self.position
    }

    /// The pointer's speed, cells per step, from the reports (see the module docs).
    pub fn speed(&self) -> f32 {
        let Some(&(last, _)) = self.reports.back() else {
            return 0.0;
        };
        let window = last.saturating_sub(SPEED_WINDOW_STEPS);
        let recent: Vec<(f32, Vec2)> = self
            .reports
            .iter()
            .filter(|(t, _)| *t >= window)
            .map(|&(t, at)| (t as f32, at))
            .collect();
        let slope = if recent.len() >= 2 {
            least_squares_slope(&recent)
        } else {
            // One report in the window: the pointer left the one before at most a window ago.
            self.reports.iter().rev().nth(1).map_or(0.0, |&(t, at)| {
                let since = (last - t.max(window)).max(1) as f32;
                (self.pointer() - at).length() / since
            })
        };
        // Reports come at most a frame apart while the pointer moves (two steps at 30 fps): silence
        // beyond that says it stayed in its cell.
        let silent = self.now - last;
        if silent > REPORT_STEPS {
            slope.min(1.0 / (silent - REPORT_STEPS) as f32)
        } else {
            slope
        }
    }

    /// Moves the target on by one step; returns where it was and where it is, cells.
    pub fn advance(&mut self) -> (Vec2, Vec2) {
        let from = self.position;
        let gap = self.pointer() - from;
        let distance = gap.length();
        let speed = self.speed();
        let allowed = (speed * CATCH_UP_STEPS).min(1.0);
        let stride = speed
            .max((distance - allowed) / CATCH_UP_STEPS)
            .max(distance / SETTLE_STEPS)
            .min(distance);
        if distance > 0.0 && stride.is_finite() {
            self.position = from + gap * (stride / distance);
        }
        self.now = self.now.saturating_add(1);
        if self.reports.len() > 2 {
            let old = self.now.saturating_sub(4 * SPEED_WINDOW_STEPS);
            while self.reports.len() > 2 && self.reports[0].0 < old {
                self.reports.pop_front();
            }
        }
        (from, self.position)
    }
}

/// |d position / d t| fitted by least squares to `(t, position)` samples; 0 if they share one time.
fn least_squares_slope(samples: &[(f32, Vec2)]) -> f32 {
    let n = samples.len() as f32;
    let t_mean = samples.iter().map(|(t, _)| t).sum::<f32>() / n;
    let p_mean = samples.iter().map(|(_, p)| *p).sum::<Vec2>() / n;
    let (mut tt, mut tp) = (0.0, Vec2::ZERO);
    for &(t, p) in samples {
        tt += (t - t_mean) * (t - t_mean);
        tp += (t - t_mean) * (p - p_mean);
    }
    if tt > 0.0 { (tp / tt).length() } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_press_alone_leaves_the_target_on_the_held_point() {
        let exact = Vec2::new(10.3, 7.9);
        let mut track = PointerTrack::new((10, 7), exact);
        for _ in 0..10 {
            assert_eq!(track.advance(), (exact, exact));
        }
    }

    #[test]
    fn a_steady_drag_moves_the_target_at_the_drags_speed_without_jumps() {
        // A cell every three steps, reported at frame boundaries (every other step): the reports
        // come two and four steps apart.
        let mut track = PointerTrack::new((0, 0), cell_centre((0, 0)));
        let mut strides = Vec::new();
        for step in 0..120u32 {
            if step % 2 == 0 {
                track.report(((step / 3) as u16, 0));
            }
            let (from, to) = track.advance();
            if step >= 60 {
                strides.push((to - from).x);
            }
        }
        let mean = strides.iter().sum::<f32>() / strides.len() as f32;
        assert!((mean - 1.0 / 3.0).abs() < 0.02, "{mean} cells a step");
        let most = strides.iter().cloned().fold(0.0, f32::max);
        assert!(most < 0.5, "the largest stride is {most} cells");
    }

    #[test]
    fn the_target_catches_up_with_a_pointer_that_stopped() {
        let mut track = PointerTrack::new((0, 0), cell_centre((0, 0)));
        for step in 0..30u32 {
            track.report(((step / 2) as u16, 0));
            track.advance();
        }
        for _ in 0..60 {
            track.advance();
        }
        assert!((track.target() - track.pointer()).length() < 1e-3);
    }
}
