//! What the app shows of the joints beyond their links (`overlays::joint_links`): the joints
//! overlay's marks (each hinge's and slider's axis through its anchor, and an arrow of the force
//! each joint holds its body B with) and the figures the inspector lists for the selected body's
//! joints. Read from the world's read-only views; nothing here writes to it.
//!
//! A joint's load ([`World::joint_load`]) keeps its axial rows (motor, limits, spring, a distance
//! joint's rod) apart from the rest; here they are folded back in along the axis they act on, so a
//! slider's or distance joint's force and a hinge's torque are the whole of what the joint applies.

use glam::Vec3;

use crate::color::Rgb;
use crate::geometry::Pose;
use crate::physics::{BodyId, Joint, JointKind, World};
use crate::render::Overlay;

/// A hinge's or slider's axis: bright yellow (xterm entry 11 at 16 colours), apart from the links'
/// light grey and the force arrows' magenta at every depth (`tests/app/inspect_overlay_colours.rs`).
pub const JOINT_AXIS_COLOR: Rgb = Rgb::new(255, 255, 0);
/// A joint's force arrow: bright magenta (entry 13), the contact normals' colour, as both are forces.
pub const JOINT_FORCE_COLOR: Rgb = Rgb::new(255, 0, 255);

/// An axis is drawn this far either side of the anchor, m: past a chain link's 12 cm radius, short
/// of the next anchor 30 cm on (the `wrecking` chain).
pub const AXIS_HALF_M: f32 = 0.25;
/// A force arrow is `FORCE_M_PER_DECADE · log₁₀(1 + F / 1 N)` long: 6 cm for 1 N, 21 cm for 10 N,
/// 40 cm for 100 N, 55 cm for the 590 N at the top of the `wrecking` chain. A logarithm, because
/// one view shows a chain link's 5 N beside the ball's 500 N and both must read; a length per decade
/// is a scale one learns once.
pub const FORCE_M_PER_DECADE: f32 = 0.2;
/// Forces below this get no arrow, N.
pub const MIN_FORCE_N: f32 = 0.01;

/// What a joint applies to its body B now (A feels the opposite), its axial rows folded in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointFigures {
    /// Force on B, world, N: the point or line rows, plus a slider's axial rows along its axis and a
    /// distance joint's along the line from A's anchor to B's.
    pub force: Vec3,
    /// Torque on B, world, N·m: the weld or hinge-axis rows, plus a hinge's axial rows about its axis.
    pub torque: Vec3,
    /// The axial rows alone (N·m for a hinge, N for a slider; positive turns B forward or pushes it
    /// away from A), for a hinge or slider with a motor or limits; `None` for the others.
    pub axial: Option<f32>,
}

/// A hinge's or slider's axis in world coordinates now (A's axis; the world's for a joint to it).
pub fn axis_world(world: &World, joint: &Joint) -> Option<Vec3> {
    match joint.desc.kind {
        JointKind::Hinge { .. } | JointKind::Slider { .. } => {
            let pose_a = joint
                .desc
                .a
                .map_or(Pose::IDENTITY, |id| *world.body(id).pose());
            Some(pose_a.rotation * joint.desc.local_axis_a)
        }
        _ => None,
    }
}

impl JointFigures {
    /// From [`World::joint_load`] (zero for a joint frozen at both ends).
    pub fn of(world: &World, joint: &Joint) -> Self {
        let load = world.joint_load(joint);
        let axis = axis_world(world, joint).unwrap_or(Vec3::ZERO);
        let (mut force, mut torque, mut axial) = (load.force, load.torque, None);
        match joint.desc.kind {
            JointKind::Hinge { limits, motor } => {
                torque += axis * load.axial;
                if limits.is_some() || motor.is_some() {
                    axial = Some(load.axial);
                }
            }
            JointKind::Slider { limits, motor } => {
                force += axis * load.axial;
                if limits.is_some() || motor.is_some() {
                    axial = Some(load.axial);
                }
            }
            JointKind::Distance { .. } => {
                let (pa, pb) = world.joint_anchors(joint);
                force += (pb - pa).normalize_or_zero() * load.axial;
            }
            JointKind::Ball | JointKind::Fixed => {}
        }
        Self {
            force,
            torque,
            axial,
        }
    }

