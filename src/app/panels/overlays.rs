//! Debug overlays: which ones exist, their names and keys, and the marks and tints each makes of the
//! world's read-only views (contacts, islands, bodies). The render layer draws the marks
//! ([`crate::render::overlay`]); nothing here writes to the world.
//!
//! Colours are the bright xterm ANSI colours (or a channel off them), so every overlay keeps its
//! colour when quantised to 256 or 16 colours.

use std::fmt;
use std::str::FromStr;

use crate::geometry::Ray;
use glam::Vec3;

use crate::app::panels::joint_view::{self, JOINT_FORCE_COLOR};
use crate::app::panels::look::BodyLook;
use crate::color::Rgb;
use crate::geometry::Shape;
use crate::physics::{NO_ISLAND, World};
use crate::render::{Drawable, Material, Overlay};

/// One debug overlay.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OverlayKind {
    /// Contact points (touching ones; speculative points waiting for a body are left out).
    Contacts,
    /// Contact normals: a line from each point along the normal, longer for a larger normal force.
    Normals,
    /// Friction: an arrow at each manifold's centroid along the friction force on B.
    Friction,
    /// Axis-aligned bounding boxes.
    Aabbs,
    /// Body axes at the centre of mass: x red, y green, z blue.
    Axes,
    /// Velocity arrows: where the centre of mass goes in the next quarter second.
    Velocity,
    /// Dynamic bodies tinted by island.
    Islands,
    /// Awake, sleeping and frozen bodies tinted apart.
    Sleep,
    /// Hinge and slider axes, and each joint's force (see [`crate::app::panels::joint_view`]).
    Joints,
}

impl OverlayKind {
    /// Every overlay, in menu order (key 1 first).
    pub const ALL: [OverlayKind; 9] = [
        OverlayKind::Contacts,
        OverlayKind::Normals,
        OverlayKind::Friction,
        OverlayKind::Aabbs,
        OverlayKind::Axes,
        OverlayKind::Velocity,
        OverlayKind::Islands,
        OverlayKind::Sleep,
        OverlayKind::Joints,
    ];

    /// The name `--overlay` takes.
    pub fn name(self) -> &'static str {
        match self {
            OverlayKind::Contacts => "contacts",
            OverlayKind::Normals => "normals",
            OverlayKind::Friction => "friction",
            OverlayKind::Aabbs => "aabbs",
            OverlayKind::Axes => "axes",
            OverlayKind::Velocity => "velocity",
            OverlayKind::Islands => "islands",
            OverlayKind::Sleep => "sleep",
            OverlayKind::Joints => "joints",
        }
    }

    /// What the menu says it shows.
    pub fn describe(self) -> &'static str {
        match self {
            OverlayKind::Contacts => "contact points",
            OverlayKind::Normals => "normals, length ~ force",
            OverlayKind::Friction => "friction forces",
            OverlayKind::Aabbs => "bounding boxes",
            OverlayKind::Axes => "body axes (x y z: r g b)",
            OverlayKind::Velocity => "velocity arrows",
            OverlayKind::Islands => "tint by island",
            OverlayKind::Sleep => "awake / asleep / frozen",
            OverlayKind::Joints => "joint axes, forces (log)",
        }
    }

    /// The digit that toggles it in the overlay menu, '1' to '9'.
    pub fn key(self) -> char {
        let i = OverlayKind::ALL
            .iter()
            .position(|&k| k == self)
            .unwrap_or(0);
        char::from(b'1' + i as u8)
    }

    /// The overlay a menu digit toggles.
    pub fn from_key(c: char) -> Option<OverlayKind> {
        let i = (c as u32).checked_sub('1' as u32)? as usize;
        OverlayKind::ALL.get(i).copied()
    }

    /// The colour its marks (or, for the tints, its legend) are drawn in.
    ///
    /// At 16 colours a mark shows as one ANSI entry, and it stands out only where the scene is not
    /// shown in that entry too. Lit bodies are mid-tone albedos shaded darker, so they dither into
    /// the dim entries (black, 1–6, grey 8): every built-in scene uses cyan (6) for its blue bodies.
    /// So the marks take the entries no surface reaches: the bright 9–15 and light grey (7). The
    /// bounding boxes were cyan (0, 205, 205), exactly entry 6: drawn over the default scene's blue
    /// box they were lost in its cyan dither dots wherever they crossed one (1.6 % of the marks'
    /// pixels, `tests/term/colour.rs`); they are light grey now, the one entry left.
    pub fn color(self) -> Rgb {
        match self {
            OverlayKind::Contacts => Rgb::new(255, 255, 0),
            OverlayKind::Normals => Rgb::new(255, 0, 255),
            OverlayKind::Friction => Rgb::new(0, 255, 255),
            OverlayKind::Aabbs => Rgb::new(229, 229, 229),
            OverlayKind::Axes => AXIS_COLORS[0],
            OverlayKind::Velocity => Rgb::WHITE,
            OverlayKind::Islands => ISLAND_COLORS[0],
            OverlayKind::Sleep => AWAKE_COLOR,
            OverlayKind::Joints => JOINT_FORCE_COLOR,
        }
    }

    fn bit(self) -> u16 {
        1 << OverlayKind::ALL
            .iter()
            .position(|&k| k == self)
            .unwrap_or(0)
    }
}

