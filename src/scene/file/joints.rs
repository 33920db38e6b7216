//! `[[joint]]` tables, checked: the bodies they name, the keys their kind has, and the numbers
//! that make a joint (`physics::JointDesc::check`), each error located at its value.

use glam::{Quat, Vec3};
use toml::Spanned;

use super::{Checked, Source};
use crate::physics::{BodyId, JointDesc, JointKind, Motor, Spring};
use crate::scene::SceneBody;
use crate::scene::schema::{self, BodyRef};
use crate::scene::vector::{Float, Floats};

/// What a joint's ends are resolved against: a scene's bodies and their names, or (a recording's
/// `add_joint`, written exact) only how many bodies the world has.
pub(crate) enum Ends<'a> {
    Scene {
        bodies: &'a [SceneBody],
        names: &'a [(String, usize)],
    },
    Count(usize),
}

impl Ends<'_> {
    fn count(&self) -> usize {
        match self {
            Ends::Scene { bodies, .. } => bodies.len(),
            Ends::Count(n) => *n,
        }
    }
}

impl Source<'_> {
    /// The joint a table describes, in its bodies' frames.
    pub(crate) fn joint(&self, raw: &schema::Joint, ends: &Ends) -> Checked<JointDesc> {
        let kind_name = raw.kind.get_ref().as_str();
        let kinds = ["ball", "hinge", "slider", "fixed", "distance"];
        if !kinds.contains(&kind_name) {
            return Err(self.error(
                raw.kind.span(),
                format!(
                    "unknown joint kind {kind_name:?} (ball, hinge, slider, fixed or distance)"
                ),
            ));
        }
        let (distance, hinge, slider) = (
            kind_name == "distance",
            kind_name == "hinge",
            kind_name == "slider",
        );
        // Keys the kind has not.
        let refuse = |given: bool, span: Option<std::ops::Range<usize>>, key: &str| {
            if given {
                Err(self.error(
                    span.unwrap_or(raw.kind.span()),
                    format!("a {kind_name} joint has no {key}"),
                ))
            } else {
                Ok(())
            }
        };
        let span_of = |v: &Option<Spanned<Float>>| v.as_ref().map(Spanned::span);
        refuse(
            !(hinge || slider) && raw.limits.is_some(),
            raw.limits.as_ref().map(Spanned::span),
            "limits",
        )?;
        refuse(
            !hinge && raw.limits_rad.is_some(),
            raw.limits_rad.as_ref().map(Spanned::span),
            "limits_rad",
        )?;
        for (value, key) in [
            (&raw.motor_speed, "motor_speed"),
            (&raw.motor_max, "motor_max"),
        ] {
            refuse(!(hinge || slider) && value.is_some(), span_of(value), key)?;
        }
        for (value, key) in [
            (&raw.length, "length"),
            (&raw.min_length, "min_length"),
            (&raw.max_length, "max_length"),
            (&raw.stiffness_hz, "stiffness_hz"),
            (&raw.damping_ratio, "damping_ratio"),
        ] {
            refuse(!distance && value.is_some(), span_of(value), key)?;
        }
        refuse(
            !(hinge || slider || kind_name == "ball") && raw.friction.is_some(),
            span_of(&raw.friction),
            "friction",
        )?;
        refuse(
            !(hinge || slider) && raw.axis.is_some(),
            raw.axis.as_ref().map(Spanned::span),
            "axis",
        )?;

        let a = match &raw.a {
            None => None,
            Some(a) => self.end(a, ends)?,
        };
        let b = self.end(&raw.b, ends)?.ok_or_else(|| {
            self.error(raw.b.span(), "b must be a body (only a may be the world)")
        })?;
        if a == Some(b) {
            return Err(self.error(raw.b.span(), "a joint needs two different bodies"));
        }

        let exact = raw.local_anchor_b.is_some();
        let mut desc = if exact {
            self.exact_frames(raw, a, b)?
        } else {
            self.world_frames(raw, a, b, ends, distance)?
        };

        let motor = match (&raw.motor_speed, &raw.motor_max) {
            (Some(speed), Some(max)) => Some(Motor {
                speed: self.finite("motor_speed", speed)?,
                max: self.non_negative(max, "motor_max")?,
            }),
            (None, None) => None,
            (Some(v), None) | (None, Some(v)) => {
                return Err(self.error(v.span(), "a motor needs both motor_speed and motor_max"));
            }
        };
        let limits = match (&raw.limits, &raw.limits_rad) {
            (Some(_), Some(l)) => {
                return Err(self.error(l.span(), "give limits or limits_rad, not both"));
            }
            (Some(l), None) => Some((l, if hinge { 1f32.to_radians() } else { 1.0 })),
            (None, Some(l)) => Some((l, 1.0)),
            (None, None) => None,
        };
        let limits = match limits {
            None => None,
            Some((l, scale)) => {
                let [lo, hi] = l.get_ref().0;
                if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                    return Err(self.error(
                        l.span(),
                        format!("limits must be finite, lower first: got [{lo}, {hi}]"),
                    ));
                }
                Some([lo * scale, hi * scale])
            }
        };
        desc.kind = match kind_name {
            "ball" => JointKind::Ball,
            "fixed" => JointKind::Fixed,
            "hinge" => JointKind::Hinge { limits, motor },
            "slider" => JointKind::Slider { limits, motor },
            _ => self.distance(raw, &desc, ends)?,
        };
        desc.collide = raw.collide.unwrap_or(false);
        if let Some(friction) = &raw.friction {
            desc.friction = self.non_negative(friction, "friction")?;
        }
        desc.check()
            .map_err(|e| self.error(raw.kind.span(), e.to_string()))?;
        Ok(desc)
    }

    /// A body named by index or name, or the world (`None`).
    fn end(&self, end: &Spanned<BodyRef>, ends: &Ends) -> Checked<Option<BodyId>> {
        let count = ends.count();
        match end.get_ref() {
            BodyRef::Index(i) if (*i as usize) < count => Ok(Some(BodyId(*i))),
            BodyRef::Index(i) => Err(self.error(
                end.span(),
                format!(
                    "there is no body {i} (the bodies are 0 to {})",
                    count.saturating_sub(1)
                ),
            )),
            BodyRef::Name(name) if name == "world" => Ok(None),
            BodyRef::Name(name) => match ends {
                Ends::Scene { names, .. } => names
                    .iter()
                    .find(|(n, _)| n == name)
                    .map(|&(_, i)| Some(BodyId(i as u32)))
                    .ok_or_else(|| self.error(end.span(), format!("no body is named {name:?}"))),
                Ends::Count(_) => {
                    Err(self.error(end.span(), "a recorded joint names its bodies by index"))
                }
            },
        }
    }

    /// The exact form: frames as written.
    fn exact_frames(
        &self,
        raw: &schema::Joint,
        a: Option<BodyId>,
        b: BodyId,
    ) -> Checked<JointDesc> {
        let need = |v: &Option<Spanned<Floats<3>>>, key: &str| -> Checked<Vec3> {
            match v {
                Some(v) => self.finite_vec(key, v),
                None => Err(self.error(
                    raw.kind.span(),
                    format!("a joint written exact (local_anchor_b) needs {key} too"),
                )),
            }
        };
        for (given, key) in [
            (&raw.anchor, "anchor"),
            (&raw.anchor_a, "anchor_a"),
            (&raw.anchor_b, "anchor_b"),
            (&raw.axis, "axis"),
        ] {
            if let Some(v) = given {
                return Err(self.error(
                    v.span(),
                    format!(
                        "{key} is the world form; this joint is written exact (local_anchor_b)"
                    ),
                ));
            }
        }
        let reference = match &raw.reference {
            Some(q) => Quat::from_array(q.get_ref().0),
            None => {
                return Err(
                    self.error(raw.kind.span(), "a joint written exact needs reference too")
                );
            }
        };
        Ok(JointDesc {
            kind: JointKind::Ball,
            a,
            b,
            local_anchor_a: need(&raw.local_anchor_a, "local_anchor_a")?,
            local_anchor_b: need(&raw.local_anchor_b, "local_anchor_b")?,
            local_axis_a: need(&raw.local_axis_a, "local_axis_a")?,
            local_axis_b: need(&raw.local_axis_b, "local_axis_b")?,
            reference,
            collide: false,
            friction: 0.0,
        })
    }

    /// The world form: anchors and axis in world coordinates, in the bodies' poses as the scene
    /// places them.
    fn world_frames(
        &self,
        raw: &schema::Joint,
        a: Option<BodyId>,
        b: BodyId,
        ends: &Ends,
        distance: bool,
    ) -> Checked<JointDesc> {
        let Ends::Scene { bodies, .. } = ends else {
            return Err(self.error(
                raw.kind.span(),
                "a recorded joint is written exact (local_anchor_a, local_anchor_b, ...)",
            ));
        };
        for (v, key) in [
            (&raw.local_anchor_a, "local_anchor_a"),
            (&raw.local_axis_a, "local_axis_a"),
            (&raw.local_axis_b, "local_axis_b"),
        ] {
            if let Some(v) = v {
                return Err(self.error(
                    v.span(),
                    format!("{key} goes with local_anchor_b (the exact form)"),
                ));
            }
        }
        let (anchor_a, anchor_b) = if distance {
            if let Some(v) = &raw.anchor {
                return Err(self.error(v.span(), "a distance joint gives anchor_a and anchor_b"));
            }
            match (&raw.anchor_a, &raw.anchor_b) {
                (Some(pa), Some(pb)) => (
                    self.finite_vec("anchor_a", pa)?,
                    self.finite_vec("anchor_b", pb)?,
                ),
                _ => {
                    return Err(self.error(
                        raw.kind.span(),
                        "a distance joint needs anchor_a and anchor_b",
                    ));
                }
            }
        } else {
            if let Some(v) = raw.anchor_a.as_ref().or(raw.anchor_b.as_ref()) {
                return Err(self.error(
                    v.span(),
                    format!("a {} joint gives one anchor", raw.kind.get_ref()),
                ));
            }
            let Some(anchor) = &raw.anchor else {
                return Err(self.error(
                    raw.kind.span(),
                    format!("a {} joint needs an anchor", raw.kind.get_ref()),
                ));
            };
            let p = self.finite_vec("anchor", anchor)?;
            (p, p)
        };
        let axis = match &raw.axis {
            Some(axis) => {
                let v = self.finite_vec("axis", axis)?;
                if v.length_squared() == 0.0 {
                    return Err(self.error(axis.span(), "axis must not be zero"));
                }
                v
            }
            None if matches!(raw.kind.get_ref().as_str(), "hinge" | "slider") => {
                return Err(self.error(
                    raw.kind.span(),
                    format!("a {} joint needs an axis", raw.kind.get_ref()),
                ));
            }
            None => Vec3::Y,
        };
        let pose = |id: BodyId| bodies[id.index()].desc.pose;
        if a.is_none_or(|a| bodies[a.index()].desc.is_static && !bodies[a.index()].frozen)
            && bodies[b.index()].desc.is_static
            && !bodies[b.index()].frozen
        {
            return Err(self.error(
                raw.b.span(),
                "a joint needs a moving body at one end at least",
            ));
        }
        Ok(JointDesc::at(
            JointKind::Ball,
            a.map(|a| (a, pose(a))),
            (b, pose(b)),
            anchor_a,
            anchor_b,
            axis,
            false,
        ))
    }

    /// A distance joint's kind from its keys (the anchors' distance is the default length).
    fn distance(&self, raw: &schema::Joint, desc: &JointDesc, ends: &Ends) -> Checked<JointKind> {
        let gap = match ends {
            Ends::Scene { bodies, .. } => {
                let point = |id: Option<BodyId>, local: Vec3| match id {
                    None => local,
                    Some(id) => {
                        let p = bodies[id.index()].desc.pose;
                        p.position + p.rotation * local
                    }
                };
                point(desc.a, desc.local_anchor_a)
                    .distance(point(Some(desc.b), desc.local_anchor_b))
            }
            Ends::Count(_) => 0.0,
        };
        let length = match &raw.length {
            Some(l) => self.non_negative(l, "length")?,
            None if raw.local_anchor_b.is_some() => {
                return Err(self.error(
                    raw.kind.span(),
                    "a distance joint written exact needs its length",
                ));
            }
            None => gap,
        };
        let min = match &raw.min_length {
            Some(l) => self.non_negative(l, "min_length")?,
            None if raw.max_length.is_some() && raw.length.is_none() => 0.0,
            None => length,
        };
        let max = match &raw.max_length {
            Some(l) => self.non_negative(l, "max_length")?,
            None => length,
        };
        if min > max {
            let span = raw
                .max_length
                .as_ref()
                .or(raw.min_length.as_ref())
                .map_or(raw.kind.span(), Spanned::span);
            return Err(self.error(span, format!("min_length {min} is above max_length {max}")));
        }
        let spring = match (&raw.stiffness_hz, &raw.damping_ratio) {
            (Some(hz), ratio) => Some(Spring {
                hertz: self.non_negative(hz, "stiffness_hz")?,
                damping_ratio: match ratio {
                    Some(r) => self.non_negative(r, "damping_ratio")?,
                    None => 0.0,
                },
            }),
            (None, None) => None,
            (None, Some(r)) => {
                return Err(self.error(r.span(), "damping_ratio goes with stiffness_hz"));
            }
        };
        Ok(JointKind::Distance {
            length,
            min,
            max,
            spring,
        })
    }
}
