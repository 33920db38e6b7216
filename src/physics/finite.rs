//! Debug builds check that every stage of a step leaves the bodies finite, so a NaN is caught at
//! the stage that made it rather than steps later as a body that "fell off the world". Inside the
//! representable range (`limits`) no stage may produce one; release builds skip the checks.

use crate::physics::body::Body;
use crate::physics::solve::solver_body::SolverBody;

/// Panics (debug builds only) if a body's pose or velocities are not finite after `stage`.
#[inline]
pub(crate) fn debug_check_bodies(bodies: &[Body], stage: &str) {
    if cfg!(debug_assertions)
        && let Some(i) = bodies.iter().position(|b| {
            !(b.pose().is_finite()
                && b.linear_velocity().is_finite()
                && b.angular_velocity().is_finite())
        })
    {
        panic!("body {i} is not finite after {stage}: {:?}", bodies[i]);
    }
}

/// Panics (debug builds only) if a solver body's velocities or displacements are not finite after
/// `stage`.
#[inline]
pub(crate) fn debug_check_solver(bodies: &[SolverBody], stage: &str) {
    if cfg!(debug_assertions)
        && let Some(i) = bodies.iter().position(|b| {
            !(b.v.is_finite() && b.w.is_finite() && b.dp.is_finite() && b.dtheta.is_finite())
        })
    {
        panic!("solver body {i} is not finite after {stage}");
    }
}

#[cfg(all(test, debug_assertions))]
mod tests {
    use super::*;
    use crate::geometry::{Pose, Shape};
    use crate::physics::BodyDesc;

    #[test]
    #[should_panic(expected = "body 1 is not finite after the test stage")]
    fn a_nan_velocity_is_caught_at_its_stage() {
        let desc = BodyDesc::dynamic(Shape::sphere(0.5), Pose::IDENTITY, 1.0);
        let good = Body::from_desc(&desc);
        let mut bad = good.clone();
        bad.linear_velocity.y = f32::NAN;
        debug_check_bodies(&[good, bad], "the test stage");
    }
}
