//! Speculative contacts taken at their time of impact.
//!
//! A speculative point is found before the bodies touch, from their poses at the start of the
//! step. Its normal is then the direction between the closest features *now*, not at the moment
//! they meet: for two balls in an oblique impact, the line of centres at the start of the step,
//! turned from the line of centres at impact by the distance the balls travel in between. The
//! impulse the solver and the impact pass apply along it is off by that angle (12.5 % of the
//! approach speed for two balls meeting 0.4 m off-centre at 3 m/s, 23.6 % at one sub-step).
//!
//! Worse, the plane of that normal is reached sooner than the ball: the distance between the
//! spheres is a convex function of time, so its tangent at the start of the step crosses zero
//! before it does, and the speculative row stopped the balls a step early, on a normal turned
//! further still (2 % at 0.1 m off-centre even once the step of the impact was right).
//!
//! So, for a one-point manifold whose bodies are apart and approaching, the relative motion over
//! the step (the velocities at its start, held) is swept to the time of impact t*, and the
//! manifold is taken at t_m = min(t*, dt) (for spheres that miss, at their closest approach or
//! dt):
//!
//! ```text
//! sphere–sphere: |Δx + v·t*| = r_a + r_b, the first root (exact: a sphere's spin does not move it)
//! box–sphere:    conservative advancement (Mirtich 1996, "Impulse-based dynamic simulation of
//!                rigid body systems", §2.3): t ← t + d(t)/(|v_rel| + |ω_box|·R_box), d(t) the
//!                distance at the poses of time t, which never steps past the impact because no
//!                point of the box closes faster than that bound (a spinning box is swept too)
//! n = the normal at t_m, the point its contact point p_m riding with A (p_m − v_a·t_m),
//! approach = (v_b − v_a)·t_m (B's anchors, see `Manifold::approach`),
//! s = d(t_m) − v_n·t_m,  v_n the relative normal velocity of the contact point
//! ```
//!
//! The separation is the one along the fixed normal at the start of the step (for two spheres
//! exactly (Δx)·n − r_a − r_b), so the speculative row v_n ≥ −s/dt lets the bodies close until t*
//! and no further, and the impact pass reads the approach along the normal they meet on. Bodies
//! that meet after this step get the plane of its end, which they do not reach (s + v_n·dt is
//! d(dt), positive); balls that miss get the plane of their closest approach, parallel to their motion. Bodies
//! that touch already (s ≤ 0, a resting ball) or part keep the manifold of their poses at the start
//! of the step, exactly as before.

use glam::{Quat, Vec3};

use crate::geometry::{Pose, Shape};
use crate::physics::Manifold;
use crate::physics::narrow::collide::{box_sphere, unit_or};

/// A body's velocities at the start of the step: what the sweep holds over it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Motion {
    /// Velocity of the centre, m/s.
    pub linear: Vec3,
    /// Angular velocity, rad/s.
    pub angular: Vec3,
}

/// Conservative advancement stops once the surfaces are this close, m.
const CLOSE_ENOUGH: f32 = 1e-5;

/// Conservative advancement gives up after this many steps (a grazing approach closes slowly),
/// and takes the manifold where it stopped: between the start and the impact, still on the near
/// side of the impact.
const MAX_ADVANCES: usize = 24;

/// `manifold` (of `shape_a` at `pose_a` and `shape_b` at `pose_b`, at the start of a step of `dt`
/// seconds) taken at the time of impact within the step, when it is a one-point speculative
/// contact of two approaching bodies of which one is a sphere and that meet within the step; else
/// `manifold` unchanged. See the module docs.
pub fn at_impact(
    (shape_a, pose_a, motion_a): (&Shape, &Pose, Motion),
    (shape_b, pose_b, motion_b): (&Shape, &Pose, Motion),
    dt: f32,
    manifold: Manifold,
) -> Manifold {
    if manifold.len != 1 || manifold.points[0].separation <= 0.0 || dt.is_nan() || dt <= 0.0 {
        return manifold;
    }
    let p = manifold.points[0].point;
    let closing = manifold.normal.dot(point_velocity(motion_b, pose_b, p))
        - manifold.normal.dot(point_velocity(motion_a, pose_a, p));
    if closing.is_nan() || closing >= 0.0 {
        return manifold;
    }
    let swept = match (*shape_a, *shape_b) {
        (Shape::Sphere { radius: r_a }, Shape::Sphere { radius: r_b }) => sphere_sphere_impact(
            r_a,
            pose_a.position,
            r_b,
            pose_b.position,
            motion_a,
            motion_b,
            dt,
        ),
        (Shape::Cuboid { half_extents }, Shape::Sphere { radius }) => box_sphere_impact(
            (half_extents, pose_a, motion_a),
            (radius, pose_b.position, motion_b.linear),
            dt,
        ),
        (Shape::Sphere { radius }, Shape::Cuboid { half_extents }) => box_sphere_impact(
            (half_extents, pose_b, motion_b),
            (radius, pose_a.position, motion_a.linear),
            dt,
        )
        .map(|(t, mut m)| {
            m.normal = -m.normal;
            (t, m)
        }),
        _ => None,
    };
    let Some((t, at_t)) = swept else {
        return manifold;
    };
    // `at_t`: the manifold of the poses at time t. Its point rides back with A to the start of the
    // step; B's anchors with B (through `approach`).
    let n = at_t.normal;
    let p_t = at_t.points[0].point;
    let (x_a_t, x_b_t) = (
        pose_a.position + motion_a.linear * t,
        pose_b.position + motion_b.linear * t,
    );
    let v_n = n.dot(motion_b.linear + motion_b.angular.cross(p_t - x_b_t))
        - n.dot(motion_a.linear + motion_a.angular.cross(p_t - x_a_t));
    let separation = at_t.points[0].separation - v_n * t;
    if !(separation > 0.0 && separation.is_finite() && n.is_finite()) {
        return manifold;
    }
    let mut out = manifold;
    out.normal = n;
    out.points[0].point = p_t - motion_a.linear * t;
    out.points[0].separation = separation;
    out.points[0].id = at_t.points[0].id;
    out.approach = (motion_b.linear - motion_a.linear) * t;
    out
}

