//! A world's state, copied out and put back: what rewind keeps and restores.
//!
//! The state that decides every later step is the settings, the bodies (pose, velocities, mass,
//! material, static and sleep flags, sleep timers and island links, pending forces), the points held for
//! the next step and what the holds pulled over the last one (the preload takes a body held again to
//! pull as it did), the persistent
//! contacts (manifolds, warm-start impulses, the poses they were computed at) and the step count.
//! The per-step scratch buffers are a cache (the broad phase's output depends on its input alone,
//! the contact graph's order on the graph alone), so they are not kept: a restored world starts
//! with empty ones and steps bit for bit as the original did (tested below).

use crate::physics::BodyId;
use crate::physics::body::Body;
use crate::physics::narrow::contact::Contact;
use crate::physics::prepare::preload::reuse::SeenAt;
use crate::physics::solve::point_drive::PointHold;
use crate::physics::{Joint, Settings, World};
use glam::Vec3;

/// Everything a world's future depends on, at one step.
#[derive(Clone, Debug)]
pub struct WorldSnapshot {
    settings: Settings,
    bodies: Vec<Body>,
    contacts: Vec<Contact>,
    statics_seen: Vec<Option<SeenAt>>,
    joints: Vec<Joint>,
    holds: Vec<PointHold>,
    hold_impulses: Vec<(BodyId, Vec3)>,
    max_penetration: f32,
    active_contacts: usize,
    steps: u64,
}

impl WorldSnapshot {
    /// The world's step count when it was taken.
    pub fn step(&self) -> u64 {
        self.steps
    }

    /// The first difference from `other`, bit for bit (every float compared by its shortest
    /// round-trip text, which tells apart every value but NaN payloads), or `None` when identical:
    /// for tests of exact restores and re-simulation.
    pub fn first_difference(&self, other: &WorldSnapshot) -> Option<String> {
        let text = |x: &dyn std::fmt::Debug| format!("{x:?}");
        if self.steps != other.steps {
            return Some(format!("step {} vs {}", self.steps, other.steps));
        }
        if text(&self.settings) != text(&other.settings) {
            return Some("settings".into());
        }
        if self.bodies.len() != other.bodies.len() {
            return Some(format!(
                "{} vs {} bodies",
                self.bodies.len(),
                other.bodies.len()
            ));
        }
        for (i, (a, b)) in self.bodies.iter().zip(&other.bodies).enumerate() {
            if text(a) != text(b) {
                return Some(format!("body {i}: {a:?} vs {b:?}"));
            }
        }
        if self.contacts.len() != other.contacts.len() {
            return Some(format!(
                "{} vs {} contacts",
                self.contacts.len(),
                other.contacts.len()
            ));
        }
        for (i, (a, b)) in self.contacts.iter().zip(&other.contacts).enumerate() {
            if text(a) != text(b) {
                return Some(format!("contact {i} ({}, {}): {a:?} vs {b:?}", a.a, a.b));
            }
        }
        if text(&self.statics_seen) != text(&other.statics_seen) {
            return Some("where the statics saw the bodies".into());
        }
        if text(&self.joints) != text(&other.joints) {
            return Some("joints".into());
        }
        if text(&self.holds) != text(&other.holds) {
            return Some("held points".into());
        }
        if text(&self.hold_impulses) != text(&other.hold_impulses) {
            return Some("the holds' last pulls".into());
        }
        let tail = |s: &WorldSnapshot| (s.max_penetration.to_bits(), s.active_contacts);
        (tail(self) != tail(other)).then(|| "penetration or contact count".into())
    }

    /// Bytes it holds: its own size plus its bodies and contacts.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.bodies.len() * std::mem::size_of::<Body>()
            + self.contacts.len() * std::mem::size_of::<Contact>()
            + self.statics_seen.len() * std::mem::size_of::<Option<SeenAt>>()
            + self.joints.len() * std::mem::size_of::<Joint>()
    }
}

impl World {
    /// A copy of the state that matters (see the module docs), sized to fit.
    pub fn snapshot(&self) -> WorldSnapshot {
        WorldSnapshot {
            settings: self.settings.clone(),
            bodies: self.bodies.clone(),
            contacts: self.contacts.clone(),
            statics_seen: self.statics_seen.clone(),
            joints: self.joints.clone(),
            holds: self.holds.clone(),
            hold_impulses: self.scratch.holds.impulses.clone(),
            max_penetration: self.max_penetration,
            active_contacts: self.active_contacts,
            steps: self.steps,
        }
    }

    /// Puts the world back as it was when `snapshot` was taken. Journaling goes on as before;
    /// restoring is not an input (the caller decides what the timeline is).
    pub fn restore(&mut self, snapshot: &WorldSnapshot) {
        self.settings.clone_from(&snapshot.settings);
        self.bodies.clone_from(&snapshot.bodies);
        self.contacts.clone_from(&snapshot.contacts);
        self.statics_seen.clone_from(&snapshot.statics_seen);
        self.joints.clone_from(&snapshot.joints);
        self.holds.clone_from(&snapshot.holds);
        self.max_penetration = snapshot.max_penetration;
        self.active_contacts = snapshot.active_contacts;
        self.steps = snapshot.steps;
        self.settings_touched = false;
        self.scratch = Default::default();
        self.scratch
            .holds
            .impulses
            .clone_from(&snapshot.hold_impulses);
    }
}