/// Body axes x, y, z: bright red, green and blue.
pub const AXIS_COLORS: [Rgb; 3] = [
    Rgb::new(255, 0, 0),
    Rgb::new(0, 255, 0),
    Rgb::new(92, 92, 255),
];
/// Island tints: six hues that stay apart in 16 colours.
pub const ISLAND_COLORS: [Rgb; 6] = [
    Rgb::new(230, 60, 60),
    Rgb::new(60, 200, 60),
    Rgb::new(70, 110, 240),
    Rgb::new(230, 210, 40),
    Rgb::new(210, 70, 210),
    Rgb::new(40, 200, 210),
];
pub const AWAKE_COLOR: Rgb = Rgb::new(70, 220, 70);
pub const ASLEEP_COLOR: Rgb = Rgb::new(80, 90, 150);
pub const FROZEN_COLOR: Rgb = Rgb::new(200, 240, 255);

/// A normal line is `NORMAL_BASE_M + NORMAL_SCALE_M · √(F / 1 N)` long, at most `MAX_MARK_M`: a
/// resting 1 kg box's four points (2.5 N each) get 18 cm, a point under a tall pile (100 N) 60 cm. The
/// square root keeps both on screen. Friction arrows use the same scale without the base.
const NORMAL_BASE_M: f32 = 0.1;
const NORMAL_SCALE_M: f32 = 0.05;
const MAX_MARK_M: f32 = 1.5;
/// Friction forces below this are not drawn, N.
const MIN_FRICTION_N: f32 = 0.01;
/// A velocity arrow shows where the centre of mass goes in this long, s.
const VELOCITY_LOOKAHEAD_S: f32 = 0.25;
/// Slower bodies get no velocity arrow, m/s.
const MIN_SPEED: f32 = 0.01;
/// Axes reach this far past the body's surface along each axis, as a fraction of its half extent.
const AXIS_REACH: f32 = 1.4;

/// A set of overlays; empty by default.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OverlaySet(u16);

impl OverlaySet {
    /// Every overlay on.
    pub const ALL: OverlaySet = OverlaySet((1 << OverlayKind::ALL.len()) - 1);

    pub fn contains(self, kind: OverlayKind) -> bool {
        self.0 & kind.bit() != 0
    }

    pub fn insert(&mut self, kind: OverlayKind) {
        self.0 |= kind.bit();
    }

