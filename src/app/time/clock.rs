//! Fixed-step time keeping: real time in, a whole number of physics steps out.

use std::time::Duration;

/// Accumulates real time and hands out fixed physics steps.
///
/// A slow frame runs several steps to catch up, but never more than `max_steps`: after a stall
/// (a suspended laptop, a debugger) the leftover time is dropped instead of spiralling.
#[derive(Clone, Debug)]
pub struct StepClock {
    dt: f64,
    accumulator: f64,
    max_steps: u32,
}

impl StepClock {
    /// `dt_s` > 0; `max_steps` ≥ 1.
    pub fn new(dt_s: f32, max_steps: u32) -> Self {
        Self {
            dt: dt_s.max(1e-6) as f64,
            accumulator: 0.0,
            max_steps: max_steps.max(1),
        }
    }

    /// Adds `elapsed` and returns how many steps to run now.
    pub fn advance(&mut self, elapsed: Duration) -> u32 {
        self.accumulator += elapsed.as_secs_f64();
        let due = (self.accumulator / self.dt).floor();
        if due >= self.max_steps as f64 {
            self.accumulator = 0.0;
            return self.max_steps;
        }
        self.accumulator -= due * self.dt;
        due as u32
    }

    /// Forgets accumulated time (after a pause, so unpausing does not fast-forward).
    pub fn reset(&mut self) {
        self.accumulator = 0.0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_follow_real_time() {
        let mut clock = StepClock::new(0.01, 8);
        assert_eq!(clock.advance(Duration::from_millis(25)), 2);
        assert_eq!(clock.advance(Duration::from_millis(5)), 1);
    }

    #[test]
    fn a_stall_is_capped_and_forgotten() {
        let mut clock = StepClock::new(0.01, 8);
        assert_eq!(clock.advance(Duration::from_secs(10)), 8);
        assert_eq!(clock.advance(Duration::from_millis(1)), 0);
    }
}
