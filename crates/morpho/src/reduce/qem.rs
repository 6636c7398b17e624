//! Quadric error memory (Garland & Heckbert 1997): a candidate new point for
//! [`super::Order::ErrorLevels`] — **an extension, not Hamann's** (the thesis places the new
//! point by the bivariate or implicit fit only; `Order::Hamann` never uses this module).
//!
//! Every input triangle contributes the squared distance to its plane, weighted by its area,
//! to each of its corners: `Q(x) = Σ w (n·x + d)²`, stored as `xᵀAx + 2bᵀx + c`. A removal
//! merges the three removed corners into the new point, whose quadric is then the sum of
//! theirs: it measures the squared distances to the planes of the input triangles around
//! every vertex that the new point has absorbed (the memory QEM decimators keep).
//!
//! The QEM point minimises `Q`. `A` is symmetric positive semi-definite; on a flat patch it
//! has rank 1 and on a crease rank 2, where the minimisers form a plane or a line. The point
//! is computed as `r + Σ_i (−vᵢ·(A r + b)/λᵢ) vᵢ` over the eigenpairs with
//! `λᵢ > REL_RANK · λ_max` ([`QemQuadric::minimizer`]): the exact minimiser when `A` is
//! well conditioned, otherwise the minimiser of `Q` closest to the reference `r` within the
//! well-determined directions (a truncated pseudo-inverse about `r`). The engine passes the
//! fitted point as `r`, so on a crease the fit is moved onto the crease, on a plane onto it.
//!
//! The point is only a candidate: the engine evaluates it by the same tracker and with the
//! same removability, fold, degeneracy, reach and self-intersection tests as the fitted
//! point and the corners, and keeps it only if it moves the input's vertices least.

use crate::geom::vec::{cross, norm, sub};
use nalgebra::{Matrix3, Vector3};

/// Eigenvalues below this fraction of the largest are treated as zero (rank loss).
pub(crate) const REL_RANK: f64 = 1e-3;

/// `xᵀAx + 2bᵀx + c` with `A` symmetric: `[a00, a01, a02, a11, a12, a22, b0, b1, b2, c]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct QemQuadric(pub [f64; 10]);

