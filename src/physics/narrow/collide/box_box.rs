//! Box–box contact: separating-axis test over the 15 candidate axes, then face clipping or edge–edge.
//!
//! Sources (read to learn, not copied): Ericson, "Real-Time Collision Detection", 4.4.1 and 5.2.1 (OBB
//! SAT with the relative rotation R = A^T B and |R|), 5.1.9 (closest points of two segments), 8.3.4
//! (Sutherland–Hodgman); Gregorius, GDC 2013 / 2015 "The Separating Axis Test" (face/edge bias, contact
//! reduction); Box2D v3 `manifold.c` (reference/incident faces, feature ids).
//!
//! ```text
//! work in A's frame: R = A^T B (columns: B's axes), t = A^T (p_B − p_A)
//! for each of A's 3 face axes, B's 3 face axes, the 9 edge axes a_i × b_j (skipping |a_i × b_j|² < ε):
//!     separation = |t·L| − r_A(L) − r_B(L)          (L normalised for edge axes)
//!     if separation > margin: return empty         (early out: a separating axis exists)
//! best face = A's best, unless B's best beats it by a relative + absolute tolerance
//! if best edge beats best face by a (larger) relative + absolute tolerance: edge–edge contact
//! else face contact:
//!     reference face: the chosen axis' face pointing at the other box
//!     incident face:  the other box's face most anti-parallel to the reference normal
//!     clip the incident quad against the reference face's 4 side planes (Sutherland–Hodgman)
//!     keep clipped points with separation below the reference face ≤ margin; reduce to ≤ 4
//! ```
//!
//! **Axis bias.** Separations are compared as `candidate > best + rel·|best| + abs`, sign-agnostic so
//! it also holds for speculative (positive) separations. B's face must beat A's face by 2 % (+abs), an
//! edge must beat the best face by 5 % (+abs), with `abs = 1e-3 ×` the smallest half-extent of the two
//! boxes. Faces give 4-point manifolds that keep stacks still; an edge axis is only taken when it is
//! clearly better, so the choice does not flicker between equal axes from step to step (a resting cube's
//! edge axes a_x × b_z equal its face axis exactly). Two boxes' faces within the bias of each other
//! still trade places as the pair stirs; the points keep their ids when they do ("Feature ids").
//! Keeping last step's reference face instead (a hysteresis) let crowds of overlapping boxes end
//! deeper in each other (`tests/physics/overlap.rs`: 10.2 to 10.5 mm against 7.9; 2026-12-01).
//!
//! **Near-face edge axes.** Two nearly parallel edges span no contact point: their axis a_i × b_j is
//! short and points wherever their few degrees of misalignment say, often within a degree of a face
//! normal. Such an axis (within [`NEAR_FACE_SIN`] of a face normal of either box) still separates,
//! but never makes an edge–edge contact: the face it nearly is makes the face contact. A face axis
//! projects the whole other box, so for long boxes a small tilt makes its separation pessimistic
//! (a 3 m block tilted 0.5° reads 13 mm deeper than it is) and the near-face edge axis beat it; the
//! clipped face gives each point its own depth. Taken as edge–edge, the blocks of a crossed tower
//! flickered between four points and one, and a twenty-layer tower woken by a 20 g ball fell
//! (`tests/physics/rest.rs`, `a_sleeping_crossed_tower_woken_by_a_small_ball_stands`).
//!
//! **Feature ids** name the pair of features a point lies on, one of each box: `feature_a |
//! feature_b << 6`, each a [`Feature`] code. A face contact's points are a vertex of one box inside
//! the other's face, or an edge of each crossing; an edge contact's one point is an edge of each.
//! Named by the boxes' own features, not by the clipping's bookkeeping (which box is the reference,
//! which polygon edge crossed which side plane), a point keeps its id when the reference face
//! passes from one box to the other, as Box2D's feature ids do when its reference polygon flips: the
//! solver warm-starts it with its own load. Named by the reference's bookkeeping, a column of a
//! dropped heap whose two face axes were within the bias of each other took one box's face or the
//! other's from one rebuild to the next, every switch renamed all four points, their loads were
//! shared out equally, and the column rocked at 14 mm/s for the whole minute (2 sub-steps; `tests/
//! physics/rest.rs`, `a_reference_face_that_changes_box_keeps_its_points_loads`).
//!
//! Measured through [`crate::physics::narrow::collide::collide`] (release; a noisy shared VM, so instruction counts from
//! cachegrind are the steadier figure; both include ~100 instructions of timing loop). The ns/call
//! column is what `nudge bench kernels` printed on 2026-11-25 (its collide rows are these cases; rerun
//! it to compare):
//!
//! | case                                   | instructions | ns/call |
//! |----------------------------------------|-------------:|--------:|
//! | separated (early out on a face axis)   |    ~400      |      26 |
//! | unit box resting on a floor (no clip)  |   ~1,700     |      95 |
//! | unit box on a unit box, offset (clip)  |   ~3,100     |     309 |
//! | 45°-turned box on a box (8 → 4 points) |   ~3,700     |     373 |
//! | crossed edges                          |   ~1,550     |     325 |

