//! Spawning with `b` and `s`: a new body is dropped into free space, never inside another.
//!
//! Where: around the point under the pointer, or, with no body under it, around the camera's target.
//! Candidate spots lie on a square grid around that centre, half a body width (plus a gap) apart. At
//! each, the new body would rest just above the highest top of every body whose bounds overlap its
//! footprint column (above whatever is there, including anything falling into it), so its bounds
//! overlap nothing. A spot counts only if
//! - it is over the ground (inside the x–z extent of a static body, half a body width in from its
//!   edge), and the pile there stays under [`MAX_PILE_LAYERS`];
//! - nothing in its column is still moving ([`SETTLED_SPEED`]): a body dropped onto one still
//!   falling lands as hard as if dropped from its height and is thrown aside;
//! - what it lands on is level: the ground, or a box lying on a face with the spot's centre over
//!   that face. Nothing is dropped onto a ball or a tipped box, and a ball only onto the ground: on
//!   a pile the least knock rolls it off the floor.
//!
//! Of those, the spot with the lowest `height + PILE_SLOPE × distance from the centre` wins: a layer
//! spreads around the centre before the next one starts, a low heap that stays on a small floor (the
//! default scene's is 8 m × 5 m) instead of a tower that topples off it. When no spot is left the
//! spawn is refused and the status bar says so.
//!
//! The body is added through the World API between steps (key handlers run between steps), so the
//! world's journal records it and a recording or a rewind replays it.

use glam::{Vec2, Vec3, Vec3Swizzles};

use crate::app::App;
use crate::color::PALETTE;
use crate::geometry::{Aabb, Pose, Shape};
use crate::physics::{BodyDesc, World};
use crate::scene::builtin::BALL_ROLLING_RESISTANCE;

/// Gap left between a new body and what it is dropped onto or beside, m.
pub const SPAWN_GAP: f32 = 0.05;
/// Metres of height a spot one metre further from the centre is worth: under 1, a layer around the
/// centre fills before the pile rises.
pub const PILE_SLOPE: f32 = 0.5;
/// Candidate spots on each side of the centre (a (2n+1)² grid).
pub const SEARCH_RINGS: i32 = 16;
/// Space kept between a spot and the edge of the ground, in half body widths: a body pushed aside
/// by the pile does not go over the edge at once.
pub const EDGE_MARGIN: f32 = 1.0;
/// A column with a body faster than this (m/s) in it is busy: a body dropped onto something still
/// falling or sliding lands hard on it when it stops (a column of bodies falling together lands as
/// hard as one dropped from its height) and is thrown aside, so busy spots are skipped.
pub const SETTLED_SPEED: f32 = 0.3;
/// The same for turning, rad/s: a box still tipping over is no floor to drop onto.
pub const SETTLED_SPIN: f32 = 0.5;
/// How far from level a box's face may be for another body to be dropped on it, degrees.
pub const LEVEL_DEG: f32 = 10.0;
/// Most bodies' heights a pile may reach above the ground before the new body (so three layers):
/// higher, a heap of boxes on the default scene's floor slumped over its edges. Beyond it a spawn is
/// refused ("no room").
pub const MAX_PILE_LAYERS: f32 = 2.0;

/// A body as a spawn sees it: what it takes up and whether it can carry another.
struct Occupant {
    bounds: Aabb,
    is_static: bool,
    /// Faster than [`SETTLED_SPEED`] or [`SETTLED_SPIN`].
    moving: bool,
    /// For a box lying on a face (one within [`LEVEL_DEG`] of level): its pose, half extents and
    /// the local axis pointing up or down. `None` for balls and boxes on an edge: a body dropped on
    /// them slides off the pile sideways.
    top_face: Option<(Pose, Vec3, usize)>,
}

impl Occupant {
    fn of(body: &crate::physics::Body) -> Self {
        let pose = *body.pose();
        let top_face = match *body.shape() {
            Shape::Cuboid { half_extents } => (0..3)
                .find(|&k| (pose.rotation * Vec3::AXES[k]).y.abs() >= LEVEL_DEG.to_radians().cos())
                .map(|k| (pose, half_extents, k)),
            Shape::Sphere { .. } => None,
        };
        Self {
            bounds: body.shape().aabb(body.pose()),
            is_static: body.is_static(),
            moving: body.linear_velocity().length() > SETTLED_SPEED
                || body.angular_velocity().length() > SETTLED_SPIN,
            top_face,
        }
    }

    /// Whether a body of footprint `half` dropped at `spot` (x, z) onto this one rests there: the
    /// ground does; a box does if it lies on a face and the spot's centre is over that face, an
    /// eighth of the new body's width in from its edges (else the new body tips off).
    fn supports(&self, spot: Vec2, half: Vec2) -> bool {
        if self.is_static {
            return true;
        }
        let Some((pose, half_extents, up)) = self.top_face else {
            return false;
        };
        let p = Vec3::new(spot.x, pose.position.y, spot.y);
        let local = pose.rotation.inverse() * (p - pose.position);
        let inset = 0.25 * half.max_element();
        (0..3)
            .filter(|&k| k != up)
            .all(|k| local[k].abs() <= half_extents[k] - inset)
    }
}

