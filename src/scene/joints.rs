//! A [`JointDesc`] as the schema's joint table, exact (in the bodies' frames, hinge limits in
//! radians, bodies by index): how saved worlds and recordings write a joint, so it reads back bit
//! for bit. Reading, in both forms, is `scene::file`'s (`Source::joint`).

use glam::Vec3;

use crate::physics::{JointDesc, JointKind, Motor};
use crate::scene::schema::{self, BodyRef, unplaced};
use crate::scene::vector::{Float, Floats};

/// The table of `desc`, exact.
pub fn exact(desc: &JointDesc) -> schema::Joint {
    let v = |v: Vec3| Some(unplaced(Floats(v.to_array())));
    let f = |x: f32| Some(unplaced(Float(x)));
    let mut table = schema::Joint {
        kind: unplaced(String::new()),
        a: desc.a.map(|a| unplaced(BodyRef::Index(a.0))),
        b: unplaced(BodyRef::Index(desc.b.0)),
        anchor: None,
        anchor_a: None,
        anchor_b: None,
        axis: None,
        local_anchor_a: v(desc.local_anchor_a),
        local_anchor_b: v(desc.local_anchor_b),
        local_axis_a: v(desc.local_axis_a),
        local_axis_b: v(desc.local_axis_b),
        reference: Some(unplaced(Floats(desc.reference.to_array()))),
        limits: None,
        limits_rad: None,
        motor_speed: None,
        motor_max: None,
        length: None,
        min_length: None,
        max_length: None,
        stiffness_hz: None,
        damping_ratio: None,
        collide: desc.collide.then_some(true),
        friction: (desc.friction != 0.0).then(|| unplaced(Float(desc.friction))),
    };
    let motor = |m: Option<Motor>, t: &mut schema::Joint| {
        t.motor_speed = m.and_then(|m| f(m.speed));
        t.motor_max = m.and_then(|m| f(m.max));
    };
    let kind = match desc.kind {
        JointKind::Ball => "ball",
        JointKind::Fixed => "fixed",
        JointKind::Hinge { limits, motor: m } => {
            table.limits_rad = limits.map(|l| unplaced(Floats(l)));
            motor(m, &mut table);
            "hinge"
        }
        JointKind::Slider { limits, motor: m } => {
            table.limits = limits.map(|l| unplaced(Floats(l)));
            motor(m, &mut table);
            "slider"
        }
        JointKind::Distance {
            length,
            min,
            max,
            spring,
        } => {
            (table.length, table.min_length, table.max_length) = (f(length), f(min), f(max));
            table.stiffness_hz = spring.and_then(|s| f(s.hertz));
            table.damping_ratio = spring.and_then(|s| f(s.damping_ratio));
            "distance"
        }
    };
    table.kind = unplaced(kind.to_owned());
    table
}