use glam::{Mat3, Vec2, Vec3};

use crate::geometry::Pose;
use crate::physics::narrow::collide::patch::patch;
use crate::physics::narrow::collide::sign_nonzero;
use crate::physics::{ContactPoint, Manifold, Patch};

/// Edge axes with |a_i × b_j|² below this (unit axes, so about (angle in rad)²) are skipped as parallel;
/// the face axes already cover them.
const PARALLEL_EDGE_EPS_SQ: f32 = 1e-6;
/// B's face axis must beat A's by this fraction of |separation| (plus the absolute tolerance).
const FACE_REL_TOL: f32 = 0.02;
/// An edge axis must beat the best face axis by this fraction of |separation| (plus the absolute one).
const EDGE_REL_TOL: f32 = 0.05;
/// Absolute tolerance as a fraction of the smaller box's smallest half-extent (scale-free).
const ABS_TOL_PER_SIZE: f32 = 1e-3;
/// An edge axis within this sine (about 3°) of a face normal of either box is not an edge contact.
const NEAR_FACE_SIN: f32 = 0.05;

/// A box's vertex, edge or face as a 6-bit code for feature ids (see the module docs): a 2-bit kind
/// above a 4-bit index. `sides` holds bit `i` where the feature is on the positive side of axis
/// `i`: vertices are numbered by it; edges `4·axis + ` its bits for the other two axes in
/// increasing order; faces `2·axis + (sign > 0)`. Integer bits, not the signs as floats: a quarter
/// fewer instructions for the ids (callgrind, rain(4000): `face_contact` 365 M → 354 M over 150
/// steps, against 307 M with the ids of the clipping's bookkeeping).
struct Feature;

impl Feature {
    fn vertex(sides: u32) -> u32 {
        (1 << 4) | (sides & 0b111)
    }

    /// The edge along `axis`, on the sides `sides` gives for the other two axes.
    fn edge(axis: usize, sides: u32) -> u32 {
        let (first, second) = match axis {
            0 => (1, 2),
            1 => (0, 2),
            _ => (0, 1),
        };
        let bits = ((sides >> first) & 1) | (((sides >> second) & 1) << 1);
        (2 << 4) | (4 * axis as u32 + bits)
    }

    fn face(axis: usize, positive: bool) -> u32 {
        (3 << 4) | (2 * axis as u32 + u32::from(positive))
    }

    /// The id of a point on `feature_a` of box A and `feature_b` of box B.
    fn pair(feature_a: u32, feature_b: u32) -> u32 {
        feature_a | (feature_b << 6)
    }
}

