//! The tree's solve against a dense solve of the same system, its fallbacks, and its responses.

use glam::{Quat, Vec3};

use super::*;
use crate::util::SplitMix64;

/// A dynamic body of random mass and inertia (mass ratios up to 100), turned at random.
fn motion(rng: &mut SplitMix64) -> SolverMotion {
    let mut scale = || 10f32.powf(rng.next_signed());
    let (inv_mass, moments) = (scale(), Vec3::new(scale(), scale(), scale()));
    let turn = Quat::from_euler(
        glam::EulerRot::XYZ,
        rng.next_signed() * 3.0,
        rng.next_signed() * 3.0,
        rng.next_signed() * 3.0,
    );
    // The tree weighs a body at its rotation, from its principal moments.
    SolverMotion {
        rotation: turn,
        inertia_local: moments.recip(),
        inv_mass,
        inv_inertia: inv_inertia_world(turn, moments),
        ..SolverMotion::DUMMY
    }
}

fn random_rows(rng: &mut SplitMix64, (a, b): (u32, u32), rows: usize) -> TreeRows {
    let mut r = TreeRows::new(a, b);
    let mut v = || Vec3::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
    for _ in 0..rows {
        let (la, aa, lb, ab, error) = (v(), v(), v(), v(), v().x);
        r.push(la, aa, lb, ab, error);
    }
    r
}

/// A random system: `bodies` solver bodies (the dummy first) of random masses and velocities, and
/// random rows, `counts[k]` of them, for each joint of `ends`.
fn random_system(
    rng: &mut SplitMix64,
    ends: &[(u32, u32)],
    counts: &[usize],
    bodies: usize,
) -> (Vec<SolverMotion>, Vec<TreeRows>, Vec<SolverBody>) {
    let motions: Vec<SolverMotion> = std::iter::once(SolverMotion::DUMMY)
        .chain((1..bodies).map(|_| motion(rng)))
        .collect();
    let rows: Vec<TreeRows> = ends
        .iter()
        .zip(counts)
        .map(|(&e, &n)| random_rows(rng, e, n))
        .collect();
    let mut start = vec![SolverBody::DUMMY; bodies];
    for b in &mut start[1..] {
        let mut v = || Vec3A::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
        (b.v, b.w) = (v(), v());
    }
    (motions, rows, start)
}

/// The solution of the dense system `h x = y` by Gaussian elimination with partial pivoting.
fn dense_solve(mut h: Vec<Vec<f64>>, mut y: Vec<f64>) -> Vec<f64> {
    let n = y.len();
    for col in 0..n {
        let p = (col..n)
            .max_by(|&p, &q| h[p][col].abs().total_cmp(&h[q][col].abs()))
            .unwrap();
        h.swap(col, p);
        y.swap(col, p);
        for r in col + 1..n {
            let f = h[r][col] / h[col][col];
            for c in col..n {
                h[r][c] -= f * h[col][c];
            }
            y[r] -= f * y[col];
        }
    }
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|c| h[i][c] * x[c]).sum();
        x[i] = (y[i] - s) / h[i][i];
    }
    x
}

