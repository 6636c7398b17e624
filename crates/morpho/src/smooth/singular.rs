//! The three-split's singular macro edges (a deviation from Veltkamp 1992, §9.6, Step 5;
//! NOTES B.5). The text solves the pair (9.4) for `L1, R1` and requires it to be independent
//! ("If this pair of equations is independent, it uniquely determines L1 and R1"); it says
//! nothing of the dependent case, which occurs whenever the two sides of an edge are mirror
//! images (octahedron, icosahedron with sphere normals, symmetric grids): then `f0 = g0`,
//! `f1 = g1` and (9.4) is singular **and inconsistent** for every ratio `e1/e0`.
//!
//! Why, and the fix (derived here, checked by the independent continuity test). On a mirror
//! symmetric edge G¹ means `(L−M) + (R−M) = μ(t) (K−M)` along the edge (the symmetric part
//! of the cross-boundary derivative lies along the boundary tangent). With the cubic boundary
//! of Step 2, `K−M` is a genuine quadratic and `μ` would have to be rational: no cubic
//! patches exist. If the boundary is a **degree-elevated quadratic** (the Farin-style boundary
//! the text points to for the two-split, §9.7), `K−M` is a degree-elevated linear polynomial
//! and `μ(t) = μ0 t + μ1 u` is linear: the linear-E,F,G conditions (9.3) are then consistent
//! with `F = G` constant, i.e. with the ratio `ρ = e1/e0` chosen so that `f1 = f0`.
//!
//! So (now used by `split3.rs` as its last resort; the quadratic boundary serves the explicit
//! construction of `transversal.rs` on every edge where it is usable):
//! 1. the two edge points become `M1 = (M0 + 2Q)/3`, `M2 = (M3 + 2Q)/3`, where `Q` is the
//!    point of both vertex tangent planes nearest a given point (the caller passes the one
//!    that keeps the boundary nearest the Step-2 one), so positions and normals are still
//!    interpolated ([`quadratic_handles`]);
//! 2. Step 5 solves (9.3b), (9.3c) with `e0 = 1`, `e1 = ρ = (f0²+g0²)/(f0 f1 + g0 g1)`
//!    (which makes `f1 = f0` exactly on symmetric edges) by the minimum-norm least-squares
//!    correction of the current `(L1, R1)` (pseudo-inverse of the 2×2 coefficient matrix):
//!    unique where the pair is independent, the smallest move where it is not
//!    ([`solve_singular`]). The residual is returned; an edge whose residual does not vanish is
//!    reported unresolved by the caller, never silently creased.
//!
//! No iteration: one closed-form step per edge. O(1) per edge.

use crate::geom::vec;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

type P3 = [f64; 3];

/// Relative cut-off of the pseudo-inverses.
const CUTOFF: f64 = 1e-9;

/// The edge points `(M1, M2)` of the degree-elevated quadratic boundary from `a` (normal
/// `na`) to `b` (normal `nb`) whose middle point `Q` lies in both tangent planes, nearest to
/// `c` along their line of intersection (anywhere in the plane when the planes coincide), or
/// `None` when no point lies in both tangent planes (parallel, offset planes) or the result is
/// not finite. `Q` is returned too.
pub(crate) fn quadratic_handles(a: P3, na: P3, b: P3, nb: P3, c: P3) -> Option<(P3, P3, P3)> {
    let len = vec::dist(a, b);
    let mid = c;
    let d = vec::cross(na, nb);
    let dl = vec::norm(d);
    let w = if dl > 1e-12 && dl.is_finite() {
        vec::scale(d, 1.0 / dl)
    } else {
        [0.0; 3]
    };
    let rows = [na, nb, w];
    // right-hand sides relative to the midpoint
    let rhs = [
        vec::dot(na, vec::sub(a, mid)),
        vec::dot(nb, vec::sub(b, mid)),
        0.0,
    ];
    let m = Matrix3::from_fn(|i, j| rows[i][j]);
    let svd = m.svd(true, true);
    let cut = CUTOFF * svd.singular_values.max();
    let x = svd.solve(&Vector3::from(rhs), cut).ok()?;
    let q = vec::add(mid, [x[0], x[1], x[2]]);
    let off = |p: P3, n: P3| vec::dot(vec::sub(q, p), n).abs();
    if !q.iter().all(|c| c.is_finite()) || off(a, na) > 1e-12 * len || off(b, nb) > 1e-12 * len {
        return None;
    }
    let m1 = vec::add_scaled(a, 2.0 / 3.0, vec::sub(q, a));
    let m2 = vec::add_scaled(b, 2.0 / 3.0, vec::sub(q, b));
    Some((m1, m2, q))
}