/// Velocity of the material point at `p` of a body at `pose` moving with `motion`.
fn point_velocity(motion: Motion, pose: &Pose, p: Vec3) -> Vec3 {
    motion.linear + motion.angular.cross(p - pose.position)
}

/// The first time t at which the spheres touch, or where they pass closest if they miss, held to
/// the step (≤ `dt`), and their manifold then.
fn sphere_sphere_impact(
    r_a: f32,
    x_a: Vec3,
    r_b: f32,
    x_b: Vec3,
    motion_a: Motion,
    motion_b: Motion,
    dt: f32,
) -> Option<(f32, Manifold)> {
    let d = x_b - x_a;
    let v = motion_b.linear - motion_a.linear;
    let reach = r_a + r_b;
    // |d + v t|² = reach²: a t² + 2 b t + c = 0, c > 0 (apart), b < 0 (approaching).
    let (a, b, c) = (v.dot(v), d.dot(v), d.dot(d) - reach * reach);
    if !(a > 0.0 && b < 0.0 && c > 0.0) {
        return None;
    }
    let disc = b * b - a * c;
    let t = if disc >= 0.0 {
        // The smaller root, in the form that does not cancel: c / (−b + √disc).
        c / (-b + disc.sqrt())
    } else {
        // A miss: the closest approach, where the plane is parallel to the motion.
        -b / a
    };
    let t = t.min(dt);
    let d_t = d + v * t;
    let n = unit_or(d_t, Vec3::Y);
    let mut m =
        crate::physics::narrow::collide::sphere_sphere(r_a, Vec3::ZERO, r_b, d_t, f32::INFINITY);
    // Back in world space at time t (A's centre then), on the exact normal of the root.
    m.normal = n;
    m.points[0].point = x_a + motion_a.linear * t + 0.5 * (d_t + n * (r_a - r_b));
    m.points[0].separation = d_t.dot(n) - reach;
    Some((t, m))
}