impl QemQuadric {
    /// `w (n·x + d)²` for the plane through `p` with unit normal `n` (`d = −n·p`).
    pub fn plane(n: [f64; 3], p: [f64; 3], w: f64) -> QemQuadric {
        let d = -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]);
        QemQuadric([
            w * n[0] * n[0],
            w * n[0] * n[1],
            w * n[0] * n[2],
            w * n[1] * n[1],
            w * n[1] * n[2],
            w * n[2] * n[2],
            w * n[0] * d,
            w * n[1] * d,
            w * n[2] * d,
            w * d * d,
        ])
    }

    /// The area-weighted plane quadric of triangle `t` (zero for a degenerate one).
    pub fn of_triangle(t: [[f64; 3]; 3]) -> QemQuadric {
        let c = cross(sub(t[1], t[0]), sub(t[2], t[0]));
        let len = norm(c);
        if !(len > 0.0 && len.is_finite()) {
            return QemQuadric::default();
        }
        QemQuadric::plane(c.map(|x| x / len), t[0], 0.5 * len)
    }

    pub fn add(&mut self, o: &QemQuadric) {
        for (a, b) in self.0.iter_mut().zip(o.0.iter()) {
            *a += b;
        }
    }

    fn a(&self) -> Matrix3<f64> {
        let q = &self.0;
        Matrix3::new(q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5])
    }

    /// `Q(x)` (the tests' oracle).
    #[cfg(test)]
    pub fn eval(&self, x: [f64; 3]) -> f64 {
        let v = Vector3::from(x);
        let b = Vector3::new(self.0[6], self.0[7], self.0[8]);
        (v.transpose() * self.a() * v)[0] + 2.0 * b.dot(&v) + self.0[9]
    }

    /// The minimiser of `Q` closest to `r` within the directions whose eigenvalue exceeds
    /// [`REL_RANK`] of the largest (see the module documentation); `None` when `A` is zero or
    /// not finite. Computed about `r` (the gradient there is `2(A r + b)`), so it does not
    /// lose digits to coordinates far from the origin beyond those of `Q`'s own terms.
    pub fn minimizer(&self, r: [f64; 3]) -> Option<[f64; 3]> {
        if !self.0.iter().all(|x| x.is_finite()) {
            return None;
        }
        let a = self.a();
        let rv = Vector3::from(r);
        let g = a * rv + Vector3::new(self.0[6], self.0[7], self.0[8]);
        let eig = a.symmetric_eigen();
        let lmax = eig.eigenvalues.iter().fold(0.0f64, |m, &l| m.max(l));
        if lmax <= 0.0 {
            return None;
        }
        let mut x = rv;
        for i in 0..3 {
            let l = eig.eigenvalues[i];
            if l > REL_RANK * lmax {
                let v = eig.eigenvectors.column(i);
                x -= v * (v.dot(&g) / l);
            }
        }
        let p = [x[0], x[1], x[2]];
        p.iter().all(|c| c.is_finite()).then_some(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::util::Rng;

    /// A coordinate uniform in [−1, 1).
    fn lcg(s: &mut Rng) -> f64 {
        2.0 * s.unit() - 1.0
    }

    fn unit(v: [f64; 3]) -> [f64; 3] {
        let l = norm(v);
        v.map(|x| x / l)
    }

    /// Full rank: the minimiser is the exact one (no perturbation lowers Q, and it does not
    /// depend on the reference); three planes: their intersection point.
    #[test]
    fn full_rank_minimizer_is_the_minimum() {
        let mut s = Rng::new(7);
        for _ in 0..200 {
            let mut q = QemQuadric::default();
            for _ in 0..6 {
                let n = unit([lcg(&mut s), lcg(&mut s), lcg(&mut s)]);
                let p = [lcg(&mut s), lcg(&mut s), lcg(&mut s)].map(|x| 3.0 + x);
                q.add(&QemQuadric::plane(n, p, 0.5 + lcg(&mut s).abs()));
            }
            let r1 = [lcg(&mut s), lcg(&mut s), lcg(&mut s)];
            let x = q.minimizer(r1).unwrap();
            let y = q.minimizer([10.0, -4.0, 2.0]).unwrap();
            let eig = q.a().symmetric_eigen();
            let lmax = eig.eigenvalues.max();
            if eig.eigenvalues.min() < 10.0 * REL_RANK * lmax {
                continue; // (nearly) rank-deficient draws are the next test's
            }
            for i in 0..3 {
                assert!((x[i] - y[i]).abs() < 1e-9, "{x:?} {y:?}");
            }
            let fx = q.eval(x);
            for _ in 0..20 {
                let d = [lcg(&mut s), lcg(&mut s), lcg(&mut s)].map(|c| 1e-3 * c);
                let z = [x[0] + d[0], x[1] + d[1], x[2] + d[2]];
                assert!(q.eval(z) >= fx - 1e-12, "{} < {fx}", q.eval(z));
            }
        }
        // three coordinate planes through (1, 2, 3)
        let mut q = QemQuadric::default();
        for n in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            q.add(&QemQuadric::plane(n, [1.0, 2.0, 3.0], 1.0));
        }
        let x = q.minimizer([0.0; 3]).unwrap();
        assert!(x
            .iter()
            .zip([1.0, 2.0, 3.0])
            .all(|(a, b)| (a - b).abs() < 1e-12));
    }

    /// Rank loss: one plane → the reference projected onto it; two planes (a crease) → the
    /// reference projected onto their line; nothing → None.
    #[test]
    fn rank_loss_projects_the_reference() {
        let mut q = QemQuadric::default();
        q.add(&QemQuadric::plane([0.0, 0.0, 1.0], [5.0, 5.0, 2.0], 3.0));
        let x = q.minimizer([0.3, -0.7, 9.0]).unwrap();
        assert!((x[0] - 0.3).abs() < 1e-12 && (x[1] + 0.7).abs() < 1e-12);
        assert!((x[2] - 2.0).abs() < 1e-12);
        // crease: the planes z = 0 and x = 1 meet in the line (1, t, 0)
        let mut q = QemQuadric::default();
        let t = QemQuadric::of_triangle([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]);
        q.add(&t);
        let t2 = QemQuadric::of_triangle([[1.0, 0.0, 0.0], [1.0, 0.0, -1.0], [1.0, 1.0, 0.0]]);
        q.add(&t2);
        let x = q.minimizer([0.8, 0.4, 0.1]).unwrap();
        assert!((x[0] - 1.0).abs() < 1e-12 && (x[1] - 0.4).abs() < 1e-12);
        assert!(x[2].abs() < 1e-12, "{x:?}");
        assert!(q.eval(x).abs() < 1e-12);
        assert_eq!(QemQuadric::default().minimizer([1.0, 2.0, 3.0]), None);
        let degenerate = QemQuadric::of_triangle([[0.0; 3], [1.0, 1.0, 1.0], [2.0, 2.0, 2.0]]);
        assert_eq!(degenerate, QemQuadric::default());
    }
}
