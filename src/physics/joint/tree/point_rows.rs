//! The exact zeros of rows that hold a point (`TreeRows::point`: ball, hinge and weld joints),
//! left out of the dot products with J. Row k < 3 of such a joint is (−e_k, −r_a × e_k) on A and
//! (e_k, r_b × e_k) on B: one linear column that is not zero, and no k-th angular component; its
//! further rows have no linear part. Every sum leaves out only terms that are exactly zero, so it
//! is the full sum to the bit (`point_rows_skip_only_exact_zeros`).

/// `Σ_{k<3} a[k]·b[k]` for `a`, row `a_row` of one Jacobian, and `b`, row `b_row` of another (or
/// that row through a mass), with the exact zeros of point rows left out (`a_point`, `b_point`:
/// whether each Jacobian's rows hold a point). The lone product is added to 0.0 as the full sum
/// adds its first one, so a zero comes out with the same sign.
#[inline(always)]
pub(super) fn linear_dot(
    a: &[f64; 6],
    a_row: usize,
    a_point: bool,
    b: &[f64],
    b_row: usize,
    b_point: bool,
) -> f64 {
    match (a_point, b_point) {
        (true, _) => {
            if a_row < 3 {
                0.0 + a[a_row] * b[a_row]
            } else {
                0.0
            }
        }
        (false, true) => {
            if b_row < 3 {
                0.0 + a[b_row] * b[b_row]
            } else {
                0.0
            }
        }
        (false, false) => (0..3).map(|k| a[k] * b[k]).sum(),
    }
}

/// `Σ_{k<3} a[k]·row[3 + k]` for `row`, row `r` of a Jacobian, with its angular part's exact zero
/// (component r, for r < 3) left out where its rows hold a point (`point`). The sum starts at
/// −0.0, as `Sum`'s does.
#[inline(always)]
pub(super) fn angular_dot(a: &[f64; 3], row: &[f64; 6], r: usize, point: bool) -> f64 {
    let mut sum = -0.0;
    for k in 0..3 {
        if !(point && k == r) {
            sum += a[k] * row[3 + k];
        }
    }
    sum
}
