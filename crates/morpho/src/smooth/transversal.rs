//! The three-split's macro edges solved explicitly, without (9.4): a degree-elevated quadratic
//! boundary and a common linear transversal (a deviation from Veltkamp 1992, §9.6, Step 5;
//! NOTES B.5; the tangent-plane condition is V (8.10) with quadratic `E` and linear `F, G`,
//! which V §8.3 allows: "polynomials of degree ≤ n−1").
//!
//! **Why (9.4) spikes on real meshes.** With the cubic boundary of Step 2 and the first rows
//! `L0, R0, L2, R2` fixed by Step 4, (9.3a, d) fix `(e, f, g)` at both ends up to scale, and
//! (9.3b, c) are a 2×2 system per coordinate with determinant `Δ = 4(f0 g1 − g0 f1)`. `Δ` is a
//! continuous function of the data that changes sign between edges (it vanishes exactly when
//! the edge direction splits the two `W` directions in the same ratio at both ends), so on a
//! mesh with 10⁵ edges some edges have `|Δ|` at 1e-6…1e-12 of its scale, and `L1, R1` move by
//! `residual/Δ` edge lengths. The residual does not vanish with `Δ`: in the singular limit
//! (9.3) is inconsistent for every ratio `e1/e0` (three equations, one free scalar). The same
//! count holds for any choice of linear `E, F, G` with a cubic boundary (writing the
//! cross-boundary derivatives as `a T + b X` with a constant `a` gives the same determinant), so
//! no threshold and no choice of free parameters can cure it: it is the data of the edge, not
//! rounding or a bug.
//!
//! **The construction.** When the boundary is a degree-elevated quadratic, its derivative
//! `T(s) = K(s) − M(s)` (V (8.8)) is *linear*: `T0 = M1 − M0`, `T1 = M3 − M2`, `M2 − M1 =
//! (T0 + T1)/2`. Take the linear transversal `X(s) = (1−s) X0 + s X1` with `X0 = n0 × T0`,
//! `X1 = n1 × T1` (in the tangent planes, perpendicular to the boundary at the ends). At each end
//! the first rows decompose uniquely in the orthogonal frames: `L0 − M0 = aL0 T0 + bL0 X0`,
//! `L2 − M2 = aL1 T1 + bL1 X1`, and likewise `R` with `aR, bR`. With the linear functions
//! `aL(s), bL(s), aR(s), bR(s)` through those end values, set the cross-boundary derivatives
//! `D_L = L − M := aL T + bL X` and `D_R = R − M := aR T + bR X`: both are quadratic, their end
//! coefficients are the given `L0 − M0`, `L2 − M2` (so nothing else moves), and their middle
//! Bernstein coefficients give the two free points
//! `L1 = M1 + (aL0 T1 + aL1 T0 + bL0 X1 + bL1 X0)/2` and the same for `R1`.
//!
//! **Why it is G¹ (proof sketch).** `bR D_L − bL D_R = (aL bR − aR bL) T` identically in `s`:
//! that is (8.10) with `E = aR bL − aL bR`, `F = bR`, `G = −bL`, so `∇_d P`, `∇_c P`, `∇_c Q`
//! all lie in `span(T(s), X(s))` and the tangent planes coincide wherever `T × X ≠ 0`. The
//! normals are `n_P ∝ T × D_L = bL (T × X)` and `n_Q ∝ (−T) × D_R = −bR (T × X)`, so they
//! agree in orientation iff `bL, bR` have opposite signs; `bL, bR` are linear, so opposite signs
//! at both ends (no fold at either end vertex, NOTES B.1) give opposite signs along the whole
//! edge. Both side conditions are checked here: `(T × X)·(n0 + n1) > 0` on all of `[0, 1]`
//! (exactly, as the nonnegativity of a quadratic in Bernstein form) and the end signs; an edge
//! that fails either is not built this way ([`transversal_edge`] returns `None`). Nothing is
//! divided by a quantity that can vanish on a valid edge: `|T0|, |T1| > 0` and the frames are
//! orthogonal, so `|L1 − M1|` is bounded by `(|L0 − M0| + |L2 − M2|)·max(|T1|/|T0|, |T0|/|T1|)`.
//! Linear precision: on a plane with one normal, `Q` is the edge midpoint, `T0 = T1`, `X0 = X1`,
//! the affine data give `aL0 = aL1`, `bL0 = bL1`, and `L1 − M1 = L0 − M0`, the affine value.
//!
//! Which edges get the quadratic boundary (the point `Q` in both tangent planes, see
//! `singular.rs`) is decided by the caller from the position of `Q`; an inflected edge (offset,
//! nearly parallel tangent planes) has no usable `Q` and keeps the cubic boundary and (9.4).
//! O(1) per edge.