/// Contact between box A (`half_a` at `pose_a`) and box B (`half_b` at `pose_b`); normal from A to B.
///
/// Up to 4 points for face contact, 1 for edge–edge; empty when a separating axis shows a gap larger
/// than `margin` (metres). See the module docs for the algorithm, axis bias and feature ids.
pub fn box_box(half_a: Vec3, pose_a: &Pose, half_b: Vec3, pose_b: &Pose, margin: f32) -> Manifold {
    let empty = Manifold::default();
    let rot_a = Mat3::from_quat(pose_a.rotation);
    // B's rotation and centre in A's frame; one matrix from the relative quaternion.
    let a_from_b = Mat3::from_quat(pose_a.rotation.conjugate() * pose_b.rotation);
    let t_v = rot_a.transpose() * (pose_b.position - pose_a.position);
    let b_axes = [a_from_b.x_axis, a_from_b.y_axis, a_from_b.z_axis];
    // Index form (Ericson 4.4.1): r[i][j] = e_i · b_j, abs_r = |r|, t and sizes as arrays.
    let r = [
        [b_axes[0].x, b_axes[1].x, b_axes[2].x],
        [b_axes[0].y, b_axes[1].y, b_axes[2].y],
        [b_axes[0].z, b_axes[1].z, b_axes[2].z],
    ];
    let abs_r = r.map(|row| row.map(f32::abs));
    let t = t_v.to_array();
    let (ha, hb) = (half_a.to_array(), half_b.to_array());

    // Each axis is tested by a macro instantiated with literal indices, so all index arithmetic and
    // bounds checks fold away (a loop over (i + 1) % 3 was not unrolled and cost a third of the SAT).
    //
    // A's face axes e_i: r_B = Σ_j h_Bj |r_ij|.
    let mut best_a_sep = f32::NEG_INFINITY;
    let mut best_a = 0;
    macro_rules! face_a {
        ($i:literal) => {
            let r_b = hb[0] * abs_r[$i][0] + hb[1] * abs_r[$i][1] + hb[2] * abs_r[$i][2];
            let sep = t[$i].abs() - ha[$i] - r_b;
            if sep > margin || sep.is_nan() {
                return empty;
            }
            // Selects, not a branch: which axis wins is data, and a mispredicted branch here cost more
            // than the test.
            let better = sep > best_a_sep;
            best_a = if better { $i } else { best_a };
            best_a_sep = if better { sep } else { best_a_sep };
        };
    }
    face_a!(0);
    face_a!(1);
    face_a!(2);
    // B's face axes b_j: r_A = Σ_i h_Ai |r_ij|.
    let mut best_b_sep = f32::NEG_INFINITY;
    let mut best_b = 0;
    macro_rules! face_b {
        ($j:literal) => {
            let r_a = ha[0] * abs_r[0][$j] + ha[1] * abs_r[1][$j] + ha[2] * abs_r[2][$j];
            let t_on_b = t[0] * r[0][$j] + t[1] * r[1][$j] + t[2] * r[2][$j];
            let sep = t_on_b.abs() - r_a - hb[$j];
            if sep > margin || sep.is_nan() {
                return empty;
            }
            let better = sep > best_b_sep;
            best_b = if better { $j } else { best_b };
            best_b_sep = if better { sep } else { best_b_sep };
        };
    }
    face_b!(0);
    face_b!(1);
    face_b!(2);
    // Edge axes L = e_i × b_j, with (i1, i2) and (j1, j2) the cyclic successors of i and j:
    //   L = −r[i2][j] e_i1 + r[i1][j] e_i2,  |L|² = r[i1][j]² + r[i2][j]²
    //   t·L = t_i2 r[i1][j] − t_i1 r[i2][j]
    //   r_A = h_A,i1 |r[i2][j]| + h_A,i2 |r[i1][j]|,  r_B = h_B,j1 |r[i][j2]| + h_B,j2 |r[i][j1]|
    let mut best_edge_sep = f32::NEG_INFINITY;
    // 3·i + j of the best edge axis e_i × b_j that may win; NO_EDGE while there is none.
    const NO_EDGE: usize = 9;
    let mut best_edge = NO_EDGE;
    // Every edge axis's separation (−∞ for a parallel pair), for the fallback below.
    let mut edge_sep = [f32::NEG_INFINITY; 9];
    macro_rules! edge {
        ($i:literal, $i1:literal, $i2:literal, $j:literal, $j1:literal, $j2:literal) => {
            let len_sq = r[$i1][$j] * r[$i1][$j] + r[$i2][$j] * r[$i2][$j];
            if len_sq >= PARALLEL_EDGE_EPS_SQ {
                let t_on_l = t[$i2] * r[$i1][$j] - t[$i1] * r[$i2][$j];
                let r_a = ha[$i1] * abs_r[$i2][$j] + ha[$i2] * abs_r[$i1][$j];
                let r_b = hb[$j1] * abs_r[$i][$j2] + hb[$j2] * abs_r[$i][$j1];
                let len = len_sq.sqrt();
                let sep = (t_on_l.abs() - r_a - r_b) / len;
                if sep > margin || sep.is_nan() {
                    return empty;
                }
                // L's components along A's faces e_i1, e_i2 are r[i2][j], r[i1][j] (over |L|), and
                // along B's faces b_j1, b_j2 are r[i][j2], r[i][j1]: one of them small, L lies
                // within a few degrees of the other face's normal.
                let near_face = abs_r[$i1][$j]
                    .min(abs_r[$i2][$j])
                    .min(abs_r[$i][$j1])
                    .min(abs_r[$i][$j2])
                    < NEAR_FACE_SIN * len;
                edge_sep[3 * $i + $j] = sep;
                let better = !near_face && sep > best_edge_sep;
                best_edge = if better { 3 * $i + $j } else { best_edge };
                best_edge_sep = if better { sep } else { best_edge_sep };
            }
        };
    }
    edge!(0, 1, 2, 0, 1, 2);
    edge!(0, 1, 2, 1, 2, 0);
    edge!(0, 1, 2, 2, 0, 1);
    edge!(1, 2, 0, 0, 1, 2);
    edge!(1, 2, 0, 1, 2, 0);
    edge!(1, 2, 0, 2, 0, 1);
    edge!(2, 0, 1, 0, 1, 2);
    edge!(2, 0, 1, 1, 2, 0);
    edge!(2, 0, 1, 2, 0, 1);
    let best_edge = (best_edge != NO_EDGE).then_some((best_edge / 3, best_edge % 3));

    let abs_tol = ABS_TOL_PER_SIZE * half_a.min_element().min(half_b.min_element());
    let use_b = best_b_sep > best_a_sep + FACE_REL_TOL * best_a_sep.abs() + abs_tol;
    let face_sep = if use_b { best_b_sep } else { best_a_sep };
    let edge_wins = best_edge_sep > face_sep + EDGE_REL_TOL * face_sep.abs() + abs_tol;

    // Edge contacts are computed in A's frame.
    let edge_in_world = |i: usize, j: usize| {
        let mut m = edge_contact(half_a, half_b, &b_axes, t_v, i, j, margin);
        m.normal = rot_a * m.normal;
        for p in &mut m.points[..m.len] {
            p.point = pose_a.position + rot_a * p.point;
        }
        finite_or_empty(m)
    };
    if let (Some((i, j)), true) = (best_edge, edge_wins) {
        return edge_in_world(i, j);
    }
    let mut m = if use_b {
        // B is the reference: A's axes (rows of r) and centre in B's frame.
        let a_axes = r.map(Vec3::from_array);
        let t_ab = -(a_from_b.transpose() * t_v);
        let mut m = face_contact(half_b, half_a, &a_axes, t_ab, best_b, true, margin);
        // The reference-frame normal points from B to A; the manifold's from A to B.
        let rot_b = rot_a * a_from_b;
        m.normal = -(rot_b * m.normal);
        for p in &mut m.points[..m.len] {
            p.point = pose_b.position + rot_b * p.point;
        }
        m
    } else {
        let mut m = face_contact(half_a, half_b, &b_axes, t_v, best_a, false, margin);
        m.normal = rot_a * m.normal;
        for p in &mut m.points[..m.len] {
            p.point = pose_a.position + rot_a * p.point;
        }
        m
    };
    if m.is_empty() {
        // Clipping found nothing within the margin (a near miss the face axis mis-predicted): the best
        // edge pair, near-face ones included, is the next-best description of the contact.
        let (k, sep) =
            edge_sep
                .iter()
                .enumerate()
                .fold((NO_EDGE, f32::NEG_INFINITY), |best, (k, &sep)| {
                    if sep > best.1 { (k, sep) } else { best }
                });
        if sep > f32::NEG_INFINITY {
            m = edge_in_world(k / 3, k % 3);
        }
    }
    finite_or_empty(m)
}

