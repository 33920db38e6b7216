//! Every knob of the simulation in one place, with units.

use glam::Vec3;

/// World and solver parameters. Defaults are the ones every test and benchmark uses unless it says.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Gravitational acceleration, m/s².
    pub gravity: Vec3,
    /// Fixed step, s; > 0.
    pub dt: f32,
    /// Sub-steps per step; ≥ 1.
    pub substeps: u32,
    /// Extra solver iterations per sub-step; ≥ 1.
    pub iterations: u32,
    /// Whether bodies at rest fall asleep.
    pub sleep: bool,
    /// Linear damping, 1/s: v decays as e^(−c·t). 0 = none (the default: no hidden damping).
    pub linear_damping: f32,
    /// Angular damping, 1/s. 0 = none.
    pub angular_damping: f32,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            dt: 1.0 / 60.0,
            substeps: 4,
            iterations: 1,
            sleep: true,
            linear_damping: 0.0,
            angular_damping: 0.0,
        }
    }
}