use crate::geom::vec;

type P3 = [f64; 3];

/// Largest relative third difference `|M3 − 3M2 + 3M1 − M0| / |M3 − M0|` accepted as a
/// degree-elevated quadratic boundary (rounding of the handles is ~1e-16).
const QUADRATIC: f64 = 1e-12;

/// What [`transversal_edge`] built for one macro edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TransversalEdge {
    /// The new `L1` (first row of the left patch, the 111 point of the micro patch).
    pub l1: P3,
    /// The new `R1`.
    pub r1: P3,
    /// `|L1 − L1_old|` over the edge length would be the displacement; this is the largest
    /// `|a|` or `|b|` coordinate met, for diagnostics.
    pub max_coord: f64,
}

/// The coordinates `(a, b)` of `d` in the orthogonal frame `(t, x)` (`t ⊥ x`).
fn frame(d: P3, t: P3, x: P3) -> (f64, f64) {
    (
        vec::dot(d, t) / vec::dot(t, t),
        vec::dot(d, x) / vec::dot(x, x),
    )
}

/// The explicit G¹ edge of the module doc: `m` the boundary control points (a degree-elevated
/// quadratic), `l`, `r` the first rows of the left and right patch (`l[1]`, `r[1]` are
/// ignored), `n0`, `n1` the unit normals at `m[0]`, `m[3]`. `None` when the boundary is not a
/// degree-elevated quadratic, when `T × X` may vanish on the edge, or when the left and right
/// first rows do not lie on opposite sides of the boundary at both ends (a fold: no transversal
/// construction is G¹ there).
pub(crate) fn transversal_edge(
    m: &[P3; 4],
    l: &[P3; 3],
    r: &[P3; 3],
    n0: P3,
    n1: P3,
) -> Option<TransversalEdge> {
    let len = vec::dist(m[0], m[3]);
    let third = vec::add(vec::sub(m[3], m[0]), vec::scale(vec::sub(m[1], m[2]), 3.0));
    if len.is_nan() || len <= 0.0 || vec::norm(third) > QUADRATIC * len {
        return None;
    }
    let t0 = vec::sub(m[1], m[0]);
    let t1 = vec::sub(m[3], m[2]);
    // X in the tangent planes, perpendicular to the boundary, as long as T
    let x0 = vec::cross(n0, t0);
    let x1 = vec::cross(n1, t1);
    if vec::norm2(x0) == 0.0 || vec::norm2(x1) == 0.0 {
        return None;
    }
    // (T × X)·(n0 + n1) > 0 on [0, 1]: Bernstein coefficients c0, c1, c2 of a quadratic
    let nm = vec::add(n0, n1);
    let c0 = vec::dot(vec::cross(t0, x0), nm);
    let c2 = vec::dot(vec::cross(t1, x1), nm);
    let c1 = 0.5 * (vec::dot(vec::cross(t0, x1), nm) + vec::dot(vec::cross(t1, x0), nm));
    if !(c0 > 0.0 && c2 > 0.0 && c1 > -(c0 * c2).sqrt()) {
        return None;
    }
    let (al0, bl0) = frame(vec::sub(l[0], m[0]), t0, x0);
    let (al1, bl1) = frame(vec::sub(l[2], m[2]), t1, x1);
    let (ar0, br0) = frame(vec::sub(r[0], m[0]), t0, x0);
    let (ar1, br1) = frame(vec::sub(r[2], m[2]), t1, x1);
    // L is the left side (X = n × T points into it), R the right one
    if !(bl0 > 0.0 && bl1 > 0.0 && br0 < 0.0 && br1 < 0.0) {
        return None;
    }
    let mid = |a0: f64, a1: f64, b0: f64, b1: f64| {
        let mut d = vec::scale(t1, 0.5 * a0);
        d = vec::add_scaled(d, 0.5 * a1, t0);
        d = vec::add_scaled(d, 0.5 * b0, x1);
        vec::add_scaled(d, 0.5 * b1, x0)
    };
    let l1 = vec::add(m[1], mid(al0, al1, bl0, bl1));
    let r1 = vec::add(m[1], mid(ar0, ar1, br0, br1));
    let max_coord = [al0, al1, bl0, bl1, ar0, ar1, br0, br1]
        .iter()
        .fold(0.0f64, |s, c| s.max(c.abs()));
    if !(l1.iter().chain(&r1).all(|c| c.is_finite())) {
        return None;
    }
    Some(TransversalEdge { l1, r1, max_coord })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::smooth::BezierTriangle;

    /// The unit normals of both patches along the edge, from their own control points.
    fn max_jump(p: &[P3; 10], q: &[P3; 10]) -> f64 {
        let (tp, tq) = (
            BezierTriangle::new(3, p.to_vec()),
            BezierTriangle::new(3, q.to_vec()),
        );
        let mut worst: f64 = 0.0;
        for k in 1..=20 {
            let s = k as f64 / 21.0;
            let n1 = tp.normal([1.0 - s, s, 0.0]);
            let n2 = tq.normal([s, 1.0 - s, 0.0]);
            worst = worst.max(vec::norm(vec::cross(n1, n2)).atan2(vec::dot(n1, n2)));
        }
        worst
    }

    #[test]
    fn a_skew_edge_is_g1_with_bounded_points() {
        // an edge a → b with tilted tangent planes and asymmetric first rows
        let (a, b) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.1]);
        let n0 = vec::scale([0.1, 0.2, 1.0], 1.0 / vec::norm([0.1, 0.2, 1.0]));
        let n1 = vec::scale([-0.3, -0.1, 1.0], 1.0 / vec::norm([-0.3, -0.1, 1.0]));
        let c = vec::lerp(a, b, 0.5);
        let (m1, m2, _) = crate::smooth::singular::quadratic_handles(a, n0, b, n1, c).unwrap();
        let m = [a, m1, m2, b];
        // first rows in the tangent planes, left (y > 0) and right (y < 0)
        let inplane = |v: P3, n: P3, d: P3| vec::add(v, vec::add_scaled(d, -vec::dot(d, n), n));
        let l = [
            inplane(a, n0, [0.2, 0.3, 0.0]),
            [0.0; 3],
            inplane(b, n1, [-0.1, 0.25, 0.0]),
        ];
        let r = [
            inplane(a, n0, [0.3, -0.2, 0.0]),
            [0.0; 3],
            inplane(b, n1, [-0.25, -0.35, 0.0]),
        ];
        let e = transversal_edge(&m, &l, &r, n0, n1).unwrap();
        // the patch P = (a, b, c) with its edge rows in tri_index order; the rest arbitrary
        let c = [0.5, 0.8, 0.3];
        let p = [
            a,
            m[1],
            l[0],
            m[2],
            e.l1,
            [0.3, 0.5, 0.2],
            b,
            l[2],
            [0.6, 0.6, 0.3],
            c,
        ];
        let d = [0.5, -0.8, 0.1];
        let q = [
            b,
            m[2],
            r[2],
            m[1],
            e.r1,
            [0.6, -0.5, 0.1],
            a,
            r[0],
            [0.4, -0.6, 0.0],
            d,
        ];
        let jump = max_jump(&p, &q);
        assert!(jump < 1e-13, "{jump}");
        assert!(vec::dist(e.l1, m[1]) < 1.0 && vec::dist(e.r1, m[1]) < 1.0);
        // a fold (both rows on the left at one end) is refused
        let bad = [r[0], [0.0; 3], inplane(b, n1, [-0.25, 0.35, 0.0])];
        assert!(transversal_edge(&m, &l, &bad, n0, n1).is_none());
        // a cubic (not quadratic) boundary is refused
        let cubic = [a, vec::add(m1, [0.0, 0.01, 0.0]), m2, b];
        assert!(transversal_edge(&cubic, &l, &r, n0, n1).is_none());
    }
}
