//! The rows only a manifold of two or more points has, stored once per lane group in one array whose
//! length depends on the point count: the spread row, the twist row, and the couplings between the
//! points (see "The spread row" in `contact_solver`). Each row is reached by name ([`MultiRow`]), never
//! by a computed index.

use std::ops::{Index, IndexMut};

use glam::Vec4;

/// How many rows a manifold of `points` points has: none for one point (no spread row, no twist), else
/// four scalar rows, two per point and one per pair of points.
pub(crate) const fn multi_row_count(points: usize) -> usize {
    if points == 1 {
        0
    } else {
        4 + 2 * points + points * (points - 1) / 2
    }
}

/// One row of [`MultiRows`].
#[derive(Clone, Copy, Debug)]
pub(crate) enum MultiRow {
    /// The spread row's effective mass, kg.
    MeanMass,
    /// The twist row's effective mass, kg·m².
    TwistMass,
    /// The twist row's radius (the points' mean distance from their centroid), m.
    TwistRadius,
    /// The number of points (0 in padding lanes).
    Count,
    /// Point i's K_ii/len: its weight in the spread row's residual.
    SpreadWeight(usize),
    /// Point i's Σ_j K_ij/len: how the spread row's increment moves its normal velocity.
    MeanResponse(usize),
    /// K_ij between points i < j, 1/kg (stored once per pair).
    Coupling(usize, usize),
}

/// The multi-point rows of four manifolds of at most `P` points, `M` = [`multi_row_count`]`(P)` of
/// them (a stable const generic cannot compute M from P, so both are given and checked to agree).
#[derive(Clone, Copy, Debug)]
#[repr(transparent)]
pub(crate) struct MultiRows<const P: usize, const M: usize>([Vec4; M]);

impl<const P: usize, const M: usize> MultiRows<P, M> {
    /// All rows zero.
    pub(crate) const ZERO: Self = {
        assert!(M == multi_row_count(P), "M must be multi_row_count(P)");
        Self([Vec4::ZERO; M])
    };

    /// Where `row` lives in the array: the scalar rows, then per point the spread weights and the mean
    /// responses, then the pairs row by row, (0, 1), (0, 2), …, (1, 2), ….
    #[inline(always)]
    const fn slot(row: MultiRow) -> usize {
        match row {
            MultiRow::MeanMass => 0,
            MultiRow::TwistMass => 1,
            MultiRow::TwistRadius => 2,
            MultiRow::Count => 3,
            MultiRow::SpreadWeight(i) => 4 + i,
            MultiRow::MeanResponse(i) => 4 + P + i,
            MultiRow::Coupling(i, j) => 4 + 2 * P + i * P - i * (i + 1) / 2 + (j - i - 1),
        }
    }
}

impl<const P: usize, const M: usize> Index<MultiRow> for MultiRows<P, M> {
    type Output = Vec4;

    #[inline(always)]
    fn index(&self, row: MultiRow) -> &Vec4 {
        &self.0[Self::slot(row)]
    }
}

impl<const P: usize, const M: usize> IndexMut<MultiRow> for MultiRows<P, M> {
    #[inline(always)]
    fn index_mut(&mut self, row: MultiRow) -> &mut Vec4 {
        &mut self.0[Self::slot(row)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row of a four-point manifold has a slot of its own, and together they fill the array.
    #[test]
    fn the_rows_of_four_points_fill_their_array_once_each() {
        const P: usize = 4;
        const M: usize = multi_row_count(P);
        let mut seen = [0; M];
        let mut rows = vec![
            MultiRow::MeanMass,
            MultiRow::TwistMass,
            MultiRow::TwistRadius,
            MultiRow::Count,
        ];
        for i in 0..P {
            rows.push(MultiRow::SpreadWeight(i));
            rows.push(MultiRow::MeanResponse(i));
            for j in i + 1..P {
                rows.push(MultiRow::Coupling(i, j));
            }
        }
        for row in rows {
            seen[MultiRows::<P, M>::slot(row)] += 1;
        }
        assert_eq!(seen, [1; M]);
        assert_eq!(multi_row_count(2), 9);
        assert_eq!(multi_row_count(1), 0);
    }
}
