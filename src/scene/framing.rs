//! The automatic camera: where to look from when a scene does not say.
//!
//! The camera looks along +z from in front and above, [`AUTO_ELEVATION_DEG`] below the horizontal,
//! and stands where the picture of the *framed solids* is centred in a [`FRAMING_ASPECT`] view (a
//! 120×40 terminal of 1:2 cells) and fills [`FRAMING_FILL`] of it across the direction it is tighter
//! in. Two kinds of solid are framed:
//!
//! - **bodies**, kept inside the picture across and down: each dynamic body *where it comes to rest*,
//!   dropped straight down onto what lies under it ([`settle`]). Scenes drop their bodies a little
//!   onto the floor, and the view is looked at for minutes after the second they fall: framed where
//!   they start, the default scene's bodies settled into the lower half of the picture under 40 % of
//!   empty sky. A body that starts higher falls into the picture from above. A body a joint holds
//!   (a pendulum's bob, a chain's links) is framed where it hangs ([`Framing::of_held`]): dropped,
//!   a chain hung 6 m up was framed on the floor, out of its own picture.
//! - **ground**, kept inside the picture top to bottom but free to run off its sides: the parts of
//!   the static bodies near the dynamic ones, so an 80 m floor under a 2 m stack neither shrinks the
//!   stack to a dot nor, being wider than the bodies, decides how wide the picture is. Precisely: D =
//!   union of the settled bodies' boxes; E = the x–z footprint of D grown on every side by max(half
//!   the height of D, [`FLOOR_MARGIN`]); ground = the top of each static body's box that reaches
//!   into E, clipped to E in x and z (the floor around the bodies is what should show, not the
//!   thickness of its slab).
//!
//! Without dynamic bodies the static ones are framed as bodies, whole.
//!
//! Each side of the picture is a plane through the eye; a solid is inside it when its support
//! function ([`Shape::reach`]) along the plane's inward normal does not cross it, which is exact for
//! boxes at any rotation and for balls (a ball's bounding box would stick out past its silhouette).

use glam::Vec3;

use super::SceneBody;
use crate::geometry::{Aabb, Camera, Pose, Projection, Ray, Shape};

/// Vertical field of view of cameras that do not give one, degrees.
pub const DEFAULT_FOV_DEG: f32 = 70.0;
/// Angle of the automatic camera's line of sight below the horizontal, degrees.
pub const AUTO_ELEVATION_DEG: f32 = 25.0;
/// Displayed width / height the automatic framing is computed for.
pub const FRAMING_ASPECT: f32 = 1.5;
/// Fraction of the half-width and half-height of the image the framed solids may cover, in (0, 1].
pub const FRAMING_FILL: f32 = 0.9;
/// Least ground the automatic camera keeps around the bodies, metres (see the module docs).
pub const FLOOR_MARGIN: f32 = 1.0;
/// Camera position of a scene with no bodies at all (the doc example's view of the origin).
pub const EMPTY_SCENE_POSITION: Vec3 = Vec3::new(0.0, 4.0, -12.0);
/// Camera target of a scene with no bodies at all.
pub const EMPTY_SCENE_TARGET: Vec3 = Vec3::new(0.0, 1.0, 0.0);
/// Far plane of scene cameras unless the scene needs more, metres.
pub const DEFAULT_FAR: f32 = 500.0;
/// How far above its bottom a solid's rays down start when it is settled, metres: a solid resting a
/// hair into the one below (as contacts leave them) still finds it.
const SETTLE_START: f32 = 0.01;
/// Least distance from the eye to any framed solid along the line of sight, metres.
const NEAREST_M: f32 = 0.5;

/// A solid the automatic camera keeps in view: a shape at a pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framed {
    pub shape: Shape,
    pub pose: Pose,
}

impl Framed {
    /// The box `b` as a solid.
    pub fn aabb(b: &Aabb) -> Self {
        Self {
            shape: Shape::Cuboid {
                half_extents: b.half_extents(),
            },
            pose: Pose::from_position(b.center()),
        }
    }

    /// Its world bounds.
    pub fn bounds(&self) -> Aabb {
        self.shape.aabb(&self.pose)
    }