/// The tree's solve of branching trees (joints of 1, 3, 5 and 6 rows, to the world at either
/// end, free bodies among them, a joint closing a loop left out) is the dense solve of the
/// same system, H = [M −Jᵀ; −J −ε·K], to the f32 the answer is given in.
#[test]
fn the_tree_solves_the_dense_system() {
    let mut rng = SplitMix64(7);
    let ends: Vec<(u32, u32)> = vec![
        (0, 1),
        (1, 2),
        (2, 3),
        (2, 4),
        (4, 5),
        (5, 0),
        (3, 6),
        (7, 6),
        (7, 4), // closes the loop 2–3–6–7–4
        (8, 0),
        (8, 9),
    ];
    let counts = [3, 5, 3, 6, 1, 3, 3, 5, 3, 6, 1];
    let bodies = 10;
    let (motions, rows, start) = random_system(&mut rng, &ends, &counts, bodies);
    let mut tree = JointTree::default();
    let in_tree = tree.shape(&ends, bodies).to_vec();
    assert_eq!(in_tree.iter().filter(|&&t| !t).count(), 1);
    assert!(!in_tree[8]);
    tree.factor(&rows, &motions, true);
    let mut solved = start.clone();
    let mut impulses = vec![[0.0f32; MAX]; ends.len()];
    tree.solve(&rows, 1.0, &mut solved, &mut impulses, false);

    // The dense system: 6 unknowns per body 1.., then each tree joint's rows.
    let joints: Vec<usize> = (0..ends.len()).filter(|&k| in_tree[k]).collect();
    let mut offset = vec![0; ends.len()];
    let mut n = 6 * (bodies - 1);
    for &k in &joints {
        offset[k] = n;
        n += counts[k];
    }
    let mut h = vec![vec![0.0; n]; n];
    let mut y = vec![0.0; n];
    for b in 1..bodies {
        let mut d = [[0.0; MAX]; MAX];
        body_mass(&motions[b], &mut d);
        for i in 0..6 {
            for j in 0..6 {
                h[6 * (b - 1) + i][6 * (b - 1) + j] = d[i][j];
            }
        }
    }
    for &k in &joints {
        let r = &rows[k];
        let o = offset[k];
        let mut d = [[0.0; MAX]; MAX];
        let share = [r.a, r.b].map(|e| if e == 0 { 0.0 } else { COMPLIANCE });
        joint_block(r, &motions, share, &mut d);
        for i in 0..r.rows {
            for j in 0..r.rows {
                h[o + i][o + j] = d[i][j];
            }
            y[o + i] = r.error[i] as f64;
        }
        for (end, j) in [(r.a, &r.j_a), (r.b, &r.j_b)] {
            if end == 0 {
                continue;
            }
            let v = velocity(&start, end);
            let ob = 6 * (end as usize - 1);
            for i in 0..r.rows {
                for c in 0..6 {
                    h[o + i][ob + c] = -j[i][c];
                    h[ob + c][o + i] = -j[i][c];
                    y[o + i] += j[i][c] * v[c];
                }
            }
        }
    }
    let x = dense_solve(h, y);

    let largest = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let close = |got: f64, want: f64| (got - want).abs() <= 1e-5 * largest;
    for b in 1..bodies {
        let (before, after) = (velocity(&start, b as u32), velocity(&solved, b as u32));
        for c in 0..6 {
            let want = x[6 * (b - 1) + c];
            assert!(close(after[c] - before[c], want), "body {b}: Δv {c}");
        }
    }
    for &k in &joints {
        for i in 0..counts[k] {
            let want = x[offset[k] + i];
            assert!(close(impulses[k][i] as f64, want), "joint {k}: row {i}");
        }
    }
}

/// A joint with a row twice over: its block is singular, the factorisation falls back to
/// Gauss–Jordan, and the repeated row gets no impulse of its own; the joint still holds.
#[test]
fn a_redundant_row_gets_zero() {
    let mut rng = SplitMix64(11);
    let motions = [SolverMotion::DUMMY, motion(&mut rng)];
    let mut rows = random_rows(&mut rng, (0, 1), 3);
    rows.j_b[3] = rows.j_b[0];
    rows.error[3] = rows.error[0];
    rows.rows = 4;
    let mut bodies = [SolverBody::DUMMY; 2];
    bodies[1].v = Vec3A::new(0.3, -0.2, 0.5);
    bodies[1].w = Vec3A::new(-0.4, 0.1, 0.2);
    let mut tree = JointTree::default();
    tree.shape(&[(0, 1)], 2);
    tree.factor(std::slice::from_ref(&rows), &motions, true);
    let mut impulses = [[0.0f32; MAX]];
    tree.solve(
        std::slice::from_ref(&rows),
        1.0,
        &mut bodies,
        &mut impulses,
        false,
    );
    let node = tree.joint_node[0] as usize;
    assert_eq!(tree.nodes[node].factor.form, Form::Inverse);
    let impulse = impulses[0];
    assert!(impulse.iter().all(|i| i.is_finite()), "{impulse:?}");
    assert!(impulse[0] == 0.0 || impulse[3] == 0.0, "{impulse:?}");
    let v = velocity(&bodies, 1);
    for row in 0..4 {
        let speed: f64 = (0..6).map(|c| rows.j_b[row][c] * v[c]).sum();
        assert!(
            (speed + rows.error[row] as f64).abs() < 1e-5,
            "row {row}: {speed}"
        );
    }
}