    /// Turns `kind` on if it was off and off if it was on; returns whether it is on now.
    pub fn toggle(&mut self, kind: OverlayKind) -> bool {
        self.0 ^= kind.bit();
        self.contains(kind)
    }

    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The overlays on, in menu order.
    pub fn iter(self) -> impl Iterator<Item = OverlayKind> {
        OverlayKind::ALL
            .into_iter()
            .filter(move |&k| self.contains(k))
    }

    /// Whether any overlay draws marks (lines or dots) rather than tints.
    fn has_marks(self) -> bool {
        self.iter()
            .any(|k| !matches!(k, OverlayKind::Islands | OverlayKind::Sleep))
    }
}

impl fmt::Display for OverlaySet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.iter().map(OverlayKind::name).collect();
        f.write_str(&names.join(","))
    }
}

/// An overlay name that is not one of [`OverlayKind::ALL`]'s.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownOverlay(pub String);

/// The names `--overlay` accepts, for messages: "contacts, normals, …, sleep (or all)".
pub fn overlay_names() -> String {
    let names: Vec<&str> = OverlayKind::ALL.iter().map(|k| k.name()).collect();
    format!("{} (or all)", names.join(", "))
}

impl fmt::Display for UnknownOverlay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Cut like any quoted value: `--overlay` may be handed a whole file by mistake.
        let name = crate::scene::readable::cut(&self.0, crate::scene::readable::MAX_QUOTED);
        write!(f, "unknown overlay '{name}' (valid: {})", overlay_names())
    }
}

impl std::error::Error for UnknownOverlay {}

impl FromStr for OverlaySet {
    type Err = UnknownOverlay;

    /// A comma-separated list of overlay names (spaces around names allowed, case-insensitive), or
    /// `all`. An empty item (`contacts,,axes`, or an empty list) is an error too: it is a typo.
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let mut set = OverlaySet::default();
        for item in text.split(',') {
            let name = item.trim().to_ascii_lowercase();
            if name == "all" {
                set = OverlaySet::ALL;
                continue;
            }
            let kind = OverlayKind::ALL
                .into_iter()
                .find(|k| k.name() == name)
                .ok_or_else(|| UnknownOverlay(item.trim().to_string()))?;
            set.insert(kind);
        }
        Ok(set)
    }
}

/// Fills `out` with the marks of the overlays in `set` (every line and dot in world space).
pub fn marks(world: &World, set: OverlaySet, out: &mut Overlay) {
    out.clear();
    joint_links(world, out);
    if !set.has_marks() {
        return;
    }
    if set.contains(OverlayKind::Joints) {
        joint_view::joint_marks(world, out);
    }
    if set.contains(OverlayKind::Aabbs) {
        let color = OverlayKind::Aabbs.color();
        for body in world.bodies() {
            let aabb = body.shape().aabb(body.pose());
            out.wire_box(aabb.min, aabb.max, color);
        }
    }
    for body in world.bodies().iter().filter(|b| !b.is_static()) {
        let pose = body.pose();
        if set.contains(OverlayKind::Axes) {
            let half = match *body.shape() {
                Shape::Cuboid { half_extents } => half_extents,
                Shape::Sphere { radius } => Vec3::splat(radius),
            };
            for (axis, color) in AXIS_COLORS.iter().enumerate() {
                let mut local = Vec3::ZERO;
                local[axis] = half[axis] * AXIS_REACH;
                out.line(pose.position, pose.transform_point(local), *color);
            }
        }
        let v = body.linear_velocity();
        if set.contains(OverlayKind::Velocity) && v.length() >= MIN_SPEED {
            let tip = pose.position + v * VELOCITY_LOOKAHEAD_S;
            out.arrow(pose.position, tip, OverlayKind::Velocity.color());
        }
    }
    let (contacts, normals, friction) = (
        set.contains(OverlayKind::Contacts),
        set.contains(OverlayKind::Normals),
        set.contains(OverlayKind::Friction),
    );
    if contacts || normals || friction {
        for c in world.contacts() {
            for p in c.points().iter().filter(|p| p.touching()) {
                if normals {
                    let length = (NORMAL_BASE_M + NORMAL_SCALE_M * p.normal_force.max(0.0).sqrt())
                        .min(MAX_MARK_M);
                    out.line(
                        p.point,
                        p.point + c.normal * length,
                        OverlayKind::Normals.color(),
                    );
                }
                if contacts {
                    out.dot(p.point, OverlayKind::Contacts.color());
                }
            }
            let force = c.friction_force.length();
            if friction && force >= MIN_FRICTION_N && c.touching() {
                let length = (NORMAL_SCALE_M * force.sqrt()).min(MAX_MARK_M);
                let from = c.centroid();
                out.arrow(
                    from,
                    from + c.friction_force / force * length,
                    OverlayKind::Friction.color(),
                );
            }
        }
    }
}