    /// The least `n · p` over the points `p` of the solid, for a unit `n`.
    fn lowest_along(&self, n: Vec3) -> f32 {
        n.dot(self.pose.position) - self.shape.reach(self.pose.rotation, n)
    }
}

/// What the automatic camera frames (see the module docs).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Framing {
    /// Kept inside the picture across and down.
    pub bodies: Vec<Framed>,
    /// Kept inside the picture top to bottom; may run off its sides.
    pub ground: Vec<Framed>,
}

impl Framing {
    /// What the automatic camera frames of `bodies`, as the module docs say.
    pub fn of(bodies: &[SceneBody]) -> Self {
        Self::of_held(bodies, &[])
    }

    /// The same, with the bodies `held[i]` marks (a joint holds them up: a pendulum, a chain) framed
    /// where they are instead of where they would land.
    pub fn of_held(bodies: &[SceneBody], held: &[bool]) -> Self {
        let solid = |b: &SceneBody| Framed {
            shape: b.desc.shape,
            pose: b.desc.pose,
        };
        let is_held = |i: usize| held.get(i).copied().unwrap_or(false);
        let statics: Vec<Framed> = bodies
            .iter()
            .filter(|b| b.desc.is_static)
            .map(solid)
            .collect();
        let mut dynamic: Vec<Framed> = bodies
            .iter()
            .enumerate()
            .filter(|&(i, b)| !b.desc.is_static && !is_held(i))
            .map(|(_, b)| solid(b))
            .collect();
        let hanging: Vec<Framed> = bodies
            .iter()
            .enumerate()
            .filter(|&(i, b)| !b.desc.is_static && is_held(i))
            .map(|(_, b)| solid(b))
            .collect();
        if dynamic.is_empty() && hanging.is_empty() {
            return Self {
                bodies: statics,
                ground: Vec::new(),
            };
        }
        settle(&mut dynamic, &statics);
        dynamic.extend(hanging);
        let settled = union(&dynamic.iter().map(Framed::bounds).collect::<Vec<_>>())
            .expect("dynamic is not empty");
        let grow = settled.half_extents().y.max(FLOOR_MARGIN);
        let (lo, hi) = (settled.min - grow, settled.max + grow);
        let ground = statics
            .iter()
            .map(Framed::bounds)
            .filter(|b| b.min.x <= hi.x && b.max.x >= lo.x && b.min.z <= hi.z && b.max.z >= lo.z)
            .map(|b| {
                Framed::aabb(&Aabb::new(
                    Vec3::new(b.min.x.max(lo.x), b.max.y, b.min.z.max(lo.z)),
                    Vec3::new(b.max.x.min(hi.x), b.max.y, b.max.z.min(hi.z)),
                ))
            })
            .collect();
        Self {
            bodies: dynamic,
            ground,
        }
    }

    /// Every framed solid, bodies first.
    pub fn all(&self) -> impl Iterator<Item = &Framed> {
        self.bodies.iter().chain(&self.ground)
    }

    /// The bounds of every framed solid; `None` when there is none.
    pub fn bounds(&self) -> Option<Aabb> {
        union(&self.all().map(Framed::bounds).collect::<Vec<_>>())
    }
}

/// The bounds of the solids the automatic camera frames ([`Framing::of`]); empty for a scene without
/// bodies.
pub fn framed_boxes(bodies: &[SceneBody]) -> Vec<Aabb> {
    Framing::of(bodies).all().map(Framed::bounds).collect()
}

/// The union of `boxes`, `None` when there are none.
pub fn union(boxes: &[Aabb]) -> Option<Aabb> {
    let (first, rest) = boxes.split_first()?;
    Some(rest.iter().fold(*first, |acc, b| acc.union(b)))
}

/// A perspective camera with vertical field of view `fov_y` (radians, in (0, π)) framing `bodies` as
/// the module docs describe.
pub fn auto_camera(bodies: &[SceneBody], fov_y: f32) -> Camera {
    framing_camera(&Framing::of(bodies), fov_y)
}