/// The manifold, or an empty one if anything in it is not finite. Inputs are finite, so this only
/// triggers when sums overflow (sizes or distances near f32::MAX); one sum of everything tests it
/// (a sum is finite only if every term is, or overflows, which also deserves the empty answer).
fn finite_or_empty(m: Manifold) -> Manifold {
    let mut sum = m.normal.x + m.normal.y + m.normal.z;
    for p in m.points() {
        sum += p.point.x + p.point.y + p.point.z + p.separation;
    }
    if sum.is_finite() {
        m
    } else {
        Manifold::default()
    }
}

/// Largest component and its index (first on ties).
#[inline]
fn max_component(v: Vec3) -> (f32, usize) {
    if v.x >= v.y && v.x >= v.z {
        (v.x, 0)
    } else if v.y >= v.z {
        (v.y, 1)
    } else {
        (v.z, 2)
    }
}

/// e_i × v for the unit axis e_i.
#[inline]
fn cross_unit(i: usize, v: Vec3) -> Vec3 {
    match i {
        0 => Vec3::new(0.0, -v.z, v.y),
        1 => Vec3::new(v.z, 0.0, -v.x),
        _ => Vec3::new(-v.y, v.x, 0.0),
    }
}

/// A convex polygon of at most 8 vertices (a quad clipped by 4 planes) in the reference face's
/// coordinates `[u, v, h]` (along the face's two side axes and along its normal axis), with per-vertex
/// feature ids and the feature code of the edge leaving each vertex (incident edge 0..=3, side plane
/// p → 4 + p).
#[derive(Clone, Copy)]
struct Polygon {
    points: [[f32; 3]; 8],
    ids: [u8; 8],
    out_edge: [u8; 8],
    len: usize,
}

impl Polygon {
    const EMPTY: Polygon = Polygon {
        points: [[0.0; 3]; 8],
        ids: [0; 8],
        out_edge: [0; 8],
        len: 0,
    };

    #[inline]
    fn push(&mut self, p: [f32; 3], id: u8, out_edge: u8) {
        // A quad clipped by 4 planes has at most 8 vertices, so this never drops one.
        if self.len < 8 {
            self.points[self.len] = p;
            self.ids[self.len] = id;
            self.out_edge[self.len] = out_edge;
            self.len += 1;
        }
    }
}

