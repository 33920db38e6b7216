//! Joints in files: a [`JointDesc`] as the schema's `add_joint` table (exact, in the bodies'
//! frames) and back, checked. Recordings carry the joints a session adds this way, bit for bit.

use glam::{Quat, Vec3};

use crate::physics::{BodyId, JointDesc, JointKind, Motor, Spring};
use crate::scene::schema;
use crate::scene::vector::Floats;

/// The table of `desc`, exact.
pub fn exact(desc: &JointDesc) -> schema::Joint {
    let v = |v: Vec3| Floats(v.to_array());
    let mut table = schema::Joint {
        kind: String::new(),
        a: desc.a.map(|a| a.0),
        b: desc.b.0,
        local_anchor_a: v(desc.local_anchor_a),
        local_anchor_b: v(desc.local_anchor_b),
        local_axis_a: v(desc.local_axis_a),
        local_axis_b: v(desc.local_axis_b),
        reference: Floats(desc.reference.to_array()),
        limits: None,
        motor_speed: None,
        motor_max: None,
        length: None,
        min_length: None,
        max_length: None,
        stiffness_hz: None,
        damping_ratio: None,
        collide: desc.collide,
    };
    let motorised = |limits: Option<[f32; 2]>, motor: Option<Motor>, t: &mut schema::Joint| {
        t.limits = limits.map(Floats);
        t.motor_speed = motor.map(|m| m.speed);
        t.motor_max = motor.map(|m| m.max);
    };
    table.kind = match desc.kind {
        JointKind::Ball => "ball",
        JointKind::Fixed => "fixed",
        JointKind::Hinge { limits, motor } => {
            motorised(limits, motor, &mut table);
            "hinge"
        }
        JointKind::Slider { limits, motor } => {
            motorised(limits, motor, &mut table);
            "slider"
        }
        JointKind::Distance {
            length,
            min,
            max,
            spring,
        } => {
            table.length = Some(length);
            table.min_length = Some(min);
            table.max_length = Some(max);
            table.stiffness_hz = spring.map(|s| s.hertz);
            table.damping_ratio = spring.map(|s| s.damping_ratio);
            "distance"
        }
    }
    .to_owned();
    table
}

/// The joint a table describes; the world checks the rest when it is added.
pub fn desc_of(t: &schema::Joint) -> Result<JointDesc, String> {
    let motor = match (t.motor_speed, t.motor_max) {
        (Some(speed), Some(max)) => Some(Motor { speed, max }),
        (None, None) => None,
        _ => return Err("a motor needs both motor_speed and motor_max".into()),
    };
    let limits = t.limits.map(|l| l.0);
    let only = |allowed: bool, key: &str| {
        if allowed {
            Ok(())
        } else {
            Err(format!("a {} joint has no {key}", t.kind))
        }
    };
    let distance = t.kind == "distance";
    let motorised = t.kind == "hinge" || t.kind == "slider";
    only(motorised || limits.is_none(), "limits")?;
    only(motorised || motor.is_none(), "motor")?;
    for (given, key) in [
        (t.length.is_some(), "length"),
        (t.min_length.is_some(), "min_length"),
        (t.max_length.is_some(), "max_length"),
        (t.stiffness_hz.is_some(), "stiffness_hz"),
        (t.damping_ratio.is_some(), "damping_ratio"),
    ] {
        only(distance || !given, key)?;
    }
    let kind = match t.kind.as_str() {
        "ball" => JointKind::Ball,
        "fixed" => JointKind::Fixed,
        "hinge" => JointKind::Hinge { limits, motor },
        "slider" => JointKind::Slider { limits, motor },
        "distance" => {
            let length = t.length.ok_or("a distance joint needs a length")?;
            let spring = match (t.stiffness_hz, t.damping_ratio) {
                (Some(hertz), damping_ratio) => Some(Spring {
                    hertz,
                    damping_ratio: damping_ratio.unwrap_or(0.0),
                }),
                (None, None) => None,
                (None, Some(_)) => return Err("damping_ratio goes with stiffness_hz".into()),
            };
            JointKind::Distance {
                length,
                min: t.min_length.unwrap_or(length),
                max: t.max_length.unwrap_or(length),
                spring,
            }
        }
        other => {
            return Err(format!(
                "unknown joint kind {other:?} (ball, hinge, slider, fixed or distance)"
            ));
        }
    };
    let v = |f: Floats<3>| Vec3::from_array(f.0);
    let desc = JointDesc {
        kind,
        a: t.a.map(BodyId),
        b: BodyId(t.b),
        local_anchor_a: v(t.local_anchor_a),
        local_anchor_b: v(t.local_anchor_b),
        local_axis_a: v(t.local_axis_a),
        local_axis_b: v(t.local_axis_b),
        reference: Quat::from_array(t.reference.0),
        collide: t.collide,
    };
    desc.check().map_err(|e| e.to_string())?;
    Ok(desc)
}
