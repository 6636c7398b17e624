//! The least-squares core shared by the surface and the trivariate fits (H §4.2 step (iv),
//! H §4.3): normal equations `UᵀU c = Uᵀd` (H (4.29)) solved by Cholesky, refused when the
//! condition number of `UᵀU` (from its symmetric eigenvalues) exceeds a bound. (Solving
//! through nalgebra's eigenvectors instead lost up to 10 % on nearly repeated eigenvalues —
//! the 5-valent vertices of an icosphere.)
//!
//! The condition number `λ_max/λ_min` of `UᵀU` does not change when the platelet is scaled
//! (all entries scale like h⁴), so the "undetermined" rule is scale-free (notes C.2, C.3);
//! an absolute determinant threshold would not be.

use nalgebra::{SMatrix, SVector};

/// Accumulated normal equations of an N-coefficient linear least-squares fit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Normal<const N: usize> {
    ata: SMatrix<f64, N, N>,
    atd: SVector<f64, N>,
    rows: usize,
}

impl<const N: usize> Normal<N> {
    pub(crate) fn new() -> Self {
        Normal {
            ata: SMatrix::zeros(),
            atd: SVector::zeros(),
            rows: 0,
        }
    }
    /// Adds the equation `row · c = d`.
    #[inline]
    pub(crate) fn add(&mut self, row: [f64; N], d: f64) {
        for i in 0..N {
            for j in i..N {
                self.ata[(i, j)] += row[i] * row[j];
            }
            self.atd[i] += row[i] * d;
        }
        self.rows += 1;
    }
    /// The least-squares solution, or `None` when fewer than N rows were added or
    /// `cond(UᵀU) > max_cond` (also when it is not finite).
    pub(crate) fn solve(&self, max_cond: f64) -> Option<SVector<f64, N>> {
        if self.rows < N {
            return None;
        }
        // (const-generic matrices have no eigen-solver in nalgebra: a dynamic copy)
        let m = nalgebra::DMatrix::from_fn(N, N, |i, j| self.ata[(i.min(j), i.max(j))]);
        let eig = m.clone().symmetric_eigenvalues();
        let lmax = eig.max();
        let lmin = eig.min();
        // written so that NaN refuses too
        if !(lmax.is_finite() && lmin > 0.0 && lmin * max_cond >= lmax) {
            return None;
        }
        // the solution by Cholesky (the eigenvectors of nearly repeated eigenvalues are not
        // accurate enough to solve with)
        let c = m
            .cholesky()?
            .solve(&nalgebra::DVector::from_column_slice(self.atd.as_slice()));
        Some(SVector::from_fn(|i, _| c[i]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_fit_and_rank_deficiency() {
        let mut n = Normal::<3>::new();
        for (u, v) in [(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (-1.0, 2.0)] {
            let row = [u * u, u * v, v * v];
            n.add(row, 3.0 * u * u - 2.0 * u * v + 0.5 * v * v);
        }
        let c = n.solve(1e10).unwrap();
        assert!((c - SVector::<f64, 3>::new(3.0, -2.0, 0.5)).norm() < 1e-12);
        let mut d = Normal::<3>::new();
        for u in [1.0, 2.0, 3.0] {
            d.add([u * u, 0.0, 0.0], 1.0);
        }
        assert!(d.solve(1e10).is_none());
    }
}