/// Sutherland–Hodgman (Ericson 8.3.4) against the half-space `sign · p[K] ≤ limit`, side plane `plane`.
///
/// An edge crossing the plane yields a vertex with id `16 + 4·edge + plane`. After a leaving crossing the
/// outgoing edge runs along the plane (code 4 + plane); after an entering one it is the rest of the
/// crossed edge.
#[inline]
fn clip<const K: usize>(input: &Polygon, sign: f32, limit: f32, plane: u8, out: &mut Polygon) {
    out.len = 0;
    let n = input.len;
    let lerp = |a: [f32; 3], b: [f32; 3], f: f32| {
        [
            a[0] + (b[0] - a[0]) * f,
            a[1] + (b[1] - a[1]) * f,
            a[2] + (b[2] - a[2]) * f,
        ]
    };
    for a in 0..n {
        let b = if a + 1 == n { 0 } else { a + 1 };
        let (p_a, p_b) = (input.points[a], input.points[b]);
        let d_a = sign * p_a[K] - limit;
        let d_b = sign * p_b[K] - limit;
        let edge = input.out_edge[a];
        let crossing_id = 16 + 4 * edge + plane;
        if d_a <= 0.0 {
            out.push(p_a, input.ids[a], edge);
            if d_b > 0.0 {
                // d_a ≤ 0 < d_b, so d_a − d_b < 0: no division by zero.
                out.push(lerp(p_a, p_b, d_a / (d_a - d_b)), crossing_id, 4 + plane);
            }
        } else if d_b <= 0.0 {
            out.push(lerp(p_a, p_b, d_a / (d_a - d_b)), crossing_id, edge);
        }
    }
}

/// `(&buffers[current], &mut buffers[1 − current])`.
#[inline]
fn split_pair(buffers: &mut [Polygon; 2], current: usize) -> (&Polygon, &mut Polygon) {
    let [first, second] = buffers;
    if current == 0 {
        (first, second)
    } else {
        (second, first)
    }
}