/// Redundant rows on both joints of a contracted body (world – 1 – 2 – 3, body 2 contracted,
/// its joints' blocks falling back to Gauss–Jordan): every row still holds after the solve.
#[test]
fn redundant_rows_through_a_contracted_body_hold() {
    let mut rng = SplitMix64(13);
    let motions: Vec<SolverMotion> = std::iter::once(SolverMotion::DUMMY)
        .chain((1..4).map(|_| motion(&mut rng)))
        .collect();
    let ends = [(0, 1), (1, 2), (2, 3)];
    let mut rows: Vec<TreeRows> = ends.iter().map(|&e| random_rows(&mut rng, e, 3)).collect();
    for r in &mut rows[1..] {
        (r.j_a[3], r.j_b[3], r.error[3]) = (r.j_a[1], r.j_b[1], r.error[1]);
        r.rows = 4;
    }
    let mut bodies = vec![SolverBody::DUMMY; 4];
    for b in &mut bodies[1..] {
        let mut v = || Vec3A::new(rng.next_signed(), rng.next_signed(), rng.next_signed());
        (b.v, b.w) = (v(), v());
    }
    let mut tree = JointTree::default();
    tree.shape(&ends, 4);
    tree.factor(&rows, &motions, true);
    let body = &tree.nodes[tree.body_node[2] as usize];
    assert_ne!(body.contracted, NONE, "body 2 is contracted");
    for k in 1..3 {
        let node = tree.joint_node[k] as usize;
        assert_eq!(tree.nodes[node].factor.form, Form::Inverse, "joint {k}");
    }
    let mut impulses = vec![[0.0f32; MAX]; 3];
    tree.solve(&rows, 1.0, &mut bodies, &mut impulses, false);
    assert!(
        impulses.iter().flatten().all(|i| i.is_finite()),
        "{impulses:?}"
    );
    for (k, r) in rows.iter().enumerate() {
        let (va, vb) = (velocity(&bodies, r.a), velocity(&bodies, r.b));
        for row in 0..r.rows {
            let speed: f64 = (0..6)
                .map(|c| r.j_a[row][c] * va[c] + r.j_b[row][c] * vb[c])
                .sum();
            assert!(
                (speed + r.error[row] as f64).abs() < 1e-4,
                "joint {k}, row {row}: {speed}"
            );
        }
    }
}

/// What an untouched tree's skipped relax pass and warm start rest on (see "Trees nothing else
/// touches"): a relax solve, a velocity change that both ways see (gravity's), a warm start along
/// the rows and the biased solve leave the bodies where the change and the biased solve alone
/// leave them, with the same impulses in all. (Measured 4.0e-6 of the largest velocity and 5.4e-6
/// of an impulse, f32 rounding; allowed 2e-5.) And a solve that skips the untouched trees leaves
/// their bodies and impulses alone and solves the others as a full solve does.
#[test]
fn an_untouched_trees_relax_pass_is_left_to_the_next_biased_pass() {
    let mut rng = SplitMix64(5);
    // Two trees: a chain hung from the world (bodies 1 to 3) and a free one (4 to 6).
    let ends: Vec<(u32, u32)> = vec![(0, 1), (1, 2), (2, 3), (4, 5), (5, 6)];
    let counts = [3, 5, 3, 6, 3];
    let bodies = 7;
    let (motions, rows, start) = random_system(&mut rng, &ends, &counts, bodies);
    let mut tree = JointTree::default();
    tree.shape(&ends, bodies);
    tree.factor(&rows, &motions, true);
    let gravity = |bodies: &mut [SolverBody]| {
        for b in &mut bodies[1..] {
            b.v += Vec3A::new(0.0, -0.16, 0.0);
        }
    };
    let no_impulses = || vec![[0.0f32; MAX]; ends.len()];
    // A warm start: M⁻¹Jᵀλ for each joint's impulses λ.
    let warm: Vec<[f32; MAX]> = (0..ends.len())
        .map(|_| std::array::from_fn(|_| rng.next_signed()))
        .collect();
    let warm_start = |bodies: &mut [SolverBody]| {
        for (r, lambda) in rows.iter().zip(&warm) {
            let lambda = lambda.map(f64::from);
            for (end, j) in [(r.a, &r.j_a), (r.b, &r.j_b)] {
                if end != 0 {
                    let mut t = [0.0; MAX];
                    with_rows!(r.rows, add_transposed(j, r.point, &lambda, &mut t));
                    let m = &motions[end as usize];
                    let [lin, ang] =
                        [0, 3].map(|i| Vec3::new(t[i] as f32, t[i + 1] as f32, t[i + 2] as f32));
                    bodies[end as usize].v += Vec3A::from(m.inv_mass * lin);
                    bodies[end as usize].w += m.inv_inertia * Vec3A::from(ang);
                }
            }
        }
    };

    let (mut relaxed, mut relax, mut biased) = (start.clone(), no_impulses(), no_impulses());
    tree.solve(&rows, 0.0, &mut relaxed, &mut relax, false);
    gravity(&mut relaxed);
    warm_start(&mut relaxed);
    tree.solve(&rows, 1.0, &mut relaxed, &mut biased, false);
    let (mut direct, mut alone) = (start.clone(), no_impulses());
    gravity(&mut direct);
    tree.solve(&rows, 1.0, &mut direct, &mut alone, false);
    let largest = direct[1..]
        .iter()
        .flat_map(|b| [b.v, b.w])
        .fold(0.0f32, |m, v| m.max(v.abs().max_element()));
    for b in 1..bodies {
        let (got, want) = (&relaxed[b], &direct[b]);
        let off = (got.v - want.v)
            .abs()
            .max((got.w - want.w).abs())
            .max_element();
        assert!(off <= 2e-5 * largest, "body {b}: {off} of {largest}");
    }
    for k in 0..ends.len() {
        for i in 0..counts[k] {
            let (got, want) = (relax[k][i] + warm[k][i] + biased[k][i], alone[k][i]);
            assert!(
                (got - want).abs() <= 2e-5 * want.abs().max(1.0),
                "joint {k}: row {i}"
            );
        }
    }

    tree.mark_untouched(|b| b <= 3, |_| false);
    let (mut skipped, mut impulses) = (start.clone(), no_impulses());
    tree.solve(&rows, 1.0, &mut skipped, &mut impulses, true);
    let (mut full, mut all) = (start.clone(), no_impulses());
    tree.solve(&rows, 1.0, &mut full, &mut all, false);
    for b in 1..bodies {
        let want = if b <= 3 { &full[b] } else { &start[b] };
        assert_eq!((skipped[b].v, skipped[b].w), (want.v, want.w), "body {b}");
    }
    assert_eq!(impulses[..3], all[..3]);
    assert_eq!(impulses[3..], no_impulses()[3..]);
}