/// Where a new body of `shape` (unrotated) is placed around `center`: its centre of mass, or `None`
/// when the ground near `center` holds all it safely can. Its bounds overlap no body of `world` (see
/// the module docs).
pub fn spawn_position(world: &World, shape: &Shape, center: Vec3) -> Option<Vec3> {
    let half = shape.aabb(&Pose::from_position(Vec3::ZERO)).max;
    // Half a body width (with its gaps) apart: a spot fits between bodies the scene put off the grid.
    let spacing = half.x.max(half.z) + SPAWN_GAP;
    // A ball is dropped only onto the ground: on a pile the least knock rolls it off the floor.
    let ball = matches!(shape, Shape::Sphere { .. });
    let columns: Vec<Occupant> = world.bodies().iter().map(Occupant::of).collect();
    // (Footprints are `Vec2`s of x and z.) What stands in the column of a body of footprint `half`
    // at `spot`, and the top of the ground under it, if it has ground: a static body whose x–z
    // extent holds the footprint with `EDGE_MARGIN` to spare.
    let rest = |spot: Vec2| -> (Option<&Occupant>, bool, Option<f32>) {
        let (lo, hi) = (spot - half.xz(), spot + half.xz());
        let (inner_lo, inner_hi) = (lo - EDGE_MARGIN * half.xz(), hi + EDGE_MARGIN * half.xz());
        let mut highest: Option<&Occupant> = None;
        let mut ground: Option<f32> = None;
        let mut busy = false;
        for occupant in &columns {
            let (min, max) = (occupant.bounds.min.xz(), occupant.bounds.max.xz());
            if max.x >= lo.x && min.x <= hi.x && max.y >= lo.y && min.y <= hi.y {
                if highest.is_none_or(|h| occupant.bounds.max.y > h.bounds.max.y) {
                    highest = Some(occupant);
                }
                busy |= occupant.moving;
            }
            let holds = min.x <= inner_lo.x
                && max.x >= inner_hi.x
                && min.y <= inner_lo.y
                && max.y >= inner_hi.y;
            if occupant.is_static && holds {
                let top = occupant.bounds.max.y;
                ground = Some(ground.map_or(top, |g| g.max(top)));
            }
        }
        (highest, busy, ground)
    };
    let mut best: Option<(f32, Vec3)> = None;
    for ring in 0..=SEARCH_RINGS {
        for i in -ring..=ring {
            for j in -ring..=ring {
                if i.abs().max(j.abs()) != ring {
                    continue;
                }
                let offset = Vec2::new(i as f32, j as f32) * spacing;
                let spot = center.xz() + offset;
                let (Some(highest), false, Some(ground)) = rest(spot) else {
                    continue;
                };
                let top = highest.bounds.max.y;
                if !highest.supports(spot, half.xz())
                    || top - ground > MAX_PILE_LAYERS * 2.0 * half.y
                    || ball && !highest.is_static
                {
                    continue;
                }
                let y = top + half.y + SPAWN_GAP;
                let cost = y + PILE_SLOPE * offset.length();
                if best.is_none_or(|(c, _)| cost < c) {
                    best = Some((cost, Vec3::new(spot.x, y, spot.y)));
                }
            }
        }
    }
    if let Some((_, position)) = best {
        return Some(position);
    }
    if columns.iter().any(|o| o.is_static) {
        // There is ground, all of it near here full or busy.
        return None;
    }
    // Nothing to stand on (a scene without static bodies): above whatever is at the centre.
    let (highest, _, _) = rest(center.xz());
    let y = highest.map_or(center.y, |h| h.bounds.max.y + half.y + SPAWN_GAP);
    Some(Vec3::new(center.x, y, center.z))
}