/// [`auto_camera`] with the bodies `held[i]` marks framed where they hang ([`Framing::of_held`]).
pub fn auto_camera_held(bodies: &[SceneBody], held: &[bool], fov_y: f32) -> Camera {
    framing_camera(&Framing::of_held(bodies, held), fov_y)
}

/// Lowers each of `dynamic`, lowest first, straight down until it rests on one of `statics` or on
/// one lowered before it. What lies under a solid is found by rays cast straight down from the
/// centre and the four corners of the bottom of its bounds (at 90 % of their half-size), starting
/// `SETTLE_START` (1 cm) above that bottom; it drops by the shortest of them, and not at all when none
/// hits. Exact for boxes and balls standing on level ground or on one another, a few centimetres
/// short or deep on a slope: enough for framing.
pub fn settle(dynamic: &mut [Framed], statics: &[Framed]) {
    dynamic.sort_by(|a, b| a.bounds().min.y.total_cmp(&b.bounds().min.y));
    // Columns as wide as the typical body, so a ray asks only the solids over its column.
    let widths: f32 = dynamic
        .iter()
        .map(|d| {
            let h = d.bounds().half_extents();
            2.0 * h.x.max(h.z)
        })
        .sum();
    let mut below = Columns::new((widths / dynamic.len().max(1) as f32).max(0.05));
    for s in statics {
        below.insert(*s);
    }
    for solid in dynamic.iter_mut() {
        let b = solid.bounds();
        let (c, h) = (b.center(), 0.9 * b.half_extents());
        let drop = [
            (0.0, 0.0),
            (-1.0, -1.0),
            (1.0, -1.0),
            (-1.0, 1.0),
            (1.0, 1.0),
        ]
        .into_iter()
        .filter_map(|(sx, sz)| {
            let origin = Vec3::new(c.x + sx * h.x, b.min.y + SETTLE_START, c.z + sz * h.z);
            below.first_hit_down(origin)
        })
        .reduce(f32::min);
        if let Some(t) = drop {
            solid.pose.position.y -= (t - SETTLE_START).max(0.0);
        }
        below.insert(*solid);
    }
}

/// Solids bucketed by the square columns (x, z) of side `side` their bounds cover, so that a ray cast
/// straight down meets only those over its column. A solid covering more than [`Columns::MAX_CELLS`]
/// columns (a floor) is kept aside and asked by every ray.
struct Columns {
    side: f32,
    solids: Vec<(Framed, Aabb)>,
    cells: std::collections::HashMap<(i64, i64), Vec<usize>>,
    large: Vec<usize>,
}

impl Columns {
    const MAX_CELLS: i64 = 64;

    fn new(side: f32) -> Self {
        Self {
            side,
            solids: Vec::new(),
            cells: std::collections::HashMap::new(),
            large: Vec::new(),
        }
    }

    fn cell(&self, v: f32) -> i64 {
        (v / self.side).floor() as i64
    }

    fn insert(&mut self, solid: Framed) {
        let b = solid.bounds();
        let index = self.solids.len();
        self.solids.push((solid, b));
        let (x0, x1) = (self.cell(b.min.x), self.cell(b.max.x));
        let (z0, z1) = (self.cell(b.min.z), self.cell(b.max.z));
        let finite = b.min.is_finite() && b.max.is_finite();
        if !finite || (x1 - x0 + 1).saturating_mul(z1 - z0 + 1) > Self::MAX_CELLS {
            self.large.push(index);
            return;
        }
        for x in x0..=x1 {
            for z in z0..=z1 {
                self.cells.entry((x, z)).or_default().push(index);
            }
        }
    }

    /// How far a ray straight down from `origin` goes before it enters a solid, if it does.
    fn first_hit_down(&self, origin: Vec3) -> Option<f32> {
        let ray = Ray {
            origin,
            dir: Vec3::NEG_Y,
        };
        let column = self
            .cells
            .get(&(self.cell(origin.x), self.cell(origin.z)))
            .map_or(&[][..], Vec::as_slice);
        column
            .iter()
            .chain(&self.large)
            .map(|&i| &self.solids[i])
            .filter(|(_, o)| {
                o.min.y <= origin.y
                    && (o.min.x..=o.max.x).contains(&origin.x)
                    && (o.min.z..=o.max.z).contains(&origin.z)
            })
            .filter_map(|(o, _)| ray.cast(&o.shape, &o.pose, 0.0, f32::INFINITY))
            .map(|hit| hit.t)
            .reduce(f32::min)
    }
}

