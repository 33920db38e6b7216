//! The representable range: what the engine promises to step without a non-finite number.
//!
//! The engine computes in f32 (about 7 significant digits, up to 3.4e38). A value that is finite is
//! not therefore usable: a ball of 1e-20 m has an inverse inertia of 1e40 (infinite in f32), and a
//! 54 km ball touching a 39 nm one differ by more than f32 can resolve. Scene files, the sandbox
//! and the command line refuse what lies outside these ranges, with a message naming the range,
//! instead of letting a step turn it into NaN. Inside them every step stays finite (tested in
//! `tests/physics/hostile_scenes.rs` at their corners).
//!
//! The ranges are wide for a sandbox, not for physics: accuracy at their corners is what f32
//! allows (a 1 mm ball 10 km from the origin moves in steps of 1 mm).

use glam::Vec3;

use crate::geometry::Shape;
use crate::physics::settings::Settings;

/// Smallest and largest radius or half extent, m.
pub const MIN_SIZE: f32 = 1e-3;
pub const MAX_SIZE: f32 = 1e3;
/// Farthest any coordinate of a body's position may be from the origin, m. (f32 spaces numbers
/// 1 mm apart here, the smallest size.)
pub const MAX_COORDINATE: f32 = 1e4;
/// Lightest and heaviest dynamic body, kg (a milligram: a 1 cm ball of the default density, 1 kg/m³,
/// weighs 4 mg).
pub const MIN_MASS: f32 = 1e-6;
pub const MAX_MASS: f32 = 1e6;
/// Largest ratio between the bounding radii, and between the masses, of two dynamic bodies of one
/// world. (Static bodies only need to be in range: they never move.)
pub const MAX_SIZE_RATIO: f32 = 1e4;
pub const MAX_MASS_RATIO: f32 = 1e6;
/// Shortest and longest fixed step, s.
pub const MIN_DT: f32 = 1e-4;
pub const MAX_DT: f32 = 0.1;
/// Strongest gravity, m/s² (100 g).
pub const MAX_GRAVITY: f32 = 1000.0;
/// Largest friction and rolling-resistance coefficients (rubber on rubber is about 1).
pub const MAX_FRICTION: f32 = 10.0;
pub const MAX_ROLLING_RESISTANCE: f32 = 1.0;
/// Most bodies in one world (5× the largest built-in scene): beyond it memory, not physics, fails.
pub const MAX_BODIES: usize = 20_000;
/// Most sub-steps and iterations per step: more only multiplies the time of a step.
pub const MAX_SUBSTEPS: u32 = 64;
pub const MAX_ITERATIONS: u32 = 64;

/// `value` if it is finite and within `[min, max]`, else a message naming `what` and the range.
pub fn in_range(what: &str, value: f32, min: f32, max: f32) -> Result<f32, String> {
    if value.is_finite() && value >= min && value <= max {
        Ok(value)
    } else {
        Err(format!(
            "{what} must be between {} and {}, got {}",
            short(min),
            short(max),
            short(value)
        ))
    }
}

/// Checks a shape's sizes against [`MIN_SIZE`] and [`MAX_SIZE`].
pub fn check_shape(shape: &Shape) -> Result<(), String> {
    match *shape {
        Shape::Sphere { radius } => in_range("radius (m)", radius, MIN_SIZE, MAX_SIZE).map(drop),
        Shape::Cuboid { half_extents } => {
            for h in half_extents.to_array() {
                if !(h.is_finite() && (MIN_SIZE..=MAX_SIZE).contains(&h)) {
                    return Err(format!(
                        "half_extents (m) must each be between {} and {}, got {}",
                        short(MIN_SIZE),
                        short(MAX_SIZE),
                        short_vec(half_extents)
                    ));
                }
            }
            Ok(())
        }
    }
}

/// Checks a position against [`MAX_COORDINATE`].
pub fn check_position(what: &str, p: Vec3) -> Result<(), String> {
    if p.is_finite() && p.abs().max_element() <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(format!(
            "{what} (m) must be finite and within {} of the origin on each axis, got {}",
            short(MAX_COORDINATE),
            short_vec(p)
        ))
    }
}

/// Checks a vector's length is finite and at most `max`.
pub fn check_length(what: &str, v: Vec3, max: f32) -> Result<(), String> {
    if v.is_finite() && v.length() <= max {
        Ok(())
    } else {
        Err(format!(
            "{what} must be finite and at most {} long, got {}",
            short(max),
            short_vec(v)
        ))
    }
}

/// Checks the settings a scene, a recording or the command line can choose: dt, gravity,
/// sub-steps and iterations.
pub fn check_settings(settings: &Settings) -> Result<(), String> {
    in_range("dt (s)", settings.dt, MIN_DT, MAX_DT)?;
    check_length("gravity (m/s²)", settings.gravity, MAX_GRAVITY)?;
    if !(1..=MAX_SUBSTEPS).contains(&settings.substeps) {
        return Err(format!(
            "substeps must be between 1 and {MAX_SUBSTEPS}, got {}",
            settings.substeps
        ));
    }
    if !(1..=MAX_ITERATIONS).contains(&settings.iterations) {
        return Err(format!(
            "iterations must be between 1 and {MAX_ITERATIONS}, got {}",
            settings.iterations
        ));
    }
    if settings.mass_ratio_iterations > MAX_ITERATIONS {
        return Err(format!(
            "mass_ratio_iterations must be at most {MAX_ITERATIONS}, got {}",
            settings.mass_ratio_iterations
        ));
    }
    Ok(())
}

/// A number in a short form that reads back the same: as written (`0.001`, `54117`) up to eight
/// characters, else scientific when that is shorter (`1e308`, not 309 digits).
pub fn short(v: f32) -> String {
    if v.is_nan() {
        return "nan".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.into();
    }
    let plain = format!("{v}");
    let scientific = format!("{v:e}");
    if plain.len() > 8 && scientific.len() < plain.len() {
        scientific
    } else {
        plain
    }
}

/// A vector as `[x, y, z]` of [`short`] numbers.
pub fn short_vec(v: Vec3) -> String {
    format!("[{}, {}, {}]", short(v.x), short(v.y), short(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_in_their_shortest_form() {
        assert_eq!(short(1e30), "1e30");
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(1e-7), "1e-7");
        assert_eq!(short(400.0), "400");
        assert_eq!(short(f32::NEG_INFINITY), "-inf");
    }

    #[test]
    fn ranges_are_inclusive_and_refuse_non_finite_values() {
        assert_eq!(in_range("x", MIN_SIZE, MIN_SIZE, MAX_SIZE), Ok(MIN_SIZE));
        assert!(in_range("x", f32::NAN, 0.0, 1.0).is_err());
        let message = in_range("radius (m)", 1e-20, MIN_SIZE, MAX_SIZE).unwrap_err();
        assert_eq!(
            message,
            "radius (m) must be between 0.001 and 1000, got 1e-20"
        );
    }

    #[test]
    fn the_default_settings_are_in_range() {
        assert_eq!(check_settings(&Settings::default()), Ok(()));
    }
}