/// Recolours the drawables of dynamic and frozen bodies for the tinting overlays in `set`: by island,
/// and (over that) awake, asleep and frozen apart. Scenery keeps its look. Tinted bodies are drawn
/// plain, so the colour is not lost in wood grain. `labels` is scratch for the island labels.
pub fn tint(
    world: &World,
    looks: &[BodyLook],
    set: OverlaySet,
    labels: &mut Vec<u32>,
    drawables: &mut [Drawable],
) {
    let (islands, sleep) = (
        set.contains(OverlayKind::Islands),
        set.contains(OverlayKind::Sleep),
    );
    if !islands && !sleep {
        return;
    }
    if islands {
        world.island_labels(labels);
    }
    for (i, (d, body)) in drawables.iter_mut().zip(world.bodies()).enumerate() {
        let scenery = looks.get(i).is_some_and(|l| l.scenery);
        if scenery {
            continue;
        }
        let mut color = None;
        if islands && let Some(&label) = labels.get(i).filter(|&&l| l != NO_ISLAND) {
            color = Some(ISLAND_COLORS[label as usize % ISLAND_COLORS.len()]);
        }
        if sleep {
            if body.is_static() {
                color = Some(FROZEN_COLOR);
            } else if body.is_sleeping() {
                color = Some(ASLEEP_COLOR);
            } else if !islands {
                color = Some(AWAKE_COLOR);
            }
        }
        if let Some(color) = color {
            d.color = color;
            d.material = Material::Plain;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_parse_in_any_order_and_case_and_all_means_every_overlay() {
        let set: OverlaySet = "Axes, contacts".parse().unwrap();
        assert!(set.contains(OverlayKind::Axes) && set.contains(OverlayKind::Contacts));
        assert_eq!(set.iter().count(), 2);
        assert_eq!(set.to_string(), "contacts,axes");
        assert_eq!("all".parse::<OverlaySet>(), Ok(OverlaySet::ALL));
        for kind in OverlayKind::ALL {
            let one: OverlaySet = kind.name().parse().unwrap();
            assert_eq!(one.iter().collect::<Vec<_>>(), vec![kind]);
            assert_eq!(OverlayKind::from_key(kind.key()), Some(kind));
        }
    }

    #[test]
    fn an_unknown_or_empty_name_is_an_error_that_lists_the_valid_ones() {
        let err = "contacts,bogus".parse::<OverlaySet>().unwrap_err();
        assert_eq!(err, UnknownOverlay("bogus".into()));
        let message = err.to_string();
        for kind in OverlayKind::ALL {
            assert!(message.contains(kind.name()), "{message}");
        }
        assert!("contacts,,axes".parse::<OverlaySet>().is_err());
        assert!("".parse::<OverlaySet>().is_err());
    }

    #[test]
    fn menu_keys_are_one_to_nine() {
        let keys: String = OverlayKind::ALL.iter().map(|k| k.key()).collect();
        assert_eq!(keys, "123456789");
        assert_eq!(OverlayKind::from_key('0'), None);
    }

    #[test]
    fn toggling_twice_leaves_the_set_as_it_was() {
        let mut set = OverlaySet::default();
        assert!(set.toggle(OverlayKind::Sleep));
        assert!(!set.toggle(OverlayKind::Sleep));
        assert!(set.is_empty());
    }
}

/// Colour of a joint's links and anchors: the light grey no surface takes, at every colour depth.
pub const JOINT_COLOR: Rgb = Rgb::new(229, 229, 229);

/// Every joint, drawn whatever the overlays: a line from each body's surface to its anchor (the
/// rod of a pendulum whose bob hangs from a pivot; none where the anchor is on or in the body, as
/// for the links of a chain), the line between two anchors apart (a distance joint's rod, rope
/// or spring), and a dot at each anchor.
pub fn joint_links(world: &World, out: &mut Overlay) {
    for joint in world.joints() {
        let (pa, pb) = world.joint_anchors(joint);
        for (end, anchor) in [(joint.desc.a, pa), (Some(joint.desc.b), pb)] {
            let Some(id) = end else { continue };
            let body = world.body(id);
            let centre = body.pose().position;
            // From the anchor towards the centre, the body's surface is where the link leaves it.
            let surface = Ray::new(anchor, centre - anchor)
                .and_then(|ray| ray.cast(body.shape(), body.pose(), 0.0, anchor.distance(centre)))
                .filter(|hit| hit.t > 1e-3);
            if let Some(hit) = surface {
                out.line(hit.point, anchor, JOINT_COLOR);
            }
            out.spaced_dot(anchor, JOINT_COLOR);
        }
        if pa.distance(pb) > 1e-3 {
            out.line(pa, pb, JOINT_COLOR);
        }
    }
}

#[cfg(test)]
mod joint_link_tests {
    use super::*;
    use crate::geometry::{Pose, Shape};
    use crate::physics::{BodyDesc, BodyId, JointDesc, JointKind};

    /// A bob hung 1 m below a pivot of the world: its rod runs from the top of the ball to the
    /// pivot, with a dot there and one at the ball's end; a chain link's anchor on its surface gets
    /// no rod.
    #[test]
    fn a_pendulum_is_drawn_as_a_rod_from_its_ball_to_its_pivot() {
        let mut world = World::new(Default::default());
        let pivot = Vec3::new(0.0, 3.0, 0.0);
        let bob = world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.2),
            Pose::from_position(pivot - Vec3::Y),
            1.0,
        ));
        let pose = *world.body(bob).pose();
        let link = world.add_body(BodyDesc::dynamic(
            Shape::sphere(0.2),
            Pose::from_position(pivot - 1.4 * Vec3::Y),
            1.0,
        ));
        let link_pose = *world.body(link).pose();
        let hinge = JointKind::Hinge {
            limits: None,
            motor: None,
        };
        world
            .add_joint(JointDesc::at(
                hinge,
                None,
                (bob, pose),
                pivot,
                pivot,
                Vec3::Z,
                false,
            ))
            .unwrap();
        let touch = pivot - 1.2 * Vec3::Y;
        world
            .add_joint(JointDesc::at(
                JointKind::Ball,
                Some((bob, pose)),
                (BodyId(link.0), link_pose),
                touch,
                touch,
                Vec3::Y,
                false,
            ))
            .unwrap();
        let mut out = Overlay::default();
        marks(&world, OverlaySet::default(), &mut out);
        assert_eq!(out.lines.len(), 1, "{:?}", out.lines);
        let rod = out.lines[0];
        assert!(rod.from.distance(pivot - 0.8 * Vec3::Y) < 1e-4, "{:?}", rod);
        assert_eq!(rod.to, pivot);
        assert_eq!(rod.color, JOINT_COLOR);
        assert_eq!(out.dots.len(), 3);
    }
}