/// A perspective camera with vertical field of view `fov_y` (radians, in (0, π)) looking along +z
/// and down at [`AUTO_ELEVATION_DEG`], where the picture of `framing` is centred and fills
/// [`FRAMING_FILL`] of the image across the direction it is tighter in (see the module docs). With
/// nothing to frame, the empty-scene camera.
pub fn framing_camera(framing: &Framing, fov_y: f32) -> Camera {
    let Some(bounds) = framing.bounds() else {
        return scene_camera(EMPTY_SCENE_POSITION, EMPTY_SCENE_TARGET, fov_y, 0.0);
    };
    let all: Vec<Framed> = framing.all().copied().collect();
    let across: &[Framed] = if framing.bodies.is_empty() {
        &all
    } else {
        &framing.bodies
    };
    let elevation = AUTO_ELEVATION_DEG.to_radians();
    let forward = Vec3::new(0.0, -elevation.sin(), elevation.cos());
    let right = forward.cross(Vec3::Y).normalize();
    let up = right.cross(forward);
    let tan_y = (0.5 * fov_y).tan() * FRAMING_FILL;
    let tan_x = tan_y * FRAMING_ASPECT;
    let nearest = all
        .iter()
        .map(|s| s.lowest_along(forward))
        .fold(f32::INFINITY, f32::min)
        - NEAREST_M;
    let along = fit_along(&all, forward, up, tan_y)
        .min(fit_along(across, forward, right, tan_x))
        .min(nearest);
    let eye = forward * along
        + up * centred(&all, forward, up, tan_y, along)
        + right * centred(across, forward, right, tan_x, along);
    // The target (what the camera orbits) is on the line of sight, as deep as the solids' centre.
    let depth = (bounds.center() - eye).dot(forward).max(1.0);
    let radius = bounds.half_extents().length();
    scene_camera(eye, eye + forward * depth, fov_y, radius)
}

/// The inward unit normals of the two sides of a view cone of half-angle tangent `tan` across the
/// image axis `side` (the camera's up or right): the side at `+side`, then the one at `−side`.
fn side_normals(forward: Vec3, side: Vec3, tan: f32) -> [Vec3; 2] {
    let s = (1.0 + tan * tan).sqrt();
    [(forward * tan - side) / s, (forward * tan + side) / s]
}

/// For each side of the cone of `tan` across `side`, the least `n · p` over the solids' points.
fn lowest_across(solids: &[Framed], forward: Vec3, side: Vec3, tan: f32) -> [f32; 2] {
    side_normals(forward, side, tan).map(|n| {
        solids
            .iter()
            .map(|s| s.lowest_along(n))
            .fold(f32::INFINITY, f32::min)
    })
}

/// The eye's coordinate along `forward` at which the solids just fit between both sides of the cone
/// of `tan` across `side`, the eye's coordinate along `side` centring them.
///
/// A solid is inside the side of inward normal n through the eye e when n · e ≤ k, the least n · p
/// over its points. With n± = (f tan ∓ side) / s, s = √(1 + tan²), both sides touch when
/// tan e_f ∓ e_side = s k±: e_f = s (k₊ + k₋) / (2 tan) and e_side = s (k₋ − k₊) / 2.
fn fit_along(solids: &[Framed], forward: Vec3, side: Vec3, tan: f32) -> f32 {
    let [k_plus, k_minus] = lowest_across(solids, forward, side, tan);
    (1.0 + tan * tan).sqrt() * (k_plus + k_minus) / (2.0 * tan)
}