impl App {
    /// Drops a new body into free space around what is under the pointer (or the camera's target).
    pub(crate) fn spawn(&mut self, shape: Shape) {
        // The representable range holds for the sandbox as for files (`physics::limits`).
        if self.world.len() >= crate::physics::limits::MAX_BODIES {
            let most = crate::physics::limits::MAX_BODIES;
            self.say(format!(
                "not spawned: the world holds {most} bodies at most"
            ));
            return;
        }
        let under_pointer = self.selection.pointer().and_then(|cell| self.pick_at(cell));
        let center = under_pointer.map_or(self.camera.get().target, |pick| pick.hit.point);
        let Some(position) = spawn_position(&self.world, &shape, center) else {
            self.say("no room to drop anything here (point at another spot, or r resets)");
            return;
        };
        if let Err(why) = crate::physics::limits::check_position("spawn position", position) {
            self.say(format!("not spawned: {why}"));
            return;
        }
        let color = PALETTE[self.world.len() % PALETTE.len()];
        let mut desc = BodyDesc::dynamic(shape, Pose::from_position(position), shape.volume());
        if matches!(shape, Shape::Sphere { .. }) {
            // As the scenes' balls do: a ball that rolls forever rolls off the floor.
            desc.rolling_resistance = BALL_ROLLING_RESISTANCE;
        }
        let id = self.world.add_body(desc);
        // After a rewind the looks of bodies of the cut-off future are still there.
        self.looks.truncate(id.index());
        self.looks.push(crate::app::panels::look::BodyLook {
            color,
            scenery: false,
        });
        self.selection.select(id);
        let name = self.body_name(id);
        let mass = self.world.body(id).mass();
        self.say(format!(
            "spawned {name} ({})",
            crate::app::panels::mass_text::mass(mass)
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    fn overlaps_any(world: &World, aabb: &Aabb) -> bool {
        world
            .bodies()
            .iter()
            .any(|b| b.shape().aabb(b.pose()).overlaps(aabb))
    }

    /// The default scene's floor (8 m × 5 m, top at y = 0) alone.
    fn bare_floor() -> World {
        let mut scene = scene::load("default").unwrap();
        scene.bodies.truncate(1);
        scene.build_world()
    }

    #[test]
    fn boxes_spawned_at_one_spot_without_a_step_never_overlap_and_stack_until_the_floor_is_full() {
        let mut world = bare_floor();
        let shape = Shape::cuboid(Vec3::splat(0.5));
        let mut placed = 0;
        while let Some(p) = spawn_position(&world, &shape, Vec3::ZERO) {
            let pose = Pose::from_position(p);
            assert!(
                !overlaps_any(&world, &shape.aabb(&pose)),
                "body {placed} at {p} overlaps"
            );
            // Three layers at most.
            assert!(p.y < 2.5 + 3.0 * SPAWN_GAP + 1e-4, "{p}");
            world.add_body(BodyDesc::dynamic(shape, pose, 1.0));
            placed += 1;
            assert!(placed < 200, "no end to the pile");
        }
        assert!(placed >= 30, "only {placed} fit");
    }

    #[test]
    fn a_spawn_lands_on_empty_floor_at_the_centre_and_the_next_beside_it() {
        let mut world = bare_floor();
        let shape = Shape::cuboid(Vec3::splat(0.5));
        let p = spawn_position(&world, &shape, Vec3::new(0.3, 0.0, -0.4)).unwrap();
        assert_eq!(p, Vec3::new(0.3, 0.5 + SPAWN_GAP, -0.4));
        world.add_body(BodyDesc::dynamic(shape, Pose::from_position(p), 1.0));
        // A layer fills before the pile rises, as a heap spreads.
        let q = spawn_position(&world, &shape, Vec3::new(0.3, 0.0, -0.4)).unwrap();
        assert_eq!(q.y, p.y);
        let apart = (q - p).length();
        assert!((apart - (1.0 + 2.0 * SPAWN_GAP)).abs() < 1e-5, "{apart}");
    }

    #[test]
    fn spots_keep_off_the_floors_edge_balls_stay_on_the_ground_and_a_full_floor_refuses_more() {
        let mut world = bare_floor();
        let shape = Shape::sphere(0.5);
        // Every footprint keeps half a width from the edge (x = ±4, z = ±2.5).
        let mut placed = 0;
        while let Some(p) = spawn_position(&world, &shape, Vec3::new(3.9, 0.0, 2.4)) {
            assert!(p.x.abs() <= 3.0 + 1e-4 && p.z.abs() <= 1.5 + 1e-4, "{p}");
            assert_eq!(p.y, 0.5 + SPAWN_GAP);
            world.add_body(BodyDesc::dynamic(shape, Pose::from_position(p), 1.0));
            placed += 1;
            assert!(placed < 200, "no end to the pile");
        }
        assert!(placed >= 10, "{placed}");
    }

    #[test]
    fn a_scene_without_ground_drops_above_whatever_is_at_the_centre() {
        let mut world = World::new(crate::physics::Settings::default());
        let shape = Shape::sphere(0.5);
        let p = spawn_position(&world, &shape, Vec3::new(1.0, 2.0, 3.0)).unwrap();
        assert_eq!(p, Vec3::new(1.0, 2.0, 3.0));
        world.add_body(BodyDesc::dynamic(shape, Pose::from_position(p), 1.0));
        let q = spawn_position(&world, &shape, Vec3::new(1.0, 2.0, 3.0)).unwrap();
        assert_eq!(q, Vec3::new(1.0, 3.0 + SPAWN_GAP, 3.0));
    }
}