/// The known terms of (9.3b), (9.3c): `A0 = (M1−M0) + f1(L0−M0) + g1(R0−M0)` and
/// `A1 = (M3−M2) + f0(L2−M2) + g0(R2−M2)` (`m` the edge points, `l`, `r` the first rows of both
/// sides), shared by [`solve_singular`] and the three-split's regular solve of (9.4).
pub(crate) fn a_terms(
    m: &[P3; 4],
    l: &[P3; 3],
    r: &[P3; 3],
    [f0, g0, f1, g1]: [f64; 4],
) -> (P3, P3) {
    let d = vec::sub;
    let mut a0 = d(m[1], m[0]);
    a0 = vec::add_scaled(a0, f1, d(l[0], m[0]));
    a0 = vec::add_scaled(a0, g1, d(r[0], m[0]));
    let mut a1 = d(m[3], m[2]);
    a1 = vec::add_scaled(a1, f0, d(l[2], m[2]));
    a1 = vec::add_scaled(a1, g0, d(r[2], m[2]));
    (a0, a1)
}

/// Step 5 on a (near-)singular edge (module doc): `m` the edge points, `l`, `r` the first rows
/// of both sides, `[f0, g0, f1, g1]` from (9.3a), (9.3d) with `e = 1`, `old` the current
/// `(L1, R1)`, `cutoff` the relative singular value below which the pseudo-inverse drops a
/// direction (at least `CUTOFF`; a larger one bounds the move where the pair is nearly
/// dependent, at the price of a residual). Returns the new `(L1, R1)` and the relative
/// residual of (9.3b), (9.3c).
pub(crate) fn solve_singular(
    m: &[P3; 4],
    l: &[P3; 3],
    r: &[P3; 3],
    [f0, g0, f1, g1]: [f64; 4],
    old: (P3, P3),
    cutoff: f64,
) -> ((P3, P3), f64) {
    let d = vec::sub;
    let dot01 = f0 * f1 + g0 * g1;
    let rho = if dot01.abs() > 0.0 && ((f0 * f0 + g0 * g0) / dot01).is_finite() {
        (f0 * f0 + g0 * g0) / dot01
    } else {
        1.0
    };
    let (a0, a1) = a_terms(m, l, r, [f0, g0, f1, g1]);
    let m21 = d(m[2], m[1]);
    // unknowns u = L1 − M1, v = R1 − M1:
    //   2 f0 u + 2 g0 v         = −ρ A0 − 2 (M2−M1)        (9.3b)
    //   2ρ f1 u + 2ρ g1 v       = −A1 − 2ρ (M2−M1)         (9.3c)
    let b = Matrix2::new(2.0 * f0, 2.0 * g0, 2.0 * rho * f1, 2.0 * rho * g1);
    let svd = b.svd(true, true);
    let cut = cutoff.max(CUTOFF) * svd.singular_values.max();
    let (u_old, v_old) = (d(old.0, m[1]), d(old.1, m[1]));
    let mut u = [0.0; 3];
    let mut v = [0.0; 3];
    let mut res: f64 = 0.0;
    for k in 0..3 {
        let rhs = Vector2::new(-rho * a0[k] - 2.0 * m21[k], -a1[k] - 2.0 * rho * m21[k]);
        let x_old = Vector2::new(u_old[k], v_old[k]);
        let corr = svd
            .solve(&(rhs - b * x_old), cut)
            .unwrap_or_else(|_| Vector2::zeros());
        let x = x_old + corr;
        u[k] = x[0];
        v[k] = x[1];
        let rv = b * x - rhs;
        res = res.max(rv[0].abs()).max(rv[1].abs());
    }
    let scale = vec::dist(m[0], m[3]) * (1.0 + f0.abs() + g0.abs()) * (1.0 + rho.abs());
    let rel = if res.is_finite() {
        res / scale
    } else {
        f64::INFINITY
    };
    ((vec::add(m[1], u), vec::add(m[1], v)), rel)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_boundary_of_the_octahedron_edge_is_the_corner_point() {
        let (m1, m2, _) = quadratic_handles(
            [1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.5, 0.0],
        )
        .unwrap();
        // Q = (1,1,0): M1 = (1, 2/3, 0), M2 = (2/3, 1, 0)
        for (p, q) in [(m1, [1.0, 2.0 / 3.0, 0.0]), (m2, [2.0 / 3.0, 1.0, 0.0])] {
            assert!(vec::dist(p, q) < 1e-15, "{p:?}");
        }
        // parallel offset tangent planes: no quadratic boundary
        assert!(quadratic_handles(
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 0.0, 1.0],
            [0.5, 0.0, 0.5]
        )
        .is_none());
        // one plane: the straight edge
        let (m1, _, _) = quadratic_handles(
            [0.0; 3],
            [0.0, 0.0, 1.0],
            [3.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.5, 0.0, 0.0],
        )
        .unwrap();
        assert!(vec::dist(m1, [1.0, 0.0, 0.0]) < 1e-15);
    }
}