    /// The figures as body `id` feels them: B's as they are, A's opposite.
    pub fn on(self, joint: &Joint, id: BodyId) -> Self {
        if joint.desc.b == id {
            return self;
        }
        Self {
            force: -self.force,
            torque: -self.torque,
            axial: self.axial.map(|a| -a),
        }
    }
}

/// The length of the arrow drawn for a force of `newtons`, m (see [`FORCE_M_PER_DECADE`]).
pub fn force_arrow_m(newtons: f32) -> f32 {
    FORCE_M_PER_DECADE * (1.0 + newtons.max(0.0)).log10()
}

/// The joints overlay: each hinge's and slider's axis, a line through A's anchor, and at B's anchor
/// an arrow along the force the joint holds B with (a hanging chain's point up, towards what holds
/// them).
pub fn joint_marks(world: &World, out: &mut Overlay) {
    for joint in world.joints() {
        let (pa, pb) = world.joint_anchors(joint);
        if let Some(axis) = axis_world(world, joint) {
            out.line(
                pa - axis * AXIS_HALF_M,
                pa + axis * AXIS_HALF_M,
                JOINT_AXIS_COLOR,
            );
        }
        let force = JointFigures::of(world, joint).force;
        let newtons = force.length();
        if newtons >= MIN_FORCE_N && newtons.is_finite() {
            out.arrow(
                pb,
                pb + force / newtons * force_arrow_m(newtons),
                JOINT_FORCE_COLOR,
            );
        }
    }
}

/// At most this many joints get a label with their force: the strongest, where a label fits.
pub const MAX_FORCE_LABELS: usize = 6;

/// A label of a joint's force, to be written over the view from `cell` (column, row, relative to
/// the view's top-left cell) rightwards.
#[derive(Clone, Debug, PartialEq)]
pub struct ForceLabel {
    pub cell: (u16, u16),
    pub text: String,
}

/// A force as a label shows it: "590 N", "4.9 N".
pub fn force_text(newtons: f32) -> String {
    if newtons >= 9.95 {
        format!("{newtons:.0} N")
    } else {
        format!("{newtons:.1} N")
    }
}

/// Labels for the joints overlay: the [`MAX_FORCE_LABELS`] strongest joints' forces, each written
/// one cell right of the cell B's anchor is drawn in (`cell_of`: the view's cell of a world point,
/// `None` behind the camera), left out where it would leave the view (`cols × rows` cells) or touch
/// a label already placed, so a chain's 21 joints give a few labels one can read rather than a
/// smear of digits.
pub fn force_labels(
    world: &World,
    cell_of: impl Fn(Vec3) -> Option<(i32, i32)>,
    cols: u16,
    rows: u16,
) -> Vec<ForceLabel> {
    let mut forces: Vec<(f32, Vec3)> = world
        .joints()
        .iter()
        .map(|joint| {
            let newtons = JointFigures::of(world, joint).force.length();
            (newtons, world.joint_anchors(joint).1)
        })
        .filter(|(newtons, _)| *newtons >= MIN_FORCE_N && newtons.is_finite())
        .collect();
    forces.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut labels: Vec<ForceLabel> = Vec::new();
    for (newtons, anchor) in forces {
        if labels.len() == MAX_FORCE_LABELS {
            break;
        }
        let Some((x, y)) = cell_of(anchor) else {
            continue;
        };
        let text = force_text(newtons);
        let (x, width) = (x + 1, text.chars().count() as i32);
        if x < 0 || y < 0 || x + width > i32::from(cols) || y >= i32::from(rows) {
            continue;
        }
        // A blank cell between labels on a row, and none on the rows next to one.
        let clear = labels.iter().all(|l| {
            let (lx, ly) = (i32::from(l.cell.0), i32::from(l.cell.1));
            let lw = l.text.chars().count() as i32;
            (ly - y).abs() > 1 || x > lx + lw || lx > x + width
        });
        if clear {
            labels.push(ForceLabel {
                cell: (x as u16, y as u16),
                text,
            });
        }
    }
    labels
}

/// A joint's kind as a scene file names it.
pub fn kind_name(kind: &JointKind) -> &'static str {
    match kind {
        JointKind::Ball => "ball",
        JointKind::Hinge { .. } => "hinge",
        JointKind::Slider { .. } => "slider",
        JointKind::Fixed => "fixed",
        JointKind::Distance { .. } => "distance",
    }
}