/// The eye's coordinate along `side` that centres the solids across it when the eye's coordinate
/// along `forward` is `along` (at or behind [`fit_along`] for `tan`): the narrower cone the solids
/// just fit in from there is found by bisection, and both its sides touch them.
fn centred(solids: &[Framed], forward: Vec3, side: Vec3, tan: f32, along: f32) -> f32 {
    let (mut lo, mut hi) = (0.0, tan);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if fit_along(solids, forward, side, mid) >= along {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let [k_plus, k_minus] = lowest_across(solids, forward, side, hi);
    (1.0 + hi * hi).sqrt() * (k_minus - k_plus) / 2.0
}

/// The eight corners of a box.
pub fn corners(b: &Aabb) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// A perspective camera whose far plane reaches past a scene of bounding radius `radius_m` around
/// `target` (never nearer than [`DEFAULT_FAR`]).
pub fn scene_camera(position: Vec3, target: Vec3, fov_y: f32, radius_m: f32) -> Camera {
    let mut camera = Camera::perspective(position, target, fov_y);
    let reach = 2.0 * ((target - position).length() + radius_m);
    if reach.is_finite() {
        camera.far = camera.far.max(DEFAULT_FAR).max(reach);
    }
    camera
}

/// The orthographic projection showing, at the target's distance, what a perspective camera with
/// vertical field of view `fov_y` shows there: view height = 2 · |target − position| · tan(fov_y / 2).
pub fn orthographic_matching(camera: &Camera, fov_y: f32) -> Projection {
    let distance = (camera.target - camera.position).length();
    Projection::Orthographic {
        view_height: 2.0 * distance * (0.5 * fov_y).tan(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Shape;
    use crate::physics::BodyDesc;

    fn body(shape: Shape, position: Vec3, is_static: bool) -> SceneBody {
        let pose = Pose::from_position(position);
        SceneBody {
            name: None,
            frozen: false,
            desc: if is_static {
                BodyDesc::fixed(shape, pose)
            } else {
                BodyDesc::dynamic(shape, pose, 1.0)
            },
            color: crate::color::Rgb::WHITE,
        }
    }

    fn ndc(camera: &Camera, p: Vec3) -> Vec3 {
        let clip = camera.clip_from_world(FRAMING_ASPECT) * p.extend(1.0);
        clip.truncate() / clip.w
    }

    /// Points on the surface of a framed solid: a box's corners, 400 points spread over a ball.
    fn surface_points(s: &Framed) -> Vec<Vec3> {
        match s.shape {
            Shape::Cuboid { half_extents } => corners(&Aabb::new(-half_extents, half_extents))
                .map(|p| s.pose.transform_point(p))
                .to_vec(),
            Shape::Sphere { radius } => (0..400)
                .map(|i| {
                    // A Fibonacci lattice.
                    let y = 1.0 - (i as f32 + 0.5) / 200.0;
                    let r = (1.0 - y * y).sqrt();
                    let a = i as f32 * 2.399_963;
                    s.pose.position + radius * Vec3::new(r * a.cos(), y, r * a.sin())
                })
                .collect(),
        }
    }

    /// The NDC bounds of `solids` seen by `camera`.
    fn ndc_bounds<'a>(camera: &Camera, solids: impl Iterator<Item = &'a Framed>) -> (Vec3, Vec3) {
        let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        for p in solids.flat_map(surface_points) {
            let q = ndc(camera, p);
            (lo, hi) = (lo.min(q), hi.max(q));
        }
        (lo, hi)
    }

    #[test]
    fn a_huge_floor_is_framed_as_its_top_around_the_bodies_settled_on_it() {
        let bodies = [
            body(
                Shape::cuboid(Vec3::new(40.0, 0.5, 40.0)),
                Vec3::new(0.0, -0.5, 0.0),
                true,
            ),
            body(Shape::sphere(0.5), Vec3::new(0.0, 2.0, 0.0), false),
        ];
        let framing = Framing::of(&bodies);
        assert_eq!(framing.bodies.len(), 1);
        let ball = framing.bodies[0].pose.position;
        assert!((ball - Vec3::new(0.0, 0.5, 0.0)).length() < 1e-5, "{ball}");
        assert_eq!(framing.ground.len(), 1);
        let ground = framing.ground[0].bounds();
        assert_eq!(ground.min, Vec3::new(-1.5, 0.0, -1.5));
        assert_eq!(ground.max, Vec3::new(1.5, 0.0, 1.5));
        let far_wall = body(Shape::cuboid(Vec3::ONE), Vec3::new(10.0, 1.0, 0.0), true);
        assert_eq!(
            Framing::of(&[bodies[0].clone(), bodies[1].clone(), far_wall]),
            framing
        );
    }

    #[test]
    fn bodies_settle_onto_the_ground_and_onto_each_other_lowest_first() {
        let floor = body(
            Shape::cuboid(Vec3::new(5.0, 0.5, 5.0)),
            Vec3::new(0.0, -0.5, 0.0),
            true,
        );
        let cube = |y: f32| {
            body(
                Shape::cuboid(Vec3::splat(0.5)),
                Vec3::new(0.0, y, 0.0),
                false,
            )
        };
        // Listed top first, with gaps; a ball off to the side, over no ground.
        let bodies = [
            floor,
            cube(5.0),
            cube(2.0),
            body(Shape::sphere(0.5), Vec3::new(20.0, 3.0, 0.0), false),
        ];
        let framing = Framing::of(&bodies);
        let mut at: Vec<Vec3> = framing.bodies.iter().map(|b| b.pose.position).collect();
        at.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        assert!((at[0].y - 0.5).abs() < 1e-4, "{at:?}");
        assert!((at[1].y - 1.5).abs() < 1e-4, "{at:?}");
        assert_eq!(at[2].y, 3.0, "nothing under it: it stays");
    }

    #[test]
    fn the_auto_camera_centres_the_bodies_and_keeps_the_ground_in_view_top_to_bottom() {
        let bodies = [
            body(
                Shape::cuboid(Vec3::new(6.0, 0.5, 2.0)),
                Vec3::new(0.0, -0.5, 0.0),
                true,
            ),
            body(
                Shape::cuboid(Vec3::splat(0.5)),
                Vec3::new(3.0, 4.0, 0.0),
                false,
            ),
            body(Shape::sphere(0.3), Vec3::new(-3.0, 0.3, 1.0), false),
        ];
        let camera = auto_camera(&bodies, DEFAULT_FOV_DEG.to_radians());
        assert!(camera.position.z < camera.target.z && camera.position.y > camera.target.y);
        let framing = Framing::of(&bodies);
        let (lo, hi) = ndc_bounds(&camera, framing.all());
        assert!(lo.z > 0.0 && hi.z < 1.0, "depth {lo} {hi}");
        // Top to bottom: everything inside the fill region (tolerance 1e-4 NDC), centred.
        assert!(
            -lo.y <= FRAMING_FILL + 1e-4 && hi.y <= FRAMING_FILL + 1e-4,
            "{lo} {hi}"
        );
        assert!((hi.y + lo.y).abs() < 1e-3, "{lo} {hi}");
        // Across: the bodies inside it and centred.
        let (lo_x, hi_x) = ndc_bounds(&camera, framing.bodies.iter());
        assert!(-lo_x.x <= FRAMING_FILL + 1e-4 && hi_x.x <= FRAMING_FILL + 1e-4);
        assert!((hi_x.x + lo_x.x).abs() < 1e-3, "{lo_x} {hi_x}");
        // Touching it one way or the other.
        assert!(hi.y.max(hi_x.x) >= FRAMING_FILL - 1e-3, "{hi} {hi_x}");
    }

    #[test]
    fn an_empty_scene_gets_the_documented_default_view() {
        let camera = auto_camera(&[], DEFAULT_FOV_DEG.to_radians());
        assert_eq!(camera.position, EMPTY_SCENE_POSITION);
        assert_eq!(camera.target, EMPTY_SCENE_TARGET);
    }

    #[test]
    fn the_matching_orthographic_view_shows_the_perspective_slab_at_the_target() {
        let camera =
            Camera::perspective(Vec3::new(0.0, 0.0, -10.0), Vec3::ZERO, 90f32.to_radians());
        let Projection::Orthographic { view_height } =
            orthographic_matching(&camera, 90f32.to_radians())
        else {
            panic!("not orthographic");
        };
        assert!((view_height - 20.0).abs() < 1e-4);
    }
}