/// Conservative advancement of a sphere (`radius`, centre `center` moving at `v_sphere`) against a
/// box (`half_extents` at `pose` moving with `motion`): the first time t at which they
/// touch (to [`CLOSE_ENOUGH`]), or where [`MAX_ADVANCES`] left it short of that, or `dt` when they
/// do not meet within the step, and the box–sphere manifold then (normal from the box).
fn box_sphere_impact(
    (half_extents, pose, motion): (Vec3, &Pose, Motion),
    (radius, center, v_sphere): (f32, Vec3, Vec3),
    dt: f32,
) -> Option<(f32, Manifold)> {
    let v = v_sphere - motion.linear;
    let bound = v.length() + motion.angular.length() * half_extents.length();
    if !(bound > 0.0 && bound.is_finite()) {
        return None;
    }
    let at = |t: f32| {
        let turned = Quat::from_scaled_axis(motion.angular * t) * pose.rotation;
        let box_pose = Pose::new(pose.position + motion.linear * t, turned.normalize());
        box_sphere(
            half_extents,
            &box_pose,
            radius,
            center + v_sphere * t,
            f32::INFINITY,
        )
    };
    let mut t = 0.0;
    let mut m = at(t);
    for _ in 0..MAX_ADVANCES {
        if m.is_empty() {
            return None;
        }
        let gap = m.points[0].separation;
        if gap <= CLOSE_ENOUGH {
            break;
        }
        t += gap / bound;
        if t >= dt {
            // Not within the step: the plane of its end, which the bodies do not reach.
            t = dt;
            m = at(t);
            break;
        }
        m = at(t);
    }
    (!m.is_empty()).then_some((t, m))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::narrow::collide::collide;

    fn still() -> Motion {
        Motion::default()
    }

    fn moving(v: Vec3) -> Motion {
        Motion {
            linear: v,
            angular: Vec3::ZERO,
        }
    }

    const DT: f32 = 1.0 / 60.0;

    /// A ball at `x` moving at `v` towards a resting ball at the origin, both of radius 0.25.
    fn balls(x: Vec3, v: Vec3) -> (Manifold, Manifold) {
        let ball = Shape::sphere(0.25);
        let (pa, pb) = (Pose::from_position(x), Pose::IDENTITY);
        let start = collide(&ball, &pa, &ball, &pb, 1.0);
        let swept = at_impact((&ball, &pa, moving(v)), (&ball, &pb, still()), DT, start);
        (start, swept)
    }

    #[test]
    fn an_oblique_impact_takes_the_line_of_centres_at_the_moment_of_impact() {
        let (x, v) = (Vec3::new(-0.48, 0.4, 0.0), Vec3::new(3.0, 0.0, 0.0));
        let (start, m) = balls(x, v);
        // Centres 0.5 apart at the impact, at x = −√(0.25 − 0.16) = −0.3: 0.06 s away, past the
        // step: the plane is the one of the step's end, which the ball does not reach in it.
        let v_n = |m: &Manifold| -v.dot(m.normal);
        assert!((start.normal - m.normal).length() > 0.01);
        let end = Vec3::ZERO - (x + v * DT);
        assert!((m.normal - end.normalize()).length() < 1e-5, "{}", m.normal);
        let at_end = m.points[0].separation + v_n(&m) * DT;
        assert!((at_end - (end.length() - 0.5)).abs() < 1e-5, "{at_end}");
        // 0.03 m short of it: the impact falls 0.01 s into the step.
        let x = Vec3::new(-0.33, 0.4, 0.0);
        let (start, m) = balls(x, v);
        let t = 0.03 / 3.0;
        let n_impact = Vec3::new(0.3, -0.4, 0.0) / 0.5;
        assert!((m.normal - n_impact).length() < 1e-5, "{}", m.normal);
        assert!((start.normal - n_impact).length() > 0.01);
        assert!((m.approach + v * t).length() < 1e-5, "{}", m.approach);
        // The separation along that normal at the start closes at v·n in exactly t.
        let v_n = -v.dot(m.normal);
        assert!((m.points[0].separation + v_n * t).abs() < 1e-6);
        // The point rides with A (moving): A's surface point at the impact, back at the start.
        let p_impact = Vec3::new(-0.15, 0.2, 0.0);
        assert!((m.points[0].point - (p_impact - v * t)).length() < 1e-5);
    }

    #[test]
    fn balls_that_touch_or_part_keep_their_manifold() {
        let v = Vec3::new(3.0, 0.0, 0.0);
        for (x, v) in [
            (Vec3::new(-0.49, 0.0, 0.0), v),
            (Vec3::new(-0.52, 0.0, 0.0), -v),
        ] {
            let (start, m) = balls(x, v);
            assert_eq!(start, m, "{x} {v}");
        }
    }

    #[test]
    fn balls_that_miss_get_the_plane_of_their_closest_approach() {
        let v = Vec3::new(3.0, 0.0, 0.0);
        // Closest 0.01 s into the step, 0.01 m apart.
        let (_, m) = balls(Vec3::new(-0.03, 0.51, 0.0), v);
        assert!((m.normal - Vec3::NEG_Y).length() < 1e-5, "{}", m.normal);
        assert!((m.points[0].separation - 0.01).abs() < 1e-5);
    }

    #[test]
    fn a_ball_striking_a_box_edge_obliquely_takes_the_normal_of_the_impact() {
        let cube = Shape::cuboid(Vec3::splat(0.5));
        let ball = Shape::sphere(0.25);
        // Moving along +x past the box's top edge at x = −0.5, y = 0.5; centre 0.2 above the top.
        let v = Vec3::new(3.0, 0.0, 0.0);
        let x = Vec3::new(-0.5 - 0.15 - 0.03, 0.7, 0.0);
        let (pb, pa) = (Pose::IDENTITY, Pose::from_position(x));
        let start = collide(&ball, &pa, &cube, &pb, 1.0);
        let m = at_impact((&ball, &pa, moving(v)), (&cube, &pb, still()), DT, start);
        // At the impact the centre is 0.25 from the edge: (−0.5 − 0.15, 0.7), normal (−0.6, 0.8)
        // from the box, so (0.6, −0.8) from the ball.
        let n = Vec3::new(0.6, -0.8, 0.0);
        assert!((m.normal - n).length() < 1e-4, "{}", m.normal);
        assert!((m.approach + v * 0.01).length() < 1e-4, "{}", m.approach);
        assert!((m.points[0].separation - 0.6 * 3.0 * 0.01).abs() < 1e-4);
    }
}