/// One of the selected body's joints, as the inspector lists it.
#[derive(Clone, Debug, PartialEq)]
pub struct JointReport {
    /// "hinge", "slider", … (see [`kind_name`]).
    pub kind: &'static str,
    /// What the other end is: a body's name, or "world".
    pub other: String,
    /// The magnitude of the force on the selected body, N.
    pub force: f32,
    /// The magnitude of the torque on it, N·m, for the kinds that hold one (hinge, fixed, slider).
    pub torque: Option<f32>,
    /// The axial rows on it (N·m for a hinge, N for a slider), for a motor or limits.
    pub axial: Option<f32>,
    /// Whether `axial` is a torque (hinge) rather than a force (slider).
    pub axial_is_torque: bool,
}

/// The joints body `id` takes part in, in the world's order, each with its other end: `None` for
/// the world.
pub fn joints_of(world: &World, id: BodyId) -> impl Iterator<Item = (&Joint, Option<BodyId>)> {
    world.joints().iter().filter_map(move |joint| {
        if joint.desc.b == id {
            Some((joint, joint.desc.a))
        } else if joint.desc.a == Some(id) {
            Some((joint, Some(joint.desc.b)))
        } else {
            None
        }
    })
}

impl JointReport {
    /// `joint` as body `id` feels it, its other end called `other`.
    pub fn of(world: &World, joint: &Joint, id: BodyId, other: String) -> Self {
        let figures = JointFigures::of(world, joint).on(joint, id);
        let torque = match joint.desc.kind {
            JointKind::Hinge { .. } | JointKind::Fixed | JointKind::Slider { .. } => {
                Some(figures.torque.length())
            }
            JointKind::Ball | JointKind::Distance { .. } => None,
        };
        Self {
            kind: kind_name(&joint.desc.kind),
            other,
            force: figures.force.length(),
            torque,
            axial: figures.axial,
            axial_is_torque: matches!(joint.desc.kind, JointKind::Hinge { .. }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Shape;
    use crate::physics::{BodyDesc, JointDesc, Motor};

    /// A 2 kg ball 1 m below a pivot of the world on a joint of `kind` about `axis` there, stepped
    /// for two seconds.
    fn hanging(kind: JointKind, axis: Vec3) -> World {
        let mut world = World::new(Default::default());
        let pivot = Vec3::new(0.0, 3.0, 0.0);
        let bob = world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.2),
            Pose::from_position(pivot - Vec3::Y),
            2.0,
        ));
        let pose = *world.body(bob).pose();
        let anchor_b = if matches!(kind, JointKind::Distance { .. }) {
            pose.position
        } else {
            pivot
        };
        world
            .add_joint(JointDesc::at(
                kind,
                None,
                (bob, pose),
                pivot,
                anchor_b,
                axis,
                false,
            ))
            .unwrap();
        for _ in 0..120 {
            world.step();
        }
        world
    }

    #[test]
    fn a_hanging_ball_is_held_up_by_its_weight_whatever_the_joint() {
        let weight = 2.0 * 9.81;
        let hinge = JointKind::Hinge {
            limits: None,
            motor: Some(Motor {
                speed: 0.0,
                max: 1.0,
            }),
        };
        let rod = JointKind::Distance {
            length: 1.0,
            min: 1.0,
            max: 1.0,
            spring: None,
        };
        // A slider across gravity holds the weight with its line rows; one along it, at its lower
        // limit, with the limit's axial row.
        let slider = JointKind::Slider {
            limits: None,
            motor: None,
        };
        let slider_on_limit = JointKind::Slider {
            limits: Some([0.0, 0.5]),
            motor: None,
        };
        for (kind, axis) in [
            (JointKind::Ball, Vec3::Y),
            (hinge, Vec3::Z),
            (JointKind::Fixed, Vec3::Y),
            (rod, Vec3::Y),
            (slider, Vec3::Z),
            (slider_on_limit, Vec3::Y),
        ] {
            let world = hanging(kind, axis);
            let joint = &world.joints()[0];
            let figures = JointFigures::of(&world, joint);
            // Measured: the weight exactly, for every kind (at rest, each row carries m·g·h).
            assert!(
                (figures.force - weight * Vec3::Y).length() < 0.01,
                "{kind:?}: {figures:?}"
            );
            let report = JointReport::of(&world, joint, BodyId(0), "world".into());
            assert!((report.force - weight).abs() < 0.01, "{report:?}");
            // The arrow at the ball's anchor points up, a log scale long.
            let mut out = Overlay::default();
            joint_marks(&world, &mut out);
            let arrow = out.lines.iter().find(|l| l.head).expect("a force arrow");
            let up = (arrow.to - arrow.from).normalize();
            assert!(up.y > 0.99, "{kind:?}: {arrow:?}");
            let length = (arrow.to - arrow.from).length();
            assert!((length - force_arrow_m(weight)).abs() < 0.01, "{length}");
            let axes = out.lines.iter().filter(|l| !l.head).count();
            let has_axis = matches!(kind, JointKind::Hinge { .. } | JointKind::Slider { .. });
            assert_eq!(axes, usize::from(has_axis), "{kind:?}");
        }
    }