/// Rows that hold a point (`TreeRows::point`: linear parts ∓e_k on A and ±e_k on B in the first
/// three rows, none after, and no k-th angular component in row k) are factored and solved with
/// those exact zeros left out, and the answer is the general products' to the bit.
#[test]
fn point_rows_skip_only_exact_zeros() {
    let mut rng = SplitMix64(11);
    let ends: Vec<(u32, u32)> = vec![(0, 1), (1, 2), (2, 3), (2, 4), (4, 5), (5, 0), (6, 5)];
    let counts = [3, 5, 3, 6, 3, 5, 1];
    let bodies = 7;
    let (motions, mut rows, start) = random_system(&mut rng, &ends, &counts, bodies);
    // A point row k < 3 is (−e_k, −r_a × e_k) on A and (e_k, r_b × e_k) on B: no linear part past
    // the third row, and no k-th angular component.
    for r in rows.iter_mut().filter(|r| r.rows >= 3) {
        for k in 0..r.rows {
            let e: [f64; 3] = std::array::from_fn(|i| if i == k { 1.0 } else { 0.0 });
            r.j_a[k][..3].copy_from_slice(&e.map(|x| -x));
            r.j_b[k][..3].copy_from_slice(&e);
            if k < 3 {
                r.j_a[k][3 + k] = 0.0;
                r.j_b[k][3 + k] = 0.0;
            }
        }
        r.point = true;
    }
    let general: Vec<TreeRows> = rows
        .iter()
        .map(|r| TreeRows { point: false, ..*r })
        .collect();
    let solved = |rows: &[TreeRows]| {
        let mut tree = JointTree::default();
        tree.shape(&ends, bodies);
        tree.factor(rows, &motions, true);
        let (mut bodies, mut impulses) = (start.clone(), vec![[0.0f32; MAX]; ends.len()]);
        tree.solve(rows, 60.0, &mut bodies, &mut impulses, false);
        let bits = |v: Vec3A| v.to_array().map(f32::to_bits);
        let velocities: Vec<_> = bodies.iter().map(|b| (bits(b.v), bits(b.w))).collect();
        let impulses: Vec<_> = impulses.iter().map(|i| i.map(f32::to_bits)).collect();
        (velocities, impulses)
    };
    assert_eq!(solved(&rows), solved(&general));
}