/// Face contact in the reference box's frame: normal (from reference to incident) and points in that
/// frame; the caller maps them to world space. `inc_axes` and `t_inc` are the incident box's axes and
/// centre in the reference frame; `axis` is the reference face axis.
fn face_contact(
    half_ref: Vec3,
    half_inc: Vec3,
    inc_axes: &[Vec3; 3],
    t_inc: Vec3,
    axis: usize,
    ref_is_b: bool,
    margin: f32,
) -> Manifold {
    // Plain arrays: runtime indexing of glam vectors compiles to a branch per access.
    const NEXT: [usize; 3] = [1, 2, 0];
    let (a1, a2) = (NEXT[axis], NEXT[NEXT[axis]]);
    let (half_ref, half_inc, t_inc) = (half_ref.to_array(), half_inc.to_array(), t_inc.to_array());
    let inc_axes = inc_axes.map(|v| v.to_array());
    // Reference-face coordinates [u, v, h]: along the face's two side axes and along its normal.
    let face = |p: [f32; 3]| [p[a1], p[a2], p[axis]];
    let s = sign_nonzero(t_inc[axis]);

    // Incident face: the one whose normal is most anti-parallel to n = s e_axis.
    let along = Vec3::new(inc_axes[0][axis], inc_axes[1][axis], inc_axes[2][axis]);
    let (_, j) = max_component(along.abs());
    let s_inc = -sign_nonzero(inc_axes[j][axis]) * s;
    let (k, l) = (NEXT[j], NEXT[NEXT[j]]);
    let (c, n_j) = (face(t_inc), face(inc_axes[j]));
    let (u, v) = (face(inc_axes[k]), face(inc_axes[l]));
    let (h_j, h_k, h_l) = (s_inc * half_inc[j], half_inc[k], half_inc[l]);
    let mut center = [0.0; 3];
    let (mut du, mut dv) = ([0.0; 3], [0.0; 3]);
    for q in 0..3 {
        center[q] = c[q] + n_j[q] * h_j;
        du[q] = u[q] * h_k;
        dv[q] = v[q] * h_l;
    }
    let corner = |su: f32, sv: f32| {
        [
            center[0] + su * du[0] + sv * dv[0],
            center[1] + su * du[1] + sv * dv[1],
            center[2] + su * du[2] + sv * dv[2],
        ]
    };
    let mut buffers = [Polygon::EMPTY, Polygon::EMPTY];
    for (id, (su, sv)) in [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .into_iter()
        .enumerate()
    {
        buffers[0].push(corner(su, sv), id as u8, id as u8);
    }

    // Clip against the reference face's side planes |u| ≤ h_a1, |v| ≤ h_a2. A plane that no vertex
    // crosses is skipped: a box resting inside a larger face (or a floor) needs no clipping at all.
    let (limit_u, limit_v) = (half_ref[a1], half_ref[a2]);
    let mut current = 0;
    for (sign, limit, plane) in [(1.0, limit_u, 0), (-1.0, limit_u, 1)] {
        let (front, back) = split_pair(&mut buffers, current);
        if front.points[..front.len]
            .iter()
            .any(|p| sign * p[0] > limit)
        {
            clip::<0>(front, sign, limit, plane, back);
            current ^= 1;
        }
    }
    for (sign, limit, plane) in [(1.0, limit_v, 2), (-1.0, limit_v, 3)] {
        let (front, back) = split_pair(&mut buffers, current);
        if front.points[..front.len]
            .iter()
            .any(|p| sign * p[1] > limit)
        {
            clip::<1>(front, sign, limit, plane, back);
            current ^= 1;
        }
    }
    let poly = &buffers[current];

    // The features a polygon point lies on (see `clip` for its local code), each box's in its own
    // axes: the reference box's are `axis` (its face, side `s`), `a1` and `a2` (side planes 0, 1 and
    // 2, 3); the incident box's `j` (its face, side `s_inc`), `k` and `l` (its face's vertices
    // 0..=3 on the sides below, edge e from vertex e to e + 1).
    const VERTEX_K: [u32; 4] = [1, 0, 0, 1];
    const VERTEX_L: [u32; 4] = [1, 1, 0, 0];
    let side = |positive: bool, axis: usize| u32::from(positive) << axis;
    let (ref_positive, inc_positive) = (s > 0.0, s_inc > 0.0);
    let (ref_face, inc_face) = (
        Feature::face(axis, ref_positive),
        Feature::face(j, inc_positive),
    );
    let (ref_sides, inc_sides) = (side(ref_positive, axis), side(inc_positive, j));
    // Side plane p: the axis it bounds and whether on its positive side.
    let plane = |p: u8| (if p < 2 { a1 } else { a2 }, p % 2 == 0);
    let features = |local: u8| -> (u32, u32) {
        if local < 16 {
            let q = usize::from(local);
            let vertex = inc_sides | (VERTEX_K[q] << k) | (VERTEX_L[q] << l);
            return (ref_face, Feature::vertex(vertex));
        }
        let (edge, crossed) = ((local - 16) / 4, (local - 16) % 4);
        let (crossed_axis, crossed_positive) = plane(crossed);
        let ref_sides = ref_sides | side(crossed_positive, crossed_axis);
        if edge >= 4 {
            // Two side planes meet at a corner of the reference face.
            let (along_axis, along_positive) = plane(edge - 4);
            let corner = ref_sides | side(along_positive, along_axis);
            return (Feature::vertex(corner), inc_face);
        }
        let e = usize::from(edge);
        let inc_edge = if e % 2 == 0 {
            Feature::edge(k, inc_sides | (VERTEX_L[e] << l))
        } else {
            Feature::edge(l, inc_sides | (VERTEX_K[e] << k))
        };
        let ref_along = if crossed_axis == a1 { a2 } else { a1 };
        (Feature::edge(ref_along, ref_sides), inc_edge)
    };
    let id_of = |local: u8| {
        let (on_ref, on_inc) = features(local);
        if ref_is_b {
            Feature::pair(on_inc, on_ref)
        } else {
            Feature::pair(on_ref, on_inc)
        }
    };

    // Keep points at most `margin` above the reference face.
    let mut kept_points = [[0.0f32; 3]; 8];
    let mut kept_ids = [0u8; 8];
    let mut separations = [0.0f32; 8];
    let mut kept = 0;
    for (p, id) in poly.points[..poly.len].iter().zip(&poly.ids) {
        let separation = s * p[2] - half_ref[axis];
        if separation <= margin {
            kept_points[kept] = *p;
            kept_ids[kept] = *id;
            separations[kept] = separation;
            kept += 1;
        }
    }

    let mut face_points = [Vec2::ZERO; 8];
    let mut face_separations = [0.0f32; 8];
    for (i, p) in poly.points[..poly.len].iter().enumerate() {
        face_points[i] = Vec2::new(p[0], p[1]);
        face_separations[i] = s * p[2] - half_ref[axis];
    }
    let mut m = Manifold {
        normal: from_face(axis, 0.0, 0.0, s),
        patch: if kept > 1 {
            patch(&face_points[..poly.len], &face_separations[..poly.len])
        } else {
            Patch::default()
        },
        ..Manifold::default()
    };
    let picked = reduce_to_four(&kept_points[..kept], &separations);
    for &index in picked.iter().take(kept.min(4)) {
        let [pu, pv, ph] = kept_points[index];
        let separation = separations[index];
        // Midpoint between the incident point and its projection on the reference face.
        m.push(ContactPoint {
            point: from_face(axis, pu, pv, ph - 0.5 * separation * s),
            separation,
            id: id_of(kept_ids[index]),
        });
    }
    m
}

/// The point with face coordinates `[u, v, h]` (see [`Polygon`]) for reference face axis `axis`, in the
/// reference box's frame: component `axis` is `h`, the next two (cyclically) are `u` and `v`.
///
/// A `match` rather than stores through runtime indices into an array: those stores, read back as one
/// vector, stall store-to-load forwarding (measured: the hottest instructions of `face_contact`).
#[inline]
fn from_face(axis: usize, u: f32, v: f32, h: f32) -> Vec3 {
    match axis {
        0 => Vec3::new(h, u, v),
        1 => Vec3::new(v, h, u),
        _ => Vec3::new(u, v, h),
    }
}

/// Indices of at most 4 points spanning the largest area, after Gregorius (GDC 2015), with a first
/// point chosen for stability. Fewer than 5 points are kept as they are.
///
/// ```text
/// p0 = argmax  p·d − DEPTH_WEIGHT · separation   (d: fixed tangent of the reference face)
/// p1 = argmax |p − p0|²
/// p2 = argmax  area(p0, p1, p)     (signed: one side of the diagonal p0 p1)
/// p3 = argmin  area(p0, p1, p)     (the other side): p0 p1 is a diagonal of the kept quad
/// ```
/// Picking the deepest point first makes the kept set jump around when a box rests flat (all depths
/// equal to within noise), which loses warm starts; the score keeps the extreme point along a fixed
/// direction unless another point is clearly deeper. `d` is tilted off the face axes so a symmetric
/// polygon has no tie. Works on the face coordinates `[u, v]` of the polygon's points.
fn reduce_to_four(points: &[[f32; 3]], separations: &[f32; 8]) -> [usize; 4] {
    const DEPTH_WEIGHT: f32 = 4.0;
    const TANGENT: [f32; 2] = [1.0, 0.37];
    let len = points.len();
    if len <= 4 {
        return [0, 1, 2, 3];
    }
    let p = points;
    let mut i0 = 0;
    let mut best = f32::NEG_INFINITY;
    for i in 0..len {
        let score = p[i][0] * TANGENT[0] + p[i][1] * TANGENT[1] - DEPTH_WEIGHT * separations[i];
        if score > best {
            best = score;
            i0 = i;
        }
    }
    let (u0, v0) = (p[i0][0], p[i0][1]);
    let mut i1 = if i0 == 0 { 1 } else { 0 };
    let mut best = f32::NEG_INFINITY;
    for (i, q) in p[..len].iter().enumerate() {
        let d = (q[0] - u0) * (q[0] - u0) + (q[1] - v0) * (q[1] - v0);
        if i != i0 && d > best {
            best = d;
            i1 = i;
        }
    }
    let (du, dv) = (p[i1][0] - u0, p[i1][1] - v0);
    let area = |i: usize| du * (p[i][1] - v0) - dv * (p[i][0] - u0);
    // Valid defaults in case every area is NaN (non-finite input): never index out of bounds.
    let first_other = |skip: &[usize]| (0..len).find(|i| !skip.contains(i)).unwrap_or(0);
    let mut i2 = first_other(&[i0, i1]);
    let (mut most, mut least) = (f32::NEG_INFINITY, f32::INFINITY);
    for i in 0..len {
        if i == i0 || i == i1 {
            continue;
        }
        let a = area(i);
        if a > most {
            most = a;
            i2 = i;
        }
    }
    let mut i3 = first_other(&[i0, i1, i2]);
    for i in 0..len {
        if i == i0 || i == i1 || i == i2 {
            continue;
        }
        let a = area(i);
        if a < least {
            least = a;
            i3 = i;
        }
    }
    let mut picked = [i0, i1, i2, i3];
    picked.sort_unstable();
    picked
}

/// Edge–edge contact in A's frame for the edge axis e_i × b_j: closest points of the two supporting edges
/// (Ericson 5.1.9); one point at their midpoint. The caller maps it to world space.
fn edge_contact(
    half_a: Vec3,
    half_b: Vec3,
    b_axes: &[Vec3; 3],
    t: Vec3,
    i: usize,
    j: usize,
    margin: f32,
) -> Manifold {
    let l = cross_unit(i, b_axes[j]);
    let mut n = l / l.length();
    if n.dot(t) < 0.0 {
        n = -n;
    }
    // A's edge parallel to e_i that is farthest along n; B's edge parallel to b_j farthest along −n.
    let mut center_a = Vec3::ZERO;
    let mut sides_a = 0;
    let mut center_b = t;
    let mut sides_b = 0;
    for k in 0..3 {
        if k == i {
            continue;
        }
        let s = sign_nonzero(n[k]);
        center_a[k] = s * half_a[k];
        sides_a |= u32::from(s > 0.0) << k;
    }
    for (k, b_k) in b_axes.iter().enumerate() {
        if k == j {
            continue;
        }
        let s = -sign_nonzero(n.dot(*b_k));
        center_b += *b_k * (s * half_b[k]);
        sides_b |= u32::from(s > 0.0) << k;
    }
    let mut dir_a = Vec3::ZERO;
    dir_a[i] = half_a[i];
    let dir_b = b_axes[j] * half_b[j];
    let (p_a, p_b) = closest_points_on_segments(
        center_a - dir_a,
        center_a + dir_a,
        center_b - dir_b,
        center_b + dir_b,
    );
    let separation = (p_b - p_a).dot(n);
    let mut m = Manifold {
        normal: n,
        ..Manifold::default()
    };
    if separation <= margin {
        m.push(ContactPoint {
            point: 0.5 * (p_a + p_b),
            separation,
            id: Feature::pair(Feature::edge(i, sides_a), Feature::edge(j, sides_b)),
        });
    }
    m
}

/// Closest points of segments [p1, q1] and [p2, q2] (Ericson 5.1.9), robust to zero-length segments and
/// parallel segments.
fn closest_points_on_segments(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> (Vec3, Vec3) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let a = d1.length_squared();
    let e = d2.length_squared();
    let f = d2.dot(r);
    let tiny = f32::MIN_POSITIVE;
    let (s, t) = if a <= tiny && e <= tiny {
        (0.0, 0.0)
    } else if a <= tiny {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(r);
        if e <= tiny {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(d2);
            let denom = a * e - b * b;
            let s = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (b * s + f) / e;
            if t < 0.0 {
                ((-c / a).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    (p1 + d1 * s, p2 + d2 * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    fn cube() -> Vec3 {
        Vec3::splat(0.5)
    }

    #[test]
    fn resting_cube_gives_four_points_at_the_overlap_depth() {
        let a = Pose::IDENTITY;
        let b = Pose::from_position(Vec3::new(0.1, 0.99, 0.0));
        let m = box_box(cube(), &a, cube(), &b, 0.0);
        assert_eq!(m.len, 4);
        assert!((m.normal - Vec3::Y).length() < 1e-6);
        for p in m.points() {
            assert!((p.separation + 0.01).abs() < 1e-5);
            assert!((p.point.y - 0.495).abs() < 1e-5);
        }
    }

    #[test]
    fn separated_boxes_beyond_margin_give_nothing() {
        let b = Pose::from_position(Vec3::new(0.0, 1.2, 0.0));
        assert!(box_box(cube(), &Pose::IDENTITY, cube(), &b, 0.1).is_empty());
        assert_eq!(box_box(cube(), &Pose::IDENTITY, cube(), &b, 0.3).len, 4);
    }

    /// Box A's face for one call, B's for the other (each call prefers its own A within the axis
    /// bias): the same points, each under the same pair of features whichever face was clipped.
    /// B overhangs a corner of A, so the points are of all three kinds (a corner of each box over
    /// the other's face, and two edges crossing).
    #[test]
    fn a_point_keeps_its_id_when_the_reference_face_passes_to_the_other_box() {
        let a = Pose::IDENTITY;
        let turn = Quat::from_rotation_x(0.0004);
        let b = Pose::new(Vec3::new(0.3, 0.998, 0.2), turn);
        let on_a = box_box(cube(), &a, cube(), &b, 0.0);
        let on_b = box_box(cube(), &b, cube(), &a, 0.0);
        assert!(
            (on_a.normal - Vec3::Y).length() < 1e-6,
            "A's face: {on_a:?}"
        );
        assert!(
            (on_b.normal - turn * Vec3::NEG_Y).length() < 1e-6,
            "B's face: {on_b:?}"
        );
        assert_eq!(on_a.len, 4);
        assert_eq!(on_b.len, 4);
        let swapped = |id: u32| (id >> 6) | ((id & 0x3f) << 6);
        for p in on_a.points() {
            let twin = on_b
                .points()
                .iter()
                .find(|q| (q.point - p.point).length() < 1e-4)
                .unwrap_or_else(|| panic!("no twin of {p:?} in {on_b:?}"));
            assert_eq!(swapped(twin.id), p.id, "{p:?} and {twin:?}");
        }
    }

    #[test]
    fn closest_points_of_crossing_segments_meet_in_the_middle() {
        let (a, b) = closest_points_on_segments(
            Vec3::new(-1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0),
        );
        assert!(a.length() < 1e-6);
        assert!((b - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn clipping_a_larger_incident_face_gives_the_reference_corners() {
        let big = Vec3::splat(2.0);
        let b = Pose::new(Vec3::new(0.0, 2.45, 0.0), Quat::from_rotation_y(0.4));
        let m = box_box(cube(), &Pose::IDENTITY, big, &b, 0.0);
        assert_eq!(m.len, 4);
        for p in m.points() {
            assert!((p.point.x.abs() - 0.5).abs() < 1e-5);
            assert!((p.point.z.abs() - 0.5).abs() < 1e-5);
            assert!((p.separation + 0.05).abs() < 1e-5);
        }
    }
}