    #[test]
    fn a_hinge_reports_its_torque_and_axial_and_the_other_end_feels_the_opposite() {
        let hinge = JointKind::Hinge {
            limits: None,
            motor: Some(Motor {
                speed: 0.0,
                max: 1.0,
            }),
        };
        let world = hanging(hinge, Vec3::Z);
        let joint = &world.joints()[0];
        let report = JointReport::of(&world, joint, BodyId(0), "world".into());
        assert_eq!(report.kind, "hinge");
        assert!(report.torque.is_some_and(f32::is_finite), "{report:?}");
        assert!(report.axial.is_some() && report.axial_is_torque);
        let b = JointFigures::of(&world, joint);
        let mut flipped = *joint;
        flipped.desc.b = BodyId(7);
        let a = b.on(&flipped, BodyId(0));
        assert_eq!(a.force, -b.force);
        assert_eq!(a.axial, b.axial.map(|x| -x));
    }

    #[test]
    fn a_joint_between_two_frozen_ends_shows_no_force() {
        let mut world = hanging(JointKind::Ball, Vec3::Y);
        world.set_static(BodyId(0), true);
        for _ in 0..10 {
            world.step();
        }
        let joint = &world.joints()[0];
        assert_eq!(world.joint_load(joint).force, Vec3::ZERO);
        assert_eq!(JointFigures::of(&world, joint).force, Vec3::ZERO);
        let mut out = Overlay::default();
        joint_marks(&world, &mut out);
        assert!(out.lines.is_empty(), "{:?}", out.lines);
    }

    #[test]
    fn labels_go_to_the_strongest_joints_where_they_fit_and_never_touch() {
        let mut world = World::new(Default::default());
        // A chain of ten 1 kg balls 0.3 m apart hanging from the world: the top joint holds ten.
        let top = Vec3::new(0.0, 5.0, 0.0);
        let mut above = None;
        for i in 0..10 {
            let pose = Pose::from_position(top - Vec3::Y * (0.3 * i as f32 + 0.15));
            let id = world.add_body(BodyDesc::dynamic(Shape::sphere(0.1), pose, 1.0));
            let anchor = top - Vec3::Y * (0.3 * i as f32);
            let a = above.map(|a: BodyId| (a, *world.body(a).pose()));
            let desc = JointDesc::at(
                JointKind::Ball,
                a,
                (id, pose),
                anchor,
                anchor,
                Vec3::Y,
                false,
            );
            world.add_joint(desc).unwrap();
            above = Some(id);
        }
        for _ in 0..60 {
            world.step();
        }
        // One row per 0.3 m, so every label is a row from the next: only every other one fits.
        let cell_of = |p: Vec3| Some((10, ((5.0 - p.y) / 0.3).round() as i32));
        let labels = force_labels(&world, cell_of, 40, 20);
        let rows: Vec<u16> = labels.iter().map(|l| l.cell.1).collect();
        assert_eq!(rows, [0, 2, 4, 6, 8], "{labels:?}");
        assert_eq!(labels[0].text, force_text(10.0 * 9.81));
        assert_eq!(labels[0].text, "98 N");
        assert_eq!(labels[0].cell.0, 11);
        // Too narrow a view: none.
        assert!(force_labels(&world, cell_of, 14, 20).is_empty());
        assert!(force_labels(&world, |_| None, 40, 20).is_empty());
    }

    #[test]
    fn the_force_scale_is_a_length_per_decade() {
        assert_eq!(force_arrow_m(0.0), 0.0);
        assert!((force_arrow_m(9.0) - FORCE_M_PER_DECADE).abs() < 1e-6);
        assert!((force_arrow_m(99.0) - 2.0 * FORCE_M_PER_DECADE).abs() < 1e-6);
    }
}
